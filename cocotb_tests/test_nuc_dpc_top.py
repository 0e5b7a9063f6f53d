"""Co-simulation of ``nuc_dpc_top`` against the golden model, every named configuration."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests.runs import check_case, cocotb_test_names, run_module
from irnuc.nuc_fixed import load_pipeline, pipeline_names

MODULE = "irnuc.cocotb_tests.tb_top"

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


@pytest.mark.parametrize("case", cocotb_test_names(MODULE))
@pytest.mark.parametrize("config", pipeline_names())
def test_nuc_dpc_top(config: str, case: str) -> None:
    check_case(run_module("nuc_dpc_top", load_pipeline(config), MODULE), case)
