"""The robot's high-level operations (seed 003, sections 4-5): the commands an agent sends and
what each does until it ends.

    (*goto ROOM)            navigate into ROOM                        (until arrival)
    (*acquire ITEM FROM)    take ITEM from person or room FROM        (handover time)
    (*deliver ITEM TO)      give ITEM to person TO, or leave it in room TO   (handover time)
    (*observe ROOM)         look into ROOM: occupied or empty          (observe time)
    (*say WORD ...)         announce the words, joined by spaces      (at once)
    (*stop)                 stop and cancel the running operation     (at once)

goto, acquire, deliver and observe use the robot's body: one runs at a time. Sending the
command that is running again continues it (a teleoreactive program sends it every cycle);
another body command pre-empts it. Each operation reports ONE outcome, when it ends:
`done`, or `failed` with the reason "AGENT: (*cmd args): CODE: detail". An operation that ends
while a command is applied is reported in that call's outcomes; one that ends during a step
in the outcomes of the next apply_actions call (world/office/percepts.md, "Outcomes").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Protocol

from world.office import ACTIONS
from world.office.robot import Operation, Robot, Site, start_goto

BODY = {"*goto": ("goto", 1), "*acquire": ("acquire", 2), "*deliver": ("deliver", 2),
        "*observe": ("observe", 1)}
KNOWN = ACTIONS  # the office Domain says the same (world/office/__init__.py)


@dataclass
class Person:
    id: str
    room: str
    office: str
    away_until: float = -1.0    # [s] a wandering person returns to the office then


@dataclass
class Item:
    id: str
    kind: str
    holder: str
    to: str = ""
    temperature: float = 0.0    # [C] coffee only


class Office(Site, Protocol):
    people: dict[str, Person]
    items: dict[str, Item]
    occupants: dict[str, int]


def outcome(action: list[Any], agent: str, code: str = "", detail: str = "") -> dict[str, Any]:
    """The neutral outcome form (docs/architecture.md): reason "" when done."""
    if not code:
        return {"action": list(action), "status": "done", "reason": ""}
    text = " ".join(_word(a) for a in action)
    return {"action": list(action), "status": "failed",
            "reason": f"{agent}: ({text}): {code}: {detail}"}


def _word(value: Any) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


def _malformed(action: Any) -> str:
    if not isinstance(action, list | tuple) or not action or not isinstance(action[0], str):
        return f"malformed action {action!r:.80}: expected [name, args...]"
    name, args = action[0], action[1:]
    if name not in KNOWN:
        return f"unknown action {name!r}; known: {' '.join(KNOWN)}"
    if any(isinstance(a, bool) or not isinstance(a, str | int | float) for a in args):
        return f"({name} ...): arguments must be symbols or numbers, got {list(args)!r:.80}"
    if name in BODY and len(args) != BODY[name][1]:
        return f"({name}) takes {BODY[name][1]} argument(s), got {len(args)}"
    if name == "*say" and not args:
        return "(*say) takes the words to say, got none"
    if name == "*stop" and args:
        return f"(*stop) takes no arguments, got {len(args)}"
    if name in BODY and not all(isinstance(a, str) for a in args):
        return f"({name}) takes ids (symbols), got {list(args)!r:.80}"
    return ""


def apply_command(site: Office, robot: Robot, action: Any) -> dict[str, Any] | None:
    """Apply one command; its outcome when it ended at once, None while it runs on.
    Operations that this command ends (pre-empted, stopped) go to robot.finished."""
    problem = _malformed(action)
    if problem:
        shown = list(action) if isinstance(action, list | tuple) else [repr(action)]
        return {"action": shown, "status": "failed", "reason": f"{robot.id}: {problem}"}
    action = list(action)
    name = action[0]
    if name == "*say":
        text = " ".join(_word(a) for a in action[1:])
        robot.counters["utterances"] += 1
        site.emit("say", robot.id, text=text)
        return outcome(action, robot.id)
    if name == "*stop":
        if robot.running():
            robot.halt()
            site.finish(robot, "stopped", "cancelled by (*stop)")
        return outcome(action, robot.id)
    op_name = BODY[name][0]
    if robot.running() and robot.op.name == op_name and robot.op.args == tuple(action[1:]):
        return None
    if robot.running():
        robot.halt()
        site.finish(robot, "pre-empted", f"by ({' '.join(_word(a) for a in action)})")
    robot.op = Operation(op_name, tuple(action[1:]), action, site.cycle)
    problem = _check(site, robot, robot.op)
    if problem:
        site.finish(robot, *problem)
    elif op_name == "goto":
        start_goto(site, robot)
    else:
        wait = site.config.observe_time if op_name == "observe" else site.config.handover
        robot.op.until = site.time + wait
    return None


def _where(site: Office, robot: Robot) -> str:
    return site.floor.locate(*robot.position)


def _meet(site: Office, robot: Robot, who: str) -> tuple[str, str] | None:
    """Is person or room `who` where the robot is? (code, detail) when not."""
    here = _where(site, robot)
    if who in site.people:
        if site.people[who].room == here:
            return None
        if site.floor.has_room(here):
            return "person-absent", f"{who} is not in {here}"
        return "not-in-room", f"{robot.id} is in {here}, not in a room with {who}"
    if not site.floor.has_room(who):
        return "unknown", f"{who!r} is neither a person nor a room"
    return None if here == who else ("not-in-room", f"{robot.id} is in {here}, not in {who}")


def _refill(site: Office, robot: Robot, item: Item, source: str) -> bool:
    """Taking a carried coffee to a kitchen refills it (the machine brews a fresh cup)."""
    return item.holder == robot.id and item.kind == "coffee" and \
        site.floor.has_room(source) and site.floor.room(source).kind == "kitchen"


def _check(site: Office, robot: Robot, op: Operation) -> tuple[str, str] | None:
    """Whether the operation can run now (at its start and every cycle until it ends)."""
    if op.name in ("goto", "observe") and not site.floor.has_room(op.args[0]):
        rooms = " ".join(r.id for r in site.floor.rooms)
        return "unknown-room", f"no room {op.args[0]!r}; rooms: {rooms}"
    if op.name == "goto":
        return None
    if op.name == "observe":
        return _can_observe(site, robot, op.args[0])
    item_id, other = op.args
    item = site.items.get(item_id)
    if item is None:
        return "unknown-item", f"no item {item_id!r}; items: {' '.join(sorted(site.items))}"
    if op.name == "deliver" and item.holder != robot.id:
        return "item-not-held", f"{robot.id} does not carry {item_id}"
    met = _meet(site, robot, other)
    if met or op.name == "deliver":
        return met
    if _refill(site, robot, item, other):
        return None
    if item.holder == robot.id:
        return "already-held", f"{robot.id} already carries {item_id}"
    if item.holder != other:
        return "item-not-held", f"{other} does not have {item_id}"
    if len(robot.carrying) >= site.config.capacity:
        return "full", f"{robot.id} carries {len(robot.carrying)} items (capacity " \
                       f"{site.config.capacity})"
    return None


def _can_observe(site: Office, robot: Robot, room_id: str) -> tuple[str, str] | None:
    here, room = _where(site, robot), site.floor.room(room_id)
    door = site.floor.door(room.door)
    if here == room_id:
        return None
    if here == room.corridor and site.doors[door.id] == "open" and \
            math.dist(robot.position, (door.x, door.y)) <= site.config.sight:
        return None
    return "not-at-room", f"{robot.id} is in {here}: neither in {room_id} nor at its open door"


def occupied(site: Office, room_id: str) -> bool:
    return site.occupants.get(room_id, 0) > 0 or \
        any(p.room == room_id for p in site.people.values())


def step_operation(site: Office, robot: Robot) -> None:
    """After a step: end a timed operation whose time is up, or that can no longer run."""
    op = robot.op
    if not robot.running() or op.name == "goto":
        return
    problem = _check(site, robot, op)
    if problem:
        code, detail = problem
        site.finish(robot, "person-left" if code == "person-absent" else code, detail)
        return
    if site.time + 1e-9 < op.until:
        return
    if op.name == "observe":
        result = "occupied" if occupied(site, op.args[0]) else "empty"
        robot.observations[op.args[0]] = (result, site.cycle)
        robot.counters["observations"] += 1
        site.emit("observed", robot.id, room=op.args[0], result=result)
        site.finish(robot)
        return
    item = site.items[op.args[0]]
    if op.name == "acquire":
        if _refill(site, robot, item, op.args[1]):
            item.temperature = site.config.coffee_brew
        else:
            item.holder = robot.id
            robot.carrying.append(item.id)
        robot.counters["acquisitions"] += 1
        site.emit("acquired", robot.id, item=item.id, source=op.args[1])
        site.finish(robot)
        return
    to = op.args[1]
    if item.kind == "coffee" and to in site.people and \
            item.temperature < site.config.coffee_cold:
        site.finish(robot, "coffee-cold", f"{to} refuses {item.id} at {item.temperature:.1f} C "
                    f"(cold below {site.config.coffee_cold:g} C)")
        return
    item.holder = to
    robot.carrying.remove(item.id)
    robot.counters["deliveries"] += 1
    site.emit("delivered", robot.id, item=item.id, to=to, room=_where(site, robot),
              addressee=item.to)
    site.finish(robot)
