"""`teleo router | echo | record | replay`: the bus subcommands (thin wrappers over bus/).

echo, record and replay reach the running launch as every tool does (tools/target.py over
tools/runfile.py: the only running launch, or `--run RUN`) and say on stderr which run and
router they reach; an explicit `--connect` (or TELEO_ZENOH_CONNECT) names a router instead.
"""

from __future__ import annotations

import dataclasses
import json
import os
import time
from pathlib import Path

import click

from bus import keys
from bus.codec import decode
from bus.config import BusConfig, bus_options
from bus.errors import BusError, CodecError
from bus.node import open_node
from bus.record import from_record
from bus.router import router_config, run_until_signalled
from bus.stage import stop_on_signals
from tools import runfile
from tools.paths import OutputPath

_SECONDS = click.FloatRange(min=0, min_open=True)
"""A watch of S > 0 seconds (--seconds of echo and record)."""


def _split(text: str) -> list[str]:
    return [p.strip() for p in text.split(",") if p.strip()]


@click.command()
@click.option("--listen", default="tcp/127.0.0.1:7447", show_default=True,
              help="Endpoints to listen on, comma-separated.")
@click.option("--connect", default="", help="Other routers to link to, comma-separated.")
def router(listen: str, connect: str) -> None:
    """Run a zenoh router (the hub of a run) until Ctrl-C; prints its endpoints."""
    try:
        run_until_signalled(router_config(_split(listen), _split(connect)))
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc


def _run_of(keyexpr: str) -> str:
    parts = keyexpr.split("/")
    if len(parts) > 1 and parts[0] == keys.ROOT:
        try:
            return keys.check_chunk(parts[1])
        except BusError:
            pass
    return "any"


def _full_key(keyexpr: str, run: str | None) -> str:
    """A key expression as given when it starts with teleo/, else under teleo/<run>/."""
    if keyexpr.startswith(f"{keys.ROOT}/") or run is None:
        return keyexpr
    return f"{keys.run_root(run)}/{keyexpr.lstrip('/') or '**'}"


def _json_line(key: str, t_ns: int, payload: bytes) -> str:
    try:
        msg = decode(key, payload)
    except CodecError as exc:
        return json.dumps({"key": key, "t_ns": t_ns, "error": exc.problem})
    return json.dumps({"key": key, "t_ns": t_ns, "kind": msg.KIND, "msg": dataclasses.asdict(msg)},
                      default=str)


@click.command()
@click.argument("keyexpr", default="**")
@click.option("--filter", "text", default=None, help="Only lines containing TEXT.")
@click.option("--count", type=click.IntRange(min=1), default=None,
              help="Exit after N printed messages.")
@click.option("--seconds", type=_SECONDS, default=None, help="Exit after S seconds.")
@runfile.run_option
@bus_options
def echo(keyexpr: str, text: str | None, count: int | None, seconds: float | None,
         run_id: str | None, bus_config: BusConfig) -> None:
    """Print messages on KEYEXPR decoded, as JSON lines: a key of the run such as
    'world/state' or 'agent/ME/**' (default: everything), or a full 'teleo/RUN/...'."""
    from tools.target import find_target

    problem = _keyexpr_problem(keyexpr)
    if problem is not None:
        raise click.BadParameter(problem, param_hint="KEYEXPR")
    target = find_target(bus_config, run=run_id)
    keyexpr = _full_key(keyexpr, target.run)
    click.echo(f"listening on {keyexpr} of {target.who}", err=True)
    stop = stop_on_signals()
    end = None if seconds is None else time.monotonic() + seconds
    try:
        with open_node(target.cfg, _run_of(keyexpr), f"echo-{os.getpid()}") as node:
            _print_messages(node.subscribe(keyexpr, raw=True), text, count, end, stop)
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc


def _keyexpr_problem(keyexpr: str) -> str | None:
    """What is wrong with a key expression (bus.keys.check_keyexpr's words), or None. The
    repair it suggests for empty chunks ('a//b' -> 'a/b') is kept only when that repair is
    itself a valid key expression; otherwise the rest of what is wrong is said instead."""
    try:
        keys.check_keyexpr(keyexpr)
        return None
    except BusError as exc:
        problem = str(exc)
    repaired = "/".join(c for c in keyexpr.split("/") if c)
    suggestion = f"; e.g. {repaired!r}"
    if not problem.endswith(suggestion):
        return problem
    if not repaired:
        return problem.removesuffix(suggestion)
    try:
        keys.check_keyexpr(repaired)
        return problem
    except BusError as rest:
        return f"{problem.removesuffix(suggestion)}; without the empty chunk: {rest}"


def _print_messages(inbox, text: str | None, count: int | None, end: float | None,
                    stop) -> None:
    """Print what arrives in `inbox` as JSON lines until `end` [monotonic s], `count`
    lines, or `stop`."""
    printed = 0
    while not stop.is_set() and (end is None or time.monotonic() < end):
        item = inbox.receive(0.1)
        if item is None:
            continue
        line = _json_line(item.key, item.t_ns, item.payload)
        if text is None or text in line:
            click.echo(line)
            printed += 1
            if count is not None and printed >= count:
                break


