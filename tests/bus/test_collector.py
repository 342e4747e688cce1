"""Garbage collection between cycles (bus/collector.py): the automatic collector is off while a
stage runs; the young generation is collected every tenth cycle, the middle one every 50th,
everything every 1000th, and garbage held in reference cycles is freed within ten cycles."""

from __future__ import annotations

import gc
import weakref

import pytest

from bus.collector import Collector


class Node:
    """An object that can sit in a reference cycle."""

    def __init__(self) -> None:
        self.other: Node | None = None


@pytest.fixture()
def collections():
    """The generations collected while the test runs, in order."""
    seen: list[int] = []

    def note(phase: str, info: dict) -> None:
        if phase == "start":
            seen.append(info["generation"])

    gc.callbacks.append(note)
    yield seen
    gc.callbacks.remove(note)


def test_generations_are_collected_on_their_cycles_and_never_by_themselves(collections):
    collector = Collector()
    try:
        collections.clear()
        for _ in range(1000):
            [object() for _ in range(2000)]   # bursts that would start automatic collections
            [[] for _ in range(2000)]
            collector.after_cycle()
        assert not gc.isenabled()
    finally:
        collector.close()
    assert len(collections) == 100
    assert collections.count(2) == 1 and collections[-1] == 2
    assert collections.count(1) == 1000 // 50 - 1
    assert [i for i, g in enumerate(collections, 1) if g == 1] == list(range(5, 100, 5))


def test_a_reference_cycle_is_freed_within_ten_cycles():
    collector = Collector()
    try:
        a, b = Node(), Node()
        a.other, b.other = b, a
        gone = weakref.ref(a)
        del a, b
        freed_after = None
        for n in range(1, 11):
            collector.after_cycle()
            if gone() is None:
                freed_after = n
                break
    finally:
        collector.close()
    assert freed_after == 10


def test_the_collector_is_given_back_as_it_was():
    gc.enable()
    Collector().close()
    assert gc.isenabled()
    gc.disable()
    try:
        Collector().close()
        assert not gc.isenabled()
    finally:
        gc.enable()


def test_generations_must_nest():
    with pytest.raises(ValueError, match=r"mid \(45\) must be a multiple of young \(10\)"):
        Collector(mid=45)
