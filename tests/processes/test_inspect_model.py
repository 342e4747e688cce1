"""The inspector's bookkeeping: rates, sizes, cycle latency and stage figures per key."""

from __future__ import annotations

from rich.console import Console

from bus.messages import Actions, Envelope, ProcessStats, WorldState
from tools.inspect import Model, render

RUN = "r1"


def env(cycle: int, sender: str, sent_ms: float) -> Envelope:
    return Envelope(1, RUN, cycle, sender, int(sent_ms * 1e6))


def test_latency_is_measured_from_the_world_state_of_the_same_cycle():
    model = Model(RUN)
    for t in range(3):
        base = 1000.0 * t
        model.feed(f"teleo/{RUN}/world/state", WorldState(env(t, "world", base), {}, {}, []),
                   b"x" * 900, int(base * 1e6))
        model.feed(f"teleo/{RUN}/agent/ME/actions",
                   Actions(env(t, "ME.executive", base + 2.5), "ME", (["*gas", 1],)), b"y" * 40,
                   int((base + 3) * 1e6))
        model.feed(f"teleo/{RUN}/stats/ME.inference",
                   ProcessStats(env(t, "ME.inference", base + 1), "ME.inference", 0.25, t), b"z",
                   int((base + 1) * 1e6))
    actions = model.keys["agent/ME/actions"]
    assert (actions.count, actions.size, actions.last_cycle) == (3, 40, 2)
    assert actions.latency_ms == 2.5
    assert 0.9 < actions.rate(int(2003e6)) < 1.1  # one per second [1/s]
    assert model.stages["ME.inference"] == {"compute_ms": 0.25, "late": 2, "cycle": 2}
    assert '"*gas"' in model.decoded("agent/ME/actions")


def test_the_view_lists_processes_and_keys():
    model = Model(RUN)
    model.feed(f"teleo/{RUN}/world/state", WorldState(env(0, "world", 0), {}, {}, []), b"x", 0)
    console = Console(width=120, record=True)
    console.print(render(model, {"world"}, {"world": 1, "ME.inference": 2}, None))
    text = console.export_text()
    assert "world/state" in text and "GONE" in text  # ME.inference appeared twice, now gone
