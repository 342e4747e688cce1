"""`teleo goal post ... --wait`: follow a posted goal to its end, as `ros2 action send_goal
--feedback` does, through the bus messages that exist: the executive's intention of each
cycle (the goal's status, its skill path, the problem solver's goal stack, the planner's
step) and the goal-entry process's goal list (a goal that leaves it was withdrawn: the
goal-entry process is then asked why, failed or cancelled).

One line at each change of the goal's status, and of what it does (at most one a second for
the same status: a driving path switches between skills every few cycles), then the end. A
goal that goes back to a line said within the last REPEAT_CYCLES cycles is thrashing (two
goals taking turns): that is said once, then a line every REPEAT_S with the number of
changes, until something new happens, not a line at every turn:

    exit 0    achieved
    exit 1    failed (the reason said)
    exit 3    ended without a verdict: cancelled by another request, or the run ended
    exit 124  --timeout S passed (the goal stays posted); 124 is what timeout(1) exits
              with, which scripts already test for (2 is click's usage error)
    exit 130  interrupted (128 + SIGINT): on a terminal it asks first whether to cancel
              the goal; --cancel-on-interrupt cancels without asking; without a terminal
              the goal stays posted (SIGTERM: 143, never asks)
"""

from __future__ import annotations

import os
import signal
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import click

from bus import keys
from bus.messages import GoalList, Intention
from tools.records.goal_reports import USER_STATUS
from tools.runs import runfile

EXIT_FAILED, EXIT_ENDED, EXIT_TIMEOUT = 1, 3, 124
ALIVE_S = 0.5  # [s] between looks at the launcher (has the run ended?)
FEEDBACK_S = 1.0  # [s] between lines for the same status (a path switching every cycle)
REPEAT_CYCLES = 20  # a line said again within this many cycles is a repeat (thrashing)
REPEAT_S = 30.0   # [s] between lines while the goal thrashes


class WaitEnded(click.ClickException):
    """The wait ended without the goal achieved; `exit_code` says how (module doc)."""

    def __init__(self, message: str, code: int) -> None:
        super().__init__(message)
        self.exit_code = code


def subscribe(node: Any, run: str, agent: str) -> Any:
    """The inbox of `agent`'s intentions and goal lists (declared before the post, so that
    no change after it is missed)."""
    inbox = node.subscribe(keys.intention(run, agent))
    node.subscribe(keys.goal_list(run, agent), inbox)
    return inbox


def doing(decision: dict[str, Any], goal_id: str) -> tuple[str, str]:
    """(what changes, how it reads) of what the agent does for `goal_id` in a decision: the
    skill path when the goal acts (`a#1 > b#2 (file:line:col) => (*gas 30)`), else the
    problem solver's goal stack, else the planner's step, else the goal's note."""
    paths = [{"goal_id": decision.get("goal_id"), "path": decision.get("path") or [],
              "actions": _main_actions(decision)}, *(decision.get("parallel") or [])]
    for p in paths:
        if p.get("goal_id") == goal_id and p.get("path"):
            skills = [str(s.get("skill", "?")) for s in p["path"]]
            acts = " ".join("(" + " ".join(map(_value, a)) + ")"
                            for a in p.get("actions") or [])
            return (" > ".join(skills),
                    f"{' > '.join(skills)} ({_where(p['path'][-1].get('where', ''))})"
                    + (f" => {acts}" if acts else ""))
    for stack in (decision.get("solver") or {}).get("stacks") or []:
        if stack.get("goal_id") == goal_id and stack.get("entries"):
            top = stack["entries"][-1]
            text = f"problem solving: {top.get('goal')} <- {top.get('why')} " \
                   f"(depth {len(stack['entries'])})"
            return text, text
    planner = decision.get("planner") or {}
    executing = planner.get("executing") or {}
    if goal_id in (executing.get("tasks") or []):
        text = f"planner: executing {executing.get('step')}"
        return text, text
    for tail in planner.get("tails") or []:
        if tail.get("id") == goal_id:
            plan = " ".join(tail.get("plan") or []) or "(to be planned)"
            text = f"planner: tail-plan {plan}" + (f" -- {tail['note']}" if tail.get("note")
                                                   else "")
            return text, text
    note = next((str(g.get("note", "")) for g in decision.get("goals") or []
                 if g.get("id") == goal_id), "")
    return note, note


