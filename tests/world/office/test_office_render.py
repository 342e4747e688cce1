"""Pictures of the office floor: a PNG of a cycle with the robot's path, a GIF of a run."""

from __future__ import annotations

import math

import pytest
from office_helpers import OFFICE, office
from PIL import Image

from world.errors import WorldError
from world.office.floor import build_floor
from world.office.render import COLORS, render_image
from world.office.snapshot import OfficeSnapshot

PX = 14.0   # render_image's default scale [px/m]; the floor is drawn 1 m in from the edges


def _px(snap: OfficeSnapshot, x: float, y: float) -> tuple[int, int]:
    height = 2 * snap.config.room_depth + 2 * snap.config.corridor_width + \
        snap.config.middle_depth
    return round((x + 1.0) * PX), round((height + 1.0 - y) * PX)


def _run(cycles: int = 40) -> list[dict]:
    world = office()
    world.inject({"kind": "close", "door": "d-5304"})
    world.inject({"kind": "block", "door": "d-north"})
    world.apply_actions("ME", [["*goto", "r-5303"]])
    snaps = []
    for _ in range(cycles):
        world.step()
        world.apply_actions("ME", [])
        snaps.append(world.snapshot_dict())
    return snaps


def test_the_picture_shows_doors_people_and_the_robot():
    snaps = _run()
    snap = OfficeSnapshot.from_dict(snaps[-1])
    img = render_image(snap, "ME")
    assert img.getpixel(_px(snap, 11.0, 18.0)) == COLORS["closed"]      # d-5304 leaf
    me = snap.robot("ME")
    back = math.radians(me.heading + 180.0)                      # behind its heading mark
    assert img.getpixel(_px(snap, me.x + 0.2 * math.cos(back), me.y + 0.2 * math.sin(back))) \
        == COLORS["me"]
    jhm = next(p for p in snap.people if p.id == "jhm")
    assert img.getpixel(_px(snap, jhm.x, jhm.y)) == COLORS["person"]


def test_a_png_and_a_gif_of_a_run(tmp_path):
    snaps = _run()
    assert OFFICE.render(snaps, tmp_path / "run.png", "ME") == 1
    assert (tmp_path / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    png = Image.open(tmp_path / "run.png")
    assert png.width > 800 and png.height >= 440
    assert OFFICE.render(snaps[::5], tmp_path / "run.gif", "ME") == 8
    gif = Image.open(tmp_path / "run.gif")
    assert gif.n_frames == 8


def test_the_path_so_far_is_drawn(tmp_path):
    snaps = _run()
    OFFICE.render(snaps, tmp_path / "run.png", "ME")
    img = Image.open(tmp_path / "run.png").convert("RGB")
    first = OfficeSnapshot.from_dict(snaps[3]).robot("ME")     # passed long ago, in c-north
    assert img.getpixel(_px(OfficeSnapshot.from_dict(snaps[0]), first.x, first.y)) == \
        COLORS["trail"]


def test_rendering_an_unknown_robot_is_refused():
    snap = OfficeSnapshot.from_dict(office().snapshot_dict())
    with pytest.raises(WorldError, match="no robot 'R9'"):
        render_image(snap, "R9")


def test_a_wide_floor_has_its_legend_below_so_the_picture_fits_a_view_panel():
    """Issue 31, N17: beside the floor the legend made a 1196 x 440 picture, which the web
    view's panel (about 740 x 820 in a 1400 x 900 window) shrank to 0.6, its 12 px text to
    7 px. Under the floor the picture is 896 x 612: shrunk to 0.83 at most there."""
    snap = OfficeSnapshot.from_dict(_run()[-1])
    img = render_image(snap, "ME")
    assert img.width / img.height < 1.6
    assert min(740 / img.width, 820 / img.height) > 0.8
    floor_h = round((build_floor(snap.config).height + 2) * PX)
    assert img.getpixel((img.width - 5, floor_h + 5)) == COLORS["legend"]   # under the floor
