"""`--set KEY=VALUE` on `teleo check`, `simulate` and `launch` (issue 25, "Launch-time
overrides"): a field changed for one run is checked exactly as the same field written in the
file (a hypothesis property over random fields and values), entries of arrays of tables are
named by id, agent or number, a mistake is one line naming the override, and the summary
and the run record say what was applied."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tools.cli import cli
from tools.commands.scenario_check import load_checked
from tools.records.run_record import RunRecord
from world.overrides import (
    STRING_FIELDS,
    Override,
    OverrideError,
    apply_overrides,
    parse_override,
)
from world.run_scenario import ScenarioError, load_scenario

ROOT = Path(__file__).resolve().parents[2]
HOLD = ROOT / "tests" / "e2e" / "fixtures" / "hold_speed.toml"
HOLD_PROGRAM = HOLD.with_name("hold_speed.tlp")
DEMO = ROOT / "scenarios" / "driving_demo.toml"


def toml_text(doc: dict) -> str:
    """A scenario document as TOML (the shapes scenarios use: tables of values, arrays of
    tables; JSON's scalars and lists are TOML's)."""
    def value(v) -> str:
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{k} = {value(x)}" for k, x in v.items()) + " }"
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return json.dumps(v)

    def is_tables(v) -> bool:
        return isinstance(v, dict) or isinstance(v, list) and bool(v) and \
            all(isinstance(e, dict) for e in v)

    lines = [f"{k} = {value(v)}" for k, v in doc.items() if not is_tables(v)]
    for name, table in doc.items():
        for entry in (table if isinstance(table, list) else [table]) if is_tables(table) else ():
            lines.append(f"[[{name}]]" if isinstance(table, list) else f"[{name}]")
            lines += [f"{k} = {value(v)}" for k, v in entry.items()]
    return "\n".join(lines) + "\n"


BASE = {
    "run": {"name": "hold", "cycles": 30, "seed": 3, "deadline": 0.2, "render_every": 10},
    "world": {"grid": [3, 3], "pedestrians": 2, "traffic": 0,
              "cars": [{"agent": "ME", "street": "B", "from": "FIRST", "toward": "SECOND",
                        "along": 20.0}],
              "packages": [{"id": "PACKET1", "address": 3, "street": "SECOND",
                            "owner": "ME"}]},
    "agents": [{"id": "ME", "program": str(HOLD_PROGRAM), "solver": False}],
    "goals": [{"agent": "ME", "goal": "(package-delivered PACKET1)", "priority": 3}],
    "events": [{"at_cycle": 5, "kind": "pedestrian", "ahead_of": "ME", "dist": 30.0}],
}


def write(folder: Path, doc: dict, name: str = "s.toml") -> Path:
    path = folder / name
    path.write_text(toml_text(doc))
    return path


def outcome(path: Path, overrides: tuple[str, ...] = ()):
    """("ok", the scenario's tables) or ("refused", each error without file and override)."""
    try:
        sc, _ = load_checked(path, overrides)
    except ScenarioError as exc:
        rest = []
        for error in exc.errors:
            assert error.startswith(f"{path}: ")
            error = error[len(f"{path}: "):]
            for o in overrides:   # each error the override brings names it
                assert error.startswith(f"--set {o}: "), error
                error = error[len(f"--set {o}: "):]
            rest.append(error)
        return "refused", rest
    return "ok", (sc.run, sc.world, sc.agents, sc.goals, sc.events)


# -- the property: --set is checked exactly as the file ------------------------------------

FIELDS = [("run", "cycles"), ("run", "seed"), ("run", "deadline"), ("run", "render_every"),
          ("run", "goals_respawn"), ("run", "secure"), ("run", "cyclez"),
          ("world", "pedestrians"), ("world", "traffic"), ("world", "speed_limit"),
          ("world", "grid"), ("world", "block_length"), ("world", "dt"),
          ("world", "pedestrianz"), ("goals", "1", "priority"), ("goals", "1", "at_cycle"),
          ("goals", "1", "force"), ("events", "1", "at_cycle"), ("events", "1", "dist"),
          ("agents", "ME", "solver"), ("world", "cars", "ME", "along"),
          ("world", "packages", "PACKET1", "address")]
VALUES = st.one_of(st.integers(-5, 20_000), st.integers(-2**70, 2**70), st.booleans(),
                   st.floats(-1e3, 1e5, allow_nan=False), st.sampled_from(["x", "", "B"]),
                   st.lists(st.integers(-1, 14), max_size=3))


def with_field(doc: dict, key: tuple[str, ...], value) -> dict:
    """``doc`` with the field ``key`` set as a person would write it in the file."""
    doc = json.loads(json.dumps(doc))
    node = doc
    for part in key[:-1]:
        if isinstance(node, list):
            node = next((e for e in node if part in (e.get("id"), e.get("agent"))), None) \
                or node[int(part) - 1]
        else:
            node = node[part]
    node[key[-1]] = value
    return doc


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                  HealthCheck.function_scoped_fixture])
@given(key=st.sampled_from(FIELDS), value=VALUES)
def test_a_set_field_is_checked_exactly_as_the_same_field_in_the_file(tmp_path, key, value):
    assert not {(key[0], key[-1])} & STRING_FIELDS
    base = write(tmp_path, BASE, "base.toml")
    if abs(value) > 2**63 - 1 if isinstance(value, int) else False:
        # the file's reader refuses it naming the key; so does --set
        with pytest.raises(ScenarioError, match="integer out of range"):
            load_checked(base, (f"{'.'.join(key)}={json.dumps(value)}",))
        return
    edited = write(tmp_path, with_field(BASE, key, value), "edited.toml")
    text = f"{'.'.join(key)}={json.dumps(value)}"
    assert outcome(base, (text,)) == outcome(edited)


