"""Commands that change a running system report its verdict (issue 12, items 2, 6, 7, 11):
the goal-entry process refuses a goal ranked above the driving laws unless forced, a goal
about a package that does not exist gets a hint, and `teleo goal list --json` serves scripts.
The demo scenario (programs/driving.tlp: five laws, p1..p5), lockstep without a cycle limit."""

from __future__ import annotations

import json

from e2e_helpers import ROOT, interrupt, wait_for

DEMO = ROOT / "scenarios" / "driving_demo.toml"


def goals(teleo) -> dict[str, dict]:
    listed = teleo("goal", "list", "--json")
    assert listed.returncode == 0, listed.stderr
    return {g["id"]: g for g in json.loads(listed.stdout)}


def demo_without_scripted_goals(folder) -> str:
    """The demo's scenario with only its first goal, g1 (PACKET1): every later id is the
    test's own, however fast the run goes."""
    text = DEMO.read_text().replace('program = "programs/driving.tlp"',
                                    f'program = "{ROOT / "programs" / "driving.tlp"}"')
    first, _, _ = text.partition('goal = "(package-delivered PACKET2)"')
    path = folder / "demo.toml"
    path.write_text(first.rsplit("[[goals]]", 1)[0])
    return str(path)


def test_priorities_above_the_laws_need_force_and_a_missing_package_gets_a_hint(teleo,
                                                                                tmp_path):
    launcher = teleo.start("launch", demo_without_scripted_goals(tmp_path), "--cycles", "0")
    try:
        teleo.run_info()
        refused = teleo("goal", "post", "(package-delivered PACKET2)", "--priority", "2")
        assert refused.returncode == 1
        assert ("priority 2 ranks the goal above the program's standing goals p3 "
                "(at-desired-speed ME), p4 (in-right-lane ME), p5 (at-cruising-speed ME)"
                in refused.stderr)
        assert "g2" not in goals(teleo)
        forced = teleo("goal", "post", "(package-delivered PACKET2)", "--priority", "2",
                       "--force")
        assert forced.returncode == 0, forced.stderr
        assert "posted g2 for ME" in forced.stdout and "forced: priority 2 ranks" in forced.stdout
        raised = teleo("goal", "priority", "g1", "1")
        assert raised.returncode == 1 and "p2 (keeping-distance ME)" in raised.stderr
        assert goals(teleo)["g1"]["priority"] == 5
        ghost = teleo("goal", "post", "(package-delivered PACKET9)", "--priority", "6")
        assert ghost.returncode == 0 and "posted g3" in ghost.stdout

        def hinted() -> bool:
            return "no percept mentions PACKET9" in goals(teleo).get("g3", {}).get("note", "")
        assert wait_for(hinted, 60), goals(teleo)
        listed = goals(teleo)
        assert set(listed["g3"]) >= {"id", "agent", "goal", "priority", "status", "note",
                                     "posted_cycle", "updated_cycle"}
        assert listed["g3"]["status"] in ("pending", "impasse", "failed")
        assert "PACKET2" not in listed["g2"]["note"]       # a package that exists: no hint
        table = teleo("goal", "list")
        assert "-- " in table.stdout and "no percept mentions PACKET9" in table.stdout
        # the user withdraws the goal that cannot be kept; the run then ends completed
        withdrawn = teleo("goal", "cancel", "g3")
        assert withdrawn.returncode == 0, withdrawn.stderr
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
