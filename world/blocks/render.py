"""Side views of the Blocks World for people: a PNG of one cycle, a GIF of a run.

Drawn: the floor and the walls, the table with its name and column marks, every block in its
own colour with its name (rotated as it lies), each agent's gripper (a bar with two jaws over
the column of its last action; the chosen agent's red, others grey) holding its block, and a
legend with cycle, time, each hand's status and counters, the events of the cycle and a key.
"""

from __future__ import annotations

import math
from pathlib import Path

from PIL import Image, ImageDraw, ImageFont

from world.blocks.snapshot import BlocksSnapshot, BlockState, HandState
from world.blocks.table import FLOOR_MARGIN, floor_span
from world.errors import WorldError
from world.pictures import save_animation, save_still, scale_bar, thinning

LEGEND_W = 260      # [px]
MARGIN = 1.0        # [m] drawn around the scene
PALETTE = ((230, 90, 70), (70, 130, 220), (240, 180, 40), (80, 170, 90), (160, 90, 200),
           (240, 130, 180), (60, 180, 190), (200, 120, 50), (120, 120, 200), (150, 190, 60))
COLORS = {"sky": (244, 246, 250), "floor": (120, 110, 100), "table": (170, 120, 70),
          "edge": (60, 50, 40), "text": (20, 20, 20), "me": (220, 40, 40),
          "other": (110, 110, 120), "legend": (250, 250, 246), "fell": (200, 40, 40)}


class _View:
    """World [m] to pixel transform (y up in the world, down in the image)."""

    def __init__(self, x0: float, x1: float, y0: float, y1: float, px_per_m: float) -> None:
        self.s, self.x0, self.y1 = px_per_m, x0, y1
        self.size = (int((x1 - x0) * px_per_m), int((y1 - y0) * px_per_m))

    def __call__(self, x: float, y: float) -> tuple[float, float]:
        return (x - self.x0) * self.s, (self.y1 - y) * self.s


def _font(size: int) -> ImageFont.ImageFont:
    return ImageFont.load_default(size=size)


def scene_top(snaps: list[BlocksSnapshot]) -> float:
    """The height [m] to draw: above every gripper and block of these snapshots."""
    tops = [h.y + 0.6 for s in snaps for h in s.hands]
    tops += [b.y + b.height for s in snaps for b in s.blocks]
    return max([s.table.height + 3.0 for s in snaps] + tops) + MARGIN


def frame_top(snaps: list[BlocksSnapshot], agent: str | None, px_per_m: float) -> float:
    """The top [m] of pictures of these snapshots: the scene's, raised so that the longest
    legend fits beside it (more sky rather than a cut legend)."""
    legend = max(20 + sum(20 if big else 17 for _, big in _legend_lines(s, agent))
                 for s in snaps)                                   # [px]
    return max(scene_top(snaps), legend / px_per_m - MARGIN)


def colour(snap: BlocksSnapshot, name: str) -> tuple[int, int, int]:
    """A block's colour: by its rank among the snapshot's block names (stable over a run)."""
    names = sorted(b.name for b in snap.blocks)
    return PALETTE[names.index(name) % len(PALETTE)] if name in names else PALETTE[0]


def render_image(snap: BlocksSnapshot, agent: str | None = None, px_per_m: float = 28.0,
                 top: float | None = None) -> Image.Image:
    """One cycle as an RGB image with the legend on the right."""
    x0, x1 = floor_span(snap.table)
    lines = _legend_lines(snap, agent)
    view = _View(x0 - MARGIN, x1 + MARGIN, -MARGIN, top or frame_top([snap], agent, px_per_m),
                 px_per_m)
    height = view.size[1]
    img = Image.new("RGB", (view.size[0] + LEGEND_W, height), COLORS["sky"])
    draw = ImageDraw.Draw(img)
    _table(draw, view, snap, height)
    held = {b.name: b for b in snap.blocks}
    for b in snap.blocks:
        _block(draw, view, b, colour(snap, b.name))
    for h in snap.hands:
        width = held[h.holding].width if h.holding in held else 2.0
        _gripper(draw, view, h, width, COLORS["me"] if h.agent == agent else COLORS["other"])
    _legend(draw, lines, view.size[0], height)
    scale_bar(draw, 12, height - 14, view.s, max_px=view.size[0] / 4)
    return img


def _table(draw: ImageDraw.ImageDraw, v: _View, snap: BlocksSnapshot, height: int) -> None:
    t = snap.table
    x0, x1 = floor_span(t)
    draw.rectangle([v(x0 - MARGIN, 0), (v(x1 + MARGIN, 0)[0], height)], fill=COLORS["floor"])
    for x in (x0, x1):
        draw.line([v(x, 0), v(x, v.y1)], fill=COLORS["edge"], width=3)
    lo, hi = t.span
    draw.rectangle([v(lo, t.height), v(hi, 0)], fill=COLORS["table"], outline=COLORS["edge"])
    small = _font(max(10, round(0.45 * v.s)))
    for k in range(t.columns):
        x, y = v(t.column_x(k), t.height)
        draw.line([(x, y), (x, y + 6)], fill=COLORS["edge"], width=2)
        draw.text((x, y + 8), str(k), fill=COLORS["edge"], font=small, anchor="mt")
    draw.text(v((lo + hi) / 2, t.height / 2), t.name, fill=(255, 255, 255),
              font=_font(max(12, round(0.8 * v.s))), anchor="mm")


