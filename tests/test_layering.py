"""The import rules of docs/architecture.md ("Dependency rule"), enforced by reading every
module's imports with ast (TYPE_CHECKING imports included), plus: no import cycles, and the
package graph of agents/lang (issue 26): the kernel's rooms in order, the mechanisms above
them, the registry the only module outside a mechanism that imports it, the assembly on top,
no import inside a function."""

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


def _function_imports(path: Path) -> list[str]:
    """``module:line`` of every import inside a function or class body."""
    tree = ast.parse(path.read_text(), str(path))
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            out += [f"{_module(path)}:{n.lineno}" for n in ast.walk(node)
                    if isinstance(n, ast.Import | ast.ImportFrom)]
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


def test_the_schema_package_imports_the_standard_library_only() -> None:
    """bus/schema/ (the field specs every process checks its messages with) sits below the
    rest of the bus, the worlds and the processes: it imports nothing of theirs, so a world
    may check its events and snapshots with it without touching the bus."""
    assert _violations("bus.schema", lambda m, i: _top(i) in STDLIB
                       or i.startswith("bus.schema")) == []


def test_only_bus_imports_zenoh_and_msgpack() -> None:
    for mod, imports in SOURCES.items():
        if not mod.startswith("bus"):
            assert not {_top(i) for i in imports} & {"zenoh", "msgpack"}, mod


def test_bus_never_imports_agents_world_or_tools() -> None:
    assert _violations("bus", lambda m, i: _top(i) not in {"agents", "world", "tools"}) == []


def test_world_never_imports_agents_or_tools_and_touches_the_bus_at_two_places() -> None:
    bus_users = {"world.process", "world.run_scenario", "world.scenario_types"}
    assert _violations("world", lambda m, i: _top(i) not in {"agents", "tools"}
                       and (_top(i) != "bus" or m in bus_users
                            or i == "bus.schema" or i.startswith("bus.schema."))) == []


def test_processes_never_import_the_command_layer() -> None:
    assert _violations("agents.processes", lambda m, i: _top(i) != "tools") == []


# The rooms of tools/ (docs/architecture.md, "tools/: its rooms") and the rooms each may
# import: runs below records, both below launching, the commands on top; the web view beside
# the commands, below them. tools/paths.py (output-file checks) and tools/alarm.py (a time
# limit on a block of code) are under every room.
TOOLS_ROOMS = {
    "tools.runs": set(),
    "tools.records": {"tools.runs"},
    "tools.launching": {"tools.records", "tools.runs"},
    "tools.view": {"tools.records", "tools.runs"},
    "tools.commands": {"tools.launching", "tools.records", "tools.runs"},
}
TOOLS_BASE = {"tools.alarm", "tools.paths"}


def _tools_room(name: str) -> str:
    return ".".join(name.split(".")[:2])


def _tools_allowed(mod: str, imp: str) -> bool:
    """May ``mod`` (in a room of tools/) import ``imp``? Its own room, the rooms below it, the
    base modules, and anything outside tools/ (the other rules see to that)."""
    if _top(imp) != "tools" or imp == "tools":
        return True
    return _tools_room(imp) in {_tools_room(mod)} | TOOLS_ROOMS[_tools_room(mod)] | TOOLS_BASE


def test_the_rooms_of_tools_import_only_the_rooms_below_them() -> None:
    """Records and launching never import a command, the view neither nor the launcher, the
    registry nothing of the others: each room is read and tested without the ones above it."""
    assert set(TOOLS_ROOMS) | TOOLS_BASE | {"tools.cli", "tools.law_programs"} == \
        {_tools_room(m) for m in SOURCES if _top(m) == "tools" and m != "tools"}
    for room in TOOLS_ROOMS:
        assert _violations(room, _tools_allowed) == []
    assert not _tools_allowed("tools.records.summary", "tools.commands.launch")
    assert not _tools_allowed("tools.launching.supervision", "tools.commands.run")
    assert not _tools_allowed("tools.view.feeds", "tools.launching.run_plan")
    assert not _tools_allowed("tools.runs.target", "tools.records.run_record")


def test_the_base_modules_of_tools_import_no_room() -> None:
    for base in TOOLS_BASE | {"tools.law_programs"}:
        assert _violations(base, lambda m, i: _top(i) != "tools") == []


