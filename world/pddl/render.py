"""A picture of a PDDL problem's state for people: a text panel (PNG/JPEG of the last cycle,
GIF of a run) with the problem, the cycle and counters, the last action done, the goal's
literals marked held or not, and the true atoms grouped by predicate."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from PIL import Image, ImageDraw, ImageFont

from world.pictures import save_animation, save_still, thinning

WIDTH = 760            # [px]
LINE = 18              # [px] a line of text
MAX_LINES = 60         # lines drawn of the atoms; the rest are counted
COLORS = {"paper": (250, 250, 246), "text": (20, 20, 20), "held": (30, 140, 60),
          "open": (200, 50, 40), "head": (60, 60, 140)}


def _lines(snap: dict[str, Any], agent: str | None) -> list[tuple[str, str]]:
    """(colour key, text) per line."""
    atoms = {tuple(a) for a in snap.get("atoms", [])}
    counters = snap.get("counters", {})
    shown = counters.get(agent) if agent in counters else next(iter(counters.values()), {})
    out = [("head", f"{snap.get('pddl_domain', '?')} / {snap.get('task', '?')}   cycle "
                    f"{snap.get('cycle', 0)}   actions done {shown.get('actions_done', 0)}, "
                    f"failed {shown.get('actions_failed', 0)}"),
           ("head", "goal " + ("holds" if snap.get("goal_holds") else "does not hold yet"))]
    for g in snap.get("goal", []):
        core = g[5:-1] if g.startswith("(not ") else g
        atom = tuple(core.strip("()").split())
        held = (atom in atoms) != g.startswith("(not ")
        out.append(("held" if held else "open", ("  [x] " if held else "  [ ] ") + g))
    out.append(("head", f"state: {len(atoms)} atoms"))
    by_pred: dict[str, list[str]] = {}
    for a in sorted(atoms):
        by_pred.setdefault(a[0], []).append("(" + " ".join(a) + ")")
    body = [("text", f"  {p}: " + " ".join(v)) for p, v in sorted(by_pred.items())]
    wrapped: list[tuple[str, str]] = []
    for key, text in body:
        while len(text) > 100:
            cut = text.rfind(" ", 0, 100)
            cut = cut if cut > 10 else 100
            wrapped.append((key, text[:cut]))
            text = "      " + text[cut:].lstrip()
        wrapped.append((key, text))
    if len(wrapped) > MAX_LINES:
        wrapped = wrapped[:MAX_LINES] + [("text", f"  ... {len(wrapped) - MAX_LINES} more "
                                                  f"lines")]
    return out + wrapped


def picture(snap: dict[str, Any], agent: str | None = None) -> Image.Image:
    """One cycle's panel."""
    lines = _lines(snap, agent)
    img = Image.new("RGB", (WIDTH, LINE * (len(lines) + 1)), COLORS["paper"])
    draw = ImageDraw.Draw(img)
    font = ImageFont.load_default(size=13)
    for k, (key, text) in enumerate(lines):
        draw.text((10, 8 + k * LINE), text, fill=COLORS[key], font=font)
    return img


def render_png(snap: dict[str, Any], path: Path, agent: str | None = None) -> Path:
    return save_still(picture(snap, agent), path)


def render_gif(snaps: list[dict[str, Any]], path: Path, agent: str | None = None) -> Path:
    step = thinning(len(snaps))
    frames = [picture(s, agent) for s in snaps[::step]]
    size = (WIDTH, max(f.size[1] for f in frames))
    padded = []
    for f in frames:
        canvas = Image.new("RGB", size, COLORS["paper"])
        canvas.paste(f, (0, 0))
        padded.append(canvas)
    return save_animation(padded, path)
