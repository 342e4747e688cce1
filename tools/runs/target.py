"""Which bus an echo, record, replay, hz or view command talks to, said out loud: the running
launch's router (found in the run registry as every tool finds it, tools/runs/runfile.py: the
only running launch, or the one named with --run; with the operator's credentials when the
run is secured), or a router named with --connect (or $TELEO_ZENOH_CONNECT), checked by
opening a client session to it, so a command never publishes into nothing or waits silently
on a port where nobody listens.

Every tool that reaches a run says so in one short line on stderr, `run R (router EP)`
(runfile.say_reached), and nothing with `--quiet` (runfile.quiet_option).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import click
from click.core import ParameterSource

from bus import keys
from bus.config import ENV_CONNECT, BusConfig, Mode
from bus.errors import BusError
from tools.runs import runfile


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
        cfg = client_of(bus_config.connect, bus_config.credentials)
        probe(cfg)
        return Target(cfg, run, f"router {', '.join(cfg.connect)}")
    try:
        info = runfile.find(run)
    except runfile.NoRunningLaunch as exc:
        raise TargetError(f"{exc}; start `teleo launch`, or name a router with "
                          f"--connect tcp/HOST:PORT (e.g. a `teleo router`)") from exc
    return Target(runfile.bus_config(info), info.run, runfile.who_of(info))


def client_of(endpoints: tuple[str, ...], credentials: str = "") -> BusConfig:
    """A client session's config for the router(s) at `endpoints`."""
    return BusConfig(mode=Mode.CLIENT, connect=endpoints, listen=(), credentials=credentials)


def launches_running() -> bool:
    """Whether any launch of this host is running (registered, its launcher alive)."""
    return any(up and not info.joined for info, up in runfile.all_runs())


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


def run_of(keyexpr: str) -> str:
    """The run a full key expression names (`teleo/<run>/...`), else "any" (a node's name)."""
    parts = keyexpr.split("/")
    if len(parts) > 1 and parts[0] == keys.ROOT:
        try:
            return keys.check_chunk(parts[1])
        except BusError:
            pass
    return "any"


def full_key(keyexpr: str, run: str | None) -> str:
    """A key expression as given when it starts with teleo/, else under teleo/<run>/."""
    if keyexpr.startswith(f"{keys.ROOT}/") or run is None:
        return keyexpr
    return f"{keys.run_root(run)}/{keyexpr.lstrip('/') or '**'}"


def keyexpr_problem(keyexpr: str) -> str | None:
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


def reach_keys(keyexpr: str, run: str | None, bus_config: BusConfig,
               what: str) -> tuple[Target, str]:
    """The bus and the full key expression of a KEYEXPR argument (echo, hz, echo --list),
    the reach line said on stderr: `run R (router EP): WHAT teleo/R/...`. A bad KEYEXPR is
    a BadParameter naming it."""
    problem = keyexpr_problem(keyexpr)
    if problem is not None:
        raise click.BadParameter(problem, param_hint="KEYEXPR")
    target = find_target(bus_config, run=run)
    full = full_key(keyexpr, target.run)
    runfile.say_reached(f"{target.who}: {what} {full}")
    return target, full
