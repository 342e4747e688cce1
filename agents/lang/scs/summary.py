"""SCS's part of the run summary (seed 002): what an agent's bodies did, from its last agent
memory (docs/bus.md, "Agent memory"): the tally, each do-best alternative's record and
discount factor, the threads still running and the world model."""

from __future__ import annotations

from typing import Any

from ..core.mechanism import AgentRecord


def bodies_entry(agent: AgentRecord) -> dict[str, Any] | None:
    """The agent's "bodies" entry, or None for an agent without bodies."""
    memory = agent.memory
    scs = memory.get("scs") if isinstance(memory, dict) else None
    if not isinstance(scs, dict) or not (scs.get("tally") or scs.get("threads")):
        return None
    return {"tally": scs.get("tally", {}),
            "choices": scs.get("choices", []),
            "threads": [{k: t.get(k) for k in ("goal_id", "goal", "skill_name", "status", "note")}
                        for t in scs.get("threads", [])],
            "model": memory.get("model", [])}


def bodies_lines(name: str, b: dict[str, Any]) -> list[str]:
    """The entry as the summary prints it."""
    tally = ", ".join(f"{k} {v}" for k, v in sorted(b["tally"].items()))
    out = [f"  {name} SCS bodies: {tally or 'nothing done'}"]
    for c in b["choices"]:
        out.append(f"    do-best {c['label']}: chosen {c['chosen']}, succeeded "
                   f"{c['succeeded']}, failed {c['failed']}, discount factor {c['factor']:.3f}")
    for t in b["threads"]:
        out.append(f"    thread {t['goal_id']} {t['goal']} <- {t['skill_name']}: "
                   f"{t['status']} ({t['note']})")
    if b["model"]:
        out.append("    world model: " + " ".join("(" + " ".join(map(str, f)) + ")"
                                             for f in b["model"]))
    return out
