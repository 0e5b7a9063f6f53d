"""Co-simulation of ``nuc_dpc_top`` against the golden model: every named configuration,
and a fixed sample of random legal configurations."""

from __future__ import annotations

import pytest

from irnuc import cosim
from irnuc.cocotb_tests import tb_top
from irnuc.cocotb_tests.runs import case_params, module_metrics, results_root, run_case
from irnuc.common.io import file_lock
from irnuc.cosim import configspace
from irnuc.cosim.coverage import BACKPRESSURE_PATTERNS, IDLE_PATTERNS
from irnuc.nuc_fixed import PipelineConfig, load_pipeline, pipeline_names

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


def _ci_configs() -> dict[str, PipelineConfig]:
    return {c.name: c for c in configspace.ci_sample("nuc_dpc_top")}


@pytest.mark.parametrize("config", list(_ci_configs()))
def test_random_configuration(config: str) -> None:
    """The fixed random sample of legal configurations (``configspace.ci_sample``: with
    the named ones, every rounding x overflow mode, fraction order, maximum-frame shape and
    parameter branch of hdl/) through every tb_top test but ``tb_top.RANDOM_CONFIG_SKIP``."""
    cfg = _ci_configs()[config]
    assert configspace.space("nuc_dpc_top").legal(cfg) is None
    cases = [t for t in cosim.cocotb_test_names(tb_top) if t not in tb_top.RANDOM_CONFIG_SKIP]
    xml = results_root() / f"{cfg.name}-{cfg.digest()[:8]}-nuc_dpc_top-random.xml"
    with file_lock(xml.with_suffix(".lock")):
        cosim.run(cosim.build("nuc_dpc_top", cfg), MODULE, testcase=cases,
                  env={"IRNUC_SEED": "1"}, results_xml=xml)
        results = cosim.read_results(xml)
        fired = cosim.assertion_failures(xml)
    assert not fired, "RTL assertions failed:\n" + "\n".join(fired[:10])
    assert sorted(results) == sorted(cases), f"ran {sorted(results)}, not {sorted(cases)}"
    failed = {k: v.message for k, v in results.items() if not v.passed}
    assert not failed, "\n".join(f"{k}: {m[:2000]}" for k, m in failed.items())
