"""Shared fixtures of the Python test suite."""

from __future__ import annotations

import pytest

from irnuc import model


@pytest.fixture
def small_cfg():
    """The default preset on a small array, without defects: a fast, clean sensor."""

    def make(**overrides):
        base = {"fpa.active_rows": 12, "fpa.active_cols": 16, "fpa.defects": {}}
        base.update(overrides)
        return model.load_preset("default", overrides=base)

    return make
