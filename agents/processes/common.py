"""What every process module shares: logging, the stop signal, and the stage loop.

A process module reads as: subscribe, call the pure core, publish. The
boilerplate around that loop lives here.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import Any

import click

from bus.config import bus_options
from bus.node import open_node
from bus.stage import Stage
from bus.stage import stop_on_signals as bus_stop_on_signals


def setup_logging(process: str, verbose: bool = False) -> logging.Logger:
    """Log lines on stderr (the launcher sends them to the process's log file)."""
    logging.basicConfig(level=logging.DEBUG if verbose else logging.INFO,
                        format=f"%(asctime)s {process} %(name)s %(levelname)s %(message)s")
    return logging.getLogger(f"teleo.{process}")


def stop_on_signals() -> threading.Event:
    """An Event set by SIGINT or SIGTERM, so the main loop ends and the node closes cleanly
    (an unclosed zenoh session keeps the process alive: docs/bus.md, "Zenoh in Python", item 1); the
    process also stops when its launcher dies (bus/lifeline.py)."""
    return bus_stop_on_signals(child=True)


def run_stage(cfg: Any, run: str, process: str, inputs: list[str], outputs: list[str],
              step: Any, log: logging.Logger, bind: Callable[[Any], None] | None = None
              ) -> None:
    """Open the node, run a bus Stage (join inputs by cycle, call `step`, publish outputs and
    stats, re-emit on a repeated cycle) until SIGINT/SIGTERM, then close the node. ``bind``
    is given the node first (for what the step asks of other processes)."""
    stop = stop_on_signals()
    with open_node(cfg, run, process) as node:
        if bind is not None:
            bind(node)
        stage = Stage(node, process, inputs, step, outputs=outputs)
        stage.start()
        log.info("announced; inputs %s", inputs)
        stage.run(stop)
        log.info("stopped after %d cycles (%d late)", stage.cycles_done, stage.late)


def agent_options(with_program: bool) -> Callable[[Callable], Callable]:
    """The flags every per-agent stage takes: --run, --agent (and --program), plus the bus's."""
    def decorate(f: Callable) -> Callable:
        f = bus_options(f)
        if with_program:
            f = click.option("--program", required=True,
                             type=click.Path(exists=True, dir_okay=False),
                             help="The agent's teleoreactive program (.tlp).")(f)
        f = click.option("--agent", required=True, help="Agent id, e.g. ME.")(f)
        f = click.option("--run", required=True, help="Run id.")(f)
        return click.command()(f)
    return decorate
