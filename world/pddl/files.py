"""A PDDL domain and problem read into plain, frozen data: the STRIPS fragment the pddl world
runs (typing with type hierarchies and `either`, constants, equality, negative preconditions).

Parsing is the `pddl` package's (Apache-2.0; `pip install 'teleo[pddl]'`); this module turns
its objects into ``Task`` and refuses, with one line naming the file, line and column where it
can, whatever the world does not run: a syntax error (what was expected), a requirement or
construct outside the fragment (conditional effects, quantifiers, disjunctions, durative
actions, numeric fluents), a problem naming an undeclared object, type or predicate.

Names are lower-cased (PDDL is case-insensitive); a variable keeps its ``?``.
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

from world.errors import ConfigError
from world.pddl.convert import domain_model, task_of
from world.pddl.costs import NOTE, declares_costs, without_costs
from world.pddl.task import DomainModel, Task, locate, position, uncommented
from world.pddl.type_list import root_alias, single_types

INSTALL = "pip install 'teleo[pddl]'"
SUPPORTED = frozenset({"strips", "typing", "negative-preconditions", "equality",
                       "action-costs"})
SYNTAX_ONLY = frozenset({"adl", "disjunctive-preconditions", "existential-preconditions",
                         "universal-preconditions", "quantified-preconditions"})
"""Requirements that only allow syntax in conditions: a domain that declares one and writes
STRIPS runs (many IPC domains declare :adl and use none of it); the construct itself, where
written, is refused at its place, naming it and its requirement (convert.py). Conditional
effects, durative actions and numeric fluents are refused where declared."""


_PARSERS: list = []   # the library's two parsers, made once per process (each builds its grammar)


def _library():
    """(domain parser, problem parser); ConfigError when the pddl package is missing."""
    if _PARSERS:
        return _PARSERS[0]
    try:
        from pddl.parser.domain import DomainParser
        from pddl.parser.problem import ProblemParser
    except ImportError:
        raise ConfigError(f"the pddl world needs the pddl package: {INSTALL}") from None
    _PARSERS.append((DomainParser(), ProblemParser()))
    return _PARSERS[0]


def reset_parsers() -> None:
    """Drop the parsers made so far (one cut short by a signal mid-parse, as `teleo solve
    --time-limit` does, is left in a broken state); the next load makes new ones."""
    _PARSERS.clear()


def load_domain(path: str | Path, text: str | None = None) -> DomainModel:
    """The domain in ``path`` (or ``text``, read from there); raises ConfigError (one line)
    for anything it cannot run."""
    parse_domain, _ = _library()
    text = _read(path) if text is None else text
    code = uncommented(text)
    _check_requirements(code, path)
    costs = declares_costs(code)
    if costs:   # run with the costs ignored (costs.py), and say so
        code = without_costs(code, path, problem=False)
    code = root_alias(single_types(code))
    for construct, name in (("durative-action", "durative actions (:durative-action)"),
                            ("functions", "numeric fluents (:functions)"),
                            ("derived", "derived predicates (:derived)")):
        m = re.search(rf"\(\s*:{construct}\b", code, re.I)
        if m:
            raise ConfigError(f"{position(path, text, m.start())}: pddl: {name} not "
                              f"supported; the pddl world runs STRIPS with {_fragment()}")
    d = _parsed(parse_domain, path, code)   # comments blanked: positions are the text's
    model = domain_model(d, str(path), text)
    return replace(model, notes=(NOTE,)) if costs else model


def load_task(domain_path: str | Path, problem_path: str | Path,
              texts: tuple[str, str] | None = None) -> Task:
    """The problem in ``problem_path`` of the domain in ``domain_path`` (or ``texts``, the
    two files' text), checked against it."""
    model = load_domain(domain_path, texts[0] if texts else None)
    _, parse_problem = _library()
    text = _read(problem_path) if texts is None else texts[1]
    code = uncommented(text)
    _check_requirements(code, problem_path)
    if model.notes or declares_costs(code):
        code = without_costs(code, problem_path, problem=True)
    p = _parsed(parse_problem, problem_path, code)
    return task_of(model, p, str(problem_path), text)


def _read(path: str | Path) -> str:
    try:
        return Path(path).read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: pddl: cannot read the file: "
                          f"{exc.strerror if isinstance(exc, OSError) else exc}") from None


def _fragment() -> str:
    return ", ".join(f":{r}" for r in sorted(SUPPORTED))


