"""`teleo check`, `teleo infer`, `teleo step`: the language engine on the command line (thin)."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import click

from agents.lang import (
    Engine,
    EngineState,
    LangError,
    ProgramError,
    load_program,
    parse_percepts,
)
from agents.lang.core.limits import MAX_STATE_CHARS, MAX_STATE_STRING, read_json
from agents.lang.core.outcomes import as_outcomes
from agents.lang.core.terms import sort_key
from agents.lang.loader import read_text
from agents.lang.reading.extend import extend_program
from agents.processes.goal_store import MAX_PRIORITY
from agents.processes.goal_texts import rank_problem
from tools.paths import OutputPath

include_option = click.option("-I", "--include", "includes", multiple=True, type=click.Path(),
                        help="Extra file read into the same program (e.g. concepts a table of "
                             "skills uses). Repeatable.")


def _fail(exc: LangError) -> None:
    """Print a language error to stderr and exit 1."""
    click.echo(str(exc), err=True)
    sys.exit(1)


def _load(path: str, includes: tuple[str, ...]):
    try:
        program = load_program(path, *includes)
    except ProgramError as exc:
        _fail(exc)
    for w in program.warnings:
        click.echo(str(w), err=True)
    return program


def _percepts(path: str):
    try:
        return parse_percepts(read_text(path), source=path)
    except LangError as exc:
        _fail(exc)


def _outcomes(path: str) -> tuple:
    """The outcomes in ``path`` (a JSON list); exits 1 naming the file and the bad item."""
    try:
        data = read_json(read_text(path), path)
        if not isinstance(data, list):
            raise LangError(f"expected a JSON list of outcomes, got {type(data).__name__}")
        found = []
        for i, item in enumerate(data):
            try:
                found += as_outcomes([item])
            except LangError as exc:
                raise LangError(f"item {i}: {exc}") from None
        return tuple(found)
    except ProgramError as exc:
        _fail(exc)
    except LangError as exc:
        _fail(LangError(f"{path}: {exc}"))


def _sorted_beliefs(beliefs) -> list:
    return sorted(beliefs, key=lambda b: (b.pred, [sort_key(a) for a in b.args]))


GOAL_ID = re.compile(r"([A-Za-z][A-Za-z0-9_-]{0,31})=(?=\()")   # 'g1=(...)'


def _goal_id(option: str) -> tuple[str | None, str]:
    """'g1=(clear B):1' -> ('g1', '(clear B):1'): the id the goal had in the run (teleo
    explain --percepts suggests it; a numbering from the program's goals on would not
    match the run's); without 'ID=', (None, option)."""
    found = GOAL_ID.match(option)
    return (found.group(1), option[found.end():]) if found else (None, option)


def _goal_option(option: str) -> tuple[str, int | None]:
    """'(clear B):1' -> ('(clear B)', 1); without ':P' (P an integer) no priority; a priority
    outside 1..MAX_PRIORITY is refused, as `teleo goal post` refuses it."""
    text, sep, prio = option.rpartition(":")
    prio = prio.strip()
    digits = prio[1:] if prio[:1] in "+-" else prio
    if not (sep and text and digits.isascii() and digits.isdigit() and len(digits) <= 18):
        return option, None
    if not 1 <= int(prio) <= MAX_PRIORITY:
        raise click.BadParameter(f"{option!r}: priority {int(prio)} is not in 1..{MAX_PRIORITY}",
                                 param_hint="'--goal'")
    return text, int(prio)


def _ranked(engine: Engine, goal: str, priority: int | None, force: bool) -> None:
    """Refuse, as the goal-entry process does, a priority that ranks a user goal above the
    program's own goals (the laws) unless ``force``."""
    if priority is None or force:
        return
    problem = rank_problem(tuple(str(g.literal) for g in engine.program.goals), priority)
    if problem:
        raise click.BadParameter(f"{goal}: {problem} (--force)", param_hint="'--goal'")


@click.command()
@click.argument("program", type=click.Path())
@click.option("--percepts", "percepts_file", required=True, type=click.Path(),
              help="Percept file: Table 3 s-expressions or JSON neutral lists.")
@include_option
def infer(program: str, percepts_file: str, includes: tuple[str, ...]) -> None:
    """Print every belief PROGRAM infers from the percepts, sorted.

    One s-expression a line."""
    engine = Engine(_load(program, includes))
    for b in _sorted_beliefs(engine.infer(_percepts(percepts_file))):
        click.echo(str(b))


@click.command()
@click.argument("program", type=click.Path())
@click.option("--percepts", "percepts_file", required=True, type=click.Path(),
              help="Percept file: Table 3 s-expressions or JSON neutral lists.")
@click.option("--outcomes", "outcomes_file", type=click.Path(),
              help="The outcomes of the previous cycle's actions: a JSON list of "
                   '{"action": [...], "status": "done"|"failed", "reason": "..."}.')
@click.option("--state", "state_file", type=click.Path(), help="Engine state (JSON) to start from.")
@click.option("--save-state", "save_file", type=OutputPath(), help="Write the next state here.")
@click.option("--goal", "goals", multiple=True,
              help="Add a user goal, e.g. '(package-delivered PACKET2)'; append :P for priority "
                   "P, e.g. '(clear B):1'; put ID= before it for its id in a run, e.g. "
                   "'g2=(clear B):1' (default: numbered on). Repeatable.")
@click.option("--force", is_flag=True,
              help="Accept a --goal priority that ranks it above the program's own goals.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of text.")
@click.option("--mechanism", default="means-ends", show_default=True,
              help="What answers an impasse: means-ends (seed 000) or rogue (seed 003).")
@include_option
def step(program: str, percepts_file: str, outcomes_file: str | None, state_file: str | None,
         save_file: str | None, goals: tuple[str, ...], force: bool, as_json: bool,
         mechanism: str, includes: tuple[str, ...]) -> None:
    """Run one cycle of PROGRAM: beliefs, goals, skill path, actions, why."""
    try:
        engine = Engine(_load(program, includes), solver=mechanism)
    except LangError as exc:
        raise click.ClickException(str(exc)) from None
    percepts = _percepts(percepts_file)
    outcomes = _outcomes(outcomes_file) if outcomes_file else ()
    try:
        state = read_state(state_file) if state_file else engine.initial_state()
        if state_file:
            _check_learned_entries(engine, state, state_file)
        for g in goals:
            goal_id, rest = _goal_id(g)
            text, priority = _goal_option(rest)
            _ranked(engine, text, priority, force)
            state = engine.add_goal(state, text, priority, goal_id)
        result = engine.cycle(state, percepts, outcomes)
    except (LangError, json.JSONDecodeError) as exc:
        where, told = state_file or program, str(exc)
        click.echo(told if told.startswith(f"{where}:") else f"{where}: {told}", err=True)
        sys.exit(1)
    if save_file:
        Path(save_file).write_text(json.dumps(result.state.to_dict(), indent=1) + "\n")
    beliefs = _sorted_beliefs(result.beliefs)
    if as_json:
        click.echo(json.dumps({"beliefs": [b.to_list() for b in beliefs],
                               "decision": result.decision.to_dict(),
                               "state": result.state.to_dict()}, indent=1))
        return
    click.echo("beliefs:")
    for b in beliefs:
        click.echo(f"  {b}")
    click.echo(result.decision.explain())


def _check_learned_entries(engine: Engine, state: EngineState, path: str) -> None:
    """Each learned skill of a state file read against the program on its own, so that a
    bad one is named by the file and its entry (`s.json: learned[2]:1:7: ...`), not as
    `<learned>`; raises LangError."""
    for k, clause in enumerate(state.learned):
        extend_program(engine.program, (clause,), f"{path}: learned[{k}]")


def read_state(path: str) -> EngineState:
    """The engine state ``teleo step --save-state`` wrote to ``path`` (within the bounds of a
    state file: limits.MAX_STATE_CHARS, MAX_STATE_STRING); raises LangError naming the file."""
    text = read_text(path, MAX_STATE_CHARS)
    return EngineState.from_dict(read_json(text, path, MAX_STATE_CHARS, MAX_STATE_STRING))


commands = [infer, step]
