"""Benchmark: teleo's means-ends problem solver and skill learner (seed 000, "Problem Solving and
Skill Learning") on the IPC tasks of blocks, gripper, logistics, miconic and movie (issue 35;
bench/ipc/suites, as distributed with pyperplan), beside pyperplan in the same run with the
same time limit.

Per domain and task: pyperplan's gbf+hff and astar+lmcut (`python -m pyperplan`); teleo fresh
(`teleo solve DOMAIN PROBLEM --json`, the program generated from the domain, no skills but its
operators); teleo again with the skills that run learned (``learned``: the same task, for the
problem-solving cycles saved); and teleo with the skills learned on another task of the domain
(``cross``: task k with those of the task before it in the list, the first with those of the
second), which must not make it unsolvable. Every run is a subprocess killed at the time limit.
Every plan is replayed under PDDL semantics by bench/ipc/strips.py (pyperplan's parser, none of
the world's code): a teleo run whose summary says achieved and whose plan the replay denies is
INVALID, counted unsolved and printed.

Prints per domain a row per task and a summary row (solved counts, plan length against the
best plan found, cycles, problem-solving cycles fresh and learned, their reduction, time),
the teleo runs not solved with their reasons, then issue 35's targets met or NOT MET with the
tasks that miss them.

Other suites (domains teleo was not tuned on, e.g. the rest of pyperplan's benchmarks/):
``--suites DIR`` takes every folder of DIR holding a ``domain.pddl`` (or a ``domainNN.pddl``
per task, as airport's) and ``taskNN.pddl`` files; ``--planners gbf-hff`` and ``--no-learned``
leave out runs to save time.

Run: .venv/bin/python bench/ipc/ipc.py [--suites DIR] [--domains blocks,gripper,...]
     [--tasks 1-10] [--limit 60] [--jobs 2] [--planners gbf-hff,astar-lmcut] [--no-learned]
     [--no-cross] [--keep DIR] [--quick]
"""

from __future__ import annotations

import datetime
import os
import platform
import shlex
import sys
import tempfile
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from importlib.metadata import version
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from bench.ipc import report  # noqa: E402
from bench.ipc.runs import PLANNERS, Run, run_pyperplan, run_teleo  # noqa: E402
from bench.planning.planning import numbers  # noqa: E402

SUITES = Path(__file__).resolve().parent / "suites"
DOMAINS = ("blocks", "gripper", "logistics", "miconic", "movie")
FULL = {"domains": ",".join(DOMAINS), "tasks": "1-10", "limit": 60.0}
QUICK = {"domains": "blocks,gripper,movie", "tasks": "1-2", "limit": 20.0}


def domain_file(suites: Path, domain: str, task: int) -> Path:
    """The domain file of task ``task``: ``domainNN.pddl`` where the suite has one per task,
    else ``domain.pddl``."""
    own = suites / domain / f"domain{task:02d}.pddl"
    return own if own.exists() else suites / domain / "domain.pddl"


def suite_names(suites: Path) -> list[str]:
    """The folders of ``suites`` that hold a suite (a domain file and task files)."""
    return sorted(p.name for p in suites.iterdir() if p.is_dir() and any(p.glob("task*.pddl"))
                  and any(p.glob("domain*.pddl")))


def plan_jobs(domains: list[str], tasks: list[int], limit: float, folder: str, cross: bool,
              cycles: int, suites: Path = SUITES, planners: tuple[str, ...] = tuple(PLANNERS),
              learned: bool = True) -> list[tuple]:
    """(tag, needs, fn, args) for every run; ``needs``: the tag whose learned skills it takes."""
    jobs = []
    for d in domains:
        have = [t for t in tasks if (suites / d / f"task{t:02d}.pddl").exists()
                and domain_file(suites, d, t).exists()]
        for i, t in enumerate(have):
            name, prob = f"task{t:02d}", str(suites / d / f"task{t:02d}.pddl")
            dom = str(domain_file(suites, d, t))
            for planner in planners:
                jobs.append(((d, name, planner), None, run_pyperplan,
                             (d, name, dom, prob, planner, limit, folder)))
            jobs.append(((d, name, "teleo-fresh"), None, run_teleo,
                         (d, name, dom, prob, limit, folder, "teleo-fresh", "", "", cycles)))
            if learned:
                jobs.append(((d, name, "teleo-learned"), (d, name, "teleo-fresh"), run_teleo,
                             (d, name, dom, prob, limit, folder, "teleo-learned", None, "",
                              cycles)))
            if cross and len(have) > 1:
                src = f"task{have[i - 1 if i else 1]:02d}"
                jobs.append(((d, name, "teleo-cross"), (d, src, "teleo-fresh"), run_teleo,
                             (d, name, dom, prob, limit, folder, "teleo-cross", None, src,
                              cycles)))
    return jobs


