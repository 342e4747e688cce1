"""The IPC bench's tables and issue 35's targets (bench/ipc/ipc.py), from the runs of
bench/ipc/runs.py: per domain a row per task and a summary row; then each target met or NOT
MET with the tasks that miss it."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from statistics import mean

from bench.ipc.runs import Run

RATIO = 1.5        # plans at most this times the best plan found
REDUCTION = 0.90   # problem-solving cycles saved by the task's own learned skills
WHO = ("teleo-fresh", "teleo-learned", "teleo-cross", "gbf-hff", "astar-lmcut")


def by_task(runs: Iterable[Run]) -> dict[tuple[str, str], dict[str, Run]]:
    """Runs keyed by (domain, task), then by who."""
    out: dict[tuple[str, str], dict[str, Run]] = {}
    for r in runs:
        out.setdefault((r.domain, r.task), {})[r.who] = r
    return out


def best(rs: dict[str, Run]) -> int:
    """The shortest valid plan any run found for a task (0: none)."""
    lengths = [r.length for r in rs.values() if r.solved]
    return min(lengths) if lengths else 0


def reduction(rs: dict[str, Run]) -> float | None:
    """1 - learned/fresh problem-solving cycles, when both solved and fresh solved anything."""
    f, lrn = rs.get("teleo-fresh"), rs.get("teleo-learned")
    if not (f and lrn and f.solved and lrn.solved and f.solving > 0):
        return None
    return 1 - lrn.solving / f.solving


def _cell(r: Run | None, best_len: int, teleo: bool) -> str:
    if r is None:
        return "-"
    if not r.solved:
        return {"timeout": "T/O", "limit": "limit", "failed": "fail", "invalid": "INVALID",
                "error": "err", "unchecked": "unchk"}.get(r.status, r.status)
    ratio = f" x{r.length / best_len:.2f}" if best_len else ""
    extra = f" c{r.cycles} s{r.solving}" if teleo else ""
    return f"{r.length}{ratio}{extra} {r.solve_s if teleo else r.wall_s:.1f}s"


def task_table(domain: str, tasks: dict[str, dict[str, Run]], emit: Callable) -> None:
    """One row per task: each run's plan length (xratio to the best), teleo's cycles (c) and
    problem-solving cycles (s), and time."""
    emit(f"\n== {domain}: per task (length xratio-to-best [c cycles s solving cycles] time: "
         "teleo's own, pyperplan's with its start; T/O killed at the limit)")
    emit(f"{'task':<8}" + "".join(f"{w:<28}" for w in WHO) + "reduction")
    for task in sorted(tasks):
        rs = tasks[task]
        b = best(rs)
        red = reduction(rs)
        emit(f"{task:<8}" + "".join(f"{_cell(rs.get(w), b, w.startswith('teleo')):<28}"
                                    for w in WHO)
             + ("-" if red is None else f"{100 * red:.0f}%"))


def summary(grouped: dict[tuple[str, str], dict[str, Run]], emit: Callable) -> None:
    """Per domain: solved counts, mean length ratio to the best, teleo's cycles and
    problem-solving cycles fresh and learned, mean reduction, total time."""
    emit("\n== summary per domain (solved/tasks; ratio: mean plan length / best found, over "
         "solved tasks; cycles and solving cycles: means over solved tasks; solve-F: teleo's "
         "own time on the tasks it solved; wall: every run's, with the interpreter's start)")
    emit(f"{'domain':<11}{'fresh':>7}{'learned':>8}{'cross':>7}{'gbf':>6}{'astar':>7}"
         f"{'ratio':>7}{'ratio-L':>8}{'cycles':>8}{'solv-F':>8}{'solv-L':>8}{'reduct':>8}"
         f"{'solve-F':>8}{'wall-F':>8}{'wall-gbf':>9}")
    for domain in sorted({d for d, _ in grouped}):
        emit(_summary_row(domain, [rs for (d, _), rs in sorted(grouped.items())
                                   if d == domain]))


def _summary_row(domain: str, tasks: list[dict[str, Run]]) -> str:
    def count(who: str) -> str:
        have = [rs[who] for rs in tasks if who in rs]
        return f"{sum(r.solved for r in have)}/{len(have)}" if have else "-"

    def ratio(who: str) -> str:
        xs = [rs[who].length / best(rs) for rs in tasks
              if who in rs and rs[who].solved and best(rs)]
        return f"{mean(xs):.2f}" if xs else "-"

    def avg(who: str, attr: str) -> str:
        xs = [getattr(rs[who], attr) for rs in tasks if who in rs and rs[who].solved]
        return f"{mean(xs):.0f}" if xs else "-"

    def total(who: str) -> str:
        return f"{sum(rs[who].wall_s for rs in tasks if who in rs):.0f}s"

    def own(who: str) -> str:
        return f"{sum(rs[who].solve_s for rs in tasks if who in rs and rs[who].solved):.1f}s"

    reds = [x for x in map(reduction, tasks) if x is not None]
    return (f"{domain:<11}{count('teleo-fresh'):>7}{count('teleo-learned'):>8}"
            f"{count('teleo-cross'):>7}{count('gbf-hff'):>6}{count('astar-lmcut'):>7}"
            f"{ratio('teleo-fresh'):>7}{ratio('teleo-learned'):>8}"
            f"{avg('teleo-fresh', 'cycles'):>8}{avg('teleo-fresh', 'solving'):>8}"
            f"{avg('teleo-learned', 'solving'):>8}"
            f"{(f'{100 * mean(reds):.0f}%' if reds else '-'):>8}"
            f"{own('teleo-fresh'):>8}{total('teleo-fresh'):>8}{total('gbf-hff'):>9}")


def failures(runs: Iterable[Run], emit: Callable) -> None:
    """Every teleo run that did not solve its task, with its reason; INVALID first."""
    bad = sorted((r for r in runs if r.who.startswith("teleo") and not r.solved),
                 key=lambda r: (r.status != "invalid", r.domain, r.task, r.who))
    if bad:
        emit("\n== teleo runs not solved")
    for r in bad:
        src = f" (skills of {r.source})" if r.source else ""
        claim = "" if not r.claimed else " [its summary claims achieved; " + (
            "the replay cannot read the task]" if r.status == "unchecked" else
            "the replay denies it]")
        emit(f"{r.domain} {r.task} {r.who}{src}: {r.status}{claim}: {r.detail or 'no reason'}")


def targets(grouped: dict[tuple[str, str], dict[str, Run]], limit_s: float,
            emit: Callable) -> list[bool]:
    """Issue 35's targets, each met or NOT MET with the tasks that miss it."""
    emit("\ntargets (issue 35):")
    met: list[bool] = []

    def line(ok: bool, text: str, misses: list[str]) -> None:
        met.append(ok)
        tail = "" if ok or not misses else ": " + ", ".join(misses[:12]) + (
            f" (+{len(misses) - 12} more)" if len(misses) > 12 else "")
        emit(f"  [{'met' if ok else 'NOT MET'}] {text}{tail}")

    domains = sorted({d for d, _ in grouped})
    short = []
    for d in domains:
        tasks = [rs for (dd, _), rs in grouped.items() if dd == d]
        t = sum(rs["teleo-fresh"].solved for rs in tasks if "teleo-fresh" in rs)
        g = sum(rs["gbf-hff"].solved for rs in tasks if "gbf-hff" in rs)
        if t < g:
            short.append(f"{d} ({t} < {g})")
    line(not short, f"within {limit_s:g} s a task, teleo solves at least as many tasks as "
         "gbf+hff in every domain", short)
    long = [f"{d} {t} {w[6:]} x{rs[w].length / best(rs):.2f}"
            for (d, t), rs in sorted(grouped.items())
            for w in ("teleo-fresh", "teleo-learned") if w in rs and rs[w].solved
            and best(rs) and rs[w].length > RATIO * best(rs)]
    line(not long, f"teleo's plans at most {RATIO}x the best plan found", long)
    few = []
    for (d, t), rs in sorted(grouped.items()):
        f, lrn = rs.get("teleo-fresh"), rs.get("teleo-learned")
        if f is None or not f.solved or lrn is None:
            continue
        red = reduction(rs)
        if not lrn.solved:
            few.append(f"{d} {t} (learned run {lrn.status})")
        elif red is not None and red < REDUCTION:
            few.append(f"{d} {t} ({100 * red:.0f}%)")
    line(not few, f"with its own learned skills a task takes at least {100 * REDUCTION:.0f}% "
         "fewer problem-solving cycles", few)
    cross = [f"{d} {t} (skills of {rs['teleo-cross'].source}: {rs['teleo-cross'].status})"
             for (d, t), rs in sorted(grouped.items())
             if "teleo-cross" in rs and "teleo-fresh" in rs and rs["teleo-fresh"].solved
             and not rs["teleo-cross"].solved]
    line(not cross, "skills learned in one task never make another task of the domain "
         "unsolvable", cross)
    teleo = [r for rs in grouped.values() for w, r in rs.items() if w.startswith("teleo")]
    silent = [f"{r.domain} {r.task} {r.who} ({r.status})" for r in teleo
              if r.status in ("failed", "limit", "error") and not r.detail]
    line(not silent, "no run ends with a goal still active and no reason given", silent)
    lies = [f"{r.domain} {r.task} {r.who}: {r.detail}" for r in teleo if r.status == "invalid"]
    line(not lies, "no summary claims a success the independent replay denies", lies)
    unread = [f"{r.domain} {r.task} {r.who}" for r in teleo if r.status == "unchecked"]
    if unread:
        emit(f"  (claimed achieved but not replayed, the replay's parser refusing the task, "
             f"counted unsolved: {', '.join(unread)})")
    killed = [f"{r.domain} {r.task} {r.who}" for r in teleo if r.status == "timeout"]
    if killed:
        emit(f"  (killed at the time limit, counted unsolved: {len(killed)} teleo runs)")
    return met
