"""Pictures of graphs for `teleo graph` and the web view: a program's goals, skills and
concepts (tools/records/program_graph.py) and a run's processes and keys (as ROS 2's
rqt_graph, tools/records/run_graph.py), laid out in layers and written as SVG by this module
or as PNG through Pillow (already teleo's library for pictures, world/pictures.py).

Here, under the commands and the web view alike, because both draw them (docs/architecture.md,
"tools/: its rooms").

    graph = Graph("blocks.tlp"); graph.node("g1", "(clear A)", "goal"); graph.edge(...)
    write_picture(graph, "blocks.svg")
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape

PICTURE_SUFFIXES = (".svg", ".png")
CHAR_W, NODE_H, GAP_X, GAP_Y, MARGIN, LOOP = 7.0, 26, 18, 56, 16, 16  # [px]
MAX_LABEL = 48  # [characters] of a node's label drawn; the rest is in its tooltip
STYLE = {  # kind -> (fill, stroke, dashed border)
    "goal": ("#fde9c8", "#c77d12", False), "skill": ("#dbe8fb", "#2f6fd6", False),
    "primitive": ("#d6f0da", "#3a9a48", False), "body": ("#ece0f7", "#7a4bb0", False),
    "step": ("#f5effb", "#7a4bb0", True), "concept": ("#f1f1f1", "#555555", False),
    "percept-concept": ("#ffffff", "#555555", True), "process": ("#dbe8fb", "#2f6fd6", False),
    "key": ("#ffffff", "#555555", True),
}
LOWER_BAND = ("concept", "percept-concept")  # kinds drawn in rows of their own, below


@dataclass(frozen=True)
class Node:
    id: str
    label: str
    kind: str
    detail: str = ""  # shown as the node's tooltip (SVG <title>)


@dataclass(frozen=True)
class Edge:
    src: str
    dst: str
    label: str = ""
    dashed: bool = False


@dataclass
class Graph:
    """Nodes and edges in the order added; ``node`` ignores an id already there."""

    title: str
    nodes: dict[str, Node] = field(default_factory=dict)
    edges: list[Edge] = field(default_factory=list)

    def node(self, id: str, label: str, kind: str, detail: str = "") -> str:
        self.nodes.setdefault(id, Node(id, label, kind, detail))
        return id

    def edge(self, src: str, dst: str, label: str = "", dashed: bool = False) -> None:
        e = Edge(src, dst, label, dashed)
        if e not in self.edges:
            self.edges.append(e)

    def to_json(self) -> dict[str, Any]:
        return {"title": self.title,
                "nodes": [{"id": n.id, "label": n.label, "kind": n.kind, "detail": n.detail}
                          for n in self.nodes.values()],
                "edges": [{"from": e.src, "to": e.dst, "label": e.label, "dashed": e.dashed}
                          for e in self.edges]}


def _layers(g: Graph) -> dict[str, int]:
    """Each node's layer: the longest path to it from a node nothing points to (edges that
    close a cycle, as a recursive concept's, are left out)."""
    out: dict[str, list[str]] = {n: [] for n in g.nodes}
    for e in g.edges:
        out[e.src].append(e.dst)
    order: list[str] = []
    state: dict[str, int] = {}
    back: set[tuple[str, str]] = set()
    for root in g.nodes:
        stack = [(root, iter(out[root]))] if root not in state else []
        state.setdefault(root, 1)
        while stack:
            n, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                state[n] = 2
                order.append(n)
                stack.pop()
            elif state.get(nxt) == 1:
                back.add((n, nxt))
            elif nxt not in state:
                state[nxt] = 1
                stack.append((nxt, iter(out[nxt])))
    layer = dict.fromkeys(g.nodes, 0)
    for n in reversed(order):  # a topological order of the edges kept
        for m in out[n]:
            if (n, m) not in back:
                layer[m] = max(layer[m], layer[n] + 1)
    lower = [n for n in g.nodes if g.nodes[n].kind in LOWER_BAND]
    upper = [layer[n] for n in g.nodes if g.nodes[n].kind not in LOWER_BAND]
    if lower and upper:  # the concepts below the goals and skills, not beside them
        shift = max(upper) + 1 - min(layer[n] for n in lower)
        for n in lower:
            layer[n] += max(shift, 0)
    return layer


def _label(n: Node) -> str:
    return n.label if len(n.label) <= MAX_LABEL else n.label[:MAX_LABEL - 1] + "…"


def layout(g: Graph) -> tuple[dict[str, tuple[float, float, float]], float, float]:
    """{node: (x, y, width)} (the box's top left [px]) and the picture's width and height."""
    layer = _layers(g)
    rows: dict[int, list[str]] = {}
    for n in g.nodes:
        rows.setdefault(layer[n], []).append(n)
    parents: dict[str, list[str]] = {n: [] for n in g.nodes}
    for e in g.edges:
        if layer[e.src] < layer[e.dst]:
            parents[e.dst].append(e.src)
    width = {n: len(_label(g.nodes[n])) * CHAR_W + 16 for n in g.nodes}
    place: dict[str, tuple[float, float, float]] = {}
    for k in sorted(rows):
        def mean_parent(n: str) -> float:
            xs = [place[p][0] + place[p][2] / 2 for p in parents[n] if p in place]
            return sum(xs) / len(xs) if xs else float("inf")
        row = sorted(rows[k], key=lambda n: (mean_parent(n), rows[k].index(n)))
        x = MARGIN
        for n in row:
            place[n] = (x, MARGIN + k * (NODE_H + GAP_Y), width[n])
            x += width[n] + GAP_X
    right = max((x + w for x, _, w in place.values()), default=MARGIN) + LOOP
    for row in rows.values():  # each row centred
        shift = (right - max(place[n][0] + place[n][2] for n in row)) / 2
        for n in row:
            x, y, w = place[n]
            place[n] = (x + shift, y, w)
    bottom = max((y + NODE_H for _, y, _ in place.values()), default=MARGIN)
    return place, right + MARGIN, bottom + MARGIN + 18


