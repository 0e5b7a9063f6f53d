"""cocotb tests of ``nuc_core`` alone (run through ``cocotb_tests/test_nuc_core.py``).

Items (code, gain, offset, user side band) are a flat stream here (no frame); the user
side band must pass unchanged. Streams ``s`` and ``m`` are found by prefix; the
scoreboard is :class:`irnuc.cosim.NucScoreboard`.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.directed import corner_coefficients
from irnuc.cocotb_tests.streams import (
    Sink,
    Source,
    StreamBus,
    coverage_sample,
    reset,
    run_streams,
)
from irnuc.cosim import coverage
from irnuc.cosim.scoreboard import NucScoreboard, ScoreResult
from irnuc.nuc_fixed import PipelineConfig, nuc_core


def _source(env: tb_lib.Env, x, g, o, user, idle: float | str = 0.0) -> Source:
    mask = (1 << env.cfg.offset_bits) - 1
    return Source(StreamBus.from_prefix(env.dut, "s"),
                  {"pix_data": x, "gain": g, "offset": np.asarray(o) & mask, "user": user},
                  idle, env.rng)


async def _run(env: tb_lib.Env, x, g, o, idle: float | str = 0.0, bp: float | str = 0.0,
               golden: PipelineConfig | None = None) -> tuple[ScoreResult, Sink]:
    """Stream the items, score them against ``golden`` (the run's golden model by default)."""
    out = StreamBus.from_prefix(env.dut, "m")
    user = env.rng.integers(0, 1 << out.width("user"), size=len(x))
    sink = Sink(out, bp, env.rng, expect=len(x))
    await run_streams(env.dut, [_source(env, x, g, o, user, idle)], sink)
    gcfg = golden or env.golden
    sb = NucScoreboard(gcfg)
    sb.expect_items(x, g, o, user)
    res = tb_lib.score(sb, sink)
    if res.passed and gcfg == env.cfg and coverage.enabled():
        coverage.model("nuc_core", env.cfg).sample_nuc(np.asarray(x), np.asarray(g),
                                                       np.asarray(o))
        coverage.export()
    return res, sink


async def _setup(dut, salt: int) -> tb_lib.Env:
    env = await tb_lib.setup(dut, salt)
    ins, out = StreamBus.from_prefix(dut, "s"), StreamBus.from_prefix(dut, "m")
    got = (ins.width("pix_data"), ins.width("gain"), ins.width("offset"), out.width("pix_data"))
    want = (env.cfg.adc_bits, env.cfg.gain_bits, env.cfg.offset_bits, env.cfg.out_bits)
    assert got == want, f"port widths {got}, configuration {want}"
    return env


@cocotb.test()
async def random_full_rate(dut) -> None:
    """Random codes at valid=1/ready=1: exact and one result per clock."""
    env = await _setup(dut, 0)
    x, g, o = tb_lib.random_codes(env.rng, env.cfg, 2000)
    res, sink = await _run(env, x, g, o)
    tb_lib.assert_passed(res)
    assert sink.last_cycle - sink.first_cycle == len(x) - 1, "bubbles at full rate"
    coverage_sample("stream.back_to_back", "frames")
    coverage.export()


@cocotb.test()
async def stream_patterns(dut) -> None:
    """Every idle x backpressure pattern: exact; at full-rate input no lost cycle."""
    env = await _setup(dut, 5)
    for idle in coverage.IDLE_PATTERNS:
        for bp in coverage.BACKPRESSURE_PATTERNS:
            res, sink = await _run(env, *tb_lib.random_codes(env.rng, env.cfg, 60), idle, bp)
            tb_lib.assert_passed(res)
            if idle == "none":
                sink.check_throughput()


@cocotb.test()
async def reset_each_stage(dut) -> None:
    """Reset while the leading item is in each stage; the stream after it is exact."""
    env = await _setup(dut, 6)
    for k, stage in enumerate(coverage.pipeline_stages("nuc_core", env.cfg)):
        x, g, o = tb_lib.random_codes(env.rng, env.cfg, 20)
        src = _source(env, x, g, o, 0 * x)
        await run_streams(dut, [src], Sink(StreamBus.from_prefix(dut, "m")),
                          stop=lambda c, s=src, k=k: bool(s.taken) and c >= s.taken[0] + k)
        await reset(dut)
        assert int(dut.m_valid_o.value) == 0
        coverage_sample("reset.stage", stage)
        tb_lib.assert_passed((await _run(env, *tb_lib.random_codes(env.rng, env.cfg, 30)))[0])


@cocotb.test()
async def random_gaps_backpressure(dut) -> None:
    env = await _setup(dut, 1)
    res, _ = await _run(env, *tb_lib.random_codes(env.rng, env.cfg, 2000), idle=0.3, bp=0.4)
    tb_lib.assert_passed(res)


@cocotb.test()
async def corner_codes(dut) -> None:
    """Largest code x largest gain, saturation (or wrap) at both ends, rounding ties."""
    env = await _setup(dut, 2)
    x, g, o, _ = corner_coefficients(env.cfg, env.rng)
    tb_lib.assert_passed((await _run(env, x, g, o, idle=0.2, bp=0.2))[0])
    if env.cfg.frac_bits:
        it = nuc_core(x, g, o, env.cfg, intermediates=True)
        f = env.cfg.frac_bits
        assert (((it.s & ((1 << f) - 1)) == (1 << (f - 1))).sum()) >= 8, "no ties covered"


@cocotb.test()
async def reset_mid_stream(dut) -> None:
    env = await _setup(dut, 3)
    x, g, o = tb_lib.random_codes(env.rng, env.cfg, 50)
    sink = Sink(StreamBus.from_prefix(dut, "m"), 0.5, env.rng, expect=10)
    await run_streams(dut, [_source(env, x, g, o, 0 * x)], sink)
    await reset(dut, 2)
    assert int(dut.m_valid_o.value) == 0
    await ClockCycles(dut.clk_i, 2)
    res, _ = await _run(env, *tb_lib.random_codes(env.rng, env.cfg, 300), idle=0.2, bp=0.2)
    tb_lib.assert_passed(res)


@cocotb.test()
async def checker_detects_mismatch(dut) -> None:
    """Against another rounding mode (or overflow mode) the checker must complain."""
    env = await _setup(dut, 4)
    cfg = env.cfg
    if cfg.frac_bits:
        other = cfg.replace(rounding="truncate" if cfg.rounding != "truncate" else "half_up")
    else:
        other = cfg.replace(overflow="wrap" if cfg.overflow == "saturate" else "saturate")
    x, g, o, _ = corner_coefficients(cfg, env.rng)
    res, _ = await _run(env, x, g, o, golden=other)
    assert not res.passed, "no mismatch reported against a different golden configuration"
    assert all(k in res.lines[0] for k in ("x ", "gain", "offset", "expected", "got", " p ",
                                           " s ", " r ")), res.lines[0]
