"""One declaration of what an agent's stages start with: the launcher writes it for a shared
process as JSON and the process reads it back; a wrong item is refused naming the item and
the key, before any bus is opened."""

from __future__ import annotations

import subprocess
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from agents.processes.agent_setup import AgentSetup

PATHS = st.none() | st.text(min_size=1, max_size=20)


@given(agent=st.text(min_size=1, max_size=10), program=st.text(min_size=1, max_size=20),
       state=PATHS, learned=PATHS, learned_out=PATHS, swapped=PATHS, solver=st.booleans(),
       mechanism=st.sampled_from(["means-ends", "rogue"]))
def test_the_json_the_launcher_writes_reads_back_the_same(**options) -> None:
    setup = AgentSetup(run="r1", **options)
    assert AgentSetup.from_json("r1", setup.to_json()) == setup
    assert "run" not in setup.to_json()


def test_defaults_are_the_executive_options_defaults() -> None:
    setup = AgentSetup.from_json("r", {"agent": "ME", "program": "p.tlp"})
    assert (setup.solver, setup.mechanism, setup.state, setup.learned) == \
        (True, "means-ends", None, None)
    assert [setup.process(s) for s in ("perception", "executive")] == \
        ["ME.perception", "ME.executive"]


@pytest.mark.parametrize("item, says", [
    ({"program": "p.tlp"}, "agent: expected a non-empty string, got None"),
    ({"agent": "ME", "program": ""}, "program: expected a non-empty string, got ''"),
    ({"agent": "ME", "program": "p", "sovler": False}, "sovler: not an option of an agent"),
    ({"agent": "ME", "program": "p", "solver": "no"}, "solver: expected true or false"),
    ({"agent": "ME", "program": "p", "state": 3}, "state: expected a path or null, got 3"),
    ({"agent": "ME", "program": "p", "mechanism": 7}, "mechanism: expected a name, got 7"),
    (["ME"], "expected a map with 'agent' and 'program', got list"),
])
def test_a_wrong_item_names_its_key(item, says) -> None:
    with pytest.raises(ValueError, match=None) as caught:
        AgentSetup.from_json("r", item)
    assert says in str(caught.value)


def test_the_shared_process_refuses_a_wrong_item_naming_it() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "agents.processes.shared", "--run", "r", "--name", "agents1",
         "--agents", '[{"agent": "A", "program": "a.tlp"}, {"agent": "B"}]'],
        capture_output=True, text=True, timeout=60)
    assert done.returncode != 0
    assert "--agents[1]: program: expected a non-empty string, got None" in done.stderr
