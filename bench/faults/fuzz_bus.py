"""The bus readers of every process, for the fuzz drill (bench/faults/fuzz.py; issue 24, item 4).

Each reader is the real code a process runs on what it reads from the bus, fed in-process:
bytes through `bus.codec.decode`, then the process's own step (agents/processes/*.py
make_step) or the world's own call (inject, apply_actions), and whatever the process then
writes checked too (encoded again, and the world's trace line made), since a value a reader
lets through must not crash the next writer. The valid messages mutated come from a real
lockstep pipeline of the same steps (`Pipeline`: a real pymunk world, perception, inference,
executive and the goal-entry process's store, one cycle after another).

    world-events-DOMAIN  an event (plain data or a WorldEvent payload) -> World.inject
    actions-DOMAIN       an Actions payload -> World.apply_actions, its memory echoed
    world-state-DOMAIN   a WorldState payload -> the perception step
    percepts-msg         a Percepts payload -> the inference step
    executive            percepts, beliefs and goal list payloads, one mutated -> executive
                         (the SCS errands program; executive-blocks: the means-ends solver
                         and learner; executive-office: ROGUE's planner)
    memory               a Percepts payload whose memory is mutated -> inference, executive
    intention            an Intention payload -> the goal-entry process's status mirror
    codec                any bytes on any key -> bus.codec.decode
"""

from __future__ import annotations

import logging
import random
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from fuzz_values import JUNK, fields_of, mutate, pool_of, swap, wire

from agents.processes import executive, inference, perception
from agents.processes.agent_setup import AgentSetup
from agents.processes.goals import GoalEntry, engine_validator
from bus import keys
from bus.codec import decode, encode
from bus.errors import CodecError, Refused
from bus.messages import Envelope, EventReply, WorldEvent, WorldState
from world.domain import get_domain
from world.run_scenario import load_scenario
from world.trace import trace_line

ROOT = Path(__file__).resolve().parents[2]
RUN = "fuzz"
SCENARIOS = {"driving": "scenarios/errands_demo.toml", "blocks": "scenarios/blocks_mishaps.toml",
             "office": "scenarios/office_errand.toml"}
WHOLE = ("malformed msgpack", "expected a msgpack map", "unknown schema version",
         "unknown message kind", "wrong message kind", "malformed envelope",
         "expected a map with a", "lacks field", ": missing; expected", "unknown field '",
         "unknown kind ")
"""Refusals of a payload as a whole, and of a field by its name where the input has none
(missing, unknown)."""
log = logging.getLogger("fuzz.bus")
log.setLevel(logging.CRITICAL)


class _Desk:
    """What the goal-entry process publishes each cycle, kept instead of sent."""

    def __init__(self) -> None:
        self.run, self.sent = RUN, []

    def envelope(self, cycle: int) -> Envelope:
        return Envelope(1, RUN, cycle, "goals", 0)

    def publish(self, key: str, msg: Any) -> None:
        self.sent.append((key, msg))

    def publish_many(self, items: Any) -> None:
        self.sent.extend(items)


