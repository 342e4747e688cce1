"""Pictures of every domain (issue 12, item 13): PNG or JPEG stills and GIF runs by suffix,
any other suffix refused before anything is drawn or run, a scale bar and a key in each, and
`teleo render SCENARIO` with the scenario's own seed."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner
from PIL import Image

from tools.cli import cli
from tools.commands.scenario_check import load_checked
from tools.commands.simulate import simulate
from tools.commands.world import load_snapshots
from world.domain import get_domain
from world.errors import WorldError
from world.pictures import nice_length, picture_format

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = {"driving": "driving_demo.toml", "blocks": "blocks_figure3.toml",
             "office": "office_errand.toml"}


@pytest.fixture(scope="module")
def runs() -> dict[str, list[dict]]:
    out = {}
    for domain, name in SCENARIOS.items():
        scenario, _ = load_checked(ROOT / "scenarios" / name)
        run = simulate(scenario, cycles=12, keep_every=4)
        out[domain] = run.snapshots + [run.final]
    return out


@pytest.mark.parametrize("domain", sorted(SCENARIOS))
def test_each_domain_writes_png_jpeg_and_gif_by_suffix(runs, domain, tmp_path):
    render = get_domain(domain).render
    for name, fmt in (("a.png", "PNG"), ("b.jpg", "JPEG"), ("c.jpeg", "JPEG"), ("d.gif", "GIF")):
        render(runs[domain], tmp_path / name, "ME")
        with Image.open(tmp_path / name) as img:
            assert img.format == fmt, name
    with Image.open(tmp_path / "d.gif") as img:
        assert img.n_frames == len(runs[domain])
    with pytest.raises(WorldError, match="expected a picture file ending in"):
        render(runs[domain], tmp_path / "e.bmp", "ME")
    assert not (tmp_path / "e.bmp").exists()


@pytest.mark.parametrize("domain", sorted(SCENARIOS))
def test_each_domains_still_has_a_scale_bar_and_a_key(runs, domain, tmp_path):
    get_domain(domain).render(runs[domain], tmp_path / "a.png", "ME")
    with Image.open(tmp_path / "a.png") as img:
        rgb = img.convert("RGB")
        bar = [rgb.getpixel((x, rgb.height - 14)) for x in range(12, 60)]
        assert bar.count((20, 20, 20)) > 30, domain          # the bar's line, bottom left
        legend = rgb.crop((rgb.width - 200, 0, rgb.width, rgb.height))
        assert (250, 250, 246) in {c for _, c in legend.getcolors(1 << 16)}   # the key panel


def test_scale_bars_have_round_lengths():
    assert [nice_length(m) for m in (0.3, 1, 4.9, 7, 99, 160)] == [0.2, 1, 2, 5, 50, 100]


@pytest.mark.parametrize("command", ["render", "simulate", "launch"])
def test_an_unknown_picture_suffix_is_refused_before_anything_runs(tmp_path, command):
    scenario = str(ROOT / "scenarios" / "driving_demo.toml")
    args = {"render": [scenario, "--out", str(tmp_path / "x.bmp")],
            "simulate": [scenario, "--render", str(tmp_path / "x.bmp")],
            "launch": [scenario, "--render", str(tmp_path / "x.bmp")]}[command]
    result = CliRunner().invoke(cli, [command, *args])
    assert result.exit_code == 1
    assert "x.bmp: expected a picture file ending in .png or .jpg (one cycle) or .gif" \
        in result.output
    assert not (tmp_path / "x.bmp").exists()
    assert "processes" not in result.output and "cycles" not in result.output   # nothing ran
    with pytest.raises(WorldError):
        picture_format("run.webp")


def test_render_of_a_scenario_uses_the_scenarios_seed():
    demo = ROOT / "scenarios" / "driving_demo.toml"             # [run] seed = 7
    own = load_snapshots(demo, steps=0)[0]
    assert own == load_snapshots(demo, steps=0, seed=7)[0]
    assert own != load_snapshots(demo, steps=0, seed=1)[0]      # pedestrians placed otherwise
