"""The examples in the Blocks World's docstrings run and hold."""

from __future__ import annotations

import doctest

import pytest

import world.blocks.perception
import world.blocks.towers


@pytest.mark.parametrize("module", [world.blocks.perception, world.blocks.towers],
                         ids=lambda m: m.__name__)
def test_docstring_examples(module):
    result = doctest.testmod(module)
    assert result.attempted > 0 and result.failed == 0
