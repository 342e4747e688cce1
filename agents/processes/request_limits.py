"""Rate limits on goal requests: one token bucket per client and one for all clients together.

A client is the `sender` of the GoalRequest's envelope (the process name it opened its bus
node with; `teleo goal` is `goal-cli`). The sender is not authenticated, so the overall
bucket bounds what any number of clients, or one client changing its name, can do. Pure:
the caller passes the time (monotonic seconds), so tests need no clock.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass

PER_CLIENT = (20, 5.0)
"""(burst [requests], sustained rate [requests/s]) of one client."""
OVERALL = (60, 20.0)
"""(burst [requests], sustained rate [requests/s]) of all clients together."""
MAX_CLIENTS = 256
"""Clients remembered; the least recently seen is forgotten first (its bucket starts full)."""
MAX_SENDER_CHARS = 64
"""[characters] of a sender name that tell clients apart (a longer name is cut)."""


@dataclass
class TokenBucket:
    """`capacity` tokens, refilled at `rate` per second; a request takes one."""

    capacity: float
    rate: float
    tokens: float
    last: float

    def take(self, now: float) -> float:
        """Take a token: 0.0 if there was one, else the seconds until there will be one."""
        self.tokens = min(self.capacity, self.tokens + (now - self.last) * self.rate)
        self.last = now
        if self.tokens >= 1.0:
            self.tokens -= 1.0
            return 0.0
        return (1.0 - self.tokens) / self.rate


class RequestLimiter:
    """Admits or refuses each request, with the reason a refused client is told."""

    def __init__(self, per_client: tuple[int, float] = PER_CLIENT,
                 overall: tuple[int, float] = OVERALL, max_clients: int = MAX_CLIENTS) -> None:
        self.per_client = per_client
        self.overall = overall
        self.max_clients = max_clients
        self._clients: OrderedDict[str, TokenBucket] = OrderedDict()
        self._all: TokenBucket | None = None

    def admit(self, sender: str, now: float) -> str:
        """"" if the request of `sender` at `now` [s] may go ahead, else why not."""
        sender = sender[:MAX_SENDER_CHARS]
        bucket = self._client(sender, now)
        wait = bucket.take(now)
        if wait:
            burst, rate = self.per_client
            return (f"too many requests from client {sender!r}: at most {burst} at once "
                    f"and {rate:g} per second; try again in {wait:.1f} s")
        if self._all is None:
            self._all = TokenBucket(self.overall[0], self.overall[1], self.overall[0], now)
        wait = self._all.take(now)
        if wait:
            burst, rate = self.overall
            return (f"too many requests from all clients together: at most {burst} at once and "
                    f"{rate:g} per second; try again in {wait:.1f} s")
        return ""

    def _client(self, sender: str, now: float) -> TokenBucket:
        bucket = self._clients.get(sender)
        if bucket is None:
            burst, rate = self.per_client
            bucket = self._clients[sender] = TokenBucket(burst, rate, burst, now)
            while len(self._clients) > self.max_clients:
                self._clients.popitem(last=False)
        else:
            self._clients.move_to_end(sender)
        return bucket
