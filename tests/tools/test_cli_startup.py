"""A `teleo` command starts quickly (issue 24, item 7; trial #7: `teleo stop` of a long run
took 19 s): it imports only the module of the command asked for, not every command's (at
load 8, 3 s of a `teleo stop` were that import, against 0.4 s for its own module); the
table of which module owns which command is the modules' own lists."""

from __future__ import annotations

import importlib
import subprocess
import sys

from tools.cli import _COMMAND_MODULES, cli

HEAVY = ("zenoh", "pymunk", "numpy", "mcap", "agents.lang", "world.driving")


def test_a_command_imports_only_what_it_needs(tmp_path) -> None:
    code = ("import sys\nfrom tools.cli import cli\n"
            "cli(['ps'], standalone_mode=False)\n"
            f"print([m for m in {HEAVY!r} if m in sys.modules])\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={"TELEO_RUN_DIR": str(tmp_path), "PATH": "/usr/bin:/bin"},
                          timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [f"no runs registered in {tmp_path / 'active'}", "[]"]


def test_the_table_of_commands_is_what_each_module_holds() -> None:
    for module, names in _COMMAND_MODULES.items():
        assert tuple(c.name for c in importlib.import_module(module).commands) == names
    every = {n for names in _COMMAND_MODULES.values() for n in names}
    assert set(cli.list_commands(None)) == every
