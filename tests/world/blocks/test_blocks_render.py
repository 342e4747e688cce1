"""Pictures of the Blocks World: a PNG of one cycle and a GIF of a run, through the domain's
render hook (what `teleo simulate --render` and `teleo launch --render` call)."""

from __future__ import annotations

from blocks_helpers import act, world
from PIL import Image

from world.blocks import DOMAIN


def _snapshots() -> list[dict]:
    w = world([["A", "B", "C"]], agents=("ME", "YOU"), holding={"YOU": "D"})
    snaps = [w.snapshot_dict()]
    for action in (["*unstack", "C", "B"], ["*putdown", "C", "T"], ["*unstack", "B", "A"]):
        act(w, *action)
        snaps.append(w.snapshot_dict())
    return snaps


def test_a_png_of_the_last_cycle(tmp_path):
    path = tmp_path / "blocks.png"
    assert DOMAIN.render(_snapshots(), path, "ME") == 1
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    img = Image.open(path).convert("RGB")
    assert img.width > 500 and img.height > 200
    # the chosen agent's gripper is red somewhere in the picture
    assert (220, 40, 40) in {img.getpixel((x, y)) for x in range(0, img.width, 2)
                             for y in range(0, img.height, 2)}


def test_a_gif_of_the_run_has_a_frame_per_snapshot(tmp_path):
    path = tmp_path / "blocks.gif"
    snaps = _snapshots()
    assert DOMAIN.render(snaps, path, None) == len(snaps)
    with Image.open(path) as gif:
        assert gif.format == "GIF" and gif.n_frames == len(snaps)
