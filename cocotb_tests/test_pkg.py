"""``hdl/irnuc_pkg.sv`` against the shared-constants spec (``irnuc.nuc_fixed.rtl_spec``), by
simulation of the generated probe (``cosim/hdl/irnuc_pkg_probe.sv``): every constant, range,
enum literal, word layout and width function of the package is read back for every named
configuration (``cocotb_tests/tb_pkg.py``).
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
