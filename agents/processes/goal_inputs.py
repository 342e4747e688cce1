"""What the goal-entry process reads each cycle (agents/processes/goals.py): the world states,
which wake it, and the executives' intentions, which wait in zenoh's own queues until it
wakes and are then taken in a batch: no wake-up per intention (each would wake the process
and take the GIL on zenoh's thread, one per agent and cycle), and every intention that came
before a world state is mirrored before that state's goal lists are made.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator, Sequence

from bus import keys
from bus.codec import decode
from bus.errors import CodecError
from bus.messages import Intention, WorldState
from bus.node import Node


class GoalInputs:
    """The subscriptions of one goal-entry process: `state(timeout)` waits for the next
    world state; `intentions()` yields those waiting, each agent's in the order it sent them."""

    def __init__(self, node: Node, run: str, agents: Sequence[str],
                 log: logging.Logger) -> None:
        self.log = log
        self._states = node.subscribe(keys.world_state(run))
        self._intentions = [node.subscribe_fifo(keys.intention(run, a)) for a in agents]

    def state(self, timeout: float) -> WorldState | None:
        """The next world state, waiting at most `timeout` [s]; None if none came."""
        msg = self._states.get(timeout=timeout)
        return msg if isinstance(msg, WorldState) else None

    def intentions(self) -> Iterator[Intention]:
        """Every intention waiting now; a payload that does not decode is logged and left
        (as an Inbox leaves it)."""
        for fifo in self._intentions:
            for key, payload in fifo.drain():
                try:
                    msg = decode(key, payload)
                except CodecError as exc:
                    self.log.warning("dropped payload: %s", exc)
                    continue
                if isinstance(msg, Intention):
                    yield msg
