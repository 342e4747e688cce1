"""A toy planning domain for the planner's unit tests (pyperplan's dummy task, in teleo's
language): a robot on a line of places A..E fetches things and brings them somewhere.
Places are 10 m apart; the robot perceives where it is, where each thing lies, and the
distance between places and from itself to each place."""

from __future__ import annotations

from agents.lang import Engine, load_program_text
from agents.lang.core.store import PerceptIndex
from agents.lang.engine import as_percepts
from agents.lang.planning.control import Control
from agents.lang.planning.domain import Domain, Metric, with_facts

PLACES = ("A", "B", "C", "D", "E")

TOY = """
(concepts
  ((at ?p) :percepts ((self ?r at ?p)))
  ((has ?x) :percepts ((self ?r) (thing ?x at ?r)))
  ((lies ?x ?p) :percepts ((thing ?x at ?p) (place ?p)))
  ((rich) :percepts ((self ?r money lots))))

(operators
  ((at ?p)
   :operator (walk ?p)
   :percepts ((place ?p))
   :effects ((not (at ?anywhere)))
   :actions ((*walk ?p)))

  ((has ?x)
   :operator (buy ?x)
   :start ((rich))
   :actions ((*buy ?x)))

  ((has ?x)
   :operator (take ?x ?p)
   :percepts ((thing ?x at ?p) (place ?p))
   :start ((at ?p))
   :actions ((*take ?x)))

  ((lies ?x ?p)
   :operator (drop ?x ?p)
   :percepts ((place ?p))
   :start ((has ?x) (at ?p))
   :effects ((not (has ?x)))
   :actions ((*drop ?x))))

(requests
  ((lies ?x ?p) :knowledge ((wanted ?x ?p))))

(control-rules
  (travel :location (at ?place)
          :between (road ?a to ?b length ?d)
          :from-here (place ?place dist ?d)
          :detour 5))
"""
"""The robot is never (rich) here and no operator makes it so: (buy ?x) is an alternative the
back-chainer tries first and gives up (backtracking)."""


def program(extra: str = ""):
    return load_program_text(TOY + extra, "toy.tlp")


def percepts(at: str = "A", things: dict[str, str] | None = None) -> list[list]:
    """The robot at ``at``; each thing where ``things`` says (a place, or "R1": held)."""
    things = {"key": "C", "box": "E"} if things is None else things
    out = [["self", "R1", "at", at]]
    out += [["thing", x, "at", p] for x, p in things.items()]
    here = PLACES.index(at)
    for i, p in enumerate(PLACES):
        out.append(["place", p, "dist", 10.0 * abs(i - here)])
        out += [["road", p, "to", q, "length", 10.0 * abs(i - j)]
                for j, q in enumerate(PLACES) if j > i]
    return out


class World:
    """Beliefs, percept index, domain and metric of one toy situation."""

    def __init__(self, extra: str = "", at: str = "A", things: dict | None = None):
        self.program = program(extra)
        raw = percepts(at, things)
        self.store = Engine(self.program, solver=None).infer(raw).store
        self.pidx = PerceptIndex(as_percepts(raw))
        self.domain = Domain(self.program)
        self.metric = Metric(self.domain.travel, self.pidx)
        self.control = Control(self.domain.rules)

    def base(self, *facts: str):
        return with_facts(self.store, tuple(facts))
