"""Top-down pictures of the driving world for people: a PNG of one cycle, a GIF of a run.

Drawn: grass, sidewalks, roads with their five lane lines, street names and segment ids,
buildings with address numbers, closed segments (red cross), each package's address (purple
diamond, green once delivered), pedestrians (teal dots; red with a cross when hit), the agent's
path so far (red line), traffic (blue cars), agent cars (orange, labelled; the chosen one red),
the chosen agent's perception range (red ring), and a legend with cycle, time, the agent's
controls, its counters and its packages.
"""

from __future__ import annotations

import math
from pathlib import Path

from PIL import Image, ImageDraw, ImageFont

from world.driving.city import (
    BUILDING_FAR,
    LANE_WIDTH,
    ROAD_HALF,
    SIDEWALK_OUTER,
    City,
    Segment,
    build_city,
)
from world.driving.snapshot import CarState, WorldSnapshot
from world.driving.vehicle import CAR_LENGTH, CAR_WIDTH
from world.errors import WorldError

MARGIN = BUILDING_FAR + 8.0     # [m] drawn around the street grid
LEGEND_W = 270                  # [px]
COLORS = {"grass": (196, 222, 180), "walk": (214, 214, 208), "road": (78, 80, 86),
          "yellow": (246, 200, 40), "white": (240, 240, 240), "curb": (150, 150, 146),
          "building": (206, 170, 126), "outline": (120, 90, 60), "text": (20, 20, 20),
          "ped": (0, 140, 120), "down": (220, 30, 30), "traffic": (60, 110, 200),
          "agent": (245, 130, 20), "me": (230, 40, 40), "range": (230, 40, 40),
          "package": (150, 40, 170), "delivered": (30, 160, 60), "trail": (230, 40, 40),
          "legend": (250, 250, 246)}


Bounds = tuple[float, float, float, float]   # x0, y0, x1, y1 [m]


class _View:
    """World [m] to pixel transform (y up in the world, down in the image)."""

    def __init__(self, bounds: Bounds, px_per_m: float) -> None:
        self.s = px_per_m
        x0, y0, x1, y1 = bounds
        self.x0, self.y1 = x0, y1
        self.size = (int((x1 - x0) * px_per_m), int((y1 - y0) * px_per_m))

    def __call__(self, x: float, y: float) -> tuple[float, float]:
        return (x - self.x0) * self.s, (self.y1 - y) * self.s


def scene_bounds(snaps: list[WorldSnapshot]) -> Bounds:
    """The area to draw [m]: the city with a margin, grown to hold every agent car that has
    left it (so a car that drives off the map stays in the picture)."""
    w, h = build_city(snaps[0].config).size
    x0, y0, x1, y1 = -MARGIN, -MARGIN, w + MARGIN, h + MARGIN
    for s in snaps:
        for c in s.cars:
            if c.kind == "agent":
                x0, x1 = min(x0, c.x - 10.0), max(x1, c.x + 10.0)
                y0, y1 = min(y0, c.y - 10.0), max(y1, c.y + 10.0)
    return x0, y0, x1, y1


def _font(size: int) -> ImageFont.ImageFont:
    return ImageFont.load_default(size=size)


def _strip(draw: ImageDraw.ImageDraw, v: _View, seg: Segment, a0: float, a1: float,
           l0: float, l1: float, fill: tuple) -> None:
    pts = [seg.point(a0, l0), seg.point(a1, l0), seg.point(a1, l1), seg.point(a0, l1)]
    draw.polygon([v(*p) for p in pts], fill=fill)


def _line(draw: ImageDraw.ImageDraw, v: _View, seg: Segment, lat: float, fill: tuple,
          width: int, dash: float = 0.0) -> None:
    a, end = ROAD_HALF, seg.length - ROAD_HALF
    step = dash or end - a
    while a < end - 1e-9:
        b = min(a + step, end)
        draw.line([v(*seg.point(a, lat)), v(*seg.point(b, lat))], fill=fill, width=width)
        a = b + (step if dash else 0.0)


