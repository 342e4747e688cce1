"""The web view's server and model on a run record (no bus): the page and its scripts come
from the package (nothing from the internet), frames and status are served as JSON and as
server-sent events, past cycles can be asked for, and a domain the page cannot draw gets
the domain's own PNG."""

from __future__ import annotations

import json
import threading
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from bus import keys
from tools.commands.scenario_check import load_checked
from tools.commands.simulate import simulate
from tools.records.program_graph import program_graph
from tools.records.run_record import RecordWriter, RunRecord
from tools.records.run_recorders import SimRecorder
from tools.records.tree import decision_tree, to_json
from tools.view import scene
from tools.view.feeds import load_file
from tools.view.model import ViewModel
from tools.view.server import STATIC, ViewServer

ROOT = Path(__file__).resolve().parents[2]
HOLD_SPEED = ROOT / "tests" / "e2e" / "fixtures" / "hold_speed.toml"


@pytest.fixture(scope="module")
def record(tmp_path_factory) -> Path:
    """A 30-cycle driving run recorded by simulate."""
    path = tmp_path_factory.mktemp("view") / "record.mcap"
    scenario, _ = load_checked(HOLD_SPEED)
    with RecordWriter(path, "hold-1") as writer:
        simulate(scenario, recorder=SimRecorder(writer, "hold-1"))
    return path


