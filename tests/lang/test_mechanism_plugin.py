"""A fourth mechanism needs no kernel edit (issue 26): a toy one, registered through the
registry's public API (``mechanisms=(*MECHANISMS, Toy())``), reads its own program section
with file:line:col errors, keeps a state slot that round-trips through to_dict/from_dict,
answers impasses by name and shows its part of the decision and the explanation. Plus the
contract every registered mechanism keeps. docs/architecture.md, "How do I add a mechanism",
walks through this file."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import pytest

from agents.lang import (
    Engine,
    EngineState,
    GoalStatus,
    LangError,
    ProgramError,
    load_program_text,
)
from agents.lang.core.mechanism import Mechanism, slot_kinds
from agents.lang.core.sexpr import Atom, SList, to_text
from agents.lang.core.terms import Loc
from agents.lang.execution.executive import Impasse, ImpasseHandler
from agents.lang.registry import MECHANISMS
from tools.records.mechanism_reports import (
    REPORTS,
    AgentRecord,
    Report,
    summary_lines,
    summary_sections,
)

# -- the toy mechanism: counts the impasses of its agent, gives up after (toy (give-up-after N))


@dataclass(frozen=True, slots=True)
class ToyState:
    """The toy's slot of EngineState ("toy" in the state file)."""

    impasses: int = 0

    def to_dict(self) -> dict[str, Any]:
        return {"impasses": self.impasses}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> ToyState:
        return cls(int(d.get("impasses", 0)))


@dataclass(frozen=True, slots=True)
class GiveUpAfter:
    """One item of a (toy ...) section: ``define``/``check`` are called by the checks."""

    after: int
    loc: Loc

    def define(self, checker: Any) -> None:
        pass   # the toy defines no predicate

    def check(self, checker: Any) -> None:
        if self.after < 1:
            checker.err(self.loc, f"(give-up-after {self.after}): give at least 1")


def toy_section(p: Any, node: SList) -> None:
    """``(toy (give-up-after N))``: read through the program parser, errors at file:line:col."""
    for item in node.items[1:]:
        if not (isinstance(item, SList) and len(item.items) == 2
                and isinstance(item.items[0], Atom) and item.items[0].value == "give-up-after"
                and isinstance(item.items[1], Atom) and isinstance(item.items[1].value, int)):
            p.err(item, f"expected (give-up-after N) in (toy ...), got {to_text(item)}")
            continue
        p.parts.sections.setdefault("toy", []).append(
            GiveUpAfter(item.items[1].value, p.loc(item)))


@dataclass(frozen=True, slots=True)
class ToySection:
    """The toy's part of a decision (its to_dict in the decision, its lines in explain)."""

    impasses: int
    name: str = "toy"

    def to_dict(self) -> dict[str, Any]:
        return {"impasses": self.impasses}

    def lines(self) -> list[str]:
        return [f"toy: impasse {self.impasses}"]


class ToyHandler(ImpasseHandler):
    """The toy's impasse handler (Engine(solver="toy"))."""

    def solve(self, finder: Any, walk: Any, entry: Any, unsatisfied: list) -> Impasse:
        n = walk.current("toy").impasses + 1
        walk.updates["toy"] = ToyState(n)
        walk.sections.append(ToySection(n))
        limit = walk.program.sections.get("toy", ())
        if limit and n >= limit[0].after:
            return Impasse(failed=f"the toy gave up after {n} impasses")
        return Impasse(note=f"the toy counted impasse {n}")


@dataclass(frozen=True)
class Toy(Mechanism):
    name: str = "toy"
    slot: str = "toy"
    state_type: type | None = ToyState

    def sections(self) -> dict[str, Any]:
        return {"toy": toy_section}

    def impasse_handlers(self) -> dict[str, Any]:
        return {"toy": ToyHandler}

WITH_TOY = (*MECHANISMS, Toy())


def toy_entry(agent: AgentRecord) -> dict[str, Any] | None:
    toy = agent.state.get("toy")
    return {"impasses": toy["impasses"]} if toy else None


def toy_lines(name: str, entry: dict[str, Any]) -> list[str]:
    return [f"  {name}: toy impasses {entry['impasses']}"]


TOY_REPORT = Report("toy", 3, toy_entry, toy_lines)   # its part of the run summary (tools')
WITH_TOY_REPORT = (*REPORTS, TOY_REPORT)
PROGRAM = """(concepts
  ((lit ?l) :percepts ((lamp ?l on T))))
(goals (lit L1))
(toy (give-up-after 2))
"""
DARK = [["lamp", "L1", "on", "F"]]


# -- the toy at work -------------------------------------------------------------------------

def test_a_toy_mechanism_runs_without_a_kernel_edit() -> None:
    program = load_program_text(PROGRAM, "toy.tlp", mechanisms=WITH_TOY)
    assert program.sections["toy"][0].after == 2
    engine = Engine(program, solver="toy")
    state = engine.initial_state()
    assert state.toy == ToyState()
    first = engine.cycle(state, DARK)
    assert first.decision.status_of("p1") is GoalStatus.IMPASSE
    assert first.decision.section("toy").to_dict() == {"impasses": 1}
    assert first.decision.to_dict()["toy"] == {"impasses": 1}
    assert "toy: impasse 1" in first.decision.explain()
    second = engine.cycle(first.state, DARK)
    assert second.decision.status_of("p1") is GoalStatus.FAILED
    assert second.state.toy == ToyState(2)
    assert second.state.failure_of("p1") == "the toy gave up after 2 impasses"


