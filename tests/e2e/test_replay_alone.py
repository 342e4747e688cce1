"""A self-contained replay (issue 25), as `ros2 bag play`: with no launch running, `teleo
replay RECORD` starts a router of its own on loopback, says where, plays the record there
(`teleo echo --connect` follows it), from `--start CYCLE`, again with `--loop`, and on a
terminal paused (`--paused`), stepped one cycle a key (s, the right arrow) and resumed
(space); its router is gone when it ends. `teleo view RECORD` serves a record with nothing
running."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import time
import urllib.request
from pathlib import Path

import pytest
from e2e_helpers import HOLD_SPEED, ROOT, TELEO, Teleo, wait_for

from tools.records.run_record import RunRecord


@pytest.fixture(scope="module")
def record(tmp_path_factory) -> Path:
    """A 30-cycle record of hold_speed.toml, made by `teleo simulate` (no bus)."""
    teleo = Teleo(tmp_path_factory.mktemp("made"))
    done = teleo("simulate", str(HOLD_SPEED), "--json", timeout=120)
    assert done.returncode == 0, done.stderr
    return Path(json.loads(done.stdout)["record"])


class Replay:
    """`teleo replay RECORD ...` in the background, its stderr in a file; `echo` follows it."""

    def __init__(self, teleo: Teleo, record: Path, *args: str, stdin=subprocess.DEVNULL):
        self.teleo = teleo
        self.err = teleo.run_dir / "replay.err"
        with open(self.err, "w") as err:
            self.proc = subprocess.Popen([*TELEO, "replay", str(record), "--wait", "60", *args],
                                         cwd=ROOT, env=teleo.env, stdin=stdin,
                                         stdout=subprocess.DEVNULL, stderr=err)
        assert wait_for(lambda: "router tcp/" in self.err.read_text() or
                        self.proc.poll() is not None, 60), self.err.read_text()
        said = self.err.read_text().splitlines()[0]
        assert said.startswith("router tcp/127.0.0.1:") and " of its own (no launch is " \
            "running): replaying run " in said, said
        self.endpoint = re.search(r"tcp/127\.0\.0\.1:\d+", said).group(0)
        assert f"teleo echo --connect {self.endpoint}" in said
        self.seen = teleo.run_dir / "echo.out"
        with open(self.seen, "w") as out:
            self.echo = subprocess.Popen([*TELEO, "echo", "--connect", self.endpoint, "-q"],
                                         cwd=ROOT, env=teleo.env, stdout=out,
                                         stderr=subprocess.DEVNULL)

    def cycles(self) -> list[int]:
        """The cycle of each message echo has printed so far."""
        lines = self.seen.read_text().splitlines()
        return [json.loads(line)["msg"]["env"]["cycle"] for line in lines if line.endswith("}")]

    def end(self, timeout: float = 120) -> tuple[int, str]:
        code = self.proc.wait(timeout)
        time.sleep(0.5)
        self.echo.send_signal(signal.SIGINT)
        self.echo.wait(30)
        return code, self.err.read_text()


def test_with_nothing_running_it_plays_on_a_router_of_its_own(teleo, record):
    assert teleo.run_files() == []   # no launch registered here
    replay = Replay(teleo, record, "--rate", "0")
    code, said = replay.end()
    # the world's static part, once in the record (issue 35), is put first as the world did
    # (outside the cycles: not counted), then the 30 cycles of 10 messages
    expected = [r["env"]["cycle"] for _, r in RunRecord(record).records()]
    assert code == 0, said
    assert replay.cycles() == expected and len(expected) == 301 and expected[0] == -1
    assert said.splitlines()[-1].startswith("replayed 300 messages (30 cycles) of run ")
    gone = teleo("echo", "--connect", replay.endpoint, "--seconds", "1")
    assert gone.returncode == 1 and "no router answers at" in gone.stderr   # stopped with it


def test_from_a_start_cycle_again_and_again_until_interrupted(teleo, record):
    replay = Replay(teleo, record, "--rate", "0", "--start", "25", "--loop")
    assert wait_for(lambda: len(replay.cycles()) >= 150, 120), replay.err.read_text()
    replay.proc.send_signal(signal.SIGINT)
    code, said = replay.end()
    assert code == 0 and "looping: cycle 25 again" in said, said
    static, *cycles = replay.cycles()   # the world's static part first (issue 35)
    assert static == -1
    passes = len(cycles) // 50     # cycles 25..29, ten messages each
    assert passes >= 3 and cycles[:50 * passes] == sorted(
        [c for c in range(25, 30) for _ in range(10)]) * passes
    assert said.rstrip().endswith("(interrupted)")


def test_on_a_terminal_paused_it_steps_one_cycle_a_key_and_resumes(teleo, record):
    master, slave = os.openpty()
    try:
        replay = Replay(teleo, record, "--rate", "0", "--paused", stdin=slave)
        assert wait_for(lambda: "paused before cycle 0" in replay.err.read_text(), 60)
        time.sleep(1.0)   # echo subscribes; nothing but the static part while paused
        assert wait_for(lambda: replay.cycles() == [-1], 30), replay.cycles()
        for n, key in enumerate((b"s", b"s", b"\x1b[C"), start=1):
            os.write(master, key)
            assert wait_for(lambda n=n: len(replay.cycles()) >= 10 * n + 1, 60), \
                replay.err.read_text()
            time.sleep(0.5)
            assert replay.cycles() == [-1, *(c for c in range(n) for _ in range(10))]
        os.write(master, b" ")
        code, said = replay.end()
    finally:
        os.close(slave)
        os.close(master)
    assert code == 0, said
    assert len(replay.cycles()) == 301
    for n in range(3):
        assert f"stepped: cycle {n} sent" in said
    assert "playing from cycle 3" in said


def test_view_of_a_record_with_nothing_running(teleo, record):
    assert teleo.run_files() == []
    proc = subprocess.Popen([*TELEO, "view", str(record), "--port", "0"], cwd=ROOT,
                            env=teleo.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        line = proc.stdout.readline()
        url = re.search(r"http://127\.0\.0\.1:\d+/", line).group(0)
        with urllib.request.urlopen(url + "api/status", timeout=30) as r:
            status = json.loads(r.read())
        assert (status["first"], status["last"]) == (0, 29)
        with urllib.request.urlopen(url + "api/frame?cycle=12", timeout=30) as r:
            frame = json.loads(r.read())
        assert frame["cycle"] == 12 and frame["agents"]["ME"]["goals"]
    finally:
        proc.send_signal(signal.SIGINT)
        assert proc.wait(30) == 0, proc.stderr.read()
