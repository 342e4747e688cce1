"""Where running launches are found: one small JSON file per run, so that every tool (`teleo
goal`, `event`, `inspect`, `echo`, `record`, `replay`, `ps`, `stop`) finds a run the same way,
from any directory, and a second launch never takes over the first one's file.

The files live in the run registry, `<state>/active/<run>.json`, where <state> is
$TELEO_RUN_DIR when set, else $XDG_RUNTIME_DIR/teleo, else ~/.local/state/teleo. Each holds
the run id, the router endpoint, the launcher's pid, the agents, the run folder, the pids of
the run's processes and, for a secured run, the operator's credentials file. The registry
folder is 0700 and the files 0600: only the user who launched a run can find or join it.
A run's folder (logs, trace, summary) is $TELEO_RUN_DIR/runs/<run>, else ./out/runs/<run>
from where the launch was started; the run file names it absolutely.
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

RUN_FILE = "teleo-run.json"  # kept for the docs of older versions: one file per run now


class NoRunningLaunch(Exception):
    """No `teleo launch` is running where the tools look for one; says where it looked."""


@dataclass(frozen=True)
class RunInfo:
    """What a tool needs to reach a running launch."""

    run: str
    endpoint: str
    pid: int
    agents: tuple[str, ...]
    run_dir: str
    scenario: str
    pids: dict[str, int] = field(default_factory=dict)  # process name -> current pid
    credentials: str = ""   # the operator's credentials file of a secured run
    joined: bool = False    # a launch that joined another host's run (no router, no world)
    started: float = 0.0    # [s since the epoch]
    restarts: dict[str, int] = field(default_factory=dict)  # process name -> times restarted
    cwd: str = ""           # the launch's folder: its scenario's relative paths start there

    @property
    def secured(self) -> bool:
        return bool(self.credentials)

    @property
    def key(self) -> str:
        """The registry file's name (a joined launch is registered beside the main one)."""
        return f"{self.run}.join-{self.pid}" if self.joined else self.run


def state_dir() -> Path:
    """The folder of the run registry (see the module doc), absolute."""
    if os.environ.get("TELEO_RUN_DIR"):
        return Path(os.environ["TELEO_RUN_DIR"]).resolve()
    if os.environ.get("XDG_RUNTIME_DIR"):
        return Path(os.environ["XDG_RUNTIME_DIR"]) / "teleo"
    return Path.home() / ".local" / "state" / "teleo"


def registry() -> Path:
    return state_dir() / "active"


def base_dir() -> Path:
    """The folder the run folders go in: $TELEO_RUN_DIR, else ./out (absolute)."""
    return Path(os.environ.get("TELEO_RUN_DIR") or "out").resolve()


def path_of(info: RunInfo) -> Path:
    return registry() / f"{info.key}.json"


def write(info: RunInfo) -> Path:
    """Register (or update) a run; the file is readable by its owner only. Its folder and
    scenario are kept absolute (a tool started in another folder must still find the
    program that the scenario names relative to the launch's folder)."""
    cwd = info.cwd or os.getcwd()
    scenario = str(Path(cwd, info.scenario)) if info.scenario else ""
    info = replace(info, cwd=cwd, scenario=scenario)
    folder = registry()
    folder.mkdir(parents=True, exist_ok=True, mode=0o700)
    path = path_of(info)
    tmp = path.with_suffix(".tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w") as out:
        out.write(json.dumps(asdict(info), indent=1))
    os.replace(tmp, path)
    return path


def remove(info: RunInfo) -> None:
    """Unregister `info` (only its own file: other runs are never touched)."""
    try:
        path_of(info).unlink()
    except FileNotFoundError:
        pass


def _load(path: Path) -> RunInfo | None:
    try:
        doc: dict[str, Any] = json.loads(path.read_text())
        return RunInfo(doc["run"], doc["endpoint"], int(doc["pid"]), tuple(doc["agents"]),
                       doc["run_dir"], doc.get("scenario", ""), dict(doc.get("pids", {})),
                       doc.get("credentials", ""), bool(doc.get("joined", False)),
                       float(doc.get("started", 0.0)), dict(doc.get("restarts", {})),
                       str(doc.get("cwd", "")))
    except (OSError, ValueError, KeyError, TypeError):
        return None


def all_runs() -> list[tuple[RunInfo, bool]]:
    """Every registered run with whether its launcher is still alive, oldest first."""
    found = [(info, alive(info.pid)) for p in sorted(registry().glob("*.json"))
             if (info := _load(p)) is not None]
    return sorted(found, key=lambda pair: pair[0].started)


def cmdline(pid: int) -> str:
    """The command line of process `pid` ("" when it cannot be read: gone, or not Linux)."""
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(
            errors="replace")
    except OSError:
        return ""


def belongs(pid: int, run: str) -> bool:
    """Whether `pid` is a live process of `run` (never a recycled pid of something else:
    every process of a run names it on its command line)."""
    return alive(pid) and run in cmdline(pid)


