"""bench/office/office.py's yardstick (bench/office/office_sets.py): its branch-and-bound optimum is
the least travel over every order of the visits that keeps each request's order, its arrival
(the robot idles only when no arrived request has a visit left) and the capacity, checked
here against plain enumeration of every order on random small sets; first-come-first-served
is such an order; the relaxed optimum (arrivals ignored) is never above it."""

from __future__ import annotations

from itertools import permutations

from hypothesis import given, settings
from hypothesis import strategies as st

from bench.office.office_sets import (
    CONFIG,
    CYCLES_PER_M,
    PEOPLE,
    ROOMS,
    STEP_CYCLES,
    Request,
    RequestSet,
    clairvoyant,
    fcfs,
    metric,
    optimal,
    random_set,
)


def enumerate_orders(s: RequestSet) -> float:
    """The least travel of a feasible order, by trying every order of the visits."""
    m = metric()
    plans = [r.visits() for r in s.requests]
    tokens = [k for k, p in enumerate(plans) for _ in p]
    best = float("inf")
    for order in set(permutations(tokens)):
        idx, here, now, travel, load, ok = [0] * len(plans), s.start, 0.0, 0.0, 0, True
        for k in order:
            left = [j for j in range(len(plans)) if idx[j] < len(plans[j])]
            if s.requests[k].arrival > now:
                if any(s.requests[j].arrival <= now for j in left):
                    ok = False        # it would idle with work to do
                    break
                now = min(s.requests[j].arrival for j in left)
                if s.requests[k].arrival > now:
                    ok = False        # another request arrives first: it must be served
                    break
            load += (1 if idx[k] == 0 else -1) if len(plans[k]) == 2 else 0
            if load > CONFIG.capacity:
                ok = False
                break
            leg = m.between(here, plans[k][idx[k]])
            steps = 2 if len(plans[k]) == 1 else 1
            now += leg * CYCLES_PER_M + steps * STEP_CYCLES
            travel += leg
            here = plans[k][idx[k]]
            idx[k] += 1
        if ok:
            best = min(best, travel)
    return round(best, 3)


requests = st.builds(
    lambda holder, to, arrival: Request("", "mail", holder, to, arrival),
    st.sampled_from(sorted(PEOPLE)), st.sampled_from([*ROOMS, *sorted(PEOPLE)]),
    st.integers(0, 150)).filter(lambda r: r.to not in (r.holder, PEOPLE[r.holder]))


@settings(max_examples=40, deadline=None)
@given(start=st.sampled_from(ROOMS), drawn=st.lists(requests, min_size=1, max_size=3))
def test_the_optimum_is_the_best_feasible_order(start, drawn):
    first = min(r.arrival for r in drawn)
    reqs = sorted((Request(f"mail-{r.holder}-{k}", "mail", r.holder, r.to,
                           r.arrival - first) for k, r in enumerate(drawn)),
                  key=lambda r: r.arrival)
    s = RequestSet(0, start, tuple(reqs))
    best, proven = optimal(s, metric())
    assert proven
    assert best == enumerate_orders(s)
    assert clairvoyant(s, metric()) <= best + 1e-6 <= fcfs(s, metric()) + 2e-6


def test_the_sets_are_drawn_from_their_seed():
    a, b = random_set(7), random_set(7)
    assert a == b and random_set(8) != a
    assert 3 <= len(a.requests) <= 8 and a.requests[0].arrival == 0
    assert all(r.to not in (r.holder,) and r.goal.startswith("(delivered ") for r in a.requests)
