"""The `teleo` command: one click group; each subcommand lives in the module that owns it.

`teleo --version`, `-h`/`--help` on every command, and summaries in `teleo --help` that are
the first sentence of each command's help (not cut at an "e.g."). Shell completion is click's:
`eval "$(_TELEO_COMPLETE=bash_source teleo)"` (zsh_source, fish_source; README, "Shell
completion").
"""

from __future__ import annotations

import errno
import importlib
import logging
import re

import click

from tools.launching import stop_signals
from tools.paths import describe_os_error

# module -> the commands it owns (its attribute `commands`, a list of click commands). A
# command's module is imported only when that command is asked for (`list_commands`, as for
# `teleo --help` or completion, imports them all): importing all of them was most of every
# command's start-up.
_COMMAND_MODULES = {
    "tools.commands.check": ("check",),         # programs, learned files, scenarios
    "tools.commands.lang": ("infer", "step"),   # language engine
    "tools.commands.bus": ("router", "echo", "record", "replay"),  # bus
    "tools.commands.rate": ("hz",),             # bus rates
    "tools.commands.world": ("render",),        # world
    "tools.commands.worlds": ("worlds",),       # the worlds found (entry points)
    "tools.commands.launch": ("launch",),       # processes
    "tools.commands.run": ("ps", "stop"),       # runs on this host
    "tools.commands.goal": ("goal",),           # goal post/list/cancel/priority
    "tools.commands.event": ("event",),         # world events into a running launch
    "tools.commands.pause": ("pause", "step-run", "resume"),  # hold a lockstep launch
    "tools.commands.program": ("program", "set"),  # change a running launch
    "tools.commands.inspect": ("inspect",),
    "tools.commands.simulate": ("simulate",),   # one process, no bus
    "tools.commands.explain": ("explain",),     # run records
    "tools.commands.plot": ("plot",),           # run records
    "tools.commands.graph": ("graph",),         # programs and runs as pictures
    "tools.commands.why": ("why",),             # why a concept instance is believed
    "tools.view": ("view",),                    # live web view
    "tools.commands.pddl": ("pddl",),           # PDDL domains as programs
    "tools.commands.solve": ("solve",),         # a PDDL problem in one process
    "tools.commands.examples": ("examples",),   # shipped programs and scenarios
}
_MODULE_OF = {name: module for module, names in _COMMAND_MODULES.items() for name in names}
SUMMARY_CHARS = 66
"""[characters] of a command's summary in `teleo --help`: what fits beside the longest
command name in 80 columns (click's own summaries stop at 45 and at the first dot)."""


class _Group(click.Group):
    """The top-level group: an OSError that escapes a command (a file it could not read or
    write) is one `Error:` line naming the file and the reason, exit 1, not a traceback.
    Every output option checks its file up front (tools/paths.py); this is the safety net.
    A closed pipe (EPIPE) is left to click, which exits quietly."""

    def invoke(self, ctx: click.Context) -> object:
        try:
            return super().invoke(ctx)
        except OSError as exc:
            if exc.errno == errno.EPIPE:
                raise
            raise click.ClickException(describe_os_error(exc)) from exc

    def get_command(self, ctx: click.Context | None, cmd_name: str) -> click.Command | None:
        """The command `cmd_name`, its module imported now if it was not yet."""
        if cmd_name not in self.commands and cmd_name in _MODULE_OF:
            _load(_MODULE_OF[cmd_name])
        return self.commands.get(cmd_name)

    def list_commands(self, ctx: click.Context | None) -> list[str]:
        """Every command's name (every command module imported)."""
        load_all()
        return sorted(self.commands)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="teleo", prog_name="teleo",
                      message="%(prog)s %(version)s")
@click.option("-v", "--verbose", count=True, help="More logging (-v info, -vv debug).")
def cli(verbose: int) -> None:
    """teleo: goal-directed, reactive agents on an Eclipse Zenoh bus."""
    level = logging.WARNING - 10 * min(verbose, 2)
    logging.basicConfig(level=level, format="%(asctime)s %(name)s %(levelname)s %(message)s")


# A sentence ends at ". " unless the dot closes one of these abbreviations.
_ABBREVIATIONS = ("e.g.", "i.e.", "etc.", "vs.", "cf.")
_SENTENCE_END = re.compile(r"\.(\s|$)")


def summary(help_text: str, width: int = SUMMARY_CHARS) -> str:
    """The first sentence of ``help_text``'s first paragraph, without its final dot, cut to
    ``width`` characters at a word with "..." when longer."""
    text = " ".join(help_text.split("\n\n")[0].split())
    end = len(text)
    for match in _SENTENCE_END.finditer(text):
        if not text[:match.end(0)].rstrip().endswith(_ABBREVIATIONS):
            end = match.start()
            break
    first = text[:end]
    if len(first) <= width:
        return first
    return first[:width - 3].rsplit(" ", 1)[0].rstrip(",;:") + "..."


def _summarise(command: click.Command) -> None:
    """Give ``command`` (and a group's subcommands) a summary unless it has its own."""
    if command.short_help is None and command.help:
        command.short_help = summary(command.help)
    for sub in getattr(command, "commands", {}).values():
        _summarise(sub)


def _load(name: str) -> None:
    """Import one command module and add its commands (with their summaries)."""
    for command in importlib.import_module(name).commands:
        _summarise(command)
        cli.add_command(command)


def load_all() -> None:
    """Add every command (`cli.commands` then holds them all)."""
    for name in _COMMAND_MODULES:
        if not all(c in cli.commands for c in _COMMAND_MODULES[name]):
            _load(name)


stop_signals.early()  # `teleo launch`: a stop signal from here on is kept (importing its
                      # modules is most of a command's start-up: seconds when busy)


def main() -> None:
    """The `teleo` console command: run it, then exit without Python's finalisation (see
    bus.lifeline.run_then_exit: zenoh's threads could otherwise abort a finished command)."""
    from bus.lifeline import run_then_exit

    run_then_exit(cli)
