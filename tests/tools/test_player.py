"""How `teleo replay` plays a record (tools/records/player.py): messages grouped by cycle in the
record's order, from `--start CYCLE`, again with `--loop`, and, with keys, paused, stepped one
cycle at a time and resumed. The keys here are a scripted sequence of presses (what a
terminal would deliver); tests/e2e/test_replay_alone.py presses them on a real terminal."""

from __future__ import annotations

import threading

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tools.records.player import PAUSE, STEP, NoKeys, Player, cycles_of, from_cycle

CYCLE_RUNS = st.lists(st.tuples(st.integers(min_value=-1, max_value=40),
                                st.integers(min_value=1, max_value=5)), max_size=30)


def items_of(runs: list[tuple[int, int]]) -> list[tuple[str, bytes, int]]:
    out = []
    for n, (cycle, count) in enumerate(runs):
        out += [(f"teleo/r/k{i}", f"{n}.{i}".encode(), cycle) for i in range(count)]
    return out


@given(CYCLE_RUNS)
def test_groups_are_the_record_in_order_cut_where_the_cycle_changes(runs):
    items = items_of(runs)
    groups = cycles_of(items, {c: c * 10**8 for c, _ in runs if c >= 0})
    assert [(k, p) for g in groups for k, p in g.items] == [(k, p) for k, p, _ in items]
    assert all(a.cycle != b.cycle for a, b in zip(groups, groups[1:], strict=False))
    for g in groups:
        if g.cycle >= 0:
            assert g.world_ns == g.cycle * 10**8


@given(CYCLE_RUNS)
def test_pacing_never_runs_back_past_the_first_world_time(runs):
    """A record started mid-run whose first cycles lack their world state (`teleo record`
    joining between a state and its agents' messages): those cycles are paced at the first
    world time the record holds, not at 0, so the play does not wait the run's age first."""
    runs = sorted((c + 4000, n) for c, n in runs if c >= 0)   # a run's cycles, late in it
    times = {c: c * 10**8 for c, _ in runs if c % 3 == 0}    # some cycles lack their state
    groups = cycles_of(items_of(runs), times)
    paced = [g.world_ns for g in groups]
    assert paced == sorted(paced)                             # never back in time
    if times:
        assert paced[0] == times[min(times)]                  # the first known, not 0


def test_a_start_past_the_record_is_refused_with_its_cycles():
    groups = cycles_of(items_of([(0, 2), (1, 2), (2, 2)]), {})
    assert [g.cycle for g in from_cycle(groups, 1)] == [1, 2]
    with pytest.raises(ValueError, match=r"the record holds cycles 0\.\.2, got 3"):
        from_cycle(groups, 3)
    with pytest.raises(ValueError, match="the record holds no cycle, got 0"):
        from_cycle([], 0)


class Presses(NoKeys):
    """Key presses, one per look at the keys (None: nothing pressed that time)."""

    def __init__(self, stop: threading.Event, presses: list[str | None]) -> None:
        super().__init__(stop)
        self.presses = list(presses)

    def poll(self, timeout: float) -> str | None:
        return self.presses.pop(0) if self.presses else None


def player(groups, keys=None, **kwargs) -> tuple[Player, list, list]:
    stop = threading.Event()
    sent, said = [], []

    def send(key: str, payload: bytes) -> None:
        sent.append(payload)

    p = Player(groups, send, 0.0, stop, keys(stop) if keys else NoKeys(stop), said.append,
               **kwargs)
    return p, sent, said


GROUPS = cycles_of(items_of([(0, 3), (1, 3), (2, 3), (3, 3)]), {c: c * 10**8 for c in range(4)})
ALL = [p for g in GROUPS for _, p in g.items]


def test_without_keys_it_plays_everything_once():
    p, sent, said = player(GROUPS)
    assert p.play() == 12 and sent == ALL and p.played_cycles == 4 and said == []


def test_paused_it_sends_nothing_until_stepped_then_one_cycle_a_step():
    presses = [None, None, STEP, None, STEP, PAUSE]
    p, sent, said = player(GROUPS, lambda stop: Presses(stop, presses), paused=True)
    p.play()
    assert sent == ALL  # stepped twice, then played on to the end
    assert said[0].startswith("paused before cycle 0")
    assert said[1:] == ["stepped: cycle 0 sent", "stepped: cycle 1 sent",
                        "playing from cycle 2"]


def test_space_while_playing_pauses_before_the_next_cycle():
    presses = [None, PAUSE, None, STEP, PAUSE]
    p, sent, said = player(GROUPS, lambda stop: Presses(stop, presses))
    p.play()
    assert sent == ALL
    assert said == ["paused before cycle 1 (space: play, s or right arrow: one cycle)",
                    "stepped: cycle 1 sent", "playing from cycle 2"]


def test_a_loop_plays_the_record_again_until_stopped():
    p, sent, said = player(GROUPS, loop=True)
    real_send = p.send

    def send(key: str, payload: bytes) -> None:
        real_send(key, payload)
        if len(sent) == 3 * len(ALL):
            p.stop.set()

    p.send = send
    p.play()
    assert sent == ALL * 3 and said == ["looping: cycle 0 again"] * 2
