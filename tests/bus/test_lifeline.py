"""A launch's child never outlives its launcher (bus/lifeline.py; drill F4: a SIGKILLed
launcher left every process running with parent 1)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
# A "launcher" that starts one child the way the supervisor does (TELEO_PARENT_PID set),
# prints the child's pid, then waits. The child ties itself to it and loops until stopped;
# it writes "clean" on an orderly stop (its SIGTERM handler ran).
CHILD = ("import sys, time\n"
         "from bus.stage import stop_on_signals\n"
         "stop = stop_on_signals(child=True)\n"
         "print('ready', flush=True)\n"
         "while not stop.wait(0.05): pass\n"
         "open(sys.argv[1], 'w').write('clean')\n")
# (SIGHUP's default action restored: under `nohup` the test would inherit it ignored)
PARENT = ("import os, signal, subprocess, sys, time\n"
          "signal.signal(signal.SIGHUP, signal.SIG_DFL)\n"
          "env = dict(os.environ, TELEO_PARENT_PID=str(os.getpid()))\n"
          "child = subprocess.Popen([sys.executable, '-c', sys.argv[1], sys.argv[2]], env=env,\n"
          "                         stdout=subprocess.PIPE, text=True)\n"
          "child.stdout.readline()\n"
          "print(child.pid, flush=True)\n"
          "time.sleep(120)\n")


def gone(pid: int, timeout: float) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[-1].split()[0]
        except OSError:
            return True
        if state in ("Z", "X"):
            return True
        time.sleep(0.02)
    return False


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGHUP, signal.SIGTERM])
def test_the_child_stops_in_order_when_its_launcher_dies(tmp_path, sig):
    marker = tmp_path / "marker"
    parent = subprocess.Popen([sys.executable, "-c", PARENT, CHILD, str(marker)], cwd=ROOT,
                              env=dict(os.environ, PYTHONPATH=str(ROOT)),
                              stdout=subprocess.PIPE, text=True)
    child = int(parent.stdout.readline())
    os.kill(parent.pid, sig)
    parent.wait(10)
    assert gone(child, 10), f"child {child} still running after its launcher got {sig.name}"
    assert marker.read_text() == "clean"  # it ran its orderly stop, not a forced exit


def test_a_child_whose_launcher_is_already_gone_stops_at_once(tmp_path):
    marker = tmp_path / "marker"
    env = dict(os.environ, PYTHONPATH=str(ROOT), TELEO_PARENT_PID="1")  # not its parent
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(marker)], cwd=ROOT, env=env,
                             stdout=subprocess.PIPE, text=True)
    assert child.wait(20) == 0 and marker.read_text() == "clean"


def test_without_a_launcher_nothing_is_tied(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "TELEO_PARENT_PID"}
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(tmp_path / "m")], cwd=ROOT,
                             env=dict(env, PYTHONPATH=str(ROOT)), stdout=subprocess.PIPE,
                             text=True)
    assert child.stdout.readline().strip() == "ready"
    time.sleep(0.5)
    assert child.poll() is None
    child.send_signal(signal.SIGINT)
    assert child.wait(10) == 0
