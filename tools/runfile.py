"""Where a running `teleo launch` can be found: a small JSON file, so that `teleo goal` and
`teleo inspect` connect to it with no flags.

The file is `$TELEO_RUN_DIR/teleo-run.json`, or `./out/teleo-run.json` without that variable.
It holds the run id, the router endpoint, the launcher's pid, the agents, the run folder, each
process's pid and how many times the launcher restarted it (for `teleo inspect`).
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict, dataclass, field
from pathlib import Path

RUN_FILE = "teleo-run.json"


class NoRunningLaunch(Exception):
    """No `teleo launch` is running where the tools look for one."""


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
    restarts: dict[str, int] = field(default_factory=dict)  # process name -> times restarted


def base_dir() -> Path:
    """The folder holding the run file and the run folders."""
    return Path(os.environ.get("TELEO_RUN_DIR", "out"))


def run_file() -> Path:
    return base_dir() / RUN_FILE


def write(info: RunInfo) -> Path:
    path = run_file()
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(asdict(info), indent=1))
    os.replace(tmp, path)
    return path


def remove(info: RunInfo) -> None:
    """Remove the run file if it still describes `info` (a newer launch may have replaced it)."""
    path = run_file()
    try:
        if json.loads(path.read_text()).get("run") == info.run:
            path.unlink()
    except (FileNotFoundError, ValueError):
        pass


def find() -> RunInfo:
    """The running launch; raises NoRunningLaunch if the file is absent or its launcher is gone."""
    path = run_file()
    try:
        doc = json.loads(path.read_text())
        info = RunInfo(doc["run"], doc["endpoint"], int(doc["pid"]), tuple(doc["agents"]),
                       doc["run_dir"], doc.get("scenario", ""), dict(doc.get("pids", {})),
                       dict(doc.get("restarts", {})))
    except FileNotFoundError as exc:
        raise NoRunningLaunch(f"no running teleo launch found (no {path})") from exc
    except (ValueError, KeyError, TypeError) as exc:
        raise NoRunningLaunch(f"no running teleo launch found ({path} unreadable: {exc})") from exc
    if not _alive(info.pid):
        raise NoRunningLaunch(
            f"no running teleo launch found ({path} names pid {info.pid}, which has exited)")
    return info


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
