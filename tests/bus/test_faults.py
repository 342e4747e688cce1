"""Fault paths of the cycle with real processes: a stage SIGKILLed (liveliness notices it
within milliseconds), a stage SIGSTOPped (only the per-cycle deadline notices it)."""

from __future__ import annotations

import os
import signal
import threading

import pytest
from bus_helpers import AGENT, PIPELINE, Stages, pipeline

from bus.clock import Clock, CycleInterrupted
from bus.cycle import CycleMode, DeadPolicy
from bus.errors import ClockStopped
from bus.messages import WorldState
from bus.node import open_node


def state(node, t: int) -> WorldState:
    return WorldState(node.envelope(t), {"cycle": t}, {}, [])


def test_killed_stage_restarts_and_rejoins_at_the_current_cycle(cfg, run_id, stages: Stages):
    """inference SIGKILLs itself when cycle 4 arrives; a supervisor thread restarts it; the
    clock re-sends state 4 and every stage still computes every cycle exactly once."""
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, {AGENT: PIPELINE}, deadline_s=30.0, restart_timeout_s=30.0)
        stages.start_agent(inference=("--die-at", "4"))
        first = stages.procs["A.inference"]

        def supervise() -> None:
            first.wait(60)
            stages.start("inference")

        supervisor = threading.Thread(target=supervise, daemon=True)
        supervisor.start()
        clock.wait_ready(set(PIPELINE), timeout=30)
        reports = [clock.run_cycle(t, state(node, t)) for t in range(8)]
        supervisor.join(60)
    assert first.returncode == -signal.SIGKILL
    assert reports[4].republished >= 1
    assert reports[4].actions[AGENT] == (["*pass", 4, 1],)
    assert all(r.dead == () and r.noop == () for r in reports)
    for process in PIPELINE:
        assert stages.cycles(process) == list(range(8)), process


def test_dead_stage_is_reported_and_the_other_agent_goes_on(cfg, run_id, stages: Stages):
    """Policy CONTINUE: B's inference is killed and not restarted; B gets the no-op (at
    once in later cycles), A keeps acting."""
    pipes = {"A": pipeline("A"), "B": pipeline("B")}
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, pipes, deadline_s=30.0, restart_timeout_s=1.0,
                      policy=DeadPolicy.CONTINUE)
        stages.start_agent("A")
        stages.start_agent("B")
        clock.wait_ready(set(pipes["A"] + pipes["B"]), timeout=30)
        assert clock.run_cycle(0, state(node, 0)).clean
        stages.procs["B.inference"].kill()
        stages.procs["B.inference"].wait(10)
        dead = clock.run_cycle(1, state(node, 1))
        again = clock.run_cycle(2, state(node, 2))
    assert dead.dead == ("B.inference",) and dead.noop == ("B",)
    assert dead.actions == {"A": (["*pass", 1, 1],), "B": ()}
    assert dead.elapsed_ms < 10_000  # reported within a bound, not waited on forever
    assert again.dead == ("B.inference",) and again.actions == {"A": (["*pass", 2, 1],), "B": ()}
    assert stages.cycles("A.executive") == [0, 1, 2]


def test_dead_stage_stops_the_clock_under_policy_stop(cfg, run_id, stages: Stages):
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, {AGENT: PIPELINE}, deadline_s=30.0, restart_timeout_s=1.0,
                      policy=DeadPolicy.STOP)
        stages.start_agent()
        clock.wait_ready(set(PIPELINE), timeout=30)
        assert clock.run_cycle(0, state(node, 0)).clean
        stages.procs["A.inference"].kill()
        stages.procs["A.inference"].wait(10)
        with pytest.raises(ClockStopped, match="A.inference") as err:
            clock.run_cycle(1, state(node, 1))
    assert err.value.dead == ("A.inference",) and err.value.cycle == 1


