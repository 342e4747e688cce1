"""MiniGrid (Farama): the state of an environment as plain data, the mission mapping and
the percepts (world/gym/percepts.md), and the environment's own frame drawn from the state.

The agent sees the whole grid (env.unwrapped.grid, fully observable), not MiniGrid's 7x7
egocentric view: teleo's perception is a function of the world state, and a program for a
partially observed grid would need exploration skills that this family does not ask for.

    state = capture(env.unwrapped)          # in the world process (imports minigrid)
    percepts = perceive(state, "ME")        # anywhere: pure Python, no minigrid
    rgb = frame(state)                      # MiniGrid's own tile renderer (imports minigrid)
"""

from __future__ import annotations

import re
from typing import Any

from world.gym.families.instructions import current_step
from world.gym.paths import DIRS, Cell, Grid, Search, ahead, cut_cells, walkable_region

NAME = "minigrid"
ACTIONS = ("left", "right", "forward", "pickup", "drop", "toggle", "done")
ROW_CHARS = {"wall": "W", "lava": "L", "floor": "F"}     # everything else is "." in rows
NAMED = ("door", "key", "ball", "box", "goal")
COLORS = ("red", "green", "blue", "purple", "yellow", "grey")
TYPES = ("key", "ball", "box", "door", "goal")


def capture(env: Any) -> dict[str, Any]:
    """The state of a MiniGrid env (its `unwrapped`) as plain data: rows of the static cells,
    the named objects, the agent, the mission and, for a compound BabyAI mission, the step
    the agent is on (instructions.py). Unnamed objects get a name here (KEY1,
    DOOR2, ...: by type, in the order first seen, kept on the object so a pickled env keeps
    them)."""
    grid = env.grid
    counts = env.__dict__.setdefault("_teleo_counts", {})
    moving = {id(o) for o in getattr(env, "obstacles", ()) or ()}
    rows, objects = [], []
    for y in range(grid.height):
        row = []
        for x in range(grid.width):
            obj = grid.get(x, y)
            row.append(ROW_CHARS.get(obj.type, ".") if obj is not None else ".")
            if obj is not None and obj.type in NAMED:
                objects.append(_object(obj, counts, x, y, id(obj) in moving))
        rows.append("".join(row))
    carrying = None
    if env.carrying is not None:
        carrying = _object(env.carrying, counts, int(env.agent_pos[0]), int(env.agent_pos[1]),
                           False)
    step = current_step(env)   # after the objects: it reads their names
    return {"family": NAME, "width": grid.width, "height": grid.height, "rows": rows,
            "objects": objects, "carrying": carrying,
            "agent": {"x": int(env.agent_pos[0]), "y": int(env.agent_pos[1]),
                      "dir": int(env.agent_dir)},
            "mission": str(env.mission), "step": step[0] if step else "",
            "named": step[1] if step else {}, "step_count": int(env.step_count),
            "max_steps": int(env.max_steps)}


def _object(obj: Any, counts: dict[str, int], x: int, y: int, moving: bool) -> dict[str, Any]:
    name = getattr(obj, "_teleo_name", None)
    if name is None:
        counts[obj.type] = counts.get(obj.type, 0) + 1
        name = f"{obj.type.upper()}{counts[obj.type]}"
        obj._teleo_name = name
    state = "none"
    if obj.type == "door":
        state = "locked" if obj.is_locked else "open" if obj.is_open else "closed"
    inside = getattr(obj, "contains", None) if obj.type == "box" else None
    return {"name": name, "type": obj.type, "color": obj.color, "x": x, "y": y,
            "state": state, "moving": moving,
            "inside": [inside.type, inside.color] if inside is not None else None}


# --- the mission ------------------------------------------------------------------------
_OBJ = r"(?:(?P<color>red|green|blue|purple|yellow|grey) )?(?P<type>key|ball|box|door|object)"
_OBJ2 = _OBJ.replace("<color>", "<color2>").replace("<type>", "<type2>")
_PUT = ("putnear", "putnext")
_MISSIONS = (
    ("goal", re.compile(r"\bgoal\b")),
    ("open", re.compile(r"open the (?P<color>\w+) (?P<type>door),? then (?:open )?the "
                        r"(?P<color2>\w+) (?P<type2>door)")),
    ("putnear", re.compile(r"put (?:the|a) " + _OBJ + r" near (?:the|a) " + _OBJ2)),
    ("putnext", re.compile(r"put (?:the|a) " + _OBJ + r" next to (?:the|a) " + _OBJ2)),
    ("pickup", re.compile(r"(?:pick up|fetch|get) (?:the|a) " + _OBJ)),
    ("goto", re.compile(r"go to (?:the|a) " + _OBJ)),
    ("open", re.compile(r"open (?:the|a) " + _OBJ)),
)


