"""cocotb tests of the stage top ``method_drift_top`` (one_point / two_point + blind_drift),
run through ``cocotb_tests/test_method_drift_top.py``.

Chain: stimulus (``method_stim`` and :mod:`irnuc.cosim.stages`, seeded) -> the drive
engine's sources (``streams``) on ``s_pix`` and ``s_coef`` (as ``tb_method``) and
``s_blind`` (each frame's blind codes, one item holding their sum, or partial sums; the
last item of a frame flagged) with pause patterns -> DUT -> sink with backpressure ->
:class:`irnuc.cosim.stages.StageScoreboard` against ``nuc_fixed.method_top``. The
calibration registers ``blind_ref`` and ``drift_gain`` are ports, set before each run of
frames (the DUT samples them with each frame's last blind item). Widths are read back
from the DUT and compared with the Python side of the layouts. The drift coverpoints
(``cosim.stage_coverage``: :class:`DriftCoverageModel`) are sampled from every run of
frames that passed against the configuration itself.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.method_stim import random_coefficients, random_raw
from irnuc.cocotb_tests.streams import Sink, Source, StreamBus, reset, run_streams
from irnuc.cosim import coverage
from irnuc.cosim.coverage import BACKPRESSURE_PATTERNS, IDLE_PATTERNS
from irnuc.cosim.scoreboard import ScoreResult
from irnuc.cosim.stages import DriftFrame, StageScoreboard, blind_items, drift_frames
from irnuc.cosim.stream import coef_stream_bits, frame_word_bits
from irnuc.nuc_fixed import PipelineConfig
from irnuc.nuc_fixed.method_top import MethodCoefficients

#: Blind items of a frame: the codes, one sum (a register), or partial sums.
BLIND_KINDS = ("codes", "sum", "partial")


async def _setup(dut, salt: int) -> tb_lib.Env:
    """Clock, reset, the configuration and a seeded rng; the stream and register widths
    read back from the DUT against the layouts."""
    env = await tb_lib.setup(dut, salt)
    cfg = env.cfg
    pix, coef, blind, out = (StreamBus.from_prefix(dut, p)
                             for p in ("s_pix", "s_coef", "s_blind", "m_pix"))
    got = (pix.width("data"), pix.width("frame"), coef.width("data"), blind.width("data"),
           len(dut.blind_ref_i), len(dut.drift_gain_i), out.width("data"))
    want = (cfg.adc_bits, frame_word_bits(cfg), coef_stream_bits(cfg), cfg.blind_sum_bits,
            cfg.registers["blind_ref"].width, cfg.registers["drift_gain"].width,
            cfg.out_bits)
    assert got == want, f"pixel, frame word, coefficient word, blind, blind_ref, " \
                        f"drift_gain and output widths {got}; the layouts give {want}"
    return env


def _registers(cfg: PipelineConfig, rng: np.random.Generator, bsum: int,
               extreme: str = "") -> dict[str, int]:
    """blind_ref near a typical blind sum (deltas over the drift range, some saturating)
    and a drift gain over its whole range; ``extreme``: ``"max"``/``"min"`` drive delta to
    saturation, ``"zero"`` gives m = 0."""
    g = cfg.registers["drift_gain"]
    glo, ghi = -(1 << (g.width - 1)), (1 << (g.width - 1)) - 1
    rmax = (1 << cfg.registers["blind_ref"].width) - 1
    if extreme == "max":
        return {"blind_ref": 0, "drift_gain": ghi}
    if extreme == "min":
        return {"blind_ref": rmax, "drift_gain": ghi}
    if extreme == "zero":
        return {"blind_ref": int(rng.integers(0, rmax + 1)), "drift_gain": 0}
    ref = int(np.clip(bsum + rng.integers(-4096, 4097), 0, rmax))
    return {"blind_ref": ref, "drift_gain": int(rng.integers(glo, ghi + 1))}


def _frames(cfg: PipelineConfig, golden: PipelineConfig, rng: np.random.Generator,
            sizes: list[tuple[int, int]], kinds: tuple[str, ...] = BLIND_KINDS,
            extreme: str = "", biased: bool = False) -> list[DriftFrame]:
    """Random frames of the given sizes, one calibration per size and one set of
    registers for all of them; each frame's blind codes (1..64 of them) around a common
    level, its items of the next kind in ``kinds``."""
    level = int(rng.integers(0, 1 << cfg.adc_bits))
    k0 = int(rng.integers(1, 65))
    regs = _registers(cfg, rng, level * k0, extreme)
    by_size: dict[tuple[int, int], MethodCoefficients] = {}
    out = []
    for i, (h, w) in enumerate(sizes):
        if (h, w) not in by_size:
            c = random_coefficients(cfg, h, w, rng, biased=biased)
            by_size[(h, w)] = MethodCoefficients(cfg, c.fields, {**c.registers, **regs})
        k = int(rng.integers(1, 65))
        codes = np.clip(level + rng.integers(-300, 301, size=k), 0, (1 << cfg.adc_bits) - 1)
        items = blind_items(codes, cfg, rng, kinds[i % len(kinds)])
        out += drift_frames(by_size[(h, w)], [random_raw(cfg, h, w, rng, biased)], [items],
                            golden=golden)
    return out


def _set_registers(dut, frames: list[DriftFrame]) -> None:
    regs = frames[0].coeffs.registers
    assert all(f.coeffs.registers == regs for f in frames), "registers change within a run"
    dut.blind_ref_i.value = int(regs["blind_ref"])
    dut.drift_gain_i.value = int(regs["drift_gain"]) & ((1 << len(dut.drift_gain_i)) - 1)


def _blind_source(dut, frames: list[DriftFrame], idle: float | str,
                  rng: np.random.Generator) -> Source:
    data = np.concatenate([f.blind for f in frames])
    last = np.concatenate([(np.arange(f.blind.size) == f.blind.size - 1).astype(np.int64)
                           for f in frames])
    return Source(StreamBus.from_prefix(dut, "s_blind"), {"data": data, "last": last}, idle,
                  rng)


async def run_frames(dut, frames: list[DriftFrame], golden: PipelineConfig,
                     rng: np.random.Generator, idle_pix: float | str = 0.0,
                     idle_coef: float | str = 0.0, idle_blind: float | str = 0.0,
                     backpressure: float | str = 0.0) -> tuple[ScoreResult, Sink]:
    """Stream ``frames`` (their blind items, pixels and words) through the DUT; return the
    scoreboard's result and the sink."""
    _set_registers(dut, frames)
    pix, coef = tb_lib.method_sources(dut, frames, rng, idle_pix, idle_coef, garbage=True)
    blind = _blind_source(dut, frames, idle_blind, rng)
    sink = Sink(StreamBus.from_prefix(dut, "m_pix"), backpressure, rng,
                expect=sum(f.raw.size for f in frames))
    await run_streams(dut, [blind, pix, coef], sink)
    sb = StageScoreboard(golden)
    for fr in frames:
        sb.expect_frame(fr)
    res = tb_lib.score(sb, sink)
    if res.passed and golden == frames[0].coeffs.cfg:
        for name, pattern in (("stream.idle", idle_pix), ("stream.idle", idle_coef),
                              ("stream.idle", idle_blind),
                              ("stream.backpressure", backpressure)):
            _sample(name, _pattern(pattern))
        if coverage.enabled():
            coverage.model("method_drift_top", golden).sample_frames_run(frames)
            coverage.export()
    return res, sink


