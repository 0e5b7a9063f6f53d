"""cocotb tests of ``dpc_core`` alone (run through ``cocotb_tests/test_dpc_core.py``).

The input is the NUC output y and the bad map with the frame markers (stream ``s``, found
by prefix, the frame size on its ports); the scoreboard is
:class:`irnuc.cosim.DpcScoreboard` (golden reference ``nuc_fixed.dpc_core``).
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.directed import dpc_bad_patterns, neighbour_maps
from irnuc.cocotb_tests.streams import Sink, Source, StreamBus, reset, run_streams
from irnuc.cosim import coverage
from irnuc.cosim.scoreboard import DpcScoreboard

Frames = list[tuple[np.ndarray, np.ndarray]]  # (y, bad) per frame


def _source(env: tb_lib.Env, frames: Frames, idle: float | str = 0.0) -> Source:
    cols = {k: [] for k in ("pix_data", "bad", "sof", "eol")}
    for y, bad in frames:
        sof, eol = tb_lib.markers(*y.shape)
        for k, v in (("pix_data", y.ravel()), ("bad", bad.ravel()), ("sof", sof), ("eol", eol)):
            cols[k].append(np.asarray(v, dtype=np.int64))
    h, w = frames[0][0].shape
    env.dut.frame_width_i.value = w
    env.dut.frame_height_i.value = h
    return Source(StreamBus.from_prefix(env.dut, "s"),
                  {k: np.concatenate(v) for k, v in cols.items()}, idle, env.rng)


async def _run(env: tb_lib.Env, frames: Frames, idle: float | str = 0.0,
               bp: float | str = 0.0) -> Sink:
    """Stream the frames (one size), score them; fail on a mismatch or a framing error."""
    src = _source(env, frames, idle)
    sink = Sink(StreamBus.from_prefix(env.dut, "m"), bp, env.rng,
                expect=sum(y.size for y, _ in frames))
    await run_streams(env.dut, [src], sink)
    sb = DpcScoreboard(env.golden)
    for y, bad in frames:
        sb.expect_frame(y, bad)
    tb_lib.assert_passed(tb_lib.score(sb, sink))
    assert int(env.dut.frame_err_o.value) == 0
    if coverage.enabled():
        cov = coverage.model("dpc_core", env.cfg)
        for _, bad in frames:
            cov.sample_dpc(bad)
        tb_lib.sample_transitions([y.shape for y, _ in frames], src.taken)
        coverage.export()
    return sink


async def _setup(dut, salt: int) -> tb_lib.Env:
    env = await tb_lib.setup(dut, salt)
    assert StreamBus.from_prefix(dut, "s").width("pix_data") == env.cfg.out_bits
    return env


def _y(env: tb_lib.Env, shape: tuple[int, int]) -> np.ndarray:
    return env.rng.integers(0, 1 << env.cfg.out_bits, size=shape)


def _frames(env: tb_lib.Env, n: int, h: int, w: int, bad_fraction: float) -> Frames:
    return [(_y(env, (h, w)), env.rng.random((h, w)) < bad_fraction) for _ in range(n)]


@cocotb.test()
async def patterns(dut) -> None:
    """Borders, corners, clusters, whole rows and columns, all bad, degenerate sizes."""
    env = await _setup(dut, 0)
    h, w = min(env.cfg.max_height, 9), min(env.cfg.max_width, 11)
    for i, bad in enumerate(dpc_bad_patterns(h, w) + neighbour_maps(h, w)):
        await _run(env, [(_y(env, bad.shape), bad)], idle=0.2 * (i % 2), bp=0.3 * ((i + 1) % 2))


@cocotb.test()
async def extreme_values(dut) -> None:
    """All neighbours at the largest code (largest sum S) and every count n = 1..8."""
    env = await _setup(dut, 1)
    ymax = (1 << env.cfg.out_bits) - 1
    if env.cfg.max_height < 3 or env.cfg.max_width < 3:
        return
    ring = [(0, 0), (0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1), (2, 2)]
    for n_bad in range(0, 9):  # n = 8 - n_bad good neighbours
        for fill in (ymax, ymax - 1, 1):
            y = np.full((3, 3), fill, dtype=np.int64)
            bad = np.zeros((3, 3), dtype=bool)
            bad[1, 1] = True
            for r, c in ring[:n_bad]:
                bad[r, c] = True
            y[1, 1] = int(env.rng.integers(0, ymax + 1))
            await _run(env, [(y, bad)])


@cocotb.test()
async def random_continuous(dut) -> None:
    """Back-to-back frames at full rate: exact and without bubbles at frame boundaries."""
    env = await _setup(dut, 2)
    cfg = env.cfg
    for h, w in ((min(cfg.max_height, 7), min(cfg.max_width, 9)), (1, 1), (1, 4), (5, 1)):
        sink = await _run(env, _frames(env, 3, h, w, 0.3))
        assert sink.last_cycle - sink.first_cycle == 3 * h * w - 1, f"bubbles for {h}x{w} frames"


@cocotb.test()
async def random_gaps_sizes(dut) -> None:
    """Random idle gaps and backpressure, frame sizes changing (end-of-frame flushes)."""
    env = await _setup(dut, 3)
    cfg = env.cfg
    sizes = [(min(cfg.max_height, 6), min(cfg.max_width, 13)), (2, cfg.max_width),
             (cfg.max_height, 1), (1, 2), (min(cfg.max_height, 4), min(cfg.max_width, 3))]
    for i, (h, w) in enumerate(sizes):
        await _run(env, _frames(env, 2, h, w, 0.25), idle=(0.4, 0.1, 0.0)[i % 3],
                   bp=(0.2, 0.5, 0.3)[i % 3])


@cocotb.test()
async def reset_mid_frame(dut) -> None:
    env = await _setup(dut, 4)
    h, w = min(env.cfg.max_height, 6), min(env.cfg.max_width, 8)
    sink = Sink(StreamBus.from_prefix(dut, "m"), expect=h * w // 2)
    await run_streams(dut, [_source(env, _frames(env, 1, h, w, 0.3))], sink)
    await reset(dut, 2)
    assert int(dut.m_valid_o.value) == 0
    await ClockCycles(dut.clk_i, 2)
    await _run(env, _frames(env, 1, h, w, 0.3), idle=0.2, bp=0.2)
