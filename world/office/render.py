"""Top-down pictures of the office floor for people: a PNG of one cycle, a GIF of a run.

Drawn: rooms coloured by kind and labelled (id, kind), corridors, walls, doors (green open,
red closed, orange blocked with a cross), people (blue, named), anonymous occupants (a count),
items beside their holders (white mail, yellow fax, brown coffee, blue once cold), obstacles
(black), each robot (red, the chosen one; orange, others) with its path so far (red line) and
the route still ahead (dashed), and a legend with cycle, time, the robot's operation, what it
carries, its counters and the key.
"""

from __future__ import annotations

import math
from itertools import pairwise
from pathlib import Path

from PIL import Image, ImageDraw, ImageFont

from world.errors import WorldError
from world.office.floor import Floor, build_floor
from world.office.physics import PERSON_RADIUS
from world.office.routes import ROBOT_RADIUS
from world.office.snapshot import OfficeSnapshot
from world.pictures import MAX_FRAMES, save_animation, save_still, scale_bar, thinning

LEGEND_W = 300     # [px]
LEGEND_BELOW_H = 220  # [px] the legend's height under a wide floor (caption | key columns)
MARGIN = 1.0       # [m]
KIND_COLORS = {"office": (236, 226, 206), "conference": (206, 222, 240),
               "mailroom": (240, 214, 226), "kitchen": (222, 240, 206),
               "lounge": (240, 236, 196), "lab": (218, 212, 240), "printer": (226, 226, 226)}
COLORS = {"floor": (250, 250, 248), "corridor": (232, 232, 228), "block": (150, 146, 140),
          "wall": (60, 56, 52), "text": (20, 20, 20), "open": (40, 170, 70),
          "closed": (210, 40, 40), "blocked": (240, 140, 20), "person": (40, 90, 200),
          "me": (220, 30, 30), "robot": (245, 140, 20), "trail": (220, 30, 30),
          "route": (120, 120, 120), "obstacle": (20, 20, 20), "legend": (250, 250, 246),
          "mail": (255, 255, 255), "fax": (250, 220, 60), "coffee": (120, 70, 30),
          "cold": (80, 150, 230), "item": (180, 180, 180)}


class _View:
    """Floor [m] to pixels (y up on the floor, down in the image)."""

    def __init__(self, floor: Floor, px_per_m: float) -> None:
        self.s, self.h = px_per_m, floor.height + MARGIN
        self.size = (round((floor.width + 2 * MARGIN) * px_per_m),
                     round((floor.height + 2 * MARGIN) * px_per_m))

    def __call__(self, x: float, y: float) -> tuple[float, float]:
        return (x + MARGIN) * self.s, (self.h - y) * self.s


def _font(size: int) -> ImageFont.ImageFont:
    return ImageFont.load_default(size=size)


def _floor(draw: ImageDraw.ImageDraw, v: _View, floor: Floor) -> None:
    for c in floor.corridors:
        draw.rectangle([v(c.x0, c.y1), v(c.x1, c.y0)], fill=COLORS["corridor"])
    for x0, y0, x1, y1 in floor.blocks:
        draw.rectangle([v(x0, y1), v(x1, y0)], fill=COLORS["block"])
    font, small = _font(max(10, round(v.s * 0.9))), _font(max(9, round(v.s * 0.7)))
    for r in floor.rooms:
        draw.rectangle([v(r.x0, r.y1), v(r.x1, r.y0)], fill=KIND_COLORS.get(r.kind, (236, 236,
                                                                                     236)))
        cx, cy = v((r.x0 + r.x1) / 2, (r.y0 + r.y1) / 2)
        draw.text((cx, cy - v.s * 0.6), r.id, fill=COLORS["text"], font=font, anchor="mm")
        draw.text((cx, cy + v.s * 0.4), r.kind, fill=(90, 90, 90), font=small, anchor="mm")
    width = max(2, round(v.s * 0.15))
    for a, b in floor.walls:
        draw.line([v(*a), v(*b)], fill=COLORS["wall"], width=width)