def _pattern(p: float | str) -> str:
    """The coverage name of a pause pattern (a probability: 0 none, else random)."""
    return p if isinstance(p, str) else ("none" if p == 0 else "random")


def _sample(name: str, value: str) -> None:
    if coverage.enabled():
        coverage.model("method_drift_top", tb_lib.config_from_env()).sample(name, value)
        coverage.export()


@cocotb.test()
async def random_frames_full_rate(dut) -> None:
    """Three back-to-back frames, each with its blind items (codes, one sum, partial
    sums), valid = ready = 1: exact, with the frames' deltas not all equal, and one pixel
    per clock from the first output to the last."""
    env = await _setup(dut, 0)
    frames = _frames(env.cfg, env.golden, env.rng, [(12, 20)] * 3)
    assert len({f.delta for f in frames}) > 1, "the frames' deltas are all equal"
    res, sink = await run_frames(dut, frames, env.golden, env.rng)
    tb_lib.assert_passed(res)
    assert sink.last_cycle - sink.first_cycle == len(sink.got) - 1, "bubbles at full rate"
    _sample("stream.back_to_back", "frames")


@cocotb.test()
async def stream_patterns(dut) -> None:
    """Every idle pattern on the pixels (another on the words and blind items) x every
    backpressure pattern: exact; at full-rate input no cycle is lost inside the DUT."""
    env = await _setup(dut, 1)
    for k, idle in enumerate(IDLE_PATTERNS):
        for bp in BACKPRESSURE_PATTERNS:
            other = IDLE_PATTERNS[(k + 1) % len(IDLE_PATTERNS)] if idle != "none" else "none"
            frames = _frames(env.cfg, env.golden, env.rng, [(4, 9), (4, 9)])
            res, sink = await run_frames(dut, frames, env.golden, env.rng, idle_pix=idle,
                                         idle_coef=other, idle_blind=other, backpressure=bp)
            tb_lib.assert_passed(res)
            if idle == "none":
                sink.check_throughput()


