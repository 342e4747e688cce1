"""Fixtures for the bus tests: one Python zenoh router per test session on loopback."""

from __future__ import annotations

import uuid
from collections.abc import Iterator
from pathlib import Path

import pytest
from bus_helpers import Stages

from bus.config import BusConfig
from bus.router import RouterProcess, spawn_router


@pytest.fixture(scope="session")
def router() -> Iterator[RouterProcess]:
    with spawn_router() as r:
        yield r


@pytest.fixture
def cfg(router: RouterProcess) -> BusConfig:
    return BusConfig(connect=(router.endpoint,))


@pytest.fixture
def run_id() -> str:
    return "t" + uuid.uuid4().hex[:8]


@pytest.fixture
def stages(cfg: BusConfig, run_id: str, tmp_path: Path) -> Iterator[Stages]:
    s = Stages(cfg, run_id, tmp_path)
    try:
        yield s
    finally:
        s.stop_all()
