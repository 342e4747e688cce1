"""The tables and targets bench/planning/planning.py prints, from the results of one run. Every
ratio is of figures measured in that run: plan lengths on the problems both sides solved, times of
the same problems on the same machine at the same time."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from bench.planning.bw_check import Verdict
from bench.planning.bw_pyperplan import PlanResult
from bench.planning.bw_tasks import CurveStep, Key
from bench.planning.bw_teleo import ORDERS, cycle_limit

MAIN = "conjunction-listed"
"""The goal as the benchmark states it: one conjunction, in the order IPC lists it."""


@dataclass
class Results:
    """Everything one run measured, by problem (n, seed)."""

    sizes: list[int]
    seeds: list[int]
    held_out: list[int]
    plans: dict[tuple[Key, str], PlanResult] = field(default_factory=dict)
    skipped: dict[tuple[int, str], str] = field(default_factory=dict)
    teleo: dict[tuple[Key, str], Verdict] = field(default_factory=dict)
    curve: list[CurveStep] = field(default_factory=list)
    fresh: dict[Key, Verdict] = field(default_factory=dict)
    skilled: dict[Key, Verdict] = field(default_factory=dict)

    def keys(self, n: int) -> list[Key]:
        return [(n, s) for s in self.seeds]

    def length(self, key: Key, planner: str) -> int | None:
        r = self.plans.get((key, planner))
        return r.length if r is not None and r.solved else None


def name(key: Key) -> str:
    return f"bw-{key[0]}-{key[1]}"


def ratio(a: float, b: float, digits: int = 2) -> str:
    return f"{a / b:.{digits}f}" if b else "-"


def mean(values: list[float], digits: int = 1) -> str:
    return f"{sum(values) / len(values):.{digits}f}" if values else "-"


def against(res: Results, runs: dict[Key, Verdict], planner: str,
            keys: list[Key]) -> tuple[int, int]:
    """(teleo's actions, the planner's) summed over ``keys`` both solved."""
    both = [(runs[k].actions, res.length(k, planner)) for k in keys
            if k in runs and runs[k].solved and res.length(k, planner) is not None]
    return sum(a for a, _ in both), sum(b for _, b in both)


def solved_text(verdicts: list[Verdict]) -> str:
    bad = sum(bool(v.invalid) for v in verdicts)
    return f"{sum(v.solved for v in verdicts)}/{len(verdicts)}" + (f"!{bad}" if bad else "")


def planner_cell(res: Results, n: int, planner: str) -> str:
    if (n, planner) in res.skipped:
        return "skip"
    got = [res.plans[(k, planner)] for k in res.keys(n) if (k, planner) in res.plans]
    return f"{sum(r.solved for r in got)}/{len(got)}"


def mode_runs(res: Results, mode: str) -> dict[Key, Verdict]:
    return {k: v for (k, m), v in res.teleo.items() if m == mode}


def table(title: str, header: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h)
              for i, h in enumerate(header)]
    line = lambda cells: "  ".join(c.rjust(w) for c, w in zip(cells, widths, strict=True))  # noqa: E731
    return ["", title, line(header), *(line(r) for r in rows)]


def conjunction_table(res: Results) -> list[str]:
    runs = mode_runs(res, MAIN)
    rows = []
    for n in res.sizes:
        keys, vs = res.keys(n), [runs[k] for k in res.keys(n) if k in runs]
        ok = [v for v in vs if v.solved]
        t_teleo, t_gbf = _times(res, runs, keys)
        rows.append([str(n), str(cycle_limit(n)), planner_cell(res, n, "gbf-hff"),
                     planner_cell(res, n, "astar-lmcut"), solved_text(vs),
                     mean([v.cycles for v in ok]), mean([v.idle for v in vs]),
                     mean([v.solving for v in vs]), mean([v.pushes for v in vs]),
                     mean([v.backtracks for v in vs]),
                     ratio(*against(res, runs, "astar-lmcut", keys)),
                     ratio(*against(res, runs, "gbf-hff", keys)),
                     mean([v.wall_s for v in vs], 2), ratio(t_teleo, t_gbf)])
    return table("conjunction (one goal for the whole goal, its literals as IPC lists them) "
                 "against pyperplan; per n, over the seeds; solved k/S!j: j runs failed the "
                 "check; cycles: mean over the solved runs, idle (cycles without an action "
                 "before the goal held), solving (cycles of problem solving), pushes "
                 "(chaining decisions), backtracks: means over all",
                 ["n", "limit", "gbf", "A*", "teleo", "cycles", "idle", "solving", "pushes",
                  "backtr", "len/opt", "len/gbf", "teleo s", "s/gbf"], rows)


def _times(res: Results, runs: dict[Key, Verdict], keys: list[Key]) -> tuple[float, float]:
    both = [k for k in keys if k in runs and runs[k].solved
            and res.length(k, "gbf-hff") is not None]
    return (sum(runs[k].wall_s for k in both),
            sum(res.plans[(k, "gbf-hff")].wall_s for k in both))


def orders_table(res: Results, form: str) -> list[str]:
    """Both orders of one goal form side by side."""
    rows = []
    for n in res.sizes:
        row = [str(n)]
        for order in ORDERS:
            runs = mode_runs(res, f"{form}-{order}")
            keys = res.keys(n)
            vs = [runs[k] for k in keys if k in runs]
            row += [solved_text(vs), mean([v.cycles for v in vs if v.solved]),
                    ratio(*against(res, runs, "astar-lmcut", keys)),
                    ratio(*against(res, runs, "gbf-hff", keys)),
                    f"{sum(not v.unfinished for v in vs)}/{len(vs)}",
                    str(sum(len(v.unfinished) for v in vs))]
        rows.append(row)
    head = ["solved", "cycles", "len/opt", "len/gbf", "ended", "open"]
    what = {"conjunction": "conjunction, one user goal",
            "list": "priority list, one user goal per literal"}[form]
    return table(f"{what}: listed (each tower top-down, as IPC lists them) | bottom-up' (each "
                 f"tower from its base); ended: runs whose every goal ended achieved or failed "
                 f"with a reason; open: goals still pending/active/impasse at the limit",
                 ["n", *head, *(f"{h}'" for h in head)], rows)


def curve_table(res: Results) -> list[str]:
    fresh = mode_runs(res, MAIN)
    rows = []
    for n in res.sizes:
        steps = [s for s in res.curve if s.key[0] == n]
        if not steps:
            continue
        now = [s.verdict for s in steps]
        was = [fresh[s.key] for s in steps if s.key in fresh]
        rows.append([str(n), solved_text(was), solved_text(now),
                     *(f"{sum(f(v) for v in was)}>{sum(f(v) for v in now)}"
                       for f in (_solving, _cycles, _actions)),
                     str(steps[-1].skills), str(sum(s.dropped for s in steps))])
    return table("learning curve: the conjunction problems in order (n up, seeds up), each "
                 "from the skills the ones before it learned; fresh>carried, summed over "
                 "the seeds", ["n", "fresh", "carried", "solving", "cycles", "actions",
                               "skills", "left out"], rows)


def _solving(v: Verdict) -> int:
    return v.solving


def _cycles(v: Verdict) -> int:
    return v.cycles


def _actions(v: Verdict) -> int:
    return v.actions


def held_out_table(res: Results) -> list[str]:
    rows = []
    for n in res.sizes:
        keys = [(n, s) for s in res.held_out if (n, s) in res.fresh]
        was = [res.fresh[k] for k in keys]
        now = [res.skilled[k] for k in keys if k in res.skilled]
        kept = [k for k in keys if res.fresh[k].solved]
        rows.append([str(n), solved_text(was), solved_text(now),
                     *(f"{sum(f(v) for v in was)}>{sum(f(v) for v in now)}"
                       for f in (_solving, _cycles, _actions)),
                     f"{sum(res.skilled[k].solved for k in kept if k in res.skilled)}"
                     f"/{len(kept)}"])
    return table("held-out problems (seeds " + ",".join(map(str, res.held_out)) + "), the "
                 "conjunction, fresh>with the curve's final skills, summed",
                 ["n", "fresh", "skills", "solving", "cycles", "actions", "kept"], rows)


def detail(v: Verdict) -> str:
    """Why a run is not solved, in one line."""
    if v.invalid:
        return f"CHECK FAILED: {v.invalid}"
    notes = [f"{g} {s}" + (f" ({note[:240]})" if note else "") for g, s, note in v.ended
             if s != "achieved"]
    return f"{v.actions} actions; " + ("; ".join(notes[:2]) or "no goal open")


def listing(keys: list[Key], why: Callable[[Key], str], most: int = 12) -> list[str]:
    out = [f"    {name(k)}: {why(k)}" for k in keys[:most]]
    if len(keys) > most:
        out.append(f"    ... and {len(keys) - most} more: "
                   + " ".join(name(k) for k in keys[most:]))
    return out
