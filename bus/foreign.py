"""What a stranger can do to a secured run (docs/bus.md "Security"; bench/faults/drills.py
foreign, tests/e2e/test_secure_live.py): the checks of docs/faults.md's foreign-client drill,
against a run started with `teleo launch --secure`.

`probe(endpoint, run, secrets)` tries, each in a session of its own:
- to open a session with no credentials at all (zenoh's default config), over plain TCP to
  the TLS port, with the CA but no password, with a wrong password: each must be refused;
- with a *real* process's credentials (an agent's perception: authenticated, but not allowed
  these keys) to read the whole run, put forged actions, world state and world events, and
  post a goal: nothing may get through;
- with the operator's credentials (the user who launched the run): list the goals and send a
  world event, which must work.
What got through is seen by an observer session with the operator's credentials.
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

import zenoh

from bus import keys
from bus.config import BusConfig, Mode
from bus.errors import BusError, NobodyServing, QueryFailed
from bus.messages import Actions, Envelope, GoalRequest, WorldEvent, WorldState
from bus.node import open_node
from bus.security import OPERATOR

FORGER = "forger"
LISTEN_S = 1.0  # [s] how long the forger and the observer listen


def _refused(conf: zenoh.Config) -> bool:
    try:
        session = zenoh.open(conf)
    except zenoh.ZError:
        return True
    session.close()
    return False


def _plain(endpoint: str) -> zenoh.Config:
    conf = zenoh.Config()
    conf.insert_json5("mode", '"client"')
    conf.insert_json5("connect/endpoints", json.dumps([endpoint]))
    conf.insert_json5("scouting/multicast/enabled", "false")
    conf.insert_json5("connect/timeout_ms", "2000")
    return conf


def _with_ca(endpoint: str, ca: str, user: str = "", password: str = "") -> zenoh.Config:
    conf = _plain(endpoint)
    conf.insert_json5("transport/link/tls/root_ca_certificate", json.dumps(ca))
    if user:
        conf.insert_json5("transport/auth/usrpwd/user", json.dumps(user))
        conf.insert_json5("transport/auth/usrpwd/password", json.dumps(password))
    return conf


def _config(endpoint: str, credentials: Path) -> BusConfig:
    return BusConfig(mode=Mode.CLIENT, connect=(endpoint,), listen=(),
                     credentials=str(credentials))


def probe(endpoint: str, run: str, secrets: Path, victim: str = "ME") -> dict[str, Any]:
    """Try everything listed in the module doc; returns what happened (see the keys)."""
    ca = str(secrets / "ca.pem")
    operator = secrets / f"{OPERATOR}.cred.json"
    result: dict[str, Any] = {
        "no_credentials_refused": _refused(_plain(endpoint)),
        "plain_tcp_refused": _refused(_plain(endpoint.replace("tls/", "tcp/", 1))),
        "no_password_refused": _refused(_with_ca(endpoint, ca)),
        "wrong_password_refused": _refused(_with_ca(endpoint, ca, OPERATOR, "not-the-password")),
    }
    with open_node(_config(endpoint, operator), run, "observer") as watcher:
        seen = watcher.subscribe(keys.run_all(run))
        time.sleep(0.3)  # the observer's subscription reaches the router
        result.update(_forge(endpoint, run, secrets / f"{victim}.perception.cred.json", victim))
        result.update(_operate(endpoint, run, operator, victim))
        time.sleep(LISTEN_S)
        senders = []
        while (msg := seen.get(0)) is not None:
            senders.append((msg.KIND, msg.env.sender))
    result["forged_messages_delivered"] = sum(1 for _, s in senders if s == FORGER)
    result["operator_event_delivered"] = ("WorldEvent", OPERATOR) in senders
    result["run_traffic_seen_by_operator"] = len(senders)
    return result


def _forge(endpoint: str, run: str, credentials: Path, victim: str) -> dict[str, Any]:
    """An authenticated process out of its rights: read all, forge, post a goal."""
    out: dict[str, Any] = {}
    with open_node(_config(endpoint, credentials), run, FORGER) as node:
        box = node.subscribe(keys.run_all(run))
        for _ in range(20):
            env = Envelope.now(run, 10**6, FORGER)
            node.publish(keys.actions(run, victim), Actions(env, victim, (["*gas", 100],)))
            node.publish(keys.world_state(run), WorldState(env, {}, {}, []))
            node.publish(keys.world_events(run), WorldEvent(env, {"kind": "block",
                                                                   "segment": "S1"}))
            time.sleep(0.02)
        time.sleep(LISTEN_S)
        read = 0
        while (msg := box.get(0)) is not None:
            read += msg.env.sender != FORGER  # its own puts come back to it locally
        out["other_user_read_messages"] = read
        try:
            node.query(keys.goals(run, victim),
                       GoalRequest(node.envelope(), "post", victim, "(stopped ME)", 1, ""), 1.0)
            out["other_user_goal_post"] = "answered"
        except (NobodyServing, QueryFailed) as exc:
            out["other_user_goal_post"] = f"refused ({type(exc).__name__})"
    return out


def _operate(endpoint: str, run: str, credentials: Path, victim: str) -> dict[str, Any]:
    """The operator's own rights: list goals, send an event."""
    try:
        with open_node(_config(endpoint, credentials), run, OPERATOR) as node:
            reply = node.query(keys.goals(run, victim),
                               GoalRequest(node.envelope(), "list", victim, "", 0, ""), 5.0)
            key = keys.world_events(run)
            node.declare([key])
            node.wait_matching([key], 5.0)
            node.publish(key, WorldEvent(node.envelope(), {"kind": "unblock",
                                                           "segment": "S1"}))
            time.sleep(0.2)
        return {"operator_goal_list_ok": bool(reply.ok)}
    except BusError as exc:
        return {"operator_goal_list_ok": False, "operator_error": str(exc)}
