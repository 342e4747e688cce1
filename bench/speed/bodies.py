"""Benchmark: the cost per cycle of the SCS body interpreter (seed 002), against an equivalent
ordinary skill program measured in the same run.

Each row is one executive decision (Engine.decide: the goal walk, path finding and, for
bodies, the threads; inference is done once outside the timing, the percepts do not change)
with every action reported done the next cycle. N goals (done Ti), one per task percept; a
(resources ...) section lets all N act in the same cycle (N concurrent threads).
  depth 1: body (repeat (*a ?x) (*b ?x))           vs a primitive skill (*a ?x)
  depth 5: five nested constructs around the same  vs a chain of five skills, each with one
           two actions (do* repeat do-any do-first    subgoal, down to the primitive skill
           do)
  waits:   the threads of the last half of the      vs a skill that can start for the first
           goals stand at a (wait ...) point, the     half only: the first goal without one
           others act                                 is in impasse and blocks those after it
Prints the median ms per cycle of each and the ratio body / skills. Times are this process's
CPU time (time.process_time), so that other jobs on a shared machine do not count.
Run: .venv/bin/python bench/speed/bodies.py [--cycles N]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from agents.lang import Engine, Percept, load_program_text  # noqa: E402
from agents.lang.core.store import PerceptIndex  # noqa: E402

COMMON = """(concepts
  ((done ?x) :percepts ((finished ?x)))
  ((go ?x) :percepts ((task ?x ready T)))
  ((l1 ?x) :percepts ((never ?x))) ((l2 ?x) :percepts ((never ?x)))
  ((l3 ?x) :percepts ((never ?x))) ((l4 ?x) :percepts ((never ?x))))
(resources (*a) (*b))
"""

BODIES = {
    "depth 1": "(repeat (*a ?x) (*b ?x))",
    "depth 5": "(do* (repeat (do-any (do-first (((task-of ?x)) (do (*a ?x) (*b ?x)))))))",
    "waits": "(repeat (*a ?x) (wait (go ?x)) (*b ?x))",
}


def body_program(case: str) -> str:
    extra = "(concepts ((task-of ?x) :percepts ((task ?x))))" if case == "depth 5" else ""
    return COMMON + extra + (f"(skills ((done ?x) :percepts ((task ?x)) "
                             f":body {BODIES[case]}))")


def skill_program(case: str) -> str:
    if case == "depth 5":
        chain = ["((done ?x) :percepts ((task ?x)) :subgoals ((l1 ?x)))"]
        chain += [f"((l{i} ?x) :percepts ((task ?x)) :subgoals ((l{i + 1} ?x)))"
                  for i in range(1, 4)]
        chain.append("((l4 ?x) :percepts ((task ?x)) :actions ((*a ?x)))")
        return COMMON + "(skills " + " ".join(chain) + ")"
    start = ":start ((go ?x))" if case == "waits" else ""
    return COMMON + f"(skills ((done ?x) :percepts ((task ?x)) {start} :actions ((*a ?x))))"


def percepts(n: int) -> list[list]:
    """N tasks; the first half (rounded up) ready."""
    return [["task", f"T{i}", "ready", "T" if i < (n + 1) // 2 else "NIL"] for i in range(n)]


def per_cycle(text: str, n: int, cycles: int) -> tuple[float, int]:
    """Median ms of one decision with N goals, and the actions of the last cycle."""
    engine = Engine(load_program_text(text, "bench.tlp"))
    state = engine.initial_state()
    for i in range(n):
        state = engine.add_goal(state, f"(done T{i})", goal_id=f"g{i}")
    index = PerceptIndex([Percept.from_list(p) for p in percepts(n)])
    beliefs = engine.infer(index)
    outcomes: list = []
    times = []
    actions = 0
    for _ in range(cycles):
        t0 = time.process_time()
        decision, state = engine.decide(state, index, beliefs, outcomes)
        times.append((time.process_time() - t0) * 1e3)
        acts = [a.to_list() for a in decision.actions]
        outcomes = [{"action": a, "status": "done", "reason": ""} for a in acts]
        actions = len(acts)
    return statistics.median(times[cycles // 5:]), actions


def main(cycles: int = 60) -> None:
    print("| case | goals | actions/cycle | bodies ms/cycle | skills ms/cycle | ratio |")
    print("|---|---:|---:|---:|---:|---:|")
    for case in BODIES:
        for n in (1, 100):
            body_ms, body_acts = per_cycle(body_program(case), n, cycles)
            skill_ms, _ = per_cycle(skill_program(case), n, cycles)
            print(f"| {case} | {n} | {body_acts} | {body_ms:.3f} | {skill_ms:.3f} | "
                  f"{body_ms / skill_ms:.2f} |")


def _count(text: str) -> int:
    """A count >= 1, else a usage error."""
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a count >= 1, got {text!r}")
    return int(text)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cycles", type=_count, metavar="N", default=60,
                        help="cycles timed per case (default 60)")
    main(parser.parse_args().cycles)
