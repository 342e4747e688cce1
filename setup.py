"""The build's one step beyond pyproject.toml: the examples go into the wheel.

The shipped programs (programs/), scenarios (scenarios/) and the tutorial (docs/tutorial.md,
whose named blocks are its files) stay where the repository has them: tests, docs and the
scenarios themselves name `programs/...` and `scenarios/...` from the repository's root. The
wheel carries a copy of them as the package `teleo_examples`, laid out the same way
(teleo_examples/programs, teleo_examples/scenarios, teleo_examples/tutorial.md), so a
scenario's `programs/x.tlp` is found there as it is in a checkout (a relative program path is
looked up beside the scenario and in each folder above it: world/run_scenario.py).

Why a build step rather than setuptools' package-dir: pyproject.toml finds the code's
packages (agents*, bus*, world*, tools*) and setuptools takes either found packages or a
listed, mapped set, not both; listing every package by hand would drop the next one added.
`teleo examples` and the scenario names (`teleo simulate blocks_figure3`) read these files
(tools/commands/examples.py); in a checkout or an editable install they read the repository's.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent
PACKAGE = "teleo_examples"
SHIPPED = {"programs": ("*.tlp", "*/*.tlp"), "scenarios": ("*.toml",)}


class BuildWithExamples(build_py):
    """build_py, then the examples copied into the build as the package teleo_examples."""

    def run(self) -> None:
        super().run()
        target = Path(self.build_lib) / PACKAGE
        if target.exists():
            shutil.rmtree(target)
        for folder, patterns in SHIPPED.items():
            for pattern in patterns:
                for source in sorted((ROOT / folder).glob(pattern)):
                    dest = target / source.relative_to(ROOT)
                    dest.parent.mkdir(parents=True, exist_ok=True)
                    shutil.copyfile(source, dest)
        shutil.copyfile(ROOT / "docs" / "tutorial.md", target / "tutorial.md")
        (target / "__init__.py").write_text(
            '"""teleo\'s shipped programs, scenarios and tutorial (`teleo examples DEST`)."""\n')


setup(cmdclass={"build_py": BuildWithExamples})
