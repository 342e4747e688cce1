"""Rate limits on goal requests: per client (the envelope's sender) and for all clients."""

from __future__ import annotations

from agents.processes.request_limits import RequestLimiter


def admitted(limiter: RequestLimiter, sender: str, count: int, now: float) -> int:
    return sum(1 for _ in range(count) if not limiter.admit(sender, now))


def test_a_client_gets_its_burst_then_its_rate():
    limiter = RequestLimiter(per_client=(5, 2.0), overall=(100, 100.0))
    assert admitted(limiter, "cli", 50, now=0.0) == 5
    reason = limiter.admit("cli", 0.0)
    assert reason == ("too many requests from client 'cli': at most 5 at once and 2 per "
                      "second; try again in 0.5 s")
    assert admitted(limiter, "cli", 50, now=1.0) == 2  # 1 s at 2 per second
    assert admitted(limiter, "cli", 50, now=100.0) == 5  # never more than the burst


def test_clients_are_limited_apart_and_all_together():
    limiter = RequestLimiter(per_client=(5, 1.0), overall=(12, 1.0))
    assert admitted(limiter, "a", 10, 0.0) == 5
    assert admitted(limiter, "b", 10, 0.0) == 5  # a's burst does not count against b
    assert admitted(limiter, "c", 10, 0.0) == 2  # all together: 12
    assert limiter.admit("d", 0.0).startswith("too many requests from all clients together")


def test_only_the_latest_clients_are_remembered():
    limiter = RequestLimiter(per_client=(1, 1.0), overall=(10_000, 1.0), max_clients=3)
    assert admitted(limiter, "c0", 2, 0.0) == 1
    assert admitted(limiter, "c1", 2, 0.0) == 1 and admitted(limiter, "c0", 1, 0.0) == 0
    for n in range(2, 5):
        limiter.admit(f"c{n}", 0.0)
    assert admitted(limiter, "c0", 2, 0.0) == 1  # forgotten, so its bucket starts full
