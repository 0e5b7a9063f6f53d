"""``hdl/irnuc_pkg.sv`` against the Python side, by simulation of a probe module.

Mode encodings (``ROUNDING_MODES``, ``OVERFLOW_MODES``), the coefficient word layout
(``pack_words``) and the DPC reciprocal table (``reciprocal_table``) are read back from the
simulated RTL for every named configuration (``cocotb_tests/tb_pkg.py``).
"""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests.runs import check_case, cocotb_test_names, run_module
from irnuc.nuc_fixed import load_pipeline, pipeline_names

MODULE = "irnuc.cocotb_tests.tb_pkg"

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


@pytest.mark.parametrize("case", cocotb_test_names(MODULE))
@pytest.mark.parametrize("config", pipeline_names())
def test_irnuc_pkg(config: str, case: str) -> None:
    check_case(run_module("irnuc_pkg_probe", load_pipeline(config), MODULE), case)
