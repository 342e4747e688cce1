"""SCS skill bodies as a mechanism (agents/lang/core/mechanism.py; seed 002): it reads, checks and
runs a skill's ``:body``, keeps its threads, choices and world model in the "scs" slot of
EngineState, adds the world model to inference, and sends that state out with the actions as
the agent memory (docs/bus.md, "Agent memory")."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from ..core.mechanism import Mechanism, SkillMap
from .carry import carried
from .checks import BodyChecks, known_actions, model_facts
from .fitting import check_fits, check_model, model_arity
from .reader import BodyReader
from .runner import ScsBody
from .state import ScsState, from_memory, model_of, to_memory
from .syntax import Act, Atomic, walk_steps


@dataclass(frozen=True)
class Scs(Mechanism):
    """SCS bodies: the ``body`` kind of skill, its state in ``state.scs``."""

    name: str = "scs"
    slot: str = "scs"
    state_type: type | None = ScsState

    def reads_body(self) -> bool:
        return True

    def read_body(self, parser: Any, node: Any) -> Any:
        return BodyReader(parser).step(node)

    def body_checks(self, checker: Any, skills: list, resources: dict | None) -> Any:
        return BodyChecks(checker, skills, known_actions(resources))

    def body_actions(self, body: Any) -> Iterable:
        """The atomic actions of a body (seed 002)."""
        out: list = []
        for _, step in walk_steps(body):
            steps = step.steps if isinstance(step, Atomic) else (step,)
            out.extend(x.action for x in steps if isinstance(x, Act))
        return out

    def asserted(self, skills: Iterable) -> list:
        """The world model's facts that bodies assert or retract (seed 002)."""
        return model_facts(skills)

    def runners(self) -> dict[str, Any]:
        return {"body": ScsBody()}

    def facts(self, state: Any) -> tuple:
        return state.scs.model

    def carry(self, value: Any, skills: SkillMap) -> tuple[Any, tuple[str, ...]]:
        """Threads and do-best records of the skills still in the new program (renumbered);
        the world model and the tally as they were."""
        return carried(value, skills.numbers, skills.names)

    def model_reader(self, program: Any) -> Callable[[Iterable], tuple]:
        arity = model_arity(program)
        return lambda model: check_model(model_of(model), arity)

    def intention(self, state: Any) -> tuple:
        return (state.scs.threads, state.scs.choices)

    def memory(self, state: Any) -> dict[str, Any]:
        return to_memory(state.scs) if state.scs != ScsState() else {}

    def remember(self, memory: dict[str, Any], program: Any) -> Any:
        return check_fits(from_memory(memory), program)
