"""ROGUE as a mechanism of the engine (agents/lang/planning/rogue.py): picked by name, each
request's status as the planner sees it, the "planner" section of the intention (to_dict,
explain, `teleo step --json`), and its state, which survives a restart exactly: a run that
stops, writes its state as JSON and goes on from it does what an uninterrupted run does."""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from agents.lang import Engine, EngineState, LangError, load_program
from agents.lang.engine import SOLVERS
from agents.lang.planning.rogue import RoguePlanner
from agents.lang.planning.state import PlannerState
from world.domain import get_domain

ROOT = Path(__file__).resolve().parents[3]
PROGRAM = ROOT / "programs" / "office_rogue.tlp"


@pytest.fixture(scope="module")
def program():
    return load_program(PROGRAM)


def start_percepts() -> list[list]:
    domain = get_domain("office")
    return domain.perceive(domain.create({}, 1, ["ME"]).snapshot_dict(), "ME")


def test_the_planner_is_a_mechanism_picked_by_name(program):
    assert SOLVERS["rogue"] is RoguePlanner
    assert isinstance(Engine(program, solver="rogue").solver, RoguePlanner)
    with pytest.raises(LangError, match="unknown solver 'prodigy'; known: means-ends, rogue"):
        Engine(program, solver="prodigy")


def test_one_cycle_sends_the_first_step_and_explains_the_plan(program):
    engine = Engine(program, solver="rogue")
    state = engine.add_goal(engine.initial_state(), "(delivered mail-mitchell r-5313)", 5,
                            "g1")
    result = engine.cycle(state, start_percepts())
    d = result.decision
    assert [a.to_list() for a in d.actions] == [["*goto", "r-5303"]]
    assert d.status_of("g1").value == "active"
    assert d.paths[0].goal_id == "g1" and d.path[0].skill == "<goto-pickup-loc mitchell r-5303>"
    planner = d.to_dict()["planner"]
    assert planner["tails"][0]["plan"] == [
        "<goto-pickup-loc mitchell r-5303>", "<acquire-item r-5303 mitchell mail-mitchell>",
        "<goto-deliver-loc mitchell r-5313>", "<deliver-item r-5313 mitchell mail-mitchell>"]
    assert planner["executing"]["waiting"] == [["*goto", "r-5303"]]
    assert planner["sending"] == [["*goto", "r-5303"]]
    assert planner["order"] == {"visits": ["g1 r-5303", "g1 r-5313"], "expected_m": 79.0}
    text = d.explain()
    assert "planner (ROGUE, seed 003): head-plan 0 step(s)" in text
    assert "  g1 p5 selected (delivered mail-mitchell r-5313) -- top priority" in text
    # until its outcome comes back the goto is sent again (the world's operation goes on)
    again = engine.cycle(result.state, start_percepts())
    assert [a.to_list() for a in again.decision.actions] == [["*goto", "r-5303"]]
    assert again.decision.status_of("g1").value == "active"
    assert again.decision.path[0].mode == "executing"
    assert again.state.planner.head == ()


def test_a_request_of_the_planners_own_model_is_satisfied_by_it(program):
    engine = Engine(program, solver="rogue")
    state = engine.add_goal(engine.initial_state(), "(mtg-scheduled)", 3, "g1")
    known = replace(state, planner=PlannerState(model=("(mtg-scheduled)",)))
    done = engine.cycle(known, start_percepts())
    assert done.decision.status_of("g1").value == "satisfied"


def test_teleo_step_shows_the_planner(tmp_path):
    percepts = tmp_path / "office.json"
    percepts.write_text(json.dumps(start_percepts()))
    teleo = str(Path(sys.executable).parent / "teleo")
    done = subprocess.run([teleo, "step", str(PROGRAM), "--percepts", str(percepts),
                           "--goal", "(mtg-scheduled):3", "--mechanism", "rogue", "--json"],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["decision"]["actions"] == [["*say", "Going", "to", "room", 5309],
                                          ["*goto", "r-5309"]]
    assert out["decision"]["planner"]["firings"] == [   # back-chaining, then goal selection
        "prefer bindings LOOK-AT-CLOSEST-CONF-ROOM-FIRST (schedule-meeting r-5309) over "
        "(schedule-meeting r-5311)",
        "select goal SELECT-TOP-PRIORITY-AND-COMPATIBLE-GOALS g1 (mtg-scheduled)"]
    assert out["state"]["planner"]["executing"]["step"]["name"] == "goto-room"
    bad = subprocess.run([teleo, "step", str(PROGRAM), "--percepts", str(percepts),
                          "--mechanism", "prodigy"], cwd=ROOT, capture_output=True, text=True,
                         timeout=60)
    assert bad.returncode == 1 and "unknown solver 'prodigy'" in bad.stderr
    assert "Traceback" not in bad.stderr


def _run(program, cycles: int, restart_at: int | None = None):
    """Figure 6 cycle by cycle in the office world; at ``restart_at`` the engine state is
    written as JSON and read back by a new Engine, as a restarted executive does."""
    domain = get_domain("office")
    world = domain.create({}, 1, ["ME"])
    engine = Engine(program, solver="rogue")
    state = engine.add_goal(engine.initial_state(), "(delivered mail-mitchell r-5313)", 5,
                            "g1")
    outcomes, sent = [], []
    for cycle in range(cycles):
        if cycle == 10:
            state = engine.add_goal(state, "(delivered fax-jhm r-5313)", 5, "g2")
        if cycle == restart_at:
            state = EngineState.from_dict(json.loads(json.dumps(state.to_dict())))
            engine = Engine(program, solver="rogue")
        result = engine.cycle(state, domain.perceive(world.snapshot_dict(), "ME"), outcomes)
        state = result.state
        actions = [a.to_list() for a in result.decision.actions]
        sent.append(actions)
        outcomes = world.apply_actions("ME", actions)
        world.step()
    return sent, state


def test_the_planner_state_survives_a_restart_exactly(program):
    whole, end = _run(program, 200)
    broken, end2 = _run(program, 200, restart_at=120)   # mid-goto to jhm, both plans pending
    assert broken == whole
    assert end2.planner.to_dict() == end.planner.to_dict()
    assert [a.step for a in end.planner.head][:3] == [
        "<goto-pickup-loc mitchell r-5303>", "<acquire-item r-5303 mitchell mail-mitchell>",
        "<goto-pickup-loc jhm r-5311>"]
