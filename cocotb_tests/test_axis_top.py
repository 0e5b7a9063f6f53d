"""Co-simulation of ``irnuc_axis_top`` with cocotbext-axi against the golden models (the
register model and the framing model, then the core's), on the named two-point
configurations."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_axis
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import load_pipeline

pytestmark = [pytest.mark.cosim]

#: minimal (short words, frequent saturation) and typical14 (the camera's widths).
CONFIGS = ("minimal", "typical14")


@pytest.mark.parametrize(("config", "case"), case_params(tb_axis, CONFIGS))
def test_irnuc_axis_top(config: str, case: str) -> None:
    run_case("irnuc_axis_top", load_pipeline(config), tb_axis, case)
