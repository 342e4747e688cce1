"""Placing things on a picture of the driving world: the world [m] to pixel transform and
the placement of labels so that no two overlap (world/driving/render.py draws with them)."""

from __future__ import annotations

from PIL import ImageDraw, ImageFont

Bounds = tuple[float, float, float, float]   # x0, y0, x1, y1 [m]


class View:
    """World [m] to pixel transform (y up in the world, down in the image)."""

    def __init__(self, bounds: Bounds, px_per_m: float) -> None:
        self.s = px_per_m
        x0, y0, x1, y1 = bounds
        self.x0, self.y1 = x0, y1
        self.size = (int((x1 - x0) * px_per_m), int((y1 - y0) * px_per_m))

    def __call__(self, x: float, y: float) -> tuple[float, float]:
        return (x - self.x0) * self.s, (self.y1 - y) * self.s


class Labels:
    """Places text so that no two labels overlap: each label tries spots around its anchor
    (below, above, right, left and the diagonals, on rings further and further out) and takes
    the first free one inside the picture; one with no free spot at all (a crowd) is drawn at
    its first choice."""

    def __init__(self, draw: ImageDraw.ImageDraw, width: int, height: int) -> None:
        self.draw, self.width, self.height = draw, width, height
        self.taken: list[tuple[float, float, float, float]] = []

    def reserve(self, box: tuple[float, float, float, float]) -> None:
        self.taken.append(box)

    def _free(self, box: tuple[float, float, float, float]) -> bool:
        x0, y0, x1, y1 = box
        if x0 < 0 or y0 < 0 or x1 > self.width or y1 > self.height:
            return False
        return all(x1 <= a or x0 >= c or y1 <= b or y0 >= d for a, b, c, d in self.taken)

    def place(self, x: float, y: float, text: str, gap: float, **style) -> None:
        """Draw ``text`` near pixel (x, y), ``gap`` [px] away, where it overlaps nothing."""
        boxes = []
        for dx, dy, anchor in _SPOTS:
            at = (x + dx * gap, y + dy * gap)
            box = self.draw.textbbox(at, text, anchor=anchor, font=style["font"],
                                     stroke_width=style.get("stroke_width", 0))
            boxes.append((at, anchor, box))
            if self._free(box):
                break
        else:
            at, anchor, box = boxes[0]
        self.reserve(box)
        self.draw.text(at, text, anchor=anchor, **style)


_DIRECTIONS = ((0, 1, "mt"), (0, -1, "mb"), (1, 0, "lm"), (-1, 0, "rm"),
               (1, 1, "lt"), (-1, 1, "rt"), (1, -1, "lb"), (-1, -1, "rb"))
_SPOTS = tuple((dx * r, dy * r, anchor) for r in (1.0, 2.5, 4.5, 7.0, 10.0)
               for dx, dy, anchor in _DIRECTIONS)



def font_of(size: int) -> ImageFont.ImageFont:
    """The default font at ``size`` [px]."""
    return ImageFont.load_default(size=size)
