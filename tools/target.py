"""Which bus an echo, record, replay or view command talks to, said out loud: the running
launch's router (found in the run registry as every tool finds it, tools/runfile.py: the
only running launch, or the one named with --run; with the operator's credentials when the
run is secured), or a router named with --connect (or $TELEO_ZENOH_CONNECT), checked by
opening a client session to it, so a command never publishes into nothing or waits silently
on a port where nobody listens.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import click
from click.core import ParameterSource

from bus.config import ENV_CONNECT, BusConfig, Mode
from bus.errors import BusError
from tools import runfile


class TargetError(click.ClickException):
    """No launch and no router to talk to; the message says where we looked."""


@dataclass(frozen=True)
class Target:
    """A bus to talk to: its client config, the run when known, and who it is (for messages)."""

    cfg: BusConfig
    run: str | None
    who: str


def connect_given() -> bool:
    """Whether the user named a router (--connect on the command line, or the environment)."""
    ctx = click.get_current_context(silent=True)
    given = ctx is not None and ctx.get_parameter_source("connect") is ParameterSource.COMMANDLINE
    return given or bool(os.environ.get(ENV_CONNECT))


def find_target(bus_config: BusConfig, explicit: bool | None = None,
                run: str | None = None) -> Target:
    """The running launch (`run`, or the only one), or the router of `bus_config` when one
    was named; raises TargetError saying what was tried."""
    if explicit if explicit is not None else connect_given():
        cfg = BusConfig(mode=Mode.CLIENT, connect=bus_config.connect, listen=(),
                        credentials=bus_config.credentials)
        probe(cfg)
        return Target(cfg, run, f"router {', '.join(cfg.connect)}")
    try:
        info = runfile.find(run)
    except runfile.NoRunningLaunch as exc:
        raise TargetError(f"{exc}; start `teleo launch`, or name a router with "
                          f"--connect tcp/HOST:PORT (e.g. a `teleo router`)") from exc
    secured = ", secured" if info.secured else ""
    return Target(runfile.bus_config(info), info.run,
                  f"launch {info.run} (router {info.endpoint}{secured}, from "
                  f"{runfile.path_of(info)})")


def probe(cfg: BusConfig) -> None:
    """Raise TargetError unless a router answers at cfg.connect (a client session opens at
    once when one does, and fails at once when none does)."""
    from bus.node import open_node

    try:
        with open_node(cfg, "probe", f"probe-{os.getpid()}"):
            pass
    except BusError as exc:
        raise TargetError(f"no router answers at {', '.join(cfg.connect)}: start "
                          f"`teleo launch` or `teleo router` there first ({exc})") from exc