def _check_requirements(text: str, path: str | Path) -> None:
    """Refuse a declared requirement outside the fragment, naming it (before parsing: the
    library reads some of them, such as durative actions, only partly)."""
    for m in re.finditer(r"\(\s*:requirements\b([^)]*)\)", text, re.I):
        for r in re.finditer(r":([\w-]+)", m.group(1)):
            if r.group(1).lower() not in SUPPORTED | SYNTAX_ONLY:
                at = position(path, text, m.start(1) + r.start())
                raise ConfigError(f"{at}: pddl: requirement :{r.group(1).lower()} is not "
                                  f"supported; the pddl world runs {_fragment()}")


def _parsed(parse, path: str | Path, text: str):
    """The library's parse of ``text``, its errors as one line at file:line:col. A parser
    that failed is dropped: the library leaves it mid-parse, and its next parse would fail
    with "parser is in an unexpected state"."""
    try:
        return _parse(parse, path, text)
    except ConfigError:
        reset_parsers()
        raise


def _parse(parse, path: str | Path, text: str):
    from lark.exceptions import (
        LarkError,
        UnexpectedCharacters,
        UnexpectedEOF,
        UnexpectedInput,
        UnexpectedToken,
    )
    from pddl.exceptions import PDDLError, PDDLMissingRequirementError

    text = text.lower()   # PDDL is case-insensitive; the library's keywords are lower-case
    try:
        for _ in range(len(SUPPORTED) + 1):
            try:
                return parse(text)
            except PDDLMissingRequirementError as exc:
                text = _implied(text, exc)   # used without being declared, as IPC files do
        return parse(text)
    except UnexpectedToken as exc:
        got = "the end of the file" if exc.token.type == "$END" else repr(str(exc.token))
        raise ConfigError(f"{path}:{exc.line}:{exc.column}: pddl: syntax error: expected "
                          f"{_expected(exc.expected)}, got {got}") from None
    except UnexpectedEOF as exc:
        lines = text.splitlines() or [""]
        raise ConfigError(f"{path}:{len(lines)}:{len(lines[-1]) + 1}: pddl: syntax error: the "
                          f"file ends early; expected {_expected(exc.expected)}") from None
    except UnexpectedCharacters as exc:
        raise ConfigError(f"{path}:{exc.line}:{exc.column}: pddl: syntax error: unexpected "
                          f"character {exc.char!r}; expected "
                          f"{_expected(exc.allowed or ())}") from None
    except UnexpectedInput as exc:
        raise ConfigError(f"{path}:{exc.line}:{exc.column}: pddl: syntax error") from None
    except (PDDLError, LarkError, AssertionError, ValueError, TypeError, KeyError) as exc:
        cause = exc.__context__ if isinstance(exc, LarkError) and exc.__context__ else exc
        raise ConfigError(_library_error(path, text, " ".join(str(cause).split())
                                         or type(cause).__name__)) from None


def _library_error(path: str | Path, text: str, message: str) -> str:
    """The library's own check failing, as one line at the place it names where it can."""
    m = re.fullmatch(r"types \['([^']+)'.*\] of term Variable\((\S+)\) are not in available "
                     r"types \{(.*)\}", message)
    if m:
        declared = ", ".join(sorted(re.findall(r"'([^']+)'", m.group(3))))
        return (f"{locate(path, text, m.group(1))}: pddl: ?{m.group(2)} is of the undeclared "
                f"type {m.group(1)!r} (declared: {declared})")
    names = re.findall(r"'([\w?-]+)'", message)
    where = next((w for w in (locate(path, text, n) for n in names) if w != str(path)),
                 str(path))
    return f"{where}: pddl: {message}"


def _implied(text: str, exc: Exception) -> str:
    """``text`` with the supported requirement that ``exc`` says is missing declared (IPC's
    miconic uses types without :typing); raises ``exc`` again for any other."""
    m = re.search(r":([\w-]+)", str(exc))
    if m is None or m.group(1) not in SUPPORTED:
        raise exc
    req = re.search(r"\(\s*:requirements\b", text)
    if req is not None:
        return f"{text[:req.end()]} :{m.group(1)}{text[req.end():]}"
    head = re.search(r"\(\s*(domain|problem)\s+[^)\s]+\s*\)", text)
    if head is None:
        raise exc
    return f"{text[:head.end()]}(:requirements :{m.group(1)}){text[head.end():]}"


_TOKENS = {"LPAR": "'('", "RPAR": "')'", "NAME": "a name", "VARIABLE": "a variable ?x",
           "TYPING_SEP": "'-'"}


def _expected(names) -> str:
    shown = sorted({_TOKENS.get(n, n.lower().replace("_", "-")) for n in names})
    if not shown:
        return "something else"
    return shown[0] if len(shown) == 1 else "one of " + ", ".join(shown[:8]) + \
        (", ..." if len(shown) > 8 else "")


