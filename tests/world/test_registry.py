"""Worlds as plug-ins (world/registry.py): the built-in worlds come from teleo's own
`teleo.worlds` entry points; a world package found on the path is listed and run like them;
one whose import fails, raises, or names something that is not a Domain is listed with a
one-line reason and never stops the others. The packages here are real distributions (a
.dist-info folder with its entry_points.txt beside real modules) on a real sys.path."""

from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from world import registry
from world.domain import DOMAINS, Domain, get_domain
from world.errors import ConfigError

BUILT_IN = ("blocks", "driving", "office")
ROOT = Path(__file__).resolve().parents[2]
TELEO = [str(Path(sys.executable).parent / "teleo")]

BROKEN = {   # entry point name -> (target, module file text)
    "lava": ("lava_world:DOMAIN", "import no_such_physics_engine\n"),
    "quake": ("quake_world:DOMAIN", "raise RuntimeError('the floor shook\\nline two')\n"),
    "fog": ("fog_world:DOMAIN", "DOMAIN = 'not a domain'\n"),
    "mirror": ("mirror_world:DOMAIN", "from world.blocks import DOMAIN\n"),
}


def _package(folder: Path, dist: str, entries: dict[str, tuple[str, str]]) -> Path:
    """A distribution ``dist`` 1.2.3 in ``folder`` whose modules and entry points are
    ``entries``; returns the folder (to put on sys.path / PYTHONPATH)."""
    info = folder / f"{dist.replace('-', '_')}-1.2.3.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 1.2.3\n")
    lines = [f"{name} = {target}" for name, (target, _) in entries.items()]
    (info / "entry_points.txt").write_text("[teleo.worlds]\n" + "\n".join(lines) + "\n")
    for target, text in entries.values():
        (folder / f"{target.split(':')[0]}.py").write_text(text)
    return folder


@pytest.fixture
def broken(tmp_path, monkeypatch):
    folder = _package(tmp_path / "site", "teleo-world-broken", BROKEN)
    monkeypatch.syspath_prepend(str(folder))
    importlib.invalidate_caches()
    registry.forget()
    yield folder
    registry.forget()


def test_the_built_in_worlds_are_entry_points_of_teleo() -> None:
    found = registry.entries()
    assert {"driving", "blocks", "office"} <= set(DOMAINS)
    for name in ("driving", "blocks", "office"):
        assert found[name].dist == "teleo" and found[name].target == f"world.{name}:DOMAIN"
        assert get_domain(name).name == name


def test_an_unknown_name_is_one_line_naming_the_near_and_the_known_ones() -> None:
    with pytest.raises(ConfigError) as err:
        get_domain("ofice")
    text = str(err.value)
    assert "\n" not in text and "unknown domain 'ofice'" in text
    known = text.split("known: ")[1]
    assert "did you mean 'office'?" in text and all(n in known for n in BUILT_IN)


def test_broken_plugins_are_listed_with_their_reasons_and_the_others_still_load(broken):
    rows = {f.entry.name: f for f in registry.survey(Domain)}
    assert rows["lava"].entry.dist == "teleo-world-broken" and rows["lava"].entry.version == "1.2.3"
    assert rows["lava"].error == ("import of lava_world:DOMAIN failed: ModuleNotFoundError: "
                                  "No module named 'no_such_physics_engine'")
    assert rows["quake"].error == ("import of quake_world:DOMAIN failed: RuntimeError: "
                                   "the floor shook")
    assert rows["fog"].error == "fog_world:DOMAIN is a str, not a world.domain.Domain"
    assert rows["mirror"].error == "mirror_world:DOMAIN is the Domain 'blocks', registered as " \
                                   "'mirror'"
    for name in ("driving", "blocks", "office"):
        assert rows[name].error == "" and rows[name].summary
    with pytest.raises(ConfigError, match=r"^\[world\] domain: world 'quake' "
                                          r"\(teleo-world-broken 1\.2\.3\) failed to load: "):
        get_domain("quake")
    world = get_domain("blocks").create({}, 1, ["ME"])     # the others run as ever
    world.step()
    assert world.snapshot_dict()["cycle"] == 1


