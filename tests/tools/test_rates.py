"""The figures of `teleo hz` and `teleo echo --list` (tools/runs/rates.py) on arrivals made up
here: the rate is the messages after the first over the time they took, the period's min, max
and standard deviation are those of the gaps, bytes per second what came after the first over
the same time, and only the last `window` messages count."""

from __future__ import annotations

import math
import statistics

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tools.runs.rates import Meter, hz_line, list_table

GAPS = st.lists(st.integers(min_value=1, max_value=10**9), min_size=1, max_size=200)
SIZES = st.integers(min_value=0, max_value=10**6)


def fed(gaps: list[int], sizes: list[int], window: int = 10_000) -> Meter:
    meter = Meter(window)
    t = 5 * 10**9
    meter.feed(t, sizes[0])
    for gap, size in zip(gaps, sizes[1:], strict=False):
        t += gap
        meter.feed(t, size)
    return meter


@given(GAPS, st.data())
def test_the_figures_are_those_of_the_gaps(gaps, data):
    sizes = data.draw(st.lists(SIZES, min_size=len(gaps) + 1, max_size=len(gaps) + 1))
    f = fed(gaps, sizes).figures()
    periods = [g / 1e9 for g in gaps]
    span = sum(gaps) / 1e9
    assert f.messages == len(gaps) + 1
    assert f.rate == pytest.approx(len(gaps) / span)
    assert f.period_min == pytest.approx(min(periods))
    assert f.period_max == pytest.approx(max(periods))
    assert f.period_std == pytest.approx(statistics.pstdev(periods), abs=1e-9)
    assert f.bytes_per_s == pytest.approx(sum(sizes[1:]) / span)
    assert f.mean_size == pytest.approx(statistics.mean(sizes))


@given(GAPS, st.integers(min_value=2, max_value=50))
def test_only_the_last_window_messages_count(gaps, window):
    sizes = list(range(len(gaps) + 1))
    meter = fed(gaps, sizes, window)
    kept = gaps[-(window - 1):] if len(gaps) >= window else gaps
    f = meter.figures()
    assert meter.count == len(gaps) + 1
    assert f.messages == min(window, len(gaps) + 1)
    assert f.rate == pytest.approx(len(kept) / (sum(kept) / 1e9))
    assert f.period_max == pytest.approx(max(kept) / 1e9)


def test_a_steady_stream_has_its_rate_and_no_spread():
    f = fed([10**8] * 99, [1000] * 100).figures()   # 100 messages 0.1 s apart, 1 kB each
    assert f.rate == pytest.approx(10.0) and f.period_std == pytest.approx(0.0, abs=1e-12)
    assert f.bytes_per_s == pytest.approx(10_000.0)
    line = hz_line("world/state", f, bw=True)
    assert line.startswith("world/state: 10.00 msg/s  period min 0.1000 s  max 0.1000 s  "
                           "std 0.0000 s  window 100")
    assert line.endswith("10.00 kB/s  mean 1.00 kB")
    assert "kB" not in hz_line("world/state", f, bw=False)


def test_one_message_has_no_rate_yet():
    meter = Meter(10)
    meter.feed(1, 300, "WorldState", "world")
    f = meter.figures()
    assert (f.messages, f.rate, f.period_min, f.mean_size) == (1, 0.0, None, 300.0)
    assert hz_line("world/state", f, bw=True) == "world/state: 1 message(s) so far, no rate yet"
    assert all(math.isfinite(v) for v in (f.rate, f.bytes_per_s, f.mean_size))


def test_the_list_names_each_keys_kind_and_publishers():
    state, actions = Meter(10), Meter(10)
    for t in range(5):
        state.feed(t * 10**8, 1000, "WorldState", "world")
        actions.feed(t * 10**8, 100, "Actions", "ME.executive")
    rows = list_table({"world/state": state, "agent/ME/actions": actions})
    assert rows[0].split() == ["KEY", "KIND", "RATE/s", "MEAN", "B", "PUBLISHERS"]
    assert rows[1].split() == ["agent/ME/actions", "Actions", "10.0", "100", "ME.executive"]
    assert rows[2].split() == ["world/state", "WorldState", "10.0", "1000", "world"]


def test_a_window_of_one_is_refused():
    with pytest.raises(ValueError, match="at least 2 messages, got 1"):
        Meter(1)