def test_values_are_toml_and_text_that_is_none_is_a_string():
    def value(text: str):
        return parse_override(text).value

    assert value("world.pedestrians=20") == 20 and value("run.deadline=0.5") == 0.5
    assert value("run.secure=true") is True and value("world.grid=[3, 4]") == [3, 4]
    assert value('world.cars=[{ agent = "ME", street = "B" }]') == [
        {"agent": "ME", "street": "B"}]
    assert value("run.mode=realtime") == "realtime"            # no TOML value: the text
    assert value('run.mode="realtime"') == "realtime"
    assert value("agents.ME.program=programs/x.tlp") == "programs/x.tlp"
    assert value("run.name=2026") == "2026"                    # a field that takes a string
    assert value("run.cycles=abc") == "abc"                    # refused by the check, below
    assert value("run.cycles = 7 ") == 7
    assert value("run.name=a=b") == "a=b"                      # the first = splits


def test_an_absolute_program_path_is_kept_and_a_relative_one_is_read_from_here(tmp_path,
                                                                                monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "mine.tlp").write_text(HOLD_PROGRAM.read_text())
    assert parse_override("agents.ME.program=mine.tlp").value == str(tmp_path / "mine.tlp")
    assert parse_override("agents.ME.program=nope.tlp").value == "nope.tlp"
    sc = load_scenario(HOLD, ["agents.ME.program=mine.tlp"])
    assert sc.agents[0].program == tmp_path / "mine.tlp"


@pytest.mark.parametrize("text, message", [
    ("nokey", "--set nokey: expected KEY=VALUE, e.g. run.cycles=300"),
    ("=3", "--set =3: expected KEY=VALUE"),
    ("world..x=3", "'world..x' is not a key"),
    ("foo.bar=1", "--set foo.bar=1: unknown table 'foo'; expected one of ['run', 'world'"),
    ("run=3", "--set run=3: name a field of [run], e.g. run.cycles=300"),
    ("run.deadline=inf", "--set run.deadline=inf: [run].deadline: expected a finite number"),
    ("world.when=1979-05-27", "expected a string, number or boolean, got the date/time"),
    ("world.x=" + "[" * 40 + "]" * 40, "nested deeper than 32 levels"),
])
def test_a_malformed_override_says_what_is_wrong(text, message):
    with pytest.raises(OverrideError, match=message.replace("[", r"\[").replace(".", r"\.")):
        parse_override(text)


# -- naming entries ---------------------------------------------------------------------------

def test_entries_are_named_by_id_agent_or_number(tmp_path):
    path = write(tmp_path, BASE)
    sc = load_scenario(path, ["agents.ME.program=" + str(HOLD_PROGRAM), "agents.1.solver=true",
                              "goals.1.priority=4", "events.1.dist=12.5",
                              "world.cars.ME.along=30.0", "world.packages.PACKET1.address=5",
                              "world.grid.2=4", "agents.ME.respawn.executive=1"])
    assert sc.agents[0].solver is True and sc.agents[0].max_restarts("executive") == 1
    assert sc.goals[0].priority == 4 and sc.events[0].event["dist"] == 12.5
    assert sc.world["cars"][0]["along"] == 30.0 and sc.world["packages"][0]["address"] == 5
    assert sc.world["grid"] == [3, 4]
    bare = write(tmp_path, {"agents": BASE["agents"]}, "bare.toml")
    made = load_scenario(bare, ["world.pedestrians=0", "run.cycles=5"])  # tables created
    assert made.world == {"pedestrians": 0} and made.run.cycles == 5
    assert BASE["run"]["cycles"] == 30 and "respawn" not in BASE["agents"][0]  # not changed


