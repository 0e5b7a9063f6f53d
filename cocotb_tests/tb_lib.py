"""What every testbench shares beside the drive engine (``streams``): the run's
configuration and seed, set-up, stimulus, scoring against the golden model, and the
helpers of the ``nuc_dpc_top`` streams.

Chain of every test: stimulus (numpy, seeded) -> :class:`~irnuc.cocotb_tests.streams.Source`
(valid/ready driver with idle patterns) -> DUT -> :class:`~irnuc.cocotb_tests.streams.Sink`
(monitor with backpressure) -> the golden model's expected outputs -> one in-order
scoreboard (:mod:`irnuc.cosim.scoreboard`) -> :func:`score` (the result, recorded for the
suite runner) -> :func:`assert_passed`.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field

import cocotb
import numpy as np
from cocotb.handle import SimHandleBase

from irnuc.cocotb_tests.streams import (
    CLK_PERIOD_NS,
    Sink,
    Source,
    StreamBus,
    config_from_env,
    reset,
    run_streams,
    start_clock_and_reset,
)
from irnuc.cosim import coverage
from irnuc.cosim.methods import MethodFrame
from irnuc.cosim.metrics import record
from irnuc.cosim.scoreboard import Scoreboard, ScoreResult, TopScoreboard
from irnuc.nuc_fixed import PipelineConfig, nuc_dpc_top, pack_words, unpack_words

__all__ = ["CLK_PERIOD_NS", "Env", "Frame", "config_from_env", "record", "reset", "setup",
           "start_clock_and_reset"]


def golden_config(cfg: PipelineConfig) -> PipelineConfig:
    """The golden model's configuration: the DUT's unless a test deliberately changes it."""
    text = os.environ.get("IRNUC_GOLDEN_JSON")
    return PipelineConfig(**json.loads(text)) if text else cfg


def seed_from_env() -> int:
    return int(os.environ.get("IRNUC_SEED", "1"))


@dataclass
class Env:
    """A test's set-up: the DUT, its configuration, the golden model's, a seeded rng."""

    dut: SimHandleBase
    cfg: PipelineConfig
    golden: PipelineConfig
    rng: np.random.Generator


async def setup(dut: SimHandleBase, salt: int = 0, reset_first: bool = True) -> Env:
    """The configuration (``$IRNUC_CONFIG_JSON``), the golden one, an rng seeded with
    ``$IRNUC_SEED + salt`` (one salt per test), then clock and reset."""
    cfg = config_from_env()
    env = Env(dut, cfg, golden_config(cfg), np.random.default_rng(seed_from_env() + salt))
    if reset_first:
        await start_clock_and_reset(dut)
    return env


# ---- stimulus ----------------------------------------------------------------------------

def random_codes(rng: np.random.Generator, cfg: PipelineConfig, n: int
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """n random raw codes, gain codes and (signed) offset codes over their full ranges."""
    x = rng.integers(0, 1 << cfg.adc_bits, size=n, dtype=np.int64)
    g = rng.integers(0, 1 << cfg.gain_bits, size=n, dtype=np.int64)
    half = 1 << (cfg.offset_bits - 1)
    return x, g, rng.integers(-half, half, size=n, dtype=np.int64)


def random_coefficients(rng: np.random.Generator, cfg: PipelineConfig, h: int, w: int,
                        bad_fraction: float = 0.05) -> np.ndarray:
    """Random coefficient words over the full gain and offset code ranges."""
    _, g, o = random_codes(rng, cfg, h * w)
    bad = rng.random((h, w)) < bad_fraction
    return pack_words(g.reshape(h, w), o.reshape(h, w), bad, cfg)


def unity_coefficients(cfg: PipelineConfig, gain: np.ndarray | float, offset: np.ndarray | float,
                       bad: np.ndarray) -> np.ndarray:
    """Words with gain/offset given as real values (rounded to the code grid, clipped)."""
    g = np.clip(np.rint(np.asarray(gain, dtype=float) * (1 << cfg.gain_frac_bits)),
                0, (1 << cfg.gain_bits) - 1).astype(np.int64)
    half = 1 << (cfg.offset_bits - 1)
    o = np.clip(np.rint(np.asarray(offset, dtype=float) * (1 << cfg.offset_frac_bits)),
                -half, half - 1).astype(np.int64)
    g, o = np.broadcast_arrays(g, o)
    return pack_words(np.broadcast_to(g, bad.shape), np.broadcast_to(o, bad.shape), bad, cfg)


def markers(h: int, w: int) -> tuple[np.ndarray, np.ndarray]:
    """sof and eol of a raster-order (H, W) frame, as 0/1 arrays."""
    pos = np.arange(h * w)
    return (pos == 0).astype(np.int64), (pos % w == w - 1).astype(np.int64)


# ---- scoring -----------------------------------------------------------------------------

def score(sb: Scoreboard, *sinks: Sink) -> ScoreResult:
    """Feed the sinks' outputs to the scoreboard, compare, and record the result for the
    suite runner (``irnuc.cosim.metrics``)."""
    for sink in sinks:
        sb.observe_arrays(**sink.outputs())
    res = sb.result()
    record(compared=res.compared, errors=res.errors, mismatches=res.mismatches,
           missing=res.missing, extra=res.extra, lines=res.lines[:10])
    return res


def assert_passed(res: ScoreResult) -> None:
    """Log the triage lines (cocotb's logger) and fail the test unless it passed."""
    if not res.passed:
        for line in res.lines:
            cocotb.log.error(line)
        raise AssertionError(res.report())


# ---- nuc_dpc_top -------------------------------------------------------------------------

@dataclass
class Frame:
    """One frame of stimulus and its golden output."""

    raw: np.ndarray     # (H, W) raw codes
    words: np.ndarray   # (H, W) uint64 coefficient words
    expected: np.ndarray = field(default_factory=lambda: np.zeros(0))


def golden_frame(raw: np.ndarray, words: np.ndarray, gcfg: PipelineConfig) -> Frame:
    return Frame(raw=raw, words=words, expected=nuc_dpc_top(raw, words, gcfg).astype(np.int64))


def top_sources(dut: SimHandleBase, frames: list[Frame], idle_pix: float | str = 0.0,
                idle_coef: float | str = 0.0, rng: np.random.Generator | None = None
                ) -> tuple[Source, Source]:
    """Pixel and coefficient sources of ``nuc_dpc_top`` for a list of frames.

    A pixel item carries the frame size ports with it (``frame_width``, ``frame_height``):
    a new size is applied together with its frame's first pixel (docs/rtl.md, frame size
    rule), so frames of different sizes can follow each other back to back.
    """
    cols: dict[str, list[np.ndarray]] = {k: [] for k in ("data", "sof", "eol", "frame_width",
                                                         "frame_height")}
    for fr in frames:
        h, w = fr.raw.shape
        sof, eol = markers(h, w)
        for k, v in (("data", fr.raw.ravel()), ("sof", sof), ("eol", eol),
                     ("frame_width", np.full(h * w, w)), ("frame_height", np.full(h * w, h))):
            cols[k].append(v)
    pix_bus = StreamBus.from_prefix(dut, "s_pix", extra=("frame_width_i", "frame_height_i"))
    pix = Source(pix_bus, {k: np.concatenate(v) for k, v in cols.items()}, idle_pix, rng)
    coef = Source(StreamBus.from_prefix(dut, "s_coef"),
                  {"data": np.concatenate([f.words.ravel().astype(object) for f in frames])},
                  idle_coef, rng)
    return pix, coef


def top_sink(dut: SimHandleBase, backpressure: float | str = 0.0,
             rng: np.random.Generator | None = None, expect: int | None = None) -> Sink:
    return Sink(StreamBus.from_prefix(dut, "m_pix"), backpressure, rng, expect)


def sample_transitions(sizes: list[tuple[int, int]], taken: list[int]) -> None:
    """Frame transitions seen by the input monitor (sizes of consecutive frames and the
    cycles their pixels were taken)."""
    top = os.environ.get("COCOTB_TOPLEVEL", "")
    if top in ("dpc_core", "nuc_dpc_top") and coverage.enabled():
        ends = np.cumsum([h * w for h, w in sizes])
        gaps = [taken[int(e)] - taken[int(e) - 1] - 1 for e in ends[:-1] if int(e) < len(taken)]
        coverage.model(top, config_from_env()).sample_frames(sizes, gaps)


async def run_top_frames(dut: SimHandleBase, frames: list[Frame], rng: np.random.Generator,
                         idle_pix: float | str = 0.0, idle_coef: float | str = 0.0,
                         backpressure: float | str = 0.0) -> tuple[Sink, int]:
    """Stream frames (of any sizes, back to back unless the sources pause) through
    ``nuc_dpc_top``; return the sink and the cycles."""
    pix, coef = top_sources(dut, frames, idle_pix, idle_coef, rng)
    sink = top_sink(dut, backpressure, rng, expect=sum(f.raw.size for f in frames))
    cycles = await run_streams(dut, [pix, coef], sink)
    sample_transitions([f.raw.shape for f in frames], pix.taken)
    return sink, cycles


def check_frames(frames: list[Frame], sink: Sink, gcfg: PipelineConfig,
                 max_report: int = 10) -> ScoreResult:
    """The top's outputs in ``sink`` against the golden frames (one :class:`TopScoreboard`),
    recorded for the suite runner; coverage of what was checked and passed."""
    sb = TopScoreboard(gcfg, max_report=max_report)
    for fr in frames:
        sb.expect_frames(fr.raw, fr.words, fr.expected)
    res = score(sb, sink)
    if res.passed and gcfg == config_from_env() and coverage.enabled():
        cov = coverage.model("nuc_dpc_top", gcfg)
        for fr in frames:
            g, o, bad = unpack_words(fr.words, gcfg)
            cov.sample_nuc(fr.raw, g, o)
            cov.sample_dpc(bad)
        coverage.export()
    return res


def check_top_widths(dut: SimHandleBase, cfg: PipelineConfig) -> None:
    """The DUT's port widths agree with the configuration's derived widths."""
    pix, coef, out = (StreamBus.from_prefix(dut, p) for p in ("s_pix", "s_coef", "m_pix"))
    got = (pix.width("data"), coef.width("data"), out.width("data"))
    assert got == (cfg.adc_bits, cfg.word_bits, cfg.out_bits), (
        f"pixel, word and output widths {got}; the configuration says "
        f"{(cfg.adc_bits, cfg.word_bits, cfg.out_bits)}")


def method_sources(dut, frames: list[MethodFrame], rng: np.random.Generator, idle_pix,
                   idle_coef, garbage: bool) -> tuple[Source, Source]:
    """The two sources of a method's top (``s_pix`` with the frame word, ``s_coef``; the
    frame size travels with the pixels); with ``garbage`` the frame word of every pixel but a
    frame's first is random (the RTL reads it at sof only)."""
    pix_bus = StreamBus.from_prefix(dut, "s_pix", extra=("frame_width_i", "frame_height_i"))
    fbits = pix_bus.width("frame")
    cols: dict[str, list[np.ndarray]] = {k: [] for k in pix_bus.names}
    for fr in frames:
        h, w = fr.raw.shape
        sof, eol = markers(h, w)
        word = np.full(h * w, fr.drive.frame_word, dtype=object)
        if garbage and h * w > 1:
            word[1:] = [int(v) for v in rng.integers(0, 1 << min(fbits, 62), size=h * w - 1)]
        for k, v in (("data", fr.raw.ravel()), ("sof", sof), ("eol", eol), ("frame", word),
                     ("frame_width", np.full(h * w, w)), ("frame_height", np.full(h * w, h))):
            cols[k].append(np.asarray(v, dtype=object))
    pix = Source(pix_bus, {k: np.concatenate(v) for k, v in cols.items()}, idle_pix, rng)
    coef = Source(StreamBus.from_prefix(dut, "s_coef"),
                  {"data": np.concatenate([f.drive.words.ravel() for f in frames])},
                  idle_coef, rng)
    return pix, coef