def test_stopped_stage_is_named_by_the_deadline(cfg, run_id, stages: Stages):
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, {AGENT: PIPELINE}, deadline_s=30.0, restart_timeout_s=30.0)
        stages.start_agent()
        clock.wait_ready(set(PIPELINE), timeout=30)
        assert clock.run_cycle(0, state(node, 0)).clean
        pid = stages.procs["A.inference"].pid
        os.kill(pid, signal.SIGSTOP)
        try:
            clock.deadline_s = 1.0  # well under the 2 s liveliness lease
            stuck = clock.run_cycle(1, state(node, 1))
        finally:
            os.kill(pid, signal.SIGCONT)
        clock.deadline_s = 30.0
        after = [clock.run_cycle(t, state(node, t)) for t in (2, 3)]
    assert stuck.late == ("A.inference",)
    assert stuck.dead == () and stuck.actions == {AGENT: ()}
    assert [r.actions[AGENT] for r in after] == [(["*pass", 2, 1],), (["*pass", 3, 1],)]
    assert stages.procs["A.inference"].poll() is None  # the stage survived being stopped


def test_realtime_defaults_a_stopped_agent_to_the_noop_and_names_the_stage(cfg, run_id, stages):
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, {AGENT: PIPELINE}, mode=CycleMode.REALTIME, period_s=0.6)
        stages.start_agent()
        clock.wait_ready(set(PIPELINE), timeout=30)
        first = clock.run_cycle(0, state(node, 0))
        pid = stages.procs["A.inference"].pid
        os.kill(pid, signal.SIGSTOP)
        try:
            stuck = clock.run_cycle(1, state(node, 1))
        finally:
            os.kill(pid, signal.SIGCONT)
        later = [clock.run_cycle(t, state(node, t)) for t in range(2, 4)]
    assert first.clean and first.actions == {AGENT: (["*pass", 0, 1],)}
    assert stuck.late == ("A.inference",) and stuck.actions == {AGENT: ()}
    assert any(r.clean for r in later)  # it catches up once resumed


def test_realtime_waits_at_its_first_cycle_for_a_stage_not_yet_answering(cfg, run_id, stages):
    """Trial 2026-12-04 N3: the tutorial's realtime run lost cycle 0 to a start-up race (the
    executive's token was up, its inputs not yet reaching it). The first cycle after start-up
    waits for every stage, sending its state again; later cycles keep the deadline."""
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, {AGENT: PIPELINE}, mode=CycleMode.REALTIME, period_s=0.3,
                      deadline_s=30.0)
        stages.start_agent()
        clock.wait_ready(set(PIPELINE), timeout=30)
        pid = stages.procs["A.executive"].pid
        os.kill(pid, signal.SIGSTOP)             # up, but not answering when the clock starts
        waker = threading.Timer(1.5, os.kill, (pid, signal.SIGCONT))
        waker.start()
        try:
            first = clock.run_cycle(0, state(node, 0))
        finally:
            waker.join()
            os.kill(pid, signal.SIGCONT)
        os.kill(pid, signal.SIGSTOP)
        try:
            later = clock.run_cycle(1, state(node, 1))
        finally:
            os.kill(pid, signal.SIGCONT)
    assert first.noop == () and first.actions == {AGENT: (["*pass", 0, 1],)}
    assert later.late == ("A.executive",) and later.actions == {AGENT: ()}


def test_a_stall_is_named_and_any_wait_is_interrupted_by_the_stop_event(cfg, run_id, stages):
    """SIGSTOP inference: a cycle that waits past stall_s names it; setting the stop event
    (a signal to the world) ends the wait at once with CycleInterrupted (drill F6)."""
    stop = threading.Event()
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, {AGENT: PIPELINE}, deadline_s=30.0, restart_timeout_s=30.0,
                      stall_s=0.3, stop=stop)
        stages.start_agent()
        clock.wait_ready(set(PIPELINE), timeout=30)
        assert clock.run_cycle(0, state(node, 0)).stalled == ()
        pid = stages.procs["A.inference"].pid
        os.kill(pid, signal.SIGSTOP)
        try:
            timer = threading.Timer(0.8, os.kill, (pid, signal.SIGCONT))
            timer.start()
            stalled = clock.run_cycle(1, state(node, 1))
            timer.join()
            os.kill(pid, signal.SIGSTOP)
            threading.Timer(0.5, stop.set).start()
            with pytest.raises(CycleInterrupted, match="cycle 2: interrupted while waiting "
                                                       "for A") as err:
                clock.run_cycle(2, state(node, 2))
        finally:
            os.kill(pid, signal.SIGCONT)
    assert stalled.stalled == ("A.inference",) and stalled.actions == {AGENT: (["*pass", 1, 1],)}
    assert err.value.cycle == 2
    assert err.value.stalled == ("A.inference",) and err.value.waited_s >= 0.3  # d2b