@pytest.fixture
def served(record):
    model = ViewModel()
    load_file(model, record)
    server = ViewServer(model, 0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield server.url, model
    finally:
        server.closing = True
        server.shutdown()
        server.server_close()


def _get(url: str) -> tuple[str, bytes]:
    with urllib.request.urlopen(url, timeout=30) as r:
        return r.headers["Content-Type"], r.read()


def test_the_page_is_served_from_the_package_with_nothing_from_the_internet(served):
    url, _ = served
    ctype, html = _get(url)
    assert ctype.startswith("text/html") and b'<script src="/view.js">' in html
    for name in ("view.js", "panel.js", "world.js", "view.css"):
        _, body = _get(url + name)
        assert body == (STATIC / name).read_bytes()
    for path in STATIC.iterdir():
        text = path.read_text()
        assert "http://" not in text and "https://" not in text and "//cdn" not in text, path


def test_frames_hold_the_world_and_each_agents_decision_tree(served, record):
    url, model = served
    _, body = _get(url + "api/frame?cycle=12")
    frame = json.loads(body)
    decision = RunRecord(record).by_cycle("intention", "ME")[12]["decision"]
    assert frame["cycle"] == 12 and frame["world"]["cycle"] == 12
    assert "config" not in frame["world"]                      # the static part is in the map
    me = frame["agents"]["ME"]
    assert me["goals"] == decision["goals"] and me["actions"] == decision["actions"]
    assert me["tree"] == to_json(decision_tree(decision, "ME, cycle 12"))
    assert me["self"]["speed"] == pytest.approx(frame["world"]["cars"][0]["speed"], abs=0.01)
    car = frame["world"]["cars"][0]
    trail = frame["trails"]["ME"]   # a point each time the car has moved 0.5 m
    assert abs(trail[-1][0] - car["x"]) + abs(trail[-1][1] - car["y"]) < 0.5
    newest = json.loads(_get(url + "api/frame")[1])
    assert newest["cycle"] == 29
    with pytest.raises(urllib.error.HTTPError, match="404"):
        _get(url + "api/frame?cycle=999")
    for bad in ("api/frame?cycle=x", "api/render.png?cycle=x"):
        with pytest.raises(urllib.error.HTTPError, match="400"):
            _get(url + bad)


def test_the_map_and_status(served):
    url, _ = served
    city = json.loads(_get(url + "api/map")[1])
    assert city["domain"] == "driving" and city["drawn"]
    assert len(city["segments"]) == 12 and city["buildings"]           # a 3 x 3 grid
    status = json.loads(_get(url + "api/status")[1])
    assert (status["first"], status["last"]) == (0, 29)
    assert {p["name"] for p in status["processes"]} == {"world", "ME.perception",
                                                         "ME.inference", "ME.executive"}
    assert status["goals"]["ME"]["g1"][0]["cycle"] == 0


def test_events_push_a_frame_and_the_status(served):
    url, _ = served
    with urllib.request.urlopen(url + "events", timeout=30) as stream:
        assert stream.headers["Content-Type"] == "text/event-stream"
        names, datas = [], []
        while len(datas) < 2:
            line = stream.readline().decode().strip()
            if line.startswith("event: "):
                names.append(line[7:])
            elif line.startswith("data: "):
                datas.append(json.loads(line[6:]))
    assert names == ["frame", "status"]
    assert datas[0]["cycle"] == 29 and datas[1]["last"] == 29


def test_a_domain_the_page_cannot_draw_gets_its_own_picture(served):
    url, model = served
    png = _get(url + "api/render.png?cycle=20")
    assert png[0] == "image/png" and png[1][:4] == b"\x89PNG"
    snap = {"domain": "blocks", "cycle": 0, "time": 0.0, "table": {"columns": 3}, "blocks": []}
    static, moving = scene.split(snap)
    assert static == {"table": {"columns": 3}} and "table" not in moving
    assert scene.map_of(snap)["drawn"] and not scene.map_of({**snap, "domain": "office"})["drawn"]


def test_the_header_links_the_agents_program_as_a_graph(served):
    """The view serves `teleo graph`'s picture of the shown agent's program (issue 34)."""
    url, model = served
    _, html = _get(url)
    assert b'<a id="graph" href="/api/graph.svg"' in html
    assert b'$("graph").href = "/api/graph.svg?agent="' in (STATIC / "view.js").read_bytes()
    ctype, svg = _get(url + "api/graph.svg?agent=ME")
    program, source = model.programs.get("ME")
    assert ctype == "image/svg+xml" and svg.startswith(b"<svg ") and source.encode() in svg
    assert svg.count(b'<g class="node ') == len(program_graph(program).nodes)
    assert _get(url + "api/graph.svg")[1] == svg          # the first agent by default
    empty = ViewServer(ViewModel(), 0)                     # no agent yet: said, not drawn
    thread = threading.Thread(target=empty.serve_forever, daemon=True)
    thread.start()
    try:
        with pytest.raises(urllib.error.HTTPError) as nothing:
            _get(empty.url + "api/graph.svg")
        assert nothing.value.code == 404 and nothing.value.read() == b"no agent yet\n"
    finally:
        empty.shutdown()
        empty.server_close()


def test_a_model_follows_one_run_only(record):
    model = ViewModel(run="someone-else")
    load_file(model, record)
    assert model.frame() is None and model.status(0)["last"] is None


def test_the_office_floor_is_the_domains_own_picture(tmp_path) -> None:
    scenario, _ = load_checked(ROOT / "scenarios" / "office_errand.toml")
    path = tmp_path / "office.mcap"
    with RecordWriter(path, "office-1") as writer:
        simulate(scenario, cycles=12, recorder=SimRecorder(writer, "office-1"))
    model = ViewModel()
    load_file(model, path)
    assert model.map["domain"] == "office" and not model.map["drawn"]
    assert "config" not in model.frame(11)["world"]
    assert scene.render_png(model.snapshots_for_render(11), "ME")[:4] == b"\x89PNG"
    for cycle in range(12):   # issue 31, N17: the picture's caption at the cycle shown
        shown = model.snapshots_for_render(cycle)[-1]
        frame = model.frame(cycle)
        assert (shown["cycle"], shown["time"]) == (frame["cycle"], frame["time"])


def _cycle(model: ViewModel, cycle: int, goals: list[dict]) -> None:
    """One cycle of a blocks run fed by hand: the world state and ME's intention."""
    env = {"v": 1, "run": "hand-1", "cycle": cycle, "sender": "test", "sent_ns": 0}
    snap = {"domain": "blocks", "cycle": cycle, "time": cycle / 10, "table": {"columns": 3},
            "blocks": []}
    model.add(keys.world_state("hand-1"), {"kind": "WorldState", "env": env, "snapshot": snap})
    decision = {"cycle": cycle, "goals": goals, "goal_id": "", "path": [], "resources": [],
                "actions": [], "parallel": [], "why": []}
    model.add(keys.intention("hand-1", "ME"), {"kind": "Intention", "env": env,
                                               "agent": "ME", "decision": decision})


def test_a_failed_goal_stays_in_the_goal_table_of_every_later_cycle() -> None:
    model = ViewModel()
    goal = {"id": "g1", "goal": "(on A B)", "priority": 5, "bindings": {}, "instance": "(on A B)"}
    for cycle in range(3):
        _cycle(model, cycle, [{**goal, "status": "suspended", "note": "waits"}])
    _cycle(model, 3, [{**goal, "status": "failed", "note": "(on A B): no plan"}])
    for cycle in (4, 5):
        _cycle(model, cycle, [])   # the executive has dropped it
    assert [g["status"] for g in model.frame(2)["agents"]["ME"]["goals"]] == ["suspended"]
    assert model.frame(3)["agents"]["ME"]["goals"][0]["status"] == "failed"
    for cycle in (4, 5):
        (row,) = model.frame(cycle)["agents"]["ME"]["goals"]
        assert (row["id"], row["status"], row["failed_at"]) == ("g1", "failed", 3)
        assert row["note"] == "(on A B): no plan"


def test_the_run_state_says_live_ended_or_record(record) -> None:
    model = ViewModel()
    assert model.status(0)["state"] == "waiting"
    _cycle(model, 0, [])
    assert model.status(0)["state"] == "live"          # sending, no liveliness tokens
    model.last_message -= 60
    assert model.status(0)["state"] == "ended"         # a replay played to its end
    model.set_presence(frozenset({"world", "ME.executive"}), {"world": 1, "ME.executive": 1})
    assert model.status(0)["state"] == "live"
    model.set_presence(frozenset(), {"world": 1, "ME.executive": 1})
    status = model.status(0)
    assert (status["state"], status["state_note"]) == ("ended", "no process of the run is "
                                                                 "up any more")
    recorded = ViewModel()
    load_file(recorded, record)
    assert recorded.status(0)["state"] == "record"


def test_a_frame_of_a_record_has_the_beliefs_panel(served) -> None:
    url, _ = served
    why = json.loads(_get(url + "api/frame?cycle=12")[1])["agents"]["ME"]["why"]
    assert why["program"].endswith("hold_speed.tlp") and why["warning"] == ""
    assert why["count"] == len(why["beliefs"]) > 0


def test_malformed_percepts_beliefs_or_paths_get_a_sentence_not_a_dead_page(record) -> None:
    model = ViewModel()
    load_file(model, record)
    env = {"v": 1, "run": "hold-1", "cycle": 5, "sender": "test", "sent_ns": 0}
    bad = [("percepts", {"kind": "Percepts", "percepts": [["man"], [1, 2]], "memory": []}),
           ("beliefs", {"kind": "Beliefs", "beliefs": [[], 7]}),
           ("intention", {"kind": "Intention", "decision": {
               "goals": [{"id": "p1", "status": "active", "instance": "(((("}],
               "path": ["x", {"where": 5, "bindings": []}], "parallel": 3}})]
    for kind, body in bad:
        model.add(f"teleo/hold-1/agent/ME/{kind}", {**body, "env": env, "agent": "ME"})
        why = model.frame(5)["agents"]["ME"]["why"]
        assert why["error"] or why["warning"] or why["goals"][0]["note"], (kind, why)
    assert "do not read" in model.frame(5)["agents"]["ME"]["why"]["error"]


def test_the_program_check_agrees_with_a_run_whose_scs_bodies_assert_facts(tmp_path) -> None:
    """errands.tlp's bodies assert facts (seed 002's world model): a simulate record echoes
    no agent memory, so the check infers with the model the previous decision held."""
    scenario, _ = load_checked(ROOT / "scenarios" / "errands_demo.toml")
    path = tmp_path / "errands.mcap"
    with RecordWriter(path, "errands-1", {"scenario": str(scenario.path)}) as writer:
        simulate(scenario, cycles=300, recorder=SimRecorder(writer, "errands-1"))
    model = ViewModel()
    load_file(model, path)
    panels = [model.frame(c)["agents"]["ME"]["why"] for c in range(0, 300, 3)]
    assert all(p["program"].endswith("errands.tlp") for p in panels)
    assert [p["warning"] for p in panels if p["warning"]] == []
    assert any(b.startswith("(served ME ") for p in panels for b in p["beliefs"])


def test_an_intention_whose_decision_is_no_map_is_refused_and_the_cycle_still_shown() -> None:
    model = ViewModel()
    _cycle(model, 0, [])
    env = {"v": 1, "run": "hand-1", "cycle": 0, "sender": "test", "sent_ns": 0}
    with pytest.raises(TypeError, match="Intention.decision: expected a map, got list"):
        model.add(keys.intention("hand-1", "ME"), {"kind": "Intention", "env": env,
                                                   "agent": "ME", "decision": [1, 2]})
    assert model.frame(0)["agents"]["ME"]["goals"] == []   # the earlier decision stays
