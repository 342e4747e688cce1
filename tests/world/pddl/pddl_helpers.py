"""Shared by the pddl world's tests: the vendored PDDL files (files/: a few small IPC tasks
from pyperplan's benchmark sets, and a hand-written typed domain) and a world of them."""

from __future__ import annotations

from pathlib import Path

FILES = Path(__file__).resolve().parent / "files"
TRUCKS = (FILES / "trucks-domain.pddl", FILES / "trucks-problem.pddl")
BLOCKS = (FILES / "blocks-domain.pddl", FILES / "blocks-task01.pddl")
BLOCKS2 = (FILES / "blocks-domain.pddl", FILES / "blocks-task02.pddl")
GRIPPER = (FILES / "gripper-domain.pddl", FILES / "gripper-task01.pddl")


def world_of(files: tuple[Path, Path], agents: tuple[str, ...] = ("ME",)):
    """A PddlWorld of a (domain, problem) pair, made as a scenario makes it."""
    from world.domain import get_domain

    table = {"domain_file": str(files[0]), "problem_file": str(files[1])}
    return get_domain("pddl").create(table, 0, list(agents))


def write_problem(tmp: Path, text: str, name: str = "p.pddl") -> Path:
    path = tmp / name
    path.write_text(text)
    return path
