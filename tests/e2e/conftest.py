"""Fixtures of the end-to-end tests."""

from __future__ import annotations

import pytest
from e2e_helpers import Teleo


@pytest.fixture
def teleo(tmp_path) -> Teleo:
    return Teleo(tmp_path)
