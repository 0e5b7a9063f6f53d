"""Co-simulation of ``nuc_dpc_top`` against the golden model, every named configuration."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_top
from irnuc.cocotb_tests.runs import case_params, module_metrics, run_case
from irnuc.cosim.coverage import BACKPRESSURE_PATTERNS, IDLE_PATTERNS
from irnuc.nuc_fixed import load_pipeline, pipeline_names

MODULE = tb_top.__name__

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


@pytest.mark.parametrize(("config", "case"), case_params(tb_top, pipeline_names()))
def test_nuc_dpc_top(config: str, case: str) -> None:
    run_case("nuc_dpc_top", load_pipeline(config), tb_top, case)


@pytest.mark.parametrize("backpressure", BACKPRESSURE_PATTERNS)
@pytest.mark.parametrize("idle", IDLE_PATTERNS)
@pytest.mark.parametrize("config", pipeline_names())
def test_stream_pattern(config: str, idle: str, backpressure: str) -> None:
    """One idle x backpressure pattern pair of ``stream_patterns``: exact, and at full-rate
    input no cycle lost inside the core (outputs + sink stalls = output cycles)."""
    lines = [m for m in module_metrics("nuc_dpc_top", load_pipeline(config), MODULE)
             if m.get("pattern") == [idle, backpressure]]
    assert lines, f"stream_patterns recorded nothing for idle {idle} / backpressure {backpressure}"
    assert lines[-1]["passed"], lines[-1]["message"]
    assert lines[-1]["outputs"] > 0
    if backpressure != "none":
        assert lines[-1]["stalls"] > 0, "the sink never stalled"
