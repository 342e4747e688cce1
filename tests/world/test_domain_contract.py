"""Every registered domain meets the World contract (world/domain.py): determinism for a
seed, plain-data snapshots, failed outcomes that name an unknown agent or action, a safe
action for a silent agent, and a perception that changes nothing."""

from __future__ import annotations

import copy
import json

import pytest

from world.domain import DOMAINS, World, get_domain
from world.errors import ConfigError


def _run(name: str, seed: int, cycles: int = 30) -> list[str]:
    domain = get_domain(name)
    world = domain.create({}, seed, ["ME"])
    out = []
    for _ in range(cycles):
        world.apply_actions("ME", world.safe_actions("ME"))
        world.step()
        out.append(json.dumps(world.snapshot_dict(), sort_keys=True))
    return out


@pytest.mark.parametrize("name", DOMAINS)
def test_one_seed_gives_one_run(name: str) -> None:
    assert _run(name, 3) == _run(name, 3)


@pytest.mark.parametrize("name", DOMAINS)
def test_snapshot_is_plain_data_naming_its_domain(name: str) -> None:
    world = get_domain(name).create({}, 1, ["ME"])
    assert isinstance(world, World)
    snap = world.snapshot_dict()
    assert json.loads(json.dumps(snap)) == snap
    assert snap["domain"] == name and snap["cycle"] == 0 and "ME" in snap["counters"]


@pytest.mark.parametrize("name", DOMAINS)
def test_unknown_agent_and_action_fail_with_their_names(name: str) -> None:
    world = get_domain(name).create({}, 1, ["ME"])
    [out] = world.apply_actions("NOBODY", [["*cruise"]])
    assert out["status"] == "failed" and "NOBODY" in out["reason"]
    [out] = world.apply_actions("ME", [["*fly-away", 3]])
    assert out["status"] == "failed" and "*fly-away" in out["reason"]


@pytest.mark.parametrize("name", DOMAINS)
def test_the_actions_a_domain_says_it_knows_are_the_ones_its_world_knows(name: str) -> None:
    """``Domain.actions`` is what `teleo check` holds programs to: each name is one the world
    takes (an outcome may fail for its arguments, never as an unknown action)."""
    domain = get_domain(name)
    world = domain.create({}, 1, ["ME"])
    actions = domain.actions or world.actions  # the pddl world's come from its domain file
    assert actions
    for action in actions:
        [out] = world.apply_actions("ME", [[action]])
        assert "unknown action" not in out["reason"], (action, out)


@pytest.mark.parametrize("name", DOMAINS)
def test_safe_actions_are_accepted(name: str) -> None:
    world = get_domain(name).create({}, 1, ["ME"])
    outcomes = world.apply_actions("ME", world.safe_actions("ME"))
    assert outcomes and all(o["status"] == "done" for o in outcomes)


@pytest.mark.parametrize("name", DOMAINS)
def test_perceive_changes_nothing(name: str) -> None:
    domain = get_domain(name)
    world = domain.create({}, 1, ["ME"])
    world.step()
    snap = world.snapshot_dict()
    before = copy.deepcopy(snap)
    percepts = domain.perceive(snap, "ME")
    assert snap == before and percepts
    assert all(isinstance(p, list) and isinstance(p[0], str) for p in percepts)


def test_an_unknown_domain_is_refused_with_the_known_ones() -> None:
    with pytest.raises(ConfigError, match="driving"):
        get_domain("moon")
