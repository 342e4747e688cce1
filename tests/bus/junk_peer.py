"""A misbehaving peer for test_receive.py, run as a subprocess: serves goal requests
(failing on "cancel") and puts garbage on a percepts key before one valid message."""

from __future__ import annotations

import signal
import threading

import click
import msgpack

from bus import keys
from bus.codec import encode
from bus.config import BusConfig, bus_options
from bus.messages import Beliefs, GoalReply, GoalRequest, Percepts
from bus.node import open_node


def bad_payloads(node) -> list[bytes]:
    env = {"v": 1, "run": node.run, "cycle": 1, "sender": node.process, "sent_ns": 0}
    return [
        b"\xc1\x00garbage",  # not msgpack at all
        msgpack.packb({"kind": "Percepts", "env": dict(env, v=99), "agent": "A",
                       "percepts": []}),  # unknown schema version
        encode(Beliefs(node.envelope(1), "A", ())),  # wrong kind for a percepts key
        msgpack.packb({"kind": "Percepts", "env": env, "agent": "A",
                       "percepts": [["x", True]]}),  # wrong type inside a percept
        msgpack.packb(["not", "a", "map"]),
    ]


@click.command()
@click.option("--run", "run_id", required=True)
@bus_options
def main(run_id: str, bus_config: BusConfig) -> None:
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())

    def handle(req: GoalRequest) -> GoalReply:
        if req.op == "cancel":
            raise RuntimeError(f"cannot cancel {req.goal_id}")
        return GoalReply(node.envelope(), True, f"{req.op} {req.goal}", ({"id": "g1"},))

    with open_node(bus_config, run_id, "junk") as node:
        key = keys.percepts(run_id, "A")
        node.serve(keys.goals(run_id, "A"), handle)
        node.declare([key])
        node.announce()
        node.wait_matching([key], 30)
        for payload in bad_payloads(node):
            node.put_raw(key, payload)
        node.publish(key, Percepts(node.envelope(9), "A", (["self", "A", "speed", 1.5],)))
        stop.wait(60)


if __name__ == "__main__":
    main()