def _block(draw: ImageDraw.ImageDraw, v: _View, b: BlockState, fill: tuple) -> None:
    a = math.radians(b.angle)
    c, s = math.cos(a), math.sin(a)
    corners = [(b.x + dx * c - dy * s, b.y + dx * s + dy * c)
               for dx, dy in ((-b.width / 2, -b.height / 2), (b.width / 2, -b.height / 2),
                              (b.width / 2, b.height / 2), (-b.width / 2, b.height / 2))]
    draw.polygon([v(*p) for p in corners], fill=fill, outline=COLORS["edge"], width=2)
    size = max(10, round(0.6 * v.s * min(1.0, b.width, b.height)))
    draw.text(v(b.x, b.y), b.name, fill=(255, 255, 255), font=_font(size), anchor="mm")


def _gripper(draw: ImageDraw.ImageDraw, v: _View, h: HandState, width: float,
             color: tuple) -> None:
    """A cable from the top, a bar and two jaws reaching down beside the held block."""
    x, y = v(h.x, h.y)
    half, reach = (width / 2 + 0.15) * v.s, 0.5 * v.s
    draw.line([(x, 0), (x, y)], fill=color, width=3)
    draw.rectangle([x - half, y - 4, x + half, y + 4], fill=color)
    for side in (-1, 1):
        draw.line([(x + side * half, y), (x + side * half, y + reach)], fill=color, width=4)
    draw.text((x + half + 6, y - 6), f"{h.agent} {h.hand}", fill=color,
              font=_font(max(10, round(0.45 * v.s))), anchor="lb")


def _legend_lines(snap: BlocksSnapshot, agent: str | None) -> list[tuple[str, bool]]:
    """The legend's lines, each with whether it is a heading."""
    lines = [(f"Blocks World  cycle {snap.cycle}", True), (f"time {snap.time:g} s", False)]
    for h in snap.hands:
        mark = "  (red)" if h.agent == agent else ""
        lines += [("", False), (f"agent {h.agent}{mark}", True),
                  (f"hand {h.hand}: {h.holding or 'empty'}", False)]
        lines += [(f"{k.replace('_', ' ')}: {n}", False)
                  for k, n in snap.counters.get(h.agent, {}).items()]
    happened = [_event_text(e) for e in snap.events]
    if happened:
        lines += [("", False), ("events", True)] + [(t, False) for t in happened[:6]]
    return lines + [("", False), ("key", True), ("block: its name, in its colour", False),
                    ("gripper: bar and jaws on a cable", False),
                    ("held block: between the jaws", False),
                    (f"table {snap.table.name}: columns 0, 1, ...", False),
                    (f"floor: {FLOOR_MARGIN:g} m each side, walls", False),
                    ("scale bar: bottom left", False)]


def _legend(draw: ImageDraw.ImageDraw, lines: list[tuple[str, bool]], x0: int,
            height: int) -> None:
    draw.rectangle([x0, 0, x0 + LEGEND_W, height], fill=COLORS["legend"])
    big, font = _font(16), _font(13)
    y = 10
    for text, heading in lines:
        draw.text((x0 + 12, y), text, fill=COLORS["text"], font=big if heading else font)
        y += 20 if heading else 17


def _event_text(e: dict) -> str:
    kind = e.get("kind", "?")
    if kind == "fell":
        who = f" ({e['agent']})" if e.get("agent") else ""
        return f"{e.get('block')} fell{who}"
    if kind == "injected":
        return f"event {e.get('event', {}).get('kind', '?')}"
    return f"{kind} {e.get('block', '')}".strip()


def render_png(snap: BlocksSnapshot, path: str | Path, agent: str | None = None,
               px_per_m: float = 28.0) -> Path:
    """Write one cycle as a PNG or JPEG (by suffix); returns the path."""
    return save_still(render_image(snap, agent, px_per_m), path)


def render_gif(snaps: list[BlocksSnapshot], path: str | Path, agent: str | None = None,
               px_per_m: float = 28.0, frame_ms: int = 500) -> Path:
    """Write an animated GIF of a run, one frame per snapshot (thinned to at most
    pictures.MAX_FRAMES), `frame_ms` [ms] each (a Blocks World cycle is one whole action, so
    shown longer than a driving frame), all frames drawn to the same height."""
    if not snaps:
        raise WorldError(f"render_gif {path}: no snapshots")
    top = frame_top(snaps, agent, px_per_m)
    chosen = snaps[::thinning(len(snaps))]
    return save_animation([render_image(s, agent, px_per_m, top) for s in chosen], path,
                          frame_ms)


__all__ = ["frame_top", "render_gif", "render_image", "render_png", "scene_top"]
