"""Where a path named in a scenario is found: a relative one beside the scenario, then in each
folder above it (so `programs/driving.tlp` in scenarios/x.toml finds the repository's
programs/ from any working directory), then in the working directory. Programs and a world's
`*_file` keys (the pddl world's `domain_file`, `problem_file`) are found so."""

from __future__ import annotations

from pathlib import Path
from typing import Any


def resolve(name: str, scenario_path: Path) -> Path:
    """The path ``name`` of a scenario in ``scenario_path`` stands for."""
    candidate = Path(name)
    if candidate.is_absolute():
        return candidate
    for folder in scenario_path.resolve().parents:
        try:
            if (folder / candidate).exists():
                return folder / candidate
        except (OSError, ValueError):  # a name too long to look up, a NUL byte: not there
            return candidate
    return candidate


def world_files(table: dict[str, Any], scenario_path: Path) -> dict[str, Any]:
    """``table`` with each relative path under a key ending in `_file` found by ``resolve``."""
    return {k: str(resolve(v, scenario_path)) if k.endswith("_file") and isinstance(v, str)
            and v else v for k, v in table.items()}
