"""A decision as a tree, rendered in one place (as py_trees explains a tree by drawing it):
`decision_tree` walks an intention's decision dict (Decision.to_dict, docs/architecture.md)
once into `Node`s;
`render_text` draws them like py_trees' ascii display, `to_json` gives them to scripts and to
the web view (tools/view), which draws the same nodes.

    goals of ME at cycle 213
    |-- [o] p1 satisfied: (not-hitting-pedestrians ME)
    |-- [*] p3 active: (at-desired-speed ME)
    |   |-- [-] at-desired-speed#1 {?self=ME}: skipped: ...
    |   `-- (at-desired-speed ME) <- at-desired-speed#2 [entered] {?self=ME}  (driving.tlp:80:3)
    |       `-- => (*brake 30)
    `-- [ ] g1 pending: (package-delivered PACKET1)

The tip of every acting path (its actions) is marked `=>`; skills passed over hang where they
were tried, before the one chosen, marked `[-]` with the reason.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

STANDARD_KEYS = frozenset({"cycle", "goals", "goal_id", "path", "resources", "actions",
                           "parallel", "why"})
"""Keys of Decision.to_dict that are not a mechanism's section."""

ASCII = {"satisfied": "[o]", "active": "[*]", "suspended": "[~]", "impasse": "[!]",
         "failed": "[x]", "pending": "[ ]", "skipped": "[-]", "tip": "=>",
         "branch": "|-- ", "last": "`-- ", "pipe": "|   ", "space": "    "}
UNICODE = {**ASCII, "satisfied": "✓", "active": "●", "suspended": "◐", "impasse": "!",
           "failed": "✗", "pending": "○", "skipped": "–", "tip": "⇒",
           "branch": "├── ", "last": "└── ", "pipe": "│   "}


@dataclass(frozen=True)
class Node:
    """One line of an explanation: a goal, a skill on a path, a skill passed over, the
    actions at a path's tip, or a field of a mechanism's section."""

    kind: str                # decision, goal, step, passed, actions, section, field
    label: str
    status: str = ""         # a goal status, "skipped" for a skill passed over
    bindings: tuple = ()     # ((var, value), ...)
    where: str = ""          # file:line:col of the skill
    note: str = ""
    tip: bool = False        # the acting end of a path
    children: tuple[Node, ...] = field(default=())


def decision_tree(decision: dict[str, Any], title: str = "") -> Node:
    """The one walk over a decision: goals in priority order, each acting goal with its path
    (skills passed over at each depth before the chosen one), then mechanism sections."""
    why = list(decision.get("why", ()))
    paths = _paths(decision)
    goals = []
    for g in decision.get("goals", ()):
        gid = g.get("id", "")
        label = f"{gid} {g.get('status', '')}: {g.get('goal', '')}"
        if g.get("instance") and g["instance"] != g.get("goal"):
            label += f" [{g['instance']}]"
        mine = [w for w in why if w.get("goal_id") == gid]
        why = [w for w in why if w.get("goal_id") != gid]
        children = _path_nodes(paths.get(gid), mine)
        goals.append(Node("goal", label, g.get("status", ""), _pairs(g.get("bindings")),
                           note=g.get("note", ""), children=children))
    rest = [_passed(w) for w in why]  # passed over for goals not in the list
    if rest:
        goals.append(Node("section", "passed over (other goals)", children=tuple(rest)))
    sections = [_section(k, v) for k, v in decision.items() if k not in STANDARD_KEYS]
    label = title or f"cycle {decision.get('cycle', '?')}"
    return Node("decision", label, children=tuple(goals + sections))


