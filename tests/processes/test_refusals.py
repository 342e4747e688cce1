"""What each process does with a malformed message it reads (issue 24, item 1): the codec
refuses it naming the field, or the process's step refuses the cycle's inputs (bus Refused:
nothing published, the cycle left for a good copy), or a bad part (a memory, an intention) is
logged and left out; the process never raises anything else. The messages are a real
pipeline's (bench/faults/fuzz_bus.py: a pymunk world, perception, inference, executive and the
goal-entry process's store, run in lockstep in-process), one field spoiled at a time."""

from __future__ import annotations

import copy
import logging
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from agents.processes import executive, inference, perception
from agents.processes.agent_setup import AgentSetup
from bus import keys
from bus.codec import decode, encode
from bus.errors import CodecError, Refused
from bus.messages import Actions, Beliefs, GoalList, Intention, Percepts, WorldState

ROOT = Path(__file__).resolve().parents[2]
sys.path.append(str(ROOT / "bench" / "faults"))
from fuzz_bus import RUN, Pipeline  # noqa: E402

LOG = logging.getLogger("test.refusals")


@pytest.fixture(scope="module")
def pipe(tmp_path_factory) -> Pipeline:
    """The SCS errands demo, 30 cycles in: the executive has a body thread and a world model."""
    return Pipeline("driving", tmp_path_factory.mktemp("pipe")).run(30)


def last(pipe: Pipeline, kind: str):
    return decode(pipe.keys[kind], encode_body(pipe.bases[kind][-1]))


def encode_body(body: dict) -> bytes:
    import msgpack

    return msgpack.packb(body, use_bin_type=True)


def agent_steps(pipe: Pipeline):
    program = str(pipe.scenario.agents[0].program)
    a = pipe.agent
    return (inference.make_step(AgentSetup(run=RUN, agent=a, program=program), LOG),
            executive.make_step(AgentSetup(run=RUN, agent=a, program=program), LOG))


def test_perception_refuses_a_snapshot_its_world_did_not_make(pipe):
    step = perception.make_step(AgentSetup(run=RUN, agent=pipe.agent))
    state = last(pipe, "state")
    assert step(state.env.cycle, {pipe.keys["state"]: state})   # the real one is perceived
    snap = copy.deepcopy(state.snapshot)
    snap["cars"][0]["x"] = "a"      # main: TypeError from math in perceive: the process died
    bad = replace(state, snapshot=snap)
    with pytest.raises(Refused, match=r"world state of cycle \d+ from 'world': snapshot: "
                                      r"cars\[0\]\.x: expected a number in \[-1e\+06, 1e\+06\], "
                                      r"got 'a'"):
        step(state.env.cycle, {pipe.keys["state"]: bad})
    with pytest.raises(Refused, match="unknown domain 'mars'"):
        step(state.env.cycle, {pipe.keys["state"]: replace(state, snapshot={**snap,
                                                                           "domain": "mars"})})


def test_inference_refuses_percepts_the_engine_cannot_read(pipe):
    infer, _ = agent_steps(pipe)
    seen = last(pipe, "percepts")
    rows = (*seen.percepts, ["building", "B5", "address", 5, "FIRST"])   # odd: no value
    with pytest.raises(Refused, match=r"the percepts of cycle 7 from 'ME.perception': percept "
                                      r"\['building', 'B5', 'address', 5, 'FIRST'\]: expected"):
        infer(7, {pipe.keys["percepts"]: replace(seen, percepts=rows)})
    assert infer(8, {pipe.keys["percepts"]: seen})   # and goes on with the next good one


def test_a_world_model_fact_of_the_wrong_arity_is_dropped_not_fatal(pipe, caplog):
    infer, _ = agent_steps(pipe)
    seen = last(pipe, "percepts")
    model = [*seen.memory.get("model", []), ["nearest-stop", "ME"]]   # a concept of 3
    out = infer(9, {pipe.keys["percepts"]: replace(seen, memory={**seen.memory,
                                                                 "model": model})})
    assert isinstance(out[0][1], Beliefs)   # main: IndexError in the fact store
    assert "world model dropped: world-model fact ['nearest-stop', 'ME']: nearest-stop " \
           "takes 3 argument(s), got 1" in caplog.text


