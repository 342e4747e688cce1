"""The Gymnasium world on MiniGrid: same seed same trace, malformed actions fail while the
episode goes on, bad input is one line naming it, checkpoint and restore, the episode ends
the run, and the environment's own frames."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import msgpack
import pytest

from tools.commands.scenario_check import load_checked
from tools.commands.simulate import simulate
from world.domain import episode_over, get_domain
from world.errors import ConfigError

ROOT = Path(__file__).resolve().parents[3]
DOORKEY = ROOT / "scenarios" / "minigrid_doorkey.toml"
TELEO = str(Path(sys.executable).parent / "teleo")
GYM = get_domain("gymnasium")


def _world(env: str = "MiniGrid-DoorKey-8x8-v0", seed: int = 1, **kwargs):
    return GYM.create({"domain": "gymnasium", "env": env, "env_kwargs": kwargs}, seed, ["ME"])


def test_same_seed_same_trace_and_another_seed_another_level():
    scenario, _ = load_checked(DOORKEY)
    first, again = simulate(scenario, seed=4), simulate(scenario, seed=4)
    assert first.trace == again.trace and len(first.trace) > 5
    other = simulate(scenario, seed=5)
    assert other.records[0] != first.records[0] or other.trace != first.trace


def test_the_snapshot_is_plain_data_and_a_restored_world_goes_on_the_same():
    world = _world("MiniGrid-Dynamic-Obstacles-8x8-v0", seed=3)
    msgpack.packb(world.snapshot_dict())
    world.apply_actions("ME", [["*right"]])
    world.step()
    copy = GYM.restore(world.checkpoint())
    for w in (world, copy):
        for action in ("*forward", "*left", "*forward"):
            w.apply_actions("ME", [[action]])
            w.step()
    assert copy.snapshot_dict() == world.snapshot_dict()


@pytest.mark.parametrize("action, reason", [
    (["*jump"], "unknown action '*jump'; known: *left, *right, *forward"),
    (["*left", 3], "*left takes no arguments"),
    (["left"], "unknown action 'left'"),
    ("forward", "malformed action"),
])
def test_a_malformed_action_fails_with_a_reason_and_the_episode_goes_on(action, reason):
    world = _world()
    before = world.snapshot_dict()
    [outcome] = world.apply_actions("ME", [action])
    world.step()
    assert outcome["status"] == "failed" and reason in outcome["reason"]
    after = world.snapshot_dict()
    assert after["state"] == before["state"] and after["episode"]["steps"] == 0
    assert after["counters"]["ME"]["actions_failed"] == 1
    [ok] = world.apply_actions("ME", [["*left"]])
    world.step()
    assert ok["status"] == "done" and world.snapshot_dict()["episode"]["steps"] == 1


def test_a_second_action_in_one_cycle_fails():
    world = _world()
    outcomes = world.apply_actions("ME", [["*left"], ["*right"]])
    assert [o["status"] for o in outcomes] == ["done", "failed"]
    assert "one action a cycle" in outcomes[1]["reason"]


@pytest.mark.parametrize("table, says", [
    ({"env": "MiniGrid-Nope-v0"}, "[world] env = 'MiniGrid-Nope-v0': not a registered"),
    ({"env": "CartPole-v1"}, "[world] env = 'CartPole-v1': no perception for its family"),
    ({"env": "MiniGrid-DoorKey-8x8-v0", "env_kwargs": {"bogus": 1}},
     "[world] env_kwargs = {'bogus': 1}: MiniGrid-DoorKey-8x8-v0 refuses them"),
    ({"env": "MiniGrid-DoorKey-8x8-v0", "env_kwargs": 3}, "[world] env_kwargs: expected a table"),
    ({"env": ""}, "[world] env: expected a registered environment id"),
    ({"env": "MiniGrid-DoorKey-8x8-v0", "size": 8}, "[world] size: unknown key"),
])
def test_bad_input_is_one_line_naming_it(table, says):
    with pytest.raises(ConfigError) as err:
        GYM.check_config({"domain": "gymnasium", **table}, ["ME"])
    assert str(err.value).startswith(says) and "\n" not in str(err.value)
    if "env = " in says:
        assert "families known: minigrid" in str(err.value)


def test_teleo_check_and_simulate_refuse_an_unknown_env_in_one_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(DOORKEY.read_text().replace("MiniGrid-DoorKey-8x8-v0", "MiniGrid-Nope-v0")
                   .replace('"programs/', f'"{ROOT}/programs/'))
    for command in (["check"], ["simulate", "--no-record"]):
        done = subprocess.run([TELEO, *command, str(bad)], capture_output=True, text=True,
                              cwd=ROOT, timeout=120)
        assert done.returncode != 0 and "Traceback" not in done.stderr + done.stdout
        assert "MiniGrid-Nope-v0" in done.stderr + done.stdout
        assert "families known: minigrid" in done.stderr + done.stdout


def test_the_episode_over_ends_the_run_and_the_summary_holds_it(tmp_path):
    out = tmp_path / "summary.json"
    done = subprocess.run([TELEO, "simulate", str(DOORKEY), "--no-record", "--summary",
                           str(out), "--render", str(tmp_path / "run.gif")],
                          capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    summary = json.loads(out.read_text())
    episode = summary["episode"]
    assert episode["terminated"] and not episode["truncated"] and episode["reward"] > 0
    assert summary["cycles"] == episode["steps"] + 1 < 700   # the last state's cycle too
    assert summary["status"] == "completed" and summary["world_reason"] == "the episode is over"
    assert summary["achievements"] == {"ME": {"missions": 1}}
    assert (tmp_path / "run.gif").read_bytes()[:6] == b"GIF89a"


def test_a_world_after_its_episode_refuses_actions():
    world = _world("MiniGrid-Empty-5x5-v0", seed=0)
    for action in ("*forward", "*forward", "*right", "*forward", "*forward"):
        world.apply_actions("ME", [[action]])
        world.step()
    assert episode_over(world) and world.snapshot_dict()["episode"]["reward"] > 0
    [refused] = world.apply_actions("ME", [["*left"]])
    assert refused["status"] == "failed" and refused["reason"] == "the episode is over"


def test_the_picture_is_the_environments_own_frame(tmp_path):
    import numpy as np
    from PIL import Image

    world = _world(seed=2)
    GYM.render([world.snapshot_dict()], tmp_path / "f.png", "ME")
    drawn = np.asarray(Image.open(tmp_path / "f.png").convert("RGB"))
    own = world.env.unwrapped.get_frame(highlight=False, tile_size=32)
    assert drawn.shape == own.shape and (drawn == own).all()


def test_the_view_shows_the_environments_frame():
    from tools.view.scene import map_of, render_png

    snap = _world(seed=2).snapshot_dict()
    assert map_of(snap)["drawn"] is False                 # the page asks for the PNG
    assert render_png([snap], "ME")[:8] == b"\x89PNG\r\n\x1a\n"
