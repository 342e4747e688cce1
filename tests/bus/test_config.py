"""BusConfig: defaults, environment, flags, and the flags handed to child processes."""

from __future__ import annotations

import json

import click
import pytest
from click.testing import CliRunner

from bus.config import BusConfig, Mode, bus_options
from bus.errors import ConfigError


def test_defaults_are_a_loopback_peer_without_multicast():
    cfg = BusConfig()
    assert cfg.mode is Mode.PEER and not cfg.multicast
    assert cfg.listen == ("tcp/127.0.0.1:0",)
    conf = cfg.to_zenoh()
    assert json.loads(conf.get_json("scouting/multicast/enabled")) is False
    assert json.loads(conf.get_json("mode")) == "peer"


def test_environment_overrides_defaults():
    cfg = BusConfig.from_env({"TELEO_ZENOH_MODE": "client",
                              "TELEO_ZENOH_CONNECT": "tcp/10.0.0.1:7447, tcp/10.0.0.2:7447",
                              "TELEO_ZENOH_LISTEN": ""})
    assert cfg == BusConfig(Mode.CLIENT, ("tcp/10.0.0.1:7447", "tcp/10.0.0.2:7447"), ())


@pytest.mark.parametrize("kwargs, problem", [
    ({"mode": "hub"}, "peer, client or router"),
    ({"connect": ("localhost",)}, "tcp/HOST:PORT"),
    ({"mode": "client", "connect": ()}, "client mode needs"),
    ({"lease_ms": 5}, "lease_ms"),
])
def test_invalid_configs_are_refused(kwargs, problem):
    with pytest.raises(ConfigError, match=problem):
        BusConfig(**kwargs)


@click.command()
@bus_options
def show(bus_config: BusConfig) -> None:
    click.echo(repr(bus_config))


@pytest.mark.parametrize("cfg", [
    BusConfig(Mode.CLIENT, ("tcp/127.0.0.1:9000",), ()),
    BusConfig(Mode.PEER, (), ("tcp/127.0.0.1:0", "tcp/127.0.0.1:7000")),
])
def test_flags_round_trip_through_to_args_and_beat_the_environment(cfg):
    runner = CliRunner(env={"TELEO_ZENOH_MODE": "router", "TELEO_ZENOH_CONNECT": "tcp/x:1"})
    out = runner.invoke(show, cfg.to_args())
    assert out.exit_code == 0, out.output
    assert out.output.strip() == repr(cfg)
    bad = runner.invoke(show, ["--connect", "nowhere"])
    assert bad.exit_code != 0 and "tcp/HOST:PORT" in bad.output
