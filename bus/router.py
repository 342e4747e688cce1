"""A Python zenoh session in router mode: the hub for local runs and tests (zenohd is not on
PyPI). `python -m bus.router --listen tcp/127.0.0.1:7447`, `teleo router`, or from code
`spawn_router()`, which starts it as a subprocess and reads back its actual endpoint.

On start the router prints one line `TELEO-ROUTER <endpoint> ...` on stdout (the endpoints
it really listens on, read from its adminspace, so port 0 works) and runs until
SIGINT/SIGTERM (or until its launcher dies: bus/lifeline.py). `--security FILE` makes it a
secured router (TLS, users, access control: bus/security.py). Started again on the same
endpoint after a crash, it is rejoined by every process within about half a second
(bus/config.py RETRY; docs/faults.md).
"""

from __future__ import annotations

import json
import logging
import os
import selectors
import subprocess
import sys
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass

import zenoh

from bus.config import BusConfig, Mode
from bus.errors import BusError, RouterError
from bus.load import overloaded, scaled
from bus.stage import stop_on_signals

log = logging.getLogger(__name__)
READY_PREFIX = "TELEO-ROUTER"


def router_config(listen: Sequence[str], connect: Sequence[str] = (),
                  security: str = "") -> BusConfig:
    """The config of a hub listening on `listen` (and linked to other routers in `connect`);
    `security`: a router security file (bus/security.py) for a secured run."""
    return BusConfig(mode=Mode.ROUTER, listen=tuple(listen), connect=tuple(connect),
                     router_security=security)


def locators(session: zenoh.Session, timeout: float = 2.0) -> list[str]:
    """The endpoints this router session actually listens on, from its adminspace."""
    for reply in session.get(f"@/{session.zid()}/router", timeout=timeout):
        if reply.ok is not None:
            return list(json.loads(reply.ok.payload.to_bytes()).get("locators", []))
    return []


def serve(cfg: BusConfig, stop: threading.Event, ready_out: object = None) -> None:
    """Run a router session from `cfg` until `stop` is set; writes the ready line to
    `ready_out` (a text stream, default stdout)."""
    out = sys.stdout if ready_out is None else ready_out
    with _open_router(cfg) as session:
        eps = locators(session) or list(cfg.listen)
        out.write(f"{READY_PREFIX} {' '.join(eps)}\n")
        out.flush()
        log.info("router %s listening on %s", session.zid(), eps)
        stop.wait()


def _open_router(cfg: BusConfig) -> zenoh.Session:
    """The router's session; raises RouterError naming the endpoints when it cannot listen
    (a port already in use: another router, or zenohd, whose default port is 7447 too)."""
    try:
        return zenoh.open(cfg.to_zenoh())
    except zenoh.ZError as exc:
        busy = "Address already in use" in str(exc)
        hint = ("; the port is in use (another `teleo router` or zenohd?): pick another, or "
                "tcp/127.0.0.1:0 for a free one") if busy else ""
        raise RouterError(f"cannot start a router listening on {', '.join(cfg.listen)}"
                          f"{hint} ({str(exc).split(' at /')[0]})") from None


def main(argv: Sequence[str] | None = None) -> None:
    """`python -m bus.router [--listen EP[,EP]] [--connect EP[,EP]]`."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m bus.router", description=__doc__)
    parser.add_argument("--listen", default="tcp/127.0.0.1:7447")
    parser.add_argument("--connect", default="")
    parser.add_argument("--security", default="", help="router security file (secured run)")
    parser.add_argument("--run", default="", help="the run it serves (to name it in `ps`)")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO,
                        format="%(asctime)s router %(name)s %(levelname)s %(message)s")
    split = [e.strip() for e in args.listen.split(",") if e.strip()]
    conn = [e.strip() for e in args.connect.split(",") if e.strip()]
    try:
        run_until_signalled(router_config(split, conn, args.security))
    except (BusError, zenoh.ZError) as exc:
        log.error("router on %s: %s", split, exc)
        raise SystemExit(2) from exc


def run_until_signalled(cfg: BusConfig) -> None:
    """Serve `cfg` until SIGINT or SIGTERM, or until the launcher that started it dies
    (then close the session and return)."""
    stop = stop_on_signals(child=True)
    serve(cfg, stop)


@dataclass
class RouterProcess:
    """A router running as a subprocess; `endpoint` is where the others connect."""

    proc: subprocess.Popen
    endpoint: str
    endpoints: tuple[str, ...]

    def stop(self, timeout: float = 5.0) -> int:
        """SIGTERM, then SIGKILL after `timeout` [s]; returns the exit code."""
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(timeout)
        if self.proc.stdout is not None:
            self.proc.stdout.close()
        return self.proc.returncode

    def __enter__(self) -> RouterProcess:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.stop()


def router_argv(listen: str, security: str = "", run: str = "") -> tuple[str, ...]:
    """The command that starts a router on `listen` with this interpreter (`run`: the run
    it serves, only so that its command line names it)."""
    extra = ("--security", security) if security else ()
    return (sys.executable, "-m", "bus.router", "--listen", listen, *extra,
            *(("--run", run) if run else ()))


ROUTER_START_S = 15.0  # [s] for the router to report ready, on a machine that is not busy


def spawn_router(listen: str = "tcp/127.0.0.1:0", timeout: float | None = None,
                 security: str = "",
                 env: dict[str, str] | None = None, log_file: str | None = None,
                 run: str = "") -> RouterProcess:
    """Start `python -m bus.router` as a subprocess listening on `listen` (port 0: a free
    port) and wait until it reports its endpoints; raises RouterError if it does not.
    `env`: extra environment; `log_file`: where its log goes (default: this stderr);
    `timeout` [s]: default ROUTER_START_S stretched by the machine's load (bus/load.py: at
    load 35-42 on 2 CPUs, launches failed at a fixed 15 s)."""
    timeout = scaled(ROUTER_START_S) if timeout is None else timeout
    full = dict(os.environ, **(env or {}))
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    full["PYTHONPATH"] = os.pathsep.join(p for p in (root, full.get("PYTHONPATH", "")) if p)
    err = open(log_file, "ab") if log_file else None  # noqa: SIM115 (the child inherits it)
    try:
        proc = subprocess.Popen(router_argv(listen, security, run), stdout=subprocess.PIPE,
                                stderr=err, stdin=subprocess.DEVNULL, text=True, env=full,
                                start_new_session=True)
    finally:
        if err is not None:
            err.close()
    try:
        line = _read_line(proc, timeout)
    except BaseException:  # KeyboardInterrupt: a Ctrl-C while it starts leaves nothing behind
        proc.kill()
        proc.wait()
        raise
    if not line.startswith(READY_PREFIX):
        proc.kill()
        proc.wait()
        raise RouterError(f"router on {listen} did not report ready within {timeout:.0f} s "
                          f"(exit code {proc.poll()}, got {line!r}){overloaded(timeout)}")
    eps = tuple(line.split()[1:])
    scheme = listen.split("/", 1)[0] + "/"
    same = [e for e in eps if e.startswith(scheme)]
    return RouterProcess(proc, (same or list(eps))[0], eps)


def _read_line(proc: subprocess.Popen, timeout: float) -> str:
    assert proc.stdout is not None
    deadline = time.monotonic() + timeout
    with selectors.DefaultSelector() as sel:
        sel.register(proc.stdout, selectors.EVENT_READ)
        while time.monotonic() < deadline:
            if sel.select(max(0.0, deadline - time.monotonic())):
                return proc.stdout.readline().strip()
            if proc.poll() is not None:
                break
    return ""


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
