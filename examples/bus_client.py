"""A client of a running teleo launch written from docs/bus.md alone: it imports zenoh and
msgpack, never teleo.

    python examples/bus_client.py --connect tcp/127.0.0.1:PORT --run RUN keys
    python examples/bus_client.py --connect ... --run RUN follow ME [--cycles 5]
    python examples/bus_client.py --connect ... --run RUN post ME "(ontable B T)" [--priority 5]

`keys` lists the processes holding liveliness tokens and every key heard for a while with its
message kind; `follow` prints an agent's intention each cycle (its goals' statuses and its
actions); `post` posts a goal on the agent's goals queryable, then asks for the agent's goals
every half second until the goal is achieved, failed or cancelled, and prints the verdict.
The router endpoint and run id are in the launch's run file ($TELEO_RUN_DIR/active/<run>.json, or
`teleo ps --json`); `--run-file` reads both from it. An open run only (a secured run needs TLS
and credentials: docs/bus.md, "Security").
"""

from __future__ import annotations

import argparse
import json
import sys
import time

import msgpack
import zenoh

MAJOR = 1  # the protocol's major version this client speaks (docs/bus.md, "Envelope")
TERMINAL = ("achieved", "failed", "cancelled")


class ClientError(Exception):
    """Something the client cannot go on with (one line)."""


def open_session(endpoint: str) -> zenoh.Session:
    """A zenoh peer that meets the run at its router, as teleo's own tools do."""
    conf = zenoh.Config()
    conf.insert_json5("mode", '"peer"')
    conf.insert_json5("connect/endpoints", json.dumps([endpoint]))
    conf.insert_json5("listen/endpoints", '["tcp/127.0.0.1:0"]')
    conf.insert_json5("scouting/multicast/enabled", "false")
    return zenoh.open(conf)


def envelope(run: str, sender: str) -> dict:
    """The envelope of a message sent outside the cycle (cycle -1)."""
    return {"v": MAJOR, "run": run, "cycle": -1, "sender": sender, "sent_ns": time.time_ns()}


def decode(key: str, payload: bytes) -> dict:
    """A message as a dict, its packed rows unpacked; ClientError for another major version."""
    msg = msgpack.unpackb(payload, raw=False)
    version = msg.get("env", {}).get("v")
    if version != MAJOR:
        raise ClientError(f"{key}: protocol major version {version!r}, this client speaks "
                          f"{MAJOR}")
    for field in ("percepts", "beliefs"):   # packed rows: one msgpack bin a row
        if isinstance(msg.get(field), list):
            msg[field] = [msgpack.unpackb(r, raw=False) if isinstance(r, bytes) else r
                          for r in msg[field]]
    return msg


def list_keys(session: zenoh.Session, run: str, seconds: float) -> None:
    """The run's live processes (liveliness tokens) and the keys heard within ``seconds``."""
    heard: dict[str, str] = {}
    tokens: set[str] = set()

    def on_sample(sample: zenoh.Sample) -> None:
        key = str(sample.key_expr)
        if key not in heard:
            heard[key] = msgpack.unpackb(sample.payload.to_bytes(), raw=False).get("kind", "?")

    def on_token(sample: zenoh.Sample) -> None:   # PUT: a token appeared; DELETE: it went
        name = str(sample.key_expr).rsplit("/", 1)[-1]
        if sample.kind == zenoh.SampleKind.PUT:
            tokens.add(name)
        else:
            tokens.discard(name)

    live = session.liveliness().declare_subscriber(f"teleo/{run}/proc/*", on_token,
                                                   history=True)
    sub = session.declare_subscriber(f"teleo/{run}/**", on_sample)
    time.sleep(seconds)
    sub.undeclare()
    live.undeclare()
    for name in sorted(tokens):
        print(f"process {name}")
    for key in sorted(heard):
        print(f"key {key} {heard[key]}")


