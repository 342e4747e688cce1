"""The bins world on a pymunk space: a walled floor, balls that roll (dynamic circles, damped),
one robot per agent (a kinematic circle that pushes the balls in its way), and bins, one per
colour, standing against the far wall.

Actions (one outcome each, every cycle):
  (*goto X)   drive toward ball or bin X, at SPEED, stopping short of it (the drive continues
              in the next cycles until the robot is there or another action replaces it)
  (*grab B)   pick up ball B, within REACH of the robot, with an empty hand
  (*drop B)   put down the held ball B in front of the robot; over a bin it falls in (counted
              as balls_sorted if the bin is of its colour, wrong_bin if not) and leaves play
  (*wait)     stop where it is
Event: kick {ball, vx, vy}: a ball on the floor is given that velocity [m/s].

pymunk is deterministic for a fixed step and insertion order, and the default balls are
placed by the seed, so one config and seed give the same run, step for step.
"""

from __future__ import annotations

import math
import random
from dataclasses import asdict, dataclass, field
from typing import Any

import pymunk

from bus.schema import FieldError, ListOf, Num, Record, Str, Tagged, TupleOf
from world.base import BaseWorld
from world.domain import event_outcome
from world.errors import ConfigError, WorldError

DT = 0.1            # [s] a cycle
SUBSTEPS = 5        # physics steps a cycle
SPEED = 1.0         # [m/s] the robot's top speed
ROBOT_R, BALL_R = 0.25, 0.15    # [m] radii
REACH = 0.5         # [m] centre to centre, to grab a ball
STOP = 0.45         # [m] a drive toward a ball or a bin stops this far from its centre
BIN_HALF = 0.7      # [m] half the side of a bin's square mouth
ACTIONS = ("*goto", "*grab", "*drop", "*wait")

_POS = Num(0.0, 100.0)
WORLD = Record({}, {
    "domain": Str(), "size": TupleOf(Num(2.0, 100.0), Num(2.0, 100.0), what="[width, depth] [m]"),
    "balls": ListOf(Record({"id": Str(), "colour": Str(), "x": _POS, "y": _POS}, what="a ball"),
                    max_len=50),
    "bins": ListOf(Record({"colour": Str(), "x": _POS, "y": _POS}, what="a bin"), max_len=10),
}, what="the [world] table of a bins scenario")
EVENTS = Tagged({"kick": Record({"ball": Str(), "vx": Num(-10.0, 10.0), "vy": Num(-10.0, 10.0)})})


@dataclass(frozen=True)
class Config:
    """The floor [m], the balls' starts (id, colour, x, y) and the bins' centres by colour."""

    size: tuple[float, float]
    balls: tuple[tuple[str, str, float, float], ...]
    bins: dict[str, tuple[float, float]]


def load_config(table: dict[str, Any], seed: int) -> Config:
    """The `[world]` table read (ConfigError naming the key); default: an 8 x 5 m floor, a red
    and a blue bin at the far wall, and three balls placed by the seed."""
    try:
        WORLD.check(table)
    except FieldError as exc:
        raise ConfigError(f"[world] {exc}") from None
    w, d = (float(v) for v in table.get("size", (8.0, 5.0)))
    bins = {b["colour"]: (float(b["x"]), float(b["y"])) for b in table.get("bins", ())} or {
        "red": (1.5, d - 0.8), "blue": (w - 1.5, d - 0.8)}
    rng = random.Random(seed)
    balls = tuple((b["id"], b["colour"], float(b["x"]), float(b["y"]))
                  for b in table.get("balls", ())) or tuple(
        (f"B{k + 1}", colour, round(rng.uniform(1.0, w - 1.0), 2), round(rng.uniform(1.0, 2.0), 2))
        for k, colour in enumerate(("red", "blue", "red")))
    for k, (_, colour, x, y) in enumerate(balls):
        if colour not in bins:
            raise ConfigError(f"[world] balls[{k}].colour: expected one of the bins' colours "
                              f"{sorted(bins)}, got {colour!r}")
        if not (BALL_R < x < w - BALL_R and BALL_R < y < d - BALL_R):
            raise ConfigError(f"[world] balls[{k}]: ({x}, {y}) is off the {w} x {d} m floor")
    if len({b[0] for b in balls}) != len(balls):
        raise ConfigError(f"[world] balls: expected distinct ids, got {[b[0] for b in balls]}")
    return Config((w, d), balls, bins)


