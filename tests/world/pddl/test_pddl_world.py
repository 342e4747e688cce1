"""The pddl world's semantics (world/pddl/): typing with a hierarchy and `either`, constants,
equality, negative preconditions; a refused action names its reason and changes nothing; one
action a cycle; snapshots, percepts, checkpoints and pictures."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from pddl_helpers import BLOCKS, TRUCKS, world_of

from world.domain import get_domain


def _atoms(world) -> set[tuple[str, ...]]:
    return {tuple(a) for a in world.snapshot_dict()["atoms"]}


def _do(world, *action, agent: str = "ME") -> dict:
    [out] = world.apply_actions(agent, [list(action)])
    world.step()
    return out


def test_an_action_whose_preconditions_hold_adds_and_deletes_its_effects():
    w = world_of(TRUCKS)
    assert _do(w, "*drive", "t1", "home", "shop")["status"] == "done"
    atoms = _atoms(w)
    assert ("at", "t1", "shop") in atoms and ("at", "t1", "home") not in atoms


def test_a_false_precondition_is_named_and_nothing_changes():
    w = world_of(TRUCKS)
    before = _atoms(w)
    out = _do(w, "*drive", "t1", "shop", "home")
    assert out["status"] == "failed"
    assert "precondition (at t1 shop) is false" in out["reason"] and "ME" in out["reason"]
    assert _atoms(w) == before
    assert w.snapshot_dict()["counters"]["ME"] == {"actions_done": 0, "actions_failed": 1}


def test_negative_precondition_and_inequality():
    w = world_of(TRUCKS)
    out = _do(w, "*drive", "v1", "depot", "home")      # v1 is broken
    assert "precondition (not (broken v1)) is false" in out["reason"]
    out = _do(w, "*drive", "t1", "shop", "shop")       # (link shop shop), but from = to
    assert "(at t1 shop) is false" in out["reason"]
    assert _do(w, "*drive", "t1", "home", "shop")["status"] == "done"
    out = _do(w, "*drive", "t1", "shop", "shop")
    assert "precondition (not (= shop shop)) is false" in out["reason"]


def test_constants_and_equality_with_a_constant():
    w = world_of(TRUCKS)
    assert "precondition (= home depot) is false" in _do(w, "*stay", "t1", "home")["reason"]
    assert _do(w, "*service", "v1")["status"] == "done"           # (at v1 depot): a constant
    assert ("ready",) in _atoms(w) and ("broken", "v1") not in _atoms(w)


def test_types_below_and_either():
    w = world_of(TRUCKS)
    out = _do(w, "*drive", "p1", "home", "shop")
    assert "argument 1 ?v: p1 is a parcel, not vehicle" in out["reason"]
    assert _do(w, "*load", "p1", "t1", "home")["status"] == "done"   # truck: one of either
    out = _do(w, "*load", "p2", "shop", "shop")
    assert "argument 2 ?v: shop is a place, not truck or van" in out["reason"]


@pytest.mark.parametrize("action, words", [
    (["*fly", "t1"], "unknown action *fly; the domain trucks knows *drive *load"),
    (["*drive", "t1"], "expected 3 argument(s) (*drive ?v ?from ?to), got 1"),
    (["*drive", "t9", "home", "shop"], "argument 1 ?v: unknown object t9"),
    (["*drive", 3, "home", "shop"], "argument 1 ?v: expected an object's name, got 3"),
    ([], "an action is a list"),
])
def test_malformed_actions_fail_with_a_reason(action, words):
    w = world_of(TRUCKS)
    before = _atoms(w)
    out = _do(w, *action)
    assert out["status"] == "failed" and words in out["reason"]
    assert _atoms(w) == before


def test_upper_case_names_are_the_same_names():
    w = world_of(TRUCKS)
    assert _do(w, "*DRIVE", "T1", "Home", "shop")["status"] == "done"
    assert w.plan == [["drive", "t1", "home", "shop"]]


def test_one_action_a_cycle_the_second_fails_and_changes_nothing():
    w = world_of(TRUCKS)
    first, second = w.apply_actions("ME", [["*drive", "t1", "home", "shop"],
                                           ["*load", "p2", "t1", "shop"]])
    assert first["status"] == "done" and second["status"] == "failed"
    assert "one action a cycle: (*drive t1 home shop) was this cycle's" in second["reason"]
    assert ("in", "p2", "t1") not in _atoms(w)
    w.step()
    assert _do(w, "*load", "p2", "t1", "shop")["status"] == "done"


def test_agents_share_the_state_each_one_action_a_cycle():
    w = world_of(TRUCKS, ("ME", "YOU"))
    assert w.apply_actions("ME", [["*drive", "t1", "home", "shop"]])[0]["status"] == "done"
    assert w.apply_actions("YOU", [["*load", "p2", "t1", "shop"]])[0]["status"] == "done"
    assert w.apply_actions("NOBODY", [["*wait"]])[0]["reason"].startswith("unknown agent")


def test_snapshot_percepts_and_goal():
    w = world_of(BLOCKS)
    snap = w.snapshot_dict()
    assert json.loads(json.dumps(snap)) == snap
    assert (snap["domain"], snap["cycle"], snap["time"]) == ("pddl", 0, 0.0)
    assert snap["goal"] == ["(on d c)", "(on c b)", "(on b a)"] and not snap["goal_holds"]
    percepts = get_domain("pddl").perceive(snap, "ME")
    assert ["object", "a", "type", "block"] in percepts
    assert ["object", "a", "type", "object"] in percepts
    assert ["handempty", "_"] in percepts and ["clear", "_", "arg1", "a"] in percepts
    for move in (["*pick-up", "b"], ["*stack", "b", "a"]):
        _do(w, *move)
    percepts = get_domain("pddl").perceive(w.snapshot_dict(), "ME")
    assert ["on", "_", "arg1", "b", "arg2", "a"] in percepts


def test_safe_action_waits_and_is_no_step_of_the_plan():
    w = world_of(BLOCKS)
    before = _atoms(w)
    assert [o["status"] for o in w.apply_actions("ME", w.safe_actions("ME"))] == ["done"]
    assert _atoms(w) == before and w.plan == []


def test_checkpoint_restores_the_same_world():
    w = world_of(TRUCKS)
    _do(w, "*drive", "t1", "home", "shop")
    again = get_domain("pddl").restore(w.checkpoint())
    assert again.snapshot_dict() == w.snapshot_dict()
    _do(w, "*load", "p2", "t1", "shop")
    _do(again, "*load", "p2", "t1", "shop")
    assert again.snapshot_dict() == w.snapshot_dict()


def test_render_draws_a_png_and_a_gif(tmp_path):
    w = world_of(BLOCKS)
    snaps = [w.snapshot_dict()]
    _do(w, "*pick-up", "b")
    snaps.append(w.snapshot_dict())
    domain = get_domain("pddl")
    assert domain.render(snaps, tmp_path / "s.png", "ME") == 1
    assert (tmp_path / "s.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert domain.render(snaps, tmp_path / "s.gif", "ME") == 2
    assert (tmp_path / "s.gif").read_bytes()[:6] == b"GIF89a"


def test_the_view_shows_the_worlds_own_picture():
    from tools.view.scene import map_of, render_png

    w = world_of(BLOCKS)
    snaps = [w.snapshot_dict()]
    assert map_of(snaps[-1])["drawn"] is False     # the page asks for the domain's PNG
    assert render_png(snaps, "ME")[:8] == b"\x89PNG\r\n\x1a\n"


def test_teleo_render_draws_a_pddl_scenario(tmp_path):
    from click.testing import CliRunner

    from tools.cli import cli

    scenario = Path(__file__).resolve().parents[3] / "scenarios" / "pddl" / "sussman.toml"
    out = CliRunner().invoke(cli, ["render", str(scenario), "--out", str(tmp_path / "s.png")])
    assert out.exit_code == 0, out.output
    assert (tmp_path / "s.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
