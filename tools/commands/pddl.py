"""`teleo pddl program DOMAIN.pddl [--problem P] [--extra F] [--out F]`: the teleo program of a
PDDL domain (world/pddl/program.py, docs/pddl.md): a primitive concept per predicate, a
primitive skill per operator and add effect; with a problem, its goal as the program's one
conjunctive goal; with `--extra`, a file of the user's own concepts and skills appended."""

from __future__ import annotations

from pathlib import Path

import click

from tools.paths import OutputPath
from world.errors import WorldError


def generated(domain: Path, problem: Path | None = None, extra: Path | None = None) -> str:
    """The program text (raises ClickException naming the file for bad input)."""
    from world.pddl.files import load_domain, load_task
    from world.pddl.program import program_text

    try:
        task = load_task(domain, problem) if problem else None
        model = task.domain if task else load_domain(domain)
        text = extra.read_text() if extra else ""
    except WorldError as exc:
        raise click.ClickException(str(exc)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise click.ClickException(f"{extra}: cannot read the file: {exc}") from None
    return program_text(model, task, text, str(domain))


@click.group("pddl")
def pddl_group() -> None:
    """PDDL domains as teleo programs (docs/pddl.md)."""


@pddl_group.command("program")
@click.argument("domain", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--problem", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=None, help="Add this problem's goal as the program's goal.")
@click.option("--extra", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=None, help="Append this file of your own concepts and skills.")
@click.option("--out", type=OutputPath(path_type=Path), default=None,
              help="Write the program here (default: standard output).")
def program_command(domain: Path, problem: Path | None, extra: Path | None,
                    out: Path | None) -> None:
    """Write the teleo program of DOMAIN (a PDDL domain file)."""
    text = generated(domain, problem, extra)
    if out is None:
        click.echo(text, nl=False)
        return
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    click.echo(f"program written to {out}", err=True)


commands = [pddl_group]
