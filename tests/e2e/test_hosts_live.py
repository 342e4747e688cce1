"""One run over two hosts (docs/faults.md "Across hosts"): the router, the world and the goal
entry in one Linux network namespace, the agent ME's three processes in another, joined by a
veth pair the test makes (as root, with iproute2) and removes, on a secured bus. The driving
demo completes with the very trace it has on one host."""

from __future__ import annotations

import json
import os
import secrets
import shutil
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from e2e_helpers import ROOT, TELEO, wait_for

DEMO = ROOT / "scenarios" / "driving_demo.toml"


def ip(*args: str) -> None:
    subprocess.run(["ip", *args], check=True, capture_output=True, text=True, timeout=30)


@pytest.fixture
def hosts() -> Iterator[tuple[str, str, str]]:
    """Two namespaces joined by a veth pair: (namespace A, namespace B, A's address)."""
    if os.geteuid() != 0 or shutil.which("ip") is None:
        pytest.skip("needs root and iproute2's `ip` (make setup installs it on Debian)")
    tag = secrets.token_hex(3)
    a, b, net = f"teleo-a-{tag}", f"teleo-b-{tag}", f"10.{int(tag[:2], 16)}.{int(tag[2:4], 16)}"
    made = []
    try:
        for ns in (a, b):
            ip("netns", "add", ns)
            made.append(ns)
        ip("link", "add", f"tva{tag}", "type", "veth", "peer", "name", f"tvb{tag}")
        for ns, dev, host in ((a, f"tva{tag}", 1), (b, f"tvb{tag}", 2)):
            ip("link", "set", dev, "netns", ns)
            ip("-n", ns, "addr", "add", f"{net}.{host}/24", "dev", dev)
            ip("-n", ns, "link", "set", dev, "up")
            ip("-n", ns, "link", "set", "lo", "up")
        yield a, b, f"{net}.1"
    finally:
        for ns in made:
            pids = subprocess.run(["ip", "netns", "pids", ns], capture_output=True, text=True)
            for pid in pids.stdout.split():
                subprocess.run(["kill", "-9", pid], capture_output=True)
            ip("netns", "del", ns)  # takes its end of the veth pair with it


def in_ns(ns: str, run_dir: Path, *args: str, out: Path) -> subprocess.Popen:
    env = {**os.environ, "TELEO_RUN_DIR": str(run_dir)}
    with out.open("w") as log:
        return subprocess.Popen(["ip", "netns", "exec", ns, *TELEO, *args], cwd=ROOT, env=env,
                                stdout=log, stderr=subprocess.STDOUT)


def registered(run_dir: Path, timeout: float = 120) -> dict:
    assert wait_for(lambda: list((run_dir / "active").glob("*.json")), timeout)
    return json.loads(next((run_dir / "active").glob("*.json")).read_text())


def net_ns(pid: int) -> str:
    return os.readlink(f"/proc/{pid}/ns/net")


def test_an_agent_on_another_host_runs_the_demo_with_the_same_trace(hosts, tmp_path):
    ns_a, ns_b, address = hosts
    single = tmp_path / "single"
    alone = subprocess.run([*TELEO, "launch", str(DEMO)], cwd=ROOT, capture_output=True,
                           text=True, env={**os.environ, "TELEO_RUN_DIR": str(single)},
                           timeout=600)
    assert alone.returncode == 0, alone.stdout + alone.stderr
    reference = next(single.glob("runs/*/trace.jsonl")).read_text()

    here, there, run = tmp_path / "a", tmp_path / "b", "two-hosts"
    endpoint = f"tls/{address}:17447"
    main = in_ns(ns_a, here, "launch", str(DEMO), "--secure", "--only", "world,goals",
                 "--listen", endpoint, "--run", run, "--summary", str(here / "summary.json"),
                 out=tmp_path / "a.out")
    joined = None
    try:
        info = registered(here)
        shutil.copytree(Path(info["run_dir"]) / "secrets", there / "secrets")  # scp -rp
        joined = in_ns(ns_b, there, "launch", str(DEMO), "--join", endpoint, "--run", run,
                       "--secure", "--secrets", str(there / "secrets"), "--only", "ME",
                       out=tmp_path / "b.out")
        agent = registered(there)
        assert sorted(agent["pids"]) == ["ME.executive", "ME.inference", "ME.perception"]
        assert net_ns(agent["pids"]["ME.executive"]) != net_ns(info["pids"]["world"])
        assert main.wait(600) == 0, (tmp_path / "a.out").read_text()
        assert joined.wait(60) == 0, (tmp_path / "b.out").read_text()
    finally:
        for proc in (main, joined):
            if proc is not None and proc.poll() is None:
                proc.kill()
    summary = json.loads((here / "summary.json").read_text())
    assert summary["status"] == "completed" and summary["goals_achieved"] == 2
    assert Path(summary["trace"]).read_text() == reference
    assert "left run two-hosts: ME.perception, ME.inference, ME.executive stopped" in \
        (tmp_path / "b.out").read_text()
