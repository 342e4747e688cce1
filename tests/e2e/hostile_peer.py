"""A stranger on an open run, for test_world_events_live.py (drill d4e over the bus): it
publishes N random world events, mutated from the run's own world's events (bench/
fuzz_events.py, bench/faults/fuzz_values.py), asks a few of them as `teleo event` does, and puts
spoilt copies of the run's own messages on every key it hears: stale ones (through each
process's codec) and world states one cycle ahead whose snapshot is not the world's (so that
perception refuses them). Prints one JSON line: what it sent and what the world answered.

    python tests/e2e/hostile_peer.py --events 300 --seed 11      (TELEO_RUN_DIR of the run)
"""

from __future__ import annotations

import json
import random
import sys
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.append(str(ROOT / "bench" / "faults"))

from fuzz_events import EVENT_BASES  # noqa: E402
from fuzz_values import JUNK, mutate, pool_of, swap, wire  # noqa: E402

from bus import keys  # noqa: E402
from bus.codec import decode  # noqa: E402
from bus.errors import BusError, CodecError  # noqa: E402
from bus.messages import EventReply, WorldEvent  # noqa: E402
from bus.node import open_node  # noqa: E402
from tools.runs import runfile  # noqa: E402
from world.domain import get_domain  # noqa: E402
from world.run_scenario import load_scenario  # noqa: E402


def event_bodies(scenario: Path, n: int, rng: random.Random) -> list:
    sc = load_scenario(scenario)
    world = get_domain(sc.domain).create(sc.world_table, sc.run.seed, sc.agent_ids)
    bases = EVENT_BASES[sc.domain](world, sc.agent_ids[0])
    pool = pool_of(bases)
    out = []
    for _ in range(n):
        base, roll = rng.choice(bases), rng.random()
        out.append(swap(base, rng, pool) if roll < 0.3 else mutate(base, rng, pool)
                   if roll < 0.95 else rng.choice(JUNK))
    return out


def envelope(run: str, cycle: int) -> dict:
    return {"v": 1, "run": run, "cycle": cycle, "sender": "stranger", "sent_ns": time.time_ns()}


def _unpacked(payload: bytes) -> object:
    """A payload as msgpack reads it, or None."""
    import msgpack

    try:
        return msgpack.unpackb(payload, raw=False)
    except (ValueError, msgpack.ExtraData, msgpack.FormatError, msgpack.StackError):
        return None


@click.command()
@click.option("--scenario", type=click.Path(exists=True), required=True)
@click.option("--events", "n", default=300)
@click.option("--asked", default=5, help="How many of the events are asked, not published.")
@click.option("--seed", default=11)
def main(scenario: str, n: int, asked: int, seed: int) -> None:
    import msgpack

    rng = random.Random(seed)
    info = runfile.locate(None)
    events_key = keys.world_events(info.run)
    sent = {"published": 0, "decodable": 0, "asked": 0, "answers": [], "spoilt": 0}
    with open_node(runfile.bus_config(info), info.run, "stranger") as node:
        heard = node.subscribe_ring(keys.run_all(info.run), capacity=256)
        time.sleep(1.0)
        # an intention's statuses are mirrored whatever its cycle: a forged one would change
        # the goals (open runs are not protected against that: docs/faults.md)
        own = [(r.key, r.payload) for r in heard.drain()
               if "/proc/" not in r.key and not r.key.endswith("/intention")]
        for i, event in enumerate(event_bodies(Path(scenario), n, rng)):
            data = wire({"kind": "WorldEvent", "env": envelope(info.run, -1), "event": event})
            if data is None:
                continue
            if sent["asked"] < asked and isinstance(event, dict):
                try:
                    reply = node.query(events_key, WorldEvent(node.envelope(), event), 20.0)
                    sent["answers"].append([reply.ok, reply.reason] if isinstance(
                        reply, EventReply) else ["not an EventReply", str(reply)])
                except BusError as exc:
                    sent["answers"].append(["no answer", str(exc)])
                sent["asked"] += 1
                continue
            node.put_raw(events_key, data)
            sent["published"] += 1
            try:
                sent["decodable"] += isinstance(decode(events_key, data), WorldEvent)
            except CodecError:
                pass
            if i % 3 == 0:
                time.sleep(0.01)   # a few events a cycle, not all at once
        for key, payload in own[:200]:
            body = msgpack.unpackb(payload, raw=False)
            if not isinstance(body, dict):
                continue
            body = mutate({k: v for k, v in body.items() if k != "env"}, rng)
            stale = wire({**body, "env": envelope(info.run, 0)} if isinstance(body, dict)
                         else body)
            if stale is not None:
                node.put_raw(key, stale)
                sent["spoilt"] += 1
        # the world's latest state (not one of the stale copies spoilt above, which this
        # session hears too), its snapshot spoilt, for cycles a little ahead
        states = [body for r in heard.drain() if r.key == keys.world_state(info.run)
                  for body in [_unpacked(r.payload)]
                  if isinstance(body, dict) and isinstance(body.get("env"), dict)
                  and body["env"].get("sender") == "world"]
        if states:
            body = max(states, key=lambda b: b["env"]["cycle"])
            body["snapshot"]["cars"][0]["x"] = "a"
            now = body["env"]["cycle"]
            for ahead in range(2, 40, 3):
                body["env"] = envelope(info.run, now + ahead)
                node.put_raw(keys.world_state(info.run), msgpack.packb(body, use_bin_type=True))
                sent["spoilt"] += 1
        time.sleep(0.5)   # let the last puts leave before the session closes
    print(json.dumps(sent))


if __name__ == "__main__":
    main()
