"""`teleo check FILE...`: check programs, files of learned skills and scenarios, each by what
it is, without running anything.

A scenario (a `.toml` file, or text that starts as TOML does: a `[table]` header or a
`key = value` line) is checked fully by tools/commands/scenario_check.py: its world table against
its domain, every agent's program, every scripted goal against its agent's program and the
priority rule, every scripted event's kind. A file of learned skills is checked against the
program named before it. Anything else is read as a program. `--json` prints one object
for scripts: {"ok": bool, "files": [{"file", "kind", "ok", "errors", "warnings", ...}]}.
"""

from __future__ import annotations

import json
import re
import sys
from typing import Any

import click

from agents.lang import Diagnostic, ProgramError, load_program
from agents.lang.loader import read_text
from agents.lang.registry import is_learned_text, program_named, read_learned
from tools.commands.examples import scenario_path
from tools.commands.lang import include_option
from tools.commands.scenario_check import override_option
from tools.records.tree import shown_path

# The first line that is not blank nor a comment, as TOML starts: [table], [[array]], key =
_TOML_START = re.compile(r"\s*(\[\[?\s*[A-Za-z0-9_\"'.-]+\s*\]\]?|[A-Za-z0-9_\"'.-]+\s*=)")


def is_scenario(path: str) -> bool:
    """Whether ``path`` is a scenario: a .toml name, or text that begins as TOML does
    (programs begin with `(` or a `;` comment)."""
    if path.endswith(".toml"):
        return True
    try:
        text = read_text(path)
    except ProgramError:
        return False
    for line in text.splitlines():
        if line.strip() and not line.lstrip().startswith("#"):
            return bool(_TOML_START.match(line))
    return False


def _diag(d: Diagnostic) -> dict[str, Any]:
    return {"file": d.source, "line": d.line, "col": d.col, "message": d.message}


def _program(path: str, includes: tuple[str, ...]) -> tuple[dict[str, Any], Any]:
    try:
        program = load_program(path, *includes)
    except ProgramError as exc:
        return {"file": path, "kind": "program", "ok": False,
                "errors": [_diag(d) for d in exc.errors],
                "warnings": [_diag(d) for d in exc.diagnostics if d.severity != "error"]}, None
    n_concepts = sum(len(c) for c in program.concepts.values())
    return {"file": path, "kind": "program", "ok": True, "errors": [],
            "warnings": [_diag(w) for w in program.warnings], "concepts": n_concepts,
            "skills": len(program.skills), "goals": len(program.goals)}, program


def _learned(path: str, program: Any, includes: tuple[str, ...]) -> dict[str, Any]:
    """A learned file against ``program`` (the program named before it), else against the
    one its first line names."""
    result = {"file": path, "kind": "learned", "ok": False, "warnings": []}
    try:
        text = read_text(path)
        if program is None:
            program = _its_program(path, text, includes)
        clauses = read_learned(program, text, path)
    except ProgramError as exc:
        return {**result, "errors": [_diag(d) for d in exc.errors]}
    return {**result, "ok": True, "errors": [], "skills": len(clauses),
            "program": program.sources[0]}


def _its_program(path: str, text: str, includes: tuple[str, ...]) -> Any:
    """The program a learned file names in its first line, loaded; ProgramError (at the
    file's first line) when it names none, or one that does not load."""
    named = program_named(text)
    if not named:
        raise ProgramError([Diagnostic(path, 1, 1, "a file of learned skills that names no "
                                       "program: name the program it was learned with before "
                                       "it (teleo check PROGRAM LEARNED)")])
    try:
        return load_program(named, *includes)
    except ProgramError as exc:
        raise ProgramError([Diagnostic(path, 1, 1, f"learned with {named} (its first line), "
                                       f"which does not load: {exc.errors[0]}; name the "
                                       f"program before it (teleo check PROGRAM LEARNED)")]) \
            from None


def _scenario(path: str, overrides: tuple[str, ...]) -> dict[str, Any]:
    from tools.commands.scenario_check import goal_warnings, load_checked
    from world.run_scenario import ScenarioError

    result = {"file": path, "kind": "scenario", "ok": False, "warnings": [],
              "overrides": list(overrides)}
    try:
        scenario, programs = load_checked(path, overrides)
    except ScenarioError as exc:
        return {**result, "errors": [{"file": path, "line": 0, "col": 0, "message": e}
                                     for e in exc.errors]}
    return {**result, "ok": True, "errors": [], "domain": scenario.domain,
            "agents": {a.id: str(a.program) for a in scenario.agents},
            "goals": len(scenario.goals), "events": len(scenario.events),
            "warnings": [_diag(w) for p in programs.values() for w in p.warnings]
            + [{"file": path, "line": 0, "col": 0, "message": w}
               for w in goal_warnings(scenario)]
            + _instance_warnings(path, scenario, programs)}


