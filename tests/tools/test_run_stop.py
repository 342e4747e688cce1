"""What a launch says while its record takes the messages the run sent before its stop
(issue 24, item 7; trial #7: a `teleo stop` of 19 s said nothing): nothing for the first
second, then a line every few seconds with the cycle reached of those the run ran."""

from __future__ import annotations

from types import SimpleNamespace

from tools.launching.run_stop import drain_progress, trace_cycles


def test_a_long_drain_says_how_far_it_has_got(tmp_path, capsys) -> None:
    (tmp_path / "trace.jsonl").write_text("{}\n" * 500 + '{"cycle": 5')  # a partial line
    assert trace_cycles(tmp_path) == 500
    show = drain_progress(tmp_path)
    recorder = SimpleNamespace(last_cycle=None)
    said = []
    for seconds, cycle in ((0.5, None), (1.1, 120), (2.0, 180), (4.2, 320), (5.0, 400)):
        recorder.last_cycle = cycle
        show(recorder, seconds)
        said.append(capsys.readouterr().err)
    line = "record: still writing what the run sent before its stop, cycle {} of 499 ({} s; " \
           "Ctrl-C again leaves the rest out)\n"
    assert said == ["", line.format(120, 1), "", line.format(320, 4), ""]
