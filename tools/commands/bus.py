"""`teleo router | echo | record | replay`: the bus subcommands (thin wrappers over bus/).

echo, record and replay reach the running launch as every tool does (tools/runs/target.py over
tools/runs/runfile.py: the only running launch, or `--run RUN`) and say so in one short line on
stderr, `run R (router EP): ...` (none with --quiet); an explicit `--connect` (or
TELEO_ZENOH_CONNECT) names a router instead. `teleo replay` with no launch running plays on a
router of its own (tools/records/replayer.py); `echo --list` and `teleo hz` are in
tools/commands/rate.py.
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
from bus.router import router_config, run_until_signalled
from bus.stage import stop_on_signals
from tools.commands.record_info import RecordWithInfo
from tools.paths import OutputPath, suffix_check
from tools.runs import runfile

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
@click.option("--seconds", type=_SECONDS, default=None,
              help="Exit after S seconds (with --list: watch S seconds; default 2).")
@click.option("--list", "as_list", is_flag=True,
              help="List the keys instead, with kind, rate, mean size and publishers "
                   "(as ros2 topic list -v).")
@click.option("--json", "as_json", is_flag=True, help="With --list: a JSON list.")
@runfile.run_option
@runfile.quiet_option
@bus_options
def echo(keyexpr: str, text: str | None, count: int | None, seconds: float | None,
         as_list: bool, as_json: bool, run_id: str | None, bus_config: BusConfig) -> None:
    """Print messages on KEYEXPR decoded, as JSON lines: a key of the run such as
    'world/state' or 'agent/ME/**' (default: everything), or a full 'teleo/RUN/...'.

    --list prints every key seen on KEYEXPR instead, with its message kind, rate, mean
    size and publishers (teleo hz KEYEXPR follows one key's rate)."""
    from tools.commands.rate import list_keys
    from tools.runs.target import reach_keys, run_of

    if as_list:
        for given, name in ((text, "--filter"), (count, "--count")):
            if given is not None:
                raise click.UsageError(f"{name} goes with printing messages, not with --list")
        return list_keys(keyexpr, seconds, as_json, run_id, bus_config)
    if as_json:
        raise click.UsageError("--json goes with --list (messages are printed as JSON lines "
                               "already)")
    target, keyexpr = reach_keys(keyexpr, run_id, bus_config, "listening on")
    stop = stop_on_signals()
    end = None if seconds is None else time.monotonic() + seconds
    try:
        with open_node(target.cfg, run_of(keyexpr), f"echo-{os.getpid()}") as node:
            seen, printed = _print_messages(node.subscribe(keyexpr, raw=True), text, count,
                                            end, stop)
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc
    if not printed:   # as `teleo hz` says it (not nothing printed and exit 0)
        within = f" within {seconds:g} s" if seconds else ""
        raise click.ClickException(
            f"{seen} message(s) on {keyexpr}{within}, none containing {text!r}" if seen else
            f"no message on {keyexpr}{within}: is the run going (teleo inspect), and the key "
            "expression right? (teleo echo --list shows the keys)")


def _print_messages(inbox, text: str | None, count: int | None, end: float | None,
                    stop) -> tuple[int, int]:
    """Print what arrives in `inbox` as JSON lines until `end` [monotonic s], `count`
    lines, or `stop`; returns (messages received, lines printed)."""
    seen = printed = 0
    while not stop.is_set() and (end is None or time.monotonic() < end):
        item = inbox.receive(0.1)
        if item is None:
            continue
        seen += 1
        line = _json_line(item.key, item.t_ns, item.payload)
        if text is None or text in line:
            click.echo(line)
            printed += 1
            if count is not None and printed >= count:
                break
    return seen, printed


@click.command(cls=RecordWithInfo)  # `teleo record info RECORD`: tools/commands/record_info.py
@click.argument("file", type=OutputPath(suffix_check((".mcap",), "a run record"),
                                        path_type=Path, create_folders=False))
@click.option("--run", "run_id", default=None,
              help="Run id: records teleo/<run>/** (default: the running launch's run).")
@click.option("--seconds", type=_SECONDS, default=None, help="Stop after S seconds.")
@click.option("--count", type=click.IntRange(min=1), default=None,
              help="Stop after N messages.")
@click.option("--force", is_flag=True, help="Replace FILE if it exists.")
@runfile.quiet_option
@bus_options
def record(file: Path, run_id: str | None, seconds: float | None, count: int | None,
           force: bool, bus_config: BusConfig) -> None:
    """Record a run's messages to FILE (MCAP, as launches record themselves) until Ctrl-C.

    FILE ends in .mcap, in a folder that exists, and is not replaced without --force.
    Without --connect it records the running launch; with --connect, the run given by --run
    on that router. `teleo record info RECORD` summarises a record instead."""
    from tools.records.recorder import FOREGROUND_SETTLE_S, FOREGROUND_STOP_S, BusRecorder
    from tools.runs.target import find_target

    if file.exists() and not force:   # never replace a record without a word
        raise click.ClickException(f"record: writing {file}: it exists already; give "
                                   f"another file, or --force to replace it")

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
    runfile.say_reached(f"{target.who}: recording run {run_id} to {file}")
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
@click.option("--rate", "--speed", "rate", type=click.FloatRange(min=0), default=1.0,
              show_default=True,
              help="Time scale on world time (2: twice as fast; 0: as fast as possible).")
@click.option("--start", "start", type=click.IntRange(min=0), default=None, metavar="CYCLE",
              help="Start at this cycle of the record.")
@click.option("--loop", is_flag=True, help="Play the record again and again, until Ctrl-C.")
@click.option("--paused", is_flag=True,
              help="Start paused (on a terminal: space plays and pauses, s or the right "
                   "arrow plays one cycle).")
@click.option("--wait", "wait_s", type=click.FloatRange(min=0), default=2.0,
              show_default=True,
              help="Wait up to S seconds for subscribers on the recorded keys first.")
@click.option("--onto", "onto", default=None, metavar="RUN",
              help="The running launch to replay onto (default: the only one; with none "
                   "running, a router of its own).")
@runfile.quiet_option
@bus_options
def replay(file: str, rate: float, start: int | None, loop: bool, paused: bool, wait_s: float,
           onto: str | None, bus_config: BusConfig) -> None:
    """Play a run record (RECORD: an .mcap file, a run folder or run id) back on the bus of
    the running launch, of the router named by --connect, or, with no launch running, of a
    router of its own on loopback, with its world-time pacing (as ros2 bag play).

    On a terminal, space pauses and resumes and s (or the right arrow) plays one cycle."""
    from tools.records.replayer import replay_record

    replay_record(file, rate, start, loop, paused, wait_s, onto, bus_config)


commands = [router, echo, record, replay]