@cocotb.test()
async def small_frames_and_sizes(dut) -> None:
    """Frames far shorter than the drift multiply (1x1, 1x3, 2x2) back to back, each
    waiting for its delta; then frames of other sizes back to back."""
    env = await _setup(dut, 2)
    for shape in ((1, 1), (1, 3), (2, 2)):
        frames = _frames(env.cfg, env.golden, env.rng, [shape] * 5)
        res, _ = await run_frames(dut, frames, env.golden, env.rng, backpressure="random")
        tb_lib.assert_passed(res)
    await ClockCycles(dut.clk_i, 60)
    frames = _frames(env.cfg, env.golden, env.rng, [(8, 12), (8, 16), (10, 16), (12, 9)])
    res, _ = await run_frames(dut, frames, env.golden, env.rng, idle_blind="bursty",
                              backpressure="random")
    tb_lib.assert_passed(res)


@cocotb.test()
async def drift_extremes(dut) -> None:
    """delta saturated at both ends of the drift format (x' far below zero and far above
    the raw range), m = 0, and biased calibrations and codes (every field at its ends,
    rounding ties), with idle cycles and backpressure."""
    env = await _setup(dut, 3)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    d = cfg.format("drift")
    top, bottom = (1 << (d.bits - 1)) - 1, -(1 << (d.bits - 1))
    for extreme, want in (("max", top), ("min", bottom), ("zero", 0), ("", None)):
        frames = _frames(cfg, golden, rng, [(6, 8)] * 2, extreme=extreme, biased=True)
        if want is not None and golden == cfg:
            assert all(f.delta == want for f in frames), (extreme, [f.delta for f in frames])
        res, _ = await run_frames(dut, frames, golden, rng, idle_pix="bursty",
                                  backpressure="alternate")
        tb_lib.assert_passed(res)


@cocotb.test()
async def reset_mid_frame(dut) -> None:
    """Reset in the middle of a frame (outputs owed, a delta and blind items in flight):
    no output until the next frame, which comes out exact."""
    env = await _setup(dut, 4)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    frames = _frames(cfg, golden, rng, [(6, 10), (6, 10)])
    _set_registers(dut, frames)
    pix, coef = tb_lib.method_sources(dut, frames, rng, 0.0, 0.0, garbage=False)
    blind = _blind_source(dut, frames, 0.0, rng)
    sink = Sink(StreamBus.from_prefix(dut, "m_pix"), 0.5, rng, expect=5)
    await run_streams(dut, [blind, pix, coef], sink)
    await reset(dut, 2)
    assert int(dut.m_pix_valid_o.value) == 0, "an output after reset"
    await ClockCycles(dut.clk_i, 2)
    frames = _frames(cfg, golden, rng, [(6, 10)])
    res, _ = await run_frames(dut, frames, golden, rng, idle_pix="random",
                              idle_blind="random", backpressure="random")
    tb_lib.assert_passed(res)
    _sample("reset.mid_frame", "reset")


@cocotb.test()
async def checker_detects_mismatch(dut) -> None:
    """Against the golden model with another rounding of delta the scoreboard must fail,
    with the frame's delta and x' in its lines."""
    env = await _setup(dut, 5)
    cfg, rng = env.cfg, env.rng
    other = cfg.replace(formats={"drift": {"rounding": "truncate"}})
    assert other.format("drift").rounding != cfg.format("drift").rounding
    frames = _frames(cfg, other, rng, [(4, 6)] * 6)
    res, _ = await run_frames(dut, frames, other, rng)
    assert res.mismatches > 0, "no mismatch against another rounding of delta"
    assert all(k in res.lines[0] for k in ("expected", "got", "delta", "x'")), res.lines[0]
