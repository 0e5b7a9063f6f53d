"""Co-simulation of ``method_dpc_top`` against ``nuc_fixed.method_top``: every base method's
named configuration, and variants that reach the other generate branches (tc_offset of
order 1, tc_housing with tc_gain, other rounding and overflow modes)."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_method
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import PipelineConfig, load_pipeline

pytestmark = [pytest.mark.cosim]


def _order1(name: str) -> PipelineConfig:
    """A tc_offset configuration of order 1 (no u^2 term, no tc2/tg2 format)."""
    data = load_pipeline(name).to_dict()
    data["formats"] = {k: v for k, v in data["formats"].items() if k not in ("tc2", "tg2")}
    return PipelineConfig(**{**data, "name": f"{name}_order1", "tc_order": 1})


#: label -> configuration: one per base method, then the variants.
CONFIGS: dict[str, PipelineConfig] = {
    **{n: load_pipeline(n) for n in ("onepoint14", "typical14", "piecewise14", "quadratic14",
                                     "tcoffset14", "tcgain14", "table14", "tchousing14")},
    "tcgain14_order1": _order1("tcgain14"),
    # tc_housing with its gain a polynomial too (tc_poly's Housing with TcGain).
    "tchousing14+tc_gain": load_pipeline("tchousing14").replace(
        tc_gain=True, formats={n: load_pipeline("tcgain14").to_dict()["formats"][n]
                               for n in ("tg1", "tg2")}),
    "piecewise14+truncate+wrap": load_pipeline("piecewise14").replace(
        rounding="truncate", overflow="wrap"),
    "quadratic14+half_even": load_pipeline("quadratic14").replace(rounding="half_even"),
}


@pytest.mark.parametrize(("label", "case"), case_params(tb_method, list(CONFIGS)))
def test_method_dpc_top(label: str, case: str) -> None:
    run_case("method_dpc_top", CONFIGS[label], tb_method, case)
