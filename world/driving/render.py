"""Top-down pictures of the driving world for people: a PNG of one cycle, a GIF of a run.

Drawn: grass, sidewalks, roads with their five lane lines, street names and segment ids,
buildings with address numbers, closed segments (orange cross), each package's address (purple
diamond, green once delivered), pedestrians (teal dots; gold with a black cross when hit), the
agent's path so far (indigo line from a start ring, with arrows every 40 m showing the way it
went), traffic (blue cars), agent cars (orange, labelled; the chosen one red), the chosen
agent's perception range (black ring), a scale bar, and a legend with cycle, time, the agent's
controls, its counters, its packages and a key of every colour. Labels (packages, cars) are
moved aside rather than drawn over another label. Stills are PNG or JPEG, runs GIFs at 10
frames a second (world/pictures.py).
"""

from __future__ import annotations

import math
from pathlib import Path

from PIL import Image, ImageDraw

from world.driving.city import (
    BUILDING_FAR,
    LANE_WIDTH,
    ROAD_HALF,
    SIDEWALK_OUTER,
    City,
    Segment,
    build_city,
)
from world.driving.placing import Bounds, Labels, View, font_of
from world.driving.snapshot import CarState, WorldSnapshot
from world.driving.vehicle import CAR_LENGTH, CAR_WIDTH
from world.errors import WorldError
from world.pictures import MAX_FRAMES, save_animation, save_still, scale_bar, thinning

MARGIN = BUILDING_FAR + 8.0     # [m] drawn around the street grid
LEGEND_W = 270                  # [px]
COLORS = {"grass": (196, 222, 180), "walk": (214, 214, 208), "road": (78, 80, 86),
          "yellow": (246, 200, 40), "white": (240, 240, 240), "curb": (150, 150, 146),
          "building": (206, 170, 126), "outline": (120, 90, 60), "text": (20, 20, 20),
          "ped": (0, 140, 120), "down": (255, 196, 0), "closed": (255, 90, 0),
          "traffic": (60, 110, 200), "agent": (245, 130, 20), "me": (220, 20, 30),
          "range": (20, 20, 20), "package": (150, 40, 170), "delivered": (30, 160, 60),
          "trail": (75, 50, 220), "legend": (250, 250, 246)}
ARROW_EVERY = 40.0              # [m] of path between direction arrows


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


def _strip(draw: ImageDraw.ImageDraw, v: View, seg: Segment, a0: float, a1: float,
           l0: float, l1: float, fill: tuple) -> None:
    pts = [seg.point(a0, l0), seg.point(a1, l0), seg.point(a1, l1), seg.point(a0, l1)]
    draw.polygon([v(*p) for p in pts], fill=fill)


def _line(draw: ImageDraw.ImageDraw, v: View, seg: Segment, lat: float, fill: tuple,
          width: int, dash: float = 0.0) -> None:
    a, end = ROAD_HALF, seg.length - ROAD_HALF
    step = dash or end - a
    while a < end - 1e-9:
        b = min(a + step, end)
        draw.line([v(*seg.point(a, lat)), v(*seg.point(b, lat))], fill=fill, width=width)
        a = b + (step if dash else 0.0)


def _streets(draw: ImageDraw.ImageDraw, v: View, city: City, labels: Labels) -> None:
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
    font = font_of(max(9, round(3.2 * v.s)))
    label = font_of(max(9, round(2.8 * v.s)))
    for seg in city.segments:
        x, y = v(*seg.point(seg.length / 2, 0.0))
        text = f"{seg.street} {seg.id}"
        labels.reserve(draw.textbbox((x, y), text, font=label, anchor="mm", stroke_width=2))
        draw.text((x, y), text, fill=(255, 255, 255), font=label,
                  anchor="mm", stroke_width=2, stroke_fill=COLORS["road"])
    for n in city.intersections:
        x, y = v(n.x, n.y)
        labels.reserve(draw.textbbox((x, y), n.id, font=font, anchor="mm"))
        draw.text((x, y), n.id, fill=(160, 160, 160), font=font, anchor="mm")


def _buildings(draw: ImageDraw.ImageDraw, v: View, city: City) -> None:
    font = font_of(max(9, round(4.0 * v.s)))
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


