"""Co-simulation of the stage top ``method_drift_top`` (two_point + blind_drift) against
``nuc_fixed.method_top``: the named configuration ``drift14``."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_stage
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import PipelineConfig, load_pipeline

pytestmark = [pytest.mark.cosim]

#: label -> configuration.
CONFIGS: dict[str, PipelineConfig] = {"drift14": load_pipeline("drift14")}


@pytest.mark.parametrize(("label", "case"), case_params(tb_stage, list(CONFIGS)))
def test_method_drift_top(label: str, case: str) -> None:
    run_case("method_drift_top", CONFIGS[label], tb_stage, case)
