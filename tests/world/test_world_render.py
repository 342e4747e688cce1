"""Pictures for people: a PNG of one cycle and a GIF of a run, checked with Pillow."""

from __future__ import annotations

from pathlib import Path

import pytest
from PIL import Image

from world.driving.config import WorldConfig
from world.driving.render import (
    COLORS,
    LEGEND_W,
    agent_trail,
    legend_key,
    render_gif,
    render_image,
    render_png,
    scene_bounds,
)
from world.driving.simulation import Simulation
from world.errors import WorldError
from world.pictures import FRAME_MS


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
        assert img.info["duration"] == 100      # 10 frames a second, whatever the run's dt


def test_rendering_an_unknown_agent_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(WorldError, match="NOBODY"):
        render_png(short_run(0)[0], tmp_path / "x.png", agent="NOBODY")
    with pytest.raises(WorldError, match="no snapshots"):
        render_gif([], tmp_path / "x.gif")


def test_follow_camera_draws_a_square_around_the_agent(tmp_path: Path) -> None:
    snaps = short_run(4)
    path = render_png(snaps[-1], tmp_path / "near.png", agent="YOU", px_per_m=5.0, follow=80.0)
    with Image.open(path) as img:
        assert img.size == (400 + LEGEND_W, 600)     # 80 m x 5 px/m; legend is 600 px tall
    gif = render_gif(snaps, tmp_path / "near.gif", px_per_m=2.0, follow=60.0)
    with Image.open(gif) as img:
        assert img.n_frames == 5 and img.size == (120 + LEGEND_W, 600)


def test_car_path_range_and_a_hit_pedestrian_have_distinct_colours(tmp_path: Path) -> None:
    """Issue 12, item 13: one red for the car, the path and the range ring (and a near red
    for a hit pedestrian) made them one blob; each now has its own, listed in the key."""
    shown = [COLORS[k] for k in ("me", "trail", "range", "down", "closed", "agent", "traffic",
                                 "ped", "package", "delivered")]
    assert len(set(shown)) == len(shown)
    assert [c for c, _ in legend_key("ME")] == shown[:3] + [COLORS[k] for k in (
        "agent", "traffic", "ped", "down", "closed", "package", "delivered")]
    snaps = short_run(30)
    path = render_png(snaps[-1], tmp_path / "c.png", agent="ME", trail=agent_trail(snaps, "ME"))
    with Image.open(path) as img:
        colors = {rgb for _, rgb in img.convert("RGB").getcolors(maxcolors=1 << 20)}
    assert {COLORS["me"], COLORS["trail"], COLORS["range"]} <= colors


def test_the_path_has_a_start_marker_and_arrows_and_there_is_a_scale_bar(tmp_path: Path) -> None:
    snaps = short_run(80)                       # ME drives ~100 m: arrows every 40 m
    trail = agent_trail(snaps, "ME")
    img = render_image(snaps[-1], "ME", 3.0, trail)
    bounds = scene_bounds([snaps[-1]])
    x0, y1 = bounds[0], bounds[3]

    def px(x: float, y: float) -> tuple[int, int]:
        return round((x - x0) * 3.0), round((y1 - y) * 3.0)

    sx, sy = px(*trail[0])
    ring = [img.getpixel((sx + dx, sy)) for dx in range(-9, 10)]
    assert COLORS["trail"] in ring and (255, 255, 255) in ring   # the white "S" ring
    plain = render_image(snaps[-1], "ME", 3.0, None)
    assert _count(img, COLORS["trail"]) - _count(plain, COLORS["trail"]) > 50
    bar = [img.getpixel((x, img.height - 14)) for x in range(14, 60)]
    assert bar.count((20, 20, 20)) > 30                           # the scale bar's line


def _count(img: Image.Image, rgb: tuple) -> int:
    return dict((c, n) for n, c in img.getcolors(maxcolors=1 << 20)).get(rgb, 0)


def test_labels_never_overlap_and_stay_in_the_picture() -> None:
    from PIL import ImageDraw

    from world.driving.placing import Labels as _Labels
    from world.driving.placing import font_of as _font

    img = Image.new("RGB", (300, 200))
    labels = _Labels(ImageDraw.Draw(img), 300, 200)
    labels.reserve((100, 100, 200, 115))                # a street label already drawn
    font = _font(12)
    for name in ("PACKET1", "PACKET2", "PACKET3", "ME", "YOU", "PACKET4"):
        labels.place(150, 100, name, 6, fill=(255, 0, 0), font=font)
    boxes = labels.taken
    for i, a in enumerate(boxes):
        assert 0 <= a[0] and a[2] <= 300 and 0 <= a[1] and a[3] <= 200
        for b in boxes[i + 1:]:
            assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (a, b)


def test_a_long_run_plays_at_ten_frames_a_second_with_the_frame_count_capped(
        tmp_path: Path) -> None:
    snaps = short_run(40)
    path = render_gif(snaps, tmp_path / "long.gif", px_per_m=0.5, max_frames=10)
    with Image.open(path) as img:
        assert img.n_frames == 9 and img.info["duration"] == FRAME_MS == 100   # 41 -> every 5th


def test_stills_are_png_or_jpeg_by_suffix_and_other_suffixes_are_refused(tmp_path: Path) -> None:
    snap = short_run(2)[-1]
    for name, fmt in (("a.png", "PNG"), ("b.jpg", "JPEG"), ("c.JPEG", "JPEG")):
        with Image.open(render_png(snap, tmp_path / name)) as img:
            assert img.format == fmt
    for name in ("d.bmp", "e", "f.png.txt"):
        with pytest.raises(WorldError, match=r"expected a picture file ending in \.png"):
            render_png(snap, tmp_path / name)
        assert not (tmp_path / name).exists()
