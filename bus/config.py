"""Bus session configuration: `BusConfig`, read from flags (`bus_options`) or the
environment (`BusConfig.from_env`), turned into a zenoh config (`to_zenoh`) or back into
command-line flags for child processes (`to_args`).

Defaults: peer mode, listening on loopback only (tcp/127.0.0.1, any free port), connecting
to a hub at tcp/127.0.0.1:7447 (`teleo router`, or the one the launcher spawns), multicast
scouting off. So it works on a machine with no multicast and no zenohd. Peers that meet at
the hub learn of each other by gossip and then talk directly.

Every mode retries a lost or refused connection to the hub every 0.1 to 0.5 s, so a restarted
router is rejoined within half a second of coming back (docs/faults.md). A secured process
(`credentials`: a file written by `teleo launch --secure`, bus/security.py) is a client over
TLS with its own user and password; a secured router reads its certificate, user dictionary
and access-control list from `router_security`.
"""

from __future__ import annotations

import enum
import functools
import json
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import click
import zenoh

from bus.errors import ConfigError
from bus.security import Credentials, RouterSecurity

DEFAULT_HUB = "tcp/127.0.0.1:7447"
LOOPBACK_ANY = "tcp/127.0.0.1:0"
ENV_MODE, ENV_CONNECT, ENV_LISTEN = "TELEO_ZENOH_MODE", "TELEO_ZENOH_CONNECT", "TELEO_ZENOH_LISTEN"
ENV_CREDENTIALS = "TELEO_CREDENTIALS"
# how a lost or refused link to the hub is retried [ms] (zenoh connect/retry)
RETRY = {"period_init_ms": 100, "period_max_ms": 500, "period_increase_factor": 2}


class Mode(enum.StrEnum):
    PEER = "peer"
    CLIENT = "client"
    ROUTER = "router"


@dataclass(frozen=True)
class BusConfig:
    """How one process joins the bus.

    mode: peer | client | router; connect / listen: zenoh endpoints such as
    "tcp/127.0.0.1:7447"; multicast: multicast scouting (off by default);
    lease_ms: link lease [ms]: a silent (e.g. SIGSTOPped) peer's liveliness token
    disappears after about this long; a SIGKILLed one within milliseconds;
    connect_timeout_ms: how long a client's open waits for an absent hub [ms] (a router
    being restarted) before failing; credentials: a credentials file (secured bus,
    bus/security.py); router_security: the router's security file (router mode only).
    """

    mode: Mode = Mode.PEER
    connect: tuple[str, ...] = (DEFAULT_HUB,)
    listen: tuple[str, ...] = (LOOPBACK_ANY,)
    multicast: bool = False
    lease_ms: int = 2000
    connect_timeout_ms: int = 5000
    credentials: str = ""
    router_security: str = ""

    def __post_init__(self) -> None:
        try:
            object.__setattr__(self, "mode", Mode(self.mode))
        except ValueError as exc:
            raise ConfigError(
                f"bus mode must be peer, client or router, got {self.mode!r}") from exc
        for name in ("connect", "listen"):
            eps = tuple(getattr(self, name))
            for ep in eps:
                if not isinstance(ep, str) or "/" not in ep:
                    raise ConfigError(f"{name} endpoint {ep!r} is not like 'tcp/HOST:PORT'")
            object.__setattr__(self, name, eps)
        if self.mode is Mode.CLIENT and not self.connect:
            raise ConfigError("client mode needs at least one connect endpoint")
        if self.lease_ms < 100:
            raise ConfigError(f"lease_ms must be >= 100, got {self.lease_ms}")

    @classmethod
    def from_env(cls, environ: Mapping[str, str] | None = None, **overrides: Any) -> BusConfig:
        """Defaults, overridden by TELEO_ZENOH_MODE / _CONNECT / _LISTEN (comma-separated)."""
        env = os.environ if environ is None else environ
        values: dict[str, Any] = {}
        if env.get(ENV_MODE):
            values["mode"] = env[ENV_MODE].strip()
        if ENV_CONNECT in env:
            values["connect"] = _split(env[ENV_CONNECT])
        if ENV_LISTEN in env:
            values["listen"] = _split(env[ENV_LISTEN])
        if env.get(ENV_CREDENTIALS):
            values["credentials"] = env[ENV_CREDENTIALS]
        values.update(overrides)
        return cls(**values)

    def with_hub(self, endpoint: str) -> BusConfig:
        """This config connecting to `endpoint` (e.g. a spawned router's) instead."""
        return replace(self, connect=(endpoint,))

    def to_args(self) -> list[str]:
        """The flags that `bus_options` parses back into this same config (for child processes)."""
        args = ["--mode", self.mode.value, "--connect", ",".join(self.connect),
                "--listen", ",".join(self.listen)]
        return args + (["--credentials", self.credentials] if self.credentials else [])

    @property
    def secured(self) -> bool:
        return bool(self.credentials or self.router_security)

    def to_zenoh(self) -> zenoh.Config:
        """The zenoh config for `zenoh.open` (docs/bus.md, "Zenoh in Python", item 4)."""
        conf = zenoh.Config()
        conf.insert_json5("mode", json.dumps(self.mode.value))
        conf.insert_json5("connect/endpoints", json.dumps(list(self.connect)))
        conf.insert_json5("listen/endpoints", json.dumps(list(self.listen)))
        conf.insert_json5("scouting/multicast/enabled", json.dumps(self.multicast))
        conf.insert_json5("transport/link/tx/lease", str(self.lease_ms))
        conf.insert_json5("connect/retry", json.dumps(RETRY))
        if self.mode is Mode.CLIENT:
            conf.insert_json5("connect/timeout_ms", str(self.connect_timeout_ms))
        if self.mode is Mode.ROUTER:
            conf.insert_json5("adminspace/enabled", "true")
        if self.credentials:
            _insert_credentials(conf, Credentials.load(self.credentials))
        if self.router_security:
            _insert_router_security(conf, RouterSecurity.load(self.router_security))
        return conf


