"""The office world of seed 003 on a pymunk space: the World protocol (world/domain.py).

One cycle: the agents' commands are applied (operations.py), then `step` runs the physics
in `substeps` pymunk steps with each navigating robot's velocity set toward its next
waypoint, and afterwards turns contacts into bumps, cools the coffee, lets people wander
(when configured), updates each robot's memory of what it sees and advances every running
operation. One seeded random.Random drives all chance, so one config and seed give the same
run, step for step.
"""

from __future__ import annotations

import math
import random
from typing import Any

from world.base import BaseWorld
from world.errors import WorldError
from world.office.config import OfficeConfig
from world.office.events import apply_injection
from world.office.floor import build_floor, door_id
from world.office.operations import Item, Person, apply_command, outcome, step_operation
from world.office.physics import Physics
from world.office.robot import Robot, check_goto, drive, look
from world.office.snapshot import (
    ItemState,
    ObstacleState,
    OfficeSnapshot,
    PersonState,
    RobotState,
)

COMMON_KINDS = ("kitchen", "lounge")    # where wandering people go
AGENT_ENDED = ("pre-empted", "stopped")  # failed, but by the agent's choice: not a failure


def _r(value: float, digits: int = 4) -> float:
    return round(float(value), digits) + 0.0


class OfficeSim(BaseWorld):
    """One floor, its people and items, and one robot per agent id."""

    def __init__(self, config: OfficeConfig, seed: int, agents: list[str]) -> None:
        if len(set(agents)) != len(agents):
            raise WorldError(f"OfficeSim: agent ids must be distinct, got {agents}")
        self.config, self.floor = config, build_floor(config)
        self.rng = random.Random(seed)
        self.cycle, self.time = 0, 0.0
        self.physics = Physics(self.floor)
        states = {door_id(r.id): r.door for r in config.rooms}
        states.update({f.id: f.state for f in config.fire_doors})
        self.doors = {d.id: states[d.id] for d in self.floor.doors}
        for d in self.floor.doors:
            self.physics.set_door(d, self.doors[d.id])
        self.occupants = {r.id: r.occupants for r in config.rooms if r.occupants}
        self.people = {p.id: Person(p.id, p.room, p.office) for p in config.people}
        self.items = {i.id: Item(i.id, i.kind, i.holder, i.to, self._fresh(i.kind, i.temperature))
                      for i in config.items}
        self.obstacles: dict[str, ObstacleState] = {}
        self._events: list[dict[str, Any]] = []      # reported in the current snapshot
        self._incoming: list[dict[str, Any]] = []    # happening during the coming step
        self.robots: dict[str, Robot] = {}
        starts = {r.agent: r.room for r in config.robots}
        default = next((r.id for r in self.floor.rooms if r.kind == "lab"), self.floor.rooms[0].id)
        for agent in agents:
            room = self.floor.room(starts.get(agent, default))
            k = sum(1 for r in self.robots.values() if self.floor.locate(*r.position) == room.id)
            dx = 0.8 * ((k + 1) // 2) * (1 if k % 2 else -1)
            body = self.physics.add_robot(agent, (room.spot[0] + dx, room.spot[1]))
            robot = Robot(agent, body)
            robot.known_doors = {d: (s, 0) for d, s in self.doors.items()}
            robot.known_people = {p.id: (p.room, 0) for p in self.people.values()}
            self.robots[agent] = robot
        self.place_people()

    def _fresh(self, kind: str, temperature: float) -> float:
        if kind != "coffee":
            return 0.0
        return temperature or self.config.coffee_brew

    # -- what operations and events call -------------------------------------------------------
    def emit(self, kind: str, agent: str, **fields: Any) -> None:
        """Record an event for the next snapshot."""
        self._incoming.append({"kind": kind, "agent": agent, "cycle": self.cycle, **fields})

    def finish(self, robot: Robot, code: str = "", detail: str = "") -> None:
        """End the robot's running operation: done (no code) or failed with a reason."""
        op = robot.op
        result = outcome(op.action, robot.id, code, detail)
        op.status, op.code, op.reason, op.ended = result["status"], code, result["reason"], \
            self.cycle
        robot.finished.append(result)
        if code and code not in AGENT_ENDED:
            robot.counters["failures"] += 1
        self.emit("operation", robot.id, action=list(op.action), status=op.status,
                  reason=op.reason)

    def place_people(self) -> None:
        """Put every person at a desk of the room they are in (by id order)."""
        seated: dict[str, int] = {}
        for p in sorted(self.people.values(), key=lambda p: p.id):
            k = seated.get(p.room, 0)
            seated[p.room] = k + 1
            self.physics.place_person(p.id, self.floor.room(p.room).desk(k))

    # -- the contract ---------------------------------------------------------------------------
    def actors(self) -> dict[str, Robot]:
        """Each agent's robot (world/base.py: the guards of apply_actions)."""
        return self.robots

    def act(self, robot: Robot, actions: Any) -> list[dict[str, Any]]:
        """Apply an agent's commands in order. Returns the outcomes of the operations that
        ended since the last call and of those that ended now; a command that starts or
        continues an operation gets its outcome when that operation ends. Never raises."""
        out, robot.finished = robot.finished, []
        for action in actions:
            now = apply_command(self, robot, action)
            out += robot.finished
            robot.finished = []
            if now is not None:
                out.append(now)
        return out

    def safe_actions(self, agent: str) -> list[list[Any]]:
        """A robot whose agent is silent stops where it is."""
        return [["*stop"]]

    def apply_event(self, event: dict[str, Any]) -> dict[str, Any]:
        """Apply a scenario event (world/office/events.py); never raises on a bad event."""
        return apply_injection(self, event)

    def step(self) -> None:
        """Advance the world by one fixed dt [s]."""
        cfg = self.config
        sub = cfg.dt / cfg.substeps
        self.physics.contacts = []
        robots = [self.robots[a] for a in sorted(self.robots)]
        for _ in range(cfg.substeps):
            for robot in robots:
                if robot.running("goto"):
                    drive(self, robot, sub)
                else:
                    robot.body.velocity = (0.0, 0.0)
            before = [r.position for r in robots]
            self.physics.step(sub)
            for robot, was in zip(robots, before, strict=True):
                robot.travelled += math.dist(was, robot.position)
        self.cycle += 1
        self.time = round(self.cycle * cfg.dt, 9)
        self._bumps()
        self._cool(cfg.dt)
        self._wander(cfg.dt)
        for robot in robots:
            look(self, robot)
            self._see_people(robot)
            if robot.running("goto"):
                check_goto(self, robot)
            step_operation(self, robot)
            robot.counters["travel_cm"] = round(robot.travelled * 100)
        self._events, self._incoming = self._incoming, []

    # -- what happens by itself -----------------------------------------------------------------
    def _bumps(self) -> None:
        for agent, label in sorted(set(self.physics.contacts)):
            robot = self.robots[agent]
            x, y = robot.position
            robot.counters["bumps"] += 1
            self.emit("bump", agent, touched=label, x=_r(x, 2), y=_r(y, 2))
            kind, _, ident = label.partition(" ")
            if kind == "obstacle" and ident in self.obstacles:
                o = self.obstacles[ident]
                robot.known_obstacles[ident] = (o.x, o.y, o.radius)
            if robot.running("goto"):
                robot.halt()
                self.finish(robot, "bumped", f"touched {label} at ({x:.1f}, {y:.1f})")

    def _cool(self, dt: float) -> None:
        """Newton's law toward the ambient temperature; a kitchen keeps its coffee fresh."""
        cfg = self.config
        decay = math.exp(-dt / cfg.coffee_tau)
        for item in self.items.values():
            if item.kind != "coffee":
                continue
            before = item.temperature
            if self.floor.has_room(item.holder) and \
                    self.floor.room(item.holder).kind == "kitchen":
                item.temperature = cfg.coffee_brew
            else:
                item.temperature = cfg.coffee_ambient + (before - cfg.coffee_ambient) * decay
            if before >= cfg.coffee_cold > item.temperature:
                holder = item.holder if item.holder in self.robots else ""
                self.emit("coffee-cold", holder, item=item.id, temperature=_r(item.temperature, 2))

    def _wander(self, dt: float) -> None:
        cfg = self.config
        if cfg.wander_rate <= 0:
            return
        common = [r.id for r in self.floor.rooms if r.kind in COMMON_KINDS]
        moved = False
        for p in sorted(self.people.values(), key=lambda p: p.id):
            if p.away_until >= 0 and self.time >= p.away_until:
                p.room, p.away_until, moved = p.office, -1.0, True
                self.emit("person-moved", "", person=p.id, room=p.room)
            elif p.away_until < 0 and p.room == p.office and common and \
                    self.rng.random() < cfg.wander_rate * dt:
                p.room = common[self.rng.randrange(len(common))]
                p.away_until, moved = self.time + cfg.wander_time, True
                self.emit("person-moved", "", person=p.id, room=p.room)
        if moved:
            self.place_people()

    def _see_people(self, robot: Robot) -> None:
        """In a room the robot sees who is there, and who it expected but is not."""
        here = self.floor.locate(*robot.position)
        if not self.floor.has_room(here):
            return
        for p in self.people.values():
            if p.room == here:
                robot.known_people[p.id] = (here, self.cycle)
            elif robot.known_people.get(p.id, ("", 0))[0] == here:
                robot.known_people[p.id] = ("unknown", self.cycle)

    # -- snapshot -------------------------------------------------------------------------------
    def _robot_state(self, r: Robot) -> RobotState:
        (x, y), v = r.position, r.body.velocity
        return RobotState(
            r.id, _r(x), _r(y), _r(r.heading, 2), _r(math.hypot(v.x, v.y)),
            self.floor.locate(x, y), tuple(r.carrying), _r(r.travelled, 3),
            r.op.to_dict() if r.op else {}, tuple((_r(px), _r(py)) for _, (px, py) in r.route),
            {d: [s, c] for d, (s, c) in sorted(r.known_doors.items())},
            {p: [room, c] for p, (room, c) in sorted(r.known_people.items())},
            {o: [ox, oy, rad] for o, (ox, oy, rad) in sorted(r.known_obstacles.items())},
            {room: [res, c] for room, (res, c) in sorted(r.observations.items())})

    def snapshot(self) -> OfficeSnapshot:
        """The frozen observable state of the current cycle (events: those of the last step)."""
        people = []
        for p in sorted(self.people.values(), key=lambda p: p.id):
            pos = self.physics.people[p.id].position
            people.append(PersonState(p.id, p.room, p.office, _r(pos.x), _r(pos.y)))
        items = tuple(ItemState(i.id, i.kind, i.holder, i.to, _r(i.temperature, 3))
                      for i in self.items.values())
        return OfficeSnapshot(
            self.cycle, self.time, self.config,
            tuple(self._robot_state(self.robots[a]) for a in sorted(self.robots)),
            tuple(people), items, dict(self.doors), dict(sorted(self.occupants.items())),
            tuple(self.obstacles[o] for o in sorted(self.obstacles)),
            {a: dict(self.robots[a].counters) for a in sorted(self.robots)}, tuple(self._events))
