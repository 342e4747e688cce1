"""The urban driving simulation (seed 000, "An Illustrative Domain") on a pymunk space.

Every vehicle and pedestrian is a pymunk body with a sensor shape: pymunk integrates the agent
cars' motion (velocity and yaw rate from the bicycle model in vehicle.py) and reports every
contact, which is how hits and collisions are detected. Traffic and pedestrians are moved by their
behaviour rules (actors.py). One seeded random.Random owned by the simulation drives all
chance, so one config and seed give the same run, step for step.
"""

from __future__ import annotations

import math
import pickle
import random
from dataclasses import dataclass, field
from typing import Any

import pymunk

from world.base import BaseWorld, deg
from world.driving.actors import (
    Pedestrian,
    Traffic,
    choose_exit,
    corridors_blocked,
    place_traffic,
    spawn_pedestrian,
    step_pedestrian,
    step_traffic,
)
from world.driving.city import LANE_CENTRE, build_city
from world.driving.config import CarStart, WorldConfig
from world.driving.injection import apply_injection
from world.driving.laws import LawState, delivers, road_events
from world.driving.paths import lane_paths, node_of
from world.driving.snapshot import COUNTERS, CarState, PackageState, PedState, WorldSnapshot
from world.driving.vehicle import (
    CAR_LENGTH,
    CAR_WIDTH,
    Controls,
    accelerate,
    apply_action,
    yaw_rate,
)
from world.errors import WorldError

AGENT_BIT, TRAFFIC_BIT, PED_BIT = 1, 2, 4
CT_AGENT, CT_TRAFFIC, CT_PED = 1, 2, 3
PED_RADIUS = 0.35   # [m]
HIT_SPEED = 0.3    # [m/s] a car slower than this does not hit a walker who bumps into it
CITY_EDGE = 20.0   # [m] beyond the outer streets: an agent's car stops there


@dataclass
class AgentCar:
    id: str
    body: pymunk.Body
    speed: float = 0.0
    controls: Controls = field(default_factory=Controls)
    law: LawState = field(default_factory=LawState)
    counters: dict[str, int] = field(default_factory=lambda: dict.fromkeys(COUNTERS, 0))
    at_edge: bool = False     # held at the city's edge (Simulation._keep_in_city)


def _body(space: pymunk.Space, shape_of: Any, ctype: int, category: int, mask: int,
          owner: tuple[str, str], owners: dict) -> pymunk.Body:
    body = pymunk.Body(1.0, float("inf"))
    shape = shape_of(body)
    shape.sensor, shape.collision_type = True, ctype
    shape.filter = pymunk.ShapeFilter(categories=category, mask=mask)
    space.add(body, shape)
    owners[shape] = owner
    return body


