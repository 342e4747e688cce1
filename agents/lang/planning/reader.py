"""Reading the planner's program sections (agents/lang/planning/syntax.py says what they
mean): each handler takes the parser (agents/lang/reading/parser.py, passed in, so this module does
not import it) and one section's node, and adds what it read to ``parts.sections``, with a
file:line:col diagnostic for anything wrong."""

from __future__ import annotations

from typing import Any

from ..core.sexpr import Atom, SList, to_text
from ..core.terms import Var
from .syntax import (
    GOAL_META,
    KINDS,
    LITERAL_META,
    META,
    VERBS,
    ControlRule,
    Meta,
    OperatorSpec,
    RequestSpec,
    Travel,
)

OPERATOR_KEYS = (":operator", ":effects", ":on-failure")
OPERATOR_FORMS = {":operator": "(name ?param ...)",
                  ":effects": "((effect ?x ...) (not (effect ?x ...)) ...)",
                  ":on-failure": "((*action arg ...) ...)"}
"""The list each operator key takes, as a message shows it."""
REQUEST_KEYS = (":percepts", ":start", ":knowledge")


def _keyed(p: Any, node: SList, allowed: tuple[str, ...], what: str,
           atoms: tuple[str, ...] = ()) -> dict[str, Any]:
    """The :key value pairs after a clause's head (errors for anything else); the value is
    a list, or an atom for the keys in ``atoms``."""
    out: dict[str, Any] = {}
    items = node.items[1:]
    for i in range(0, len(items), 2):
        key = items[i]
        if not (isinstance(key, Atom) and isinstance(key.value, str)
                and key.value in allowed):
            p.err(key, f"expected one of {' '.join(allowed)} in {what}, got {to_text(key)}")
            continue
        if i + 1 >= len(items) or not isinstance(items[i + 1], Atom if key.value in atoms
                                                     else SList):
            p.err(key, f"{key.value} needs {'a number' if key.value in atoms else 'a list'} "
                  "after it")
            continue
        out[key.value] = items[i + 1]
    return out


def operators_section(p: Any, node: SList) -> None:
    """``(operators CLAUSE ...)``: each clause read as a skill (agents/lang/reading/parser.py) once
    the operator keys are taken out; the skill is kept in the operator, not among the
    program's skills (only the planner applies operators)."""
    for item in node.items[1:]:
        if not (isinstance(item, SList) and item.items and isinstance(item.items[0], SList)):
            p.err(item, f"expected an operator ((primary-effect ...) :operator (name ?p ...) "
                  f":start ... :effects ... :actions ...), got {to_text(item)}")
            continue
        _operator(p, item)


def _operator(p: Any, item: SList) -> None:
    rest, extra = [item.items[0]], {}
    pairs = item.items[1:]
    for i in range(0, len(pairs), 2):
        key = pairs[i]
        if isinstance(key, Atom) and key.value in OPERATOR_KEYS and i + 1 < len(pairs):
            if isinstance(pairs[i + 1], SList):
                extra[key.value] = pairs[i + 1]
            else:
                p.err(pairs[i + 1], f"{key.value} needs a list after it, such as "
                      f"{OPERATOR_FORMS[key.value]}, got {to_text(pairs[i + 1])}")
        else:
            rest += pairs[i:i + 2]
    if not any(isinstance(x, Atom) and x.value in (":actions", ":subgoals", ":body")
               for x in rest):   # an operator applied in the planner's model only
        rest += [Atom(":actions", item.line, item.col), SList((), item.line, item.col)]
    before = len(p.parts.skills)
    p.clause(SList(tuple(rest), item.line, item.col), "skills")
    if len(p.parts.skills) == before:
        return
    skill = p.parts.skills.pop()
    name_node = extra.get(":operator")
    sig = p.literal(name_node, "operator name", allow_not=False) if name_node is not None \
        else None
    if name_node is None:
        p.err(item, f"operator {skill.head} needs :operator (name ?param ...)")
    if sig is None:
        return
    effects = [e for e in p.conditions(extra.get(":effects"), tests=False)]
    if not any(e == skill.head for e in effects):
        effects.insert(0, skill.head)
    fails = tuple(a for a in (p.action(x) for x in p.items(extra.get(":on-failure"),
                                                          "(*action arg ...)"))
                  if a is not None)
    p.parts.sections.setdefault("operators", []).append(OperatorSpec(
        skill, sig.pred, sig.args, tuple(effects), fails, p.loc(item)))


def requests_section(p: Any, node: SList) -> None:
    """``(requests ((goal-pattern) :percepts ... :start ... :knowledge (facts)) ...)``."""
    for item in node.items[1:]:
        head = p.literal(item.items[0], "request pattern", allow_not=False) \
            if isinstance(item, SList) and item.items else None
        if head is None:
            if not (isinstance(item, SList) and item.items):
                p.err(item, f"expected ((goal-pattern) :knowledge (...)), got {to_text(item)}")
            continue
        f = _keyed(p, item, REQUEST_KEYS, "a (requests ...) clause")
        knowledge = tuple(x for x in (p.literal(k, "fact", allow_not=False)
                                      for k in p.items(f.get(":knowledge"), "(fact ...)"))
                          if x is not None)
        p.parts.sections.setdefault("requests", []).append(RequestSpec(
            head, p.patterns(f.get(":percepts")), tuple(p.conditions(f.get(":start"))),
            knowledge, p.loc(item)))


def control_section(p: Any, node: SList) -> None:
    """``(control-rules (control-rule ...) ... (travel ...))``."""
    for item in node.items[1:]:
        first = item.items[0].value if isinstance(item, SList) and item.items and \
            isinstance(item.items[0], Atom) else None
        if first == "control-rule":
            rule = _rule(p, item)
        elif first == "travel":
            rule = _travel(p, item)
        else:
            p.err(item, f"expected (control-rule NAME (if ...) (then ...)) or (travel ...), "
                  f"got {to_text(item)[:60]}")
            continue
        if rule is not None:
            p.parts.sections.setdefault("control-rules", []).append(rule)


