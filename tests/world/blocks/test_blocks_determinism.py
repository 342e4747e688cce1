"""One config, seed and action sequence give the same run, snapshot for snapshot; random
towers are a function of their seed."""

from __future__ import annotations

import json

from blocks_helpers import world

from world.blocks.config import load_blocks_config
from world.blocks.snapshot import BlocksSnapshot

SCRIPT = [["*unstack", "C", "B"], ["*putdown", "C", "T"], ["*unstack", "B", "A"],
          ["*stack", "B", "C"], ["*pickup", "A", "T"], ["*stack", "A", "B"], ["*wait"]]


def _run(seed: int, **table) -> list[str]:
    w = world([["A", "B", "C"]], seed=seed, **table)
    w.inject({"kind": "add", "block": "D", "column": 4, "size": [1.0, 1.0]})
    w.inject({"kind": "knock", "block": "D", "speed": 3.0})
    out = []
    for action in SCRIPT:
        w.apply_actions("ME", [action])
        w.step()
        out.append(json.dumps(w.snapshot_dict(), sort_keys=True))
    return out


def test_the_same_run_twice_is_identical_to_the_last_bit():
    first, second = _run(1), _run(1)
    assert first == second
    final = json.loads(first[-1])
    assert final["counters"]["ME"] == {"actions_done": 6, "actions_failed": 0,
                                       "blocks_moved": 3, "blocks_dropped": 0}
    assert any(e["kind"] == "fell" and e["block"] == "D"
               for snap in first for e in json.loads(snap)["events"])


def test_random_towers_are_a_function_of_their_seed():
    def layout(**kw):
        return load_blocks_config({"random_towers": {"blocks": 7, **kw}}, seed=kw.pop("s", 0))

    assert layout(seed=3).towers == layout(seed=3).towers
    assert len({layout(seed=s).towers for s in range(10)}) > 5
    towers = layout(seed=3).towers
    assert sorted(b for t in towers for b in t) == list("ABCDEFG")


def test_random_towers_without_a_seed_follow_the_run_seed():
    a = load_blocks_config({"random_towers": 6}, seed=11).towers
    assert a == load_blocks_config({"random_towers": 6}, seed=11).towers
    assert any(load_blocks_config({"random_towers": 6}, seed=s).towers != a for s in range(5))


def test_a_snapshot_round_trips_through_plain_data():
    w = world([["A", "B"]], agents=("ME", "YOU"), holding={"YOU": "C"})
    w.inject({"kind": "knock", "block": "B"})
    w.step()
    d = json.loads(json.dumps(w.snapshot_dict()))
    assert BlocksSnapshot.from_dict(d).to_dict() == d
    assert [b["held_by"] for b in d["blocks"]] == ["", "", "YOU"]
