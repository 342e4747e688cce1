"""The launcher's supervisor: respawn per policy (like ros2 launch respawn) and ordered stop."""

from __future__ import annotations

import sys

from tools.supervisor import ProcSpec, Supervisor, wait_until

CRASH = "import sys; print('started'); sys.exit(3)"
# Writes its name to a shared file when told to stop, so the stop order can be checked.
SLEEPER = ("import signal, sys, time\n"
           "def bye(*_):\n"
           "    open(sys.argv[1], 'a').write(sys.argv[2] + '\\n'); sys.exit(0)\n"
           "signal.signal(signal.SIGINT, bye)\n"
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


def test_stop_all_goes_in_the_given_order_then_the_rest(tmp_path):
    order = tmp_path / "order.txt"
    sup = Supervisor(tmp_path / "logs")
    for name in ("router", "goals", "world"):
        sup.start(ProcSpec(name, (sys.executable, "-c", SLEEPER, str(order), name)))
    logs = tmp_path / "logs"
    assert wait_until(lambda: all("ready" in (logs / f"{n}.log").read_text()
                                  for n in ("router", "goals", "world")), timeout=30)
    codes = sup.stop_all(["world"])
    assert codes == {"world": 0, "goals": 0, "router": 0}
    assert order.read_text().split() == ["world", "goals", "router"]
    assert sup.poll() == []  # stopped processes are not restarted
