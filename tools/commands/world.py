"""`teleo render`: draw a run of the driving world to a PNG (one cycle) or an animated GIF.

Sources: a run's `snapshots.jsonl` (one snapshot dict a line, as the world process saves them),
a `.json` file (one snapshot dict or a list of them), a run record (the record.mcap of a
launch, a simulate or `teleo record`: its world states), or a scenario `.toml`: its world as
the scenario starts it, at cycle 0, so that every line of the picture's caption is true (no
agent has run: a robot "idle" and "travelled 0.0 m" at cycle 100 would say it idled for
50 s); `--steps N` steps the world N cycles without its agents (traffic and
pedestrians move, the agents' cars and robots stand), and the command's line says so.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

from tools.paths import OutputPath, picture_check
from tools.records.run_record import RecordError, locate
from world.domain import DEFAULT_DOMAIN, domain_of, get_domain
from world.driving.render import agent_trail, render_gif, render_png
from world.driving.snapshot import WorldSnapshot
from world.errors import WorldError
from world.pictures import is_animation
from world.scenario_paths import world_files
from world.toml_text import read_toml

_POSITIVE = click.FloatRange(min=0, min_open=True)  # --scale [px/m], --follow [m]
MAX_SNAPSHOT_CHARS = 256 << 20
"""[characters] of a snapshots file `teleo render` reads (a day-long run's is ~100 MB)."""


def _from_json(path: Path) -> list[dict[str, Any]]:
    from agents.lang import LangError
    from agents.lang.core.limits import read_json

    text = path.read_bytes()[:MAX_SNAPSHOT_CHARS + 1].decode("utf-8", errors="replace")
    try:
        if path.suffix == ".jsonl":
            rows = [read_json(line, f"{path}:{n}", max_chars=MAX_SNAPSHOT_CHARS,
                              max_string=1 << 20)
                    for n, line in enumerate(text.splitlines(), 1) if line.strip()]
        else:
            data = read_json(text, str(path), max_chars=MAX_SNAPSHOT_CHARS, max_string=1 << 20)
            rows = data if isinstance(data, list) else [data]
    except LangError as exc:
        raise click.ClickException(str(exc)) from None
    return [r.get("snapshot", r) if isinstance(r, dict) else r for r in rows]


def _check_rows(source: Path, rows: list) -> None:
    """Refuse rows that are not world snapshots, saying what the file seems to be."""
    for n, row in enumerate(rows, 1):
        if isinstance(row, dict) and {"cycle", "time", "counters"} <= set(row):
            continue
        hint = ""
        if isinstance(row, dict) and "digest" in row:
            hint = ("; it is a run's trace: draw the snapshots.jsonl beside it, or the run "
                    "record")
        raise click.ClickException(
            f"{source}: item {n} is not a world snapshot (expected an object with cycle, time "
            f"and counters, as in a run's snapshots.jsonl){hint}")


def _from_recording(path: Path) -> list[dict[str, Any]]:
    """The world snapshots of a run record (tools/records/run_record.py: an .mcap file)."""
    from tools.records.run_record import RecordError, RunRecord

    try:
        return [r["snapshot"] for _, r in RunRecord(path).kinds("state")]
    except RecordError as exc:
        raise click.ClickException(str(exc)) from exc


def _from_scenario(path: Path, steps: int, seed: int | None) -> list[dict[str, Any]]:
    """A scenario's world simulated for `steps` cycles with idle agents (a scenario may hold
    only its [world] table: the agents are then its cars, or ME)."""
    try:
        doc = read_toml(path)
    except WorldError as exc:
        raise click.ClickException(str(exc)) from None
    table = dict(doc.get("world", {}) if isinstance(doc.get("world"), dict) else {})
    domain = get_domain(str(table.pop("domain", DEFAULT_DOMAIN)))
    table = world_files(table, path)
    agents = [a.get("id") for a in doc.get("agents", []) if isinstance(a, dict)]
    agents = agents or [c.get("agent") for c in table.get("cars", [])] or ["ME"]
    run = doc.get("run") if isinstance(doc.get("run"), dict) else {}
    run_seed = run.get("seed", 1) if isinstance(run.get("seed"), int) else 1
    world = domain.create(table, run_seed if seed is None else seed, agents)
    snaps = [world.snapshot_dict()]
    for _ in range(steps):
        world.step()
        snaps.append(world.snapshot_dict())
    return snaps


def load_snapshots(source: Path, steps: int = 100, seed: int | None = None) -> list[dict]:
    """The snapshot dicts of a source file (see the module doc), in cycle order."""
    if source.suffix == ".toml":
        return _from_scenario(source, steps, seed)
    rows = _from_json(source) if source.suffix in (".json", ".jsonl") else _from_recording(source)
    _check_rows(source, rows)
    return sorted(rows, key=lambda s: s.get("cycle", 0) if isinstance(s, dict) else 0)


@click.command()
@click.argument("source", metavar="SOURCE", type=click.Path(path_type=Path))
@click.option("--out", "out", required=True, type=OutputPath(picture_check, path_type=Path),
              help="FILE.png or FILE.jpg (one cycle) or FILE.gif (the whole run).")
@click.option("--agent", default=None, help="Whose car, range and counters to show.")
@click.option("--cycle", "cycle", type=click.IntRange(min=0), default=None,
              help="PNG: the cycle to draw (default: the last).")
@click.option("--every", type=click.IntRange(min=1), default=1, show_default=True,
              help="GIF: use every N-th snapshot.")
@click.option("--scale", type=_POSITIVE, default=None, help="Pixels per metre.")
@click.option("--follow", type=_POSITIVE, default=None,
              help="Draw only a square of this side [m] that follows the agent's car.")
@click.option("--steps", type=click.IntRange(min=0), default=0, show_default=True,
              help="Scenario source: cycles to step its world without its agents "
                   "(0: the world as the scenario starts it).")
@click.option("--seed", type=int, default=None,
              help="Scenario source: seed (default: the scenario's).")
def render(source: Path, out: Path, agent: str | None, cycle: int | None, every: int,
           scale: float | None, follow: float | None, steps: int, seed: int | None) -> None:
    """Draw a run or a scenario to a PNG, JPEG or GIF.

    SOURCE: a run's snapshots (.jsonl/.json), a run record (an .mcap, a run folder or a
    run id, as `teleo explain` takes), or a scenario .toml (its world at cycle 0, or after
    --steps cycles without its agents, with its own seed)."""
    if not source.is_file():
        try:
            source = locate(source)
        except RecordError as exc:
            raise click.ClickException(str(exc)) from None
    try:
        rows = load_snapshots(source, steps, seed)
        if not rows:
            raise click.ClickException(f"{source}: no world snapshots in it")
        out.parent.mkdir(parents=True, exist_ok=True)
        domain = domain_of(rows[0])
        if domain.name != "driving":
            upto = [r for r in rows if cycle is None or r.get("cycle", 0) <= cycle]
            frames = domain.render(upto, out, agent)
            click.echo(f"{out}: {frames} frame(s){_world_only(source, rows)}")
            return
        snaps = [WorldSnapshot.from_dict(r) for r in rows]
        if is_animation(out):
            render_gif(snaps, out, agent=agent, every=max(1, every),
                       px_per_m=scale or (4.0 if follow else 1.5), follow=follow)
            click.echo(f"{out}: {len(snaps[::max(1, every)])} frame(s), cycles "
                       f"{snaps[0].cycle}..{snaps[-1].cycle}{_world_only(source, rows)}")
            return
        chosen = snaps[-1] if cycle is None else next(
            (s for s in snaps if s.cycle == cycle), None)
        if chosen is None:
            raise click.ClickException(f"{source}: no snapshot of cycle {cycle}; have "
                                       f"{snaps[0].cycle}..{snaps[-1].cycle}")
        upto = [s for s in snaps if s.cycle <= chosen.cycle]
        render_png(chosen, out, agent=agent, px_per_m=scale or (6.0 if follow else 3.0),
                   trail=agent_trail(upto, agent), follow=follow)
        click.echo(f"{out}: cycle {chosen.cycle}{_world_only(source, rows)}")
    except (WorldError, ValueError, OSError) as exc:
        raise click.ClickException(str(exc)) from exc


def _world_only(source: Path, rows: list[dict[str, Any]]) -> str:
    """What the line of a scenario's picture adds: that no agent ran in it."""
    if source.suffix != ".toml":
        return ""
    last = rows[-1].get("cycle", 0) if rows else 0
    return (" (the scenario's world as it starts; no agent has run)" if not last else
            f" (the world stepped {last} cycles without its agents: they stood still)")


commands = [render]