@pytest.mark.parametrize("text, message", [
    ("agents.YOU.program=x.tlp",
     "--set agents.YOU.program=x.tlp: no entry 'YOU': name one by its id (ME) or its number "
     "(1..1)"),
    ("goals.2.priority=4", "--set goals.2.priority=4: no entry '2': name one by its number "
                           "(1..1)"),
    ("world.cars.YOU.along=3", "no entry 'YOU'"),
    ("run.cycles.x=3", "--set run.cycles.x=3: run.cycles is 30, not a table or an array"),
])
def test_an_override_with_no_place_in_the_scenario_is_refused(tmp_path, text, message):
    path = write(tmp_path, BASE)
    with pytest.raises(ScenarioError) as info:
        load_checked(path, (text,))
    assert info.value.errors == (f"{path}: {message}",) or message in str(info.value)
    bare = write(tmp_path, {"agents": BASE["agents"]}, "bare.toml")
    with pytest.raises(ScenarioError, match=r"the scenario has no \[\[goals\]\] entries"):
        load_checked(bare, ("goals.1.priority=4",))


# -- every error, each naming its override ----------------------------------------------------

def test_every_error_is_reported_and_each_names_the_override_that_brings_it(tmp_path):
    path = write(tmp_path, BASE)
    with pytest.raises(ScenarioError) as info:
        load_checked(path, ("world.pedestrianz=3", "run.cycles=-5", "nokey",
                            "agents.YOU.solver=true", "agents.ME.program=nope.tlp",
                            "world.pedestrians=4"))
    assert info.value.errors == (
        f"{path}: --set nokey: expected KEY=VALUE, e.g. run.cycles=300 or "
        "agents.ME.program=programs/x.tlp",
        f"{path}: --set agents.YOU.solver=true: no entry 'YOU': name one by its id (ME) or "
        "its number (1..1)",
        f"{path}: --set run.cycles=-5: [run].cycles: expected >= 0, got -5",
        f"{path}: --set world.pedestrianz=3: [world] unknown keys ['pedestrianz']; known: "
        "['block_length', 'cars', 'crossing_rate', 'dt', 'ew_streets', 'grid', 'ns_streets', "
        "'packages', 'pedestrians', 'perception_range', 'speed_limit', 'traffic']",
        f"{path}: --set agents.ME.program=nope.tlp: agent ME: program nope.tlp not found")


def test_an_error_only_two_overrides_bring_together_names_both(tmp_path):
    path = write(tmp_path, BASE)
    both = ("world.grid=[2, 3]", "world.packages.PACKET1.address=7")
    for one in both:     # each alone is fine: SECOND has address 7 in a 3 x 3 city
        load_checked(path, (one,))
    with pytest.raises(ScenarioError) as info:
        load_checked(path, both)
    assert info.value.errors == (f"{path}: --set world.grid=[2, 3], --set "
                                 "world.packages.PACKET1.address=7: [world] package PACKET1: "
                                 "no address 7 on SECOND",)
    cars = '[{ agent = "ME", street = "B", from = "FIRST", toward = "SECOND" }]'
    changed = load_checked(path, (f"world.cars={cars}", "world.cars.ME.along=5.0"))[0]
    assert changed.world["cars"] == [{"agent": "ME", "street": "B", "from": "FIRST",
                                      "toward": "SECOND", "along": 5.0}]


def test_an_error_of_the_file_itself_is_not_blamed_on_an_override(tmp_path):
    doc = with_field(BASE, ("run", "render_every"), 0)
    path = write(tmp_path, doc)
    with pytest.raises(ScenarioError) as info:
        load_checked(path, ("run.cycles=-1",))
    assert info.value.errors == (f"{path}: --set run.cycles=-1: [run].cycles: expected >= 0, "
                                 "got -1",                    # in the order of the fields
                                 f"{path}: [run].render_every: expected >= 1, got 0")
    fixed = load_checked(path, ("run.render_every=2",))[0]   # an override may mend the file
    assert fixed.run.render_every == 2 and fixed.overrides == ("run.render_every=2",)


# -- the commands -----------------------------------------------------------------------------

