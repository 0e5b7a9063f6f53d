"""Co-simulation of the stage top ``method_drift_top`` (two_point + blind_drift) against
``nuc_fixed.method_top``: the named configuration ``drift14``; the drift coverage of that
one run closes (``cosim.stage_coverage``: every bin hit)."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_stage
from irnuc.cocotb_tests.runs import case_params, coverage_json, run_case, run_module
from irnuc.cocotb_tests.test_coverage import _assert_closed
from irnuc.cosim import coverage
from irnuc.nuc_fixed import PipelineConfig, load_pipeline

pytestmark = [pytest.mark.cosim]

#: label -> configuration.
CONFIGS: dict[str, PipelineConfig] = {"drift14": load_pipeline("drift14")}


@pytest.mark.parametrize(("label", "case"), case_params(tb_stage, list(CONFIGS)))
def test_method_drift_top(label: str, case: str) -> None:
    run_case("method_drift_top", CONFIGS[label], tb_stage, case)


@pytest.mark.parametrize("label", list(CONFIGS))
def test_drift_coverage_complete(label: str) -> None:
    """Every bin of the drift stage (cosim.stage_coverage.DRIFT_POINTS) and of the stream
    points is hit by tb_stage on method_drift_top: the run test_method_drift_top makes,
    read again (no simulation of its own)."""
    cfg = CONFIGS[label]
    run_module("method_drift_top", cfg, tb_stage.__name__)
    summary = coverage.summarize(coverage.merge(
        [coverage_json("method_drift_top", cfg, tb_stage.__name__)]))
    points = summary["configurations"].get(coverage.config_label(cfg), {}).get("coverpoints", {})
    assert any(p.startswith("drift.") for p in points), "no drift coverpoint exported"
    _assert_closed(summary, coverage.config_label(cfg))
