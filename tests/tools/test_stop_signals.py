"""The launcher's three signal phases (tools/launching/stop_signals.py), with real signals sent to
this process: while the command starts a stop signal is kept, not lost and not raised inside an
import; while the run starts or runs it raises KeyboardInterrupt (one kept earlier at once);
while the run stops it only calls the hook, so a second Ctrl-C never breaks off the stop."""

from __future__ import annotations

import os
import signal

import pytest

from tools.launching import stop_signals


@pytest.fixture(autouse=True)
def handlers():
    """Each test's handlers and kept signals are undone after it."""
    saved = {sig: signal.getsignal(sig) for sig in stop_signals.STOP_SIGNALS}
    yield
    for sig, handler in saved.items():
        signal.signal(sig, handler)
    stop_signals._noted.clear()


def test_the_command_is_the_first_argument_that_is_not_an_option() -> None:
    assert stop_signals.command_of(["-v", "launch", "x.toml", "--cycles", "5"]) == "launch"
    assert stop_signals.command_of(["--version"]) == ""
    assert stop_signals.command_of(["goal", "post", "launch"]) == "goal"


@pytest.mark.parametrize("sig", stop_signals.STOP_SIGNALS, ids=lambda s: s.name)
def test_a_signal_while_a_launch_starts_is_kept_then_raised_when_it_can_stop(sig) -> None:
    assert stop_signals.early(["-v", "launch", "scenario.toml"])
    os.kill(os.getpid(), sig)     # delivered here, between two bytecodes: nothing raised
    assert stop_signals.noted() == (sig,)
    with pytest.raises(KeyboardInterrupt):
        stop_signals.running()


def test_other_commands_keep_the_signals_as_they_were_given() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)   # a background job of a script
    assert not stop_signals.early(["goal", "list"])
    assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    assert signal.getsignal(signal.SIGTERM) is not stop_signals._note


def test_a_running_launch_raises_on_a_signal_even_one_its_shell_ignored() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    stop_signals.running()
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)


def test_a_signal_while_the_run_stops_only_calls_the_hook() -> None:
    calls: list[str] = []
    stop_signals.stopping(lambda: calls.append("cut short"))
    for sig in (signal.SIGINT, signal.SIGTERM):
        os.kill(os.getpid(), sig)
    assert calls == ["cut short", "cut short"]
