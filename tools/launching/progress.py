"""A progress bar of cycles, with cycles per second, for long `teleo simulate` and
`teleo launch --cycles N` runs: drawn on stderr when stderr is a terminal, nothing otherwise
(a script's output stays as it was), and gone when the run ends (transient), so the summary
follows on a clean screen.

    with CycleProgress(650, "simulate") as bar:
        for t in range(650):
            ...
            bar.done(t + 1)
"""

from __future__ import annotations

from collections.abc import Iterator

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    Task,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)
from rich.text import Text


class _Rate(ProgressColumn):
    """Cycles per second over rich's recent samples."""

    def render(self, task: Task) -> Text:
        return Text(f"{task.speed or 0.0:8.1f} cycles/s")


class CycleProgress:
    """A bar for ``total`` cycles (0: forever, a counter without a bar), shown only when
    ``console`` (default: stderr) is a terminal."""

    def __init__(self, total: int, label: str, console: Console | None = None) -> None:
        self.console = console or Console(stderr=True)
        self.shown = self.console.is_terminal
        self.total = total
        self._progress: Progress | None = None
        self._task = None
        self.label = label

    def __enter__(self) -> CycleProgress:
        if self.shown:
            columns = [TextColumn(f"{self.label}"), BarColumn(), MofNCompleteColumn(),
                       TextColumn("cycles"), _Rate(), TimeElapsedColumn()]
            if self.total:
                columns.append(TimeRemainingColumn())
            self._progress = Progress(*columns, console=self.console, transient=True,
                                      refresh_per_second=5)
            self._progress.__enter__()
            self._task = self._progress.add_task(self.label, total=self.total or None)
        return self

    def done(self, cycles: int) -> None:
        """``cycles`` cycles are done."""
        if self._progress is not None:
            self._progress.update(self._task, completed=cycles)

    def __exit__(self, *exc: object) -> None:
        if self._progress is not None:
            self._progress.__exit__(*exc)
            self._progress = None


def progress_cycles(total: int, show: bool, label: str = "simulate") -> Iterator[int]:
    """``range(total)``, with a CycleProgress while ``show`` (and stderr is a terminal)."""
    if not show:
        yield from range(total)
        return
    with CycleProgress(total, label) as bar:
        for cycle in range(total):
            yield cycle
            bar.done(cycle + 1)


class WorldProgress(CycleProgress):
    """The progress of a launched run, read from the world's ProcessStats on
    teleo/<run>/stats/world (one a cycle, world/process.py) with a ring subscriber: call
    ``poll()`` now and then from the launcher's loop."""

    def __init__(self, node, run: str, total: int, console: Console | None = None) -> None:
        super().__init__(total, f"run {run}", console)
        self.shown = self.shown and total > 0
        self._ring = None
        if self.shown:
            from bus import keys

            self._ring = node.subscribe_ring(keys.stats(run, "world"), capacity=64)

    def poll(self) -> None:
        """Take the world's latest cycle from what arrived since the last poll."""
        if self._ring is None:
            return
        latest = [item.msg.env.cycle for item in self._ring.drain() if item.msg is not None]
        if latest:
            self.done(max(latest) + 1)
