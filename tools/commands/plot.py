"""`teleo plot RUN`: a run record drawn as one PNG, over world time [s]:

1. what the domain has to show: its Domain's `plot` hook (world/domain.py; driving, each
   agent's speed and the limit it perceives; blocks, each block's height; office, how far
   each robot has gone); a world without one, nothing here;
2. the domain's counters of violations and of work done (world/domain.py) as they grow;
3. each agent's goals as a timeline, coloured by status;
4. the compute time of every stage per cycle [ms] (a rolling mean), stacked.

matplotlib (Agg, no screen) draws it: axes, ticks, legends and shared time axes for free,
where Pillow, already a dependency, would need a hand-made plotting layer to maintain.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path
from typing import Any

import click

from tools.paths import OutputPath, suffix_check
from tools.records.run_record import RecordError, RunRecord, locate

PLOT_SUFFIXES = (".png", ".svg", ".pdf")
"""What a plot is written as (matplotlib's own backends), by the file's suffix."""
plot_check = suffix_check(PLOT_SUFFIXES, "a plot")
"""The check of a plot's file name for `--plot` and `plot --out` (tools/paths.py)."""

STATUS_COLOURS = {"satisfied": "#3a9a48", "active": "#2f6fd6", "suspended": "#e59a1d",
                  "impasse": "#d23c3c", "failed": "#222222", "pending": "#c9c9c9"}


class Series:
    """The per-cycle data of a record that the panels draw."""

    def __init__(self, rec: RunRecord) -> None:
        states = rec.by_cycle("state")
        self.cycles = sorted(states)
        self.time = {c: float(states[c]["snapshot"].get("time", 0.0)) for c in self.cycles}
        self.snapshots = {c: states[c]["snapshot"] for c in self.cycles}
        self.domain = rec.meta.get("teleo.run", {}).get("domain") or (
            self.snapshots[self.cycles[0]].get("domain", "driving") if self.cycles else "")
        self.agents = rec.agents()
        self.percepts = {a: rec.by_cycle("percepts", a) for a in self.agents}
        self.intentions = {a: rec.by_cycle("intention", a) for a in self.agents}
        self.stats: dict[str, dict[int, float]] = defaultdict(dict)
        from bus.stats import record_stats

        for _, r in rec.records():  # each stage's stats, alone or carried in its output
            for process, cycle, ms, _ in record_stats(r, own=True):
                self.stats[process][cycle] = ms

    def t(self, cycles: list[int]) -> list[float]:
        return [self.time.get(c, 0.0) for c in cycles]


def _domain(s: Series) -> Any:
    """The run's Domain (world/domain.py), or None for a world not installed here (or one that
    fails to load): the plot then has no world panel and shows every counter."""
    from world.domain import get_domain
    from world.errors import ConfigError

    try:
        return get_domain(s.domain)
    except ConfigError:
        return None


def _counters(ax: Any, s: Series) -> bool:
    """The domain's law violations and work done (world/domain.py), as they grow."""
    spec = _domain(s)
    wanted = set(spec.violations + spec.achievements) if spec else None
    rows: dict[str, list[tuple[int, int]]] = defaultdict(list)
    for c in s.cycles:
        for agent, counts in s.snapshots[c].get("counters", {}).items():
            for name, n in counts.items():
                if wanted is None or name in wanted:
                    rows[f"{agent} {name}"].append((c, int(n)))
    shown = {k: v for k, v in rows.items() if any(n for _, n in v)}
    for label, pts in sorted(shown.items()):
        ax.step(s.t([c for c, _ in pts]), [n for _, n in pts], where="post", label=label)
    ax.set_ylabel("count")
    if not shown:
        ax.text(0.5, 0.5, "all counters 0", transform=ax.transAxes, ha="center")
    return True


def _goals(ax: Any, s: Series) -> bool:
    lanes: list[str] = []
    dt = (s.time[s.cycles[1]] - s.time[s.cycles[0]]) if len(s.cycles) > 1 else 0.1
    for agent in s.agents:
        spans: dict[str, list[tuple[float, str]]] = {}
        for c, rec in sorted(s.intentions[agent].items()):
            for g in rec["decision"].get("goals", ()):
                spans.setdefault(f"{agent} {g['id']} {g['goal']}", []).append(
                    (s.time.get(c, c * dt), g["status"]))
        for label, points in spans.items():
            y = len(lanes)
            lanes.append(label)
            for status in STATUS_COLOURS:
                bars = [(t, dt) for t, st in points if st == status]
                if bars:
                    ax.broken_barh(bars, (y - 0.4, 0.8), color=STATUS_COLOURS[status],
                                   linewidth=0)
    ax.set_yticks(range(len(lanes)), lanes, fontsize=7)
    ax.set_ylim(-0.6, max(len(lanes), 1) - 0.4)
    ax.invert_yaxis()
    from matplotlib.patches import Patch

    ax.legend(handles=[Patch(color=c, label=n) for n, c in STATUS_COLOURS.items()],
              fontsize=7, ncol=6, loc="upper center", bbox_to_anchor=(0.5, -0.12))
    return bool(lanes)


def _stages(ax: Any, s: Series) -> bool:
    window = max(1, len(s.cycles) // 100)
    names = sorted(s.stats)
    ys = [_rolling([s.stats[n].get(c, 0.0) for c in s.cycles], window) for n in names]
    if names:
        ax.stackplot(s.t(s.cycles), ys, labels=names)
        totals = sorted(sum(col) for col in zip(*ys, strict=True))
        ax.set_ylim(0, 1.3 * totals[int(0.99 * (len(totals) - 1))] or 1.0)  # no start-up spike
    ax.set_ylabel(f"compute [ms]\n(mean of {window})")
    ax.set_xlabel("world time [s]")
    return bool(names)


def _rolling(values: list[float], window: int) -> list[float]:
    out, total = [], 0.0
    for i, v in enumerate(values):
        total += v - (values[i - window] if i >= window else 0.0)
        out.append(total / min(i + 1, window))
    return out


def plot_record(path: Path, out: Path) -> Path:
    """Draw the record at `path` into `out` (a PNG, SVG or PDF by its suffix); raises
    RecordError."""
    problem = plot_check(out)
    if problem is not None:
        raise RecordError(problem)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rec = RunRecord(path)
    s = Series(rec)
    if not s.cycles:
        raise RecordError(f"{path}: no world state recorded: nothing to plot")
    spec = _domain(s)
    panels = [(spec.plot[1], spec.plot[0])] if spec is not None and spec.plot else []
    panels += [(_counters, "violations and work done"), (_goals, "goal statuses"),
               (_stages, "stage compute time per cycle")]
    n_goals = sum(len({g["id"] for r in i.values() for g in r["decision"].get("goals", ())})
                  for i in s.intentions.values())
    ratios = [3] * (len(panels) - 2) + [max(2, n_goals * 0.35), 3]
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(11, sum(ratios) * 0.9 + 1),
                             gridspec_kw={"height_ratios": ratios}, squeeze=False)
    for ax, (fn, title) in zip(axes[:, 0], panels, strict=True):
        ax.set_title(title, fontsize=9, loc="left")
        ax.grid(alpha=0.3)
        if fn(ax, s) and fn is not _goals and ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="upper left")
    fig.suptitle(f"run {rec.run}: {len(s.cycles)} cycles, {s.domain}", fontsize=11)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return out


def plot_command_output(run: str | Path, out: Path) -> str:
    """Plot a run for `--plot` of launch and simulate; the line to print."""
    try:
        return f"plot written to {plot_record(locate(run), out)}"
    except RecordError as exc:
        return f"no plot: {exc}"


@click.command()
@click.argument("run", metavar="RUN")
@click.option("--out", type=OutputPath(plot_check, path_type=Path), default=None,
              help="PNG (or .svg, .pdf) to write (default: plot.png beside the record).")
def plot(run: str, out: Path | None) -> None:
    """Plot a run record: speed and limit (driving), counters, goal timeline, stage times."""
    try:
        path = locate(run)
        click.echo(f"plot written to {plot_record(path, out or path.with_name('plot.png'))}")
    except RecordError as exc:
        raise click.ClickException(str(exc)) from exc


commands = [plot]