class Simulation(BaseWorld):
    """One city, its traffic and pedestrians, and one car per agent id."""

    def __init__(self, config: WorldConfig, seed: int, agents: list[str]) -> None:
        if len(set(agents)) != len(agents):
            raise WorldError(f"Simulation: agent ids must be distinct, got {agents}")
        self.config, self.city = config, build_city(config)
        self.paths = lane_paths(self.city)
        self.rng = random.Random(seed)
        self.cycle = 0
        self.space = pymunk.Space()
        self._owners: dict[pymunk.Shape, tuple[str, str]] = {}
        self._contacts: list[tuple[tuple[str, str], tuple[str, str]]] = []
        self.space.on_collision(begin=self._on_contact)
        self.cars: dict[str, AgentCar] = {}
        self.traffic: list[Traffic] = []
        self.walkers: list[Pedestrian] = []
        self.packages: dict[str, PackageState] = {p.id: PackageState(p.id, p.address, p.street,
                                                                       p.owner)
                                                    for p in config.packages}
        self.blocked: set[str] = set()
        self._events: list[dict[str, Any]] = []      # reported in the current snapshot
        self._incoming: list[dict[str, Any]] = []    # happening during the coming step
        self._traffic_bodies: list[pymunk.Body] = []
        self._ped_bodies: list[pymunk.Body] = []
        starts = {c.agent: c for c in config.cars}
        for k, agent in enumerate(agents):
            self._add_agent(agent, starts.get(agent) or self._default_start(agent, k))
        for k in range(config.traffic):
            self._add_traffic(f"V{k + 1}")
        for k in range(config.pedestrians):
            self.add_pedestrian(spawn_pedestrian(self.city, self.rng, f"M{k + 1}"))

    # -- construction -------------------------------------------------------------------------
    def _default_start(self, agent: str, k: int) -> CarStart:
        """Agent k without a configured start: block by block along the ordinal streets (FIRST
        A-B, SECOND A-B, ..., FIRST B-C, ...), eastbound, 20, 45 or 70 m into the block."""
        cfg = self.config
        slots = [(row, col) for col in range(len(cfg.ns_streets) - 1)
                 for row in range(len(cfg.ew_streets))]
        row, col = slots[k % len(slots)]
        along = 20.0 + 25.0 * ((k // len(slots)) % 3)
        return CarStart(agent, cfg.ew_streets[row], cfg.ns_streets[col], cfg.ns_streets[col + 1],
                        along)

    def _add_agent(self, agent: str, start: CarStart) -> None:
        cfg, L = self.config, self.config.block_length
        if start.street in cfg.ns_streets:
            x = cfg.ns_streets.index(start.street) * L
            y0, y1 = (cfg.ew_streets.index(n) * L for n in (start.from_street, start.toward))
            d = 1.0 if y1 > y0 else -1.0
            pos, angle = (x + LANE_CENTRE * d, y0 + start.along * d), math.pi / 2 * d
        else:
            y = cfg.ew_streets.index(start.street) * L
            x0, x1 = (cfg.ns_streets.index(n) * L for n in (start.from_street, start.toward))
            d = 1.0 if x1 > x0 else -1.0
            pos, angle = (x0 + start.along * d, y - LANE_CENTRE * d), 0.0 if d > 0 else math.pi
        body = _body(self.space, lambda b: pymunk.Poly.create_box(b, (CAR_LENGTH, CAR_WIDTH)),
                     CT_AGENT, AGENT_BIT, AGENT_BIT | TRAFFIC_BIT | PED_BIT, ("car", agent),
                     self._owners)
        body.position, body.angle = pos, angle
        self.cars[agent] = AgentCar(agent, body, speed=start.speed)

    def _add_traffic(self, ident: str) -> None:
        keys = sorted(k for k in self.paths if k[0] == "lane")
        for _ in range(100):
            key = keys[self.rng.randrange(len(keys))]
            t = Traffic(ident, key, self.rng.uniform(0.0, self.paths[key].length),
                        self.config.speed_limit)
            place_traffic(t, self.paths)
            if all(math.hypot(t.x - x, t.y - y) > 15.0
                   for _, x, y, _ in self._vehicle_points()):
                break
        choose_exit(self.city, t, self.rng, frozenset(self.blocked))
        body = _body(self.space, lambda b: pymunk.Poly.create_box(b, (CAR_LENGTH, CAR_WIDTH)),
                     CT_TRAFFIC, TRAFFIC_BIT, AGENT_BIT, ("car", ident), self._owners)
        self._sync(body, t.x, t.y, t.heading)
        self.traffic.append(t)
        self._traffic_bodies.append(body)

    def add_pedestrian(self, p: Pedestrian) -> None:
        """Add a pedestrian (used at start and by injected events)."""
        body = _body(self.space, lambda b: pymunk.Circle(b, PED_RADIUS), CT_PED, PED_BIT,
                     AGENT_BIT, ("ped", p.id), self._owners)
        self._sync(body, p.x, p.y, p.heading)
        self.walkers.append(p)
        self._ped_bodies.append(body)

    @staticmethod
    def _sync(body: pymunk.Body, x: float, y: float, heading: float) -> None:
        """Place a traffic or pedestrian body (their velocity stays 0: they are moved here)."""
        body.position, body.angle = (x, y), math.radians(heading)

    def _vehicle_points(self) -> list[tuple[str, float, float, float]]:
        pts = [(a, c.body.position.x, c.body.position.y, math.degrees(c.body.angle))
               for a, c in self.cars.items()]
        return pts + [(t.id, t.x, t.y, t.heading) for t in self.traffic]

    # -- the contract ---------------------------------------------------------------------------
    def actors(self) -> dict[str, AgentCar]:
        """Each agent's car (world/base.py: the guards of apply_actions)."""
        return self.cars

    def act(self, actor: AgentCar, actions: Any) -> list[dict[str, Any]]:
        """Apply an agent's actions of this cycle in order (later ones win); one outcome each."""
        return [apply_action(actor.controls, a) for a in actions]

    def safe_actions(self, agent: str) -> list[list[Any]]:
        """What a car gets when its agent's actions did not arrive: full brake, wheel held
        (the car stops on its current arc instead of swerving) until the agent is back."""
        return [["*brake", 100]]

    def apply_event(self, event: dict[str, Any]) -> dict[str, Any]:
        """Apply a scenario event (see world/injection.py); returns {"event", "status", "reason"}.
        Never raises on a bad event (world/base.py reports and logs it)."""
        return apply_injection(self, event)

    def step(self) -> None:
        """Advance the world by one fixed dt [s]."""
        dt = self.config.dt
        for car in self.cars.values():
            car.speed = accelerate(car.speed, car.controls, dt)
            a = car.body.angle
            car.body.velocity = (car.speed * math.cos(a), car.speed * math.sin(a))
            car.body.angular_velocity = yaw_rate(car.speed, car.controls.wheel)
        points = self._vehicle_points()
        ahead = corridors_blocked(self.traffic, points, [(p.x, p.y) for p in self.walkers])
        blocked = frozenset(self.blocked)
        busy = {node_of(self.city, t.key) for t in self.traffic
                if t.key[0] == "turn" or t.committed}
        for t, body, jam in zip(self.traffic, self._traffic_bodies, ahead, strict=True):
            step_traffic(self.city, t, self.paths, self.rng, dt, points, jam, blocked, busy)
            self._sync(body, t.x, t.y, t.heading)
        for p, body in zip(self.walkers, self._ped_bodies, strict=True):
            step_pedestrian(self.city, p, self.rng, dt)
            self._sync(body, p.x, p.y, p.heading)
        self._contacts = []
        self.space.step(dt)
        self.cycle += 1
        self._handle_contacts()
        for car in self.cars.values():
            self._keep_in_city(car)
            self._check_laws(car)
        self._events, self._incoming = self._incoming, []

    def _on_contact(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        a, b = arbiter.shapes
        if a in self._owners and b in self._owners:
            self._contacts.append((self._owners[a], self._owners[b]))

    def _handle_contacts(self) -> None:
        peds = {p.id: p for p in self.walkers}
        for first, second in sorted(self._contacts):
            pair = (first, second)
            cars = [ident for kind, ident in pair if kind == "car" and ident in self.cars]
            ped = next((ident for kind, ident in pair if kind == "ped"), None)
            moving = [c for c in cars if self.cars[c].speed >= HIT_SPEED]
            if ped is not None and cars and not moving:
                continue       # a walker bumping a standing car: the driver hit nobody
            if ped is not None and moving and peds[ped].mode != "down":
                peds[ped].mode, peds[ped].speed = "down", 0.0
                self._count(moving[0], "pedestrian_hits", "pedestrian_hit", other=ped)
            elif ped is None and cars:
                other = [ident for _, ident in pair]
                for car_id in cars:
                    self.cars[car_id].speed = 0.0
                    rival = other[1] if other[0] == car_id else other[0]
                    self._count(car_id, "vehicle_collisions", "vehicle_collision", other=rival)
                for t in self.traffic:
                    if t.id in other:
                        t.speed = 0.0

    def _keep_in_city(self, car: AgentCar) -> None:
        """Stop a car that drives more than CITY_EDGE [m] past the outer streets at that
        distance, with a `city_edge` event once per stay: off the map, the view lost it and
        its percepts placed it on a street 100 m away. It may turn there and
        drive back into the city."""
        width, height = self.city.size
        x, y = car.body.position
        kept = (min(max(x, -CITY_EDGE), width + CITY_EDGE),
                min(max(y, -CITY_EDGE), height + CITY_EDGE))
        was, car.at_edge = car.at_edge, kept != (x, y)
        if not car.at_edge:
            return
        car.body.position, car.body.velocity, car.speed = kept, (0.0, 0.0), 0.0
        self.space.reindex_shapes_for_body(car.body)
        if not was:
            self._incoming.append({"kind": "city_edge", "agent": car.id, "cycle": self.cycle,
                                   "x": float(kept[0]), "y": float(kept[1])})

    def _count(self, agent: str, counter: str, kind: str, **extra: Any) -> None:
        car = self.cars[agent]
        car.counters[counter] += 1
        pos = car.body.position
        self._incoming.append({"kind": kind, "agent": agent, "cycle": self.cycle,
                             "x": float(pos.x), "y": float(pos.y), **extra})

    def _check_laws(self, car: AgentCar) -> None:
        x, y = car.body.position
        heading = math.degrees(car.body.angle)
        kinds = road_events(self.city, car.law, x, y, heading, car.speed)
        names = {"off_road": "off_road", "yellow_crossing": "yellow_crossings"}
        for kind in kinds:
            if kind in names:
                self._count(car.id, names[kind], kind)
            else:
                self._incoming.append({"kind": kind, "agent": car.id, "cycle": self.cycle,
                                     "x": float(x), "y": float(y)})
        if car.law.speeding:
            car.counters["speeding_cycles"] += 1
        for pid, pkg in self.packages.items():
            if pkg.owner == car.id and not pkg.delivered and delivers(
                    self.city.building(pkg.street, pkg.address), x, y, heading, car.speed):
                self.packages[pid] = PackageState(pkg.id, pkg.address, pkg.street, pkg.owner,
                                                  True)
                self._count(car.id, "deliveries", "delivery", package=pid)

    def snapshot(self) -> WorldSnapshot:
        """The frozen observable state of the current cycle (events: those of the last step)."""
        cars = [CarState(c.id, "agent", float(c.body.position.x), float(c.body.position.y),
                         deg(c.body.angle), c.speed, c.controls.wheel, c.controls.throttle,
                         c.controls.brake) for c in self.cars.values()]
        cars += [CarState(t.id, "traffic", t.x, t.y, t.heading, t.speed) for t in self.traffic]
        peds = tuple(PedState(p.id, p.x, p.y, p.heading, p.speed, p.mode) for p in self.walkers)
        snap = WorldSnapshot(self.cycle, round(self.cycle * self.config.dt, 9), self.config,
                             tuple(cars), peds, tuple(self.packages.values()),
                             {a: dict(c.counters) for a, c in self.cars.items()},
                             tuple(self._events), tuple(sorted(self.blocked)))
        return snap

    # -- restart (world/domain.py, Restartable) -------------------------------------------------
    def checkpoint(self) -> bytes:
        """The whole simulation as a pickle: the pymunk space (bodies, shapes and its cached
        contacts, so a contact under way is not counted twice), the random generator, the
        traffic, walkers, packages and counters."""
        return pickle.dumps(self, protocol=pickle.HIGHEST_PROTOCOL)


def restore(blob: bytes) -> Simulation:
    """The Simulation saved by `Simulation.checkpoint` (raises WorldError if it is not one)."""
    try:
        sim = pickle.loads(blob)
    except (pickle.UnpicklingError, EOFError, AttributeError, ImportError, TypeError) as exc:
        raise WorldError(f"restore: not a driving checkpoint: {exc}") from exc
    if not isinstance(sim, Simulation):
        raise WorldError(f"restore: expected a driving Simulation, got {type(sim).__name__}")
    return sim