def _insert_credentials(conf: zenoh.Config, cred: Credentials) -> None:
    """A client of a secured router: TLS checked against the run's CA, user and password."""
    conf.insert_json5("transport/link/tls/root_ca_certificate", json.dumps(cred.ca))
    conf.insert_json5("transport/auth/usrpwd/user", json.dumps(cred.user))
    conf.insert_json5("transport/auth/usrpwd/password", json.dumps(cred.password))


def _insert_router_security(conf: zenoh.Config, sec: RouterSecurity) -> None:
    """A secured router: its TLS certificate, the user dictionary, the access-control list."""
    conf.insert_json5("transport/link/tls/root_ca_certificate", json.dumps(sec.ca))
    conf.insert_json5("transport/link/tls/listen_certificate", json.dumps(sec.cert))
    conf.insert_json5("transport/link/tls/listen_private_key", json.dumps(sec.key))
    conf.insert_json5("transport/auth/usrpwd/dictionary_file", json.dumps(sec.users_file))
    conf.insert_json5("access_control", json.dumps(sec.acl))


def _split(text: str) -> tuple[str, ...]:
    return tuple(p.strip() for p in text.split(",") if p.strip())


def _merge(values: Sequence[str]) -> tuple[str, ...] | None:
    if not values:
        return None
    out: list[str] = []
    for v in values:
        out.extend(_split(v))
    return tuple(out)


def bus_options(fn: Callable) -> Callable:
    """Click decorator: adds --mode/--connect/--listen and passes `bus_config: BusConfig`.

    Flags override the environment (TELEO_ZENOH_*), which overrides the defaults.
    --connect/--listen take comma-separated endpoints and may repeat; an empty
    value (--listen '') means none.
    """

    @click.option("--mode", type=click.Choice([m.value for m in Mode]), default=None,
                  help="zenoh mode [env TELEO_ZENOH_MODE; default peer].")
    @click.option("--connect", multiple=True, metavar="ENDPOINTS",
                  help=f"Endpoints to connect to, comma-separated [env TELEO_ZENOH_CONNECT; "
                       f"default {DEFAULT_HUB}].")
    @click.option("--listen", multiple=True, metavar="ENDPOINTS",
                  help=f"Endpoints to listen on, comma-separated [env TELEO_ZENOH_LISTEN; "
                       f"default {LOOPBACK_ANY}].")
    @click.option("--credentials", default=None, metavar="FILE",
                  help="Credentials of a secured run (user, password, CA) [env "
                       "TELEO_CREDENTIALS].")
    @functools.wraps(fn)
    def wrapper(*args: Any, mode: str | None, connect: tuple[str, ...],
                listen: tuple[str, ...], credentials: str | None, **kwargs: Any) -> Any:
        overrides: dict[str, Any] = {}
        if mode:
            overrides["mode"] = mode
        if credentials:
            overrides["credentials"] = credentials
        for name, given in (("connect", connect), ("listen", listen)):
            merged = _merge(given)
            if merged is not None or given:
                overrides[name] = merged or ()
        try:
            kwargs["bus_config"] = BusConfig.from_env(**overrides)
        except ConfigError as exc:
            raise click.BadParameter(str(exc)) from exc
        return fn(*args, **kwargs)

    return wrapper
