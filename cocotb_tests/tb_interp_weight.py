"""cocotb tests of ``interp_weight`` (run through ``cocotb_tests/test_interp_weight.py``):
the table index and the weight of a reading, against ``nuc_fixed.tempcomp.interp_weight``.
"""

from __future__ import annotations

import itertools

import cocotb
import numpy as np
from cocotb.triggers import RisingEdge

from irnuc.cocotb_tests import tb_lib
from irnuc.cosim import coverage
from irnuc.nuc_fixed.tempcomp import interp_weight

TOP = "interp_weight"


async def _compute(dut, reading: int, readings: list[int], bits: int) -> tuple[int, int, int, int]:
    """Start one computation; return (j, w, error, cycles from start to done)."""
    dut.reading_i.value = reading
    dut.table_readings_i.value = sum(int(r) << (bits * i) for i, r in enumerate(readings))
    dut.start_i.value = 1
    await RisingEdge(dut.clk_i)
    dut.start_i.value = 0
    cycles = 0
    while True:
        await RisingEdge(dut.clk_i)
        cycles += 1
        assert cycles < 200, "interp_weight never finished"
        if int(dut.done_o.value):
            break
        assert int(dut.busy_o.value), "neither busy nor done during a computation"
    assert not int(dut.busy_o.value)
    return int(dut.j_o.value), int(dut.weight_o.value), int(dut.error_o.value), cycles


def _cases(cfg, rng: np.random.Generator) -> list[tuple[int, list[int]]]:
    """Readings at, between, below and above random table readings; exact rounding ties
    of both quotient parities; a span of 1; the ends of the reading range."""
    k = int(cfg.tables or 2)
    hi = (1 << int(cfg.reading_bits or 1)) - 1
    out: list[tuple[int, list[int]]] = []
    # Exact rounding ties: with spans of 2^(Wf+1), an odd num gives num/2, a fraction of
    # exactly 1/2, on an even (num = 1, 5) and an odd (num = 3, 7) quotient.
    span = 1 << (cfg.format("weight").frac_bits + 1)
    if (k - 1) * span <= hi:
        rs = [i * span for i in range(k)]
        out += [(r + n, rs) for r in rs[:-1] for n in (1, 3, 5, 7) if n < span]
    for trial in range(40):
        if trial == 0:
            rs = list(range(k))                     # spans of 1 from 0
        elif trial == 1:
            rs = list(range(hi - k + 1, hi + 1))    # up to the largest reading
        else:
            rs = sorted(int(v) for v in rng.choice(hi + 1, size=k, replace=False))
        marks = rs + [(a + b) // 2 for a, b in itertools.pairwise(rs)]
        marks += [(a + b + 1) // 2 for a, b in itertools.pairwise(rs)]
        marks += [max(0, rs[0] - 1), 0, min(hi, rs[-1] + 1), hi]
        marks += [int(v) for v in rng.integers(0, hi + 1, size=4)]
        out += [(m, rs) for m in marks]
    return out


@cocotb.test()
async def weights_match_golden(dut) -> None:
    """j and w of every case equal the golden model's; done_o holds the result."""
    env = await tb_lib.setup(dut, 0)
    cfg, rng = env.cfg, env.rng
    bits = len(dut.reading_i)
    assert bits == cfg.reading_bits
    assert len(dut.weight_o) == cfg.format("weight").frac_bits + 1
    cov = coverage.model(TOP, cfg) if coverage.enabled() else None
    bad = []
    for reading, rs in _cases(cfg, rng):
        j, w, err, _ = await _compute(dut, reading, rs, bits)
        want = interp_weight(reading, rs, cfg)
        if (j, w, err) != (want.j, want.w, 0) and len(bad) < 10:
            bad.append(f"reading {reading} tables {rs}: got j {j} w {w} error {err}, "
                       f"expected j {want.j} w {want.w}")
        if cov is not None:
            from irnuc.cosim.method_coverage import weight_classes

            cov.sample_classes(weight_classes(reading, rs, cfg))
    assert not bad, "\n".join(bad)
    if cov is not None:
        coverage.export()


@cocotb.test()
async def unordered_readings_flagged(dut) -> None:
    """Table readings that do not increase strictly raise error_o (the golden model
    refuses them); the next ordered ones clear it. Each pair on its own too (a tie, the
    rest increasing): a check that misses one pair is hidden when another pair fails."""
    cfg = (await tb_lib.setup(dut, 1)).cfg
    bits = len(dut.reading_i)
    k = int(cfg.tables or 2)
    ties = [[i - (i > p) for i in range(k)] for p in range(k - 1)]  # r_(p+1) = r_p
    for rs in ([5] * k, list(range(k, 0, -1)), *ties):
        _, _, err, _ = await _compute(dut, 3, rs, bits)
        assert err == 1, f"table readings {rs}: error_o not raised"
    _, _, err, _ = await _compute(dut, 3, list(range(k)), bits)
    assert err == 0, "error_o stays after ordered readings"
    if coverage.enabled():
        coverage.model(TOP, cfg).sample("iw.error", "order")
        coverage.export()


@cocotb.test()
async def result_holds_until_next_start(dut) -> None:
    """After done, j and w hold while start is low; a new start clears done."""
    cfg = (await tb_lib.setup(dut, 2)).cfg
    bits = len(dut.reading_i)
    k = int(cfg.tables or 2)
    rs = [10 * (i + 1) for i in range(k)]
    j, w, _, cycles = await _compute(dut, 15, rs, bits)
    assert cycles == cfg.format("weight").frac_bits + 6, f"done after {cycles} cycles"
    for _ in range(5):
        await RisingEdge(dut.clk_i)
        assert (int(dut.j_o.value), int(dut.weight_o.value), int(dut.done_o.value)) == (j, w, 1)
    dut.start_i.value = 1
    await RisingEdge(dut.clk_i)
    dut.start_i.value = 0
    await RisingEdge(dut.clk_i)
    assert int(dut.done_o.value) == 0 and int(dut.busy_o.value) == 1