@dataclass
class Pipeline:
    """One agent's lockstep cycle in-process, as the processes run it; `bases` holds the
    bus form (msgpack bodies as plain data) of every message of every cycle run."""

    domain: str
    tmp: Path

    def __post_init__(self) -> None:
        sc = self.scenario = load_scenario(ROOT / SCENARIOS[self.domain])
        self.agent, program = sc.agent_ids[0], str(sc.agents[0].program)
        self.world = get_domain(sc.domain).create(sc.world_table, sc.run.seed, sc.agent_ids)
        a = self.agent
        self.keys = {"state": keys.world_state(RUN), "percepts": keys.percepts(RUN, a),
                     "beliefs": keys.beliefs(RUN, a), "goals": keys.goal_list(RUN, a),
                     "actions": keys.actions(RUN, a), "intention": keys.intention(RUN, a),
                     "events": keys.world_events(RUN)}
        self.perceive = perception.make_step(AgentSetup(run=RUN, agent=a))
        self.infer = inference.make_step(AgentSetup(run=RUN, agent=a, program=program), log)
        self.decide = executive.make_step(AgentSetup(run=RUN, agent=a, program=program), log)
        self.entry = GoalEntry(sc, self.tmp / f"goals-{self.domain}.json",
                               engine_validator(sc), log)
        self.bases: dict[str, list[dict]] = {k: [] for k in self.keys}
        self.outcomes: dict = {a: []}
        self.memory: dict = {a: {}}
        self.cycle = 0

    def _bus(self, kind: str, msg: Any) -> Any:
        """``msg`` as its reader gets it (encoded and decoded), its body kept as a base."""
        data = encode(msg)
        self.bases[kind].append(decode_plain(data))
        return decode(self.keys[kind], data)

    def run(self, cycles: int) -> Pipeline:
        for _ in range(cycles):
            t, a = self.cycle, self.agent
            state = self._bus("state", WorldState(Envelope(1, RUN, t, "world", 0),
                                                  self.world.snapshot_dict(), self.outcomes,
                                                  [], dict(self.memory)))
            desk = _Desk()
            self.entry.on_world_state(desk, t)
            goals = self._bus("goals", next(m for k, m in desk.sent if k == self.keys["goals"]))
            percepts = self._bus("percepts", self.perceive(t, {self.keys["state"]: state})[0][1])
            beliefs = self._bus("beliefs", self.infer(t, {self.keys["percepts"]: percepts})[0][1])
            outs = dict(self.decide(t, {self.keys["percepts"]: percepts,
                                        self.keys["beliefs"]: beliefs,
                                        self.keys["goals"]: goals}))
            self._bus("intention", outs[self.keys["intention"]])
            acts = self._bus("actions", outs[self.keys["actions"]])
            self.memory[a] = acts.memory
            self.outcomes = {a: self.world.apply_actions(a, [list(x) for x in acts.actions])}
            self.world.step()
            self.cycle += 1
        return self


def decode_plain(data: bytes) -> dict:
    """A payload's msgpack body as plain data, packed rows unpacked (so they mutate too)."""
    import msgpack

    from bus.rows import unpacked_rows

    body = msgpack.unpackb(data, raw=False)
    for name in ("percepts", "beliefs"):
        if name in body:
            body[name] = unpacked_rows(body[name])
    return body


@dataclass(frozen=True)
class BusReader:
    """Inputs from the pipeline's bases, and the feed: True when accepted, else the reason
    of the refusal (a string); anything raised that is not a refusal is a crash."""

    make: Callable[[random.Random], Any]
    feed: Callable[[Any], bool | str]
    fields: Callable[[Any], set[str]]


def _payload(base: dict, rng: random.Random, pool: dict, where: str | None = None) -> bytes:
    """A mutated base (or, at ``where``, only that field mutated) as bytes; sometimes bytes
    cut or flipped after packing."""
    for _ in range(5):
        if where is None and rng.random() < 0.2:
            body = swap(base, rng, pool)
        elif where is None:
            body = mutate(base, rng, pool)
        else:
            body = {**base, where: mutate(base.get(where, {}), rng, pool)}
        data = wire(body)
        if data is not None:
            break
    else:
        data = wire(base)
    if rng.random() < 0.05:
        i = rng.randrange(len(data))
        data = data[:i] + bytes([rng.randrange(256)]) + data[i + 1:] if rng.random() < 0.5 \
            else data[:i]
    return data


def _fields(data: Any) -> set[str]:
    """What a refusal of ``data`` may name: its keys and short strings (packed rows read
    when they can be)."""
    import msgpack

    if not isinstance(data, bytes):
        return fields_of(data)
    try:
        return fields_of(decode_plain(data))
    except Exception:  # noqa: BLE001 - a packed row msgpack cannot read
        pass
    try:
        return fields_of(msgpack.unpackb(data, raw=False))
    except Exception:  # noqa: BLE001 - bytes msgpack cannot read: a whole-payload refusal
        return set()


def _checked_out(pipe: Pipeline, outs: list) -> None:
    """What a step wrote must encode, and decode at its reader's key."""
    for key, msg in outs:
        decode(key, encode(msg))