def test_a_solver_is_an_impasse_handler_and_none_leaves_the_impasse() -> None:
    """Every hook of the base class is a no-op: ``solver=None`` is the base class itself (the
    goal stays in impasse); an object with the hooks is adopted; anything else is refused,
    naming it."""
    program = load_program_text(PROGRAM, "toy.tlp", mechanisms=WITH_TOY)
    engine = Engine(program, solver=None)
    assert type(engine.solver) is ImpasseHandler
    first = engine.cycle(engine.initial_state(), DARK)
    assert first.decision.status_of("p1") is GoalStatus.IMPASSE
    assert engine.cycle(first.state, DARK).decision.status_of("p1") is GoalStatus.IMPASSE

    class Duck:   # the duck-typed protocol of earlier releases: adopted, its hook called
        calls = 0

        def solve(self, finder: Any, walk: Any, entry: Any, unsatisfied: list) -> Impasse:
            Duck.calls += 1
            return Impasse()

    ducked = Engine(program, solver=Duck())
    assert isinstance(ducked.solver, ImpasseHandler)
    assert ducked.cycle(ducked.initial_state(), DARK).decision.status_of("p1") \
        is GoalStatus.IMPASSE and Duck.calls == 1

    class NoHandler:
        pass

    with pytest.raises(LangError, match=r"Engine: solver must be a name \(.*toy.*\), an "
                                        r"ImpasseHandler or None, got NoHandler"):
        Engine(program, solver=NoHandler())


def test_the_toy_slot_round_trips_through_the_state_file() -> None:
    engine = Engine(load_program_text(PROGRAM, "toy.tlp", mechanisms=WITH_TOY), solver="toy")
    state = engine.cycle(engine.initial_state(), DARK).state
    d = state.to_dict()
    assert d["toy"] == {"impasses": 1}
    assert list(d)[-2:] == ["toy", "loops"]   # after the registered slots, as ever
    back = EngineState.from_dict(d, slot_kinds(WITH_TOY))
    assert back == state and back.toy == ToyState(1)


def test_the_toy_has_its_entry_and_lines_in_the_run_summary() -> None:
    engine = Engine(load_program_text(PROGRAM, "toy.tlp", mechanisms=WITH_TOY), solver="toy")
    state = engine.cycle(engine.initial_state(), DARK).state
    agents = {"ME": AgentRecord(state=state.to_dict()), "YOU": AgentRecord()}
    summary = summary_sections(agents, WITH_TOY_REPORT)
    assert list(summary) == ["learned", "bodies", "planner", "toy"]
    assert summary["toy"] == {"ME": {"impasses": 1}}
    assert summary["learned"] == summary["bodies"] == summary["planner"] == {}
    assert summary_lines(summary, WITH_TOY_REPORT) == ["  ME: toy impasses 1"]
    assert "toy" not in summary_sections(agents)


def test_the_toy_section_reports_file_line_col() -> None:
    with pytest.raises(ProgramError) as err:
        load_program_text(PROGRAM.replace("(give-up-after 2)", "(give-up-after 2)\n  (later)"),
                          "toy.tlp", mechanisms=WITH_TOY)
    assert "toy.tlp:5:3: expected (give-up-after N) in (toy ...), got (later)" \
        in str(err.value)
    with pytest.raises(ProgramError, match=r"toy.tlp:4:6: \(give-up-after 0\)"):
        load_program_text(PROGRAM.replace("after 2", "after 0"), "toy.tlp", mechanisms=WITH_TOY)


def test_without_the_toy_its_section_is_unknown_and_nothing_else_changed() -> None:
    with pytest.raises(ProgramError, match="unknown section 'toy'"):
        load_program_text(PROGRAM, "toy.tlp")
    assert "toy" not in EngineState().to_dict()
    assert "toy" not in {m.name for m in MECHANISMS}


# -- the contract of every registered mechanism ----------------------------------------------

@pytest.mark.parametrize("mechanism", [*MECHANISMS, Toy()], ids=lambda m: m.name)
def test_each_mechanism_implements_the_protocol(mechanism: Mechanism) -> None:
    assert isinstance(mechanism, Mechanism) and mechanism.name
    assert dataclasses.is_dataclass(mechanism)
    with pytest.raises(dataclasses.FrozenInstanceError):
        mechanism.name = "other"  # type: ignore[misc]
    assert all(callable(h) for h in mechanism.sections().values())
    assert all(isinstance(f(), ImpasseHandler) for f in mechanism.impasse_handlers().values())
    assert all(hasattr(r, "expand") for r in mechanism.runners().values())
    if mechanism.slot:
        empty = mechanism.state_type()
        assert mechanism.state_type.from_dict(empty.to_dict()) == empty
        assert hash(empty) is not None   # frozen: an EngineState stays hashable
    assert mechanism.memory(EngineState()) == {}


def test_mechanisms_are_unique_by_name_slot_section_and_handler() -> None:
    for key in (lambda m: [m.name], lambda m: [m.slot] if m.slot else [],
                lambda m: list(m.sections()), lambda m: list(m.impasse_handlers())):
        names = [k for m in MECHANISMS for k in key(m)]
        assert len(names) == len(set(names)), names
    assert sum(m.reads_body() for m in MECHANISMS) <= 1
    assert [k for k, _ in slot_kinds(MECHANISMS)] == ["solver", "scs", "planner"]
