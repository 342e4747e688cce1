"""A child process of `teleo launch` never outlives its launcher.

The launcher puts its pid in TELEO_PARENT_PID for every child. `hold_on_to_parent()`, called
first thing in each child, asks Linux to send SIGTERM when the parent dies
(prctl(PR_SET_PDEATHSIG), through ctypes) and starts a watchdog thread that notices the same
by polling the parent pid (other systems, and the race where the parent died before the
prctl). The child's SIGTERM handler then stops it in an orderly way; if it has not exited
`GRACE_S` seconds later, the watchdog ends it with `os._exit`. So a launcher killed by any
signal (SIGKILL, SIGHUP of a closed terminal) takes its whole run with it within a second or
two (docs/faults.md). A stopped (SIGSTOPped) child runs nothing until continued: it exits when
it is.
"""

from __future__ import annotations

import cProfile
import ctypes
import ctypes.util
import logging
import os
import signal
import sys
import threading
import time
from collections.abc import Callable
from typing import NoReturn

log = logging.getLogger(__name__)
ENV_PARENT = "TELEO_PARENT_PID"
ENV_PROFILE = "TELEO_PROFILE"  # a folder: each process writes a cProfile of its run there
POLL_S = 0.2    # [s] how often the watchdog looks at the parent pid
GRACE_S = 1.5   # [s] from the parent's death to a forced exit
EXIT_ORPHANED = 75  # exit status of a child forced out after its launcher died
_PR_SET_PDEATHSIG = 1


def hold_on_to_parent(environ: dict[str, str] | None = None) -> int | None:
    """Tie this process's life to the launcher named in TELEO_PARENT_PID (no-op without it);
    returns that pid. Call it from the main thread after the signal handlers are installed."""
    env = os.environ if environ is None else environ
    text = env.get(ENV_PARENT, "")
    if not text.isdigit():
        return None
    parent = int(text)
    _set_pdeathsig(signal.SIGTERM)
    threading.Thread(target=_watch, args=(parent,), name="lifeline", daemon=True).start()
    if os.getppid() != parent:  # died before the prctl took effect
        os.kill(os.getpid(), signal.SIGTERM)
    return parent


def _set_pdeathsig(sig: int) -> bool:
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        return libc.prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0) == 0
    except (OSError, AttributeError) as exc:
        log.warning("prctl(PR_SET_PDEATHSIG) unavailable (%s); polling the parent only", exc)
        return False


def _watch(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(POLL_S)
    log.warning("launcher (pid %d) is gone: stopping", parent)
    os.kill(os.getpid(), signal.SIGTERM)  # a second SIGTERM after PDEATHSIG is harmless
    time.sleep(GRACE_S)
    log.error("still running %.1f s after the launcher died: exiting now", GRACE_S)
    logging.shutdown()
    os._exit(EXIT_ORPHANED)


def run_then_exit(main: Callable[[], object]) -> NoReturn:
    """Run a process's `main` (a click command), then leave at once with its exit status,
    skipping the interpreter's finalisation: zenoh's native threads can still call into
    Python while it finalises, which aborts the process ("FATAL: exception not rethrown",
    status -6) after its work was done. Every file is closed and logging flushed first."""
    code = 1
    profile = _profiler()
    try:
        main()
        code = 0
    except SystemExit as exc:
        code = _status(exc.code)
    except KeyboardInterrupt:
        code = 130
    finally:
        if profile is not None:
            _save_profile(*profile)
        logging.shutdown()
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):  # a closed pipe: nothing more can be said
                pass
    os._exit(code)


def _profiler() -> tuple[cProfile.Profile, str] | None:
    """A running profiler and the file it is to be saved in, when TELEO_PROFILE names a
    folder (``<module>-<pid>.prof``: read with ``python -m pstats`` or snakeviz)."""
    folder = os.environ.get(ENV_PROFILE, "")
    if not folder:
        return None
    spec = getattr(sys.modules.get("__main__"), "__spec__", None)
    name = spec.name if spec is not None else os.path.basename(sys.argv[0])
    profile = cProfile.Profile()
    profile.enable()
    return profile, os.path.join(folder, f"{name}-{os.getpid()}.prof")


def _save_profile(profile: cProfile.Profile, path: str) -> None:
    profile.disable()
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        profile.dump_stats(path + ".tmp")
        os.replace(path + ".tmp", path)   # a process killed meanwhile leaves no torn file
    except OSError as exc:
        log.error("cannot save the profile %s: %s", path, exc)


def _status(code: object) -> int:
    """sys.exit's argument as a process status (a message is printed, as Python does)."""
    if code is None:
        return 0
    if isinstance(code, int):
        return code & 0xFF
    sys.stderr.write(f"{code}\n")  # what Python prints for SystemExit("message")
    return 1