def _value(value: Any) -> str:
    """An action's argument as the summaries write numbers: at most 3 decimals."""
    return f"{round(value, 3):g}" if isinstance(value, float) else str(value)


def _where(where: str) -> str:
    """A skill's file:line:col, the file relative to here when it is below here."""
    path, sep, pos = str(where).partition(":")
    rel = os.path.relpath(path) if os.path.isabs(path) else path
    return f"{rel if not rel.startswith('..') else path}{sep}{pos}"


def _main_actions(decision: dict[str, Any]) -> list:
    """The main path's actions: the decision's actions are the paths' in order, main first."""
    actions = list(decision.get("actions") or [])
    others = sum(len(p.get("actions") or []) for p in decision.get("parallel") or [])
    return actions[:len(actions) - others]


def status_line(cycle: int, status: str, text: str = "") -> str:
    """One line of the follow: `cycle     39  failed`, what the goal does after it."""
    return f"cycle {cycle:>6}  {status:<9}  {text}".rstrip()


@dataclass
class Follower:
    """What is known of one goal (pure; fed with the messages): its last status and doing,
    its cycle, and how it ended (`ended`: "achieved", "failed", "withdrawn" or "")."""

    goal_id: str
    posted_cycle: int
    status: str = "posted"
    cycle: int = -1
    reason: str = ""
    ended: str = ""
    _last: tuple[str, str] | None = field(default=None, repr=False)
    _said_at: float = field(default=-FEEDBACK_S, repr=False)
    _seen: dict[tuple[str, str], int] = field(default_factory=dict, repr=False)  # -> cycle
    _repeats: int = field(default=0, repr=False)   # changes back to a recent line, in a row
    _repeat_from: int = field(default=0, repr=False)

    def intention(self, cycle: int, decision: dict[str, Any], now: float) -> str | None:
        """The line to print for this cycle's decision (`now`: monotonic [s]): at each status
        change, and when what it does changed, at most every FEEDBACK_S."""
        report = next((g for g in decision.get("goals") or [] if g.get("id") == self.goal_id),
                      None)
        if report is None or self.ended:
            return None
        status = USER_STATUS.get(str(report.get("status")), str(report.get("status")))
        key, text = doing(decision, self.goal_id)
        self.status, self.cycle = status, cycle
        if status in ("achieved", "failed"):  # the reason is said once, at the end
            self.ended, self.reason = status, str(report.get("note", ""))
            key = text = ""
        pair, line = (status, key), status_line(cycle, status, text)
        recent, self._seen[pair] = self._seen.get(pair), cycle
        if pair == self._last:
            return None
        if self._last is not None and status == self._last[0] and \
                now - self._said_at < FEEDBACK_S:
            return None
        if recent is not None and cycle - recent <= REPEAT_CYCLES and not self.ended:
            self._last, self._repeats = pair, self._repeats + 1
            if self._repeats == 1:
                self._said_at, self._repeat_from = now, cycle
                return (f"{line}  [back to a line of the last {REPEAT_CYCLES} cycles: such "
                        f"repeats are not printed, a count every {REPEAT_S:g} s]")
            if now - self._said_at >= REPEAT_S:
                self._said_at = now
                return f"{line}  [{self._repeats} changes since cycle {self._repeat_from}]"
            return None
        self._last, self._said_at, self._repeats = pair, now, 0
        return line

    def goal_list(self, cycle: int, goals: tuple[dict[str, Any], ...]) -> bool:
        """Whether the goal left the goal list with this cycle's (it was withdrawn)."""
        if self.ended or cycle < self.posted_cycle:
            return False
        if any(g.get("id") == self.goal_id for g in goals):
            return False
        self.ended, self.cycle = "withdrawn", cycle
        return True


class _Signals:
    """SIGINT and SIGTERM noted (not raised) while following; `restore` puts back Python's
    own SIGINT (a second Ctrl-C, while asked, interrupts at once)."""

    def __init__(self) -> None:
        self.got = threading.Event()
        self.signum = 0
        self._old = {s: signal.signal(s, self._note) for s in (signal.SIGINT, signal.SIGTERM)}

    def _note(self, signum: int, _frame: object) -> None:
        self.signum = signum
        self.got.set()

    def restore(self) -> None:
        for sig, old in self._old.items():
            signal.signal(sig, old)