@dataclass
class Robot:
    """An agent's robot: its body, where it is driving to, the ball it holds, its counters."""

    id: str
    body: pymunk.Body
    target: str = ""
    holding: str = ""
    facing: tuple[float, float] = (0.0, 1.0)
    counters: dict[str, int] = field(default_factory=lambda: {
        "balls_sorted": 0, "wrong_bin": 0, "actions_failed": 0})


@dataclass(frozen=True)
class Snapshot:
    """One cycle's state; ``balls`` rows {id, colour, x, y, bin} ("" bin: on the floor or
    held), ``robots`` rows {agent, id, x, y, holding}."""

    cycle: int
    time: float
    size: tuple[float, float]
    bins: dict[str, tuple[float, float]]
    robots: tuple[dict[str, Any], ...]
    balls: tuple[dict[str, Any], ...]
    counters: dict[str, dict[str, int]]
    events: tuple[dict[str, Any], ...]

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["size"], d["bins"] = list(self.size), {c: list(p) for c, p in self.bins.items()}
        d["robots"], d["balls"] = list(d["robots"]), list(d["balls"])
        d["events"] = list(d["events"])
        return {"domain": "bins", **d}


class BinsWorld(BaseWorld):
    """The World protocol (world/domain.py); BaseWorld does its guards, inject, snapshot_dict."""

    def __init__(self, config: Config, seed: int, agents: list[str]) -> None:
        if not agents or len(set(agents)) != len(agents):
            raise WorldError(f"BinsWorld: expected distinct agent ids, got {agents}")
        self.config, self.seed, self.cycle = config, seed, 0
        self.space = pymunk.Space()
        self.space.damping = 0.3            # balls roll to a stop within a few seconds
        w, d = config.size
        for a, b in (((0, 0), (w, 0)), ((w, 0), (w, d)), ((w, d), (0, d)), ((0, d), (0, 0))):
            wall = pymunk.Segment(self.space.static_body, a, b, 0.05)
            wall.elasticity = 0.5
            self.space.add(wall)
        self.balls: dict[str, pymunk.Body] = {}
        self.colour = {name: colour for name, colour, _, _ in config.balls}
        self.in_bin: dict[str, str] = {}
        for name, _, x, y in config.balls:
            body = pymunk.Body(0.2, pymunk.moment_for_circle(0.2, 0, BALL_R))
            body.position = (x, y)
            shape = pymunk.Circle(body, BALL_R)
            shape.elasticity, shape.friction = 0.6, 0.5
            self.space.add(body, shape)
            self.balls[name] = body
        self.robots: dict[str, Robot] = {}
        for k, agent in enumerate(agents):
            body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            body.position = (w / 2 + (k - (len(agents) - 1) / 2) * 0.8, 0.5)
            self.space.add(body, pymunk.Circle(body, ROBOT_R))
            self.robots[agent] = Robot(f"R{k + 1}", body)
        self._events: list[dict[str, Any]] = []
        self._incoming: list[dict[str, Any]] = []

    # -- BaseWorld's hooks ---------------------------------------------------------------------
    def actors(self) -> dict[str, Robot]:
        return self.robots

    def act(self, robot: Robot, actions: Any) -> list[dict[str, Any]]:
        out = []
        for action in actions:
            reason = self._do(robot, action) if isinstance(action, list | tuple) and action \
                else f"expected an action [name, args...], got {action!r:.80}"
            robot.counters["actions_failed"] += bool(reason)
            out.append({"action": list(action) if isinstance(action, list | tuple) else
                        [repr(action)], "status": "failed" if reason else "done",
                        "reason": reason})
        return out

    def apply_event(self, event: dict[str, Any]) -> dict[str, Any]:
        try:
            EVENTS.check(event)
        except FieldError as exc:
            return event_outcome(event, f"inject: {exc}")
        body = self.balls.get(event["ball"])
        if body is None or body not in self.space.bodies:
            return event_outcome(event, f"inject: ball: expected one on the floor "
                                        f"{sorted(self._on_floor())}, got {event['ball']!r}")
        body.velocity = (float(event["vx"]), float(event["vy"]))
        return event_outcome(event)

    # -- the World protocol's own half ---------------------------------------------------------
    def safe_actions(self, agent: str) -> list[list[Any]]:
        """A robot whose agent is silent stops where it is."""
        return [["*wait"]]

    def step(self) -> None:
        """Drive each robot toward its target for DT [s], in SUBSTEPS physics steps."""
        for robot in self.robots.values():
            robot.body.velocity = self._drive(robot)
        for _ in range(SUBSTEPS):
            self.space.step(DT / SUBSTEPS)
        self.cycle += 1
        self._events, self._incoming = self._incoming, []

    def snapshot(self) -> Snapshot:
        robots = tuple({"agent": a, "id": r.id, "x": _r(r.body.position.x),
                        "y": _r(r.body.position.y), "holding": r.holding}
                       for a, r in self.robots.items())
        balls = []
        for name, body in self.balls.items():
            held = next((r for r in self.robots.values() if r.holding == name), None)
            x, y = held.body.position if held else body.position
            balls.append({"id": name, "colour": self.colour[name], "x": _r(x), "y": _r(y),
                          "bin": self.in_bin.get(name, "")})
        return Snapshot(self.cycle, round(self.cycle * DT, 9), self.config.size,
                        dict(self.config.bins), robots, tuple(balls),
                        {a: dict(r.counters) for a, r in self.robots.items()},
                        tuple(self._events))

    # -- actions -------------------------------------------------------------------------------
    def _do(self, robot: Robot, action: list[Any] | tuple[Any, ...]) -> str:
        """Apply one action; "" when done, else why it failed."""
        name, args = action[0], list(action[1:])
        if name not in ACTIONS:
            return f"unknown action {name!r}; known: *goto X, *grab B, *drop B, *wait"
        if len(args) != (name != "*wait"):
            return f"{name}: expected {int(name != '*wait')} argument(s), got {args!r:.80}"
        if name == "*wait":
            robot.target = ""
            return ""
        what = str(args[0])
        if name == "*goto":
            if what not in self.balls and bin_id(_colour(what)) != what or \
                    what not in self.balls and _colour(what) not in self.config.bins:
                return f"*goto: expected a ball {sorted(self.balls)} or a bin, got {what!r}"
            robot.target = what
            return ""
        if name == "*grab":
            return self._grab(robot, what)
        return self._drop(robot, what)

    def _grab(self, robot: Robot, ball: str) -> str:
        if robot.holding:
            return f"*grab: the hand already holds {robot.holding}"
        if ball not in self._on_floor():
            return f"*grab: expected a ball on the floor {sorted(self._on_floor())}, got {ball!r}"
        dist = robot.body.position.get_distance(self.balls[ball].position)
        if dist > REACH:
            return f"*grab: {ball} is {dist:.2f} m away; the reach is {REACH} m"
        self.space.remove(self.balls[ball], *self.balls[ball].shapes)
        robot.holding, robot.target = ball, ""
        return ""

    def _drop(self, robot: Robot, ball: str) -> str:
        if robot.holding != ball:
            return f"*drop: the hand holds {robot.holding or 'nothing'}, not {ball!r}"
        body, (fx, fy), ahead = self.balls[ball], robot.facing, ROBOT_R + BALL_R + 0.02
        x, y = robot.body.position + (fx * ahead, fy * ahead)
        robot.holding, body.position, body.velocity = "", (x, y), (0.0, 0.0)
        into = next((c for c, (bx, by) in self.config.bins.items()
                     if abs(x - bx) <= BIN_HALF and abs(y - by) <= BIN_HALF), "")
        if not into:
            self.space.add(body, *body.shapes)
            return ""
        self.in_bin[ball] = into
        right = into == self.colour[ball]
        robot.counters["balls_sorted" if right else "wrong_bin"] += 1
        self._incoming.append({"kind": "sorted" if right else "wrong_bin", "cycle": self.cycle,
                               "ball": ball, "bin": into})
        return ""

    def _on_floor(self) -> list[str]:
        held = {r.holding for r in self.robots.values()}
        return [b for b in self.balls if b not in self.in_bin and b not in held]

    def _drive(self, robot: Robot) -> tuple[float, float]:
        """The robot's velocity [m/s] for this cycle: toward its target, stopping STOP short."""
        if not robot.target or (robot.target in self.balls and robot.target not in
                                self._on_floor()):
            return (0.0, 0.0)
        goal = (self.balls[robot.target].position if robot.target in self.balls
                else self.config.bins[_colour(robot.target)])
        dx, dy = goal[0] - robot.body.position.x, goal[1] - robot.body.position.y
        dist = math.hypot(dx, dy)
        if dist <= STOP + 1e-6:
            return (0.0, 0.0)
        robot.facing = (dx / dist, dy / dist)
        speed = min(SPEED, (dist - STOP) / DT)
        return (robot.facing[0] * speed, robot.facing[1] * speed)


def bin_id(colour: str) -> str:
    """A bin's name in percepts and actions: its colour and "-bin" (red-bin)."""
    return f"{colour}-bin"


def _colour(bin_name: str) -> str:
    return bin_name.removesuffix("-bin")


def _r(value: float) -> float:
    return round(float(value), 4) + 0.0
