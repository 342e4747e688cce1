"""The SCS state under a new program (`teleo program load`, agents/lang/swap.py): a body
thread goes on only where its skill is in the new program unchanged, and a do-best record
only where its skill is; the world model and the tally stay as they were (the facts are the
agent's, not the program's)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

from .state import ScsState


def carried(scs: ScsState, numbers: Mapping[int, int], names: Mapping[str, str]
            ) -> tuple[ScsState, tuple[str, ...]]:
    """``scs`` with the threads and choices of the skills still there (renumbered and renamed
    by ``numbers`` and ``names``: old -> new), and a sentence for each one dropped."""
    dropped: list[str] = []
    threads = []
    for t in scs.threads:
        if t.skill not in numbers:
            dropped.append(f"SCS thread of goal {t.goal_id} {t.goal} (skill {t.skill_name}): "
                           "its body is not in the new program")
            continue
        n = numbers[t.skill]
        threads.append(replace(t, key=f"{t.key.rsplit('|', 1)[0]}|{n}", skill=n,
                               skill_name=names.get(t.skill_name, t.skill_name)))
    choices = []
    for c in scs.choices:
        skill, at, where = c.key.partition("@")
        if skill not in names:
            dropped.append(f"do-best record {c.key} ({c.label}): its skill is not in the new "
                           "program")
            continue
        choices.append(replace(c, key=f"{names[skill]}{at}{where}"))
    return ScsState(tuple(sorted(threads, key=lambda t: t.key)),
                    tuple(sorted(choices, key=lambda c: c.key)), scs.model,
                    scs.tally), tuple(dropped)
