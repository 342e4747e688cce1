"""Pictures for people: a PNG of one cycle and a GIF of a run, checked with Pillow."""

from __future__ import annotations

from pathlib import Path

import pytest
from PIL import Image

from world.driving.config import WorldConfig
from world.driving.render import COLORS, LEGEND_W, render_gif, render_png
from world.driving.simulation import Simulation
from world.errors import WorldError


def short_run(steps: int) -> list:
    sim = Simulation(WorldConfig(pedestrians=6, traffic=3), seed=3, agents=["ME", "YOU"])
    sim.apply_actions("ME", [["*gas", 40]])
    snaps = [sim.snapshot()]
    for _ in range(steps):
        sim.step()
        snaps.append(sim.snapshot())
    return snaps


def test_png_of_one_cycle(tmp_path: Path) -> None:
    snap = short_run(5)[-1]
    path = render_png(snap, tmp_path / "cycle.png", agent="ME")
    with Image.open(path) as img:
        assert img.format == "PNG" and img.width > 800 and img.height > 600
        assert img.getpixel((img.width - 50, 5)) != img.getpixel((5, 5))   # legend panel
        colors = {rgb for _, rgb in img.convert("RGB").getcolors(maxcolors=1 << 20)}
    for name in ("me", "agent", "traffic", "ped", "building", "yellow", "road"):
        assert COLORS[name] in colors, name


def test_gif_of_a_run(tmp_path: Path) -> None:
    snaps = short_run(6)
    path = render_gif(snaps, tmp_path / "run.gif", every=2, px_per_m=0.8)
    with Image.open(path) as img:
        assert img.format == "GIF" and img.n_frames == 4
        assert img.info["duration"] == 200      # 2 cycles of 0.1 s per frame: real time


def test_rendering_an_unknown_agent_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(WorldError, match="NOBODY"):
        render_png(short_run(0)[0], tmp_path / "x.png", agent="NOBODY")
    with pytest.raises(WorldError, match="no snapshots"):
        render_gif([], tmp_path / "x.gif")


def test_follow_camera_draws_a_square_around_the_agent(tmp_path: Path) -> None:
    snaps = short_run(4)
    path = render_png(snaps[-1], tmp_path / "near.png", agent="YOU", px_per_m=5.0, follow=80.0)
    with Image.open(path) as img:
        assert img.size == (400 + LEGEND_W, 520)     # 80 m x 5 px/m; legend is 520 px tall
    gif = render_gif(snaps, tmp_path / "near.gif", px_per_m=2.0, follow=60.0)
    with Image.open(gif) as img:
        assert img.n_frames == 5 and img.size == (120 + LEGEND_W, 520)
