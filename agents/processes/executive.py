"""The executive process of one agent: percepts, beliefs and goal list of t in; actions and
intention of t out.

    python -m agents.processes.executive --run RUN --agent ME --program FILE
        [--state FILE] [--learned FILE] [--learned-out FILE] [--no-solver]
        [--mechanism NAME] [bus flags]

Each cycle it brings the engine's user goals in line with the goal list the goal-entry
process published for t (posted, cancelled, reprioritised goals), then takes one executive
step: the first unsatisfied goal of the prioritised list gets a skill path, the previous
path preferred (seed 000, Adding Goal Priorities). The intention is Decision.to_dict(): the
goal list with statuses, the skill path with bindings, the actions and why (and the problem
solver's goal stacks). The goals live in the goal-entry process; the engine state (paths, goal
stacks, learned skills, SCS threads) lives here and, with --state, in a file written after
every cycle that changed it and read back at start, so a restart loses none of it
(agents/processes/persist.py).
A program that comes with the percepts of a cycle (`teleo program load`) is swapped in before
that cycle's step, the state carried over (agents/processes/swapping.py).
The SCS state (body threads, discount factors, world model) also goes out with the actions as
the agent's memory and comes back through the world with the next percepts, which is how the
world model reaches the inference process (docs/bus.md, "Agent memory"). --learned starts
from skills learned in an earlier run; --learned-out writes the skills as they are learned;
--no-solver runs the executive alone (an impasse stays an impasse); --mechanism names
what answers an impasse (agents.lang.engine.SOLVERS: means-ends, the default; rogue, the
planner of seed 003, whose tail-plans, head-plan and monitoring live in the same state).
"""

from __future__ import annotations

import logging
from dataclasses import replace
from operator import is_
from pathlib import Path
from typing import Any

import click

from agents.lang import Belief, Engine, LangError, SharedRows
from agents.lang.core.outcomes import as_outcomes
from agents.lang.core.store import BeliefSet
from agents.lang.loader import read_text
from agents.lang.registry import memory_of, read_learned, remember
from agents.lang.swap import carry_state
from agents.processes.agent_setup import AgentSetup
from agents.processes.common import agent_options, run_stage, setup_logging
from agents.processes.goal_sync import GoalSync
from agents.processes.hints import with_hints
from agents.processes.per_object import PerObject
from agents.processes.persist import LearnedFile, Saved, StateFile, read_back_learned
from agents.processes.swapping import keep, kept, note, read_program, said
from bus import keys
from bus.config import BusConfig
from bus.errors import Refused
from bus.messages import Actions, Envelope, Intention, Message
from bus.schema import brief


