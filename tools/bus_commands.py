"""`teleo router | echo | record | replay`: the bus subcommands (thin wrappers over bus/).

echo, record and replay find the running launch as every tool does (tools/runfile.py: the
only running one, or `--run RUN`) and say on stderr which run and router they reach; an
explicit `--connect` (or TELEO_ZENOH_CONNECT) bypasses the lookup, for a bus that no launch
of this host runs.
"""

from __future__ import annotations

import dataclasses
import json
import os
import time

import click

from bus import keys
from bus.codec import decode
from bus.config import BusConfig, bus_options
from bus.errors import BusError, CodecError
from bus.node import open_node
from bus.record import Recorder, read_recording
from bus.router import router_config, run_until_signalled
from bus.stage import stop_on_signals
from tools import runfile


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


def _reach(bus_config: BusConfig, run_id: str | None) -> tuple[BusConfig, str | None]:
    """The bus to use and the run it carries: the given flags when --connect (or its
    environment variable) was given, else the located run's router."""
    ctx = click.get_current_context()
    explicit = ctx.get_parameter_source("connect") is click.core.ParameterSource.COMMANDLINE
    if explicit or os.environ.get("TELEO_ZENOH_CONNECT"):
        click.echo(f"bus: {', '.join(bus_config.connect) or 'no hub'} (from the flags)",
                   err=True)
        return bus_config, run_id
    info = runfile.locate(run_id)
    return runfile.bus_config(info), info.run


def _full_key(keyexpr: str, run: str | None) -> str:
    """A key expression as given when it starts with teleo/, else under teleo/<run>/."""
    if keyexpr.startswith(f"{keys.ROOT}/") or run is None:
        return keyexpr
    return f"{keys.run_root(run)}/{keyexpr.lstrip('/') or '**'}"


def _run_of(keyexpr: str) -> str:
    parts = keyexpr.split("/")
    if len(parts) > 1 and parts[0] == keys.ROOT:
        try:
            return keys.check_chunk(parts[1])
        except BusError:
            pass
    return "any"


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
@click.option("--count", type=int, default=None, help="Exit after N printed messages.")
@click.option("--seconds", type=float, default=None, help="Exit after S seconds.")
@runfile.run_option
@bus_options
def echo(keyexpr: str, text: str | None, count: int | None, seconds: float | None,
         run_id: str | None, bus_config: BusConfig) -> None:
    """Print messages on KEYEXPR decoded, as JSON lines: a key of the run such as
    'world/state' or 'agent/ME/**' (default: everything), or a full 'teleo/RUN/...'."""
    bus_config, run = _reach(bus_config, run_id)
    keyexpr = _full_key(keyexpr, run)
    click.echo(f"listening on {keyexpr}", err=True)
    stop = stop_on_signals()
    end = None if seconds is None else time.monotonic() + seconds
    printed = 0
    with open_node(bus_config, _run_of(keyexpr), f"echo-{os.getpid()}") as node:
        inbox = node.subscribe(keyexpr, raw=True)
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
@click.argument("file", type=click.Path(dir_okay=False, writable=True))
@runfile.run_option
@click.option("--seconds", type=float, default=None, help="Stop after S seconds.")
@click.option("--count", type=int, default=None, help="Stop after N samples.")
@bus_options
def record(file: str, run_id: str | None, seconds: float | None, count: int | None,
           bus_config: BusConfig) -> None:
    """Record all traffic of a run (key, time, raw payload) to FILE until Ctrl-C."""
    bus_config, run_id = _reach(bus_config, run_id)
    if run_id is None:
        raise click.ClickException("record: name the run with --run RUN (with --connect)")
    stop = stop_on_signals()
    end = None if seconds is None else time.monotonic() + seconds
    with open_node(bus_config, run_id, "record") as node, open(file, "wb") as out:
        rec = Recorder(out, run_id)
        inbox = node.subscribe(keys.run_all(run_id), raw=True)
        node.announce()  # after subscribing: anyone waiting for "record" may now publish
        while not stop.is_set() and (end is None or time.monotonic() < end):
            if count is not None and rec.count >= count:
                break
            item = inbox.receive(0.1)
            if item is not None:
                rec.write(item.key, item.t_ns, item.payload)
    click.echo(f"recorded {rec.count} samples of run {run_id} to {file}", err=True)


@click.command()
@click.argument("file", type=click.Path(exists=True, dir_okay=False))
@click.option("--speed", type=float, default=1.0, show_default=True,
              help="Time scale (2: twice as fast; 0: as fast as possible).")
@click.option("--wait", "wait_s", type=float, default=2.0, show_default=True,
              help="Wait up to S seconds for subscribers on the recorded keys first.")
@runfile.run_option
@bus_options
def replay(file: str, speed: float, wait_s: float, run_id: str | None,
           bus_config: BusConfig) -> None:
    """Re-publish a recording made by `teleo record`, keeping its timing."""
    try:
        header, samples = read_recording(file)
        items = list(samples)
    except CodecError as exc:
        raise click.ClickException(str(exc)) from exc
    bus_config, _ = _reach(bus_config, run_id)
    stop = stop_on_signals()
    with open_node(bus_config, header["run"], f"replay-{os.getpid()}") as node:
        node.declare({s.key for s in items})
        unheard = node.wait_matching({s.key for s in items}, wait_s)
        if unheard and len(unheard) == len({s.key for s in items}):
            raise click.ClickException(f"nobody subscribes to any of the {len(unheard)} "
                                       f"recorded keys (waited {wait_s:g} s): nothing replayed")
        start, t0 = time.monotonic(), (items[0].t_ns if items else 0)
        for s in items:
            if speed > 0:
                due = start + (s.t_ns - t0) / 1e9 / speed
                if stop.wait(max(0.0, due - time.monotonic())):
                    break
            node.put_raw(s.key, s.payload)
    click.echo(f"replayed {len(items)} samples of run {header['run']}", err=True)


commands = [router, echo, record, replay]
