"""The report's paper phase kept in the cache: a warm run reads what a cold run made, with
the same section, metrics, figures and notes; other settings are computed again."""

from __future__ import annotations

import copy
import json

import pytest

from irnuc.reports.report import base
from irnuc.reports.report.config import load_report_config
from irnuc.reports.report.phases import paper
from irnuc.reports.report.sections import thaw


def _paper_config() -> dict:
    from pathlib import Path

    from irnuc.reports import report

    cfg = load_report_config(str(Path(report.__file__).with_name("report_small.toml")))
    p = copy.deepcopy(cfg["paper"])
    # smaller still: the cache is the subject, not the tables
    p.update(rows=16, cols=24, grid_temps=[300.0, 350.0], frac_bits=[3, 4],
             reference_nu=[0.0348, 0.0181])
    p["table1"] = {"rows": 8, "cols": 12, "temps": [300.0], "tolerances": [1e-4],
                   "skimming": ["row"]}
    return {"paper": p}


def _run(config: dict) -> base.Report:
    rep = base.Report(config=copy.deepcopy(config), verbose=False)
    paper.phase_paper(rep, progress=False)
    return rep


def _outcome(rep: base.Report) -> str:
    return json.dumps({"section": thaw(rep.sections["paper"]), "metrics": rep.metrics,
                       "figures": [[c, png.hex()] for c, png in rep.figures["paper"]],
                       "notes": rep.notes}, sort_keys=True)


def test_a_warm_paper_phase_reads_the_cold_ones_results(own_cache, monkeypatch) -> None:
    config = _paper_config()
    cold = _run(config)
    stored = paper.paper_cache_file(config["paper"])
    assert stored.is_file() and stored.is_relative_to(own_cache)
    assert len(cold.figures["paper"]) == 3  # Table 2, the comparison, Table 1

    def no_work(*_a, **_k):
        raise AssertionError("the paper phase computed again with a stored result")

    monkeypatch.setattr(paper, "_compute_paper", no_work)
    warm = _run(config)
    assert _outcome(warm) == _outcome(cold)
    # another seed is another result: computed, not read
    other = copy.deepcopy(config)
    other["paper"]["seed"] += 1
    assert paper.paper_cache_file(other["paper"]) != stored
    with pytest.raises(AssertionError, match="computed again"):
        _run(other)


def test_a_damaged_stored_result_is_computed_again(own_cache) -> None:
    config = _paper_config()
    path = paper.paper_cache_file(config["paper"])
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text('{"format": 1, "rows": [')
    rep = _run(config)
    assert rep.sections["paper"] is not None
    assert json.loads(path.read_text())["format"] == 1