def follow(session: zenoh.Session, run: str, agent: str, cycles: int, timeout: float) -> None:
    """Print ``cycles`` of the agent's intentions: cycle, each goal's status, the actions."""
    key = f"teleo/{run}/agent/{agent}/intention"
    seen = 0
    with session.declare_subscriber(key) as sub:
        deadline = time.monotonic() + timeout
        while seen < cycles:
            sample = sub.try_recv()
            if sample is None:
                if time.monotonic() > deadline:
                    raise ClientError(f"{key}: no intention within {timeout:g} s")
                time.sleep(0.02)
                continue
            decision = decode(key, sample.payload.to_bytes())["decision"]
            goals = ", ".join(f"{g['id']} {g['goal']} {g['status']}" for g in decision["goals"])
            actions = " ".join("(" + " ".join(map(str, a)) + ")" for a in decision["actions"])
            print(f"intention {agent} cycle {decision['cycle']}: goals {goals or 'none'}; "
                  f"actions {actions or 'none'}")
            seen += 1


def ask(session: zenoh.Session, run: str, agent: str, request: dict, timeout: float) -> dict:
    """A GoalRequest on the agent's goals queryable; its GoalReply as a dict."""
    key = f"teleo/{run}/agent/{agent}/goals"
    body = {"kind": "GoalRequest", "env": envelope(run, "bus-client"), "agent": agent,
            **request}
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:   # the queryable may not be routed here yet
        for reply in session.get(key, payload=msgpack.packb(body), timeout=2.0):
            if reply.ok is None:
                raise ClientError(f"{key}: {reply.err.payload.to_bytes().decode()}")
            return decode(key, reply.ok.payload.to_bytes())
        time.sleep(0.1)
    raise ClientError(f"{key}: nobody answered within {timeout:g} s")


def post(session: zenoh.Session, run: str, agent: str, goal: str, priority: int,
         timeout: float) -> str:
    """Post ``goal`` and wait for its verdict in the agent's goal list; the verdict."""
    before = {g["id"] for g in ask(session, run, agent, {"op": "list"}, timeout)["goals"]}
    reply = ask(session, run, agent, {"op": "post", "goal": goal, "priority": priority},
                timeout)
    if not reply["ok"]:
        raise ClientError(f"goal refused: {reply['reason']}")
    print(f"posted: {reply['reason']}")
    goal_id = next(g["id"] for g in reply["goals"] if g["id"] not in before)
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:   # the store keeps every goal, finished ones too
        goals = ask(session, run, agent, {"op": "list"}, timeout)["goals"]
        mine = next(g for g in goals if g["id"] == goal_id)
        if mine["status"] in TERMINAL:
            note = f" ({mine['note']})" if mine["note"] else ""
            return f"verdict {goal_id} {mine['status']} at cycle {mine['updated_cycle']}{note}"
        time.sleep(0.5)
    raise ClientError(f"{goal_id}: no verdict within {timeout:g} s")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--connect", help="the run's router endpoint (tcp/HOST:PORT)")
    parser.add_argument("--run", help="the run id")
    parser.add_argument("--run-file", help="a launch's run file: endpoint and run from it")
    parser.add_argument("--timeout", type=float, default=60.0, help="[s] to wait at most")
    sub = parser.add_subparsers(dest="command", required=True)
    keys = sub.add_parser("keys")
    keys.add_argument("--seconds", type=float, default=2.0)
    fol = sub.add_parser("follow")
    fol.add_argument("agent")
    fol.add_argument("--cycles", type=int, default=5)
    pst = sub.add_parser("post")
    pst.add_argument("agent")
    pst.add_argument("goal")
    pst.add_argument("--priority", type=int, default=5)
    args = parser.parse_args(argv)
    endpoint, run = args.connect, args.run
    if args.run_file:
        with open(args.run_file) as f:
            info = json.load(f)
        endpoint, run = endpoint or info["endpoint"], run or info["run"]
    if not endpoint or not run:
        parser.error("give --connect and --run, or --run-file")
    session = open_session(endpoint)
    try:
        if args.command == "keys":
            list_keys(session, run, args.seconds)
        elif args.command == "follow":
            follow(session, run, args.agent, args.cycles, args.timeout)
        else:
            print(post(session, run, args.agent, args.goal, args.priority, args.timeout))
    except ClientError as exc:
        print(f"bus_client: {exc}", file=sys.stderr)
        return 1
    finally:
        session.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
