"""`teleo render`: from a scenario, from saved snapshots, with readable errors."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner
from PIL import Image

from tools.commands.world import render
from world.driving.config import WorldConfig
from world.driving.simulation import Simulation

SCENARIO = """
[world]
pedestrians = 4
traffic = 2
cars = [{ agent = "ME", street = "SECOND", from = "A", toward = "B" }]
"""


def test_render_a_scenario_to_png(tmp_path: Path) -> None:
    (tmp_path / "s.toml").write_text(SCENARIO)
    result = CliRunner().invoke(render, [str(tmp_path / "s.toml"), "--out",
                                         str(tmp_path / "a.png"), "--steps", "3"])
    assert result.exit_code == 0, result.output
    assert "cycle 3" in result.output
    assert Image.open(tmp_path / "a.png").format == "PNG"


def test_a_scenario_is_drawn_as_it_starts_unless_steps_are_asked_for(tmp_path: Path) -> None:
    """Issue 24, #14: the office robot was captioned "cycle 100, idle, travelled 0.0 m", as
    if it had idled for 50 s, though no agent had run. Now cycle 0, and the line says that no
    agent ran; with --steps the world moved without its agents, and the line says that."""
    office = Path(__file__).resolve().parents[2] / "scenarios" / "office_figure6.toml"
    runner = CliRunner()
    start = runner.invoke(render, [str(office), "--out", str(tmp_path / "o.png")])
    assert start.exit_code == 0, start.output
    assert start.output == (f"{tmp_path / 'o.png'}: 1 frame(s) (the scenario's world as it "
                            "starts; no agent has run)\n")
    (tmp_path / "s.toml").write_text(SCENARIO)
    first = runner.invoke(render, [str(tmp_path / "s.toml"), "--out", str(tmp_path / "a.png")])
    assert first.output == (f"{tmp_path / 'a.png'}: cycle 0 (the scenario's world as it "
                            "starts; no agent has run)\n")
    moved = runner.invoke(render, [str(tmp_path / "s.toml"), "--out", str(tmp_path / "b.gif"),
                                   "--steps", "4"])
    assert moved.output == (f"{tmp_path / 'b.gif'}: 5 frame(s), cycles 0..4 (the world stepped "
                            "4 cycles without its agents: they stood still)\n")
    assert Image.open(tmp_path / "b.gif").n_frames == 5


def test_render_saved_snapshots_to_gif_and_one_cycle(tmp_path: Path) -> None:
    sim = Simulation(WorldConfig(pedestrians=3, traffic=1), seed=1, agents=["ME"])
    lines = []
    for _ in range(4):
        sim.step()
        lines.append(json.dumps(sim.snapshot().to_dict()))
    (tmp_path / "snapshots.jsonl").write_text("\n".join(lines) + "\n")
    runner = CliRunner()
    gif = runner.invoke(render, [str(tmp_path / "snapshots.jsonl"), "--out",
                                 str(tmp_path / "run.gif"), "--scale", "0.8"])
    assert gif.exit_code == 0 and Image.open(tmp_path / "run.gif").n_frames == 4
    png = runner.invoke(render, [str(tmp_path / "snapshots.jsonl"), "--out",
                                 str(tmp_path / "c.png"), "--cycle", "2", "--scale", "1"])
    assert png.exit_code == 0 and "cycle 2" in png.output
    missing = runner.invoke(render, [str(tmp_path / "snapshots.jsonl"), "--out",
                                     str(tmp_path / "c.png"), "--cycle", "99"])
    assert missing.exit_code != 0 and "no snapshot of cycle 99" in missing.output


def test_render_a_run_record(tmp_path: Path) -> None:
    from bus import keys
    from bus.messages import Envelope, WorldState
    from bus.record import message_record
    from tools.records.run_record import RecordWriter

    sim = Simulation(WorldConfig(pedestrians=2, traffic=1), seed=1, agents=["ME"])
    with RecordWriter(tmp_path / "run.mcap", "r1") as rec:
        for t in range(3):
            sim.step()
            msg = WorldState(Envelope(1, "r1", t, "world", 0), sim.snapshot().to_dict(), {}, [])
            rec.add(keys.world_state("r1"), message_record(keys.world_state("r1"), msg))
    result = CliRunner().invoke(render, [str(tmp_path / "run.mcap"), "--out",
                                         str(tmp_path / "last.png"), "--scale", "1"])
    assert result.exit_code == 0, result.output
    assert "cycle 3" in result.output