def follow(info: runfile.RunInfo, agent: str, posted: dict[str, Any], inbox: Any,
           ask: Callable, timeout: float | None, cancel_on_interrupt: bool) -> None:
    """Follow goal `posted` (the post's reply record) of `agent` until it ends (module doc);
    returns when achieved, else raises WaitEnded or click's Exit(130/143)."""
    gid = posted["id"]
    follower = Follower(gid, int(posted.get("posted_cycle", 0)))
    signals = _Signals()
    try:
        _pump(info, agent, follower, inbox, ask, timeout, signals)
    finally:
        signals.restore()
    if not follower.ended:
        _interrupted(follower, agent, ask, signals.signum, cancel_on_interrupt)
    if follower.ended == "withdrawn":
        _withdrawn(follower, agent, ask)
    if follower.ended == "achieved":
        click.echo(f"{gid} achieved at cycle {follower.cycle}")
        return
    raise WaitEnded(f"{gid} failed at cycle {follower.cycle}: {follower.reason}", EXIT_FAILED)


def _pump(info: runfile.RunInfo, agent: str, follower: Follower, inbox: Any, ask: Callable,
          timeout: float | None, signals: _Signals) -> None:
    """Read the messages until the goal ends or a signal comes; raises WaitEnded for a
    timeout and for a run that ended."""
    start = time.monotonic()
    look = start + ALIVE_S
    while not follower.ended and not signals.got.is_set():
        msg = inbox.get(timeout=0.1)
        if isinstance(msg, Intention) and msg.agent == agent:
            line = follower.intention(msg.env.cycle, msg.decision, time.monotonic())
            if line is not None:
                click.echo(line)
        elif isinstance(msg, GoalList) and msg.agent == agent:
            follower.goal_list(msg.env.cycle, msg.goals)
        now = time.monotonic()
        if timeout is not None and now - start >= timeout and not follower.ended:
            raise WaitEnded(f"{follower.goal_id} not done after {timeout:g} s (--timeout): "
                            f"{_last(follower)}; it stays posted", EXIT_TIMEOUT)
        if now >= look:
            look = now + ALIVE_S
            if not runfile.alive(info.pid) and inbox.pending() == 0:
                raise WaitEnded(f"run {info.run} ended before {follower.goal_id} was achieved "
                                f"({_last(follower)})", EXIT_ENDED)


def _last(follower: Follower) -> str:
    return "not reported yet" if follower.cycle < 0 else \
        f"{follower.status} at cycle {follower.cycle}"


def _withdrawn(follower: Follower, agent: str, ask: Callable) -> None:
    """A goal that left the goal list: failed (the follower says so, with the goal-entry
    process's reason), else a WaitEnded saying it was cancelled."""
    reply = ask("list", agent)
    record = next((g for g in reply.goals if g.get("id") == follower.goal_id), None)
    gid, cycle = follower.goal_id, follower.cycle
    if record is not None and record.get("status") == "failed":
        follower.ended, follower.reason = "failed", str(record.get("note", ""))
        follower.cycle = int(record.get("updated_cycle", cycle))
        # no decision reported it (the goal left the list first): the line it would have had
        click.echo(status_line(follower.cycle, "failed"))
        return
    if record is not None and record.get("status") == "cancelled":
        raise WaitEnded(f"{gid} was cancelled at cycle {record.get('updated_cycle', cycle)} "
                        "by another request (teleo goal cancel, or the scenario's)",
                        EXIT_ENDED)
    raise WaitEnded(f"{gid} left the goal list of {agent} at cycle {cycle}", EXIT_ENDED)


def _interrupted(follower: Follower, agent: str, ask: Callable, signum: int,
                 cancel_on_interrupt: bool) -> None:
    """Ctrl-C (or SIGTERM): cancel the goal if told to or, on a terminal, if the user says
    so; then exit 130 (143 for SIGTERM)."""
    gid = follower.goal_id
    code = 128 + signum
    cancel = cancel_on_interrupt
    if not cancel and signum == signal.SIGINT and sys.stdin.isatty():
        click.echo("", err=True)
        cancel = click.confirm(f"cancel {gid}?", default=False, err=True)
    if cancel:
        reply = ask("cancel", agent, goal_id=gid)
        said = reply.reason if reply.ok else f"not cancelled: {reply.reason}"
        click.echo(f"interrupted: {said}", err=True)
    else:
        click.echo(f"interrupted: {gid} stays posted ({_last(follower)}); `teleo goal cancel "
                   f"{gid}` cancels it", err=True)
    raise click.exceptions.Exit(code)
