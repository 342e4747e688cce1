"""Run records without the bus: the writer's timing rules, `teleo simulate`'s record of
seed 000's Figure 3, finding a run, and `teleo plot` of a domain other than driving."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from bus import keys
from bus.messages import Envelope, GoalList, Intention, Percepts, WorldEvent, WorldState
from bus.record import message_record
from tools.cli import cli
from tools.records.record_coverage import coverage
from tools.records.run_record import RECORD_FILE, RecordError, RecordWriter, RunRecord, locate

ROOT = Path(__file__).resolve().parents[2]
FIGURE3 = ROOT / "scenarios" / "blocks_figure3.toml"


def _add(rec: RecordWriter, key: str, msg) -> None:
    rec.add(key, message_record(key, msg))


def test_a_record_waits_for_its_cycles_world_state_to_take_its_time(tmp_path) -> None:
    path = tmp_path / "r.mcap"
    env = lambda c: Envelope(1, "r1", c, "t", 99)  # noqa: E731
    with RecordWriter(path, "r1") as rec:
        _add(rec, keys.percepts("r1", "A"), Percepts(env(0), "A", ()))   # before its state
        _add(rec, keys.world_state("r1"), WorldState(env(0), {"time": 1.5}, {}, []))
        _add(rec, keys.world_events("r1"), WorldEvent(env(-1), {"kind": "x"}))  # no cycle
        _add(rec, keys.world_state("r1"), WorldState(env(1), {"time": 1.6}, {}, []))
        _add(rec, keys.percepts("r1", "A"), Percepts(env(3), "A", ()))   # state never came
    from mcap.reader import make_reader

    with path.open("rb") as f:
        got = [(json.loads(m.data)["kind"], json.loads(m.data)["env"]["cycle"], m.log_time,
                m.publish_time) for _, _, m in make_reader(f).iter_messages()]
    assert got == [("WorldState", 0, 1_500_000_000, 99), ("Percepts", 0, 1_500_000_000, 99),
                   ("WorldEvent", -1, 1_500_000_000, 99), ("WorldState", 1, 1_600_000_000, 99),
                   ("Percepts", 3, 1_800_000_000, 99)]   # extrapolated with the last step


def test_a_spoilt_cycle_far_out_of_range_is_recorded_not_left_to_fail_the_close(tmp_path):
    path = tmp_path / "r.mcap"
    env = lambda c, sent=99: Envelope(1, "r1", c, "t", sent)  # noqa: E731
    with RecordWriter(path, "r1") as rec:
        _add(rec, keys.world_state("r1"), WorldState(env(0), {"time": 1.5}, {}, []))
        _add(rec, keys.world_state("r1"), WorldState(env(1), {"time": 1.6}, {}, []))
        _add(rec, keys.percepts("r1", "A"), Percepts(env(2**62), "A", ()))  # time past 2**64 ns
        _add(rec, keys.percepts("r1", "A"), Percepts(env(-2**40, -5), "A", ()))
    from mcap.reader import make_reader

    with path.open("rb") as f:
        got = sorted((json.loads(m.data)["env"]["cycle"], m.log_time, m.publish_time)
                     for _, _, m in make_reader(f).iter_messages())
    assert got == [(-2**40, 1_600_000_000, 0), (0, 1_500_000_000, 99),
                   (1, 1_600_000_000, 99), (2**62, 2**64 - 1, 99)]


def test_the_summary_says_which_share_of_the_run_its_record_lacks(tmp_path) -> None:
    assert coverage(tmp_path, 5) is None                     # not recorded: nothing to say
    env = lambda c: Envelope(1, "r1", c, "t", 99)  # noqa: E731
    with RecordWriter(tmp_path / RECORD_FILE, "r1") as rec:
        for cycle in (0, 1, 1, 3, 4):                        # 1 twice (a re-sent state), 2 lost
            _add(rec, keys.world_state("r1"), WorldState(env(cycle), {"time": cycle}, {}, []))
    assert coverage(tmp_path, 5) == {"file": str(tmp_path / RECORD_FILE), "world_states": 4,
                                     "missing": 1, "gaps": [[2, 2]]}
    assert coverage(tmp_path, 2)["missing"] == 0             # the cycles 0 and 1 are there
    assert coverage(tmp_path, 7)["gaps"] == [[2, 2], [5, 6]]   # the end never came
    (tmp_path / RECORD_FILE).write_bytes(b"\x89MCAP0\r\n")   # never closed: read as it is
    assert coverage(tmp_path, 5)["gaps"] == [[0, 4]]
    (tmp_path / RECORD_FILE).write_bytes(b"not a record at all")
    assert coverage(tmp_path, 5)["missing"] is None


def test_a_goal_that_leaves_the_goal_list_without_failing_was_cancelled(tmp_path) -> None:
    """The executive never reports a cancellation (it no longer has the goal): the history
    takes it from the goal-entry process's goal list; a failed goal, withdrawn too, stays
    failed."""
    env = lambda c: Envelope(1, "r1", c, "t", 99)  # noqa: E731
    g1 = {"id": "g1", "goal": "(cruising ME)", "priority": 5}
    g2 = {"id": "g2", "goal": "(flying ME)", "priority": 6}
    listed = {0: [g1, g2], 1: [g1, g2], 2: [g1], 3: []}
    told = {0: [("g1", "active"), ("g2", "active")], 1: [("g1", "satisfied"), ("g2", "failed")],
            2: [("g1", "satisfied")], 3: []}
    with RecordWriter(tmp_path / RECORD_FILE, "r1") as rec:
        for cycle in range(4):
            _add(rec, keys.world_state("r1"), WorldState(env(cycle), {"time": cycle}, {}, []))
            _add(rec, keys.goal_list("r1", "ME"),
                 GoalList(env(cycle), "ME", tuple({**g, "status": "active"}
                                                  for g in listed[cycle])))
            goals = [{"id": i, "status": s, "priority": 5} for i, s in told[cycle]]
            _add(rec, keys.intention("r1", "ME"), Intention(env(cycle), "ME", {"goals": goals}))
    history = RunRecord(tmp_path / RECORD_FILE).goal_history()["ME"]
    assert [(c["cycle"], c["status"]) for c in history["g1"]] == [
        (0, "active"), (1, "satisfied"), (3, "cancelled")]
    assert [(c["cycle"], c["status"]) for c in history["g2"]] == [(0, "active"), (1, "failed")]
    told = CliRunner().invoke(cli, ["explain", str(tmp_path / RECORD_FILE), "--goal", "g1"])
    assert told.exit_code == 0, told.output
    assert told.output.splitlines()[-1].split() == [
        "cycle", "3", "cancelled", "--", "withdrawn", "from", "the", "goal", "list"]


def test_simulate_records_figure_3_with_the_launch_channels(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    done = CliRunner().invoke(cli, ["simulate", str(FIGURE3), "--json"])
    assert done.exit_code == 0, done.output
    out = json.loads(done.stdout)
    rec = RunRecord(locate(out["record"]))
    assert rec.meta["teleo.run"]["source"] == "simulate"
    run = rec.run
    counts: dict[str, int] = {}
    for key, _ in rec.records():
        counts[key] = counts.get(key, 0) + 1
    stages = [keys.stats(run, p) for p in ("world", "ME.perception", "ME.inference",
                                           "ME.executive")]
    assert counts == {keys.world_static(run): 1, **{k: out["cycles"] for k in (
        keys.world_state(run), keys.percepts(run, "ME"), keys.beliefs(run, "ME"),
        keys.intention(run, "ME"), keys.actions(run, "ME"), keys.goal_list(run, "ME"), *stages)}}
    # issue 35: the table is held once; each world state read back has it again
    raw = [r for _, r in RunRecord(rec.path, raw=True).kinds("state")]
    assert raw and not any("table" in r["snapshot"] for r in raw)
    assert all("table" in r["snapshot"] for _, r in rec.kinds("state"))
    # Figure 3: unstack C from B, put C down, unstack B from A (cycles that act)
    actions = [r["actions"] for _, r in sorted(rec.by_cycle("actions", "ME").items())]
    assert [a for a in actions if a] == [[["*unstack", "C", "B"]], [["*putdown", "C", "T"]],
                                         [["*unstack", "B", "A"]]]
    assert rec.goal_history()["ME"]["g1"][-1]["status"] == "satisfied"
    assert locate(run) == locate(Path(out["record"]).parent) == Path(out["record"])


def test_simulate_without_a_record(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    done = CliRunner().invoke(cli, ["simulate", str(FIGURE3), "--no-record", "--json"])
    assert done.exit_code == 0 and json.loads(done.stdout)["record"] is None
    assert not list(tmp_path.rglob("*.mcap"))


def test_a_run_that_is_not_there_is_named_with_the_places_looked_at(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    with pytest.raises(RecordError, match="nope: no run record here .*no run in .* has a record"):
        locate("nope")
    bad = tmp_path / "bad.mcap"
    bad.write_text("not an mcap file")
    with pytest.raises(RecordError, match="bad.mcap: not a readable run record"):
        RunRecord(bad)
    shown = CliRunner().invoke(cli, ["explain", "nope"])
    assert shown.exit_code == 1 and "no run record here" in shown.output
    assert "Traceback" not in shown.output


def test_plot_of_a_blocks_run_and_explain_of_its_goals(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    runner = CliRunner()
    out = json.loads(runner.invoke(cli, ["simulate", str(FIGURE3), "--json"]).stdout)
    drawn = runner.invoke(cli, ["plot", out["record"], "--out", str(tmp_path / "p.png")])
    assert drawn.exit_code == 0, drawn.output
    assert (tmp_path / "p.png").read_bytes()[:4] == b"\x89PNG"
    told = runner.invoke(cli, ["explain", out["record"], "--goal", "g1"])
    assert told.exit_code == 0, told.output
    lines = told.output.splitlines()
    assert lines[0].startswith("goal g1 of ME: (clear A), priority 1")
    rows = [(int(ln.split()[1]), ln.split()[2]) for ln in lines[1:]]  # "cycle N status"
    intentions = RunRecord(locate(out["record"])).by_cycle("intention", "ME")
    for cycle, status in rows:  # each change is the status the decision of that cycle gave
        assert status == next(g["status"] for g in intentions[cycle]["decision"]["goals"]
                              if g["id"] == "g1")
    assert rows[0][0] == 0 and rows[-1][1] == "satisfied" and len(rows) >= 2
    wrong = runner.invoke(cli, ["explain", out["record"], "--agent", "YOU"])
    assert wrong.exit_code == 2 and "no agent 'YOU'; agents: ME" in wrong.output


def test_simulate_times_the_stages_apart_yet_decides_as_engine_cycle(tmp_path) -> None:
    """simulate splits Engine.cycle into infer and decide to time them; with an SCS body that
    asserts facts into the world model (programs/errands.tlp) the actions must stay the same."""
    from agents.lang import Engine, load_program
    from tools.commands.scenario_check import load_checked
    from tools.commands.simulate import simulate
    from tools.records.run_recorders import SimRecorder
    from world.domain import get_domain

    scenario, _ = load_checked(ROOT / "scenarios" / "errands_demo.toml")
    with RecordWriter(tmp_path / "r.mcap", "e1") as writer:
        split = simulate(scenario, cycles=120, recorder=SimRecorder(writer, "e1"))
    beliefs = RunRecord(tmp_path / "r.mcap").by_cycle("beliefs", "ME")
    domain = get_domain(scenario.domain)
    world = domain.create(scenario.world_table, scenario.run.seed, ["ME"])
    agent = scenario.agents[0]
    engine = Engine(load_program(agent.program), solver="means-ends" if agent.solver else None)
    state, outcomes, modelled = engine.initial_state(), [], 0
    for k, g in enumerate(scenario.goals):
        assert g.at_cycle == 0 and g.op == "post"
        state = engine.add_goal(state, g.goal, priority=g.priority, goal_id=g.goal_id or f"s{k+1}")
    for cycle in range(120):
        for event in scenario.events:
            if event.at_cycle == cycle:
                world.inject(event.event)
        result = engine.cycle(state, domain.perceive(world.snapshot_dict(), "ME"), outcomes)
        state, modelled = result.state, modelled + bool(result.state.scs.model)
        actions = [a.to_list() for a in result.decision.actions]
        assert actions == split.records[cycle]["ME"]["actions"], cycle
        assert sorted(b.to_list() for b in result.beliefs) == sorted(
            beliefs[cycle]["beliefs"]), cycle  # world-model facts included
        outcomes = world.apply_actions("ME", actions)
        world.step()
    assert modelled > 0  # the world model took part


def test_render_takes_a_run_as_explain_does(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    runner = CliRunner()
    out = json.loads(runner.invoke(cli, ["simulate", str(FIGURE3), "--json"]).stdout)
    run_dir = Path(out["record"]).parent
    for source in (run_dir.name, str(run_dir), out["record"]):   # id, folder, file
        drawn = runner.invoke(cli, ["render", source, "--out", str(tmp_path / "r.png")])
        assert drawn.exit_code == 0, drawn.output
        assert (tmp_path / "r.png").read_bytes()[:4] == b"\x89PNG"
    missing = runner.invoke(cli, ["render", "nope", "--out", str(tmp_path / "r.png")])
    assert missing.exit_code == 1 and "nope: no run record here" in missing.output
    assert f"newest first: {run_dir.name}" in missing.output


def test_explain_of_a_goal_finds_its_agent_in_a_run_of_several(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    runner = CliRunner()
    two = ROOT / "scenarios" / "two_cars.toml"
    out = json.loads(runner.invoke(cli, ["simulate", str(two), "--cycles", "105",
                                         "--json"]).stdout)
    owner = {g["id"]: g["agent"] for g in out["goals"]}
    assert len(set(owner.values())) == 2, owner
    for goal_id, agent in owner.items():   # goal ids are the run's: no --agent needed
        told = runner.invoke(cli, ["explain", out["record"], "--goal", goal_id])
        assert told.exit_code == 0, told.output
        assert told.output.startswith(f"goal {goal_id} of {agent}: ")
    asked = runner.invoke(cli, ["explain", out["record"]])   # a decision: whose, then?
    assert asked.exit_code == 2 and "choose one with --agent" in asked.output


def test_a_record_cut_at_any_byte_reads_as_far_as_it_goes(tmp_path) -> None:
    """A record whose disk filled (or whose writer was killed) is cut anywhere, even inside
    a record's header (drill full-disk: struct.error escaped the reader): it reads back
    what it holds, a run of its first cycles, or says it is not a record; never a crash."""
    env = lambda c: Envelope(1, "r1", c, "t", 99)  # noqa: E731
    whole = tmp_path / "whole.mcap"
    with RecordWriter(whole, "r1") as rec:
        for cycle in range(60):
            _add(rec, keys.world_state("r1"), WorldState(env(cycle), {"time": cycle,
                                                                        "pad": "x" * 300},
                                                         {}, []))
    data = whole.read_bytes()
    cut = tmp_path / RECORD_FILE
    for end in range(0, len(data), 97):
        cut.write_bytes(data[:end])
        try:
            held = sorted(r["env"]["cycle"] for _, r in RunRecord(cut).records())
        except RecordError as exc:
            assert "not a readable run record" in str(exc)
            continue
        assert held == list(range(len(held))), (end, held)


def test_explain_of_a_decision_that_does_not_read_says_so_in_one_line(tmp_path) -> None:
    """A record is only shape-checked: a decision whose parts are of the wrong kind (here
    `parallel: 3`) made `teleo explain` print a traceback (found by the view's own checks)."""
    from tools.records.run_record import RecordWriter

    path = tmp_path / "bad.mcap"
    env = {"v": 1, "run": "bad-1", "cycle": 0, "sender": "ME.executive", "sent_ns": 0}
    decision = {"cycle": 0, "goals": [{"id": "p1", "goal": "(x)", "priority": 1,
                                       "status": "active", "bindings": {}}],
                "path": [], "actions": [], "parallel": 3, "why": []}
    with RecordWriter(path, "bad-1") as writer:
        writer.add("teleo/bad-1/agent/ME/intention",
                   {"kind": "Intention", "env": env, "agent": "ME", "decision": decision})
    told = CliRunner().invoke(cli, ["explain", str(path), "--cycle", "0"])
    assert told.exit_code == 1 and "Traceback" not in told.output, told.output
    assert told.output.startswith("Error: run bad-1: the decision of ME at cycle 0 does not "
                                  "read (TypeError"), told.output


def test_a_simulate_record_carries_the_agent_memory_as_a_launch_does(tmp_path) -> None:
    """docs/records.md: simulate writes a launch's channels. Its Percepts and Actions carried
    no memory (the view's program check had to take the world model from the decision);
    now the actions of t send the memory and the world state and percepts of t + 1 hand it
    back, as in a launch (docs/bus.md, "Agent memory")."""
    from tools.commands.scenario_check import load_checked
    from tools.commands.simulate import simulate
    from tools.records.run_record import RecordWriter, RunRecord
    from tools.records.run_recorders import SimRecorder

    scenario, _ = load_checked(ROOT / "scenarios" / "errands_demo.toml")
    path = tmp_path / "errands.mcap"
    with RecordWriter(path, "errands-1") as writer:
        simulate(scenario, cycles=80, recorder=SimRecorder(writer, "errands-1"))
    rec = RunRecord(path)
    sent = {r["env"]["cycle"]: r["memory"] for _, r in rec.kinds("actions")}
    back = {r["env"]["cycle"]: r["memory"] for _, r in rec.kinds("percepts")}
    states = {r["env"]["cycle"]: r["memory"].get("ME", {}) for _, r in rec.kinds("state")}
    assert any(sent.values()), "the errands body's thread is in the memory"
    assert all(back[t + 1] == sent[t] == states[t + 1] for t in range(79)), "handed back"
