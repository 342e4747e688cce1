"""The launcher's supervisor: respawn per policy (like ros2 launch respawn) and ordered stop."""

from __future__ import annotations

import os
import signal
import sys

from tools.launching.supervisor import ProcSpec, Supervisor, wait_until

CRASH = "import sys; print('started'); sys.exit(3)"
# Writes its name to a shared file when told to stop, so the stop order can be checked.
SLEEPER = ("import signal, sys, time\n"
           "def bye(*_):\n"
           "    open(sys.argv[1], 'a').write(sys.argv[2] + '\\n'); sys.exit(0)\n"
           "signal.signal(signal.SIGTERM, bye)\n"
           "print('ready', flush=True)\n"
           "while True: time.sleep(0.05)\n")


def test_a_crashing_process_is_restarted_up_to_its_limit(tmp_path):
    sup = Supervisor(tmp_path / "logs")
    sup.start(ProcSpec("crasher", (sys.executable, "-c", CRASH), max_restarts=2))
    exits = []
    assert wait_until(lambda: exits.extend(sup.poll()) or any(not e.restarted for e in exits),
                      timeout=30)
    assert [(e.restarted, e.returncode) for e in exits] == [(True, 3), (True, 3), (False, 3)]
    assert sup.restarts() == {"crasher": 2}
    assert (tmp_path / "logs" / "crasher.log").read_text().count("started") == 3


def test_exempt_processes_are_reported_not_restarted(tmp_path):
    sup = Supervisor(tmp_path / "logs")
    sup.start(ProcSpec("world", (sys.executable, "-c", "pass"), max_restarts=5))
    exits = []
    assert wait_until(lambda: exits.extend(sup.poll(exempt=("world",))) or exits, timeout=30)
    assert exits[0].name == "world" and not exits[0].restarted and exits[0].returncode == 0


def test_stop_all_goes_first_then_the_rest_at_once_then_last(tmp_path):
    order = tmp_path / "order.txt"
    sup = Supervisor(tmp_path / "logs")
    names = ("router", "goals", "ME.inference", "world")
    for name in names:
        sup.start(ProcSpec(name, (sys.executable, "-c", SLEEPER, str(order), name)))
    logs = tmp_path / "logs"
    assert wait_until(lambda: all("ready" in (logs / f"{n}.log").read_text() for n in names),
                      timeout=30)
    codes = sup.stop_all(["world"], last=["router"], first_s=10, rest_s=10, last_s=10)
    assert codes == dict.fromkeys(names, 0) | {"world": 0}
    seen = order.read_text().split()
    assert seen[0] == "world" and seen[-1] == "router"
    assert sorted(seen[1:3]) == ["ME.inference", "goals"]
    assert sup.poll() == []  # stopped processes are not restarted


def test_stop_all_can_keep_the_router_until_the_record_is_drained(tmp_path):
    order = tmp_path / "order.txt"
    sup = Supervisor(tmp_path / "logs")
    names = ("router", "goals", "world")
    for name in names:
        sup.start(ProcSpec(name, (sys.executable, "-c", SLEEPER, str(order), name)))
    logs = tmp_path / "logs"
    assert wait_until(lambda: all("ready" in (logs / f"{n}.log").read_text() for n in names),
                      timeout=30)
    assert sup.stop_all(["world"], keep=["router"], first_s=10, rest_s=10) == \
        {"world": 0, "goals": 0}
    assert sup.running("router") and order.read_text().split() == ["world", "goals"]
    assert sup.stop_all([], last=["router"], last_s=10)["router"] == 0
    assert order.read_text().split() == ["world", "goals", "router"]


# Ignores SIGTERM (and is then SIGSTOPped by the test): only a kill ends it.
STUBBORN = ("import signal, time\n"
            "signal.signal(signal.SIGTERM, signal.SIG_IGN)\n"
            "print('ready', flush=True)\n"
            "while True: time.sleep(0.05)\n")


def test_a_stopped_or_deaf_process_is_killed_when_its_time_is_up(tmp_path):
    sup = Supervisor(tmp_path / "logs")
    for name in ("deaf", "stopped"):
        sup.start(ProcSpec(name, (sys.executable, "-c", STUBBORN)))
    logs = tmp_path / "logs"
    assert wait_until(lambda: all("ready" in (logs / f"{n}.log").read_text()
                                  for n in ("deaf", "stopped")), timeout=30)
    os.kill(sup.pid("stopped"), signal.SIGSTOP)
    codes = sup.stop_all([], rest_s=0.5)
    assert codes == {"deaf": -signal.SIGKILL, "stopped": -signal.SIGKILL}


def test_a_restart_gets_its_restart_args_and_the_launchers_pid(tmp_path):
    marker = tmp_path / "argv.txt"
    code = ("import os, sys\n"
            "open(sys.argv[1], 'a').write(' '.join(sys.argv[2:]) + ' '"
            " + os.environ['TELEO_PARENT_PID'] + '\\n')\n"
            "sys.exit(0 if '--resume' in sys.argv else 9)\n")
    sup = Supervisor(tmp_path / "logs")
    sup.start(ProcSpec("world", (sys.executable, "-c", code, str(marker)), 2,
                       restart_args=("--resume",)))
    exits = []
    assert wait_until(lambda: exits.extend(sup.poll()) or len(exits) == 2, timeout=30)
    assert [(e.returncode, e.restarted) for e in exits] == [(9, True), (0, True)]
    mine = str(os.getpid())
    assert [x.split() for x in marker.read_text().splitlines()] == [[mine], ["--resume", mine]]


# Stops cleanly on SIGTERM, saying so, unless it is stopped (SIGSTOP) when the stop comes.
POLITE = ("import signal, sys, time\n"
          "def bye(*_):\n"
          "    print('stopped cleanly', flush=True); sys.exit(0)\n"
          "signal.signal(signal.SIGTERM, bye)\n"
          "print('ready', flush=True)\n"
          "while True: time.sleep(0.05)\n")


def test_a_stopped_process_is_killed_at_once_and_the_others_still_stop_cleanly(tmp_path):
    """Ctrl-C during a stall (drill d2b): the stop never waits on a SIGSTOPped stage (it
    has nothing to finish); the others get their SIGTERM and stop in order."""
    sup = Supervisor(tmp_path / "logs")
    for name in ("stalled", "goals"):
        sup.start(ProcSpec(name, (sys.executable, "-c", POLITE)))
    logs = tmp_path / "logs"
    assert wait_until(lambda: all("ready" in (logs / f"{n}.log").read_text()
                                  for n in ("stalled", "goals")), timeout=30)
    os.kill(sup.pid("stalled"), signal.SIGSTOP)
    codes = sup.stop_all([], rest_s=60)
    assert codes == {"stalled": -signal.SIGKILL, "goals": 0}
    assert "stopped cleanly" not in (logs / "stalled.log").read_text()
    assert "stopped cleanly" in (logs / "goals.log").read_text()


def test_a_process_still_starting_stops_quietly(tmp_path):
    """A process stopped before it has set its handlers (still importing: the world in
    drill d1c) ends without a KeyboardInterrupt traceback in its log."""
    sup = Supervisor(tmp_path / "logs")
    sup.start(ProcSpec("world", (sys.executable, "-c",
                                 "import time; print('importing', flush=True); time.sleep(60)")))
    log = tmp_path / "logs" / "world.log"
    assert wait_until(lambda: "importing" in log.read_text(), timeout=30)
    assert sup.stop_all(["world"], first_s=30) == {"world": -signal.SIGTERM}
    assert "Traceback" not in log.read_text()