def mission(text: str) -> dict[str, str]:
    """The mission string as a goal (docs/minigrid.md, "Missions"): kind (goal, pickup,
    goto, open, putnear, putnext, unknown), type and colour of the object (colour "any" when
    the mission names none; type "object": a key, ball or box), and for putnear and putnext
    the second object (near: the eight
    cells around it, MiniGrid's PutNear; next to: the four beside it, BabyAI's PutNext).

    >>> mission("use the key to open the door and then get to the goal")["kind"]
    'goal'
    >>> mission("open the red door then the blue door")["color2"]
    'blue'
    >>> mission("put a ball next to the purple door")["kind"]
    'putnext'
    >>> mission("open the purple door, then open the red door")["color2"]
    'red'
    >>> [mission(t)["type"] for t in ("go to a grey box", "pick up the green object")]
    ['box', 'object']
    >>> mission("put the red box next to a key")["color2"]
    'any'
    >>> sorted(mission("you must fetch a blue key").items())
    [('color', 'blue'), ('color2', 'none'), ('kind', 'pickup'), ('type', 'key'), ('type2', 'none')]
    """
    for kind, pattern in _MISSIONS:
        m = pattern.search(text)
        if m:
            found = m.groupdict()
            type2 = found.get("type2") or "none"
            return {"kind": kind, "type": found.get("type") or "goal",
                    "color": found.get("color") or "any", "type2": type2,
                    "color2": found.get("color2") or ("none" if type2 == "none" else "any")}
    return {"kind": "unknown", "type": "none", "color": "any", "type2": "none", "color2": "none"}


# --- perception -------------------------------------------------------------------------
def grid_of(state: dict[str, Any]) -> Grid:
    """The state's cells for the path search (paths.py)."""
    cells: dict[tuple[int, int], Cell] = {}
    for y, row in enumerate(state["rows"]):
        for x, ch in enumerate(row):
            if ch == "W":
                cells[(x, y)] = Cell("wall")
            elif ch == "L":
                cells[(x, y)] = Cell("lava")
            elif ch == "F":
                cells[(x, y)] = Cell("floor")
    for o in state["objects"]:
        kind = "obstacle" if o["moving"] else \
            f"door-{o['state']}" if o["type"] == "door" else o["type"]
        cells[(o["x"], o["y"])] = Cell(kind, o["color"], o["name"])
    return Grid(int(state["width"]), int(state["height"]), cells)


def perceive(state: dict[str, Any], agent: str, episode: dict[str, Any]) -> list[list[Any]]:
    """The agent's percepts (world/gym/percepts.md): itself, the mission, the episode, and
    each object with the affordances a grid agent needs."""
    grid = grid_of(state)
    a = state["agent"]
    me = (int(a["x"]), int(a["y"]), int(a["dir"]))
    carried = state.get("carrying")
    key_color = carried["color"] if carried and carried["type"] == "key" else ""
    search = Search(grid, me, key_color)
    bare = Search(grid, me, "") if carried else search   # with empty hands
    goal = mission(state.get("step") or state["mission"])   # a BabyAI mission's step
    front = grid.at(*ahead(me))
    out: list[list[Any]] = [
        ["agent", agent, "x", me[0], "y", me[1], "dir", me[2],
         "carrying", carried["name"] if carried else "none", "ahead", front.kind,
         "drop-next", _next(search.to_drop(_drop_fits(grid, me))) if carried else "none"],
        ["mission", "M", "kind", goal["kind"], "type", goal["type"], "color", goal["color"],
         "type2", goal["type2"], "color2", goal["color2"],
         "named", "yes" if state.get("named") else "no"],
        ["episode", "E", "won", "yes" if episode.get("terminated") and
         float(episode.get("reward", 0)) > 0 else "no",
         "over", "yes" if episode.get("terminated") or episode.get("truncated") else "no"],
    ]
    named = state.get("named") or {}
    anchors = set(named["anchor"]) if "anchor" in named else None
    for o in state["objects"]:
        out.append(_thing(o, grid, search, bare, goal, False, anchors))
    if carried:
        out.append(_thing(carried, grid, search, bare, goal, True, anchors))
    out += [["named", name, "as", role] for role, names in sorted(named.items())
            for name in names]
    return out


