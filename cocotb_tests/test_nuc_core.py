"""Co-simulation of ``nuc_core`` against the golden model.

Every named configuration, plus variants of the smallest one so that every rounding mode
and both overflow modes are built and checked (rounding ties included).
"""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_nuc
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import PipelineConfig, load_pipeline, pipeline_names

pytestmark = [pytest.mark.cosim, pytest.mark.slow]

# name -> configuration; variants change only the modes of a named configuration.
_VARIANTS: dict[str, tuple[str, dict[str, str]]] = {
    **{name: (name, {}) for name in pipeline_names()},
    "minimal+truncate": ("minimal", {"rounding": "truncate"}),
    "minimal+half_up": ("minimal", {"rounding": "half_up"}),
    "minimal+wrap": ("minimal", {"overflow": "wrap", "rounding": "truncate"}),
    "typical14+half_even+wrap": ("typical14", {"rounding": "half_even", "overflow": "wrap"}),
}


def _config(variant: str) -> PipelineConfig:
    base, changes = _VARIANTS[variant]
    cfg = load_pipeline(base)
    return cfg.replace(**changes) if changes else cfg


@pytest.mark.parametrize(("variant", "case"), case_params(tb_nuc, list(_VARIANTS)))
def test_nuc_core(variant: str, case: str) -> None:
    run_case("nuc_core", _config(variant), tb_nuc, case)
