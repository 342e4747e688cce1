"""`teleo router | echo | record | replay`: the bus subcommands (thin wrappers over bus/)."""

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


def _json_line(key: str, t_ns: int, payload: bytes) -> str:
    try:
        msg = decode(key, payload)
    except CodecError as exc:
        return json.dumps({"key": key, "t_ns": t_ns, "error": exc.problem})
    return json.dumps({"key": key, "t_ns": t_ns, "kind": msg.KIND, "msg": dataclasses.asdict(msg)},
                      default=str)


@click.command()
@click.argument("keyexpr")
@click.option("--filter", "text", default=None, help="Only lines containing TEXT.")
@click.option("--count", type=int, default=None, help="Exit after N printed messages.")
@click.option("--seconds", type=float, default=None, help="Exit after S seconds.")
@bus_options
def echo(keyexpr: str, text: str | None, count: int | None, seconds: float | None,
         bus_config: BusConfig) -> None:
    """Print messages on KEYEXPR (e.g. 'teleo/demo/**') decoded, as JSON lines."""
    try:
        keys.check_keyexpr(keyexpr)
    except BusError as exc:
        raise click.BadParameter(str(exc), param_hint="KEYEXPR") from None
    stop = stop_on_signals()
    end = None if seconds is None else time.monotonic() + seconds
    try:
        with open_node(bus_config, _run_of(keyexpr), f"echo-{os.getpid()}") as node:
            _print_messages(node.subscribe(keyexpr, raw=True), text, count, end, stop)
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc


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
@click.argument("file", type=click.Path(dir_okay=False, writable=True))
@click.option("--run", "run_id", required=True, help="Run id: records teleo/<run>/**.")
@click.option("--seconds", type=float, default=None, help="Stop after S seconds.")
@click.option("--count", type=int, default=None, help="Stop after N samples.")
@bus_options
def record(file: str, run_id: str, seconds: float | None, count: int | None,
           bus_config: BusConfig) -> None:
    """Record all traffic of a run (key, time, raw payload) to FILE until Ctrl-C."""
    try:
        keys.check_chunk(run_id, "run")
    except BusError as exc:
        raise click.BadParameter(f"{exc} (a run id, e.g. driving-demo-3f2a1c, as `teleo "
                                 "launch` prints it)", param_hint="--run") from None
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
@bus_options
def replay(file: str, speed: float, wait_s: float, bus_config: BusConfig) -> None:
    """Re-publish a recording made by `teleo record`, keeping its timing."""
    try:
        header, samples = read_recording(file)
        items = list(samples)
    except CodecError as exc:
        raise click.ClickException(str(exc)) from exc
    stop = stop_on_signals()
    with open_node(bus_config, header["run"], f"replay-{os.getpid()}") as node:
        node.declare({s.key for s in items})
        node.wait_matching({s.key for s in items}, wait_s)
        start, t0 = time.monotonic(), (items[0].t_ns if items else 0)
        for s in items:
            if speed > 0:
                due = start + (s.t_ns - t0) / 1e9 / speed
                if stop.wait(max(0.0, due - time.monotonic())):
                    break
            node.put_raw(s.key, s.payload)
    click.echo(f"replayed {len(items)} samples of run {header['run']}", err=True)


commands = [router, echo, record, replay]