def world_events_reader(pipe: Pipeline, every: int = 50) -> BusReader:
    """World.inject on events (half of them through the codec first), as the world process
    applies them: each outcome must be one the world can answer with (an EventReply) and
    write; every ``every`` events the world steps, and its state with those events' outcomes
    is encoded and its trace line written (a cycle with many events)."""
    from fuzz_events import EVENT_BASES

    bases = EVENT_BASES[pipe.domain](pipe.world, pipe.agent)
    pool = pool_of(bases)
    counter = iter(range(1 << 62))
    world, outcomes = pipe.world, []

    def make(rng: random.Random) -> Any:
        roll = rng.random()
        base = rng.choice(bases)
        event = swap(base, rng, pool) if roll < 0.3 else mutate(base, rng, pool) \
            if roll < 0.95 else rng.choice(JUNK)
        if rng.random() < 0.5:
            data = wire(encode_body("WorldEvent", {"event": event}))
            return data if data is not None else event
        return event

    def feed(item: Any) -> bool | str:
        event = item
        if isinstance(item, bytes):
            try:
                msg = decode(pipe.keys["events"], item)
            except CodecError as exc:
                return str(exc)
            event = msg.event if isinstance(msg, WorldEvent) else None
        outcome = world.inject(event)
        n = next(counter)
        encode(EventReply(Envelope(1, RUN, n, "world", 0), outcome["status"] == "done",
                          outcome["reason"], outcome))
        outcomes.append(outcome)
        if len(outcomes) >= every:
            snap = world.snapshot_dict()
            decode(pipe.keys["state"], encode(WorldState(Envelope(1, RUN, n, "world", 0), snap,
                                                         {}, outcomes, {})))
            trace_line(n, snap, {}, outcomes)
            outcomes.clear()
            world.step()
        return True if outcome["status"] == "done" else outcome["reason"]

    return BusReader(make, feed, _fields)


def encode_body(kind: str, fields: dict) -> dict:
    return {"kind": kind, "env": {"v": 1, "run": RUN, "cycle": 0, "sender": "fuzz",
                                  "sent_ns": 0}, **fields}


def actions_reader(pipe: Pipeline) -> BusReader:
    """An Actions payload: decoded, applied by the world, its memory echoed in the next
    world state and written to the trace; the world steps every 20 inputs."""
    bases = pipe.bases["actions"]
    pool = pool_of(bases)
    counter = iter(range(1 << 62))
    world, agent = pipe.world, pipe.agent

    def make(rng: random.Random) -> bytes:
        return _payload(rng.choice(bases), rng, pool)

    def feed(data: bytes) -> bool | str:
        try:
            msg = decode(pipe.keys["actions"], data)
        except CodecError as exc:
            return str(exc)
        applied = [list(x) for x in msg.actions]
        outcomes = world.apply_actions(agent, applied)
        n = next(counter)
        if n % 20 == 0:
            world.step()
        snap = world.snapshot_dict()
        decode(pipe.keys["state"], encode(WorldState(Envelope(1, RUN, n, "world", 0), snap,
                                                     {agent: outcomes}, [],
                                                     {agent: msg.memory})))
        trace_line(n, snap, {agent: applied}, (), {agent: msg.memory})
        failed = [o["reason"] for o in outcomes if o["status"] != "done"]
        return failed[0] if failed else True

    return BusReader(make, feed, _fields)


def _stage(step: Callable, cycle_of: Callable[[], int], inputs: dict[str, Any]) -> bool | str:
    """Run a process's step on decoded inputs; its outputs checked; Refused is a refusal."""
    try:
        outs = step(cycle_of(), inputs)
    except Refused as exc:
        return str(exc)
    return outs


def state_reader(pipe: Pipeline) -> BusReader:
    """A WorldState payload -> the perception step; its percepts must decode at inference."""
    bases = pipe.bases["state"]
    pool = pool_of(bases)
    step = perception.make_step(AgentSetup(run=RUN, agent=pipe.agent))
    counter = iter(range(1 << 62))

    def make(rng: random.Random) -> bytes:
        return _payload(rng.choice(bases), rng, pool)

    def feed(data: bytes) -> bool | str:
        try:
            msg = decode(pipe.keys["state"], data)
        except CodecError as exc:
            return str(exc)
        outs = _stage(step, lambda: next(counter), {pipe.keys["state"]: msg})
        if isinstance(outs, str):
            return outs
        _checked_out(pipe, outs)
        return True

    return BusReader(make, feed, _fields)


