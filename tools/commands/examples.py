"""`teleo examples DEST`: the shipped programs, scenarios and tutorial files, copied into DEST;
and the shipped scenarios by name (`teleo simulate blocks_figure3`).

The examples are the repository's programs/ and scenarios/, and the files the tutorial
(docs/tutorial.md) writes, one per named block (```tlp cruise.tlp). A wheel carries them as
the package teleo_examples, laid out as in the repository (setup.py says why); in a checkout
or an editable install they are read from the repository itself. DEST gets programs/,
scenarios/ and tutorial/, so every scenario finds its `programs/x.tlp` there as it does in the
repository. A file already in DEST is left alone, and the command refused before anything is
written, unless `--force`.

A scenario argument of `teleo launch`, `simulate` and `check` that is no file, and has no
folder in it, is looked up among the shipped scenarios by its name (with or without .toml);
an unknown name is one line naming the nearest shipped ones.
"""

from __future__ import annotations

import difflib
import importlib.util
import json
import re
from pathlib import Path
from typing import Any

import click

_CHECKOUT = Path(__file__).resolve().parents[2]
FENCE = re.compile(r"^```([^\n]*)\n(.*?)^```$", re.M | re.S)
"""A fenced block of the tutorial: its info line ("tlp cruise.tlp") and its body."""


class ExamplesError(click.ClickException):
    """The examples cannot be found or copied, or a scenario name is unknown (one line)."""


def examples_root() -> Path:
    """The folder holding programs/, scenarios/ and the tutorial: the checkout this code runs
    from, else the installed package teleo_examples."""
    if (_CHECKOUT / "scenarios").is_dir() and (_CHECKOUT / "docs" / "tutorial.md").is_file():
        return _CHECKOUT
    spec = importlib.util.find_spec("teleo_examples")
    if spec is None or not spec.submodule_search_locations:
        raise ExamplesError("teleo examples: no shipped examples found (neither a checkout's "
                            "scenarios/ nor the package teleo_examples); reinstall teleo")
    return Path(next(iter(spec.submodule_search_locations)))


def _tutorial_md(root: Path) -> Path:
    return root / "tutorial.md" if (root / "tutorial.md").is_file() else \
        root / "docs" / "tutorial.md"


def shipped_scenarios() -> dict[str, Path]:
    """Each shipped scenario's name (its file name without .toml) and file."""
    return {p.stem: p for p in sorted((examples_root() / "scenarios").glob("*.toml"))}


def scenario_path(text: str) -> str:
    """``text`` as given when it is a file or names a folder; else the shipped scenario it
    names (`blocks_figure3` or `blocks_figure3.toml`); ExamplesError (one line, the nearest
    names) when there is none."""
    path = Path(text)
    if path.exists() or len(path.parts) != 1 or path.suffix not in ("", ".toml"):
        return text
    shipped = shipped_scenarios()
    name = path.stem if path.suffix == ".toml" else text
    if name in shipped:
        return str(shipped[name])
    near = difflib.get_close_matches(name, list(shipped), n=4, cutoff=0.5)
    hint = f"; near: {', '.join(near)}" if near else \
        f"; shipped: {', '.join(list(shipped)[:6])}, ..."
    raise ExamplesError(f"scenario {text}: no such file nor shipped scenario{hint} "
                        f"(teleo examples DEST copies them all)")


class ScenarioArg(click.ParamType):
    """A scenario argument: a file, or a shipped scenario's name (``scenario_path``)."""

    name = "scenario"

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> str:
        if Path(str(value)).is_dir():
            self.fail(f"{value} is a folder, not a scenario file", param, ctx)
        return scenario_path(str(value))


def tutorial_files(markdown: str) -> dict[str, str]:
    """The files the tutorial writes: each named block's name and text (a later block of
    the same name wins, as when the tutorial is followed)."""
    files = {}
    for info, body in FENCE.findall(markdown):
        words = info.split()
        if len(words) > 1:
            files[words[1]] = body.rstrip("\n") + "\n"
    return files


def example_files() -> dict[str, bytes]:
    """Every example: its path under DEST (programs/..., scenarios/..., tutorial/...) and
    its content."""
    root = examples_root()
    out = {}
    for folder, patterns in (("programs", ("*.tlp", "*/*.tlp")), ("scenarios", ("*.toml",))):
        for pattern in patterns:
            for source in sorted((root / folder).glob(pattern)):
                out[source.relative_to(root).as_posix()] = source.read_bytes()
    text = _tutorial_md(root).read_text(encoding="utf-8")
    for name, body in tutorial_files(text).items():
        out[f"tutorial/{name}"] = body.encode("utf-8")
    return out


@click.command("examples")
@click.argument("dest", type=click.Path(file_okay=False, path_type=Path))
@click.option("--force", is_flag=True, help="Overwrite files already in DEST.")
@click.option("--json", "as_json", is_flag=True,
              help="Print one JSON object: the folder and the files written.")
def examples(dest: Path, force: bool, as_json: bool) -> None:
    """Copy the shipped programs, scenarios and tutorial files into DEST.

    DEST gets programs/, scenarios/ and tutorial/ (the files docs/tutorial.md writes);
    `teleo simulate DEST/scenarios/blocks_figure3.toml` then runs as in the repository. A
    shipped scenario also runs by its name alone: `teleo simulate blocks_figure3`."""
    files = example_files()
    existing = [name for name in files if (dest / name).exists()]
    if existing and not force:
        more = f" (and {len(existing) - 1} more)" if len(existing) > 1 else ""
        raise ExamplesError(f"teleo examples: {dest / existing[0]} exists{more}: give "
                            f"--force to overwrite, or another DEST")
    try:
        for name, content in files.items():
            target = dest / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(content)
    except OSError as exc:
        raise ExamplesError(f"teleo examples: cannot write into {dest}: "
                            f"{exc.strerror or exc}") from exc
    if as_json:
        click.echo(json.dumps({"dest": str(dest), "files": list(files),
                               "overwritten": existing}))
        return
    counts = {top: sum(1 for n in files if n.startswith(top + "/"))
              for top in ("programs", "scenarios", "tutorial")}
    click.echo(f"{len(files)} files written into {dest}: " +
               ", ".join(f"{top}/ ({n})" for top, n in counts.items()) +
               (f"; {len(existing)} overwritten" if existing else ""))


commands = [examples]
