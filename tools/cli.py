"""The `teleo` command: one click group; each subcommand lives in the module that owns it."""

from __future__ import annotations

import importlib
import logging

import click

# (module, attribute holding a list of click commands). Each module owns its subcommands.
_COMMAND_MODULES = (
    "tools.lang_commands",   # check, infer, step        (language engine)
    "tools.bus_commands",    # router, echo, record, replay (bus)
    "tools.world_commands",  # render                    (world)
    "tools.launch",          # launch                    (processes)
    "tools.goal_commands",   # goal post/list/cancel/priority
    "tools.event_commands",  # event                     (world events into a running launch)
    "tools.inspect",         # inspect
    "tools.simulate",        # simulate                  (one process, no bus)
    "tools.explain",         # explain                   (run records)
    "tools.plot",            # plot                      (run records)
    "tools.view",            # view                      (live web view)
)


@click.group()
@click.option("-v", "--verbose", count=True, help="More logging (-v info, -vv debug).")
def cli(verbose: int) -> None:
    """teleo: goal-directed, reactive agents on an Eclipse Zenoh bus."""
    level = logging.WARNING - 10 * min(verbose, 2)
    logging.basicConfig(level=level, format="%(asctime)s %(name)s %(levelname)s %(message)s")


def _register() -> None:
    for name in _COMMAND_MODULES:
        module = importlib.import_module(name)
        for command in module.commands:
            cli.add_command(command)


_register()


def main() -> None:
    cli()
