"""What every process module shares: logging, the stop signal, and the stage loop.

A process module reads as: subscribe, call the pure core, publish (DESIGN.md). The
boilerplate around that loop lives here.
"""

from __future__ import annotations

import logging
import signal
import threading
from typing import Any


def setup_logging(process: str, verbose: bool = False) -> logging.Logger:
    """Log lines on stderr (the launcher sends them to the process's log file)."""
    logging.basicConfig(level=logging.DEBUG if verbose else logging.INFO,
                        format=f"%(asctime)s {process} %(name)s %(levelname)s %(message)s")
    return logging.getLogger(f"teleo.{process}")


def stop_on_signals() -> threading.Event:
    """An Event set by SIGINT or SIGTERM, so the main loop ends and the node closes cleanly
    (an unclosed zenoh session keeps the process alive: notes/zenoh.md, pitfall 1)."""
    stop = threading.Event()

    def handler(signum: int, frame: object) -> None:
        logging.getLogger("teleo").info("signal %s: stopping", signal.Signals(signum).name)
        stop.set()

    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, handler)
    return stop


def run_stage(cfg: Any, run: str, process: str, inputs: list[str], outputs: list[str],
              step: Any, log: logging.Logger) -> None:
    """Open the node, run a bus Stage (join inputs by cycle, call `step`, publish outputs and
    stats, re-emit on a repeated cycle) until SIGINT/SIGTERM, then close the node."""
    from bus.node import open_node
    from bus.stage import Stage

    stop = stop_on_signals()
    with open_node(cfg, run, process) as node:
        stage = Stage(node, process, inputs, step, outputs=outputs)
        stage.start()
        log.info("announced; inputs %s", inputs)
        stage.run(stop)
        log.info("stopped after %d cycles (%d late)", stage.cycles_done, stage.late)
