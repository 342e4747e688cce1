"""A payload's round trip between two processes over zenoh, sent as plain bytes or in a
zenoh shared-memory buffer (zenoh.shm), for bench/speed/bus_shm.py (zenoh's
shared-memory transport between processes on one host, measured against today's puts).

    python -m bus.shm_probe --endpoint tcp/127.0.0.1:PORT    # the echo side, until killed

Both sides are peers on one loopback endpoint, shared memory enabled (zenoh's default, which
teleo's processes keep: puts of 3 KB or more are then copied into shared memory by the
transport itself) or disabled; the echo side sends back each payload it receives as it came.
"""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import threading
import time

import click
import zenoh

PING, PONG = "teleo/probe/ping", "teleo/probe/pong"


def _config(listen: str | None, connect: str | None, shm: bool = True) -> zenoh.Config:
    conf = zenoh.Config()
    conf.insert_json5("mode", '"peer"')
    conf.insert_json5("scouting/multicast/enabled", "false")
    conf.insert_json5("listen/endpoints", json.dumps([listen] if listen else []))
    conf.insert_json5("connect/endpoints", json.dumps([connect] if connect else []))
    conf.insert_json5("transport/shared_memory/enabled", json.dumps(shm))
    return conf


def round_trips(size: int, n: int, shm: bool,
                enabled: bool = True) -> tuple[list[float], int]:
    """``n`` round trips [ms] of a ``size``-byte payload to an echo process on a free
    loopback port (started here, stopped at the end), after 50 not counted, and how many of
    all the answers came back in shared memory. ``shm``: the payload sent in a shared-memory
    buffer; ``enabled``: shared memory enabled on both sides."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        endpoint = f"tcp/127.0.0.1:{s.getsockname()[1]}"
    echo = subprocess.Popen([sys.executable, "-m", "bus.shm_probe", "--endpoint", endpoint,
                             *([] if enabled else ["--no-shm"])])
    try:
        with zenoh.open(_config(None, endpoint, enabled)) as session:
            got, in_shm = threading.Event(), [0]

            def pong(sample: zenoh.Sample) -> None:
                in_shm[0] += sample.payload.as_shm() is not None
                got.set()

            sub = session.declare_subscriber(PONG, pong)
            pub = session.declare_publisher(PING)
            provider = zenoh.shm.ShmProvider.default_backend(max(1 << 20, 8 * size))
            policy = zenoh.shm.BlockOn(zenoh.shm.GarbageCollect())
            data = bytes(range(256)) * (size // 256) + bytes(size % 256)
            _wait_for_echo(pub, got)
            out = [_one(pub, got, data, provider, policy, shm) for _ in range(n + 50)]
            sub.undeclare()
            return out[50:], in_shm[0]
    finally:
        echo.kill()
        echo.wait(timeout=10)


def _wait_for_echo(pub, got: threading.Event, seconds: float = 20.0) -> None:
    """Ping until the echo process answers (it starts and connects in its own time)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        got.clear()
        pub.put(b"ready?")
        if got.wait(0.2):
            return
    raise SystemExit(f"the echo process did not answer within {seconds:.0f} s")


def _one(pub, got: threading.Event, data: bytes, provider, policy, shm: bool) -> float:
    got.clear()
    t0 = time.perf_counter()
    if shm:
        buf = provider.alloc(len(data), policy=policy)
        buf[:] = data
        pub.put(buf)
    else:
        pub.put(data)
    if not got.wait(5.0):
        raise SystemExit("no echo within 5 s: is the probe's endpoint free?")
    return (time.perf_counter() - t0) * 1e3


@click.command()
@click.option("--endpoint", required=True, help="The loopback endpoint to listen on.")
@click.option("--no-shm", is_flag=True, help="Shared memory disabled.")
def main(endpoint: str, no_shm: bool) -> None:
    """Echo every ping back as a pong until killed."""
    with zenoh.open(_config(endpoint, None, not no_shm)) as session:
        pub = session.declare_publisher(PONG)
        session.declare_subscriber(PING, lambda s: pub.put(s.payload))
        threading.Event().wait()


if __name__ == "__main__":
    main()