def _ends(a: tuple, b: tuple) -> tuple[float, float, float, float]:
    """Where an edge from box ``a`` to box ``b`` leaves and arrives."""
    ax, ay, aw = a
    bx, by, bw = b
    if by > ay:
        return ax + aw / 2, ay + NODE_H, bx + bw / 2, by
    if by < ay:
        return ax + aw / 2, ay, bx + bw / 2, by + NODE_H
    return (ax + aw, ay + NODE_H / 2, bx, by + NODE_H / 2) if bx > ax else \
        (ax, ay + NODE_H / 2, bx + bw, by + NODE_H / 2)


def to_svg(g: Graph) -> str:
    """The graph as an SVG document (nodes' details as tooltips)."""
    place, w, h = layout(g)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0f}" height="{h:.0f}" '
           f'viewBox="0 0 {w:.0f} {h:.0f}" font-family="monospace" font-size="12">',
           f"<title>{escape(g.title)}</title>",
           '<defs><marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="7" '
           'markerHeight="7" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" '
           'fill="#666"/></marker></defs>', '<rect width="100%" height="100%" fill="white"/>']
    for e in g.edges:
        x1, y1, x2, y2 = _ends(place[e.src], place[e.dst])
        d = f"M{x1:.1f},{y1:.1f} C{x1:.1f},{(y1 + y2) / 2:.1f} {x2:.1f},{(y1 + y2) / 2:.1f} " \
            f"{x2:.1f},{y2:.1f}"
        if e.src == e.dst:  # a recursive skill or concept: a loop on the box's right side
            x, y, bw = place[e.src]
            d = f"M{x + bw:.1f},{y + 6:.1f} C{x + bw + LOOP:.1f},{y - 6:.1f} {x + bw + LOOP:.1f}," \
                f"{y + NODE_H + 6:.1f} {x + bw:.1f},{y + NODE_H - 6:.1f}"
        dash = ' stroke-dasharray="4 3"' if e.dashed else ""
        out.append(f'<g class="edge"><title>{escape(e.src)} -> {escape(e.dst)} '
                   f'{escape(e.label)}</title><path d="{d}" '
                   f'fill="none" stroke="#888"{dash} marker-end="url(#arrow)"/></g>')
    for n in g.nodes.values():
        x, y, bw = place[n.id]
        fill, stroke, dashed = STYLE.get(n.kind, STYLE["concept"])
        dash = ' stroke-dasharray="4 3"' if dashed else ""
        tip = escape(n.detail or n.label)
        out.append(f'<g class="node {escape(n.kind)}" id="{escape(n.id, {chr(34): "&quot;"})}">'
                   f"<title>{tip}</title><rect x=\"{x:.1f}\" y=\"{y:.1f}\" width=\"{bw:.1f}\" "
                   f'height="{NODE_H}" rx="5" fill="{fill}" stroke="{stroke}"{dash}/>'
                   f'<text x="{x + bw / 2:.1f}" y="{y + NODE_H / 2 + 4:.1f}" '
                   f'text-anchor="middle">{escape(_label(n))}</text></g>')
    out.append(f'<text x="{MARGIN}" y="{h - 8:.0f}" fill="#666">{escape(g.title)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def to_png(g: Graph, path: Path) -> None:
    """The graph drawn with Pillow into ``path`` (the same layout as the SVG)."""
    from PIL import Image, ImageDraw, ImageFont

    place, w, h = layout(g)
    img = Image.new("RGB", (int(w), int(h)), "white")
    draw = ImageDraw.Draw(img)
    font = ImageFont.load_default(size=11)
    for e in g.edges:
        if e.src == e.dst:  # a loop on the box's right side
            x, y, bw = place[e.src]
            draw.arc([x + bw - LOOP / 2, y + 2, x + bw + LOOP / 2, y + NODE_H - 2], -90, 90,
                     fill="#888888")
            continue
        x1, y1, x2, y2 = _ends(place[e.src], place[e.dst])
        draw.line([(x1, y1), (x2, y2)], fill="#888888", width=1)
        draw.regular_polygon((x2, y2 - 3 if y2 > y1 else y2 + 3, 4), 3,
                             rotation=180 if y2 > y1 else 0, fill="#666666")
    for n in g.nodes.values():
        x, y, bw = place[n.id]
        fill, stroke, _ = STYLE.get(n.kind, STYLE["concept"])
        draw.rounded_rectangle([x, y, x + bw, y + NODE_H], 5, fill=fill, outline=stroke)
        draw.text((x + bw / 2, y + NODE_H / 2), _label(n), fill="black", font=font, anchor="mm")
    draw.text((MARGIN, h - 14), g.title, fill="#666666", font=font)
    img.save(path, format="PNG")


def write_picture(g: Graph, path: str | Path) -> Path:
    """``g`` written to ``path``, SVG or PNG by its suffix (checked by the caller)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".png":
        to_png(g, path)
    else:
        path.write_text(to_svg(g))
    return path
