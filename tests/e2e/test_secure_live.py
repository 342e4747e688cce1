"""A secured run (`[run] secure = true` or `--secure`; docs/bus.md "Security"): without the
run's credentials nobody can open a session; with another process's credentials nothing can
be read, forged or posted outside that process's own keys; with the operator's (the user who
launched it) the tools work; every secret is readable by its owner only (drill F10)."""

from __future__ import annotations

import json
import stat
from pathlib import Path

from e2e_helpers import interrupt, wait_for
from fault_helpers import scenario, wait_cycles

from bus.foreign import probe


def mode(path: Path) -> int:
    return stat.S_IMODE(path.stat().st_mode)


def test_a_stranger_can_do_nothing_and_the_operator_everything(teleo):
    launcher = teleo.start("launch", str(scenario(teleo.run_dir, secure=True)), "--cycles",
                           "0", "--summary", str(teleo.run_dir / "summary.json"))
    try:
        info = teleo.run_info()
        assert info["endpoint"].startswith("tls/127.0.0.1:")
        secrets = Path(info["run_dir"]) / "secrets"
        assert mode(teleo.run_files()[0]) == 0o600 and mode(teleo.run_dir / "active") == 0o700
        assert mode(secrets) == 0o700 and {mode(p) for p in secrets.iterdir()} == {0o600}
        wait_cycles(info, 10)
        seen = probe(info["endpoint"], info["run"], secrets)
        assert seen["no_credentials_refused"] and seen["plain_tcp_refused"]
        assert seen["no_password_refused"] and seen["wrong_password_refused"]
        assert seen["other_user_read_messages"] == 0
        assert seen["forged_messages_delivered"] == 0
        assert seen["other_user_goal_post"] == "refused (NobodyServing)"
        assert seen["operator_goal_list_ok"] and seen["operator_event_delivered"]
        assert seen["run_traffic_seen_by_operator"] > 0
        posted = teleo("goal", "post", "(package-delivered PACKET2)", "--priority", "9")
        assert posted.returncode == 0 and "posted g2" in posted.stdout, posted.stderr
        assert ", secured)" in posted.stderr.splitlines()[0]
        sent = teleo("event", '{"kind": "pedestrian", "ahead_of": "ME", "dist": 25}')
        assert sent.returncode == 0, sent.stderr
        trace = Path(info["run_dir"]) / "trace.jsonl"
        assert wait_for(lambda: '"ahead_of": "ME", "dist": 25' in trace.read_text(), 30)
    finally:
        code = interrupt(launcher)
    assert code == 0, teleo.launch_output()
    summary = json.loads((teleo.run_dir / "summary.json").read_text())
    assert summary["secured"] and summary["status"] == "completed"


def test_a_secured_launch_refuses_a_plain_endpoint(teleo):
    done = teleo("launch", str(scenario(teleo.run_dir)), "--secure", "--listen",
                 "tcp/127.0.0.1:0")
    assert done.returncode != 0
    assert "a secured run listens and connects on tls/ endpoints, got 'tcp/127.0.0.1:0'" \
        in done.stderr
    assert not list(teleo.run_dir.glob("runs/*"))