def _doors(draw: ImageDraw.ImageDraw, v: _View, floor: Floor, states: dict[str, str]) -> None:
    width = max(3, round(v.s * 0.3))
    for d in floor.doors:
        half = d.width / 2
        a, b = ((d.x - half, d.y), (d.x + half, d.y)) if d.across_x else \
            ((d.x, d.y - half), (d.x, d.y + half))
        state = states.get(d.id, "open")
        if state == "open":
            draw.line([v(*a), v(*b)], fill=COLORS["corridor"], width=width)
            draw.line([v(*a), v(*b)], fill=COLORS["open"], width=max(1, width // 3))
        else:
            draw.line([v(*a), v(*b)], fill=COLORS[state], width=width)
        if state == "blocked":
            r = v.s * 0.45
            x, y = v(d.x, d.y)
            draw.line([(x - r, y - r), (x + r, y + r)], fill=COLORS["blocked"], width=width // 2)
            draw.line([(x - r, y + r), (x + r, y - r)], fill=COLORS["blocked"], width=width // 2)


def _dot(draw: ImageDraw.ImageDraw, v: _View, x: float, y: float, radius: float,
         fill: tuple, outline: tuple = (20, 20, 20)) -> None:
    cx, cy = v(x, y)
    r = radius * v.s
    draw.ellipse([cx - r, cy - r, cx + r, cy + r], fill=fill, outline=outline)


def _things(draw: ImageDraw.ImageDraw, v: _View, floor: Floor, snap: OfficeSnapshot) -> None:
    small = _font(max(9, round(v.s * 0.7)))
    where: dict[str, tuple[float, float]] = {p.id: (p.x, p.y) for p in snap.people}
    where |= {r.id: (r.x, r.y) for r in snap.robots}
    where |= {r.id: ((r.x0 + r.x1) / 2, (r.y0 + r.y1) / 2 - 1.8) for r in floor.rooms}
    for room, n in snap.occupants.items():
        if n:
            r = floor.room(room)
            x, y = v((r.x0 + r.x1) / 2, (r.y0 + r.y1) / 2 + 1.8)
            draw.text((x, y), f"{n} people", fill=COLORS["person"], font=small, anchor="mm")
    for p in snap.people:
        _dot(draw, v, p.x, p.y, PERSON_RADIUS, COLORS["person"])
        x, y = v(p.x, p.y)
        draw.text((x, y + v.s * 0.45), p.id, fill=COLORS["person"], font=small, anchor="mt")
    stacked: dict[str, int] = {}
    for item in snap.items:
        k = stacked.get(item.holder, 0)
        stacked[item.holder] = k + 1
        hx, hy = where.get(item.holder, (0.0, 0.0))
        color = COLORS.get(item.kind, COLORS["item"])
        if item.kind == "coffee" and item.temperature < snap.config.coffee_cold:
            color = COLORS["cold"]
        x, y = v(hx + 0.5 + 0.45 * k, hy + 0.4)
        h = v.s * 0.2
        draw.rectangle([x - h, y - h, x + h, y + h], fill=color, outline=(20, 20, 20))
    for o in snap.obstacles:
        _dot(draw, v, o.x, o.y, o.radius, COLORS["obstacle"])


def _robots(draw: ImageDraw.ImageDraw, v: _View, snap: OfficeSnapshot, agent: str | None,
            trail: list[tuple[float, float]]) -> None:
    if len(trail) > 1:
        draw.line([v(*p) for p in trail], fill=COLORS["trail"], width=max(2, round(v.s * 0.12)))
    for r in snap.robots:
        if r.id == agent and r.route:
            pts = [v(r.x, r.y)] + [v(*p) for p in r.route]
            for a, b in pairwise(pts):
                n = max(1, int(math.dist(a, b) / 6))
                for k in range(0, n, 2):
                    draw.line([_lerp(a, b, k / n), _lerp(a, b, (k + 1) / n)],
                              fill=COLORS["route"], width=2)
    for r in snap.robots:
        color = COLORS["me"] if r.id == agent else COLORS["robot"]
        _dot(draw, v, r.x, r.y, ROBOT_RADIUS * 1.6, color)
        h = math.radians(r.heading)
        tip = (r.x + 0.5 * math.cos(h), r.y + 0.5 * math.sin(h))
        draw.line([v(r.x, r.y), v(*tip)], fill=(20, 20, 20), width=2)
        x, y = v(r.x, r.y)
        draw.text((x, y - v.s * 0.6), r.id, fill=color, font=_font(max(10, round(v.s * 0.8))),
                  anchor="ms", stroke_width=2, stroke_fill=(255, 255, 255))


def _lerp(a: tuple[float, float], b: tuple[float, float], t: float) -> tuple[float, float]:
    return a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])


def _legend(img: Image.Image, snap: OfficeSnapshot, agent: str | None,
            top: int = 0) -> None:
    """The caption and key: beside the floor (``top`` 0), or below it from ``top`` [px] with
    the key in a second column."""
    draw = ImageDraw.Draw(img)
    x0 = img.width - LEGEND_W if not top else 0
    draw.rectangle([x0, top, img.width, img.height], fill=COLORS["legend"])
    big, font = _font(15), _font(12)
    lines = [(f"cycle {snap.cycle}   t = {snap.time:.1f} s", big)]
    if agent is not None:
        me = snap.robot(agent)
        op = me.operation
        doing = " ".join([op["name"], *map(str, op["args"])]) + f": {op['status']}" if op else \
            "idle"
        lines += [(f"robot {agent} in {me.place}", big), (doing, font),
                  (f"  {op['code']}" if op and op["code"] else "", font),
                  (f"carrying: {', '.join(me.carrying) or 'nothing'}", font),
                  (f"travelled {me.travelled:.1f} m", font)]
        lines += [(f"{k.replace('_', ' ')}: {n}", font)
                  for k, n in snap.counters.get(agent, {}).items() if n and k != "travel_cm"]
    if not top:
        lines += [("", font), ("key", big)]
    y = top + 10
    for text, f in lines:
        draw.text((x0 + 10, y), text, fill=COLORS["text"], font=f)
        y += 20 if f is big else 16
    if top:   # the key in its own column
        x0, y = x0 + LEGEND_W, top + 10
        draw.text((x0 + 10, y), "key", fill=COLORS["text"], font=big)
        y += 20
    for color, text in ((COLORS["me"], f"robot {agent or ''}, its path"),
                        (COLORS["route"], "route ahead (dashed)"), (COLORS["person"], "person"),
                        (COLORS["open"], "door open"), (COLORS["closed"], "door closed"),
                        (COLORS["blocked"], "door blocked"), (COLORS["mail"], "mail"),
                        (COLORS["fax"], "fax"), (COLORS["coffee"], "coffee (hot)"),
                        (COLORS["cold"], "coffee (cold)"), (COLORS["obstacle"], "obstacle")):
        draw.rectangle([x0 + 10, y + 2, x0 + 22, y + 12], fill=color, outline=(20, 20, 20))
        draw.text((x0 + 30, y), text, fill=COLORS["text"], font=font)
        y += 16


def render_image(snap: OfficeSnapshot, agent: str | None = None, px_per_m: float = 14.0,
                 trail: list[tuple[float, float]] | None = None) -> Image.Image:
    """The picture of one snapshot (RGB); agent: whose legend and route to show (default:
    the first robot); trail: its earlier positions [m]."""
    robots = [r.id for r in snap.robots]
    if agent is None and robots:
        agent = robots[0]
    if agent is not None and agent not in robots:
        raise WorldError(f"render: no robot {agent!r} in cycle {snap.cycle}; robots: {robots}")
    floor = build_floor(snap.config)
    v = _View(floor, px_per_m)
    below = v.size[0] > v.size[1] + LEGEND_W   # a wide floor: the legend goes under it,
    # so the picture is nearer a square and fits the view's panel without shrinking its text
    size = (max(v.size[0], 2 * LEGEND_W), v.size[1] + LEGEND_BELOW_H) if below else \
        (v.size[0] + LEGEND_W, max(v.size[1], 440))
    img = Image.new("RGB", size, COLORS["floor"])
    draw = ImageDraw.Draw(img)
    _floor(draw, v, floor)
    _doors(draw, v, floor, snap.doors)
    _things(draw, v, floor, snap)
    _robots(draw, v, snap, agent, trail or [])
    _legend(img, snap, agent, v.size[1] if below else 0)
    scale_bar(draw, 12, img.height - 14, v.s, max_px=v.size[0] / 4)
    return img


def robot_trail(snaps: list[OfficeSnapshot], agent: str | None) -> list[tuple[float, float]]:
    """The positions [m] of a robot over snapshots (default: the first robot)."""
    out = []
    for s in snaps:
        robots = [r for r in s.robots if agent is None or r.id == agent]
        if robots:
            out.append((robots[0].x, robots[0].y))
    return out


def render_png(snaps: list[OfficeSnapshot], path: str | Path, agent: str | None = None,
               px_per_m: float = 14.0) -> Path:
    """Write a PNG or JPEG (by suffix) of the last snapshot with the robot's path over all."""
    if not snaps:
        raise WorldError(f"render_png {path}: no snapshots")
    return save_still(render_image(snaps[-1], agent, px_per_m, robot_trail(snaps, agent)), path)


def render_gif(snaps: list[OfficeSnapshot], path: str | Path, agent: str | None = None,
               px_per_m: float = 10.0, max_frames: int = MAX_FRAMES) -> Path:
    """Write an animated GIF of a run: thinned to at most max_frames frames, at
    pictures.FRAME_MS per frame (a smooth 10 frames/s, faster than real time)."""
    if not snaps:
        raise WorldError(f"render_gif {path}: no snapshots")
    chosen = range(0, len(snaps), thinning(len(snaps), max_frames=max_frames))
    trail = robot_trail(snaps, agent)
    return save_animation([render_image(snaps[k], agent, px_per_m, trail[:k + 1])
                           for k in chosen], path)
