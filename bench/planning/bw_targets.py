"""Issue 22's targets for the planning benchmark, each judged on one run's results
(bench/bw_report.Results) and printed as met or NOT MET with the problems (and seeds) that
miss it, so that whoever tunes the solver knows where to look."""

from __future__ import annotations

from bench.planning.bw_report import MAIN, Results, against, detail, listing, mode_runs, name
from bench.planning.bw_teleo import ORDERS


def _line(ok: bool, text: str) -> str:
    return f"  [{'met' if ok else 'NOT MET'}] {text}"


def conjunction_target(res: Results) -> list[str]:
    runs = mode_runs(res, MAIN)
    other = mode_runs(res, "conjunction-bottom-up")
    missed = sorted(k for k, v in runs.items() if not v.solved)
    out = [_line(not missed and bool(runs), f"conjunction solved in 100% of problems within "
                 f"10n + 20 cycles: {len(runs) - len(missed)}/{len(runs)} (its literals "
                 f"given bottom-up instead: {sum(v.solved for v in other.values())}/"
                 f"{len(other)})")]
    out += listing(missed, lambda k: detail(runs[k]))
    up = sorted(k for k, v in other.items() if not v.solved)
    return out + listing(up, lambda k: "given bottom-up: " + detail(other[k]))


def length_targets(res: Results) -> list[str]:
    out = []
    for planner, bound, text in (("astar-lmcut", 1.3, "within 1.3x the optimum (A* LM-cut's)"),
                                 ("gbf-hff", 1.0, "no longer than greedy h_FF's")):
        runs = mode_runs(res, MAIN)
        keys = sorted(runs)
        mine, theirs = against(res, runs, planner, keys)
        over = sorted({k[0] for k in keys
                       if (r := _size_ratio(res, runs, planner, k[0])) is not None
                       and r > bound})
        both = sum(1 for k in keys if runs[k].solved and res.length(k, planner) is not None)
        ok = bool(theirs) and mine <= bound * theirs
        shown = f"{mine / theirs:.2f}x" if theirs else "nothing to compare"
        up = mode_runs(res, "conjunction-bottom-up")
        a, b = against(res, up, planner, sorted(up))
        out.append(_line(ok, f"mean plan length {text}: {shown} over the {both} problems "
                             f"both solved" + (f"; above it at n = {', '.join(map(str, over))}"
                                               if over else "")
                         + (f" (given bottom-up: {a / b:.2f}x)" if b else "")))
    return out


def _size_ratio(res: Results, runs, planner: str, n: int) -> float | None:
    mine, theirs = against(res, runs, planner, res.keys(n))
    return mine / theirs if theirs else None


def list_targets(res: Results) -> list[str]:
    out = []
    for order in ORDERS:
        runs = mode_runs(res, f"list-{order}")
        open_ = sorted(k for k, v in runs.items() if v.unfinished)
        out.append(_line(not open_ and bool(runs),
                         f"priority list ({order}): every goal ends achieved or failed with its "
                         f"reason within the limit: {len(runs) - len(open_)}/{len(runs)} runs"))
        out += listing(open_, lambda k, r=runs: ", ".join(r[k].unfinished[:3])
                       + (f" (+{len(r[k].unfinished) - 3})" if len(r[k].unfinished) > 3
                          else ""))
    return out


def learning_targets(res: Results) -> list[str]:
    keys = sorted(res.fresh)
    lost = [k for k in keys if res.fresh[k].solved and not res.skilled[k].solved]
    fresh = mode_runs(res, MAIN)
    lost_curve = [s.key for s in res.curve if s.key in fresh and fresh[s.key].solved
                  and not s.verdict.solved]
    out = [_line(not lost and not lost_curve,
                 f"learned skills keep every fresh solve: held out {len(lost)} lost of "
                 f"{sum(res.fresh[k].solved for k in keys)}; in the curve {len(lost_curve)} "
                 f"lost of {sum(fresh[s.key].solved for s in res.curve if s.key in fresh)}")]
    out += listing(lost, lambda k: "held out, with skills: " + detail(res.skilled[k]))
    out += listing(lost_curve, lambda k: "in the curve: " + detail(
        next(s.verdict for s in res.curve if s.key == k)))
    for field, cut in (("solving", 0.9), ("cycles", 0.3)):
        was = sum(getattr(res.fresh[k], field) for k in keys)
        now = sum(getattr(res.skilled[k], field) for k in keys)
        got = 1 - now / was if was else 0.0
        what = "problem-solving cycles" if field == "solving" else "total cycles"
        out.append(_line(bool(was) and got >= cut,
                         f"learned skills cut {what} on held-out problems by at least "
                         f"{cut:.0%}: {was} -> {now} ({got:.0%} cut)"))
    return out


STALE = "(it held when the last cycle's decision was taken; that cycle's action undid it)"


def invalid_runs(res: Results) -> list[str]:
    """Every teleo run whose check failed (it counts as not solved); the runs whose summary
    is one cycle behind the world (a goal the last cycle's action undid still shown
    achieved) on one line."""
    found = [(f"{name(k)} {m}", v) for (k, m), v in sorted(res.teleo.items())]
    found += [(f"{name(k)} held out fresh", v) for k, v in sorted(res.fresh.items())]
    found += [(f"{name(k)} held out with skills", v) for k, v in sorted(res.skilled.items())]
    found += [(f"{name(s.key)} curve", s.verdict) for s in res.curve]
    bad = [(who, v.invalid) for who, v in found if v.invalid]
    stale = [who for who, why in bad if why.startswith("the summary says")
             and why.count("the summary says") == 1 and why.endswith(STALE)]
    out = [f"    {who}: {why}" for who, why in bad if who not in stale]
    out += [f"    {name(k)} {p}: {r.detail}" for (k, p), r in sorted(res.plans.items())
            if r.status == "error"]
    if stale:
        out.append(f"    {len(stale)} runs whose summary calls a goal achieved that the last "
                   f"cycle's action undid (a goal given up and redone every cycle): "
                   + ", ".join(stale))
    refused = [(who, v) for who, v in found if v.refused]
    notes = ["", f"runs in which the world refused actions (left out of the replay): "
                 f"{len(refused)}; refused though STRIPS allows them: "
                 f"{sum(v.refused_legal for _, v in refused)}"]
    notes += [f"    {who}: {v.refused} refused, {v.refused_legal} of them allowed by STRIPS"
              for who, v in refused[:12]]
    if len(refused) > 12:
        notes.append(f"    ... and {len(refused) - 12} more")
    head = "runs whose check failed (counted as not solved): " + (str(len(bad) + len(
        [1 for r in res.plans.values() if r.status == "error"])) if out else "none")
    return ["", head, *out, *notes]


def targets(res: Results) -> list[str]:
    return ["", "targets (issue 22):", *conjunction_target(res), *length_targets(res),
            *list_targets(res), *learning_targets(res)]
