"""Pure cycle bookkeeping: joining inputs by cycle, picking what to act on, the clock's book."""

from __future__ import annotations

import pytest

from bus.cycle import CycleBook, CycleReport, Joined, Joiner, culprit, pick
from bus.messages import Actions, Beliefs, Envelope, Percepts, ProcessStats
from bus.stats import record_stats, stats_of

P, B = "teleo/r/agent/A/percepts", "teleo/r/agent/A/beliefs"


def msg(cycle: int, tag: str = "") -> Percepts:
    return Percepts(Envelope(1, "r", cycle, "x", 0), "A", ([tag],))


def test_join_waits_for_every_input_of_the_same_cycle():
    j = Joiner([P, B])
    assert j.add(P, msg(1, "p1")) is None
    assert j.add(B, msg(2, "b2")) is None  # other cycle: never mixed with cycle 1
    done = j.add(B, msg(1, "b1"))
    assert done == Joined(1, {P: msg(1, "p1"), B: msg(1, "b1")}, repeat=False)


def test_completing_a_newer_cycle_drops_older_incomplete_ones():
    j = Joiner([P, B])
    j.add(P, msg(1))
    j.add(P, msg(2))
    assert j.add(B, msg(2)).cycle == 2
    assert j.stale == 1
    assert j.add(B, msg(1)) is None  # cycle 1 was dropped: its P must come again
    assert j.add(P, msg(1)).cycle == 1


def test_repeats_and_stale_cycles_after_done():
    j = Joiner([P])
    j.done(5)
    assert j.add(P, msg(5)).repeat is True
    assert j.add(P, msg(4)) is None and j.stale == 1
    assert j.add(P, msg(6)).repeat is False


def test_unknown_keys_are_ignored_and_no_inputs_is_an_error():
    assert Joiner([P]).add(B, msg(1)) is None
    with pytest.raises(ValueError):
        Joiner([])


def test_pick_acts_on_the_newest_cycle_and_counts_the_skipped():
    a, b, c = Joined(3, {}, False), Joined(4, {}, False), Joined(5, {}, False)
    assert pick([None, a, b, None, c]) == (c, 2)
    assert pick([Joined(2, {}, True), a]) == (a, 0)
    assert pick([None]) == (None, 0)


def stats(process: str, cycle: int, ms: float = 1.0) -> ProcessStats:
    return ProcessStats(Envelope(1, "r", cycle, process, 0), process, ms, 0)


def test_book_keeps_actions_of_its_cycle_only_and_tracks_stats():
    book, seen = CycleBook(7, frozenset({"A"})), {}
    book.record(Actions(Envelope(1, "r", 6, "x", 0), "A", (["*old"],)), seen)
    book.record(Actions(Envelope(1, "r", 7, "x", 0), "Z", (["*other"],)), seen)
    assert not book.has("A")
    book.record(Actions(Envelope(1, "r", 7, "x", 0), "A", (["*gas", 1.0],)), seen)
    book.record(stats("A.perception", 7, 2.5), seen)
    book.record(stats("A.inference", 5), seen)
    assert book.actions == {"A": (["*gas", 1.0],)}
    assert book.stage_ms == {"A.perception": 2.5}
    assert seen == {"A.perception": 7, "A.inference": 5}


def test_book_takes_the_stats_an_agents_actions_carry_for_its_pipeline():
    """Issue 36: the stages' stats come with the Actions, no message of their own."""
    book, seen = CycleBook(7, frozenset({"A"})), {"A.inference": 9}
    carried = {"A.perception": [2.5, 0], "A.inference": [1.0, 3], "A.executive": [0.5, 0]}
    book.record(Actions(Envelope(1, "r", 7, "A.executive", 0), "A", (), {}, carried), seen)
    book.record(Actions(Envelope(1, "r", 6, "B.executive", 0), "B", (), {},
                        {"B.perception": [4.0, 0]}), seen)
    assert book.actions == {"A": ()}
    assert book.stage_ms == {"A.perception": 2.5, "A.inference": 1.0, "A.executive": 0.5}
    assert seen == {"A.perception": 7, "A.inference": 9, "A.executive": 7, "B.perception": 6}


def test_stats_of_reads_a_process_stats_and_the_stats_an_output_carries():
    env = Envelope(1, "r", 4, "A.inference", 11)
    beliefs = Beliefs(env, "A", (), {}, {"A.perception": [2.0, 0], "A.inference": [1.5, 2]})
    assert stats_of(beliefs) == (
        ProcessStats(Envelope(1, "r", 4, "A.perception", 11), "A.perception", 2.0, 0),
        ProcessStats(Envelope(1, "r", 4, "A.inference", 11), "A.inference", 1.5, 2))
    assert [s.process for s in stats_of(beliefs, own=True)] == ["A.inference"]
    assert stats_of(stats("A.executive", 3)) == (stats("A.executive", 3),)
    assert stats_of(Percepts(env, "A", ())) == ()
    wire = {"kind": "Beliefs", "env": {"cycle": 4, "sender": "A.inference"},
            "stats": {"A.perception": [2.0, 0], "A.inference": [1.5, 2]}}
    assert list(record_stats(wire, own=True)) == [("A.inference", 4, 1.5, 2)]
    old = {"kind": "ProcessStats", "env": {"cycle": 3}, "process": "A.executive",
           "compute_ms": 0.25, "late": 1}   # a record written before issue 36
    assert list(record_stats(old)) == [("A.executive", 3, 0.25, 1)]


def test_culprit_is_the_first_stage_behind_in_pipeline_order():
    pipe = ["A.perception", "A.inference", "A.executive"]
    assert culprit(pipe, {"A.perception": 7, "A.inference": 6, "A.executive": 6}, 7) == \
        "A.inference"
    assert culprit(pipe, {}, 0) == "A.perception"
    assert culprit(pipe, dict.fromkeys(pipe, 7), 7) == "A.executive"


def test_report_is_clean_only_without_faults():
    assert CycleReport(1, {"A": ()}).clean
    assert not CycleReport(1, {"A": ()}, late=("A.inference",), noop=("A",)).clean


def test_a_joiner_says_whether_an_older_cycle_is_still_to_complete():
    j = Joiner([P, B])
    assert not j.pending_before(5)
    j.add(P, msg(3))
    assert j.pending_before(5) and not j.pending_before(3)
    assert j.add(B, msg(3)) is not None   # complete: no longer pending
    assert not j.pending_before(5)
