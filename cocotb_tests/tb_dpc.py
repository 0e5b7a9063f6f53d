"""cocotb tests of ``dpc_core`` alone (run through ``cocotb_tests/test_dpc_core.py``).

The input is the NUC output y and the bad map, driven directly; the golden reference is
``nuc_fixed.dpc_core``.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.directed import dpc_bad_patterns, neighbour_maps
from irnuc.cosim import coverage
from irnuc.nuc_fixed import dpc_core


def _frame_rows(y: np.ndarray, bad: np.ndarray) -> np.ndarray:
    h, w = y.shape
    ys, xs = np.mgrid[0:h, 0:w]
    return np.stack([y.ravel(), bad.ravel(), ((ys == 0) & (xs == 0)).ravel(),
                     (xs == w - 1).ravel()], axis=1).astype(np.int64)


def _check(frames, got, cfg, max_report=10):
    lines, k = [], 0
    for fi, (y, bad) in enumerate(frames):
        exp = dpc_core(y, bad, cfg)
        h, w = y.shape
        for r in range(h):
            for c in range(w):
                if k >= len(got):
                    return [*lines, f"frame {fi}: output ended at {k} pixels"]
                d, sof, eol = got[k]
                k += 1
                es, ee = int(r == 0 and c == 0), int(c == w - 1)
                if d != exp[r, c] or sof != es or eol != ee:
                    nb = y[max(r - 1, 0): r + 2, max(c - 1, 0): c + 2].tolist()
                    nbb = bad[max(r - 1, 0): r + 2, max(c - 1, 0): c + 2].astype(int).tolist()
                    lines.append(f"frame {fi} x {c} y {r}: y {y[r, c]} bad {int(bad[r, c])} "
                                 f"window {nb} bad {nbb} | expected {exp[r, c]} got {d} | "
                                 f"sof {sof}/{es} eol {eol}/{ee}" if len(lines) < max_report
                                 else "")
    if k != len(got):
        lines.append(f"{len(got) - k} extra outputs")
    return lines


async def _run(dut, frames, rng, idle=0.0, bp=0.0):
    cfg = tb_lib.config_from_env()
    assert len(dut.s_pix_data_i) == cfg.out_bits
    h, w = frames[0][0].shape
    dut.frame_width_i.value = w
    dut.frame_height_i.value = h
    src = tb_lib.Source(dut.s_valid_i, dut.s_ready_o,
                        [dut.s_pix_data_i, dut.s_bad_i, dut.s_sof_i, dut.s_eol_i],
                        np.concatenate([_frame_rows(y, b) for y, b in frames]), idle)
    sink = tb_lib.Sink(dut.m_valid_o, dut.m_ready_i, [dut.m_pix_data_o, dut.m_sof_o,
                                                      dut.m_eol_o], bp)
    await tb_lib.run_streams(dut, [src], sink, sum(y.size for y, _ in frames), rng)
    lines = _check(frames, sink.got, tb_lib.golden_config(cfg))
    if lines:
        for ln in lines:
            if ln:
                dut._log.error(ln)
        raise AssertionError(f"{len(lines)} mismatches; first:\n"
                             + "\n".join([ln for ln in lines if ln][:10]))
    assert int(dut.frame_err_o.value) == 0
    if coverage.enabled():
        cov = coverage.model("dpc_core", cfg)
        for _, bad in frames:
            cov.sample_dpc(bad)
        tb_lib.sample_transitions([y.shape for y, _ in frames], src.taken)
        coverage.export()
    return sink


def _y(rng, cfg, shape):
    return rng.integers(0, 1 << cfg.out_bits, size=shape)


@cocotb.test()
async def patterns(dut) -> None:
    """Borders, corners, clusters, whole rows and columns, all bad, degenerate sizes."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env())
    await tb_lib.start_clock_and_reset(dut)
    h, w = min(cfg.max_height, 9), min(cfg.max_width, 11)
    for i, bad in enumerate(dpc_bad_patterns(h, w) + neighbour_maps(h, w)):
        await _run(dut, [(_y(rng, cfg, bad.shape), bad)], rng, idle=0.2 * (i % 2),
                   bp=0.3 * ((i + 1) % 2))


