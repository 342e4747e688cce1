"""What every domain's pictures share: the file formats (by suffix), saving a still or an
animation, the frame rate of animations, and a scale bar.

A still is a PNG or a JPEG (`.png`, `.jpg`, `.jpeg`), an animation a GIF (`.gif`); any other
suffix is refused before anything is drawn (`picture_format`), so `--render out.bmp` fails at
once instead of writing PNG data under a BMP name. Animations play at FRAME_MS per frame (10
frames a second: smooth enough to follow a car); a long run is thinned to at most MAX_FRAMES
frames rather than played slower.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

from PIL import Image, ImageDraw, ImageFont

from world.errors import WorldError

FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG", ".gif": "GIF"}
FRAME_MS = 100        # [ms] per animation frame (10 frames/s)
MAX_FRAMES = 300      # frames of one animation (30 s of playback)


def picture_format(path: str | Path) -> str:
    """PNG, JPEG or GIF by the suffix of ``path``; raises WorldError for any other."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise WorldError(f"{path}: expected a picture file ending in .png or .jpg (one cycle) "
                         f"or .gif (the run), got {suffix or 'no suffix'!r}")
    return FORMATS[suffix]


def is_animation(path: str | Path) -> bool:
    """Whether ``path`` asks for the whole run (a GIF) rather than one cycle."""
    return picture_format(path) == "GIF"


def save_still(img: Image.Image, path: str | Path) -> Path:
    """Save one picture as PNG or JPEG by ``path``'s suffix (a GIF suffix: one frame)."""
    path = Path(path)
    fmt = picture_format(path)
    if fmt == "JPEG":
        img.convert("RGB").save(path, format="JPEG", quality=90)
    else:
        img.save(path, format=fmt)
    return path


def thinning(count: int, every: int = 1, max_frames: int = MAX_FRAMES) -> int:
    """The step through ``count`` snapshots that keeps at most ``max_frames`` of them."""
    return max(1, every, math.ceil(count / max_frames))


def save_animation(frames: Sequence[Image.Image], path: str | Path,
                   frame_ms: int = FRAME_MS) -> Path:
    """Save ``frames`` as a looping GIF at ``frame_ms`` per frame."""
    if not frames:
        raise WorldError(f"{path}: no frames to save")
    path = Path(path)
    first, *rest = [f.convert("P", palette=Image.Palette.ADAPTIVE) for f in frames]
    first.save(path, format="GIF", save_all=True, append_images=rest, duration=frame_ms,
               loop=0)
    return path


def nice_length(most: float) -> float:
    """The longest of 1, 2 or 5 times a power of ten not above ``most`` [m] (> 0)."""
    power = 10.0 ** math.floor(math.log10(most))
    return max(k * power for k in (1, 2, 5) if k * power <= most)


def scale_bar(draw: ImageDraw.ImageDraw, x: float, y: float, px_per_m: float,
              max_px: float = 160, color: tuple = (20, 20, 20)) -> float:
    """Draw a scale bar with its left end at pixel (x, y): a round length [m] no longer than
    ``max_px`` pixels, with end ticks and its length written above. Returns the length [m]."""
    metres = nice_length(max_px / px_per_m)
    w = metres * px_per_m
    draw.rectangle([x - 2, y - 18, x + w + 2, y + 6], fill=(255, 255, 255))
    draw.line([(x, y), (x + w, y)], fill=color, width=3)
    for tick in (x, x + w / 2, x + w):
        draw.line([(tick, y - 5), (tick, y + 4)], fill=color, width=2)
    draw.text((x + w / 2, y - 6), f"{metres:g} m", fill=color,
              font=ImageFont.load_default(size=12), anchor="ms")
    return metres
