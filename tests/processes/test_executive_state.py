"""The executive process's state file (agents/processes/persist.py) with the real engine and
the Blocks World program: a restarted executive (a new make_step on the same file) goes on
with the goal stack and learned skills, re-emits a decision it had made before it died instead
of deciding again, and a file that cannot be read is kept aside, never a crash."""

from __future__ import annotations

import json
import logging
from pathlib import Path

from agents.lang import Engine, load_program
from agents.lang.registry import read_learned
from agents.processes.agent_setup import AgentSetup
from agents.processes.executive import make_step
from agents.processes.persist import Saved, StateFile, set_aside_files
from bus import keys
from bus.messages import Beliefs, Envelope, GoalList, Percepts
from tests.lang import test_blocks as blocks

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = str(ROOT / "programs" / "blocks.tlp")
LOG = logging.getLogger("test")


def executive_step(state: str, learned_out: str | None = None):
    """The executive process's step for agent ME of run r, its state kept in ``state``."""
    return make_step(AgentSetup(run="r", agent="ME", program=PROGRAM, state=state,
                                learned_out=learned_out), LOG)
TOWER = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"],
         ["block", "A", "xpos", 0, "ypos", 2, "height", 2],
         ["block", "B", "xpos", 0, "ypos", 4, "height", 2],
         ["block", "C", "xpos", 0, "ypos", 6, "height", 2]]


FIGURE3 = ({"id": "g1", "goal": "(clear A)", "priority": 1, "status": "pending"},)


def _inputs(cycle: int, percepts: list) -> dict:
    env = Envelope.now("r", cycle, "test")
    beliefs = tuple(b.to_list() for b in Engine(load_program(PROGRAM)).infer(percepts))
    return {keys.percepts("r", "ME"): Percepts(env, "ME", tuple(percepts)),
            keys.beliefs("r", "ME"): Beliefs(env, "ME", beliefs),
            keys.goal_list("r", "ME"): GoalList(env, "ME", FIGURE3)}


def _decision(outs) -> dict:
    return next(msg.decision for key, msg in outs if key.endswith("/intention"))


def test_a_restarted_executive_goes_on_with_its_goal_stack(tmp_path):
    path = tmp_path / "state-ME.json"
    step = executive_step(str(path))
    first = _decision(step(0, _inputs(0, TOWER)))
    assert first["solver"]["stacks"][0]["entries"][1]["goal"] == "(unstackable B A)"
    # the process dies after deciding cycle 0; the clock sends cycle 0 again to the new one
    again = executive_step(str(path))
    repeated = again(0, _inputs(0, TOWER))
    assert _decision(repeated) == first                       # re-emitted, not decided twice
    second = _decision(again(1, _inputs(1, TOWER)))
    assert [e["goal"] for e in second["solver"]["stacks"][0]["entries"]] == [
        "(clear A)", "(unstackable B A)", "(clear B)"]        # the stack went on: one deeper
    assert second["actions"] == [["*unstack", "C", "B"]]
    saved = StateFile(path, LOG).load()
    assert saved.cycle == 1 and saved.state.solver.stacks[0].goals()[-1] == "(clear B)"


def test_a_shorter_state_after_a_longer_one_reads_back(tmp_path):
    path = tmp_path / "s.json"
    engine = Engine(load_program(PROGRAM))
    file = StateFile(path, LOG)
    long_state = engine.add_goal(engine.initial_state(), "(ontable ?b T)")
    file.save(Saved(3, long_state, {"why": ["x" * 500]}, []))
    file.save(Saved(4, engine.initial_state(), {}, [["*putdown", "C", "T"]]))
    back = StateFile(path, LOG).load()
    assert (back.cycle, back.state, back.actions) == (4, engine.initial_state(),
                                                      [["*putdown", "C", "T"]])


def test_an_unreadable_state_file_is_kept_aside_and_the_run_starts_afresh(tmp_path, caplog):
    path = tmp_path / "s.json"
    path.write_text(json.dumps({"cycle": 2, "state": {"version": 99}}))
    assert StateFile(path, LOG).load() is None
    assert (tmp_path / "s.json.bad").exists() and not path.exists()
    assert "cannot be read" in caplog.text and "engine state version 99" in caplog.text