def _prodigy_vars(node: Any) -> Any:
    """``node`` with PRODIGY's variables ``<goal>`` (seed 003, Table 2) as ``?goal``."""
    if isinstance(node, SList):
        return SList(tuple(_prodigy_vars(x) for x in node.items), node.line, node.col)
    if isinstance(node, Atom) and isinstance(node.value, str) and len(node.value) > 2 \
            and node.value[0] == "<" and node.value[-1] == ">":
        return Atom(Var(node.value[1:-1]), node.line, node.col)
    return node


def _rule(p: Any, item: SList) -> ControlRule | None:
    item = _prodigy_vars(item)
    parts = item.items
    if len(parts) != 4 or not isinstance(parts[1], Atom) or _head(parts[2]) != "if" \
            or _head(parts[3]) != "then" or len(parts[2].items) != 2:
        p.err(item, "expected (control-rule NAME (if CONDITION) (then select|prefer|reject "
              "goal|operator|bindings ARG ...))")
        return None
    name = str(parts[1].value)
    cond = _cond(p, parts[2].items[1])
    then = parts[3].items[1:]
    verb = then[0].value if then and isinstance(then[0], Atom) else None
    kind = then[1].value if len(then) > 1 and isinstance(then[1], Atom) else None
    if verb not in VERBS or kind not in KINDS:
        p.err(parts[3], f"control rule {name}: expected (then select|prefer|reject "
              f"goal|operator|bindings ...), got {to_text(parts[3])}")
        return None
    want = 2 if verb == "prefer" else 1
    if len(then) - 2 != want:
        p.err(parts[3], f"control rule {name}: {verb} {kind} takes {want} argument(s), got "
              f"{len(then) - 2}")
        return None
    args = []
    for a in then[2:]:
        if kind == "bindings":
            args.append(p.literal(a, "operator pattern such as (schedule-meeting ?room)",
                                  allow_not=False))
        elif isinstance(a, Atom) and (kind == "goal" or isinstance(a.value, str)):
            args.append(a.value)
        else:
            p.err(a, f"control rule {name}: expected a {'term' if kind == 'goal' else 'name'}"
                  f", got {to_text(a)}")
            args.append(None)
    if cond is None or any(a is None for a in args):
        return None
    return ControlRule(name, cond, verb, kind, tuple(args), p.loc(item))


def _cond(p: Any, node: Any) -> Meta | None:
    name = _head(node)
    if name in ("and", "or", "not"):
        kids = [_cond(p, x) for x in node.items[1:]]
        if name == "not" and len(kids) != 1:
            p.err(node, f"(not ...) takes one condition, got {len(kids)}")
            return None
        return None if any(k is None for k in kids) else Meta(name, tuple(kids), p.loc(node))
    if name not in META:
        p.err(node, f"expected a meta-predicate ({' '.join(META)}) or and/or/not, got "
              f"{to_text(node)[:60]}")
        return None
    args = node.items[1:]
    want = 2 if name == "closer" else 1
    if len(args) != want:
        p.err(node, f"({name} ...) takes {want} argument(s), got {len(args)}")
        return None
    if name in GOAL_META or name == "closer":
        if not all(isinstance(a, Atom) for a in args):
            p.err(node, f"({name} ...) takes terms such as ?goal, got {to_text(node)}")
            return None
        return Meta(name, tuple(a.value for a in args), p.loc(node))
    lit = p.literal(args[0], "literal" if name in LITERAL_META else "operator pattern",
                    allow_not=False)
    return None if lit is None else Meta(name, (lit,), p.loc(node))


def _travel(p: Any, item: SList) -> Travel | None:
    f = _keyed(p, item, (":location", ":between", ":from-here", ":detour", ":carrying",
                         ":capacity"), "(travel ...)", atoms=(":detour",))
    missing = [k for k in (":location", ":between", ":from-here") if k not in f]
    if missing:
        p.err(item, f"(travel ...) needs {' '.join(missing)}")
        return None
    where = p.literal(f[":location"], "location literal", allow_not=False)
    between = p.patterns(SList((f[":between"],), item.line, item.col))
    here = p.patterns(SList((f[":from-here"],), item.line, item.col))
    detour = 10.0
    if ":detour" in f:
        node = f[":detour"]
        if not (isinstance(node.value, int | float) and node.value >= 0):
            p.err(node, f"(travel ...) :detour: expected metres >= 0, got {to_text(node)}")
            return None
        detour = float(node.value)
    carrying = p.literal(f[":carrying"], "carrying literal", allow_not=False) \
        if ":carrying" in f else None
    capacity = p.patterns(SList((f[":capacity"],), item.line, item.col)) \
        if ":capacity" in f else []
    if (":carrying" in f) != (":capacity" in f):
        p.err(item, "(travel ...) :carrying and :capacity go together (what the robot "
              "carries, and the percept that says how much it can)")
        return None
    if where is None or not between or not here or (":capacity" in f and
                                                    (carrying is None or not capacity)):
        return None
    return Travel(where, between[0], here[0], detour, p.loc(item), carrying,
                  capacity[0] if capacity else None)


def _head(node: Any) -> Any:
    return node.items[0].value if isinstance(node, SList) and node.items and \
        isinstance(node.items[0], Atom) else None


PLANNING_SECTIONS = {"operators": operators_section, "requests": requests_section,
                     "control-rules": control_section}
"""Section name -> handler(parser, node), the parser's through Planning.sections."""
