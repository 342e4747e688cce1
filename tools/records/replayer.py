"""`teleo replay RECORD`: a run record played back on a bus (the command is in
tools/commands/bus.py, the playing in tools/records/player.py).

Which bus: the running launch's (the only one, or `--onto RUN`), the router named with
`--connect`, or, when no launch is running and none is named, a router of its own on
loopback at an ephemeral port (`python -m bus.router`, tied to this command's life as a
launch's children are: bus/lifeline.py), said on stderr so that `teleo echo --connect` or
`teleo view --connect` can follow; it is stopped when the replay ends. The replayed run keeps
its own run id.
"""

from __future__ import annotations

import contextlib
import os

import click

from bus.codec import decode
from bus.config import LOOPBACK_ANY, BusConfig
from bus.errors import BusError
from bus.keys import world_static
from bus.lifeline import ENV_PARENT
from bus.node import open_node
from bus.record import from_record
from bus.router import RouterProcess, spawn_router
from bus.stage import stop_on_signals
from tools.records.player import NoKeys, Player, cycles_of, from_cycle, terminal_keys
from tools.runs import runfile
from tools.runs.target import Target, client_of, connect_given, find_target, launches_running

SETTLE_S = 1.0
"""[s] a router of its own is kept after the last message, for what it still delivers."""


def replay_record(file: str, rate: float, start: int | None, loop: bool, paused: bool,
                  wait_s: float, onto: str | None, bus_config: BusConfig) -> None:
    """Play RECORD (see the module doc); one clear line for every refusal."""
    from tools.records.run_record import RecordError, RunRecord, locate

    stop = stop_on_signals()
    keys = terminal_keys(stop)
    if paused and keys is None:
        raise click.UsageError("--paused needs a terminal on stdin (its keys resume the "
                               "play: space); without one, leave --paused out")
    try:
        rec = RunRecord(locate(file), raw=True)   # the world states as they were sent
        items = [(key, from_record(key, r), r["env"]["cycle"]) for key, r in rec.records()]
        static = next(((k, p) for k, p, _ in items if k == world_static(rec.run)), None)
        items = [item for item in items if item[0] != world_static(rec.run)]   # not a cycle
        groups = cycles_of(items, _log_times(rec))
    except (RecordError, BusError) as exc:
        raise click.ClickException(str(exc)) from exc
    if start is not None:
        try:
            groups = from_cycle(groups, start)
        except ValueError as exc:
            raise click.BadParameter(f"{rec.path}: {exc}", param_hint="--start") from None
    for _, r in rec.kinds("percepts"):   # the programs swapped in (teleo program load)
        if isinstance(r.get("program"), dict) and r["program"]:
            _say(f"cycle {r['env']['cycle']}: {r.get('agent')} runs "
                 f"{r['program'].get('name')} from here on (swapped in while it ran)")
    target, router = _bus(bus_config, onto)
    try:
        _play(rec.run, groups, target, router, Player(
            groups, lambda k, p: None, rate, stop, keys or NoKeys(stop), _say, paused, loop),
              keys, wait_s, static)
    finally:
        if router is not None:
            router.stop()


def _bus(bus_config: BusConfig, onto: str | None) -> tuple[Target, RouterProcess | None]:
    """The bus to play on, and the router started for it (None when it is a launch's or
    one named)."""
    if onto is not None or connect_given() or launches_running():
        return find_target(bus_config, run=onto), None
    try:
        router = spawn_router(LOOPBACK_ANY, env={ENV_PARENT: str(os.getpid())},
                              log_file=os.devnull)
    except BusError as exc:
        raise click.ClickException(f"no launch is running, and a router of its own could "
                                   f"not start: {exc}") from exc
    return Target(client_of((router.endpoint,)), None,
                  f"router {router.endpoint} of its own"), router


def _play(run: str, groups: list, target: Target, router: RouterProcess | None,
          player: Player, keys, wait_s: float, static: tuple[str, bytes] | None = None
          ) -> None:
    """Say where, wait for subscribers, play, say how many were sent; answer queries for the
    world's static part as the world did (`static`: its key and payload)."""
    if target.run == run:
        raise click.ClickException(
            f"run {run} is the running launch itself: its own record would be played into "
            f"it, every cycle twice; stop it first, or replay onto another run's router "
            f"(--onto RUN, --connect)")
    hub = target.cfg.connect[0] if target.cfg.connect else ""
    messages = sum(len(g.items) for g in groups)
    held = f", cycles {groups[0].cycle}..{groups[-1].cycle}" if groups else ""
    why = " (no launch is running)" if router is not None else ""
    runfile.say_reached(f"{target.who}{why}: replaying run {run} ({messages} messages{held}); "
                        f"follow it with `teleo echo --connect {hub}` or `teleo view "
                        f"--connect {hub} --run {run}`")
    if keys is not None and not player.paused:
        _say("keys: space pauses and plays, s or the right arrow plays one cycle when paused")
    key_names = {key for g in groups for key, _ in g.items} | ({static[0]} if static else set())
    try:
        with open_node(target.cfg, run, f"replay-{os.getpid()}") as node:
            node.declare(key_names)
            if static is not None:   # and asked of it as of the world (no cycle to play)
                told = decode(*static)
                node.serve(static[0], lambda _asked: told)
            if node.wait_matching(key_names, wait_s):
                _say(f"nobody subscribed to some keys of run {run} within {wait_s:g} s; "
                     "replaying anyway")
            player.send = node.put_raw
            if static is not None:   # as the world: put once, before the first cycle
                node.put_raw(*static)
            with keys if keys is not None else contextlib.nullcontext():
                sent = player.play()
            if router is not None and not player.stop.is_set():
                player.stop.wait(SETTLE_S)  # the router still holds what is in flight
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc
    end = " (interrupted)" if player.stop.is_set() else ""
    _say(f"replayed {sent} messages ({player.played_cycles} cycles) of run {run} to "
         f"{target.who}{end}")


def _say(text: str) -> None:
    click.echo(text, err=True)


def _log_times(rec) -> dict[int, int]:
    """cycle -> world time [ns] of a record (from its world states)."""
    return {r["env"]["cycle"]: round(float(r["snapshot"].get("time", 0.0)) * 1e9)
            for _, r in rec.kinds("state")}
