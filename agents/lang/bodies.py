"""The kinds of skill body and the runner of each (STYLE.md, "One interface for every skill
body"): ``Skill.kind`` names the kind; the path finder asks its runner for the path below an
entered skill. A new kind (an SCS body, a learned or planned skill) is a new runner here,
not a new branch in the path finder."""

from __future__ import annotations

from .paths import BodyRunner, PrimitiveBody, SubgoalBody


def body_runners() -> dict[str, BodyRunner]:
    """``Skill.kind`` -> runner, for every kind this engine can execute."""
    return {"primitive": PrimitiveBody(), "nonprimitive": SubgoalBody()}
