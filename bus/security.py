"""The secured bus (`teleo launch --secure`, docs/bus.md "Security"): TLS links, one user and
password per process, and an access-control list that lets each process use only its own
keys. Everything here is plain data; the certificates and passwords are made by
tools/secrets.py and the files are read by zenoh itself (bus/config.py).

Topology: in a secured run every process is a zenoh *client* of the run's router, which is the
only thing listening (`tls/HOST:PORT`). The router checks each client's user and password
(`transport/auth/usrpwd`) and applies the access-control list below to every message in and
out, by user name: the world alone puts world state, only the goal-entry process serves goal
requests, an agent's executive alone puts that agent's actions, and so on. The `operator`
user (the `teleo goal`, `event`, `inspect`, `echo`, `record` commands of the person who
launched the run) may read everything, post goal requests and world events, and nothing else.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from bus import keys
from bus.errors import ConfigError

OPERATOR = "operator"
LAUNCH = "launch"
AGENT_STAGES = ("perception", "inference", "executive")
_SUB = ("declare_subscriber",)


@dataclass(frozen=True)
class Credentials:
    """What one client needs to join a secured run: its user, password and the CA that
    signed the router's certificate (a PEM file)."""

    user: str
    password: str
    ca: str

    @classmethod
    def load(cls, path: str | Path) -> Credentials:
        """Read a credentials file (JSON); raises ConfigError naming the file and the key."""
        try:
            doc = json.loads(Path(path).read_text())
        except OSError as exc:
            raise ConfigError(f"{path}: cannot read credentials: {exc.strerror}") from exc
        except ValueError as exc:
            raise ConfigError(f"{path}: credentials are not valid JSON: {exc}") from exc
        if not isinstance(doc, dict):
            raise ConfigError(f"{path}: expected a JSON object with user, password and ca")
        for key in ("user", "password", "ca"):
            if not isinstance(doc.get(key), str) or not doc[key]:
                raise ConfigError(f"{path}: key {key!r}: expected a non-empty string, "
                                  f"got {doc.get(key)!r}")
        ca = Path(doc["ca"])
        if not ca.is_absolute():
            ca = Path(path).parent / ca
        return cls(doc["user"], doc["password"], str(ca))

    def save(self, path: Path) -> Path:
        """Write this as a JSON file readable by its owner only."""
        write_private(path, json.dumps({"user": self.user, "password": self.password,
                                        "ca": self.ca}, indent=1))
        return path


@dataclass(frozen=True)
class RouterSecurity:
    """The router's side: its certificate and key, the CA, the user/password dictionary
    file (lines `user:password`) and the access-control list (a dict, zenoh's schema)."""

    ca: str
    cert: str
    key: str
    users_file: str
    acl: dict[str, Any]

    @classmethod
    def load(cls, path: str | Path) -> RouterSecurity:
        try:
            doc = json.loads(Path(path).read_text())
            return cls(doc["ca"], doc["cert"], doc["key"], doc["users_file"], doc["acl"])
        except OSError as exc:
            raise ConfigError(f"{path}: cannot read router security: {exc.strerror}") from exc
        except (ValueError, KeyError, TypeError) as exc:
            raise ConfigError(f"{path}: router security file is malformed: {exc!r}") from exc

    def save(self, path: Path) -> Path:
        write_private(path, json.dumps(self.__dict__, indent=1))
        return path


def write_private(path: Path, text: str) -> None:
    """Write `text` to `path` with mode 0600 from the start (never readable by others)."""
    path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
    tmp = path.with_name(path.name + ".tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w") as out:
        out.write(text)
    os.replace(tmp, path)


def process_users(agents: Iterable[str]) -> list[str]:
    """Every user of a run: one per process, plus the launcher and the operator."""
    names = ["world", "goals", LAUNCH, OPERATOR]
    for agent in agents:
        names += [f"{agent}.{stage}" for stage in AGENT_STAGES]
    return names


def _rule(rid: str, messages: Iterable[str], flows: Iterable[str],
          key_exprs: Iterable[str]) -> dict[str, Any]:
    return {"id": rid, "permission": "allow", "messages": list(messages),
            "flows": list(flows), "key_exprs": list(key_exprs)}


