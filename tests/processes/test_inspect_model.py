"""The inspector's bookkeeping: rates, sizes, latencies by arrival and stage figures per key
(issue 12, item 12)."""

from __future__ import annotations

from rich.console import Console

from bus.messages import Actions, Beliefs, Envelope, Percepts, ProcessStats, WorldState
from tools.commands.inspect import Model, render

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
                   int((base + 2.5) * 1e6))
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


def test_the_realtime_pacing_wait_is_not_counted_as_latency():
    """In realtime the world stamps its state ~100 ms before it sends it (the clock waits for
    the period's start); latencies are by arrival, so they show the pipeline, 3 ms here."""
    model = Model(RUN)
    arrive = {"world/state": 100.0, "agent/ME/percepts": 101.0, "agent/ME/beliefs": 101.5,
              "agent/ME/actions": 103.0}
    model.feed(f"teleo/{RUN}/world/state", WorldState(env(7, "world", 0.0), {}, {}, []), b"x",
               int(arrive["world/state"] * 1e6))               # stamped 100 ms early
    model.feed(f"teleo/{RUN}/agent/ME/percepts", Percepts(env(7, "ME.perception", 100.9), "ME",
               ()), b"p", int(arrive["agent/ME/percepts"] * 1e6))
    model.feed(f"teleo/{RUN}/agent/ME/beliefs", Beliefs(env(7, "ME.inference", 101.4), "ME",
               ()), b"b", int(arrive["agent/ME/beliefs"] * 1e6))
    model.feed(f"teleo/{RUN}/agent/ME/actions", Actions(env(7, "ME.executive", 102.9), "ME",
               ()), b"a", int(arrive["agent/ME/actions"] * 1e6))
    latency = {k: round(model.keys[k].latency_ms, 3) for k in arrive}
    stage = {k: model.keys[k].stage_ms for k in arrive}
    assert latency == {"world/state": 0.0, "agent/ME/percepts": 1.0, "agent/ME/beliefs": 1.5,
                       "agent/ME/actions": 3.0}
    assert stage == {"world/state": None, "agent/ME/percepts": 1.0, "agent/ME/beliefs": 0.5,
                     "agent/ME/actions": 1.5}


def test_the_view_shows_restarts_and_the_worlds_own_stats():
    model = Model(RUN)
    model.feed(f"teleo/{RUN}/stats/world", ProcessStats(env(4, "world", 0), "world", 0.8, 0),
               b"s", 0)
    console = Console(width=160, record=True)
    console.print(render(model, {"world", "ME.inference"}, {"world": 1, "ME.inference": 2},
                         None, {"ME.inference": 1}))
    rows = {line.split()[1]: line.split()[2:] for line in console.export_text().splitlines()
            if line.strip().startswith("│") and len(line.split()) > 8}
    assert rows["world"][:6] == ["│", "up", "│", "1", "│", "0"] and "0.80" in rows["world"]
    assert rows["ME.inference"][:6] == ["│", "up", "│", "2", "│", "1"]


def test_stage_figures_are_read_from_the_stats_an_output_carries():
    """Issue 36: a stage's stats travel in its output; the inspector shows its own only (the
    executive's Actions carry the whole pipeline's, each counted where its stage sent it)."""
    model = Model(RUN)
    carried = {"ME.perception": [1.25, 0], "ME.inference": [0.5, 1]}
    model.feed(f"teleo/{RUN}/agent/ME/beliefs",
               Beliefs(env(5, "ME.inference", 0), "ME", (), {}, carried), b"b", 0)
    model.feed(f"teleo/{RUN}/agent/ME/actions",
               Actions(env(5, "ME.executive", 0), "ME", (), {},
                       {**carried, "ME.perception": [9.0, 0], "ME.executive": [0.75, 0]}),
               b"a", 0)
    assert model.stages == {"ME.inference": {"compute_ms": 0.5, "late": 1, "cycle": 5},
                            "ME.executive": {"compute_ms": 0.75, "late": 0, "cycle": 5}}