def test_a_name_two_packages_claim_goes_to_the_first_and_the_second_is_listed(broken,
                                                                              tmp_path):
    again = _package(tmp_path / "other", "teleo-world-copy",
                     {"lava": ("lava_copy:DOMAIN", "from world.blocks import DOMAIN\n")})
    sys.path.append(str(again))
    try:
        registry.forget()
        rows = [f for f in registry.survey(Domain) if f.entry.name == "lava"]
        assert [f.entry.dist for f in rows] == ["teleo-world-broken", "teleo-world-copy"]
        assert rows[1].error == "name already registered by teleo-world-broken 1.2.3"
    finally:
        sys.path.remove(str(again))


def _teleo(folder: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(folder)}
    return subprocess.run([*TELEO, *args], cwd=folder, env=env, capture_output=True, text=True,
                          timeout=120)


def test_teleo_worlds_and_a_run_with_a_broken_plugin_installed(broken):
    listed = _teleo(broken, "worlds")
    assert listed.returncode == 0 and "Traceback" not in listed.stdout + listed.stderr
    lines = {line.split()[0]: line for line in listed.stdout.splitlines()}
    assert "FAILED: import of lava_world:DOMAIN failed: ModuleNotFoundError" in lines["lava"]
    assert "teleo-world-broken 1.2.3" in lines["lava"] and "the Blocks World" in lines["blocks"]
    assert listed.stdout.splitlines()[-1] == "4 world(s) failed to load; the others run as ever"
    doc = json.loads(_teleo(broken, "worlds", "--json").stdout)
    by_name = {w["name"]: w for w in doc["worlds"]}
    assert by_name["quake"]["error"].endswith("RuntimeError: the floor shook")
    assert by_name["office"] == {"name": "office", "package": "teleo", "version": "0.1.0",
                                 "target": "world.office:DOMAIN", "error": "",
                                 "summary": get_domain("office").summary}
    ran = _teleo(broken, "simulate", str(ROOT / "scenarios" / "blocks_figure3.toml"),
                 "--no-record")
    assert ran.returncode == 0 and "goals achieved: 1 of 1" in ran.stdout, ran.stderr
    refused = _teleo(broken, "check", str(_scenario(broken, "lava")))
    assert refused.returncode == 1 and "Traceback" not in refused.stderr
    assert "world 'lava' (teleo-world-broken 1.2.3) failed to load: import of lava_world" \
           in refused.stdout + refused.stderr


def _scenario(folder: Path, domain: str) -> Path:
    path = folder / f"{domain}.toml"
    path.write_text(f'[run]\nname = "x"\ncycles = 3\n\n[world]\ndomain = "{domain}"\n\n'
                    f'[[agents]]\nid = "ME"\nprogram = "{ROOT / "programs" / "blocks.tlp"}"\n')
    return path


def test_a_checkout_reads_its_own_table_so_a_world_added_there_needs_no_reinstall(tmp_path):
    """teleo's installed entry points are its pyproject.toml table's (`make setup` writes them
    from it; a line added since, by a merge, is not installed yet but is read from the table),
    and a line added to the table is found there."""
    table = {e.name: e.target for e in registry.source_entries()}
    found = {e.name: e.target for e in registry.entries().values() if e.dist == "teleo"}
    assert found == table and set(table) >= {"driving", "blocks", "office"}
    text = registry.CHECKOUT.read_text()
    marker = '[project.entry-points."teleo.worlds"]\n'
    added = tmp_path / "pyproject.toml"
    added.write_text(text.replace(marker, marker + 'sokoban = "world.sokoban:DOMAIN"\n'))
    assert {e.name: e.target for e in registry.source_entries(added)} == {
        **table, "sokoban": "world.sokoban:DOMAIN"}
    other = tmp_path / "other.toml"
    other.write_text(text.replace('name = "teleo"', 'name = "someone-else"'))
    assert registry.source_entries(other) == []
