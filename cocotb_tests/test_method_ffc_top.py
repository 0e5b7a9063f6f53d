"""Co-simulation of the stage top ``method_ffc_top`` (base method + ffc) against
``nuc_fixed.method_top``: the named configurations ffc14 (two_point, hold), quadffc14
(quadratic, pass) and tcffc14 (tc_offset of order 2 with its gain polynomial, hold)."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_ffc
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import PipelineConfig, load_pipeline

pytestmark = [pytest.mark.cosim]

#: label -> configuration.
CONFIGS: dict[str, PipelineConfig] = {n: load_pipeline(n) for n in ("ffc14", "quadffc14",
                                                                  "tcffc14")}


@pytest.mark.parametrize(("label", "case"), case_params(tb_ffc, list(CONFIGS)))
def test_method_ffc_top(label: str, case: str) -> None:
    run_case("method_ffc_top", CONFIGS[label], tb_ffc, case)