def agent_reader(pipe: Pipeline, which: str) -> BusReader:
    """The inference and executive steps on mutated inputs. ``which``: "percepts" (a
    Percepts payload to inference), "executive" (one of its three inputs mutated) or
    "memory" (only a Percepts' memory mutated, to inference and executive)."""
    program = str(pipe.scenario.agents[0].program)
    a, k = pipe.agent, pipe.keys
    infer = inference.make_step(AgentSetup(run=RUN, agent=a, program=program), log)
    decide = executive.make_step(AgentSetup(run=RUN, agent=a, program=program), log)
    counter = iter(range(1 << 62))
    inputs = ("percepts", "beliefs", "goals")
    pools = {x: pool_of(pipe.bases[x]) for x in inputs}

    def make(rng: random.Random) -> dict[str, bytes]:
        i = rng.randrange(len(pipe.bases["percepts"]))
        out = {x: wire(pipe.bases[x][i]) for x in inputs}
        target = "percepts" if which in ("percepts", "memory") else rng.choice(inputs)
        where = "memory" if which == "memory" else None
        out[target] = _payload(pipe.bases[target][i], rng, pools[target], where)
        return out

    def feed(item: dict[str, bytes]) -> bool | str:
        try:
            msgs = {k[x]: decode(k[x], item[x]) for x in inputs}
        except CodecError as exc:
            return str(exc)
        t = next(counter)
        msgs = {key: replace(m, env=replace(m.env, cycle=t)) for key, m in msgs.items()}
        if which != "executive":
            outs = _stage(infer, lambda: t, {k["percepts"]: msgs[k["percepts"]]})
            if isinstance(outs, str):
                return outs
            _checked_out(pipe, outs)
        if which == "percepts":
            return True
        outs = _stage(decide, lambda: t, msgs)
        if isinstance(outs, str):
            return outs
        _checked_out(pipe, outs)
        return True

    return BusReader(make, feed, lambda item: set().union(*(_fields(v) for v in item.values())))


def intention_reader(pipe: Pipeline) -> BusReader:
    """An Intention payload -> the goal-entry process's mirror of the goals' statuses."""
    bases = pipe.bases["intention"]
    pool = pool_of(bases)

    def make(rng: random.Random) -> bytes:
        return _payload(rng.choice(bases), rng, pool)

    def feed(data: bytes) -> bool | str:
        try:
            msg = decode(pipe.keys["intention"], data)
        except CodecError as exc:
            return str(exc)
        pipe.entry.on_intention(msg)
        return True

    return BusReader(make, feed, _fields)


def codec_reader(pipes: list[Pipeline]) -> BusReader:
    """Any bytes on any key of a run: a base of any kind (or of another kind: the wrong key)
    mutated before or after packing, or random bytes."""
    cases = [(p.keys[kind], base) for p in pipes for kind, bases in p.bases.items()
             for base in bases[:40]]
    cases += [(keys.goals(RUN, "ME"), encode_body("GoalRequest", {"op": "post", "agent": "ME",
                                                                   "goal": "(x)"}))]
    pool = pool_of([b for _, b in cases])
    every_key = sorted({key for key, _ in cases})

    def make(rng: random.Random) -> tuple[str, bytes]:
        key, base = rng.choice(cases)
        if rng.random() < 0.1:
            key = rng.choice(every_key)
        if rng.random() < 0.05:
            return key, bytes(rng.randrange(256) for _ in range(rng.randint(0, 64)))
        return key, _payload(base, rng, pool)

    def feed(item: tuple[str, bytes]) -> bool | str:
        try:
            msg = decode(*item)
        except CodecError as exc:
            return str(exc)
        encode(msg)
        return True

    return BusReader(make, feed, lambda item: _fields(item[1]))


def readers(tmp: Path, cycles: int = 60) -> dict[str, Callable[[], BusReader]]:
    """Name -> a maker of each bus reader (pipelines are run once, on first use)."""
    made: dict[str, Pipeline] = {}

    def pipe(domain: str) -> Pipeline:
        if domain not in made:
            made[domain] = Pipeline(domain, tmp).run(cycles)
        return made[domain]

    out: dict[str, Callable[[], BusReader]] = {}
    for d in SCENARIOS:   # events need no bases: a world of its own, at cycle 0
        out[f"world-events-{d}"] = lambda d=d: world_events_reader(Pipeline(d, tmp))
        out[f"actions-{d}"] = lambda d=d: actions_reader(pipe(d))
        out[f"world-state-{d}"] = lambda d=d: state_reader(pipe(d))
    for which in ("percepts", "executive", "memory"):
        name = "percepts-msg" if which == "percepts" else which
        out[name] = lambda which=which: agent_reader(pipe("driving"), which)
    for d in ("blocks", "office"):   # the solver with learning, and ROGUE's planner
        out[f"executive-{d}"] = lambda d=d: agent_reader(pipe(d), "executive")
    out["intention"] = lambda: intention_reader(pipe("driving"))
    out["codec"] = lambda: codec_reader([pipe(d) for d in SCENARIOS])
    return out

