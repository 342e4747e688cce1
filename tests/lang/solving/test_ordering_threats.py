"""The agenda's threat check by index (ordering.py, ``Threats``) orders a conjunction
exactly as comparing every conjunct with every need of the others' plans did: the pairwise
agenda is kept here as the reference, and both run on random STRIPS domains (the pddl world's
programs: stated effects, negative preconditions) and on random Blocks World situations (the
seed's program: effects read from its concept definitions)."""

from __future__ import annotations

import random

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from agents.lang import Engine, as_percepts, load_program, load_program_text
from agents.lang.core.store import PerceptIndex, store_of
from agents.lang.execution.effects import Effects
from agents.lang.solving.landmarks import key, landmarks, needs, one_step, threatens
from agents.lang.solving.landmarks import plan_depth as _depth
from agents.lang.solving.ordering import agenda
from agents.lang.solving.state import condition, literal, pushable
from agents.lang.solving.task import Task
from agents.lang.solving.typed import TypedEffects
from world.pddl.perception import perceive
from world.pddl.program import program_text
from world.pddl.task import DomainModel, Lit, Operator
from world.pddl.task import Task as PddlTask

from ..conftest import BLOCKS
from ..test_blocks import percepts as blocks_percepts
from .blocksworld import on_facts, random_state


def pairwise_agenda(task: Task, conds: tuple[str, ...], current: str = "",
                    above: tuple[str, ...] = ()) -> list[str]:
    """The agenda as it was before the index (ordering.py at aa1ed15), uncached."""
    unsat = [c for c in conds if pushable(condition(c)) and not task.holds(c)]
    plans = {h: needs(task, h, above) for h in unsat}
    free, promote = [], []
    later = {h for h in unsat if any(g != h and threatens(task, g, literal(h), "")
                                     for g in unsat)}
    for g in unsat:
        threats = [(h, need, above) for h in unsat if h != g
                   for need, above in plans[h].items() if threatens(task, g, need, above)
                   and not (h in later and need == literal(h) and not above)]
        if not threats:
            free.append(g)
        elif not any(key(need) in landmarks(task, literal(h)) for h, need, _ in threats):
            promote += [above for _, _, above in threats if above]
    if current and current not in conds:
        current = min((h for h in [*free, *unsat] if literal(current) in plans[h]),
                      key=lambda h: (h not in free, _depth(plans[h], literal(current))),
                      default=current)
    if free:
        now = [g for g in free if one_step(task, g)]
        now += [p for p in dict.fromkeys(promote) if p not in now and one_step(task, p)]
        out = now + [g for g in free if g == current and g not in now] + \
            [g for g in free if g not in now and g != current]
        out = [g for g in out if g not in later] + [g for g in out if g in later]
    elif promote:
        out = list(dict.fromkeys(promote))
    else:
        out = unsat
    return out


def _task(program, raw: list[list]) -> Task:
    index = PerceptIndex(as_percepts(raw))
    store = store_of(Engine(program).infer(index))
    effects = TypedEffects(program, Effects(program))
    effects.see(index, store)
    return Task(program, index, store, effects=effects)


def _both(program, raw: list[list], conds: tuple[str, ...], current: str,
          above: tuple[str, ...]) -> tuple[list[str], list[str]]:
    return (agenda(_task(program, raw), conds, current, above),
            pairwise_agenda(_task(program, raw), conds, current, above))


OBJECTS = ("a", "b", "c", "d")


@st.composite
def strips(draw):
    """A random STRIPS domain (2-4 predicates of arity 1-2, 2-4 operators over ?x ?y, some
    preconditions negated), a state and a goal of 2-10 atoms, and the agenda's ``current``
    and ``above``."""
    preds = [(f"p{k}", draw(st.integers(1, 2))) for k in range(draw(st.integers(2, 4)))]
    params = (("?x", ("obj",)), ("?y", ("obj",)))

    def lits(n_min, n_max, negatable=False):
        out = []
        for _ in range(draw(st.integers(n_min, n_max))):
            p, n = draw(st.sampled_from(preds))
            args = tuple(draw(st.sampled_from(("?x", "?y"))) for _ in range(n))
            out.append(Lit(p, args, negatable and draw(st.booleans())))
        return tuple(dict.fromkeys(out))

    ops = tuple(Operator(f"op{k}", params, lits(1, 3, True), lits(1, 2), lits(0, 2))
                for k in range(draw(st.integers(2, 4))))
    model = DomainModel("random", (("obj", "object"),), (),
                        tuple((p, params[:n]) for p, n in preds), ops)
    atoms = sorted({(p, *(draw(st.sampled_from(OBJECTS)) for _ in range(n)))
                    for p, n in preds for _ in range(draw(st.integers(0, 4)))})
    goal = [(p, *(draw(st.sampled_from(OBJECTS)) for _ in range(n)))
            for p, n in (draw(st.sampled_from(preds)) for _ in range(draw(st.integers(2, 10))))]
    task = PddlTask(model, "r", tuple((o, "obj") for o in OBJECTS), frozenset(atoms),
                    tuple(Lit(g[0], g[1:]) for g in goal))
    program = load_program_text(program_text(model, task))
    raw = perceive({"objects": [[o, ["obj", "object"]] for o in OBJECTS],
                    "atoms": [list(a) for a in atoms]}, "agent")
    conds = tuple("(" + " ".join(g) + ")" for g in goal)
    current = draw(st.sampled_from(("", *conds, "(p0 a)", "(p1 a b)")))
    above = draw(st.sampled_from(((), conds[:1])))
    return program, raw, conds, current, above


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(strips())
def test_the_indexed_agenda_is_the_pairwise_one_on_random_strips_domains(case):
    program, raw, conds, current, above = case
    new, old = _both(program, raw, conds, current, above)
    assert new == old


BLOCKS_PROGRAM = load_program(BLOCKS)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10**6), st.integers(3, 6))
def test_the_indexed_agenda_is_the_pairwise_one_in_blocks_world(seed, n):
    rng = random.Random(seed)
    names = [f"B{k}" for k in range(n)]
    start, goal = random_state(rng, names), random_state(rng, names)
    support = dict(on_facts(start))   # top: what it is on
    support.update({t[0]: "T" for t in start})
    conds = tuple(f"(on {a} {b})" for a, b in on_facts(goal)) + \
        tuple(f"(clear {t[-1]})" for t in goal if rng.random() < 0.5)
    current = rng.choice(["", *conds, f"(clear {names[0]})", f"(holding {names[1]})"])
    new, old = _both(BLOCKS_PROGRAM, blocks_percepts(support), conds, current, ())
    assert new == old


def test_the_reference_is_not_vacuous():
    """The Sussman anomaly: every conjunct threatens the other, and the part of a plan the
    threat is to comes first; both agendas say so."""
    support = {"C": "A", "A": "T", "B": "T"}
    conds = ("(on A B)", "(on B C)")
    new, old = _both(BLOCKS_PROGRAM, blocks_percepts(support), conds, "", ())
    assert new == old == ["(clear A)"]
