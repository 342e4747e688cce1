"""Inbox without a bus: what zenoh's callback enqueues comes out decoded (or raw and
stamped); bad payloads are counted and skipped; polling an empty inbox returns None."""

from __future__ import annotations

import time

from bus import keys
from bus.codec import encode
from bus.inbox import Inbox
from bus.messages import Envelope, Percepts

KEY = keys.percepts("r", "ME")
MSG = Percepts(Envelope(1, "r", 4, "ME.perception", 1), "ME", (["a", 1, 2.5],))


class FakeSample:
    """The two attributes of zenoh.Sample that the inbox reads."""

    class _Payload:
        def __init__(self, data: bytes) -> None:
            self.data = data

        def to_bytes(self) -> bytes:
            return self.data

    def __init__(self, key: str, data: bytes) -> None:
        self.key_expr = key
        self.payload = self._Payload(data)


def test_decoded_inbox_skips_bad_payloads_and_polls_empty():
    inbox = Inbox()
    assert inbox.receive(0) is None
    for data in (b"\xc1junk", encode(MSG)):
        inbox.callback(FakeSample(KEY, data))
    before = time.time_ns()
    got = inbox.receive(1.0)
    assert got is not None and got.msg == MSG and got.key == KEY
    assert got.payload == encode(MSG) and got.t_ns >= before
    assert (inbox.dropped, inbox.received, inbox.pending()) == (1, 1, 0)
    assert inbox.receive(0) is None and inbox.get(0.01) is None


def test_raw_inbox_stamps_arrival_and_does_not_decode():
    inbox = Inbox(raw=True)
    before = time.time_ns()
    inbox.callback(FakeSample(KEY, b"\xc1junk"))
    after = time.time_ns()
    time.sleep(0.01)
    got = inbox.receive(0)
    assert got is not None and got.msg is None and got.payload == b"\xc1junk"
    assert before <= got.t_ns <= after
    assert (inbox.dropped, inbox.received) == (0, 1)