@click.command()
@click.argument("file", type=OutputPath(path_type=Path))
@click.option("--run", "run_id", default=None,
              help="Run id: records teleo/<run>/** (default: the running launch's run).")
@click.option("--seconds", type=_SECONDS, default=None, help="Stop after S seconds.")
@click.option("--count", type=click.IntRange(min=1), default=None,
              help="Stop after N messages.")
@bus_options
def record(file: Path, run_id: str | None, seconds: float | None, count: int | None,
           bus_config: BusConfig) -> None:
    """Record a run's messages to FILE (MCAP, as launches record themselves) until Ctrl-C.

    Without --connect it records the running launch; with --connect, the run given by --run
    on that router."""
    from tools.recorder import FOREGROUND_SETTLE_S, FOREGROUND_STOP_S, BusRecorder
    from tools.target import find_target

    if run_id is not None:
        try:
            keys.check_chunk(run_id, "run")
        except BusError as exc:
            raise click.BadParameter(f"{exc} (a run id, e.g. driving-demo-3f2a1c, as `teleo "
                                     "launch` prints it)", param_hint="--run") from None
    target = find_target(bus_config, run=run_id)
    run_id = run_id or target.run
    if run_id is None:
        raise click.UsageError("--run RUN is needed with --connect (which run to record)")
    try:
        keys.check_chunk(run_id, "run")
        recorder = BusRecorder(target.cfg, run_id, file, {"source": "record"}).start(
            announce=True)
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc
    click.echo(f"recording run {run_id} from {target.who} to {file}", err=True)
    stop = stop_on_signals()
    end = None if seconds is None else time.monotonic() + seconds
    while not stop.wait(0.05):
        if (end is not None and time.monotonic() >= end) or \
                (count is not None and recorder.received >= count):
            break
    # what was sent until now and no more (the run goes on publishing); bounded, so that a
    # clock or a replay that fools "sent before the stop" cannot hold the command
    writer = recorder.stop(settle_s=FOREGROUND_SETTLE_S, timeout=FOREGROUND_STOP_S)
    cycles = "no cycle" if recorder.first_cycle is None else \
        f"{recorder.cycles} cycles, {recorder.first_cycle}..{recorder.last_cycle}"
    click.echo(f"recorded {writer.messages} messages ({cycles}) of run {run_id} to {file}",
               err=True)


@click.command()
@click.argument("file", metavar="RECORD", type=click.Path())
@click.option("--speed", type=click.FloatRange(min=0), default=1.0, show_default=True,
              help="Time scale on world time (2: twice as fast; 0: as fast as possible).")
@click.option("--wait", "wait_s", type=click.FloatRange(min=0), default=2.0,
              show_default=True,
              help="Wait up to S seconds for subscribers on the recorded keys first.")
@click.option("--onto", "onto", default=None, metavar="RUN",
              help="The running launch to replay onto (default: the only one).")
@bus_options
def replay(file: str, speed: float, wait_s: float, onto: str | None,
           bus_config: BusConfig) -> None:
    """Play a run record (RECORD: an .mcap file, a run folder or run id) back on the bus of
    the running launch, or of the router named by --connect, with its world-time pacing."""
    from tools.records import RecordError, RunRecord, locate
    from tools.target import find_target

    try:
        rec = RunRecord(locate(file))
        items = [(key, from_record(key, r), r["env"]["cycle"]) for key, r in rec.records()]
        times = _log_times(rec)
    except (RecordError, BusError) as exc:
        raise click.ClickException(str(exc)) from exc
    target = find_target(bus_config, run=onto)
    if target.run == rec.run:
        raise click.ClickException(
            f"run {rec.run} is the running launch itself: its own record would be played into "
            f"it, every cycle twice; stop it first, or replay onto another run's router "
            f"(--onto RUN, --connect)")
    hub = target.cfg.connect[0] if target.cfg.connect else ""
    click.echo(f"replaying run {rec.run} ({len(items)} messages) to {target.who}; watch it "
               f"with `teleo view --run {rec.run} --connect {hub}`", err=True)
    stop = stop_on_signals()
    with open_node(target.cfg, rec.run, f"replay-{os.getpid()}") as node:
        node.declare({key for key, _, _ in items})
        if node.wait_matching({key for key, _, _ in items}, wait_s):
            click.echo(f"nobody subscribed to some keys of run {rec.run} within {wait_s:g} s; "
                       "replaying anyway", err=True)
        start, sent = time.monotonic(), 0
        t0 = times.get(items[0][2], 0) if items else 0
        for key, payload, cycle in items:
            if speed > 0:
                due = start + (times.get(cycle, t0) - t0) / 1e9 / speed
                if stop.wait(max(0.0, due - time.monotonic())):
                    break
            node.put_raw(key, payload)
            sent += 1
    click.echo(f"replayed {sent} messages of run {rec.run} to {target.who}", err=True)


def _log_times(rec) -> dict[int, int]:
    """cycle -> world time [ns] of a record (from its world states)."""
    return {r["env"]["cycle"]: round(float(r["snapshot"].get("time", 0.0)) * 1e9)
            for _, r in rec.kinds("state")}


commands = [router, echo, record, replay]
