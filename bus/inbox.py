"""Where a process's subscriptions deliver: `Inbox` (a FIFO read by the main loop) and
`RingInbox` (zenoh's own ring buffer, drained now and then) and `FifoInbox` (zenoh's own
FIFO, drained in batches: nothing lost). Made by `Node.subscribe`, `Node.subscribe_ring` and
`Node.subscribe_fifo`; also importable from `bus.node`.

Hand-off cost (docs/bus.md, "Benchmark"): every sample crosses from zenoh's callback thread
to the reading thread. For decoded inboxes the callback is `SimpleQueue.put` itself, so the
callback thread runs no Python bytecode and gives the GIL back at once; the reading thread
copies the payload and decodes it.
"""

from __future__ import annotations

import logging
import queue
import time
from collections.abc import Callable
from typing import Any, NamedTuple

import zenoh

from bus.codec import decode
from bus.errors import CodecError
from bus.messages import Message

log = logging.getLogger(__name__)


class Received(NamedTuple):
    """One delivered sample: its key, the decoded message (None for raw inboxes), the raw
    payload and the local receive time [ns since the epoch]: when zenoh delivered it for raw
    inboxes (record, echo), when the reading thread took it for decoded ones."""

    key: str
    msg: Message | None
    payload: bytes
    t_ns: int


class Inbox:
    """A FIFO of samples from one or more subscriptions, read by the process's main loop.

    zenoh's callback thread only enqueues (never blocks); decoding happens in
    `get`/`receive`. Malformed, unknown-version or wrong-kind payloads are logged with
    their key, counted in `dropped` and skipped.
    """

    def __init__(self, raw: bool = False) -> None:
        self.raw = raw
        self.dropped = 0
        self.received = 0
        # decoded inboxes queue zenoh Samples, raw ones (key, payload, arrival ns) tuples
        self._q: queue.SimpleQueue[Any] = queue.SimpleQueue()

    @property
    def callback(self) -> Callable[[zenoh.Sample], None]:
        """The subscriber callback feeding this inbox (run on zenoh's callback thread)."""
        return self._push_stamped if self.raw else self._q.put

    def _push_stamped(self, sample: zenoh.Sample) -> None:
        self._q.put((str(sample.key_expr), sample.payload.to_bytes(), time.time_ns()))

    def receive(self, timeout: float | None) -> Received | None:
        """Next valid sample, waiting at most `timeout` [s] (None: forever); None on timeout."""
        if timeout == 0 and self._q.empty():
            return None  # polling an empty inbox: no clock reads, no queue.Empty raised
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            remaining = None if deadline is None else max(0.0, deadline - time.monotonic())
            try:
                item = self._q.get(timeout=remaining)
            except queue.Empty:
                return None
            if self.raw:
                key, payload, t_ns = item
                self.received += 1
                return Received(key, None, payload, t_ns)
            got = self._decoded(item)
            if got is not None:
                return got

    def _decoded(self, sample: zenoh.Sample) -> Received | None:
        """The decoded Received of `sample`, or None (logged, counted) if it is bad."""
        key, payload = str(sample.key_expr), sample.payload.to_bytes()
        t_ns = time.time_ns()
        try:
            msg = decode(key, payload)
        except CodecError as exc:
            self.dropped += 1
            log.warning("dropped payload: %s", exc)
            return None
        self.received += 1
        return Received(key, msg, payload, t_ns)

    def get(self, timeout: float | None) -> Message | None:
        """Next decoded message, waiting at most `timeout` [s]; None on timeout."""
        item = self.receive(timeout)
        return None if item is None else item.msg

    def pending(self) -> int:
        """Samples queued but not yet read (approximate)."""
        return self._q.qsize()


class RingInbox:
    """The latest `capacity` samples of a subscription, kept in zenoh's own ring buffer: no
    Python thread wakes per sample, so it costs the process almost nothing between reads.
    For side channels read now and then (the clock's view of ProcessStats); the oldest
    samples are lost when more than `capacity` arrive between two `drain` calls."""

    def __init__(self, subscriber: zenoh.Subscriber) -> None:
        self._sub = subscriber
        self.dropped = 0

    def drain(self) -> list[Received]:
        """Every sample buffered now, decoded; bad payloads are logged, counted, skipped."""
        out: list[Received] = []
        while (sample := self._sub.try_recv()) is not None:
            key, payload = str(sample.key_expr), sample.payload.to_bytes()
            try:
                out.append(Received(key, decode(key, payload), payload, time.time_ns()))
            except CodecError as exc:
                self.dropped += 1
                log.warning("dropped payload: %s", exc)
        return out


class FifoInbox:
    """Every raw sample of a subscription, queued in zenoh's own FIFO and taken in batches
    with `drain`: no Python runs on zenoh's thread per sample and the reader wakes when it
    chooses, so a busy subscription (the run record: every message of a run) costs the
    process's other threads little. Nothing is dropped: when `capacity` samples wait unread,
    zenoh's receiving thread waits for the reader."""

    def __init__(self, subscriber: zenoh.Subscriber) -> None:
        self._sub = subscriber

    def drain(self, most: int = 4096) -> list[tuple[str, bytes]]:
        """Up to `most` samples waiting now, oldest first, as (key, payload)."""
        out: list[tuple[str, bytes]] = []
        while len(out) < most and (sample := self._sub.try_recv()) is not None:
            out.append((str(sample.key_expr), sample.payload.to_bytes()))
        return out
