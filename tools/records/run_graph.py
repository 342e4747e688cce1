"""A run's processes and the bus keys between them (`teleo graph --run RUN`; as ROS 2's
rqt_graph): a node for each process of the run that holds its liveliness token now (the live
system's own answer, bus/presence.py: the world with its clock, each agent's perception,
inference and executive, the goal entry, the launch's recorder), a node for each key, an edge
from a process to each key it publishes and from each key to each process that subscribes to
it (a queryable it serves: dashed).

Which keys a process uses is read from the one declaration of them, bus/security.py
``grants`` (the access-control list a secured run's router enforces), with its wildcards
(`agent/*/intention`, `stats/*`, `**`) matched against the keys of the processes that are up.
The recorder and `teleo record` hold tokens under the operator's grants: they are drawn with
what they subscribe to and their own stats key, not with what the operator's other commands
may send. A run that has ended is drawn from its record: its processes are the senders of its
messages (each envelope names one), with the keys each was seen to publish.
"""

from __future__ import annotations

from bus import keys
from bus.security import OPERATOR, grants, process_users
from tools.records.drawing import Graph


def matches(pattern: str, key: str) -> bool:
    """Whether the key expression ``pattern`` (chunks `*`, `**`) covers the concrete ``key``."""
    return _match(pattern.split("/"), key.split("/"))


def _match(pat: list[str], key: list[str]) -> bool:
    if not pat:
        return not key
    if pat[0] == "**":
        return any(_match(pat[1:], key[i:]) for i in range(len(key) + 1))
    return bool(key) and pat[0] in ("*", key[0]) and _match(pat[1:], key[1:])


def agents_of(processes: set[str]) -> list[str]:
    """The agents whose stages are among ``processes`` (`ME.perception` -> ME)."""
    return sorted({p.rpartition(".")[0] for p in processes
                   if p.rpartition(".")[2] in ("perception", "inference", "executive")})


def user_of(run: str, process: str, users: list[str]) -> str | None:
    """The user of the run whose grants hold ``process``'s liveliness token, else None."""
    token = keys.proc(run, process)
    return next((u for u in users if token in grants(run, u)["token"]), None)


def uses(run: str, process: str, agents: list[str]) -> dict[str, list[str]]:
    """{"put": ..., "sub": ..., "serve": ...}: the key expressions ``process`` uses."""
    user = user_of(run, process, process_users(agents))
    if user is None:
        return {"put": [], "sub": [], "serve": []}
    g = grants(run, user)
    own_stats = keys.stats(run, process)
    stats = keys.all_stats(run)
    put = [k for k in g["put"] if k == own_stats or not matches(stats, k)]
    if user == OPERATOR:  # the person's commands may send, the recorder does not
        put = [k for k in put if k == own_stats]
    return {"put": put, "sub": list(g["sub"]), "serve": list(g["serve"])}


def _expand(run: str, expr: str, agents: list[str]) -> list[str]:
    """A key expression of a grant as the concrete keys of this run it stands for (an agent
    wildcard: one key per agent); a wildcard left (`stats/*`, `**`) stays for matching."""
    agent_any = f"{keys.run_root(run)}/agent/*/"
    if expr.startswith(agent_any):
        return [expr.replace("/agent/*/", f"/agent/{a}/", 1) for a in agents]
    return [expr]


def short(run: str, key: str) -> str:
    """A key without its `teleo/<run>/` prefix."""
    return key.removeprefix(keys.run_root(run) + "/")


def _order(process: str) -> tuple:
    """The cycle's order: the world (and its clock), each agent's stages, the rest."""
    stage = process.rpartition(".")[2]
    stages = ("perception", "inference", "executive")
    return (0,) if process == "world" else (1, stages.index(stage), process) \
        if stage in stages else (2, process)


def run_graph(run: str, processes: set[str], stats: bool = False,
              sent: dict[str, set[str]] | None = None) -> Graph:
    """The graph of ``run`` with ``processes`` up (see the module doc); ``stats``: with the
    keys each process says its compute time on (`stats/<process>`; left out by default, as
    rqt_graph leaves out debug topics); ``sent``: process -> the keys it was seen to publish
    (a run record's senders), drawn instead of those its grants allow."""
    g = Graph(f"run {run}{' (record)' if sent is not None else ''}: processes and keys")
    agents = agents_of(processes)
    used = {p: uses(run, p, agents) for p in sorted(processes, key=_order)}
    if sent is not None:
        for p, u in used.items():
            u["put"] = sorted(sent.get(p, ()))
    for u in used.values():
        for mode in u:
            u[mode] = [k for k in u[mode] if stats or not (
                matches(keys.all_stats(run), k) or k == keys.all_stats(run))]
    published = {p: [k for e in u["put"] for k in _expand(run, e, agents)]
                 for p, u in used.items()}
    put = {k for ks in published.values() for k in ks}
    for p in used:
        g.node(f"proc:{p}", p, "process", f"process {p} (liveliness token "
               f"{keys.proc(run, p)})" if sent is None else f"process {p} (a sender in the "
               "record)")
        for k in published[p]:
            g.node(f"key:{k}", short(run, k), "key", k)
            g.edge(f"proc:{p}", f"key:{k}", "publishes")
    for p, u in used.items():
        for mode in ("sub", "serve"):
            for expr in u[mode]:
                named = [e for e in _expand(run, expr, agents) if "*" not in e]
                # a wildcard stands for the keys published; a key named, for itself
                for k in sorted(put | set(named)):
                    if k in published[p] or not any(matches(e, k) for e in
                                                     _expand(run, expr, agents)):
                        continue
                    g.node(f"key:{k}", short(run, k), "key", k)
                    g.edge(f"key:{k}", f"proc:{p}", "subscribes" if mode == "sub"
                           else "serves", dashed=mode == "serve")
    return g
