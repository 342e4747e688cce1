"""What a running launch lets change, and how (`teleo program load`, `teleo set`; docs/bus.md,
"Changing a running launch").

The world process checks each change asked for on its control key (bus/pause.py Gate) and,
at the start of the cycle it is due, puts it in that cycle's world state (WorldState.control)
and its trace line, so that every stage takes it at the same cycle, the record holds it, and
the same change at the same cycle gives the same run:

- a program for an agent ({"op": "load", "agent", "name", "text"}): the agent's perception
  forwards it with the percepts of the cycle, its inference and executive swap it in there
  (agents/processes/swapping.py) and say so with their beliefs and intention of that cycle;
- a field of the scenario (`teleo set KEY=VALUE`, {"op": "set", "text": "KEY=VALUE"}), one of
  RUNTIME_KEYS, checked as `launch --set` checks it: the scenario with the launch's overrides
  and this one, read and checked whole (world/run_scenario.py), its new value applied by the
  world. Any other key is refused with a sentence naming it: it is read when the run starts.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from world.errors import WorldError
from world.overrides import parse_override
from world.run_scenario import Scenario, load_scenario

RUNTIME_KEYS = {
    ("run", "deadline"): "the realtime period of a cycle [s]",
    ("run", "render_every"): "how often a snapshot is kept for rendering [cycles]",
}
"""(table, field) -> what it is: the scenario fields the world applies at a cycle boundary.
`agents.<id>.program` changes too, as `teleo program load` (tools/commands/program.py)."""
MAX_PROGRAM_CHARS = 1024 * 1024  # [characters] of a program sent (agents/lang MAX_TEXT_CHARS)


def fixed_key(key: str) -> str:
    """The sentence refusing a change of ``key`` while the run runs."""
    can = ", ".join(".".join(k) for k in RUNTIME_KEYS)
    return (f"{key} cannot change while the run runs (it is read when the run starts: "
            f"relaunch with --set {key}=...); what can: {can}, agents.<id>.program")


class Changes:
    """The world's side of the changes of one running launch (module doc)."""

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario

    def check(self, event: dict[str, Any]) -> str:
        """"" when ``event`` may be scheduled, else why not (one line). A set is given its
        "key" and checked "value" here (what the asker is answered with)."""
        if event.get("op") == "load":
            return self._check_load(event)
        text = event.get("text")
        if not isinstance(text, str):
            return f"expected \"text\": \"KEY=VALUE\", got {text!r:.80}"
        try:
            o = parse_override(text)
        except WorldError as exc:
            return str(exc)
        if o.key not in RUNTIME_KEYS:
            return fixed_key(".".join(o.key))
        try:
            scenario = load_scenario(self.scenario.path, (*self.scenario.overrides, text))
        except WorldError as exc:   # the scenario's errors with this set: named by it
            errors = [e.removeprefix(f"{self.scenario.path}: ") for e in str(exc).splitlines()]
            return f"{text.strip()}: {'; '.join(errors)}"
        event["key"], event["value"] = ".".join(o.key), getattr(scenario.run, o.key[1])
        return ""

    def _check_load(self, event: dict[str, Any]) -> str:
        agent, name, text = event.get("agent"), event.get("name"), event.get("text")
        if agent not in self.scenario.agent_ids:
            return (f"no agent {agent!r} in this run; agents: "
                    f"{', '.join(self.scenario.agent_ids)}")
        if not isinstance(name, str) or not isinstance(text, str):
            return "expected the program's \"name\" and \"text\" as strings"
        if len(text) > MAX_PROGRAM_CHARS:
            return f"program {name}: {len(text)} characters, more than {MAX_PROGRAM_CHARS}"
        return ""

    def control(self, due: list[dict[str, Any]]) -> dict[str, Any]:
        """The WorldState.control of a cycle from the changes due at its start ({} for none):
        a later program for the same agent wins; each set is applied to the scenario kept
        here (a later `set` is checked on top of it) and listed with its new value."""
        programs: dict[str, dict[str, str]] = {}
        sets: list[dict[str, Any]] = []
        for event in due:
            if event["op"] == "load":
                programs[event["agent"]] = {"name": event["name"], "text": event["text"]}
                continue
            field = event["key"].split(".")[1]
            self.scenario = replace(self.scenario,
                                    run=replace(self.scenario.run, **{field: event["value"]}),
                                    overrides=(*self.scenario.overrides, event["text"]))
            sets.append({"key": event["key"], "value": event["value"]})
        out: dict[str, Any] = {}
        if programs:
            out["programs"] = programs
        if sets:
            out["set"] = sets
        return out

    def at_cycle(self, due: list[dict[str, Any]], clock: Any, rec: Any, t: int
                 ) -> dict[str, Any]:
        """The control of cycle `t` (``control``), its sets applied to the world's `clock`
        (bus/clock.py) and `rec` (world/recorder.py), each change noted in the health record."""
        control = self.control(due)
        for agent, program in control.get("programs", {}).items():
            rec.event("program", cycle=t, agent=agent, name=program["name"])
        for change in control.get("set", ()):
            if change["key"] == "run.deadline":
                clock.period_s = float(change["value"])
            elif change["key"] == "run.render_every":
                rec.render_every = int(change["value"])
            rec.event("set", cycle=t, key=change["key"], value=change["value"])
        return control
