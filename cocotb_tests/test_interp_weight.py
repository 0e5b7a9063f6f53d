"""Co-simulation of ``interp_weight`` (the per-frame table index and weight of
table_interp) against ``nuc_fixed.tempcomp.interp_weight``: table14, and variants with two
and sixteen tables, the two other rounding modes and no fraction bits."""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_interp_weight
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import PipelineConfig, load_pipeline

pytestmark = [pytest.mark.cosim]


def _variant(name: str, **changes: object) -> PipelineConfig:
    return load_pipeline("table14").replace(name=name, **changes)


CONFIGS: dict[str, PipelineConfig] = {
    "table14": load_pipeline("table14"),
    "two_tables_half_even": _variant(
        "iw_two_half_even", tables=2, reading_bits=8,
        formats={"weight": {"rounding": "half_even", "frac_bits": 6}}),
    "sixteen_tables_truncate": _variant(
        "iw_sixteen_truncate", tables=16, formats={"weight": {"rounding": "truncate"}}),
    "no_fraction": _variant("iw_no_fraction", formats={"weight": {"frac_bits": 0}}),
}


@pytest.mark.parametrize(("label", "case"), case_params(tb_interp_weight, list(CONFIGS)))
def test_interp_weight(label: str, case: str) -> None:
    run_case("interp_weight", CONFIGS[label], tb_interp_weight, case)
