"""`teleo record` against a live run: a run that goes on publishing never leaves its bus quiet,
and the record must still stop when told (--seconds, Ctrl-C, SIGTERM), with what was sent
until then and no more, in a file that reads back whole, and say truly what it holds.

(It once waited for a quiet bus: `--seconds 2` took 33 s, recorded 32 s of the run and
counted "2394 cycles", the last cycle number plus one.)"""

from __future__ import annotations

import re
import signal
import subprocess
import time
from pathlib import Path

import pytest
from e2e_helpers import HOLD_SPEED, ROOT, TELEO, Teleo, interrupt, trace_lines, wait_for

from tools.records.run_record import RunRecord

STOP_BOUND_S = 15.0  # [s] far below the 30 s the stop once took
SAID = re.compile(r"recorded (\d+) messages \((\d+) cycles, (\d+)\.\.(\d+)\) of run (\S+) "
                  r"to (\S+)")


@pytest.fixture(scope="module")
def live(tmp_path_factory):
    """A lockstep run that goes on until stopped (its own record off: only ours runs)."""
    teleo = Teleo(tmp_path_factory.mktemp("live"))
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0", "--no-record")
    try:
        info = teleo.run_info()
        assert wait_for(lambda: trace_lines(info) > 20, 60), teleo.launch_output()
        yield teleo, info
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()


def what_the_file_holds(path: Path) -> tuple[RunRecord, list[int], float]:
    """The record read back with the project's reader; its cycles (>= 0, sorted, distinct)
    and the wall-clock span of its messages' sends [s]."""
    rec = RunRecord(path)
    records = rec.records()
    assert not rec.truncated and records, path
    cycles = sorted({r["env"]["cycle"] for _, r in records if r["env"]["cycle"] >= 0})
    sent = [r["env"]["sent_ns"] for _, r in records]
    return rec, cycles, (max(sent) - min(sent)) / 1e9


def check_said(said: str, path: Path, run: str) -> tuple[RunRecord, list[int], float]:
    """The command's last line tells what the file holds: messages, distinct cycles, span."""
    found = SAID.search(said)
    assert found, said
    messages, count, first, last = (int(g) for g in found.groups()[:4])
    assert found.group(5) == run and Path(found.group(6)).name == path.name, said
    rec, cycles, span_s = what_the_file_holds(path)
    assert messages == len(rec.records()), said
    assert (count, first, last) == (len(cycles), cycles[0], cycles[-1]), said
    assert rec.meta["teleo.recorder"]["received"] == str(messages)
    assert rec.run == run
    return rec, cycles, span_s


def test_record_seconds_stops_in_time_with_about_that_much_of_the_run(live, tmp_path):
    teleo, info = live
    path = tmp_path / "r2.mcap"
    before, t0 = trace_lines(info), time.monotonic()
    done = teleo("record", str(path), "--seconds", "2", timeout=60)
    took_s, ran = time.monotonic() - t0, trace_lines(info) - before
    assert done.returncode == 0, done.stderr
    assert took_s < STOP_BOUND_S, (took_s, done.stderr)
    assert "still draining" not in done.stderr, done.stderr
    rec, cycles, span_s = check_said(done.stderr, path, info["run"])
    # about 2 s of the run by the senders' clocks (not 30), and in cycles at most what the
    # run went through meanwhile, about its rate times 2 s (a generous 4 s allowed)
    assert 1.0 <= span_s <= 2.6, span_s
    spanned = cycles[-1] - cycles[0] + 1
    rate = ran / took_s  # [cycles/s] over the whole command, start-up included
    assert 0 < spanned <= ran + 1, (spanned, ran)
    assert spanned <= 4.0 * rate + 5, (spanned, rate)
    # every message of the cycles in between was recorded: each key as often as the next;
    # the stats a process sends alone only once idle after a cycle (issue 36: a stage's, the
    # goal entry's) come in some cycles, not in each, and at most once a cycle
    counts, alone = {}, {}
    for key, r in rec.records():
        if cycles[0] < r["env"]["cycle"] < cycles[-1]:
            box = alone if "/stats/" in key and not key.endswith("/stats/world") else counts
            box[key] = box.get(key, 0) + 1
    assert set(counts.values()) == {spanned - 2}, counts
    assert all(n <= spanned - 2 for n in alone.values()), alone


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_a_signal_ends_the_record_promptly_with_a_whole_file(live, tmp_path, sig):
    teleo, info = live
    path = tmp_path / "rec.mcap"
    said = tmp_path / "record.err"
    with said.open("w") as err:
        proc = subprocess.Popen([*TELEO, "record", str(path)], cwd=ROOT, env=teleo.env,
                                stdout=subprocess.DEVNULL, stderr=err, text=True)
    try:
        assert wait_for(lambda: "recording run" in said.read_text() or proc.poll() is not None,
                        60), said.read_text()
        time.sleep(1.5)
        t0 = time.monotonic()
        proc.send_signal(sig)
        rc = proc.wait(STOP_BOUND_S)
        took_s = time.monotonic() - t0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    text = said.read_text()
    assert rc == 0, text
    assert took_s < 5.0, (took_s, text)
    assert "still draining" not in text, text
    _, _, span_s = check_said(text, path, info["run"])
    assert span_s <= 1.5 + took_s + 1.0, (span_s, text)


def test_a_live_runs_own_record_is_not_replayed_into_it_and_another_runs_can_be_watched(
        live, tmp_path):
    teleo, info = live
    own = tmp_path / "own.mcap"
    assert teleo("record", str(own), "--seconds", "1", timeout=60).returncode == 0
    refused = teleo("replay", str(own), "--speed", "0", timeout=60)
    assert refused.returncode == 1 and "Traceback" not in refused.stderr
    assert f"run {info['run']} is the running launch itself" in refused.stderr
    # a run that is no launch's (one `teleo replay` plays) is followed on the launch's router
    viewer = subprocess.Popen([*TELEO, "view", "--run", "some-replayed-run", "--port", "0"],
                              cwd=ROOT, env=teleo.env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    try:
        first = viewer.stdout.readline()
        assert "teleo view of run some-replayed-run" in first, first + viewer.stderr.read()
    finally:
        viewer.terminate()
        viewer.wait(30)