class EngineHost:
    """The engine and engine state of one agent in its executive process, plus the user
    goals it was last given (the engine's own executive is agents/lang/execution)."""

    def __init__(self, engine: Any, log: logging.Logger, state: Any = None,
                 solver: str | None = "means-ends") -> None:
        self.engine, self.solver = engine, solver
        self.log = log
        self.state = engine.initial_state() if state is None else state
        self.goals = GoalSync.of(self.state)   # the user goals the state already holds
        self.beliefs = BeliefReader(engine.program.arity)

    def sync_goals(self, goal_list: tuple[dict[str, Any], ...]) -> None:
        """Add new goals, drop withdrawn ones, move reprioritised ones (in list order)."""
        self.state = self.goals.apply(self.engine, self.state, goal_list, self.log)

    def swap(self, entry: dict[str, Any]) -> dict[str, Any]:
        """Run the program of ``entry`` ({"name", "text"}) from now on, the engine state
        carried over (agents/lang/swap.py); returns the verdict (swapping.note). A goal the
        new program cannot pursue is not offered to it again."""
        program, why = read_program(entry)
        if program is None:
            return note(entry, why)
        new = Engine(program, solver=self.solver)
        carried = carry_state(self.engine, new, self.state)
        before = set(self.goals.user)
        self.engine, self.state = new, carried.state
        self.goals = GoalSync.of(self.state)   # one refused before is offered to the new one
        self.goals.refused = before - set(self.goals.user)
        self.beliefs = BeliefReader(new.program.arity)
        return note(entry, "", carried.dropped)

    def remember(self, memory: dict[str, Any]) -> None:
        """Take the SCS state from the memory the world handed back (a malformed one is
        logged and ignored: the executive goes on with its own)."""
        if not memory:
            return
        try:
            self.state = remember(self.state, memory, self.engine.program,
                                  self.engine.mechanisms)
        except LangError as exc:
            self.log.warning("agent memory dropped: %s", exc)

    def memory(self) -> dict[str, Any]:
        """What goes out with the actions, for the world to hand back next cycle."""
        return memory_of(self.state, self.engine.mechanisms)

    def decide(self, percepts: tuple, belief_lists: tuple, outcomes: tuple = ()) -> Any:
        """One executive step; returns the engine's Decision. A malformed outcome is logged
        and left out, never a crash (the world's outcomes are checked by the engine)."""
        beliefs = self.beliefs.read(belief_lists)
        good = []
        for o in outcomes:
            try:
                good += as_outcomes([o])
            except LangError as exc:
                self.log.warning("outcome dropped: %s", exc)
        decision, self.state = self.engine.decide(self.state, SharedRows(percepts), beliefs,
                                                  good)
        return decision


class BeliefReader:
    """Belief lists as the bus delivers them (a list seen last cycle is the same object,
    bus/rows.py) to a BeliefSet: a list seen before keeps its Belief, and the
    same lists as last cycle give last cycle's BeliefSet, its fact store built once. A belief
    of a concept of the program with the wrong number of arguments is refused (LangError
    naming it): the matcher indexes a fact's arguments by the concept's arity."""

    def __init__(self, arity: dict[str, int] | None = None) -> None:
        self.lists: tuple = ()
        self.arity = arity or {}
        self.beliefs = PerObject(self._belief)
        self.last: Any = None

    def _belief(self, items: list) -> Any:
        want = self.arity.get(items[0])
        if want is not None and want != len(items) - 1:
            raise LangError(f"belief {brief(items)}: {items[0]} takes {want} argument(s), "
                            f"got {len(items) - 1}")
        return Belief.from_list(items)

    def read(self, lists: tuple) -> Any:
        if self.last is None or len(lists) != len(self.lists) \
                or not all(map(is_, lists, self.lists)):
            self.lists, self.last = lists, BeliefSet(self.beliefs.of(lists))
        return self.last


def make_host(setup: AgentSetup, log: logging.Logger, state: Any = None) -> EngineHost:
    """The engine host of ``setup``'s agent: from ``state`` (read back after a restart) if
    given, else fresh, starting from the skills in its own learned file ``learned_out`` (the
    one it writes: after a restart whose state file could not be read, those skills are not
    lost) or else in the learned file ``learned``; the program swapped in and kept in
    ``swapped`` if any (agents/processes/swapping.py). Raises LangError (a ProgramError naming
    file:line:col) for a bad program or ``learned`` file."""
    program = kept(setup.swapped, setup.program, log)
    solver = setup.mechanism if setup.solver else None
    engine = Engine(program, solver=solver)
    if state is None:
        own = setup.learned_out
        skills = read_back_learned(program, Path(own), log) if own else None
        if skills is None and setup.learned:
            skills = read_learned(program, read_text(setup.learned), setup.learned)
        if skills is not None:
            state = engine.initial_state(learned=skills)
    return EngineHost(engine, log, state, solver)


