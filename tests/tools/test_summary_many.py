"""A summary of many agents stays readable (issue 31, N20): agents in natural order (A2
before A10), the lines of agents that read alike folded into one, and a cycle time of 150
stages told by its largest shares, wrapped."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from tools.cli import cli
from tools.records import summary
from tools.records.summary_agents import names_text, natural, shares_text

ROOT = Path(__file__).resolve().parents[2]


def twelve_cars(tmp_path: Path) -> Path:
    cars = ", ".join(f'{{ agent = "A{k}", street = "{"ABCD"[k % 4]}", from = "FIRST", '
                     f'toward = "SECOND", along = {10 + 30 * (k // 4)}.0 }}' for k in range(12))
    agents = "".join(f'[[agents]]\nid = "A{k}"\nprogram = "{ROOT}/programs/driving.tlp"\n'
                     for k in range(12))
    path = tmp_path / "twelve.toml"
    path.write_text(f'[run]\nname = "twelve"\ncycles = 2\n[world]\ngrid = [4, 4]\n'
                    f'pedestrians = 0\ntraffic = 0\ncars = [{cars}]\n{agents}')
    return path


def test_twelve_agents_in_natural_order_and_folded(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = twelve_cars(tmp_path)
    done = CliRunner().invoke(cli, ["simulate", str(path), "--no-record", "--learned-out",
                                    str(tmp_path / "learned.tlp")])
    assert done.exit_code == 0, done.output
    lines = done.output.splitlines()
    assert "  A0..A11 (12 agents): deliveries 0, law violations 0" in lines
    folded = [x for x in lines if "learned skills 0" in x]
    assert folded == ["  A0..A11 (12 agents): learned skills 0 "
                      f"({tmp_path}/learned-{{agent}}.tlp)"], lines
    data = json.loads(CliRunner().invoke(cli, ["simulate", str(path), "--no-record", "--json",
                                               "--learned-out",
                                               str(tmp_path / "learned.tlp")]).stdout)
    assert list(data["learned"]) == [f"A{k}" for k in range(12)]


def test_natural_order_and_names():
    assert sorted(["A10", "A2", "B1", "A1"], key=natural) == ["A1", "A2", "A10", "B1"]
    assert names_text(["A3", "A0", "A1", "A2", "B7", "C1", "C2", "ME"]) == \
        "A0..A3, B7, C1, C2, ME"


def test_a_cycle_time_of_150_stages_is_folded_and_wrapped(capsys):
    shares = {"world": 2.0, "goals": 1.0}
    shares |= {f"A{k}.{s}": 0.5 + (k == 7) * 3 for k in range(50)
               for s in ("perception", "inference", "executive")}
    shares["bus and waits"] = 21.0
    told = shares_text(shares)
    assert told[:2] == ["world 2.0 %", "goals 1.0 %"] and told[-1] == "bus and waits 21.0 %"
    assert told[2:7] == ["A0.perception 0.5 %", "A0.inference 0.5 %",   # in their order
                         "A7.perception 3.5 %", "A7.inference 3.5 %", "A7.executive 3.5 %"]
    assert told[7] == "145 other stages 72.5 %"
    few = {"world": 10.0, "ME.executive": 20.0, "bus and waits": 70.0}
    assert shares_text(few) == ["world 10.0 %", "ME.executive 20.0 %", "bus and waits 70.0 %"]
    result = {"run": "r", "status": "completed", "cycles": 1, "elapsed_s": 1.0,
              "cycles_per_s": 1.0, "mode": "lockstep", "seed": 1, "failures": [],
              "late_stages": {}, "dead_stages": {}, "stalls": [], "restarts": {},
              "cycle_time": {"ms": 9.0, "shares": shares}, "world_resumes": [],
              "goals_achieved": 0, "goals": [], "law_violations": {}, "achievements": {}}
    summary.echo(result)
    printed = capsys.readouterr().out.splitlines()
    timing = [x for x in printed if x.startswith("  cycle time") or x.startswith("    ")]
    assert 1 < len(timing) and all(len(x) <= 100 for x in timing)
    assert " ".join(x.strip() for x in timing).startswith("cycle time 9.0 ms: world 2.0 %")


def test_the_cycle_time_of_one_agent_stays_on_one_line(capsys):
    """The README's and the tutorial's summaries print it on one line, as before."""
    shares = {"world": 6.7, "goals": 1.8, "ME.perception": 9.9, "ME.inference": 11.8,
              "ME.executive": 16.9, "bus and waits": 52.9}
    summary.echo({"run": "r", "status": "completed", "cycles": 1, "elapsed_s": 1.0,
                  "cycles_per_s": 1.0, "mode": "lockstep", "seed": 1, "failures": [],
                  "late_stages": {}, "dead_stages": {}, "stalls": [], "restarts": {},
                  "cycle_time": {"ms": 11.025, "shares": shares}, "world_resumes": [],
                  "goals_achieved": 0, "goals": [], "law_violations": {}, "achievements": {}})
    assert "  cycle time 11.025 ms: world 6.7 %, goals 1.8 %, ME.perception 9.9 %, " \
           "ME.inference 11.8 %, ME.executive 16.9 %, bus and waits 52.9 %" \
           in capsys.readouterr().out.splitlines()
