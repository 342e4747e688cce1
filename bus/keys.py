"""The one module that builds teleo key expressions (docs/architecture.md, bus section).

Layout (keys are static; the cycle number travels in the payload envelope, so declared
publishers and matching status keep working across cycles):

    teleo/<run>/world/state                  WorldState
    teleo/<run>/world/events                 WorldEvent; queryable: WorldEvent -> EventReply
    teleo/<run>/world/control                queryable: WorldEvent -> EventReply (pause, step)
    teleo/<run>/agent/<agent>/percepts       Percepts
    teleo/<run>/agent/<agent>/beliefs        Beliefs
    teleo/<run>/agent/<agent>/actions        Actions
    teleo/<run>/agent/<agent>/intention      Intention
    teleo/<run>/agent/<agent>/goals          queryable: GoalRequest -> GoalReply
    teleo/<run>/agent/<agent>/goal-list      GoalList (goal-entry process, once per cycle)
    teleo/<run>/stats/<process>              ProcessStats
    teleo/<run>/proc/<process>               liveliness tokens
"""

from __future__ import annotations

from bus.errors import KeyFormatError
from bus.messages import MESSAGE_TYPES

ROOT = "teleo"
_FORBIDDEN = set("/*$?#@ ")


def check_chunk(name: str, what: str = "name") -> str:
    """Return `name` if it is usable as one key chunk, else raise KeyFormatError."""
    if not isinstance(name, str) or not name:
        raise KeyFormatError(f"{what} must be a non-empty string, got {name!r}")
    bad = sorted(set(name) & _FORBIDDEN)
    if bad:
        raise KeyFormatError(f"{what} {name!r} contains forbidden character(s) {''.join(bad)!r}")
    return name


MAX_KEYEXPR_CHARS = 1024
"""[characters] of a key expression a user types (`teleo echo KEYEXPR`)."""


def check_keyexpr(expr: str) -> str:
    """Return ``expr`` if zenoh accepts it as a key expression (canonical form), else raise
    KeyFormatError saying what is wrong and, where zenoh's rule has one, the right form:
    chunks separated by single slashes, none empty; `*` and `**` alone in a chunk; `$*`
    inside one; no `#` or `?`; no `**/**` or `**/*`."""
    if not isinstance(expr, str) or not expr:
        raise KeyFormatError("key expression must be a non-empty string, e.g. 'teleo/**', "
                             f"got {expr!r}")
    if len(expr) > MAX_KEYEXPR_CHARS:
        raise KeyFormatError(f"key expression of {len(expr)} characters is longer than "
                             f"{MAX_KEYEXPR_CHARS}")
    bad = sorted(set(expr) & set("#?"))
    if bad:
        raise KeyFormatError(f"key expression {expr!r}: {''.join(bad)!r} may not appear in a key")
    chunks = expr.split("/")
    if "" in chunks:
        raise KeyFormatError(f"key expression {expr!r}: empty chunk (a leading, trailing or "
                             f"double slash); e.g. {'/'.join(c for c in chunks if c)!r}")
    for chunk in chunks:
        _check_wild_chunk(expr, chunk)
    for a, b in zip(chunks, chunks[1:], strict=False):
        if a == "**" and b in ("**", "*"):
            right = "**" if b == "**" else "*/**"
            raise KeyFormatError(f"key expression {expr!r}: write {right!r} for '**/{b}'")
    return expr


def _check_wild_chunk(expr: str, chunk: str) -> None:
    if chunk in ("*", "**"):
        return
    if chunk == "$*":
        raise KeyFormatError(f"key expression {expr!r}: write '*' for the chunk '$*'")
    rest = chunk.replace("$*", "")
    if "*" in rest:
        raise KeyFormatError(f"key expression {expr!r}: chunk {chunk!r}: '*' stands alone in a "
                             "chunk ('*' or '**'), or as '$*' inside one")
    if "$" in rest or "$*$*" in chunk:
        raise KeyFormatError(f"key expression {expr!r}: chunk {chunk!r}: '$' is only allowed "
                             "in '$*' (and not twice in a row)")


def run_root(run: str) -> str:
    """`teleo/<run>`: the prefix of everything in one run."""
    return f"{ROOT}/{check_chunk(run, 'run')}"


def run_all(run: str) -> str:
    """`teleo/<run>/**`: every data key of one run (what `teleo record` subscribes to)."""
    return f"{run_root(run)}/**"


