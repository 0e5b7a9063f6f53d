"""cocotb tests of ``nuc_core`` alone (run through ``cocotb_tests/test_nuc_core.py``).

Pixels are a flat stream here (no frame); the user sideband must pass unchanged.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.directed import corner_coefficients
from irnuc.cosim import coverage
from irnuc.nuc_fixed import nuc_core


def _check(x, g, o, user, got, gcfg, max_report=10):
    """In-order check; mismatch lines carry the inputs and golden p, s, r."""
    it = nuc_core(x, g, o, gcfg, intermediates=True)
    lines = []
    if len(got) != len(x):
        lines.append(f"{len(got)} outputs for {len(x)} inputs")
    for i, (d, u) in enumerate(got[: len(x)]):
        if d != it.y[i] or u != user[i]:
            if len(lines) < max_report:
                lines.append(f"pixel {i}: x {x[i]} gain {g[i]} offset {o[i]} user {user[i]} | "
                             f"expected {it.y[i]} got {d} (user {u}) | golden p {it.p[i]} "
                             f"s {it.s[i]} r {it.r[i]}")
            else:
                lines.append("")
    return lines


async def _run(dut, cfg, gcfg, x, g, o, rng, idle=0.0, bp=0.0):
    assert len(dut.s_pix_data_i) == cfg.adc_bits
    assert len(dut.s_gain_i) == cfg.gain_bits
    assert len(dut.s_offset_i) == cfg.offset_bits
    assert len(dut.m_pix_data_o) == cfg.out_bits
    ubits = len(dut.s_user_i)
    user = rng.integers(0, 1 << ubits, size=len(x))
    o_field = np.asarray(o, dtype=np.int64) & ((1 << cfg.offset_bits) - 1)
    src = tb_lib.Source(dut.s_valid_i, dut.s_ready_o,
                        [dut.s_pix_data_i, dut.s_gain_i, dut.s_offset_i, dut.s_user_i],
                        np.stack([x, g, o_field, user], axis=1), idle)
    sink = tb_lib.Sink(dut.m_valid_o, dut.m_ready_i, [dut.m_pix_data_o, dut.m_user_o], bp)
    await tb_lib.run_streams(dut, [src], sink, len(x), rng)
    lines = _check(x, g, o, user, sink.got, gcfg)
    if not lines and gcfg == cfg and coverage.enabled():
        coverage.model("nuc_core", cfg).sample_nuc(np.asarray(x), np.asarray(g),
                                                   np.asarray(o))
        coverage.export()
    return lines, sink


def _random(cfg, rng, n):
    x = rng.integers(0, 1 << cfg.adc_bits, size=n)
    g = rng.integers(0, 1 << cfg.gain_bits, size=n)
    half = 1 << (cfg.offset_bits - 1)
    o = rng.integers(-half, half, size=n)
    return x, g, o


def _fail(dut, lines):
    shown = [ln for ln in lines if ln]
    for ln in shown:
        dut._log.error(ln)
    raise AssertionError(f"{len(lines)} mismatches; first:\n" + "\n".join(shown[:10]))


@cocotb.test()
async def random_full_rate(dut) -> None:
    """Random codes at valid=1/ready=1: exact and one result per clock."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env())
    await tb_lib.start_clock_and_reset(dut)
    x, g, o = _random(cfg, rng, 2000)
    lines, sink = await _run(dut, cfg, tb_lib.golden_config(cfg), x, g, o, rng)
    if lines:
        _fail(dut, lines)
    assert sink.last_cycle - sink.first_cycle == len(x) - 1, "bubbles at full rate"
    coverage.model("nuc_core", cfg).sample("stream.back_to_back", "frames")
    coverage.export()


