"""A fleet of cars that really drive and deliver, for bench/speed/cycle.py: N agents A1..AN in the
default 4 x 4 city, each with one package of its own one block ahead and the goal
``(package-delivered Pk)`` from cycle 0, all running ONE program file that names no agent.

The program is programs/driving.tlp with the agent bound through its ``self`` percept: where
its top-level goals name the car ``ME``, they are rewritten to ``?self`` (docs/language.md,
"Goals with variables": each car perceives one ``self``, its own), in a copy; the file itself
is never changed.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DRIVING = ROOT / "programs" / "driving.tlp"
GRID = 4
LETTERS = [chr(ord("A") + i) for i in range(GRID)]
ORDINALS = ["FIRST", "SECOND", "THIRD", "FOURTH"][:GRID]
MAX_AGENTS = 4 * 2 * GRID  # four starts on each of the 2 * GRID streets
# The cars after the first 16 (the second lap of start places, block 1 and the one before the
# last) start 30 m further along their block: the program has no right-of-way rule, and with
# all at 20 m four cars reached three inner crossings at once from four sides and jammed
# there for good (32 cars: 12 never delivered); staggered, all 32 deliver.
FIRST_LAP = 2 * 2 * GRID


def agent_free_program(text: str) -> str:
    """``text`` with the agent named ``ME`` in its top-level goals replaced by ``?self``."""
    head, sep, goals = text.partition("\n(goals")
    if not sep:
        return text
    return head + sep + re.sub(r"\bME\b", "?self", goals)


def starts() -> list[tuple[str, str, str, int]]:
    """(street, from, toward, package address) of every start place, in the order used.

    On each street: forward from block 0 and block 1, backward from the last block and the one
    before it; the package is in the next block, on the car's right (even addresses on the
    right going up the street's axis, odd going down: docs/scenarios.md, addresses)."""
    out = []
    for cross_forward, cross_back in ((0, GRID - 1), (1, GRID - 2)):
        for street, crossing in [*((s, ORDINALS) for s in LETTERS),
                                 *((s, LETTERS) for s in ORDINALS)]:
            b = cross_forward  # block b lies between crossings b and b + 1
            out.append((street, crossing[b], crossing[b + 1], 6 + 4 * b))
            b = cross_back     # going down from crossing b toward b - 1: the next block is b - 2
            out.append((street, crossing[b], crossing[b - 1], 1 + 4 * (b - 2)))
    return out


def scenario_text(agents: int, program: Path, cycles: int, seed: int = 1) -> str:
    """A lockstep scenario: ``agents`` cars, each with its own package and delivery goal."""
    if not 1 <= agents <= MAX_AGENTS:
        raise ValueError(f"agents: expected 1..{MAX_AGENTS}, got {agents}")
    cars, packages = [], []
    for k, (street, frm, toward, address) in enumerate(starts()[:agents], start=1):
        along = 20.0 if k <= FIRST_LAP else 50.0
        cars.append(f'{{ agent = "A{k}", street = "{street}", from = "{frm}", '
                    f'toward = "{toward}", along = {along} }}')
        packages.append(f'{{ id = "P{k}", address = {address}, street = "{street}", '
                        f'owner = "A{k}" }}')
    lines = ["[run]", 'name = "bench"', 'mode = "lockstep"', f"cycles = {cycles}",
             f"seed = {seed}", "", "[world]", f"grid = [{GRID}, {GRID}]", "pedestrians = 12",
             "traffic = 4", "cars = [", *(f"  {c}," for c in cars), "]", "packages = [",
             *(f"  {p}," for p in packages), "]", ""]
    for k in range(1, agents + 1):
        lines += ["[[agents]]", f'id = "A{k}"', f'program = "{program}"', "",
                  "[[goals]]", f'agent = "A{k}"', f'goal = "(package-delivered P{k})"',
                  "priority = 5", "at_cycle = 0", ""]
    return "\n".join(lines)


def write_fleet(folder: Path, agents: int, cycles: int) -> Path:
    """Write the shared program and the scenario into ``folder``; return the scenario's path."""
    program = folder / "driving_any_car.tlp"
    program.write_text(agent_free_program(DRIVING.read_text()))
    path = folder / f"fleet{agents}.toml"
    path.write_text(scenario_text(agents, program, cycles))
    return path