def _thing(o: dict[str, Any], grid: Grid, search: Search, bare: Search,
           goal: dict[str, str], carried: bool, anchors: set[str] | None) -> list[Any]:
    """A thing's percept; ``anchors``: the names of the objects a put's step picks (BabyAI),
    None where the mission's words alone pick them."""
    x, y = int(o["x"]), int(o["y"])
    if carried:
        reach = bare_reach = None
    elif o["type"] == "goal":
        reach, bare_reach = search.to_stand_on(x, y), bare.to_stand_on(x, y)
    else:
        reach, bare_reach = search.to_face(x, y), bare.to_face(x, y)
    percept = ["thing", o["name"], "type", o["type"], "color", o["color"], "x", x, "y", y,
               "state", o["state"], "moving", "yes" if o["moving"] else "no",
               "carried", "yes" if carried else "no",
               "inside-type", (o.get("inside") or ["none"])[0],
               "inside-color", (o.get("inside") or ["none", "none"])[1],
               "dist", reach.steps if reach else -1, "next", _next(reach),
               "via", (reach.via or "none") if reach else "none",
               "free", "yes" if bare_reach is not None and bare_reach.reachable else "no"]
    anchor = o["name"] in anchors if anchors is not None else \
        goal["type2"] in (o["type"], "object") and goal["color2"] in ("any", o["color"])
    if goal["kind"] in _PUT and anchor:
        fits = _near_fits(grid, x, y, diagonal=goal["kind"] == "putnear")
        percept += ["place-next", _next(search.to_drop(fits))]
    return percept


def _next(reach: Any) -> str:
    return reach.next if reach is not None else "none"


def _drop_fits(grid: Grid, me: tuple[int, int, int]):
    """Where a carried object may be put down out of the way, best first: rank 0, an empty
    cell next to no door whose filling leaves every other cell the agent can walk to
    reachable; rank 1, such a cell next to a door; rank 2, any empty cell."""
    cuts = cut_cells(walkable_region(grid, (me[0], me[1]), None))
    known: dict[tuple[int, int], int | None] = {}

    def fits(x: int, y: int) -> int | None:
        if (x, y) not in known:
            known[(x, y)] = rank(x, y)
        return known[(x, y)]

    def rank(x: int, y: int) -> int | None:   # the same wherever the agent stands in region
        if grid.at(x, y).kind != "empty":
            return None
        if (x, y) in cuts:
            return 2
        return 1 if any(grid.at(x + dx, y + dy).kind.startswith("door") for dx, dy in DIRS) \
            else 0
    return fits


def _near_fits(grid: Grid, tx: int, ty: int, diagonal: bool):
    """An empty cell next to (tx, ty): one of the eight around it with ``diagonal`` (MiniGrid's
    PutNear), else one of the four beside it (BabyAI's PutNext)."""
    def fits(x: int, y: int) -> int | None:
        dx, dy = abs(x - tx), abs(y - ty)
        beside = max(dx, dy) == 1 if diagonal else dx + dy == 1
        return 0 if beside and grid.at(x, y).kind == "empty" else None
    return fits


def frame(state: dict[str, Any], tile: int = 32) -> Any:
    """The environment's own picture of the state (MiniGrid's tile renderer), an RGB array."""
    from minigrid.core.grid import Grid as MiniGrid
    from minigrid.core.world_object import Ball, Box, Door, Floor, Goal, Key, Lava, Wall

    g = MiniGrid(int(state["width"]), int(state["height"]))
    for y, row in enumerate(state["rows"]):
        for x, ch in enumerate(row):
            if ch in "WLF":
                g.set(x, y, {"W": Wall, "L": Lava, "F": Floor}[ch]())
    make = {"key": Key, "ball": Ball, "box": Box, "goal": lambda c: Goal()}
    for o in state["objects"]:
        if o["type"] == "door":
            obj = Door(o["color"], is_open=o["state"] == "open", is_locked=o["state"] == "locked")
        else:
            obj = make[o["type"]](o["color"])
        g.set(int(o["x"]), int(o["y"]), obj)
    a = state["agent"]
    return g.render(tile, (int(a["x"]), int(a["y"])), int(a["dir"]))
