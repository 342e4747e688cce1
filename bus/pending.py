"""Queries answered later, from a process's main loop: `serve_later(node, key)`.

`Node.serve` answers a query on zenoh's callback thread, at once. Some answers can only be
given at a point of the main loop: the world applies an event at a cycle boundary, so its
verdict on a `teleo event` exists only then. Here the callback only decodes the request and
queues it with the zenoh Query; the main loop takes the queued requests when it is ready
(`take`) and answers each (`Pending.answer`, or `fail`), which sends the reply and finalises
the query. The asker waits on its own `get` timeout meanwhile (docs/bus.md, "World events").

    desk = serve_later(node, keys.world_events(run))
    for pending in desk.take():                       # at the cycle boundary
        pending.answer(EventReply(node.envelope(t), ok, reason, outcome))
    desk.close("the run ended")                       # whatever is left gets an error reply
"""

from __future__ import annotations

import logging
import queue
from dataclasses import dataclass

import zenoh

from bus.codec import encode
from bus.messages import Message
from bus.node import decode_query

log = logging.getLogger(__name__)
__all__ = ["Pending", "PendingQueries", "serve_later"]


@dataclass
class Pending:
    """One decoded request waiting for its answer."""

    request: Message
    key: str
    _query: zenoh.Query

    def answer(self, reply: Message) -> None:
        """Send ``reply`` and finalise the query (once)."""
        try:
            self._query.reply(self.key, encode(reply))
        finally:
            self._query.drop()

    def fail(self, reason: str) -> None:
        """Answer with an error reply saying ``reason`` (the asker gets QueryFailed)."""
        try:
            self._query.reply_err(reason)
        finally:
            self._query.drop()


class PendingQueries:
    """The queries received on one key and not yet answered, in arrival order."""

    def __init__(self, node, key: str) -> None:
        self.key = key
        self._queue: queue.SimpleQueue[Pending] = queue.SimpleQueue()
        self._queryable = node.session.declare_queryable(key, self._on_query)

    def _on_query(self, query: zenoh.Query) -> None:
        """zenoh's callback thread: decode and queue; a bad request is answered at once."""
        qkey = str(query.key_expr)
        request = decode_query(query)
        if request is None:
            query.drop()
            return
        self._queue.put(Pending(request, qkey, query))

    def take(self) -> list[Pending]:
        """Every request queued so far (never blocks)."""
        taken = []
        while True:
            try:
                taken.append(self._queue.get_nowait())
            except queue.Empty:
                return taken

    def close(self, reason: str) -> None:
        """Fail every request still queued with ``reason`` and stop serving the key."""
        for pending in self.take():
            pending.fail(reason)
        self._queryable.undeclare()


def serve_later(node, key: str) -> PendingQueries:
    """Serve queries on ``key`` from ``node``'s session, to be answered from the main loop."""
    return PendingQueries(node, key)