def leftovers(info: RunInfo) -> list[int]:
    """The processes of a registered run that are still there."""
    return [pid for pid in info.pids.values() if belongs(pid, info.run)]


def prune() -> tuple[list[RunInfo], list[RunInfo]]:
    """Remove the entries whose launcher is gone and of whose processes none is left (a
    launcher killed by SIGKILL leaves its entry behind); returns (removed, kept): the stale
    entries kept are those with processes still there, for `teleo stop RUN` to stop."""
    removed, kept = [], []
    for info, up in all_runs():
        if up:
            continue
        if leftovers(info):
            kept.append(info)
        else:
            remove(info)
            removed.append(info)
    return removed, kept


def find(run: str | None = None) -> RunInfo:
    """The running launch named `run`, or the only one; raises NoRunningLaunch saying where
    it looked and what it found (none, several, or a launcher that has exited)."""
    where = registry()
    runs = [(i, up) for i, up in all_runs() if not i.joined]
    if run is not None:
        match = [(i, up) for i, up in runs if i.run == run]
        if not match:
            names = ", ".join(i.run for i, _ in runs) or "none"
            raise NoRunningLaunch(f"no run {run!r} in {where} (runs there: {names})")
        info, up = match[0]
        if not up:
            raise NoRunningLaunch(f"run {run} in {where} names launcher pid {info.pid}, which "
                                  f"has exited (see `teleo ps`, `teleo stop {run}`)")
        return info
    live = [i for i, up in runs if up]
    if len(live) == 1:
        return live[0]
    if not live:
        stale = f" ({len(runs)} stale: see `teleo ps`)" if runs else ""
        raise NoRunningLaunch(f"no running teleo launch found in {where}{stale}")
    raise NoRunningLaunch(f"{len(live)} runs are running ({', '.join(i.run for i in live)}): "
                          f"choose one with --run")


def with_pids(info: RunInfo, pids: dict[str, int]) -> RunInfo:
    return replace(info, pids=dict(pids))


def alive(pid: int) -> bool:
    """Whether a process with this pid exists and has not exited (a zombie has)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return True  # no /proc here: existing is all we can tell
    return stat.rsplit(")", 1)[-1].split()[0] not in ("Z", "X")


def locate(run: str | None = None) -> RunInfo:
    """`find` for a command: a ClickException instead of NoRunningLaunch, and one short line
    on stderr saying which run it reaches, `run R (router EP)` (none with --quiet)."""
    import click

    try:
        info = find(run)
    except NoRunningLaunch as exc:
        raise click.ClickException(str(exc)) from exc
    say_reached(who_of(info))
    return info


def bus_config(info: RunInfo):
    """The bus configuration a tool uses to reach the run: a client of its router, with the
    operator's credentials when the run is secured."""
    from bus.config import BusConfig

    return BusConfig(mode="client", connect=(info.endpoint,), listen=(),
                     credentials=info.credentials)


def run_option(f):
    """Click option `--run RUN` (the run to reach; default: the only running one)."""
    import click

    return click.option("--run", "run_id", default=None, metavar="RUN",
                        help="The run to reach (default: the only running one; see "
                             "`teleo ps`).")(f)


QUIET = "teleo.quiet"
"""The click context's meta key set by --quiet."""


def quiet_option(f):
    """Click option `--quiet`/`-q`: no line on stderr saying which run the command reached."""
    import click

    def remember(ctx, _param, value: bool) -> None:
        ctx.meta[QUIET] = ctx.meta.get(QUIET, False) or value

    return click.option("--quiet", "-q", is_flag=True, expose_value=False, is_eager=True,
                        callback=remember,
                        help="Say nothing on stderr about which run (and router) the command "
                             "reached.")(f)


def say_reached(text: str) -> None:
    """Print `text` (the run or router reached, and what the command does there) on stderr,
    unless the command was given --quiet: every tool that reaches a run says so this way."""
    import click

    ctx = click.get_current_context(silent=True)
    if ctx is None or not ctx.meta.get(QUIET, False):
        click.echo(text, err=True)


def echo_pruned(removed: list[RunInfo], kept: list[RunInfo], err: bool = False) -> None:
    """Say which stale entries `prune` removed, and which it kept and why (`teleo ps
    --prune`, and every launch before it registers its run)."""
    import click

    for info in removed:
        click.echo(f"removed the stale entry of run {info.key} (its launcher {info.pid} is "
                   f"gone, and nothing of the run is left)", err=err)
    for info in kept:
        left = leftovers(info)
        click.echo(f"kept the stale entry of run {info.key}: its launcher {info.pid} is gone "
                   f"but {len(left)} of its processes are still there (pids "
                   f"{', '.join(map(str, left))}); `teleo stop {info.key}` stops them",
                   err=err)


def who_of(info: RunInfo) -> str:
    """`run R (router EP)`, `, secured` added for a secured run: how a tool names a launch
    (where its registry file is, `teleo ps` says)."""
    secured = ", secured" if info.secured else ""
    return f"run {info.run} (router {info.endpoint}{secured})"
