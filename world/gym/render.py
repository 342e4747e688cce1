"""The environment's own frames (its family's `frame`: MiniGrid's tile renderer) of
snapshot dicts, as a still (PNG, JPEG: the last) or an animation (GIF: them all)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from PIL import Image

from world.gym.families import family
from world.pictures import is_animation, save_animation, save_still, thinning


def _image(snapshot: dict[str, Any]) -> Image.Image:
    state = snapshot["state"]
    return Image.fromarray(family(state["family"]).frame(state))


def render_frames(snapshots: Sequence[dict[str, Any]], path: Path) -> int:
    """Write the picture; returns the frames drawn."""
    if is_animation(path):
        every = thinning(len(snapshots))
        frames = [_image(s) for s in list(snapshots)[::every]]
        save_animation(frames, path)
        return len(frames)
    save_still(_image(snapshots[-1]), path)
    return 1
