"""What one agent's stage processes are started with: one declaration of the options and
their defaults, read from the command line of a stage process or from the JSON that
`teleo launch --agents-per-process` hands a shared process (agents/processes/shared.py)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields
from typing import Any


@dataclass(frozen=True, kw_only=True)
class AgentSetup:
    """One agent of run ``run``: its program [path], and the executive's options: ``state``
    the engine state file read back at start and written as it changes, ``learned`` an
    earlier run's learned skills to start from, ``learned_out`` where learned skills are
    written, ``solver`` False to leave an impasse an impasse, ``mechanism`` what answers it,
    ``swapped`` where a program swapped in at run time is kept. Only names and paths: the
    program and the mechanism are read where the engine is built."""

    run: str
    agent: str
    program: str = ""
    state: str | None = None
    learned: str | None = None
    learned_out: str | None = None
    solver: bool = True
    mechanism: str = "means-ends"
    swapped: str | None = None

    def process(self, stage: str) -> str:
        """The process name of this agent's ``stage``: ``ME.executive``."""
        return f"{self.agent}.{stage}"

    def to_json(self) -> dict[str, Any]:
        """The map `from_json` reads back (the run left out: the shared process has its own)."""
        return {k: v for k, v in asdict(self).items() if k != "run"}

    @classmethod
    def from_json(cls, run: str, item: Any) -> AgentSetup:
        """The setup in ``item`` (a map with at least "agent" and "program"); ValueError
        naming the key and what is wrong."""
        if not isinstance(item, dict):
            raise ValueError(f"expected a map with 'agent' and 'program', got "
                             f"{type(item).__name__}")
        known = {f.name for f in fields(cls)} - {"run"}
        for key in ("agent", "program"):
            if not isinstance(item.get(key), str) or not item[key]:
                raise ValueError(f"{key}: expected a non-empty string, got {item.get(key)!r}")
        unknown = sorted(set(item) - known)
        if unknown:
            raise ValueError(f"{unknown[0]}: not an option of an agent (known: "
                             f"{', '.join(sorted(known))})")
        for key in ("state", "learned", "learned_out", "swapped"):
            if item.get(key) is not None and not isinstance(item[key], str):
                raise ValueError(f"{key}: expected a path or null, got {item[key]!r}")
        if not isinstance(item.get("solver", True), bool):
            raise ValueError(f"solver: expected true or false, got {item['solver']!r}")
        if not isinstance(item.get("mechanism", ""), str):   # a name the Engine knows: it
            raise ValueError(f"mechanism: expected a name, got "   # says which it knows
                             f"{item['mechanism']!r}")
        return cls(run=run, **item)
