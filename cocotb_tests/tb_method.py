"""cocotb tests of ``method_dpc_top`` (run through ``cocotb_tests/test_method_dpc_top.py``),
for the base method the DUT was built with.

Chain: stimulus (``method_stim``, seeded) -> the drive engine's sources (``streams``) on
``s_pix`` (raw code, markers, frame word; the frame size travels with it) and ``s_coef``
(the method's coefficient word) with pause patterns -> DUT -> sink with backpressure ->
:class:`irnuc.cosim.methods.MethodScoreboard` against ``nuc_fixed.method_top``. Widths are
read back from the DUT and compared with the Python side of the stream layouts
(``irnuc.cosim.stream``).
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Sequence

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.method_stim import (
    FramePlan,
    corner_frames,
    random_coefficients,
    random_raw,
    random_reading,
    random_registers,
)
from irnuc.cocotb_tests.streams import Sink, StreamBus, reset, run_streams
from irnuc.cosim import coverage
from irnuc.cosim.coverage import BACKPRESSURE_PATTERNS, IDLE_PATTERNS
from irnuc.cosim.methods import MethodFrame, MethodScoreboard, golden_frames
from irnuc.cosim.scoreboard import ScoreResult
from irnuc.cosim.stream import coef_stream_bits, frame_word_bits
from irnuc.nuc_fixed import PipelineConfig

TOP = "method_dpc_top"
#: Frames that change size follow each other back to back only from this many pixels on
#: (the size is sampled in dpc_core, after the method's pipeline: docs/rtl.md).
SIZE_CHANGE_MIN_PIXELS = 64


async def _setup(dut, salt: int) -> tb_lib.Env:
    """Clock, reset, the configuration and a seeded rng; the stream widths read back from
    the DUT against the layouts of irnuc.cosim.stream."""
    env = await tb_lib.setup(dut, salt)
    cfg = env.cfg
    pix, coef, out = (StreamBus.from_prefix(dut, p) for p in ("s_pix", "s_coef", "m_pix"))
    got = (pix.width("data"), pix.width("frame"), coef.width("data"), out.width("data"))
    want = (cfg.adc_bits, frame_word_bits(cfg), coef_stream_bits(cfg), cfg.out_bits)
    assert got == want, f"pixel, frame word, coefficient word and output widths {got}; " \
                        f"the layouts give {want}"
    return env


def _model(cfg: PipelineConfig):
    return coverage.model(TOP, cfg) if coverage.enabled() else None


def _frames(plans: list[FramePlan], golden: PipelineConfig) -> list[MethodFrame]:
    out = []
    for p in plans:
        out += golden_frames(p.coeffs, [p.raw], [p.reading], golden=golden)
    return out


async def run_frames(dut, frames: list[MethodFrame], golden: PipelineConfig,
                     rng: np.random.Generator, idle_pix: float | str = 0.0,
                     idle_coef: float | str = 0.0, backpressure: float | str = 0.0,
                     garbage: bool = True) -> tuple[ScoreResult, Sink, list[int]]:
    """Stream ``frames`` back to back (unless the sources pause) through the DUT; return the
    scoreboard's result (recorded for the suite runner), the sink and the input cycles of
    the pixels."""
    pix, coef = tb_lib.method_sources(dut, frames, rng, idle_pix, idle_coef, garbage)
    sink = Sink(StreamBus.from_prefix(dut, "m_pix"), backpressure, rng,
                expect=sum(f.raw.size for f in frames))
    await run_streams(dut, [pix, coef], sink)
    sb = MethodScoreboard(golden)
    for fr in frames:
        sb.expect_frame(fr)
    return tb_lib.score(sb, sink), sink, pix.taken


def _check(res: ScoreResult, frames: list[MethodFrame], cfg: PipelineConfig,
           golden: PipelineConfig, taken: list[int] | None = None,
           patterns: tuple[str, str, str] | None = None,
           bins: Sequence[tuple[str, str]] = ()) -> None:
    """The scoreboard's verdict (AssertionError with the first mismatch lines); on a pass
    the frames' coverage is sampled (against the configuration's own golden model), and
    ``bins`` (coverpoint, bin) the test reached."""
    tb_lib.assert_passed(res)
    cov = _model(cfg)
    if cov is None:
        return
    for point, name in bins:
        cov.sample(point, name)
    if golden != cfg:
        coverage.export()
        return
    for fr in frames:
        cov.sample_frame(fr.coeffs, fr.raw, fr.reading)
    for a, b in itertools.pairwise(frames):
        cov.sample_boundary(a.drive.frame_word, b.drive.frame_word, b.raw.size)
    if taken is not None:
        ends = np.cumsum([f.raw.size for f in frames])
        gaps = [taken[int(e)] - taken[int(e) - 1] - 1 for e in ends[:-1] if int(e) < len(taken)]
        cov.sample_frames([f.raw.shape for f in frames], gaps)
    if patterns is not None:
        cov.sample("stream.idle", patterns[0])
        cov.sample("stream.idle", patterns[1])
        cov.sample("stream.backpressure", patterns[2])
    coverage.export()


def _plans(cfg: PipelineConfig, rng: np.random.Generator, sizes: list[tuple[int, int]],
           same_coeffs: bool = False, bad_fraction: float = 0.05) -> list[FramePlan]:
    """Random frames of the given sizes, each with its own reading; one calibration per
    size (``same_coeffs``: registers kept across frames of one size)."""
    regs = random_registers(cfg, rng)
    by_size: dict[tuple[int, int], object] = {}
    plans = []
    for h, w in sizes:
        if not same_coeffs or (h, w) not in by_size:
            by_size[(h, w)] = random_coefficients(
                cfg, h, w, rng, bad_fraction, registers=regs if same_coeffs else None)
        c = by_size[(h, w)]
        plans.append(FramePlan(coeffs=c, raw=random_raw(cfg, h, w, rng),  # type: ignore[arg-type]
                               reading=random_reading(cfg, c, rng)))  # type: ignore[arg-type]
    return plans


@cocotb.test()
async def random_frames_full_rate(dut) -> None:
    """Three back-to-back frames (readings differ), valid = ready = 1: exact, and one pixel
    per clock from the first output to the last."""
    env = await _setup(dut, 0)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    frames = _frames(_plans(cfg, rng, [(12, 20)] * 3, same_coeffs=True), golden)
    res, sink, taken = await run_frames(dut, frames, golden, rng)
    _check(res, frames, cfg, golden, taken)
    assert sink.last_cycle - sink.first_cycle == len(sink.got) - 1, "bubbles at full rate"
    cov = _model(cfg)
    if cov is not None:
        cov.sample("stream.back_to_back", "frames")
        coverage.export()


@cocotb.test()
async def stream_patterns(dut) -> None:
    """Every idle pattern on each input x every backpressure pattern: exact; at full-rate
    input no cycle is lost inside the DUT."""
    env = await _setup(dut, 1)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    for k, idle in enumerate(IDLE_PATTERNS):
        for bp in BACKPRESSURE_PATTERNS:
            other = IDLE_PATTERNS[(k + 1) % len(IDLE_PATTERNS)] if idle != "none" else "none"
            frames = _frames(_plans(cfg, rng, [(4, 9), (4, 9)], same_coeffs=True), golden)
            res, sink, taken = await run_frames(dut, frames, golden, rng, idle_pix=idle,
                                                idle_coef=other, backpressure=bp)
            _check(res, frames, cfg, golden, taken, (idle, other, bp))
            tb_lib.record(pattern=[idle, bp], passed=True, message="", outputs=len(sink.got),
                          stalls=sink.stalls)
            if idle == "none":
                sink.check_throughput()


@cocotb.test()
async def frame_word_changes(dut) -> None:
    """The frame word (reading, registers, weight) changes at every frame boundary, frames
    back to back, down to 1x1 frames far shorter than the pipeline; every pixel but a
    frame's first carries a random word that must be ignored. Then a word that stays:
    frames of one calibration and one reading back to back."""
    env = await _setup(dut, 2)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    for shape in ((1, 1), (1, 3), (2, 2), (6, 11)):
        frames = _frames(_plans(cfg, rng, [shape] * 6), golden)
        res, _, taken = await run_frames(dut, frames, golden, rng, backpressure="random")
        _check(res, frames, cfg, golden, taken)
    plans = _plans(cfg, rng, [(6, 11)] * 3, same_coeffs=True)
    frames = _frames([dataclasses.replace(p, reading=plans[0].reading) for p in plans], golden)
    res, _, taken = await run_frames(dut, frames, golden, rng, backpressure="random")
    _check(res, frames, cfg, golden, taken)


@cocotb.test()
async def frame_size_changes(dut) -> None:
    """Frames of other sizes back to back (width only, height only, both), then 1xN, Nx1
    and 1x1 frames after an idle gap; every frame with its own calibration and reading."""
    env = await _setup(dut, 3)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    big = [(8, 12), (8, 16), (10, 16), (12, 9), (12, 9)]
    assert all(h * w >= SIZE_CHANGE_MIN_PIXELS for h, w in big)
    # Under backpressure, then at full rate: a stall can delay a frame's first pixel (an
    # idle gap, not a back-to-back change); at full rate every change is back to back.
    for bp in ("random", 0.0):
        frames = _frames(_plans(cfg, rng, big), golden)
        res, _, taken = await run_frames(dut, frames, golden, rng, backpressure=bp)
        _check(res, frames, cfg, golden, taken)
    for shape in ((1, 7), (7, 1), (1, 1)):
        await ClockCycles(dut.clk_i, 60)  # the previous frame leaves: a new size is safe
        frames = _frames(_plans(cfg, rng, [shape, shape]), golden)
        res, _, taken = await run_frames(dut, frames, golden, rng)
        _check(res, frames, cfg, golden, taken, bins=[("frame.transition", "after_idle")])


@cocotb.test()
async def corners(dut) -> None:
    """Frames chosen to hit every bin of the method's coverage (saturation of every
    intermediate, polynomial and interpolation extremes, rounding ties, breakpoints),
    with idle cycles and backpressure."""
    env = await _setup(dut, 4)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    frames = _frames(corner_frames(cfg, rng), golden)
    res, _, taken = await run_frames(dut, frames, golden, rng, idle_pix="bursty",
                                     backpressure="alternate")
    _check(res, frames, cfg, golden, taken)


@cocotb.test()
async def reset_mid_frame(dut) -> None:
    """Reset in the middle of a frame (outputs owed, coefficients in flight): no output
    until the next frame, which comes out exact."""
    env = await _setup(dut, 5)
    cfg, golden, rng = env.cfg, env.golden, env.rng
    frames = _frames(_plans(cfg, rng, [(6, 10)]), golden)
    pix, coef = tb_lib.method_sources(dut, frames, rng, 0.0, 0.0, garbage=False)
    sink = Sink(StreamBus.from_prefix(dut, "m_pix"), 0.5, rng, expect=5)
    await run_streams(dut, [pix, coef], sink)
    await reset(dut, 2)
    assert int(dut.m_pix_valid_o.value) == 0, "an output after reset"
    await ClockCycles(dut.clk_i, 2)
    frames = _frames(_plans(cfg, rng, [(6, 10)]), golden)
    res, _, taken = await run_frames(dut, frames, golden, rng, idle_pix="random",
                                     backpressure="random")
    _check(res, frames, cfg, golden, taken, bins=[("reset.mid_frame", "reset")])


@cocotb.test()
async def checker_detects_mismatch(dut) -> None:
    """Against the golden model of another rounding mode the scoreboard must fail, with the
    inputs and the golden core's intermediates in its lines."""
    env = await _setup(dut, 6)
    cfg, rng = env.cfg, env.rng
    other = cfg.replace(rounding="truncate" if cfg.rounding != "truncate" else "half_up")
    frames = _frames(corner_frames(cfg, rng), other)
    res, _, _ = await run_frames(dut, frames, other, rng)
    assert res.mismatches > 0, "no mismatch against another rounding mode"
    assert all(k in res.lines[0] for k in ("raw", "expected", "got", "golden s", " r ")), \
        res.lines[0]
