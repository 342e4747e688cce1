"""Every file teleo writes reads back (issue 22, seed 000's goals carrying their reasons): the
engine state that `teleo step --save-state` writes is read by `teleo step --state` whatever it
holds: failure reasons naming a long chain of subgoals, conjunctive goals, goal stacks, loop
watches, learned skills. On main a reason over 256 characters made the file unreadable
(``s.json:18:9: string of 269 characters is longer than 256``)."""

from __future__ import annotations

import json
from dataclasses import replace

from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine
from tools.cli import cli
from tools.commands.lang import read_state

from .conftest import BLOCKS, figure3_program
from .test_blocks import act, percepts
from .test_properties import towers

ENGINE = Engine(figure3_program())
LONG = "QUITE-A-LONG-BLOCK-NAME-FOR-A-BLOCK-NOBODY-HAS-SEEN-YET"


@st.composite
def states(draw):
    """An engine state reached by running a random Blocks World problem for some cycles (goal
    stacks, loop watches and learned skills as they come), given a conjunctive goal and
    failure reasons of any length and any characters."""
    support, holding = draw(towers())
    blocks = sorted(support)
    on = [f"(on {a} {b})" for a in blocks for b in blocks if a != b]
    goal = draw(st.sampled_from([*on, *(f"(clear {b})" for b in blocks)]))
    state = ENGINE.add_goal(ENGINE.initial_state(), goal, 2, "g1")
    conj = draw(st.lists(st.sampled_from(on), min_size=1, max_size=4, unique=True)) if on \
        else ["(clear A)"]
    state = ENGINE.add_goal(state, "(and " + " ".join(conj) + ")", 3, "g2")
    for _ in range(draw(st.integers(0, 8))):
        result = ENGINE.cycle(state, percepts(support, holding))
        state = result.state
        for a in result.decision.actions:
            support, holding = act(support, holding, a.to_list())
    reasons = draw(st.lists(st.text(max_size=3000), max_size=3))
    failed = tuple(sorted(zip(["g1", "g2", "p1"], reasons, strict=False)))
    return replace(state, failed=failed)


@settings(max_examples=40, deadline=None)
@given(states())
def test_any_saved_state_reads_back_as_it_was(tmp_path_factory, state):
    path = tmp_path_factory.mktemp("state") / "s.json"
    path.write_text(json.dumps(state.to_dict(), indent=1) + "\n")   # as --save-state writes
    assert read_state(str(path)) == state


def test_step_reads_back_the_state_it_saved_with_a_long_reason(tmp_path):
    """Seed 000's failed goal keeps its reason in the state; the next `teleo step --state`
    reads it (the reason here is over 256 characters: it names the missing block)."""
    seen = tmp_path / "percepts.json"
    seen.write_text(json.dumps(percepts({"A": "T", "B": "T"})))
    first, second = tmp_path / "s1.json", tmp_path / "s2.json"
    runner = CliRunner()
    done = runner.invoke(cli, ["step", str(BLOCKS), "--percepts", str(seen),
                               "--goal", f"(clear {LONG})", "--save-state", str(first)])
    assert done.exit_code == 0, done.output
    reason = json.loads(first.read_text())["failed"]["g1"]
    assert len(reason) > 256 and reason.startswith(f"(clear {LONG}) cannot be achieved")
    again = runner.invoke(cli, ["step", str(BLOCKS), "--percepts", str(seen),
                                "--state", str(first), "--save-state", str(second)])
    assert again.exit_code == 0, again.output
    assert f"failed    (clear {LONG})  -- {reason}" in again.output
    assert json.loads(second.read_text())["failed"] == {"g1": reason}
