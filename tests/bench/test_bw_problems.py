"""The planning bench's problems (bench/planning/bw_problems.py): states drawn uniformly, exactly,
as Slaney and Thiebaux count them; the PDDL it writes (bench/planning/bw_pddl.py) read by pyperplan,
whose A* with LM-cut finds the optimum a breadth-first search finds."""

from __future__ import annotations

import math
import random
from collections import Counter
from fractions import Fraction
from pathlib import Path

import pytest
from pyperplan.heuristics.lm_cut import LmCutHeuristic
from pyperplan.planner import search_plan
from pyperplan.search import astar_search

from bench.planning import bw_problems
from bench.planning.bw_pddl import DOMAIN, plan_steps, problem_pddl
from bench.planning.bw_problems import canonical, g, problem, random_state, states
from bench.planning.bw_strips import replay, shortest_plan


def all_states(blocks: list[str]) -> set[tuple[tuple[str, ...], ...]]:
    """Every state of ``blocks`` by brute force: the last block is a tower of its own or goes
    anywhere into a tower of a state of the others."""
    if not blocks:
        return {()}
    out = set()
    b = blocks[-1]
    for s in all_states(blocks[:-1]):
        out.add(canonical(s + ((b,),)))
        for k, t in enumerate(s):
            for i in range(len(t) + 1):
                out.add(canonical(s[:k] + (t[:i] + (b,) + t[i:],) + s[k + 1:]))
    return out


@pytest.mark.parametrize("n", range(7))
def test_the_count_is_the_number_of_states(n):
    assert states(n) == len(all_states(bw_problems.block_names(n)))
    assert states(3) == 13


class Scripted(random.Random):
    """An rng whose randrange answers are given, to walk every branch of the generator."""

    def __init__(self, answers: list[int]):
        super().__init__(0)
        self.answers, self.asked = list(answers), []

    def randrange(self, stop):  # type: ignore[override]
        self.asked.append(stop)
        return self.answers.pop(0) if self.answers else 0


def exact_distribution(n: int) -> dict:
    """The probability of each state the generator can return, over all its random draws."""
    dist: Counter = Counter()

    def walk(prefix: list[int]) -> None:
        rng = Scripted(prefix)
        state = random_state(n, rng)
        if len(rng.asked) == len(prefix):
            p = Fraction(1)
            for stop in rng.asked:
                p /= stop
            dist[canonical(state)] += p
            return
        for r in range(rng.asked[len(prefix)]):
            walk(prefix + [r])

    walk([])
    return dist


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_every_state_has_exactly_the_same_chance(n):
    dist = exact_distribution(n)
    assert set(dist) == all_states(bw_problems.block_names(n))
    assert set(dist.values()) == {Fraction(1, states(n))}


def test_draws_pass_a_chi_square_test_over_the_13_states_of_3_blocks():
    rng, draws = random.Random(2001), 13 * 800
    seen = Counter(canonical(random_state(3, rng)) for _ in range(draws))
    assert len(seen) == 13
    chi2 = sum((c - draws / 13) ** 2 / (draws / 13) for c in seen.values())
    assert chi2 < 32.91          # the 0.999 quantile of chi-square with 12 degrees of freedom


def test_a_problem_is_its_seed_and_holds_every_block_once_in_start_and_goal():
    for n in (3, 17, 30):
        p = problem(n, 4)
        assert p == problem(n, 4) and p != problem(n, 5)
        for s in (p.start, p.goal_state):
            assert sorted(b for t in s for b in t) == sorted(bw_problems.block_names(n))
        assert g(n, 0) == states(n) and math.log10(states(30)) > 30


def test_goal_orders_list_each_tower_top_down_as_ipc_or_from_its_base():
    p = bw_problems.Problem(4, 0, (("B1", "B2", "B3", "B4"),), (("B4", "B3", "B2"), ("B1",)))
    assert p.goal("listed") == [("B2", "B3"), ("B3", "B4")]
    assert p.goal("bottom-up") == [("B3", "B4"), ("B2", "B3")]


@pytest.mark.parametrize("n,seed", [(3, 1), (4, 2), (5, 3), (5, 4), (6, 1)])
def test_pyperplan_reads_the_pddl_and_a_star_lm_cut_finds_the_bfs_optimum(tmp_path: Path,
                                                                          n, seed):
    p = problem(n, seed)
    domain, task = tmp_path / "domain.pddl", tmp_path / "p.pddl"
    domain.write_text(DOMAIN)
    task.write_text(problem_pddl(p))
    plan = search_plan(str(domain), str(task), astar_search, LmCutHeuristic)
    steps = plan_steps([op.name for op in plan])
    assert not set(p.goal()) - {(f[1], f[2]) for f in replay(p.start, steps) if f[0] == "on"}
    assert len(steps) == len(shortest_plan(p.start, p.goal()))