def _car(draw: ImageDraw.ImageDraw, v: View, car: CarState, fill: tuple,
         labels: Labels | None) -> None:
    draw.polygon([v(*p) for p in _box(car.x, car.y, car.heading, CAR_LENGTH, CAR_WIDTH)],
                 fill=fill, outline=(20, 20, 20))
    h = math.radians(car.heading)
    nose = (car.x + 0.5 * CAR_LENGTH * math.cos(h), car.y + 0.5 * CAR_LENGTH * math.sin(h))
    draw.line([v(car.x, car.y), v(*nose)], fill=(20, 20, 20), width=max(1, round(0.3 * v.s)))
    if labels is not None:
        x, y = v(car.x, car.y)
        labels.place(x, y, car.id, 3.5 * v.s, fill=fill, font=font_of(max(10, round(4 * v.s))),
                     stroke_width=2, stroke_fill=(255, 255, 255))


def _dynamic(draw: ImageDraw.ImageDraw, v: View, city: City, snap: WorldSnapshot,
             agent: str | None, labels: Labels) -> None:
    for seg_id in snap.blocked:
        seg = city.segment(seg_id)
        a, b = v(*seg.point(seg.length * 0.4, 5.0)), v(*seg.point(seg.length * 0.6, -5.0))
        c, d = v(*seg.point(seg.length * 0.4, -5.0)), v(*seg.point(seg.length * 0.6, 5.0))
        draw.line([a, b], fill=COLORS["closed"], width=max(2, round(v.s)))
        draw.line([c, d], fill=COLORS["closed"], width=max(2, round(v.s)))
    small = font_of(max(9, round(3 * v.s)))
    for p in snap.packages:
        x, y = v(*city.building(p.street, p.address).curb)
        r = 1.8 * v.s
        color = COLORS["delivered"] if p.delivered else COLORS["package"]
        draw.polygon([(x, y - r), (x + r, y), (x, y + r), (x - r, y)], fill=color)
        labels.place(x, y, p.id, r + 2, fill=color, font=small, stroke_width=2,
                     stroke_fill=(255, 255, 255))
    r = max(2.0, 0.9 * v.s)
    for p in snap.pedestrians:
        x, y = v(p.x, p.y)
        if p.mode == "down":   # a hit pedestrian: a gold dot under a black cross
            draw.ellipse([x - 1.6 * r, y - 1.6 * r, x + 1.6 * r, y + 1.6 * r],
                         fill=COLORS["down"], outline=(0, 0, 0))
            draw.line([(x - 2 * r, y - 2 * r), (x + 2 * r, y + 2 * r)], fill=(0, 0, 0), width=2)
            draw.line([(x - 2 * r, y + 2 * r), (x + 2 * r, y - 2 * r)], fill=(0, 0, 0), width=2)
        else:
            draw.ellipse([x - r, y - r, x + r, y + r], fill=COLORS["ped"])
    for car in snap.cars:
        if car.kind == "traffic":
            _car(draw, v, car, COLORS["traffic"], None)
    for car in snap.cars:
        if car.kind == "agent":
            _car(draw, v, car, COLORS["me"] if car.id == agent else COLORS["agent"], labels)
    if agent is not None:
        me = snap.car(agent)
        rr = snap.config.perception_range * v.s
        x, y = v(me.x, me.y)
        draw.ellipse([x - rr, y - rr, x + rr, y + rr], outline=COLORS["range"], width=2)


def _trail(draw: ImageDraw.ImageDraw, v: View, trail: list[tuple[float, float]]) -> None:
    """The path: a line, a ring where it starts, and an arrowhead every ARROW_EVERY metres
    pointing the way the car went."""
    color, width = COLORS["trail"], max(2, round(v.s / 2))
    draw.line([v(x, y) for x, y in trail], fill=color, width=width)
    sx, sy = v(*trail[0])
    r = max(5.0, 2.2 * v.s)
    draw.ellipse([sx - r, sy - r, sx + r, sy + r], outline=color, width=width, fill=(255, 255, 255))
    draw.text((sx, sy), "S", fill=color, font=font_of(max(9, round(1.6 * r))), anchor="mm")
    run, size = 0.0, max(5.0, 2.5 * v.s)
    for (x0, y0), (x1, y1) in zip(trail, trail[1:], strict=False):
        step = math.hypot(x1 - x0, y1 - y0)
        run += step
        if run < ARROW_EVERY or step < 1e-6:
            continue
        run = 0.0
        (px, py), (qx, qy) = v(x0, y0), v(x1, y1)
        a = math.atan2(qy - py, qx - px)
        tip = (qx, qy)
        left = (qx - size * math.cos(a - 0.5), qy - size * math.sin(a - 0.5))
        right = (qx - size * math.cos(a + 0.5), qy - size * math.sin(a + 0.5))
        draw.polygon([tip, left, right], fill=color)


