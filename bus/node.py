"""One process's handle on the bus: a zenoh session plus teleo's keys and codec.

    with open_node(cfg, run="r1", process="ME.perception") as node:
        inbox = node.subscribe(keys.world_state("r1"))
        node.declare([keys.percepts("r1", "ME")])
        node.announce()                       # liveliness token, after pubs/subs exist
        msg = inbox.get(timeout=1.0)          # decoded message or None
        node.publish(keys.percepts("r1", "ME"), Percepts(node.envelope(msg.env.cycle), ...))

The session is always closed on leaving the `with` block: an open session's callback
threads keep the interpreter alive (docs/bus.md, "Zenoh in Python", item 1). Open nodes only in
processes started by spawn/subprocess, never in a child forked after a session was open.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager

import zenoh

from bus import keys
from bus.codec import decode, encode
from bus.config import BusConfig
from bus.errors import BusError, CodecError, NobodyServing, QueryFailed
from bus.inbox import FifoInbox, Inbox, Received, RingInbox
from bus.messages import Envelope, Message, ProcessStats
from bus.presence import Presence

log = logging.getLogger(__name__)
__all__ = ["FifoInbox", "Inbox", "Node", "Received", "RingInbox", "open_node"]
_MSGPACK = zenoh.Encoding("application/msgpack")


class Node:
    """A zenoh session bound to one run and one process name. Build it with `open_node`."""

    def __init__(self, session: zenoh.Session, cfg: BusConfig, run: str, process: str) -> None:
        self.session = session
        self.cfg = cfg
        self.run = keys.check_chunk(run, "run")
        self.process = keys.check_chunk(process, "process")
        self._pubs: dict[str, zenoh.Publisher] = {}
        self._encodings: dict[str, zenoh.Encoding] = {}
        self._entities: list[object] = []  # subscribers/queryables kept alive until close
        self._token: zenoh.LivelinessToken | None = None
        self._aliases: list[zenoh.LivelinessToken] = []
        self._presence: Presence | None = None
        self._lock = threading.Lock()

    # -- publishing -------------------------------------------------------------------
    def envelope(self, cycle: int = -1) -> Envelope:
        """A fresh envelope from this node for `cycle` (-1: outside the cycle)."""
        return Envelope.now(self.run, cycle, self.process)

    def declare(self, keys_: Iterable[str]) -> None:
        """Declare publishers for `keys_` now (before `announce`), so subscribers can match."""
        for key in keys_:
            self._publisher(key)

    def _publisher(self, key: str) -> zenoh.Publisher:
        pub = self._pubs.get(key)
        if pub is None:
            with self._lock:  # serve() handlers may publish from zenoh's threads
                pub = self._pubs.get(key)
                if pub is None:
                    pub = self.session.declare_publisher(
                        key, encoding=_MSGPACK, express=False,
                        congestion_control=zenoh.CongestionControl.BLOCK)
                    self._pubs[key] = pub
        return pub

    def publish(self, key: str, msg: Message) -> None:
        """Encode `msg` and put it on `key` (reliable, BLOCK congestion control, not express:
        see docs/bus.md)."""
        self._publisher(key).put(encode(msg), encoding=self._encoding(msg))

    def publish_many(self, items: Iterable[tuple[str, Message]]) -> None:
        """Publish several messages in order: all are encoded first, then put back to back,
        so the first put's wake-up of zenoh's sending thread also carries the others (a put
        into an idle session pays for that wake-up, one right after another hardly at all).
        A message on a key no subscriber matches now is left out unencoded: zenoh, whose
        routing the matching status is, would send it nowhere (a shared process's percepts
        and beliefs in a run without a record)."""
        encoded = [(pub, self._encoding(msg), encode(msg)) for key, msg in items
                   if (pub := self._publisher(key)).matching_status.matching]
        for pub, enc, payload in encoded:
            pub.put(payload, encoding=enc)

    def _encoding(self, msg: Message) -> zenoh.Encoding:
        enc = self._encodings.get(msg.KIND)
        if enc is None:
            enc = _MSGPACK.with_schema(f"teleo.{msg.KIND}/{msg.env.v}")
            self._encodings[msg.KIND] = enc
        return enc

    def publish_stats(self, cycle: int, compute_ms: float, late: int = 0) -> None:
        """Publish this process's ProcessStats for `cycle` on teleo/<run>/stats/<process>
        (compute_ms [ms]; late: cycles skipped so far [count]), for the inspector."""
        self.publish(keys.stats(self.run, self.process),
                     ProcessStats(self.envelope(cycle), self.process, compute_ms, late))

    def put_raw(self, key: str, payload: bytes) -> None:
        """Put raw bytes on `key` (replay, fault injection); no encoding check."""
        self._publisher(key).put(payload)

    def matching(self, key: str) -> bool:
        """Whether the publisher on `key` currently has at least one matching subscriber."""
        return bool(self._publisher(key).matching_status.matching)

    def wait_matching(self, keys_: Iterable[str], timeout: float) -> set[str]:
        """Wait up to `timeout` [s] until every key's publisher has a subscriber; return the
        keys still unmatched (empty set: all matched)."""
        pending = set(keys_)
        deadline = time.monotonic() + timeout
        waiter = threading.Event()
        while True:
            pending = {k for k in pending if not self.matching(k)}
            if not pending or time.monotonic() >= deadline:
                return pending
            waiter.wait(0.005)  # polling the matching status; bounded by `timeout`

    # -- subscribing ------------------------------------------------------------------
    def subscribe(self, key_expr: str, inbox: Inbox | None = None, raw: bool = False) -> Inbox:
        """Subscribe to `key_expr`; samples go to `inbox` (a new one unless given, so several
        subscriptions can feed one main loop). `raw=True` skips decoding (record/replay)."""
        box = inbox if inbox is not None else Inbox(raw=raw)
        sub = self.session.declare_subscriber(key_expr, box.callback)
        with self._lock:
            self._entities.append(sub)
        return box

    def subscribe_ring(self, key_expr: str, capacity: int = 1024) -> RingInbox:
        """Subscribe to `key_expr` into a RingInbox (read with `drain()`, never blocks)."""
        sub = self.session.declare_subscriber(key_expr, zenoh.handlers.RingChannel(capacity))
        with self._lock:
            self._entities.append(sub)
        return RingInbox(sub)

    def subscribe_fifo(self, key_expr: str, capacity: int = 1 << 16) -> FifoInbox:
        """Subscribe to `key_expr` into a FifoInbox (raw samples, read in batches with
        `drain()`; zenoh's thread waits when `capacity` samples are unread)."""
        sub = self.session.declare_subscriber(key_expr, zenoh.handlers.FifoChannel(capacity))
        with self._lock:
            self._entities.append(sub)
        return FifoInbox(sub)

    # -- liveliness -------------------------------------------------------------------
    def announce(self, also: Iterable[str] = ()) -> None:
        """Declare the liveliness token teleo/<run>/proc/<process>, and one for each name in
        `also` (the stages a shared process runs). Call it after all publishers and
        subscribers are declared: it means "ready"."""
        if self._token is None:
            liveliness = self.session.liveliness()
            self._token = liveliness.declare_token(keys.proc(self.run, self.process))
            self._aliases = [liveliness.declare_token(keys.proc(self.run, keys.check_chunk(
                name, "process"))) for name in also]

    @property
    def presence(self) -> Presence:
        """Live view of which processes of this run hold liveliness tokens."""
        if self._presence is None:
            self._presence = Presence(self.session, self.run)
        return self._presence

    def alive(self) -> set[str]:
        """Names of the processes of this run currently announced (liveliness get+subscriber)."""
        return set(self.presence.snapshot())

    # -- request / reply --------------------------------------------------------------
    def serve(self, key: str, handler: Callable[[Message], Message]) -> None:
        """Answer queries on `key`: each request is decoded, `handler(request) -> reply` is
        called (on zenoh's callback thread: keep it short, thread-safe) and the reply sent.
        Bad requests and handler errors are answered with an error reply, never crash."""

        def on_query(query: zenoh.Query) -> None:
            qkey = str(query.key_expr)
            request = decode_query(query)
            if request is None:
                return
            try:
                reply = handler(request)
                payload = encode(reply)
            except Exception as exc:  # the serving process must survive any handler error
                log.exception("query handler for %s failed", qkey)
                query.reply_err(f"{type(exc).__name__}: {exc}")
                return
            query.reply(qkey, payload)

        q = self.session.declare_queryable(key, on_query)
        with self._lock:
            self._entities.append(q)

    def query(self, key: str, request: Message, timeout: float = 2.0) -> Message:
        """Send `request` to the queryable on `key` and return its decoded reply.

        Raises NobodyServing if no queryable answers within `timeout` [s], QueryFailed on
        an error reply, CodecError if the reply cannot be decoded.
        """
        deadline = time.monotonic() + timeout
        self._await_queryable(key, deadline)
        replies = self.session.get(key, payload=encode(request),
                                   timeout=max(0.05, deadline - time.monotonic()))
        for reply in replies:
            if reply.ok is not None:
                return decode(str(reply.ok.key_expr), reply.ok.payload.to_bytes())
            raise QueryFailed(key, reply.err.payload.to_bytes().decode(errors="replace"))
        raise NobodyServing(key, timeout)

    def _await_queryable(self, key: str, deadline: float) -> None:
        """Wait until a queryable on `key` is known here, or `deadline` [monotonic s]. A get
        that no known queryable matches comes back at once with no reply: right after a
        router restart a tool would ask before the serving process is routed again (the
        request is never delivered, so waiting for the route cannot answer a request twice)."""
        querier = self.session.declare_querier(key)
        try:
            while not querier.matching_status.matching and time.monotonic() < deadline:
                time.sleep(0.02)
        finally:
            querier.undeclare()

    def close(self) -> None:
        """Undeclare the token first (so peers see us go at once), then everything else."""
        for token in self._aliases:
            token.undeclare()
        self._aliases = []
        if self._token is not None:
            self._token.undeclare()
            self._token = None


@contextmanager
def open_node(cfg: BusConfig, run: str, process: str) -> Iterator[Node]:
    """Open a zenoh session from `cfg` as `process` of `run`; always closed on exit."""
    try:
        session = zenoh.open(cfg.to_zenoh())
    except zenoh.ZError as exc:
        raise BusError(f"cannot open zenoh session ({cfg.mode.value}, connect={list(cfg.connect)}, "
                       f"listen={list(cfg.listen)}) for {process!r}: {exc}") from exc
    try:
        node = Node(session, cfg, run, process)
        try:
            yield node
        finally:
            node.close()
    finally:
        _close(session, process)


def _close(session: zenoh.Session, process: str) -> None:
    """Close the session; a close that times out (a machine too busy to finish it in time)
    is logged, never raised over what ended the process (an error it is reporting)."""
    try:
        session.close()
    except zenoh.ZError as exc:
        log.warning("%s: closing the zenoh session failed: %s", process, exc)


def decode_query(query: zenoh.Query) -> Message | None:
    """The request a query carries, or None after answering a bad one with an error reply
    naming the key and what is wrong (a serving process never crashes on bad input)."""
    qkey = str(query.key_expr)
    try:
        return decode(qkey, b"" if query.payload is None else query.payload.to_bytes())
    except CodecError as exc:
        log.warning("bad query: %s", exc)
        query.reply_err(str(exc))
        return None
