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


@pytest.fixture
def own_cache(tmp_path, monkeypatch):
    """A cache of the test's own (verdicts, summaries), sharing the session's Verilator
    builds (``sim_build``): what a campaign decides is made again, its builds are not."""
    from irnuc.common.cache import cache_dir

    builds = cache_dir("sim_build")
    root = tmp_path / "cache"
    root.mkdir()
    (root / "sim_build").symlink_to(builds, target_is_directory=True)
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(root))
    return root
