"""`teleo hz KEYEXPR` and `teleo echo --list`: how often messages come, as `ros2 topic hz`,
`ros2 topic bw` and `ros2 topic list -v` say it (tools/runs/rates.py keeps the figures).

Both reach the running launch as every bus tool does (tools/runs/target.py; `--run RUN`, or a
router named with `--connect`) and watch the keys matching KEYEXPR: a key of the run such as
`world/state` or `agent/*/actions`, or a full `teleo/RUN/...`.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable

import click

from bus.codec import decode
from bus.config import BusConfig, bus_options
from bus.errors import BusError, CodecError
from bus.node import open_node
from bus.stage import stop_on_signals
from tools.runs import runfile
from tools.runs.rates import DEFAULT_WINDOW, Meter, hz_line, list_table
from tools.runs.target import reach_keys, run_of

LIST_S = 2.0  # [s] `teleo echo --list` watches this long unless --seconds says


def watch(cfg: BusConfig, keyexpr: str, run: str, seconds: float | None, window: int,
          decoded: bool, every: Callable[[dict[str, Meter]], None] | None = None,
          every_s: float = 1.0) -> dict[str, Meter]:
    """Meters of every key matching `keyexpr`, watched for `seconds` [s] (None: until
    SIGINT or SIGTERM); `decoded`: note each message's kind and publisher too (a payload that
    does not decode counts as kind "undecodable"). `every(meters)` is called each `every_s`."""
    from bus.node import Inbox

    meters: dict[str, Meter] = {}
    stop = stop_on_signals()
    now = time.monotonic()
    end = None if seconds is None else now + seconds
    due = now + every_s
    with open_node(cfg, run, f"hz-{os.getpid()}") as node:
        inbox: Inbox = node.subscribe(keyexpr, raw=True)
        while not stop.is_set() and (end is None or time.monotonic() < end):
            item = inbox.receive(0.05)
            if item is not None:
                kind, sender = _kind_and_sender(item.key, item.payload) if decoded else ("", "")
                meters.setdefault(item.key, Meter(window)).feed(
                    item.t_ns, len(item.payload), kind, sender)
            if every is not None and time.monotonic() >= due:
                due += every_s
                every(meters)
    return meters


def _kind_and_sender(key: str, payload: bytes) -> tuple[str, str]:
    try:
        msg = decode(key, payload)
    except CodecError:
        return "undecodable", ""
    return msg.KIND, msg.env.sender


def _short(key: str, run: str | None) -> str:
    prefix = f"teleo/{run}/"
    return key[len(prefix):] if run and key.startswith(prefix) else key


def list_keys(keyexpr: str, seconds: float | None, as_json: bool, run_id: str | None,
              bus_config: BusConfig) -> None:
    """`teleo echo --list`: every key seen on KEYEXPR within `seconds` (LIST_S by default),
    with its kind, rate, mean size and publishers; exit 1 when none was seen."""
    target, full = reach_keys(keyexpr, run_id, bus_config, "listing the keys of")
    watched = LIST_S if seconds is None else seconds
    try:
        meters = watch(target.cfg, full, run_of(full), watched, DEFAULT_WINDOW, decoded=True)
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc
    if not meters:
        raise click.ClickException(f"no message on {full} within {watched:g} s: is the run "
                                   "going (teleo inspect), and the key expression right?")
    shown = {_short(k, target.run): m for k, m in meters.items()}
    if as_json:
        click.echo(json.dumps([{"key": k, "kinds": sorted(m.kinds),
                                "publishers": sorted(m.publishers), "count": m.count,
                                **m.figures().to_dict()} for k, m in sorted(shown.items())],
                              indent=1))
        return
    for line in list_table(shown):
        click.echo(line)


@click.command()
@click.argument("keyexpr")
@click.option("--window", type=click.IntRange(min=2), default=DEFAULT_WINDOW,
              show_default=True, help="Figures over the last N messages of each key.")
@click.option("--bw", is_flag=True, help="Also bytes per second and the mean message size.")
@click.option("--seconds", type=click.FloatRange(min=0, min_open=True), default=None,
              help="Stop after S seconds (default: Ctrl-C).")
@click.option("--json", "as_json", is_flag=True,
              help="JSON lines: {key, messages, rate, period_min, period_max, period_std, "
                   "bytes_per_s, mean_size} per key, each second.")
@runfile.run_option
@runfile.quiet_option
@bus_options
def hz(keyexpr: str, window: int, bw: bool, seconds: float | None, as_json: bool,
       run_id: str | None, bus_config: BusConfig) -> None:
    """Print the rate of messages on KEYEXPR each second, as ros2 topic hz and bw do.

    Messages per second, the period's min, max and standard deviation over the window, and
    with --bw bytes per second and the mean message size. KEYEXPR is a key of the run such
    as 'world/state' or 'agent/*/actions' (one line per key it matches), or a full
    'teleo/RUN/...'. Exit 1 when no message came at all."""
    target, full = reach_keys(keyexpr, run_id, bus_config, "rates of")
    reported = [-1]  # messages seen at the last report: the end repeats none

    def report(meters: dict[str, Meter], final: bool = False) -> None:
        seen = sum(m.count for m in meters.values())
        if seen == reported[0]:
            if not final and not as_json:
                click.echo(f"no new messages on {_short(full, target.run)}")
            return
        reported[0] = seen
        for key in sorted(meters):
            name, figures = _short(key, target.run), meters[key].figures()
            click.echo(json.dumps({"key": name, **figures.to_dict()}) if as_json
                       else hz_line(name, figures, bw))

    try:
        meters = watch(target.cfg, full, run_of(full), seconds, window, decoded=False, every=report)
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc
    if not meters:
        raise click.ClickException(f"no message on {full}"
                                   + (f" within {seconds:g} s" if seconds else "")
                                   + ": is the run going (teleo inspect), and the key "
                                     "expression right?")
    report(meters, final=True)


commands = [hz]
