"""The outcome table (``outcomes.py``): one test per row."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from robustness.harness import run_cli
from robustness.outcomes import OUTCOMES


def _files(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def test_outcome_synth_cache_carries_the_asked_name(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    from irnuc.cosim import synth
    from irnuc.nuc_fixed import load_pipeline

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    # The tools replaced by fakes: the cache and the naming are under test, not Yosys.
    counts = {"xc7": {k: 1 for k in synth.XC7_KEYS}, "ecp5": {k: 2 for k in synth.ECP5_KEYS}}
    monkeypatch.setattr(synth, "synth_xc7", lambda *a, **k: {
        **counts["xc7"], "cells": {}, "seconds": 0.0})
    monkeypatch.setattr(synth, "synth_ecp5", lambda *a, **k: (tmp_path / "net.json", {
        **counts["ecp5"], "cells": {}, "seconds": 0.0}))
    monkeypatch.setattr(synth, "place_route_ecp5", lambda *a, **k: {
        "fmax_mhz": 123.0, "utilization": {}, "critical_path": [], "seconds": 0.0})
    monkeypatch.setattr(synth, "tool_versions", lambda: {})
    first = synth.synth_config(load_pipeline("typical14"))
    assert first["cached"] is False and first["config"]["name"] == "typical14"
    alias = tmp_path / "alias.toml"
    alias.write_text(load_pipeline("typical14").to_toml().replace("[typical14]", "[alias]"))
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    assert run_cli(["synth", "-q", "--workers", "0", "--pipeline", str(alias), "--pipeline",
                    "minimal", "--out", "syn"]) == 0
    index = json.loads((work / "syn" / "synth.json").read_text())
    assert [c["name"] for c in index["configurations"]] == ["alias", "minimal"]
    got = json.loads((work / "syn" / "alias" / "synth.json").read_text())
    assert got["cached"] is True and got["config"]["name"] == "alias"
    assert got["config_digest"] == load_pipeline(str(alias)).digest()
    assert got["source_digest"] == first["source_digest"]  # the same design, from the cache
    assert _files(work) == {"syn", "syn/.irnuc-output", "syn/synth.json", "syn/alias",
                            "syn/alias/synth.json", "syn/minimal", "syn/minimal/synth.json",
                            ".syn.lock"}


def test_every_outcome_is_tested() -> None:
    tests = {n.removeprefix("test_outcome_") for n in globals() if n.startswith("test_outcome_")}
    assert tests == set(OUTCOMES)
