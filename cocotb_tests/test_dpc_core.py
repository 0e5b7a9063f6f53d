"""Co-simulation of ``dpc_core`` against the golden model, and the proof that its
reciprocal-table division is exact (the RTL's table itself is read back from simulation
and compared with :func:`irnuc.nuc_fixed.dpc.reciprocal_table` in ``cocotb_tests/test_pkg.py``)."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.cocotb_tests import tb_dpc
from irnuc.cocotb_tests.runs import case_params, run_case
from irnuc.nuc_fixed import load_pipeline, pipeline_names
from irnuc.nuc_fixed.dpc import reciprocal_table


@pytest.mark.cosim
@pytest.mark.slow
@pytest.mark.parametrize(("config", "case"), case_params(tb_dpc, pipeline_names()))
def test_dpc_core(config: str, case: str) -> None:
    run_case("dpc_core", load_pipeline(config), tb_dpc, case)


def _out_bits_to_prove() -> list[int]:
    # Every legal B up to 20 exhaustively (cheap), plus every configured B.
    return sorted(set(range(1, 21)) | {load_pipeline(n).out_bits for n in pipeline_names()})


@pytest.mark.parametrize("out_bits", _out_bits_to_prove())
def test_reciprocal_division_exact(out_bits: int) -> None:
    """(M * R[n]) >> K == floor((2S + n) / (2n)) for every S <= 8 (2^B - 1), n = 1..8.

    M = S + floor(n/2) is what dpc_core divides; the reference is Python/numpy integer
    division of the contract's formula.
    """
    shift, table = reciprocal_table(out_bits)
    s = np.arange(0, 8 * ((1 << out_bits) - 1) + 1, dtype=np.uint64)
    for n in range(1, 9):
        m = s + np.uint64(n // 2)
        assert int(m.max()) < (1 << (out_bits + 3)), "numerator exceeds its B+3 bits"
        got = (m * np.uint64(table[n])) >> np.uint64(shift)
        want = (2 * s + np.uint64(n)) // np.uint64(2 * n)
        bad = np.flatnonzero(got != want)
        assert bad.size == 0, f"n={n}: first failing S={int(s[bad[0]])}"
        assert int(m.max()) * table[n] < (1 << 64), "numpy uint64 product overflowed"
