"""`teleo goal post ... --wait` over real launches (issue 25), as `ros2 action send_goal
--feedback`: it follows the goal to achieved (exit 0) or failed (exit 1, the reason said), ends
on --timeout (124), on a cancel by someone else and on a run that ends (3), and on Ctrl-C (130:
without a terminal the goal stays posted, --cancel-on-interrupt cancels it, a terminal is
asked). Also the trial's goal errors (2026-12-02, #15 and #16) and the one short line every
tool says on stderr about the run it reached (none with --quiet)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time

from e2e_helpers import FIXTURES, HOLD_SPEED, ROOT, TELEO, interrupt, wait_for


def goal_rows(teleo) -> dict[str, dict]:
    listed = teleo("goal", "list", "--json", "-q")
    assert listed.returncode == 0 and listed.stderr == "", listed.stderr
    return {g["id"]: g for g in json.loads(listed.stdout)}


def reach_line(teleo, run: str, stderr: str) -> None:
    """The one line a tool says about the run it reached: `run R (router EP)`."""
    first = stderr.splitlines()[0]
    assert first.startswith(f"run {run} (router tcp/127.0.0.1:") and first.endswith(")"), \
        stderr


class Waiting:
    """`teleo goal post ... --wait` in the background, its output in files."""

    def __init__(self, teleo, *args: str, stdin=subprocess.DEVNULL) -> None:
        self.out, self.err = teleo.run_dir / f"wait-{args[0][-8:-1]}.out", \
            teleo.run_dir / f"wait-{args[0][-8:-1]}.err"
        with open(self.out, "w") as out, open(self.err, "w") as err:
            self.proc = subprocess.Popen([*TELEO, "goal", "post", *args, "--wait"], cwd=ROOT,
                                         env=teleo.env, stdin=stdin, stdout=out, stderr=err,
                                         text=True)

    def following(self, timeout: float = 60) -> bool:
        """Whether it has printed its first status line (its signal handlers are set)."""
        return wait_for(lambda: "cycle " in self.out.read_text() or
                        self.proc.poll() is not None, timeout) and self.proc.poll() is None

    def end(self, timeout: float = 60) -> tuple[int, str, str]:
        code = self.proc.wait(timeout)
        return code, self.out.read_text(), self.err.read_text()


def test_a_goal_is_followed_to_achieved_with_its_path(teleo):
    launcher = teleo.start("launch", str(FIXTURES / "deliver_ahead.toml"), "--summary",
                           str(teleo.run_dir / "summary.json"))   # the record: its history
    try:
        run = teleo.run_info()["run"]
        done = teleo("goal", "post", "(package-delivered PACKET2)", "-p", "3", "--wait",
                     "--timeout", "300", timeout=360)
        assert done.returncode == 0, done.stdout + done.stderr
        lines = done.stdout.splitlines()
        assert lines[0].startswith("posted g2 for ME: (package-delivered PACKET2) (from cycle ")
        active = [line for line in lines if line.split()[2:3] == ["active"]]
        assert active and "package-delivered#" in active[0] and "deliver_ahead.tlp:" in \
            active[0] and "=> (*gas" in active[0], done.stdout
        assert lines[-2].split()[2] == "achieved"
        assert lines[-1].startswith("g2 achieved at cycle ")
        achieved = int(lines[-1].split()[-1])
        reach_line(teleo, run, done.stderr)
        assert len(done.stderr.splitlines()) == 1
        # trial #15: the goal once, its position as a column, one line
        bad = teleo("goal", "post", "(cruising ME", "--priority", "5")
        assert bad.returncode == 1 and "Traceback" not in bad.stderr
        reach_line(teleo, run, bad.stderr)
        assert bad.stderr.splitlines()[1:] == [
            "Error: refused: ME cannot take goal '(cruising ME': column 1: '(' is never "
            "closed (missing ')')"]
        quiet = teleo("goal", "post", "(cruising ME", "--priority", "5", "-q")
        assert quiet.stderr.splitlines() == bad.stderr.splitlines()[1:]
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
    summary = json.loads((teleo.run_dir / "summary.json").read_text())
    g2 = next(g for g in summary["goals"] if g["id"] == "g2")
    assert g2["status"] == "achieved" and g2["history"][-1] == {"cycle": achieved,
                                                                "status": "achieved"}


def test_a_goal_the_solver_gives_up_fails_with_its_reason(teleo, tmp_path):
    text = HOLD_SPEED.read_text().replace("solver = false", "solver = true")
    text = text[:text.index("[[goals]]")] + text[text.index("[[events]]"):]  # none scripted
    (tmp_path / "solver.toml").write_text(text)
    (tmp_path / "hold_speed.tlp").write_text((FIXTURES / "hold_speed.tlp").read_text())
    launcher = teleo.start("launch", str(tmp_path / "solver.toml"), "--cycles", "0",
                           "--no-record")
    try:
        teleo.run_info()
        done = teleo("goal", "post", "(package-delivered PACKET1)", "-p", "3", "--wait",
                     "--timeout", "120", "-q", timeout=180)
        assert done.returncode == 1, done.stdout + done.stderr
        assert done.stdout.splitlines()[-1].split()[2] == "failed"
        assert done.stderr.startswith("Error: g1 failed at cycle ")
        assert ": (package-delivered PACKET1) cannot be achieved: nothing to chain off" in \
            done.stderr and len(done.stderr.splitlines()) == 1
        assert goal_rows(teleo)["g1"]["status"] == "failed"
    finally:
        stopped = interrupt(launcher)
    assert stopped == 1, teleo.launch_output()   # the launch says so too: a goal failed
    assert "failed: goal g1 (package-delivered PACKET1) could not be kept" in \
        teleo.launch_output()


def test_a_wait_ends_on_timeout_on_a_cancel_on_ctrl_c_and_when_the_run_ends(teleo):
    # hold_speed.toml's executive has no skill for a delivery and no solver: a posted
    # delivery is never achieved nor failed
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0", "--no-record")
    try:
        run = teleo.run_info()["run"]
        timed = teleo("goal", "post", "(package-delivered PACKET2)", "-p", "3", "--wait",
                      "--timeout", "2", timeout=120)
        assert timed.returncode == 124, timed.stdout + timed.stderr
        assert timed.stderr.splitlines()[-1].startswith(
            "Error: g2 not done after 2 s (--timeout): ")
        assert timed.stderr.endswith("; it stays posted\n")
        assert goal_rows(teleo)["g2"]["status"] in {"pending", "impasse"}

        other = Waiting(teleo, "(package-delivered PACKET3)", "-p", "3")
        assert other.following(), other.err.read_text()
        assert teleo("goal", "cancel", "g3").returncode == 0
        code, _, err = other.end()
        assert code == 3 and "Error: g3 was cancelled at cycle " in err, err

        kept = Waiting(teleo, "(package-delivered PACKET4)", "-p", "3")
        assert kept.following(), kept.err.read_text()
        kept.proc.send_signal(signal.SIGINT)
        code, _, err = kept.end()
        assert code == 130 and "interrupted: g4 stays posted (" in err, err
        assert goal_rows(teleo)["g4"]["status"] in {"pending", "impasse"}

        dropped = Waiting(teleo, "(package-delivered PACKET5)", "-p", "3",
                          "--cancel-on-interrupt")
        assert dropped.following(), dropped.err.read_text()
        dropped.proc.send_signal(signal.SIGINT)
        code, _, err = dropped.end()
        assert code == 130 and "interrupted: cancelled g5 (from cycle " in err, err
        assert goal_rows(teleo)["g5"]["status"] == "cancelled"

        asked = _asked_on_a_terminal(teleo, "(package-delivered PACKET6)")
        assert asked[0] == 130 and "cancel g6? [y/N]" in asked[1], asked
        assert "interrupted: cancelled g6" in asked[1]
        assert goal_rows(teleo)["g6"]["status"] == "cancelled"

        # trial #16: p1 is the program's own goal
        for args, what in ((("cancel", "p1"), "cancelled"),
                           (("priority", "p1", "7"), "given another priority")):
            done = teleo("goal", *args)
            reach_line(teleo, run, done.stderr)
            assert done.returncode == 1 and done.stderr.splitlines()[1] == (
                f"Error: refused: p1 is a program goal of ME, (at-desired-speed ME): it cannot "
                f"be {what} (program goals rank in the program's order; user goals are g1, "
                "g2, ...)"), done.stderr

        ending = Waiting(teleo, "(package-delivered PACKET7)", "-p", "3")
        assert ending.following(), ending.err.read_text()
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
    code, _, err = ending.end()
    assert code == 3 and f"Error: run {run} ended before g7 was achieved (" in err, err


def _asked_on_a_terminal(teleo, goal: str) -> tuple[int, str]:
    """Ctrl-C of a --wait whose stdin is a terminal, answering "y" to its question."""
    master, slave = os.openpty()
    try:
        waiting = Waiting(teleo, goal, "-p", "3", stdin=slave)
        assert waiting.following(), waiting.err.read_text()
        waiting.proc.send_signal(signal.SIGINT)
        assert wait_for(lambda: "[y/N]" in waiting.err.read_text(), 30), \
            waiting.err.read_text()
        time.sleep(0.2)
        os.write(master, b"y\n")
        code, _, err = waiting.end()
        return code, err
    finally:
        os.close(slave)
        os.close(master)


def test_without_a_launch_a_wait_says_so(teleo):
    done = teleo("goal", "post", "(x)", "--wait")
    assert done.returncode == 1 and "Traceback" not in done.stderr
    assert done.stderr.startswith("Error: no running teleo launch found in ")
    assert len(done.stderr.splitlines()) == 1