def make_step(setup: AgentSetup, log: logging.Logger):
    """step(cycle, {percepts, beliefs, goal list}) -> [(intention, ...), (actions, ...)].
    Percepts or beliefs the engine cannot read are refused (bus Refused)."""
    run, agent, process = setup.run, setup.agent, setup.process("executive")
    state_path, learned_out = setup.state, setup.learned_out
    saver = StateFile(state_path, log) if state_path else None
    saved = saver.load() if saver else None
    host = make_host(setup, log, saved.state if saved else None)
    out = LearnedFile(learned_out, setup.program) if learned_out else None
    p_key, b_key, g_key = (keys.percepts(run, agent), keys.beliefs(run, agent),
                           keys.goal_list(run, agent))

    def outputs(cycle: int, intention: dict, actions: list, swap: dict | None = None
                ) -> list[tuple[str, Message]]:
        env = Envelope.now(run, cycle, process)
        return [(keys.intention(run, agent), Intention(env, agent, intention, swap or {})),
                (keys.actions(run, agent), Actions(env, agent, tuple(actions),
                                                   host.memory()))]

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        if saved is not None and cycle <= saved.cycle:
            log.info("cycle %d was decided before the restart: its outputs again", cycle)
            return outputs(cycle, saved.intention, saved.actions)
        seen = inputs[p_key]
        host.sync_goals(inputs[g_key].goals)
        host.state = replace(host.state, cycle=cycle)   # the bus's cycle, also
        host.remember(seen.memory)                           # after a restart
        swap = host.swap(seen.program) if seen.program else {}   # the old program's
        if swap:                                                      # memory read first
            said(process, cycle, swap, log)
            if swap["ok"]:
                keep(setup.swapped, seen.program, cycle, log)
        try:
            decision = host.decide(seen.percepts, inputs[b_key].beliefs, seen.outcomes)
        except LangError as exc:   # percepts or beliefs the engine cannot read
            raise Refused(f"{p_key}, {b_key}: the inputs of cycle {cycle}: {exc}") from None
        intention = with_hints(decision.to_dict(), seen.percepts, host.engine.program)
        actions = [a.to_list() for a in decision.actions]
        if saver is not None and saver.changed(host.state):
            saver.save(Saved(cycle, host.state, intention, actions))
        if out is not None:
            out.save(host.state.learned)
        return outputs(cycle, intention, actions, swap)

    return step


@click.option("--mechanism", default="means-ends", show_default=True,
              help="What answers an impasse: means-ends (seed 000) or rogue (seed 003).")
@click.option("--no-solver", "no_solver", is_flag=True,
              help="No means-ends problem solver: an impasse stays an impasse.")
@click.option("--learned-out", type=click.Path(dir_okay=False),
              help="Write the learned skills here (program syntax) whenever one is learned.")
@click.option("--learned", type=click.Path(exists=True, dir_okay=False),
              help="Start from the skills in this learned file (an earlier run's).")
@click.option("--swapped", type=click.Path(dir_okay=False),
              help="Keep a program swapped in here, and start from the one it holds.")
@click.option("--state", "state_path", type=click.Path(dir_okay=False),
              help="Engine state file: read back at start if it exists, written after every "
                   "cycle that changed the state (so a restart keeps paths, goal stacks and "
                   "learned skills).")
@agent_options(with_program=True)
def main(run: str, agent: str, program: str, bus_config: BusConfig, state_path: str | None,
         learned: str | None, learned_out: str | None, no_solver: bool,
         mechanism: str, swapped: str | None) -> None:
    """Prioritised executive of one agent."""
    setup = AgentSetup(run=run, agent=agent, program=program, state=state_path,
                       learned=learned, learned_out=learned_out, solver=not no_solver,
                       mechanism=mechanism, swapped=swapped)
    process = setup.process("executive")
    log = setup_logging(process)
    inputs = [keys.percepts(run, agent), keys.beliefs(run, agent), keys.goal_list(run, agent)]
    try:
        step = make_step(setup, log)
    except LangError as exc:
        raise click.ClickException(str(exc)) from exc
    run_stage(bus_config, run, process, inputs, [keys.actions(run, agent)], step, log)


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
