"""`teleo why RUN INSTANCE`: why a concept instance is or is not believed at a cycle of a real
run record (`teleo simulate` of seed 000's Figure 3: C on B on A, the goal (clear A))."""

from __future__ import annotations

import json
from itertools import product
from pathlib import Path

import pytest
from click.testing import CliRunner

from tools.cli import cli
from tools.records.run_record import RunRecord, locate

ROOT = Path(__file__).resolve().parents[2]
FIGURE3 = ROOT / "scenarios" / "blocks_figure3.toml"
BLOCKS = ROOT / "programs" / "blocks.tlp"


@pytest.fixture(scope="module")
def run(tmp_path_factory) -> str:
    folder = tmp_path_factory.mktemp("runs")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("TELEO_RUN_DIR", str(folder))
        done = CliRunner().invoke(cli, ["simulate", str(FIGURE3), "--json"])
    assert done.exit_code == 0, done.output
    return str(Path(json.loads(done.stdout)["record"]).parent)


def _why(run: str, *args: str) -> tuple[int, str, str]:
    done = CliRunner().invoke(cli, ["why", run, *args])
    return done.exit_code, done.stdout, done.stderr


def test_a_believed_instance_shows_the_clause_and_what_matched_each_condition(run) -> None:
    code, out, _ = _why(run, "(clear C)", "--cycle", "0")
    assert code == 0
    lines = out.splitlines()
    assert lines[0].startswith("(clear C) at cycle 0 of run ") and lines[0].endswith(
        ": believed")
    assert lines[1].startswith("  clause clear#1 (") and lines[1].endswith(
        "blocks.tlp:24:3) holds with ?b=C:")
    assert lines[2:] == ["    (block C)            <- percept (block C xpos 0 ypos 6 height 2)",
                         "    (not (on ?other C))  <- no belief matches (on ?other C)",
                         "    (not (holding C))    <- no belief matches (holding C)"]


def test_one_not_believed_shows_each_clauses_first_failure_and_what_was_there(run) -> None:
    _, out, _ = _why(run, "(clear A)", "--cycle", "0")
    assert out.splitlines()[0].endswith(": not believed")
    assert "fails at (not (on ?other A))" in out
    assert "but believed: (on B A) (by on#1: (block B xpos 0 ypos 4) (block A xpos 0 ypos 2 " \
        "height 2))" in out
    _, out, _ = _why(run, "(holding C)", "--cycle", "0")
    assert "fails at (hand ?h status C)" in out
    assert "percept seen instead: (hand H1 status empty)" in out
    _, out, _ = _why(run, "(on A B)", "--cycle", "0")
    assert "fails at (= 2 (+ 4 2))" in out and "with ?h = 2, ?y1 = 2, ?y2 = 4" in out
    _, out, _ = _why(run, "(pickupable A T)", "--cycle", "0")    # down to the missing belief
    assert "fails at (clear A)\n    no such belief, because:\n      clause clear#1" in out


def test_by_the_last_cycle_a_is_clear_and_the_json_says_so(run) -> None:
    code, out, _ = _why(run, "(clear A)", "--json")
    report = json.loads(out)
    assert code == 0 and report["cycle"] == 7 and report["believed"] and report["recorded"]
    assert report["clauses"][0]["kind"] == "holds"
    assert report["clauses"][0]["bindings"] == {"?b": "A"}


def test_the_verdict_is_the_runs_own_beliefs_for_every_instance(run) -> None:
    """Every instance of every concept over the run's objects, at every recorded cycle: `why`
    believes exactly what the run's inference recorded."""
    rec = RunRecord(locate(run))
    beliefs = rec.by_cycle("beliefs", "ME")
    names = ["A", "B", "C", "T"]
    concepts = {"on": 2, "ontable": 2, "holding": 1, "hand-empty": 0, "clear": 1,
                "unstackable": 2, "stackable": 2, "above": 2}
    for cycle in (0, 2, 5):
        held = {tuple(b) for b in beliefs[cycle]["beliefs"]}
        for pred, n in concepts.items():
            for args in product(names, repeat=n):
                text = f"({' '.join((pred, *args))})"
                code, out, err = _why(run, text, "--cycle", str(cycle), "--json")
                assert code == 0, err
                report = json.loads(out)
                assert report["believed"] == ((pred, *args) in held), (cycle, text)
                assert report["recorded"] == report["believed"]
                holds = [c for c in report["clauses"] if c["kind"] == "holds"]
                assert bool(holds) == report["believed"], (cycle, text)


def test_bad_input_is_one_line(run, tmp_path) -> None:
    for args, said in (
            (["(clearx A)"], "Error: concept instance (clearx A): undefined concept 'clearx'"),
            (["(clear A"], "Error: concept instance '(clear A': column 1: '(' is never closed"),
            (["(clear A B)"], "Error: concept instance (clear A B): concept clear takes 1 "
                              "argument(s), got 2"),
            (["(and (clear A) (clear B))"], "expected one concept instance such as (clear A)"),
            (["(clear A)", "--cycle", "99"], "no percepts of ME at cycle 99; recorded cycles "
                                             "0..7"),
            (["(clear A)", "--agent", "X"], "has no agent 'X'; agents: ME")):
        code, out, err = _why(run, *args)
        assert code == 1 and out == "" and len(err.splitlines()) == 1, (args, err)
        assert said in err, (args, err)
    code, _, err = _why(str(tmp_path), "(clear A)")
    assert code == 1 and len(err.splitlines()) == 1 and "no run record here" in err
    bad = tmp_path / "bad.tlp"
    bad.write_text("(concepts ((on ?a) :relations ((nothing ?a)))")
    code, _, err = _why(run, "(on A)", "--program", str(bad))
    assert code == 1 and len(err.splitlines()) == 1 and err.startswith(f"Error: {bad}:")


def test_another_program_file_is_read_with_program(run, tmp_path) -> None:
    """--program: the file given, not the scenario's (here one whose clear ignores the hand);
    the recorded beliefs then disagree, and the text says so."""
    other = tmp_path / "other.tlp"
    other.write_text(BLOCKS.read_text().replace(
        ":relations ((not (on ?other ?b)) (not (holding ?b))))",
        ":relations ((not (on ?other ?b))))"))
    code, out, _ = _why(run, "(clear C)", "--cycle", "2", "--program", str(other))  # held
    assert code == 0 and ": believed" in out.splitlines()[0] and str(other) in out
    assert "note: the run's recorded beliefs say not believed" in out


def test_a_fact_an_scs_body_asserted_is_believed_from_the_world_model(tmp_path, monkeypatch):
    """errands.tlp's body asserts (on-route ME) as the route begins (seed 002's world model);
    a simulate record holds it in the previous decision, which `why` reads as the view does."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    done = CliRunner().invoke(cli, ["simulate", "errands_demo", "--cycles", "12", "--json"])
    assert done.exit_code == 0, done.output
    errands = str(Path(json.loads(done.stdout)["record"]).parent)
    report = json.loads(_why(errands, "(on-route ME)", "--cycle", "10", "--json")[1])
    assert report["believed"] and report["asserted"] and report["recorded"]
    _, out, _ = _why(errands, "(on-route ME)", "--cycle", "0")
    assert out.splitlines()[1:] == ["  no clause defines it (a predicate only SCS bodies assert)"]