def run_all(jobs: list[tuple], workers: int, say) -> list[Run]:
    """Run ``jobs`` on a pool of ``workers``, each once the run it needs is done (a run whose
    source learned no file runs with no skills: its fresh run's figures are the source's)."""
    done: dict[tuple, Run] = {}
    waiting = list(jobs)
    with ProcessPoolExecutor(workers) as pool:
        running: dict = {}
        while waiting or running:
            for job in list(waiting):
                if len(running) >= workers:
                    break
                tag, need, fn, args = job
                if need is not None and need not in done:
                    continue
                if need is not None:
                    args = tuple(done[need].learned if a is None else a for a in args)
                waiting.remove(job)
                running[pool.submit(fn, *args)] = tag
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for fut in finished:
                tag = running.pop(fut)
                done[tag] = r = fut.result()
                say(f"  {' '.join(tag)}: {r.status} {r.length or ''}".rstrip())
    return list(done.values())


@click.command(context_settings={"help_option_names": ["-h", "--help"]})
@click.option("--suites", type=click.Path(exists=True, file_okay=False, path_type=Path),
              default=None, help="A folder of suites (one folder per domain: domain.pddl or "
                                 "domainNN.pddl, taskNN.pddl) [bench/ipc/suites].")
@click.option("--domains", default=None,
              help=f"Comma-separated domains of the suites [{','.join(DOMAINS)}; with "
                   "--suites, all of its].")
@click.option("--tasks", default=None, help="Task numbers, e.g. 1-10,12 [1-10].")
@click.option("--limit", type=click.FloatRange(min=1), default=None,
              help="Time limit per run [s] [60].")
@click.option("--cycles", type=click.IntRange(min=0), default=0,
              help="teleo's cycle limit per run (0: teleo solve's default).")
@click.option("--jobs", type=click.IntRange(1, 2), default=2, show_default=True,
              help="Runs at a time (the machine has 2 cores).")
@click.option("--planners", default=",".join(PLANNERS), show_default=True,
              help="Comma-separated pyperplan configurations to run beside teleo (none: '').")
@click.option("--learned/--no-learned", default=True, show_default=True,
              help="Also run each task again with the skills it learned.")
@click.option("--cross/--no-cross", default=True, show_default=True,
              help="Also run each task with the skills learned on another.")
@click.option("--keep", type=click.Path(file_okay=False), default=None,
              help="Keep the runs' files (learned skills, plans) in this folder.")
@click.option("--quick", is_flag=True,
              help=f"About a minute: domains {QUICK['domains']}, tasks {QUICK['tasks']}, "
                   f"limit {QUICK['limit']:g} s (each unless given).")
def main(suites: Path | None, domains: str | None, tasks: str | None, limit: float | None,
         cycles: int, jobs: int, planners: str, learned: bool, cross: bool, keep: str | None,
         quick: bool) -> None:
    """Run teleo and pyperplan on the IPC suites and print the figures and targets."""
    base = QUICK if quick else FULL
    known = suite_names(suites) if suites else list(DOMAINS)
    suites = suites or SUITES
    if not known:
        raise click.BadParameter(f"{suites} holds no suite (a folder with domain*.pddl and "
                                 "task*.pddl files)", param_hint="--suites")
    domains = domains or (",".join(known) if suites != SUITES else str(base["domains"]))
    chosen_planners = tuple(p.strip() for p in planners.split(",") if p.strip())
    bad = [p for p in chosen_planners if p not in PLANNERS]
    if bad:
        raise click.BadParameter(f"no planner {', '.join(bad)}; expected some of "
                                 f"{', '.join(PLANNERS)}", param_hint="--planners")
    tasks = tasks or str(base["tasks"])
    limit = float(limit or base["limit"])
    chosen = [d.strip() for d in domains.split(",") if d.strip()]
    unknown = [d for d in chosen if d not in known]
    if unknown or not chosen:
        raise click.BadParameter(f"no suite {', '.join(unknown) or '(none given)'}; expected "
                                 f"some of {', '.join(known)}", param_hint="--domains")
    numbers_ = numbers(tasks, "--tasks", 1, 99)
    folder = keep or tempfile.mkdtemp(prefix="teleo-ipc-")
    Path(folder).mkdir(parents=True, exist_ok=True)
    echo = click.echo
    echo(f"IPC suites (issue 35): {', '.join(chosen)}; tasks {tasks}; limit {limit:g} s a run; "
         f"{jobs} at a time")
    echo(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python "
         f"{platform.python_version()}, pyperplan {version('pyperplan')}; "
         f"{datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC")
    echo("command: " + shlex.join([".venv/bin/python", "bench/ipc/ipc.py", *sys.argv[1:]]))
    runs = run_all(plan_jobs(chosen, numbers_, limit, folder, cross, cycles, suites,
                             chosen_planners, learned), jobs,
                   lambda s: click.echo(s, err=True))
    grouped = report.by_task(runs)
    for d in chosen:
        report.task_table(d, {t: rs for (dd, t), rs in grouped.items() if dd == d}, echo)
    report.summary(grouped, echo)
    report.failures(runs, echo)
    report.targets(grouped, limit, echo)
    if keep:
        echo(f"files kept in {folder}")


if __name__ == "__main__":
    main()