def world_state(run: str) -> str:
    return f"{run_root(run)}/world/state"


def world_static(run: str) -> str:
    """The world's static configuration, published once at its start and served as a query
    (bus/messages.py WorldStatic; world/static.py)."""
    return f"{run_root(run)}/world/static"


def world_events(run: str) -> str:
    """Events into the world: published (applied at the next cycle), or asked as a query
    (applied at the next cycle and answered with the world's EventReply)."""
    return f"{run_root(run)}/world/events"


def world_control(run: str) -> str:
    """The world's control desk, asked as a query (`teleo pause`, `step-run`, `resume`):
    answered by the world process at a cycle boundary with its verdict (bus/pause.py)."""
    return f"{run_root(run)}/world/control"


def _agent(run: str, agent: str, leaf: str) -> str:
    return f"{run_root(run)}/agent/{check_chunk(agent, 'agent')}/{leaf}"


def percepts(run: str, agent: str) -> str:
    return _agent(run, agent, "percepts")


def beliefs(run: str, agent: str) -> str:
    return _agent(run, agent, "beliefs")


def actions(run: str, agent: str) -> str:
    return _agent(run, agent, "actions")


def intention(run: str, agent: str) -> str:
    return _agent(run, agent, "intention")


def goals(run: str, agent: str) -> str:
    return _agent(run, agent, "goals")


def goal_list(run: str, agent: str) -> str:
    """The agent's goal list of each cycle, published by the goal-entry process."""
    return _agent(run, agent, "goal-list")


def all_actions(run: str) -> str:
    """`teleo/<run>/agent/*/actions`: every agent's actions (the clock subscribes to this)."""
    return f"{run_root(run)}/agent/*/actions"


def stats(run: str, process: str) -> str:
    return f"{run_root(run)}/stats/{check_chunk(process, 'process')}"


def all_stats(run: str) -> str:
    return f"{run_root(run)}/stats/*"


RECORDER = "launch.record"
"""The process name of a launch's recorder (tools/records/recorder.py): its liveliness token says it
is there, its ProcessStats carry the last cycle it has recorded whole (the world keeps pace
with it: bus/clock.py Clock.keep_pace)."""


def proc(run: str, process: str) -> str:
    """Liveliness token key of one process."""
    return f"{run_root(run)}/proc/{check_chunk(process, 'process')}"


def all_procs(run: str) -> str:
    return f"{run_root(run)}/proc/*"


def process_of_token(run: str, key: str) -> str | None:
    """The process name of a liveliness token key of this run, or None if it is not one."""
    prefix = f"{run_root(run)}/proc/"
    if not key.startswith(prefix):
        return None
    name = key[len(prefix):]
    return name if name and "/" not in name else None


def kind_of_key(key: str) -> frozenset[str]:
    """The message kinds allowed on `key` (empty if the key is not a teleo data key): those
    whose declared KEYS (bus/kinds.py) match the key below ``teleo/<run>/``.

    The codec uses it to reject a message of the wrong kind on a key.
    """
    parts = key.split("/")
    if len(parts) < 4 or parts[0] != ROOT:
        return frozenset()
    tail = parts[2:]
    return frozenset(kind for kind, patterns in _key_patterns().items()
                     if any(_matches(p, tail) for p in patterns))


def _key_patterns() -> dict[str, tuple[tuple[str, ...], ...]]:
    """Per declared kind, its KEYS split into chunks (rebuilt when a kind is declared)."""
    global _PATTERNS
    if _PATTERNS[0] != len(MESSAGE_TYPES):
        _PATTERNS = (len(MESSAGE_TYPES), {
            kind: tuple(tuple(p.split("/")) for p in cls.KEYS)
            for kind, cls in MESSAGE_TYPES.items()})
    return _PATTERNS[1]


_PATTERNS: tuple[int, dict[str, tuple[tuple[str, ...], ...]]] = (-1, {})


def _matches(pattern: tuple[str, ...], tail: list[str]) -> bool:
    return len(pattern) == len(tail) and all(p in ("*", t) for p, t in zip(pattern, tail,
                                                                           strict=True))


def agent_of_key(key: str) -> str | None:
    """The agent chunk of an agent key (`teleo/<run>/agent/<agent>/...`), else None."""
    parts = key.split("/")
    if len(parts) >= 5 and parts[0] == ROOT and parts[2] == "agent":
        return parts[3]
    return None
