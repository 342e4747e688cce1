"""A Blocks World problem (bench/planning/bw_problems.py) as PDDL for the standard four-operator
domain of the IPC-2000 Blocks World, track 1 (pick-up, put-down, stack, unstack; untyped STRIPS),
the domain pyperplan's own blocks benchmarks use. Names go lower case (PDDL readers fold case):
block B7 is b7.

    >>> from bench.planning.bw_problems import Problem
    >>> print(problem_pddl(Problem(3, 1, (("B1", "B2"), ("B3",)), (("B3", "B1", "B2"),))))
    (define (problem bw-3-1)
      (:domain blocks)
      (:objects b1 b2 b3)
      (:init (handempty) (ontable b1) (on b2 b1) (clear b2) (ontable b3) (clear b3))
      (:goal (and (on b2 b1) (on b1 b3))))
    <BLANKLINE>
"""

from __future__ import annotations

from bench.planning.bw_problems import Problem, Towers

DOMAIN = """\
(define (domain blocks)
  (:requirements :strips)
  (:predicates (on ?x ?y) (ontable ?x) (clear ?x) (handempty) (holding ?x))
  (:action pick-up
    :parameters (?x)
    :precondition (and (clear ?x) (ontable ?x) (handempty))
    :effect (and (not (ontable ?x)) (not (clear ?x)) (not (handempty)) (holding ?x)))
  (:action put-down
    :parameters (?x)
    :precondition (holding ?x)
    :effect (and (not (holding ?x)) (clear ?x) (handempty) (ontable ?x)))
  (:action stack
    :parameters (?x ?y)
    :precondition (and (holding ?x) (clear ?y))
    :effect (and (not (holding ?x)) (not (clear ?y)) (clear ?x) (handempty) (on ?x ?y)))
  (:action unstack
    :parameters (?x ?y)
    :precondition (and (on ?x ?y) (clear ?x) (handempty))
    :effect (and (holding ?x) (clear ?y) (not (clear ?x)) (not (handempty))
                 (not (on ?x ?y)))))
"""


def init_facts(towers: Towers) -> list[str]:
    """The state's facts in PDDL: (handempty), then each tower from its base."""
    facts = ["(handempty)"]
    for t in towers:
        facts.append(f"(ontable {t[0].lower()})")
        facts += [f"(on {t[i + 1].lower()} {t[i].lower()})" for i in range(len(t) - 1)]
        facts.append(f"(clear {t[-1].lower()})")
    return facts


def problem_pddl(p: Problem, order: str = "listed") -> str:
    """The problem file: the start state's facts, the goal state's `on` facts in ``order``."""
    objects = " ".join(b.lower() for t in sorted(p.start) for b in t)
    objects = " ".join(sorted(objects.split(), key=lambda b: int(b[1:])))
    goal = " ".join(f"(on {a.lower()} {b.lower()})" for a, b in p.goal(order))
    return (f"(define (problem {p.name})\n  (:domain blocks)\n  (:objects {objects})\n"
            f"  (:init {' '.join(init_facts(p.start))})\n  (:goal (and {goal})))\n")


def plan_steps(lines: list[str]) -> list[tuple[str, ...]]:
    """A pyperplan solution ("(stack b1 b2)" per line) as (operator, BLOCK, ...) tuples with
    the blocks' names as teleo writes them."""
    out = []
    for line in lines:
        words = line.strip().strip("()").split()
        if words:
            out.append((words[0], *(w.upper() for w in words[1:])))
    return out