@cocotb.test()
async def stream_patterns(dut) -> None:
    """Every idle x backpressure pattern: exact; at full-rate input no lost cycle."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 5)
    await tb_lib.start_clock_and_reset(dut)
    for idle in coverage.IDLE_PATTERNS:
        for bp in coverage.BACKPRESSURE_PATTERNS:
            x, g, o = _random(cfg, rng, 60)
            lines, sink = await _run(dut, cfg, tb_lib.golden_config(cfg), x, g, o, rng,
                                     idle=idle, bp=bp)
            if lines:
                _fail(dut, lines)
            if idle == "none":
                sink.check_throughput()


@cocotb.test()
async def reset_each_stage(dut) -> None:
    """Reset while the leading item is in each stage; the stream after it is exact."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 6)
    await tb_lib.start_clock_and_reset(dut)
    stages = coverage.pipeline_stages("nuc_core", cfg)
    for k, stage in enumerate(stages):
        x, g, o = _random(cfg, rng, 20)
        src = tb_lib.Source(dut.s_valid_i, dut.s_ready_o,
                            [dut.s_pix_data_i, dut.s_gain_i, dut.s_offset_i, dut.s_user_i],
                            np.stack([x, g, o & ((1 << cfg.offset_bits) - 1), 0 * x], axis=1))
        sink = tb_lib.Sink(dut.m_valid_o, dut.m_ready_i, [dut.m_pix_data_o, dut.m_user_o])
        await tb_lib.run_streams(dut, [src], sink, 10**9, rng,
                                 stop=lambda c, s=src, k=k: bool(s.taken) and
                                 c >= s.taken[0] + k)
        await tb_lib.reset(dut)
        assert int(dut.m_valid_o.value) == 0
        coverage.model("nuc_core", cfg).sample("reset.stage", stage)
        x, g, o = _random(cfg, rng, 30)
        lines, _ = await _run(dut, cfg, tb_lib.golden_config(cfg), x, g, o, rng)
        if lines:
            _fail(dut, lines)


@cocotb.test()
async def random_gaps_backpressure(dut) -> None:
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 1)
    await tb_lib.start_clock_and_reset(dut)
    x, g, o = _random(cfg, rng, 2000)
    lines, _ = await _run(dut, cfg, tb_lib.golden_config(cfg), x, g, o, rng, idle=0.3, bp=0.4)
    if lines:
        _fail(dut, lines)


@cocotb.test()
async def corner_codes(dut) -> None:
    """Largest code x largest gain, saturation (or wrap) at both ends, rounding ties."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 2)
    await tb_lib.start_clock_and_reset(dut)
    x, g, o, _ = corner_coefficients(cfg, rng)
    lines, _ = await _run(dut, cfg, tb_lib.golden_config(cfg), x, g, o, rng, idle=0.2, bp=0.2)
    if lines:
        _fail(dut, lines)
    if cfg.frac_bits:
        it = nuc_core(x, g, o, cfg, intermediates=True)
        f = cfg.frac_bits
        assert (((it.s & ((1 << f) - 1)) == (1 << (f - 1))).sum()) >= 8, "no ties covered"


@cocotb.test()
async def reset_mid_stream(dut) -> None:
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 3)
    await tb_lib.start_clock_and_reset(dut)
    x, g, o = _random(cfg, rng, 50)
    src = tb_lib.Source(dut.s_valid_i, dut.s_ready_o,
                        [dut.s_pix_data_i, dut.s_gain_i, dut.s_offset_i, dut.s_user_i],
                        np.stack([x, g, o & ((1 << cfg.offset_bits) - 1), 0 * x], axis=1))
    sink = tb_lib.Sink(dut.m_valid_o, dut.m_ready_i, [dut.m_pix_data_o, dut.m_user_o], 0.5)
    await tb_lib.run_streams(dut, [src], sink, 10, rng)
    await tb_lib.reset(dut, 2)
    assert int(dut.m_valid_o.value) == 0
    await ClockCycles(dut.clk_i, 2)
    x, g, o = _random(cfg, rng, 300)
    lines, _ = await _run(dut, cfg, tb_lib.golden_config(cfg), x, g, o, rng, idle=0.2, bp=0.2)
    if lines:
        _fail(dut, lines)


@cocotb.test()
async def checker_detects_mismatch(dut) -> None:
    """Against another rounding mode (or overflow mode) the checker must complain."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 4)
    await tb_lib.start_clock_and_reset(dut)
    if cfg.frac_bits:
        other = cfg.replace(rounding="truncate" if cfg.rounding != "truncate" else "half_up")
    else:
        other = cfg.replace(overflow="wrap" if cfg.overflow == "saturate" else "saturate")
    x, g, o, _ = corner_coefficients(cfg, rng)
    lines, _ = await _run(dut, cfg, other, x, g, o, rng)
    assert lines, "no mismatch reported against a different golden configuration"
    assert all(k in lines[0] for k in ("x ", "gain", "offset", "expected", "got", " p ",
                                        " s ", " r ")), lines[0]
