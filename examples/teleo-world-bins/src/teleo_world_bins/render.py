"""A top view of the bins world for people: a PNG (or JPEG) of the last snapshot, or a GIF of
them all, by the file's suffix (world/pictures.py). `teleo view` shows this PNG, since the
Domain has no scene hook of its own, and `teleo render`/`simulate --render` write it."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from PIL import Image, ImageDraw

from world.pictures import is_animation, save_animation, save_still, thinning

PX = 80             # [px/m]
COLOURS = {"red": (220, 60, 50), "blue": (60, 110, 220), "green": (60, 170, 80),
           "yellow": (230, 190, 40)}


def _frame(snap: dict[str, Any], agent: str | None) -> Image.Image:
    w, d = snap["size"]
    img = Image.new("RGB", (int(w * PX), int(d * PX) + 24), (245, 245, 240))
    draw = ImageDraw.Draw(img)

    def px(x: float, y: float) -> tuple[float, float]:
        return x * PX, (d - y) * PX

    draw.rectangle([0, 0, w * PX - 1, d * PX - 1], outline=(40, 40, 40), width=3)
    for colour, (bx, by) in snap["bins"].items():
        (x0, y0), (x1, y1) = px(bx - 0.7, by + 0.7), px(bx + 0.7, by - 0.7)
        draw.rectangle([x0, y0, x1, y1], outline=COLOURS.get(colour, (90, 90, 90)), width=4)
    for b in snap["balls"]:
        x, y = px(b["x"], b["y"])
        fill = COLOURS.get(b["colour"], (90, 90, 90))
        draw.ellipse([x - 12, y - 12, x + 12, y + 12], fill=fill, outline=(30, 30, 30))
        draw.text((x - 6, y - 6), b["id"], fill=(255, 255, 255))
    for r in snap["robots"]:
        x, y = px(r["x"], r["y"])
        edge = (220, 40, 40) if r["agent"] == agent else (60, 60, 60)
        draw.ellipse([x - 20, y - 20, x + 20, y + 20], outline=edge, width=3)
        draw.text((x - 8, y - 6), r["id"], fill=edge)
    sorted_n = sum(n.get("balls_sorted", 0) for n in snap["counters"].values())
    draw.text((6, d * PX + 6), f"cycle {snap['cycle']}  t {snap['time']:.1f} s  "
              f"balls sorted {sorted_n}", fill=(20, 20, 20))
    return img


def render(snapshots: Sequence[dict[str, Any]], path: Path, agent: str | None = None) -> int:
    """The last snapshot as a still, or every snapshot as a GIF; returns the frames drawn."""
    if is_animation(path):
        frames = [_frame(s, agent) for s in snapshots[::thinning(len(snapshots))]]
        save_animation(frames, path)
        return len(frames)
    save_still(_frame(snapshots[-1], agent), path)
    return 1
