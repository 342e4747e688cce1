"""The files the `teleo` commands write, checked when the command line is read.

Every option that names a file to write (`--summary`, `--trace`, `--render`, `--plot`,
`--save-state`, ...) has the type OutputPath: before any work (a long launch or simulation is
not wasted on a file it cannot write) it checks that the file's folder exists or can be
created and is writable, that an existing file can be written, and, where the option has one,
that the suffix names a format the command can write (`--render x.bmp`, `--plot x.txt`;
`teleo record FILE` makes no folder and takes only .mcap, as `cp` or a shell redirection
would refuse a missing folder: a typo must not leave a tree of folders behind). A
failure is one `Error:` line naming the option, the path and the reason, exit 1 (a runtime
failure, as when the file itself cannot be written later), never a traceback.

``describe_os_error`` words an OSError the same way for the CLI's safety net (tools/cli.py).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import click

from world.errors import WorldError
from world.pictures import picture_format

NameCheck = Callable[[Path], str | None]
"""The problem with a file's name (its suffix, say), or None when the name is fine."""


def describe_os_error(exc: OSError) -> str:
    """One line for an OSError: the file(s) it names and the system's reason."""
    reason = exc.strerror or str(exc) or type(exc).__name__
    if exc.filename is None:
        return reason
    names = f"{exc.filename}" + (f" -> {exc.filename2}" if exc.filename2 is not None else "")
    return f"{names}: {reason}"


def suffix_check(suffixes: Sequence[str], what: str) -> NameCheck:
    """A NameCheck accepting only these suffixes (lower case, with their dot) for ``what``
    (e.g. "a plot")."""
    def check(path: Path) -> str | None:
        suffix = path.suffix.lower()
        if suffix in suffixes:
            return None
        listed = ", ".join(suffixes[:-1]) + f" or {suffixes[-1]}" if len(suffixes) > 1 \
            else suffixes[0]
        return f"{path}: expected {what} file ending in {listed}, got {suffix or 'no suffix'!r}"
    return check


def picture_check(path: Path) -> str | None:
    """A NameCheck for pictures: world.pictures.picture_format's formats and message."""
    try:
        picture_format(path)
    except WorldError as exc:
        return str(exc)
    return None


def output_problem(path: Path, create_folders: bool = True) -> str | None:
    """Why ``path`` cannot be written (its folder missing and not creatable, or missing at all
    when not ``create_folders``; not a folder, not writable; the file itself a folder or not
    writable), or None when it can. The folder is probed with a temporary file (or folder)
    that is removed at once: permission bits alone do not say it (root ignores them; /proc
    refuses new files whatever they say), and the reason given is the system's answer to
    that probe, so the words and the reason in brackets never disagree."""
    try:
        if path.is_dir():
            return f"{path} is a folder"
        if path.is_file():
            with path.open("ab"):  # opened to append, nothing written: the file is unchanged
                pass
            return None
        folder, missing = path.parent, None
        while not (folder.exists() or folder.is_symlink()) and folder.parent != folder:
            folder, missing = folder.parent, folder
        if not folder.is_dir():
            return f"{folder} is not a folder"
        if missing is not None and not create_folders:
            return (f"its folder {path.parent} does not exist (create it first: "
                    f"mkdir -p {path.parent})")
    except OSError as exc:
        return describe_os_error(exc)
    try:
        if missing is not None:
            os.rmdir(tempfile.mkdtemp(dir=folder, prefix=".teleo-check-"))
        else:
            fd, probe = tempfile.mkstemp(dir=folder, prefix=".teleo-check-")
            os.close(fd)
            os.unlink(probe)
    except OSError as exc:
        reason = exc.strerror or str(exc)
        if missing is not None:
            return f"its folder {missing} cannot be created ({reason})"
        return f"no file can be created in its folder {folder} ({reason})"
    return None


class OutputPath(click.Path):
    """A file the command will write (see the module doc); ``check``: a NameCheck of the
    formats the option writes (suffix_check, picture_check), if it has any;
    ``create_folders``: whether a folder that is not there yet is made (else refused)."""

    def __init__(self, check: NameCheck | None = None, path_type: type | None = None,
                 create_folders: bool = True) -> None:
        super().__init__(dir_okay=False, path_type=path_type)
        self.check = check
        self.create_folders = create_folders

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> Any:
        converted = super().convert(value, param, ctx)
        path = Path(os.fsdecode(converted))
        problem = (self.check(path) if self.check else None) or \
            output_problem(path, self.create_folders)
        if problem is not None:
            raise click.ClickException(f"{_option_name(param)}: cannot write {path}: {problem}"
                                       if not problem.startswith(f"{path}:")
                                       else f"{_option_name(param)}: {problem}")
        return converted


def _option_name(param: click.Parameter | None) -> str:
    if param is None:
        return "output"
    if isinstance(param, click.Option) and param.opts:
        return max(param.opts, key=len)
    return param.human_readable_name
