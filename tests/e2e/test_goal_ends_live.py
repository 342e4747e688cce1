"""`teleo goal post --once` and `--deadline CYCLES` on a live launch (issue 34, item 2): a once
goal is achieved and its wait exits 0; a goal not achieved in time fails with its reason."""

from __future__ import annotations

from e2e_helpers import ROOT, interrupt, wait_for

FIGURE3 = ROOT / "scenarios" / "blocks_figure3.toml"


def test_goals_that_end_over_a_launch(teleo):
    launcher = teleo.start("launch", str(FIGURE3), "--cycles", "0")
    try:
        teleo.run_info()
        late = teleo("goal", "post", "(on C B)", "--deadline", "1", "--wait", "--timeout", "120",
                     "--quiet")
        assert late.returncode == 1, late.stdout + late.stderr
        assert "deadline 1 cycles" in late.stdout, late.stdout
        assert "(on C B) not achieved by cycle" in late.stdout + late.stderr
        once = teleo("goal", "post", "(ontable C T)", "--once", "--wait", "--timeout", "120",
                     "--quiet")
        assert once.returncode == 0, once.stdout + once.stderr
        assert "; once" in once.stdout and "achieved" in once.stdout, once.stdout
        assert wait_for(lambda: '"once": true' in teleo("goal", "list", "--json").stdout, 30)
    finally:
        status = interrupt(launcher)
    out = teleo.launch_output()
    assert status == 1 and "g2 ME (on C B) p100: failed" in out, out   # a goal failed
    assert "g3 ME (ontable C T) p100: achieved" in out, out
