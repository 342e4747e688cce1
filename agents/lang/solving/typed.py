"""The effect model the solver orders its choices by, with the objects' types: what
achieving a literal undoes is what every primitive skill that *can* achieve it deletes, and a
skill whose typed :percepts do not admit the literal's objects cannot. In logistics,
``(at tru1 apt1)`` is achieved by driving, not by unloading (tru1 is no package), so it undoes
``(at tru1 pos1)``: loading a package at pos1 comes before driving the truck to where it is
unloaded. Without the types, the skills that unload a package have nothing in common with
driving, and nothing was predicted undone.

A type is a :percepts pattern whose attributes are all constants (``(object ?truck type
truck)``); the objects each admits are read from the percepts of the situation, and the
predictions are kept while they stay the same. Pure."""

from __future__ import annotations

from itertools import islice

from ..core.matcher import solve
from ..core.program import Program
from ..core.terms import Literal, PerceptPattern, Var
from ..execution.effects import Effects
from .relaxed import MAX_DOMAIN, InferredEffects


class TypedEffects(InferredEffects):
    """InferredEffects whose ``_admits`` leaves out the skills whose typed :percepts do
    not admit the objects of the literal; ``see`` gives it the situation's objects."""

    def __init__(self, program: Program, base: Effects) -> None:
        super().__init__(program, base)
        self.patterns = sorted({(p.type, p.attrs) for s in program.skills
                                if s.kind == "primitive" for p in s.percepts
                                if p.attrs and isinstance(p.id, Var)
                                and not any(isinstance(t, Var) for _, t in p.attrs)}, key=str)
        self.admits: dict[tuple, frozenset] = {}

    def see(self, pidx, store) -> None:
        """Read which objects each type admits this cycle; forget the predictions when that
        changed."""
        admits = {}
        for kind, attrs in self.patterns:
            x = Var("x")
            admits[(kind, attrs)] = frozenset(
                b[x] for b in islice(solve([PerceptPattern(kind, x, attrs)], {}, pidx, store),
                                     MAX_DOMAIN) if x in b)
        if admits != self.admits:
            self.admits = admits
            self._undoes.clear()
            self._achieved.clear()
            self._actions.clear()
            self._inferred.clear()

    def undoes(self, e: Literal) -> tuple[Literal, ...]:
        hit = self._inferred.get(e)
        if hit is None:
            hit = tuple(dict.fromkeys((*Effects.undoes(self, e), *self._implied(e))))
            if len(self._inferred) < MAX_DOMAIN:
                self._inferred[e] = hit
        return hit

    def _admits(self, s, b: dict) -> bool:
        """Whether skill ``s``'s typed :percepts admit the objects ``b`` binds."""
        for p in s.percepts:
            ids = self.admits.get((p.type, p.attrs))
            if ids is not None and isinstance(p.id, Var) and p.id in b and \
                    b[p.id] not in ids:
                return False
        return True
