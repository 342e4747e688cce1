"""The import rules of docs/architecture.md ("Dependency rule"), enforced by reading every
module's imports with ast (TYPE_CHECKING imports included), plus: no import cycles."""

from __future__ import annotations

import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("agents", "bus", "world", "tools")
STDLIB = set(sys.stdlib_module_names)


def _module(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(), str(path))
    out: set[str] = set()
    here = _module(path).split(".")
    is_pkg = path.name == "__init__.py"
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here if is_pkg else here[:-1]
                base = base[:len(base) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            out.add(mod)
            out |= {f"{mod}.{a.name}" for a in node.names}
    return out


def _sources() -> dict[str, set[str]]:
    return {_module(p): _imports(p) for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py")}


SOURCES = _sources()


def _violations(prefix: str, allowed) -> list[str]:
    bad = []
    for mod, imports in sorted(SOURCES.items()):
        if mod == prefix or mod.startswith(prefix + "."):
            bad += [f"{mod} imports {i}" for i in sorted(imports) if not allowed(mod, i)]
    return bad


def _top(name: str) -> str:
    return name.split(".")[0]


def test_the_language_engine_imports_the_standard_library_only() -> None:
    assert _violations("agents.lang", lambda m, i: _top(i) in STDLIB
                       or i.startswith("agents.lang")) == []


def test_only_bus_imports_zenoh_and_msgpack() -> None:
    for mod, imports in SOURCES.items():
        if not mod.startswith("bus"):
            assert not {_top(i) for i in imports} & {"zenoh", "msgpack"}, mod


def test_bus_never_imports_agents_world_or_tools() -> None:
    assert _violations("bus", lambda m, i: _top(i) not in {"agents", "world", "tools"}) == []


def test_world_never_imports_agents_or_tools_and_touches_the_bus_at_two_places() -> None:
    bus_users = {"world.process", "world.run_scenario", "world.scenario_types"}
    assert _violations("world", lambda m, i: _top(i) not in {"agents", "tools"}
                       and (_top(i) != "bus" or m in bus_users)) == []


def test_processes_never_import_the_command_layer() -> None:
    assert _violations("agents.processes", lambda m, i: _top(i) != "tools") == []


def test_no_import_cycles_between_modules() -> None:
    graph = {m: {i for i in imports if i in SOURCES and i != m}
             for m, imports in SOURCES.items()}
    # a package's __init__ importing its own submodules is not a cycle of the design
    graph = {m: {i for i in deps if not m.startswith(i + ".")} for m, deps in graph.items()}
    state: dict[str, int] = {}
    cycles: list[list[str]] = []

    def visit(node: str, stack: list[str]) -> None:
        state[node] = 1
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycles.append(stack[stack.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m, [m])
    assert cycles == []
