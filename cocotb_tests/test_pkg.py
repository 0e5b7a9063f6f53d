"""``hdl/irnuc_pkg.sv`` against the shared-constants spec (``irnuc.nuc_fixed.rtl_spec``), by
simulation of the generated probe (``cosim/hdl/irnuc_pkg_probe.sv``): every constant, range,
enum literal, word layout and width function of the package is read back for every named
configuration (``cocotb_tests/tb_pkg.py``).
"""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_pkg
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import load_pipeline, pipeline_names

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


@pytest.mark.parametrize(("config", "case"), case_params(tb_pkg, pipeline_names()))
def test_irnuc_pkg(config: str, case: str) -> None:
    run_case("irnuc_pkg_probe", load_pipeline(config), tb_pkg, case)