def test_the_executive_refuses_a_belief_of_the_wrong_arity(pipe):
    _, decide = agent_steps(pipe)
    k = pipe.keys
    inputs = {k["percepts"]: last(pipe, "percepts"), k["beliefs"]: last(pipe, "beliefs"),
              k["goals"]: last(pipe, "goals")}
    bad = replace(inputs[k["beliefs"]], beliefs=(*inputs[k["beliefs"]].beliefs, ["stopped"]))
    with pytest.raises(Refused, match=r"belief \['stopped'\]: stopped takes 1 argument\(s\), "
                                      "got 0"):   # main: IndexError in the matcher
        decide(40, {**inputs, k["beliefs"]: bad})
    assert [key for key, _ in decide(41, inputs)] == [k["intention"], k["actions"]]


@pytest.mark.parametrize("spoil, reason", [
    (lambda t: t.update(skill=10**6), "skill: 1000000 is not a skill with a :body"),
    (lambda t: t["root"].update(cur=2**63 - 1), "cur: expected -1 .. "),
    (lambda t: t["root"].update(done=[99]), "done: expected steps 0 .. "),
    (lambda t: t["root"].update(since=2**64 - 1), "is not a 64-bit integer"),
])
def test_a_memory_that_does_not_fit_the_program_is_dropped_not_fatal(pipe, caplog, spoil,
                                                                     reason):
    """The memory comes back through the world each cycle (docs/bus.md, "Agent memory"): one
    the program did not make is logged and the executive goes on with its own state (on
    main: IndexError in the SCS interpreter, or an Actions message too big to encode)."""
    _, decide = agent_steps(pipe)
    k = pipe.keys
    seen = last(pipe, "percepts")
    memory = copy.deepcopy(seen.memory)
    assert memory["scs"]["threads"], "the errands body should be running"
    spoil(memory["scs"]["threads"][0])
    outs = dict(decide(42, {k["percepts"]: replace(seen, memory=memory),
                            k["beliefs"]: last(pipe, "beliefs"), k["goals"]: last(pipe, "goals")}))
    actions = outs[k["actions"]]
    assert isinstance(actions, Actions)
    decode(k["actions"], encode(actions))   # what it sends can be read again
    assert "agent memory dropped" in caplog.text and reason in caplog.text


def test_a_goal_list_with_a_goal_id_the_engine_would_rename_is_refused():
    """A goal of id "" was added by the engine as g<n>, so the executive later removed a goal
    it did not have: GoalError, the process died."""
    msg = GoalList(env_of(), "ME", ({"id": "", "goal": "(x)", "priority": 5,
                                     "status": "pending"},))
    with pytest.raises(CodecError, match=r"GoalList\.goals\[0\]\.id: expected a goal id "
                                         r"\(not empty\), got ''"):
        decode(keys.goal_list("r", "ME"), encode(msg))


def test_the_goal_entry_process_leaves_an_intention_it_cannot_read(pipe, caplog):
    entry = pipe.entry
    caplog.set_level(logging.WARNING, logger=entry.log.name)
    before = entry.store
    for goals in ([5], [{"id": []}], "x", [{"id": "g1", "status": {"k": 1}}]):
        entry.on_intention(Intention(env_of(), pipe.agent, {"goals": goals}))  # main: crashed
    assert entry.store is before
    assert "refused: intention of ME at cycle 3: decision.goals[0]: expected a goal " \
           "{id, status, note}, got 5" in caplog.text


def test_an_action_without_a_name_is_refused_by_the_codec():
    for row in ([], [3, "x"]):
        with pytest.raises(CodecError, match=r"Actions\.actions: expected arrays \[name, value,"):
            decode(keys.actions("r", "ME"), encode(Actions(env_of(), "ME", (row,))))


def test_a_world_state_the_perception_would_forward_is_checked_at_the_codec():
    bad = WorldState(env_of(), {}, {"ME": [{"action": ["*gas", 5], "status": "maybe",
                                            "reason": ""}]}, [])
    with pytest.raises(CodecError, match=r"WorldState\.outcomes\.ME\[0\]\.status: expected one "
                                         r"of 'done', 'failed', got 'maybe'"):
        decode(keys.world_state("r"), encode(bad))
    deep: list = []
    for _ in range(200):
        deep = [deep]
    with pytest.raises(CodecError, match=r"Percepts\.memory\.x.*nested deeper than 128 levels"):
        decode(keys.percepts("r", "ME"), encode(Percepts(env_of(), "ME", (), (), {"x": deep})))


def env_of():
    from bus.messages import Envelope

    return Envelope(1, "r", 3, "test", 0)