def _legend(img: Image.Image, snap: WorldSnapshot, agent: str | None) -> None:
    draw = ImageDraw.Draw(img)
    x0 = img.width - LEGEND_W
    draw.rectangle([x0, 0, img.width, img.height], fill=COLORS["legend"])
    big, font = font_of(16), font_of(13)
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
    for color, text in legend_key(agent):
        draw.rectangle([x0 + 12, y + 3, x0 + 24, y + 13], fill=color, outline=(20, 20, 20))
        draw.text((x0 + 32, y), text, fill=COLORS["text"], font=font)
        y += 18


def legend_key(agent: str | None) -> tuple[tuple[tuple, str], ...]:
    """The legend's key: each colour of the picture and what it shows."""
    return ((COLORS["me"], f"agent car {agent or ''}"),
            (COLORS["trail"], "its path: S = start, arrows = way"),
            (COLORS["range"], "its perception range (ring)"),
            (COLORS["agent"], "other agent car"), (COLORS["traffic"], "traffic"),
            (COLORS["ped"], "pedestrian"), (COLORS["down"], "pedestrian hit (black cross)"),
            (COLORS["closed"], "closed road (cross)"),
            (COLORS["package"], "package address"), (COLORS["delivered"], "package delivered"))


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
    v = View(bounds or scene_bounds([snap]), px_per_m)
    img = Image.new("RGB", (v.size[0] + LEGEND_W, max(v.size[1], 600)), COLORS["grass"])
    draw = ImageDraw.Draw(img)
    labels = Labels(draw, v.size[0], img.height)
    _streets(draw, v, city, labels)
    _buildings(draw, v, city)
    if trail and len(trail) > 1:
        _trail(draw, v, trail)
    _dynamic(draw, v, city, snap, agent, labels)
    scale_bar(draw, 14, img.height - 14, v.s, max_px=min(200, v.size[0] / 3))
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
    """Write a top-down PNG or JPEG (by suffix) of one cycle (with the agent's path so far, if
    given); follow: draw only a square of that side [m] around the agent's car instead of
    the whole city. Returns the path."""
    bounds = follow_bounds(snap, agent, follow) if follow else None
    return save_still(render_image(snap, agent, px_per_m, trail, bounds), path)


def agent_trail(snaps: list[WorldSnapshot], agent: str | None) -> list[tuple[float, float]]:
    """The positions [m] of an agent's car over snapshots (default: the first agent car)."""
    out = []
    for s in snaps:
        cars = [c for c in s.cars if c.kind == "agent" and (agent is None or c.id == agent)]
        if cars:
            out.append((cars[0].x, cars[0].y))
    return out


def render_gif(snaps: list[WorldSnapshot], path: str | Path, agent: str | None = None,
               every: int = 1, px_per_m: float = 1.5, max_frames: int = MAX_FRAMES,
               follow: float | None = None) -> Path:
    """Write an animated GIF of a run (every `every`-th snapshot, thinned to at most
    max_frames frames) at pictures.FRAME_MS per frame, a smooth 10 frames/s; follow: a
    camera square of that side [m] that moves with the agent's car. Returns the path."""
    if not snaps:
        raise WorldError(f"render_gif {path}: no snapshots")
    every = thinning(len(snaps), every, max_frames)
    chosen = list(snaps[::every])
    trail, whole = agent_trail(snaps, agent), scene_bounds(chosen)
    return save_animation([render_image(s, agent, px_per_m, trail[:k * every + 1],
                                        follow_bounds(s, agent, follow) if follow else whole)
                           for k, s in enumerate(chosen)], path)
