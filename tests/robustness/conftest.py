"""Fixtures of the robustness tables."""

from __future__ import annotations

from pathlib import Path

import pytest

from robustness.world import build_world


@pytest.fixture(scope="session")
def world(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Valid and hostile input files shared by the cases (never written by a case)."""
    return build_world(tmp_path_factory.mktemp("robustness"))