def _command_table() -> dict[str, tuple[str, ...]]:
    """tools/cli.py's `_COMMAND_MODULES`, read with ast (importing cli sets signal handlers)."""
    tree = ast.parse((ROOT / "tools" / "cli.py").read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and \
                any(getattr(t, "id", "") == "_COMMAND_MODULES" for t in node.targets):
            return ast.literal_eval(node.value)
    raise AssertionError("tools/cli.py has no _COMMAND_MODULES")


def test_the_command_group_imports_a_command_module_only_when_asked() -> None:
    """`teleo` starts fast (tests/tools/test_cli_startup.py): tools/cli.py imports the stop
    signals and the path checks; every command module is in its table, loaded by name when
    its command is asked for, and only from tools/commands/ or the web view's package."""
    assert {_tools_room(i) for i in SOURCES["tools.cli"] if _top(i) == "tools" and i != "tools"} \
        <= {"tools.launching", "tools.paths"}
    assert {i for i in SOURCES["tools.cli"] if _tools_room(i) == "tools.launching"} <= \
        {"tools.launching", "tools.launching.stop_signals"}
    modules = set(_command_table())
    assert {m for m in modules if not m.startswith("tools.commands.")} == {"tools.view"}
    assert modules <= set(SOURCES)
    assert not any(i.startswith("tools.commands") for m, imports in SOURCES.items()
                   if not m.startswith("tools.commands") for i in imports)


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


# -- agents/lang: kernel rooms < mechanisms < registry < assembly (docs/architecture.md) -------

LANG = "agents.lang"
ROOMS = {"core": 0, "reading": 1, "inference": 2, "execution": 2}
"""The kernel's rooms by level: a room imports its own modules and lower levels only (the two
of level 2 not each other)."""
REGISTRY = "agents.lang.registry"
ASSEMBLY = {"agents.lang", "agents.lang.engine", "agents.lang.loader"}
MAX_MODULES = 15


def _room(mod: str) -> str:
    """The subpackage of agents.lang that ``mod`` is in or is ("" for none)."""
    parts = mod.split(".")
    if len(parts) >= 3 and parts[:2] == ["agents", "lang"] \
            and ".".join(parts[:3]) in PACKAGES_OF_LANG:
        return parts[2]
    return ""


def _on_top(mod: str) -> bool:
    """True for the registry and the assembly (and what they hold)."""
    return any(mod == t or mod.startswith(t + ".") for t in (REGISTRY, *ASSEMBLY - {LANG})) \
        or mod == LANG


PACKAGES_OF_LANG = {_module(p) for p in (ROOT / "agents/lang").glob("*/__init__.py")}
MECHANISMS = {m.split(".")[2] for m in PACKAGES_OF_LANG} - set(ROOMS)


def lang_violations(sources: dict[str, set[str]], mechanisms: set[str] = MECHANISMS
                    ) -> list[str]:
    """Every import of ``sources`` (module -> imported names) that breaks agents/lang's graph:
    a kernel room importing a higher or sibling room, a mechanism, the registry or the
    assembly; a mechanism importing the registry, the assembly, agents.processes or tools;
    a module outside the mechanisms but the registry importing one. (A mechanism may build on
    another: the planner's Back-Chainer runs on the solver's chaining code, seed 003.)"""
    bad = []
    for mod, imports in sorted(sources.items()):
        here = _room(mod)
        for i in sorted(imports):
            there = _room(i)
            if there in mechanisms and here not in mechanisms and mod != REGISTRY:
                bad.append(f"{mod} imports mechanism {i} (only {REGISTRY} may)")
            elif here in ROOMS and i.startswith(LANG):
                if there not in ROOMS or not (there == here or ROOMS[there] < ROOMS[here]):
                    bad.append(f"{mod} (room {here}) imports {i}")
            elif here in mechanisms and (_top(i) == "tools" or i.startswith("agents.processes")
                                         or _on_top(i)):
                bad.append(f"{mod} (mechanism {here}) imports {i}")
    return bad


def test_agents_lang_keeps_its_package_graph() -> None:
    assert lang_violations(SOURCES) == []


def test_the_rule_checker_reports_a_kernel_module_importing_a_mechanism() -> None:
    fabricated = {"agents.lang.execution.paths": {"agents.lang.scs.state",
                                                   "agents.lang.scs.state.ScsState"},
                  "agents.lang.core.terms": {"agents.lang.execution.state"},
                  "agents.lang.inference.rules": {"agents.lang.execution.paths"},
                  "agents.lang.scs.runner": {"agents.lang.registry", "tools.cli"},
                  "agents.processes.persist": {"agents.lang.solving.learned"},
                  "agents.lang.registry": {"agents.lang.scs.state"},
                  "agents.lang.scs.syntax": {"agents.lang.core.terms"},
                  "agents.lang.planning.backchain": {"agents.lang.solving.search"}}
    assert lang_violations(fabricated, {"scs", "solving", "planning"}) == [
        "agents.lang.core.terms (room core) imports agents.lang.execution.state",
        "agents.lang.execution.paths imports mechanism agents.lang.scs.state (only "
        "agents.lang.registry may)",
        "agents.lang.execution.paths imports mechanism agents.lang.scs.state.ScsState (only "
        "agents.lang.registry may)",
        "agents.lang.inference.rules (room inference) imports agents.lang.execution.paths",
        "agents.lang.scs.runner (mechanism scs) imports agents.lang.registry",
        "agents.lang.scs.runner (mechanism scs) imports tools.cli",
        "agents.processes.persist imports mechanism agents.lang.solving.learned (only "
        "agents.lang.registry may)",
    ]


def test_outside_the_mechanisms_only_the_registry_imports_them() -> None:
    users = {m for m, imports in SOURCES.items() for i in imports
             if _room(i) in MECHANISMS and _room(m) not in MECHANISMS}
    assert users == {REGISTRY}


def test_no_function_level_imports_in_agents_lang() -> None:
    assert [x for p in (ROOT / "agents/lang").rglob("*.py") for x in _function_imports(p)] \
        == []


def test_each_package_of_agents_lang_holds_at_most_fifteen_modules() -> None:
    for pkg in [ROOT / "agents/lang", *(ROOT / "agents/lang").glob("*/")]:
        if (pkg / "__init__.py").exists():
            modules = [p for p in pkg.glob("*.py") if p.name != "__init__.py"]
            assert len(modules) <= MAX_MODULES, (pkg.name, len(modules))
    assert set(ROOMS) <= {m.split(".")[2] for m in PACKAGES_OF_LANG}
    assert MECHANISMS == {"solving", "scs", "planning"}