@cocotb.test()
async def extreme_values(dut) -> None:
    """All neighbours at the largest code (largest sum S) and every count n = 1..8."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 1)
    await tb_lib.start_clock_and_reset(dut)
    ymax = (1 << cfg.out_bits) - 1
    h, w = 3, min(cfg.max_width, 3)
    if cfg.max_height < 3 or cfg.max_width < 3:
        return
    for n_bad in range(0, 9):  # n = 8 - n_bad good neighbours
        for fill in (ymax, ymax - 1, 1):
            y = np.full((h, w), fill, dtype=np.int64)
            bad = np.zeros((h, w), dtype=bool)
            bad[1, 1] = True
            ring = [(0, 0), (0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1), (2, 2)]
            for r, c in ring[:n_bad]:
                bad[r, c] = True
            y[1, 1] = int(rng.integers(0, ymax + 1))
            await _run(dut, [(y, bad)], rng)


@cocotb.test()
async def random_continuous(dut) -> None:
    """Back-to-back frames at full rate: exact and without bubbles at frame boundaries."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 2)
    await tb_lib.start_clock_and_reset(dut)
    for h, w in ((min(cfg.max_height, 7), min(cfg.max_width, 9)), (1, 1), (1, 4), (5, 1)):
        frames = [(_y(rng, cfg, (h, w)), rng.random((h, w)) < 0.3) for _ in range(3)]
        sink = await _run(dut, frames, rng)
        n = 3 * h * w
        assert sink.last_cycle - sink.first_cycle == n - 1, f"bubbles for {h}x{w} frames"


@cocotb.test()
async def random_gaps_sizes(dut) -> None:
    """Random idle gaps and backpressure, frame sizes changing (end-of-frame flushes)."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 3)
    await tb_lib.start_clock_and_reset(dut)
    sizes = [(min(cfg.max_height, 6), min(cfg.max_width, 13)), (2, cfg.max_width),
             (cfg.max_height, 1), (1, 2), (min(cfg.max_height, 4), min(cfg.max_width, 3))]
    for i, (h, w) in enumerate(sizes):
        frames = [(_y(rng, cfg, (h, w)), rng.random((h, w)) < 0.25) for _ in range(2)]
        await _run(dut, frames, rng, idle=(0.4, 0.1, 0.0)[i % 3], bp=(0.2, 0.5, 0.3)[i % 3])


@cocotb.test()
async def reset_mid_frame(dut) -> None:
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 4)
    await tb_lib.start_clock_and_reset(dut)
    h, w = min(cfg.max_height, 6), min(cfg.max_width, 8)
    y, bad = _y(rng, cfg, (h, w)), rng.random((h, w)) < 0.3
    dut.frame_width_i.value = w
    dut.frame_height_i.value = h
    src = tb_lib.Source(dut.s_valid_i, dut.s_ready_o,
                        [dut.s_pix_data_i, dut.s_bad_i, dut.s_sof_i, dut.s_eol_i],
                        _frame_rows(y, bad))
    sink = tb_lib.Sink(dut.m_valid_o, dut.m_ready_i, [dut.m_pix_data_o, dut.m_sof_o,
                                                      dut.m_eol_o])
    await tb_lib.run_streams(dut, [src], sink, h * w // 2, rng)
    await tb_lib.reset(dut, 2)
    assert int(dut.m_valid_o.value) == 0
    await ClockCycles(dut.clk_i, 2)
    await _run(dut, [(_y(rng, cfg, (h, w)), rng.random((h, w)) < 0.3)], rng, idle=0.2, bp=0.2)