def test_a_state_file_that_is_not_utf8_is_set_aside_not_a_crash(tmp_path, caplog):
    """Drills 2026-12-04 D1: bytes that are not UTF-8 raised UnicodeDecodeError."""
    path = tmp_path / "state-ME.json"
    path.write_bytes(b"\xff\xfe\x00binary")
    (tmp_path / "state-ME.json.bad").write_text("an earlier one, kept")
    assert StateFile(path, LOG).load() is None
    assert (tmp_path / "state-ME.json.bad-2").read_bytes() == b"\xff\xfe\x00binary"
    assert (tmp_path / "state-ME.json.bad").read_text() == "an earlier one, kept"
    assert "cannot be read" in caplog.text
    assert [p.name for p in set_aside_files(tmp_path)] == ["state-ME.json.bad",
                                                          "state-ME.json.bad-2"]


def _learn(tmp_path: Path):
    """An executive with a state file and its own learned file, run until it learned."""
    state, out = tmp_path / "state-ME.json", tmp_path / "learned-ME.tlp"
    step = executive_step(str(state), learned_out=str(out))
    support, holding = dict(blocks.TOWER), None
    for cycle in range(6):   # the world: each action applied as the world would
        outs = step(cycle, _inputs(cycle, blocks.percepts(support, holding)))
        for action in _decision(outs)["actions"]:
            support, holding = blocks.act(support, holding, action)
    skills = read_learned(load_program(PROGRAM), out.read_text(), str(out))
    assert len(skills) == 2
    return state, out, skills


def test_a_restart_after_an_unreadable_state_keeps_the_learned_skills_on_disk(tmp_path):
    """Drills 2026-12-04 D4: the restarted executive rewrote learned-ME.tlp with 0 skills."""
    state, out, skills = _learn(tmp_path)
    for damage in (b"\xff\xfe\x00binary", b'{"cycle": "forty"}'):
        state.write_bytes(damage)
        again = executive_step(str(state), learned_out=str(out))
        again(6, _inputs(6, TOWER))
        assert read_learned(load_program(PROGRAM), out.read_text(), str(out)) == skills
        assert StateFile(state, LOG).load().state.learned == skills


def test_an_unreadable_learned_file_is_set_aside_and_the_executive_starts(tmp_path):
    state, out, _ = _learn(tmp_path)
    state.unlink()
    out.write_bytes(b"\xff\xfe(not a skill")
    again = executive_step(str(state), learned_out=str(out))
    again(0, _inputs(0, TOWER))
    assert (tmp_path / "learned-ME.tlp.bad").read_bytes() == b"\xff\xfe(not a skill"


CLEAR = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"],
         ["block", "C", "xpos", 0, "ypos", 2, "height", 2],
         ["block", "B", "xpos", 0, "ypos", 4, "height", 2],
         ["block", "A", "xpos", 0, "ypos", 6, "height", 2]]
WORLD = [CLEAR] * 3 + [TOWER] * 4   # A clear: nothing to do; then A covered: the stack grows


def test_the_state_is_written_only_when_a_decision_changed_it(tmp_path):
    path = tmp_path / "state-ME.json"
    step = executive_step(str(path))
    written = []
    for cycle, percepts in enumerate(WORLD):
        step(cycle, _inputs(cycle, percepts))
        written.append(json.loads(path.read_bytes())["cycle"])
    assert written == [0, 0, 0, 3, 4, 5, 6]   # (clear A) held: cycles 1 and 2 changed nothing


def test_a_killed_executive_loses_nothing_whichever_cycle_it_dies_in(tmp_path):
    """Killed after deciding cycle k, written or not: restarted on its file, given cycle k again
    (its outputs were not published) or cycle k + 1 (they were), it decides every cycle as the
    executive that never died."""
    ref = executive_step(str(tmp_path / "ref.json"))
    undisturbed = [_decision(ref(c, _inputs(c, p))) for c, p in enumerate(WORLD)]
    for k in range(len(WORLD) - 1):
        for resent in (True, False):
            path = tmp_path / f"state-{k}-{resent}.json"
            step = executive_step(str(path))
            got = [_decision(step(c, _inputs(c, WORLD[c]))) for c in range(k + 1)]
            again = executive_step(str(path))
            if resent:
                got[k] = _decision(again(k, _inputs(k, WORLD[k])))
            got += [_decision(again(c, _inputs(c, WORLD[c]))) for c in range(k + 1, len(WORLD))]
            assert got == undisturbed, (k, resent)
