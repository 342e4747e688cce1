"""Lay out IPC domains of Fast Downward's benchmark collection (github.com/aibasel/
downward-benchmarks: one folder a domain, ``domain.pddl`` or a domain file per problem, and
problems named ``p01.pddl``, ``probBLOCKS-4-0.pddl`` ...) as bench/ipc/ipc.py's ``--suites``
reads them: ``OUT/DOMAIN/taskNN.pddl`` with ``domain.pddl`` or ``domainNN.pddl``, the first
N problems in name order.

    git clone https://github.com/aibasel/downward-benchmarks /tmp/downward-benchmarks
    .venv/bin/python bench/ipc/downward_layout.py /tmp/downward-benchmarks /tmp/ipc-downward \\
        --domains driverlog,storage,visitall-sat11-strips --tasks 3
    .venv/bin/python bench/ipc/ipc.py --suites /tmp/ipc-downward --tasks 1-3 --limit 20 \\
        --jobs 1 --planners '' --no-learned --no-cross
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import click


def domain_of(folder: Path, problem: Path) -> Path | None:
    """The domain file of ``problem``: the folder's ``domain.pddl``, else the one whose name
    carries the problem's (``domain_p01.pddl``, ``p01-domain.pddl``)."""
    if (folder / "domain.pddl").exists():
        return folder / "domain.pddl"
    stem = problem.stem
    for name in (f"domain_{stem}.pddl", f"{stem}-domain.pddl", f"domain-{stem}.pddl"):
        if (folder / name).exists():
            return folder / name
    return None


def lay_out(source: Path, out: Path, domain: str, tasks: int) -> int:
    """Copy ``tasks`` problems of ``domain`` (and their domain files); the number copied."""
    folder = source / domain
    problems = sorted(p for p in folder.glob("*.pddl") if "domain" not in p.name)[:tasks]
    target = out / domain
    target.mkdir(parents=True, exist_ok=True)
    done = 0
    for k, problem in enumerate(problems, 1):
        dom = domain_of(folder, problem)
        if dom is None:
            continue
        shutil.copyfile(problem, target / f"task{k:02d}.pddl")
        own = "domain.pddl" if dom.name == "domain.pddl" else f"domain{k:02d}.pddl"
        shutil.copyfile(dom, target / own)
        done += 1
    return done


@click.command()
@click.argument("source", type=click.Path(exists=True, file_okay=False, path_type=Path))
@click.argument("out", type=click.Path(file_okay=False, path_type=Path))
@click.option("--domains", required=True, help="Comma-separated folder names of SOURCE.")
@click.option("--tasks", default=3, show_default=True, help="Problems per domain.")
def main(source: Path, out: Path, domains: str, tasks: int) -> None:
    """Lay out DOMAINS of SOURCE (a downward-benchmarks checkout) under OUT."""
    for domain in [d for d in domains.split(",") if d]:
        if not (source / domain).is_dir():
            raise click.UsageError(f"--domains: {domain}: no such folder in {source}")
        n = lay_out(source, out, domain, tasks)
        click.echo(f"{domain}: {n} task(s)")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