def _paths(decision: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """goal id -> {"path", "actions", "resources", "parallel"} of every acting goal."""
    parallel = list(decision.get("parallel", ()))
    out = {p["goal_id"]: p for p in parallel}
    if decision.get("goal_id"):
        actions = list(decision.get("actions", ()))
        own = len(actions) - sum(len(p.get("actions", ())) for p in parallel)
        out[decision["goal_id"]] = {"path": decision.get("path", ()), "actions": actions[:own],
                                    "resources": decision.get("resources", ()),
                                    "parallel": False}
    return out


def _path_nodes(path: dict[str, Any] | None, why: list[dict[str, Any]]) -> tuple[Node, ...]:
    """The path below a goal, built from its tip up: at each depth the skills passed over,
    then the chosen step holding the rest."""
    steps = list(path.get("path", ())) if path else []
    below: tuple[Node, ...] = ()
    if path is not None:
        acts = " ".join(_action(a) for a in path.get("actions", ())) or "no action"
        note = ("parallel, resources: " + " ".join(path.get("resources", ()))
                if path.get("parallel") else "")
        below = (Node("actions", acts, tip=True, note=note),)
    for depth in range(len(steps) - 1, -1, -1):
        s = steps[depth]
        label = f"{s.get('goal', '')} <- {s.get('skill', '')} [{s.get('mode', '')}]"
        step = Node("step", label, bindings=_pairs(s.get("bindings")),
                    where=s.get("where", ""), children=below)
        below = tuple(_passed(w) for w in why if w.get("depth") == depth) + (step,)
    deeper = tuple(_passed(w) for w in why if w.get("depth", 0) >= len(steps) and steps)
    return below + deeper if steps else tuple(_passed(w) for w in why) + below


def _passed(w: dict[str, Any]) -> Node:
    label = f"{w.get('goal', '')} <- {w.get('skill') or 'no skill'}"
    return Node("passed", label, "skipped", _pairs(w.get("bindings")), note=w.get("reason", ""))


def _section(name: str, value: Any) -> Node:
    """A mechanism's section (solver, scs, planner, ...) as nested fields."""
    return Node("section", name, children=_fields(value))


def _fields(value: Any) -> tuple[Node, ...]:
    if isinstance(value, dict):
        return tuple(_field(str(k), v) for k, v in value.items())
    if isinstance(value, list):
        return tuple(_field(f"[{i}]", v) for i, v in enumerate(value))
    return (Node("field", _atom(value)),)


def _field(name: str, value: Any) -> Node:
    if isinstance(value, (dict, list)) and any(isinstance(v, (dict, list)) for v in
                                               (value.values() if isinstance(value, dict)
                                                else value)):
        return Node("field", name, children=_fields(value))
    if isinstance(value, dict):
        return Node("field", f"{name}: " + (", ".join(f"{k}={_atom(v)}" for k, v in
                                                      value.items()) or "(none)"))
    if isinstance(value, list):
        return Node("field", f"{name}: " + (", ".join(_atom(v) for v in value) or "(none)"))
    return Node("field", f"{name}: {_atom(value)}")


def _pairs(bindings: Any) -> tuple:
    return tuple((str(k), v) for k, v in (bindings or {}).items())


def _atom(v: Any) -> str:
    """A value as people read it: floats to 4 decimals (the JSON keeps them exact)."""
    return repr(round(v, 4)) if isinstance(v, float) else str(v)


def _action(a: list[Any]) -> str:
    return "(" + " ".join(_atom(x) for x in a) + ")"


def bindings_text(bindings: tuple) -> str:
    """{?self=ME, ?speed=7.9}"""
    return "{" + ", ".join(f"?{k}={_atom(v)}" for k, v in bindings) + "}"


def fold(node: Node) -> Node:
    """The tree with the skills passed over for goals that do not act folded into one line
    ("... 6 skills passed over"), as py_trees folds the branches it did not visit."""
    children = tuple(fold(c) for c in node.children)
    if node.kind == "goal" and node.status != "active":
        passed = [c for c in children if c.kind == "passed"]
        if passed:
            rest = tuple(c for c in children if c.kind != "passed")
            many = "s" if len(passed) > 1 else ""
            children = rest + (Node("passed", f"... {len(passed)} skill{many} passed over"),)
    return Node(node.kind, node.label, node.status, node.bindings, node.where, node.note,
                node.tip, children)


# -- back ends -------------------------------------------------------------------------------
def walk(node: Node, symbols: dict[str, str] = ASCII, prefix: str = "",
         last: bool = True, root: bool = True) -> Iterator[tuple[str, Node]]:
    """(indentation, node) for every node, depth first: the drawing shared by text views."""
    yield ("" if root else prefix + symbols["last" if last else "branch"]), node
    inner = "" if root else prefix + symbols["space" if last else "pipe"]
    for i, child in enumerate(node.children):
        yield from walk(child, symbols, inner, i == len(node.children) - 1, False)


def line(node: Node, symbols: dict[str, str] = ASCII) -> str:
    """One node as text (without its indentation)."""
    mark = symbols["tip"] + " " if node.tip else \
        (symbols[node.status] + " " if node.status in symbols else "")
    text = mark + node.label
    if node.bindings:
        text += " " + bindings_text(node.bindings)
    if node.where:
        text += f"  ({_near(node.where)})"
    if node.note:
        text += f": {node.note}" if node.kind == "passed" else f"  -- {node.note}"
    return text


def shown_path(path: str) -> str:
    """A path as a person reads it: relative to the current folder when it is inside it."""
    try:
        return str(Path(path).resolve().relative_to(Path.cwd().resolve()))
    except (ValueError, OSError):
        return path


def _near(where: str) -> str:
    """file:line:col with the file shown as `shown_path` shows it."""
    file, sep, rest = where.partition(":")
    return shown_path(file) + sep + rest


def render_text(node: Node, symbols: dict[str, str] = ASCII) -> str:
    """The tree as text, one node a line."""
    return "\n".join(indent + line(n, symbols) for indent, n in walk(node, symbols))


def to_json(node: Node) -> dict[str, Any]:
    """The tree as plain data: {kind, label, status, bindings, where, note, tip, children}."""
    return {"kind": node.kind, "label": node.label, "status": node.status,
            "bindings": {k: v for k, v in node.bindings}, "where": node.where,
            "note": node.note, "tip": node.tip, "children": [to_json(c) for c in node.children]}