def grants(run: str, user: str) -> dict[str, list[str]]:
    """What `user` may do, as {"put": keys, "sub": keys, "serve": keys, "ask": keys,
    "token": keys}: put = publish; sub = subscribe and receive; serve = answer queries;
    ask = send queries and receive the replies; token = declare liveliness tokens. The one
    declaration of which keys each process of a run uses: the secured router enforces it,
    `teleo graph --run` draws it (tools/records/run_graph.py)."""
    root = keys.run_root(run)
    own = {"put": [keys.stats(run, user)], "sub": [], "serve": [], "ask": [],
           "token": [keys.proc(run, user)]}
    if user == "world":
        own["put"] += [keys.world_state(run), keys.world_static(run)]
        own["sub"] += [keys.all_actions(run), keys.all_stats(run), keys.world_events(run)]
        own["serve"] += [keys.world_static(run)]   # its static part, asked
        own["serve"] += [keys.world_events(run)]   # `teleo event` asks for a verdict
        own["serve"] += [keys.world_control(run)]  # `teleo pause`, `step-run`, `resume`
    elif user == "goals":
        own["put"] += [f"{root}/agent/*/goal-list"]
        own["sub"] += [keys.world_state(run), f"{root}/agent/*/intention"]
        own["serve"] += [f"{root}/agent/*/goals"]
    elif user == OPERATOR:  # the person's tools, and the launch's recorder (its progress)
        own["put"] = [keys.world_events(run), keys.stats(run, keys.RECORDER)]
        own["sub"] += [keys.run_all(run)]
        own["ask"] += [f"{root}/agent/*/goals", keys.world_events(run)]
        own["ask"] += [keys.world_control(run), keys.world_static(run)]
        own["token"] = [keys.proc(run, "record"), keys.proc(run, keys.RECORDER)]
    elif user == LAUNCH:
        own["put"] = []
    else:
        agent, _, stage = user.rpartition(".")
        own["put"] += _stage_outputs(run, agent, stage)
        own["sub"] += _stage_inputs(run, agent, stage)
        if stage == "perception":   # the world's static part
            own["ask"] += [keys.world_static(run)]
    return own


def _stage_inputs(run: str, agent: str, stage: str) -> list[str]:
    if stage == "perception":
        return [keys.world_state(run)]
    if stage == "inference":
        return [keys.percepts(run, agent)]
    if stage == "executive":
        return [keys.percepts(run, agent), keys.beliefs(run, agent), keys.goal_list(run, agent)]
    raise ConfigError(f"user {agent}.{stage}: unknown stage {stage!r}; expected one of "
                      f"{list(AGENT_STAGES)}")


def _stage_outputs(run: str, agent: str, stage: str) -> list[str]:
    if stage == "perception":
        return [keys.percepts(run, agent)]
    if stage == "inference":
        return [keys.beliefs(run, agent)]
    return [keys.intention(run, agent), keys.actions(run, agent)]


def access_control(run: str, users: Iterable[str]) -> dict[str, Any]:
    """zenoh's `access_control` config for a run's router: deny by default; each user may
    only what `grants` lists (ingress: what it sends; egress: what the router delivers to
    it). Every user may watch the liveliness tokens of the run (who is up)."""
    procs = keys.all_procs(run)
    rules = [_rule("presence-in", ["declare_liveliness_subscriber", "liveliness_query"],
                   ["ingress"], [procs]),
             _rule("presence-out", ["liveliness_token", "reply"], ["egress"], [procs]),
             # who subscribes to or serves what (key expressions, never data): a publisher
             # that is not told of a subscriber does not send at all (zenoh's write-side
             # filtering), and the clock subscribes with wildcards (agent/*/actions)
             _rule("declarations-out", ["declare_subscriber", "declare_queryable"],
                   ["egress"], [keys.run_all(run)])]
    common = ["presence-in", "presence-out", "declarations-out"]
    subjects, policies = [], [{"rules": common, "subjects": []}]
    for n, user in enumerate(users):
        subject = f"s{n}"
        subjects.append({"id": subject, "usernames": [user]})
        policies[0]["subjects"].append(subject)
        g = grants(run, user)
        mine = [
            _rule(f"u{n}-put", ["put", "delete"], ["ingress"], g["put"]),
            _rule(f"u{n}-sub", _SUB, ["ingress"], g["sub"]),
            _rule(f"u{n}-recv", ["put", "delete"], ["egress"], g["sub"]),
            _rule(f"u{n}-serve", ["declare_queryable", "reply"], ["ingress"], g["serve"]),
            _rule(f"u{n}-queried", ["query"], ["egress"], g["serve"]),
            _rule(f"u{n}-ask", ["query"], ["ingress"], g["ask"]),
            _rule(f"u{n}-answered", ["reply"], ["egress"], g["ask"]),
            _rule(f"u{n}-token", ["liveliness_token"], ["ingress"], g["token"]),
        ]
        mine = [r for r in mine if r["key_exprs"]]
        rules += mine
        policies.append({"rules": [r["id"] for r in mine], "subjects": [subject]})
    return {"enabled": True, "default_permission": "deny", "rules": rules,
            "subjects": subjects, "policies": policies}
