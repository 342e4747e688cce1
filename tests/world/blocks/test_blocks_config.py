"""The `[world]` table of a blocks scenario: defaults, and every mistake refused with the key,
the expected and the actual value (docs/scenarios.md, "The Blocks World")."""

from __future__ import annotations

import pytest

from world.blocks import check_config
from world.blocks.config import BlocksConfig, BlockSpec, TableSpec, load_blocks_config
from world.errors import ConfigError


def test_an_empty_table_is_figure_3():
    config = load_blocks_config({})
    assert config == BlocksConfig()
    assert config.towers == (("A", "B", "C"),) and config.table == TableSpec("T", 6, 3.0, 2.0)
    assert config.blocks == (BlockSpec("A"), BlockSpec("B"), BlockSpec("C"))


def test_the_default_table_has_room_for_every_block_side_by_side():
    assert load_blocks_config({"towers": [list("ABCDEFGH")]}).table.columns == 9
    assert load_blocks_config({"towers": [[n] for n in "ABCDEFG"]}).table.columns == 8
    assert load_blocks_config({"towers": [list("ABCDEFGH")], "table": {"columns": 2}}) \
        .table.columns == 2


def test_sizes_offsets_and_holding_are_read():
    config = load_blocks_config({"towers": [["A", "B"], [], ["C"]], "sizes": {"B": [1.5, 0.5]},
                                 "offsets": {"B": 0.25}, "holding": {"ME": "D"},
                                 "block_size": [1.0, 1.0], "resolution": 0.5, "dt": 0.25})
    assert config.block("B") == BlockSpec("B", 1.5, 0.5)
    assert config.block("D") == BlockSpec("D", 1.0, 1.0)
    assert config.towers == (("A", "B"), (), ("C",)) and config.holding == {"ME": "D"}
    assert config.resolution == 0.5 and config.dt == 0.25


BAD = [
    ({"colour": "red"}, "[world]: unknown keys ['colour']"),
    ({"towers": "ABC"}, "[world] towers: expected a list of towers"),
    ({"towers": [["A", 3]]}, "[world] towers[0][1]: expected a block name"),
    ({"towers": [["A", "empty"]]}, "not ['empty', 'floor']"),
    ({"towers": [["floor"]]}, "not ['empty', 'floor']"),
    ({"towers": [["A", "B"], ["B"]]}, "block B appears twice"),
    ({"towers": [["A", "T"]]}, "block T appears twice (or names the table)"),
    ({"towers": [[n] for n in "ABCDEFG"], "table": {"columns": 6}},
     "7 towers on a table of 6 columns"),
    ({"towers": [["A"], ["B"]], "sizes": {"B": [4.5, 1.0]}}, "towers[1]: ['B'] overlaps ['A']"),
    ({"towers": [["A"]], "sizes": {"A": [4.0, 1.0]}}, "towers[0]: A (-2 .. 2 m) hangs over"),
    ({"sizes": {"Z": [1.0, 1.0]}}, "sizes: blocks ['Z'] stand in no tower and no hand"),
    ({"sizes": {"A": [1.0]}}, "sizes.A: expected [width, height] in [0.25, 20] [m]"),
    ({"sizes": {"A": [1.1, 1.0]}}, "sizes.A: expected a multiple of the resolution 0.25"),
    ({"resolution": 0.1}, "resolution: expected a power of two"),
    ({"offsets": {"Z": 1.0}}, "offsets: ['Z'] stand in no tower"),
    ({"offsets": {"B": "left"}}, "offsets.B: expected a number"),
    ({"table": {"legs": 4}}, "table: unknown keys ['legs']"),
    ({"table": {"columns": 0}}, "table.columns: expected an integer in [1, 64], got 0"),
    ({"table": {"name": "empty"}}, "table.name: expected a symbol"),
    ({"towers": [["A"]], "random_towers": 3}, "give towers or random_towers, not both"),
    ({"random_towers": 30}, "random_towers.blocks: expected an integer in [1, 25], got 30"),
    ({"random_towers": {"blocks": 3, "shape": "x"}}, "random_towers: unknown keys ['shape']"),
    ({"dt": 0}, "[world] dt: expected a number in [0.05, 5], got 0"),
    ({"holding": {"ME": "A"}}, "block A appears twice"),
]


@pytest.mark.parametrize("table, message", BAD, ids=[m for _, m in BAD])
def test_a_bad_table_is_refused_naming_the_key(table, message):
    with pytest.raises(ConfigError) as err:
        load_blocks_config(table)
    assert message in str(err.value)


def test_a_block_held_by_an_agent_not_in_the_run_is_refused():
    with pytest.raises(ConfigError, match=r"holding.YOU: not an agent of this run \(agents: ME\)"):
        check_config({"holding": {"YOU": "D"}}, ["ME"])
    check_config({"holding": {"ME": "D"}}, ["ME"])