def _streets(draw: ImageDraw.ImageDraw, v: _View, city: City) -> None:
    for seg in city.segments:
        _strip(draw, v, seg, -SIDEWALK_OUTER, seg.length + SIDEWALK_OUTER, -SIDEWALK_OUTER,
               SIDEWALK_OUTER, COLORS["walk"])
    for seg in city.segments:
        _strip(draw, v, seg, -ROAD_HALF, seg.length + ROAD_HALF, -ROAD_HALF, ROAD_HALF,
               COLORS["road"])
    w = max(1, round(0.3 * v.s))
    for seg in city.segments:
        _line(draw, v, seg, 0.0, COLORS["yellow"], w)
        for lat in (LANE_WIDTH, -LANE_WIDTH):
            _line(draw, v, seg, lat, COLORS["white"], max(1, w // 2), dash=3.0)
        for lat in (ROAD_HALF, -ROAD_HALF):
            _line(draw, v, seg, lat, COLORS["curb"], w)
    font = _font(max(9, round(3.2 * v.s)))
    label = _font(max(9, round(2.8 * v.s)))
    for seg in city.segments:
        x, y = v(*seg.point(seg.length / 2, 0.0))
        draw.text((x, y), f"{seg.street} {seg.id}", fill=(255, 255, 255), font=label,
                  anchor="mm", stroke_width=2, stroke_fill=COLORS["road"])
    for n in city.intersections:
        x, y = v(n.x, n.y)
        draw.text((x, y), n.id, fill=(160, 160, 160), font=font, anchor="mm")


def _buildings(draw: ImageDraw.ImageDraw, v: _View, city: City) -> None:
    font = _font(max(9, round(4.0 * v.s)))
    for b in city.buildings:
        pts = [v(*c) for c in b.corners]
        draw.polygon(pts, fill=COLORS["building"], outline=COLORS["outline"])
        cx, cy = sum(p[0] for p in pts) / 4, sum(p[1] for p in pts) / 4
        draw.text((cx, cy), str(b.address), fill=COLORS["text"], font=font, anchor="mm")


def _box(x: float, y: float, heading: float, length: float, width: float) -> list:
    h = math.radians(heading)
    c, s = math.cos(h), math.sin(h)
    return [(x + c * dx - s * dy, y + s * dx + c * dy)
            for dx, dy in ((length / 2, width / 2), (length / 2, -width / 2),
                           (-length / 2, -width / 2), (-length / 2, width / 2))]


def _car(draw: ImageDraw.ImageDraw, v: _View, car: CarState, fill: tuple, label: bool) -> None:
    draw.polygon([v(*p) for p in _box(car.x, car.y, car.heading, CAR_LENGTH, CAR_WIDTH)],
                 fill=fill, outline=(20, 20, 20))
    h = math.radians(car.heading)
    nose = (car.x + 0.5 * CAR_LENGTH * math.cos(h), car.y + 0.5 * CAR_LENGTH * math.sin(h))
    draw.line([v(car.x, car.y), v(*nose)], fill=(20, 20, 20), width=max(1, round(0.3 * v.s)))
    if label:
        x, y = v(car.x, car.y)
        draw.text((x, y - 3.5 * v.s), car.id, fill=fill, font=_font(max(10, round(4 * v.s))),
                  anchor="ms", stroke_width=2, stroke_fill=(255, 255, 255))


def _dynamic(draw: ImageDraw.ImageDraw, v: _View, city: City, snap: WorldSnapshot,
             agent: str | None) -> None:
    for seg_id in snap.blocked:
        seg = city.segment(seg_id)
        a, b = v(*seg.point(seg.length * 0.4, 5.0)), v(*seg.point(seg.length * 0.6, -5.0))
        c, d = v(*seg.point(seg.length * 0.4, -5.0)), v(*seg.point(seg.length * 0.6, 5.0))
        draw.line([a, b], fill=COLORS["down"], width=max(2, round(v.s)))
        draw.line([c, d], fill=COLORS["down"], width=max(2, round(v.s)))
    small = _font(max(9, round(3 * v.s)))
    for p in snap.packages:
        x, y = v(*city.building(p.street, p.address).curb)
        r = 1.8 * v.s
        color = COLORS["delivered"] if p.delivered else COLORS["package"]
        draw.polygon([(x, y - r), (x + r, y), (x, y + r), (x - r, y)], fill=color)
        draw.text((x, y + r + 2), p.id, fill=color, font=small, anchor="mt",
                  stroke_width=2, stroke_fill=(255, 255, 255))
    r = max(2.0, 0.9 * v.s)
    for p in snap.pedestrians:
        x, y = v(p.x, p.y)
        color = COLORS["down"] if p.mode == "down" else COLORS["ped"]
        draw.ellipse([x - r, y - r, x + r, y + r], fill=color)
        if p.mode == "down":
            draw.line([(x - 2 * r, y - 2 * r), (x + 2 * r, y + 2 * r)], fill=color, width=2)
            draw.line([(x - 2 * r, y + 2 * r), (x + 2 * r, y - 2 * r)], fill=color, width=2)
    for car in snap.cars:
        if car.kind == "traffic":
            _car(draw, v, car, COLORS["traffic"], label=False)
    for car in snap.cars:
        if car.kind == "agent":
            _car(draw, v, car, COLORS["me"] if car.id == agent else COLORS["agent"], True)
    if agent is not None:
        me = snap.car(agent)
        rr = snap.config.perception_range * v.s
        x, y = v(me.x, me.y)
        draw.ellipse([x - rr, y - rr, x + rr, y + rr], outline=COLORS["range"], width=2)


def _legend(img: Image.Image, snap: WorldSnapshot, agent: str | None) -> None:
    draw = ImageDraw.Draw(img)
    x0 = img.width - LEGEND_W
    draw.rectangle([x0, 0, img.width, img.height], fill=COLORS["legend"])
    big, font = _font(16), _font(13)
    lines = [(f"cycle {snap.cycle}   t = {snap.time:.1f} s", big),
             (f"limit {snap.config.speed_limit:g} m/s   dt {snap.config.dt:g} s", font)]
    if agent is not None:
        me = snap.car(agent)
        lines += [("", font), (f"agent {agent}", big),
                  (f"speed {me.speed:.1f} m/s  heading {me.heading:.0f} deg", font),
                  (f"throttle {me.throttle:.0f}%  brake {me.brake:.0f}%", font),
                  (f"wheel {me.wheel:.1f} deg", font), ("", font)]
        for k, n in snap.counters.get(agent, {}).items():
            lines.append((f"{k.replace('_', ' ')}: {n}", font))
        for p in snap.packages:
            if p.owner == agent:
                state = "delivered" if p.delivered else "carried"
                lines.append((f"{p.id} -> {p.address} {p.street}: {state}", font))
    lines += [("", font), ("key", big)]
    y = 12
    for text, f in lines:
        draw.text((x0 + 12, y), text, fill=COLORS["text"], font=f)
        y += 22 if f is big else 18
    for color, text in ((COLORS["me"], f"agent car {agent or ''}"), (COLORS["agent"],
                        "other agent car"), (COLORS["traffic"], "traffic"),
                        (COLORS["ped"], "pedestrian"), (COLORS["down"], "pedestrian hit / closed"),
                        (COLORS["package"], "package address"),
                        (COLORS["delivered"], "package delivered"),
                        (COLORS["range"], "perception range (ring), path")):
        draw.rectangle([x0 + 12, y + 3, x0 + 24, y + 13], fill=color)
        draw.text((x0 + 32, y), text, fill=COLORS["text"], font=font)
        y += 18


def render_image(snap: WorldSnapshot, agent: str | None = None, px_per_m: float = 3.0,
                 trail: list[tuple[float, float]] | None = None,
                 bounds: Bounds | None = None) -> Image.Image:
    """The picture of one snapshot (RGB). agent: whose range and legend to show (default: the
    first agent car, if any); trail: that car's earlier positions [m], drawn as its path;
    bounds: the area to draw (default: scene_bounds of this snapshot)."""
    agents = [c.id for c in snap.cars if c.kind == "agent"]
    if agent is None and agents:
        agent = agents[0]
    if agent is not None and agent not in agents:
        raise WorldError(f"render: no agent car {agent!r} in cycle {snap.cycle}; cars: {agents}")
    city = build_city(snap.config)
    v = _View(bounds or scene_bounds([snap]), px_per_m)
    img = Image.new("RGB", (v.size[0] + LEGEND_W, max(v.size[1], 520)), COLORS["grass"])
    draw = ImageDraw.Draw(img)
    _streets(draw, v, city)
    _buildings(draw, v, city)
    if trail and len(trail) > 1:
        draw.line([v(x, y) for x, y in trail], fill=COLORS["trail"], width=max(2, round(v.s / 2)))
    _dynamic(draw, v, city, snap, agent)
    _legend(img, snap, agent)
    return img


def follow_bounds(snap: WorldSnapshot, agent: str | None, window: float) -> Bounds:
    """A window x window [m] square centred on the agent's car (the first agent by default)."""
    cars = [c for c in snap.cars if c.kind == "agent" and (agent is None or c.id == agent)]
    if not cars:
        raise WorldError(f"render: no agent car {agent!r} to follow in cycle {snap.cycle}")
    h = window / 2
    return cars[0].x - h, cars[0].y - h, cars[0].x + h, cars[0].y + h


def render_png(snap: WorldSnapshot, path: str | Path, agent: str | None = None,
               px_per_m: float = 3.0, trail: list[tuple[float, float]] | None = None,
               follow: float | None = None) -> Path:
    """Write a top-down PNG of one cycle (with the agent's path so far, if given); follow:
    draw only a square of that side [m] around the agent's car instead of the whole city.
    Returns the path."""
    path = Path(path)
    bounds = follow_bounds(snap, agent, follow) if follow else None
    render_image(snap, agent, px_per_m, trail, bounds).save(path, format="PNG")
    return path


def agent_trail(snaps: list[WorldSnapshot], agent: str | None) -> list[tuple[float, float]]:
    """The positions [m] of an agent's car over snapshots (default: the first agent car)."""
    out = []
    for s in snaps:
        cars = [c for c in s.cars if c.kind == "agent" and (agent is None or c.id == agent)]
        if cars:
            out.append((cars[0].x, cars[0].y))
    return out


def render_gif(snaps: list[WorldSnapshot], path: str | Path, agent: str | None = None,
               every: int = 1, px_per_m: float = 1.5, max_frames: int = 400,
               follow: float | None = None) -> Path:
    """Write an animated GIF of a run (every `every`-th snapshot, thinned to at most max_frames
    frames; real-time playback, from the snapshots' times); follow: a camera square of that
    side [m] that moves with the agent's car. Returns the path."""
    if not snaps:
        raise WorldError(f"render_gif {path}: no snapshots")
    every = max(every, math.ceil(len(snaps) / max_frames))
    chosen = list(snaps[::every])
    trail, whole = agent_trail(snaps, agent), scene_bounds(chosen)
    frames = [render_image(s, agent, px_per_m, trail[:k * every + 1],
                           follow_bounds(s, agent, follow) if follow else whole)
              .convert("P", palette=Image.Palette.ADAPTIVE) for k, s in enumerate(chosen)]
    gap = chosen[1].time - chosen[0].time if len(chosen) > 1 else snaps[0].config.dt
    duration = max(20, round(1000 * gap))     # [ms] per frame: plays in real time
    path = Path(path)
    frames[0].save(path, format="GIF", save_all=True, append_images=frames[1:],
                   duration=duration, loop=0)
    return path
