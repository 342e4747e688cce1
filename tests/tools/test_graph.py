"""`teleo graph PROGRAM`: a program's goals, skills and concepts as a hierarchy (SVG, PNG,
JSON), checked against the program the loader reads; and the graph of a run's processes and
keys drawn from bus/security.py's grants (the live side: tests/e2e/test_graph_live.py)."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

from click.testing import CliRunner
from PIL import Image

from agents.lang import load_program
from bus import keys
from bus.security import grants
from tools.cli import cli
from tools.records.drawing import NODE_H, layout
from tools.records.program_graph import program_graph
from tools.records.run_graph import matches, run_graph

ROOT = Path(__file__).resolve().parents[2]
BLOCKS = ROOT / "programs" / "blocks.tlp"
DRIVING = ROOT / "programs" / "driving.tlp"
ERRANDS = ROOT / "programs" / "errands.tlp"


def _graph(*args: str) -> dict:
    done = CliRunner().invoke(cli, ["graph", *args, "--json"])
    assert done.exit_code == 0, done.output
    return json.loads(done.stdout)


def _edges(g: dict) -> set[tuple[str, str]]:
    return {(e["from"], e["to"]) for e in g["edges"]}


def test_concepts_point_to_what_they_are_defined_from_and_primitive_skills_are_marked() -> None:
    g = _graph(str(BLOCKS))
    kinds = {n["id"]: n["kind"] for n in g["nodes"]}
    program = load_program(str(BLOCKS))
    assert {i for i, k in kinds.items() if k in ("concept", "percept-concept")} == \
        {f"concept:{p}" for p in program.concepts}
    assert {i for i, k in kinds.items() if k == "primitive"} == \
        {f"skill:{s.name}" for s in program.skills}            # blocks' skills all act
    assert kinds["concept:on"] == "percept-concept" and kinds["concept:clear"] == "concept"
    expected = {(f"concept:{p}", f"concept:{r.pred}", r.negated) for p, cs in
                program.concepts.items() for c in cs for r in c.relations}
    assert {(e["from"], e["to"], e["dashed"]) for e in g["edges"]} == expected
    assert ("concept:clear", "concept:on", True) in expected   # (not (on ?other ?b)): dashed


def test_goals_point_to_their_skills_and_skills_to_their_subgoals_skills() -> None:
    g = _graph(str(DRIVING))
    program = load_program(str(DRIVING))
    edges = _edges(g)
    assert len(program.goals) == 2
    for k, goal in enumerate(program.goals, 1):
        skills = program.skills_for(goal.literal.pred)
        assert skills and {(f"goal:p{k}", f"skill:{s.name}") for s in skills} <= edges
    below = [(s, sub) for s in program.skills for sub in s.subgoals]
    assert below, "driving.tlp has nonprimitive skills"
    for s, sub in below:
        targets = {f"skill:{t.name}" for t in program.skills_for(sub.pred)} or \
            {f"concept:{sub.pred}"}
        assert {(f"skill:{s.name}", t) for t in targets} <= edges
    assert {n["kind"] for n in g["nodes"]} >= {"goal", "skill", "primitive", "concept"}


def test_an_scs_body_is_drawn_as_its_steps_down_to_its_subgoals_skills() -> None:
    g = _graph(str(ERRANDS))
    nodes = {n["id"]: n for n in g["nodes"]}
    body = [i for i, n in nodes.items() if n["kind"] == "body"]
    assert body == ["skill:errands-done#1"]
    out: dict[str, set[str]] = {}
    for a, b in _edges(g):
        out.setdefault(a, set()).add(b)
    reached, todo = set(), [body[0]]
    while todo:  # everything below the body's skill
        for n in out.get(todo.pop(), ()):
            if n not in reached:
                reached.add(n)
                todo.append(n)
    labels = {nodes[n]["label"] for n in reached if nodes[n]["kind"] == "step"}
    assert {"do*", "repeat", "do-first", "do-best", "(package-delivered ?p)"} <= labels
    delivering = {f"skill:{s.name}" for s in
                  load_program(str(ERRANDS)).skills_for("package-delivered")}
    assert delivering and delivering <= reached


def test_the_picture_is_svg_or_png_with_a_box_for_each_node(tmp_path) -> None:
    svg, png = tmp_path / "deep" / "blocks.svg", tmp_path / "blocks.png"
    for out in (svg, png):
        done = CliRunner().invoke(cli, ["graph", str(BLOCKS), "--out", str(out)])
        assert done.exit_code == 0, done.output
        assert done.stdout == f"{out}: 17 nodes, 13 edges\n"
    root = ET.fromstring(svg.read_text())
    ns = "{http://www.w3.org/2000/svg}"
    boxes = [g for g in root.iter(f"{ns}g") if "node" in g.get("class", "").split()]
    assert len(boxes) == 17 and {b.get("id") for b in boxes} >= {"concept:clear", "skill:clear#1"}
    assert len([g for g in root.iter(f"{ns}g") if g.get("class") == "edge"]) == 13
    with Image.open(png) as img:
        assert img.format == "PNG" and img.width > 200 and img.height > 3 * NODE_H


def test_layers_go_down_the_hierarchy_and_boxes_never_overlap() -> None:
    g = program_graph(load_program(str(DRIVING)))
    place, width, height = layout(g)
    for e in g.edges:
        if e.src != e.dst and not (g.nodes[e.src].kind == g.nodes[e.dst].kind == "concept"
                                   and place[e.dst][1] <= place[e.src][1]):
            assert place[e.src][1] < place[e.dst][1], e  # parents above (a cycle aside)
    rows: dict[float, list] = {}
    for x, y, w in place.values():
        rows.setdefault(y, []).append((x, w))
        assert 0 <= x and x + w <= width and y + NODE_H <= height
    for boxes in rows.values():
        boxes.sort()
        assert all(a[0] + a[1] < b[0] for a, b in zip(boxes, boxes[1:], strict=False))
    skills_bottom = max(place[n][1] for n in g.nodes if g.nodes[n].kind not in
                        ("concept", "percept-concept"))
    assert min(place[n][1] for n in g.nodes if g.nodes[n].kind.endswith("concept")) > \
        skills_bottom                            # the concepts in rows of their own, below


def test_a_scenario_names_its_agents_program() -> None:
    g = _graph("blocks_figure3", "--agent", "ME")
    assert _edges(g) == _edges(_graph(str(BLOCKS)))
    done = CliRunner().invoke(cli, ["graph", "blocks_figure3", "--agent", "NOBODY", "--json"])
    assert done.exit_code == 2 and "has no agent 'NOBODY'; agents: ME" in done.output


def test_a_bad_program_is_the_loaders_one_line_error(tmp_path) -> None:
    bad = tmp_path / "bad.tlp"
    bad.write_text("(concepts\n  ((on ?a ?b) :percepts ((block ?a)))\n  ((clear ?x) :relations "
                   "((nothing ?x)))\n")
    done = CliRunner().invoke(cli, ["graph", str(bad), "--out", str(tmp_path / "x.svg")])
    assert done.exit_code == 1 and not (tmp_path / "x.svg").exists()
    assert len(done.stderr.splitlines()) == 1 and done.stderr.startswith(f"Error: {bad}:"), \
        done.stderr
    line, col = done.stderr.split(f"{bad}:")[1].split(":")[:2]
    assert line.isdigit() and col.isdigit()


def test_bad_command_lines_say_what_is_wrong(tmp_path) -> None:
    for args, said in ((["graph"], "name a PROGRAM or --run RUN"),
                       (["graph", str(BLOCKS)], "name --out F.svg|F.png, or --json"),
                       (["graph", str(BLOCKS), "--run", "r"], "name a PROGRAM or --run RUN"),
                       (["graph", str(BLOCKS), "--out", str(tmp_path / "x.gif")],
                        "expected a graph file ending in .svg or .png")):
        done = CliRunner().invoke(cli, args)
        assert done.exit_code in (1, 2) and said in done.output, (args, done.output)


def test_a_runs_graph_draws_the_keys_the_grants_give_each_process() -> None:
    procs = {"world", "goals", "ME.perception", "ME.inference", "ME.executive",
             keys.RECORDER}
    g = run_graph("r1", procs)
    edges = {(e.src, e.dst) for e in g.edges}
    assert {n.label for n in g.nodes.values() if n.kind == "process"} == procs
    for stage in ("perception", "inference", "executive"):   # the ACL's word, drawn
        for k in grants("r1", f"ME.{stage}")["put"]:
            if "/stats/" not in k:
                assert (f"proc:ME.{stage}", f"key:{k}") in edges
        for k in grants("r1", f"ME.{stage}")["sub"]:
            assert (f"key:{k}", f"proc:ME.{stage}") in edges
    published = {e.dst for e in g.edges if e.src.startswith("proc:")}
    assert {e.src for e in g.edges if e.dst == f"proc:{keys.RECORDER}"} == published
    assert (f"key:{keys.actions('r1', 'ME')}", "proc:world") in edges   # the clock's input
    assert (f"key:{keys.goal_list('r1', 'ME')}", "proc:ME.executive") in edges
    assert not any("/stats/" in n for n in g.nodes)
    assert any("/stats/" in n for n in run_graph("r1", procs, stats=True).nodes)
    assert matches("teleo/r1/**", "teleo/r1/agent/ME/percepts")
    assert not matches("teleo/r1/agent/*/goals", "teleo/r1/agent/ME/percepts")


def test_a_run_that_has_ended_is_drawn_from_its_records_senders(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    done = CliRunner().invoke(cli, ["simulate", "blocks_figure3", "--json"])
    assert done.exit_code == 0, done.output
    folder = Path(json.loads(done.stdout)["record"]).parent
    g = _graph("--run", folder.name)                  # a run id under the runs folder
    run = folder.name
    assert g["title"] == f"run {run} (record): processes and keys"
    published = {(e["from"], e["to"]) for e in g["edges"] if e["label"] == "publishes"}
    assert published == {(f"proc:{p}", f"key:teleo/{run}/{k}") for p, k in (
        ("world", "world/state"), ("world", "world/static"),
        ("ME.perception", "agent/ME/percepts"), ("ME.inference", "agent/ME/beliefs"),
        ("ME.executive", "agent/ME/actions"),
        ("ME.executive", "agent/ME/intention"), ("goals", "agent/ME/goal-list"))}
    assert (f"key:teleo/{run}/agent/ME/actions", "proc:world") in _edges(g)
    nothing = CliRunner().invoke(cli, ["graph", "--run", "no-such-run", "--json"])
    assert nothing.exit_code == 1 and len(nothing.stderr.splitlines()) == 1
    assert "no run 'no-such-run'" in nothing.stderr and "nor is there a record" in nothing.stderr