def _instance_warnings(path: str, scenario: Any, programs: dict) -> list[dict[str, Any]]:
    """A warning for each goal, the scenario's [[goals]] and its agents' programs' (goals
    ...), whose instances in the world as the scenario starts include one that no skill or
    concept can make true (agents/processes/goal_warnings.py)."""
    from agents.processes.goal_warnings import engine_warner

    warn = engine_warner(scenario, programs)
    out = [(f"[[goals]] #{k + 1}", g.agent, g.goal) for k, g in enumerate(scenario.goals)
           if g.op == "post" and g.goal]
    out += [(f"agent {a}'s program goal p{k + 1}", a, str(g.literal))
            for a, p in programs.items() for k, g in enumerate(p.goals)]
    return [{"file": path, "line": 0, "col": 0, "message": f"{where}: {line}"}
            for where, agent, goal in out if (line := warn(agent, goal))]


def _is_learned(path: str) -> bool:
    try:
        return is_learned_text(read_text(path))
    except ProgramError:
        return False


def _echo(result: dict[str, Any]) -> None:
    """One file's result for a person: errors and warnings on stderr, the verdict."""
    path = result["file"]
    for item in result["errors"] + result["warnings"]:
        where = f"{item['file']}:{item['line']}:{item['col']}: " if item["line"] else \
            "" if item["message"].startswith(f"{item['file']}:") else \
            f"{item['file']}: "  # the whole file (it cannot be read, say)
        tag = "warning: " if item in result["warnings"] else ""
        click.echo(f"{where}{tag}{item['message']}", err=True)
    if not result["ok"]:
        n = len(result["errors"])
        if result["kind"] == "program" or n > 1:
            click.echo(f"{path}: {n} error{'s' if n != 1 else ''}", err=True)
        return
    if result["kind"] == "program":
        click.echo(f"{path}: ok ({result['concepts']} concepts, {result['skills']} skills, "
                   f"{result['goals']} goals)")
    elif result["kind"] == "learned":
        click.echo(f"{path}: ok ({result['skills']} learned skills for {result['program']})")
    else:
        agents = ", ".join(f"{a} ({shown_path(p)})" for a, p in result["agents"].items())
        changed = f"; --set {', '.join(result['overrides'])}" if result["overrides"] else ""
        click.echo(f"{path}: ok (scenario, {result['domain']} world; agents {agents}; "
                   f"{result['goals']} scripted goals, {result['events']} events{changed})")


@click.command()
@click.argument("files", metavar="FILE...", nargs=-1, required=True, type=click.Path())
@include_option
@override_option
@click.option("--json", "as_json", is_flag=True,
              help="Print one JSON object (ok, and each file's errors and warnings).")
def check(files: tuple[str, ...], includes: tuple[str, ...], overrides: tuple[str, ...],
          as_json: bool) -> None:
    """Check programs, learned skills and scenarios without running them.

    Exit 0 when all are valid, 1 with every error otherwise. A scenario (.toml) is checked
    fully: world table, programs, scripted goals and events. A file of learned skills is
    checked against the program named before it (PROGRAM LEARNED), else against the one its
    first line names. A shipped scenario may be named without a path (blocks_figure3).
    `--set KEY=VALUE` changes a field of every scenario checked, as `teleo launch --set`
    does."""
    results, program = [], None
    files = tuple(p if p.endswith(".tlp") else scenario_path(p) for p in files)
    kinds = ["learned" if _is_learned(p) else "scenario" if is_scenario(p) else "program"
             for p in files]
    if overrides and "scenario" not in kinds:
        raise click.UsageError("--set changes a scenario's fields: name a scenario (.toml)")
    for path, kind in zip(files, kinds, strict=True):
        if kind == "learned":
            results.append(_learned(path, program, includes))
        elif kind == "scenario":
            results.append(_scenario(path, overrides))
        else:
            result, program = _program(path, includes)
            results.append(result)
    ok = all(r["ok"] for r in results)
    if as_json:
        click.echo(json.dumps({"ok": ok, "files": results}, indent=1))
    else:
        for result in results:
            _echo(result)
    sys.exit(0 if ok else 1)


program_checked = _program   # `teleo program load` checks a file as this command does
echo_checked = _echo

commands = [check]