def invoke(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_check_takes_set_and_says_what_it_applied(tmp_path):
    path = write(tmp_path, BASE)
    done = invoke("check", path, "--set", "world.pedestrians=20", "--set", "run.cycles=300")
    assert done.exit_code == 0, done.output
    assert done.output.endswith("1 scripted goals, 1 events; --set world.pedestrians=20, "
                                "run.cycles=300)\n")
    doc = json.loads(invoke("check", "--json", path, "--set", "run.cycles=300").output)
    assert doc["files"][0]["overrides"] == ["run.cycles=300"]
    only_program = invoke("check", HOLD_PROGRAM, "--set", "run.cycles=3")
    assert only_program.exit_code == 2 and "--set changes a scenario's fields" \
        in only_program.output


@pytest.mark.parametrize("command", ["check", "simulate", "launch"])
def test_a_refused_override_is_one_line_naming_it_and_nothing_starts(tmp_path, monkeypatch,
                                                                     command):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = write(tmp_path, BASE)
    done = invoke(command, path, "--set", "world.pedestrianz=3")
    assert done.exit_code == 1 and "Traceback" not in done.output
    lines = [line for line in done.output.splitlines() if line]
    assert lines == [("Error: " if command != "check" else "") +
                     f"{path}: --set world.pedestrianz=3: [world] unknown keys ['pedestrianz']; "
                     "known: ['block_length', 'cars', 'crossing_rate', 'dt', 'ew_streets', "
                     "'grid', 'ns_streets', 'packages', 'pedestrians', 'perception_range', "
                     "'speed_limit', 'traffic']"]
    assert not (tmp_path / "runs").exists()             # no run folder, no process


def test_simulate_applies_set_and_its_summary_and_record_say_so(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = write(tmp_path, BASE)
    done = invoke("simulate", path, "--set", "run.cycles=12", "--set", "world.pedestrians=0",
                  "--summary", tmp_path / "s.json", "--trace", tmp_path / "t.jsonl")
    assert done.exit_code == 0, done.output
    assert done.output.splitlines()[1] == "  --set: run.cycles=12, world.pedestrians=0"
    assert f"summary written to {tmp_path / 's.json'}" in done.output
    summary = json.loads((tmp_path / "s.json").read_text())
    assert summary["overrides"] == ["run.cycles=12", "world.pedestrians=0"]
    assert summary["cycles"] == 12 and len((tmp_path / "t.jsonl").read_text().splitlines()) == 12
    meta = RunRecord(Path(summary["record"])).meta["teleo.run"]
    assert json.loads(meta["overrides"]) == ["run.cycles=12", "world.pedestrians=0"]
    # the world was the changed one: its trace is that of the file with the field edited
    edited = write(tmp_path, with_field(with_field(BASE, ("run", "cycles"), 12),
                                        ("world", "pedestrians"), 0), "edited.toml")
    invoke("simulate", edited, "--no-record", "--trace", tmp_path / "e.jsonl")
    plain = invoke("simulate", path, "--cycles", "12", "--no-record", "--trace",
                   tmp_path / "p.jsonl")
    assert plain.exit_code == 0
    assert (tmp_path / "e.jsonl").read_text() == (tmp_path / "t.jsonl").read_text() != \
        (tmp_path / "p.jsonl").read_text()


ANY = st.recursive(st.one_of(st.integers(-10, 10**6), st.booleans(), st.text(max_size=6),
                             st.floats(-1e6, 1e6, allow_nan=False)),
                   lambda inner: st.lists(inner, max_size=3)
                   | st.dictionaries(st.sampled_from(["id", "agent", "x", "kind"]), inner,
                                     max_size=3), max_leaves=6)
EVERY_FIELD = [*FIELDS, ("run", "name"), ("run", "mode"), ("agents", "1"),
               ("agents", "ME", "id"), ("agents", "ME", "program"), ("agents", "ME", "respawn"),
               ("agents", "ME", "mechanism"), ("goals", "1"), ("goals", "1", "goal"),
               ("goals", "1", "op"), ("goals", "1", "agent"), ("goals", "1", "goal_id"),
               ("events", "1", "kind"), ("events", "1"), ("world", "cars"),
               ("world", "packages"), ("world", "domain")]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                  HealthCheck.function_scoped_fixture])
@given(key=st.sampled_from(EVERY_FIELD), value=ANY)
def test_any_value_in_any_place_is_accepted_or_refused_never_a_crash(tmp_path, key, value):
    """Every table, field and entry of a scenario, given a value of any kind (as a file
    could): the check accepts it or refuses it with ScenarioError lines, and goes on to
    report the rest; nothing else is raised (TypeError, KeyError, AttributeError)."""
    doc, wrong = apply_overrides(BASE, (Override(".".join(key), key, value),))
    assert not wrong
    path = write(tmp_path, doc)
    try:
        load_checked(path)
    except ScenarioError as exc:
        assert exc.errors and all(e.startswith(f"{path}: ") for e in exc.errors)
