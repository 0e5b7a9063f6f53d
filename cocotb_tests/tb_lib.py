"""Shared cocotb testbench parts: stream drivers, the output monitor and the checker.

Chain: stimulus (numpy, seeded) -> driver (valid/ready sources, random idle gaps) -> DUT
-> monitor (sink with random backpressure) -> in-order checker against the golden model
(``nuc_fixed``), which reports frame, x, y, the inputs, expected, got and the golden NUC
intermediates p, s, r of every mismatching pixel.

Timing convention (measured on Verilator 5 + cocotb 2): at ``RisingEdge(clk)`` a read
returns the value sampled by that edge, and a write is seen by the next edge. So one
await per cycle is enough: read ready/valid (transfers that just happened), then drive
the next cycle. Every width is read back from the DUT, never restated.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field

import numpy as np
from cocotb.clock import Clock
from cocotb.handle import SimHandleBase
from cocotb.triggers import ClockCycles, RisingEdge, Timer

from irnuc.cosim.scoreboard import ScoreResult, TopScoreboard
from irnuc.cosim.suite import METRICS_ENV
from irnuc.nuc_fixed import PipelineConfig, dpc_core, nuc_dpc_top, pack_words

CLK_PERIOD_NS = 10


def config_from_env(var: str = "IRNUC_CONFIG_JSON") -> PipelineConfig:
    """The configuration the DUT was built with (set by ``irnuc.cosim.run``)."""
    return PipelineConfig(**json.loads(os.environ[var]))


def golden_config(cfg: PipelineConfig) -> PipelineConfig:
    """The golden model's configuration: the DUT's unless a test deliberately changes it."""
    text = os.environ.get("IRNUC_GOLDEN_JSON")
    return PipelineConfig(**json.loads(text)) if text else cfg


def seed_from_env() -> int:
    return int(os.environ.get("IRNUC_SEED", "1"))


async def start_clock_and_reset(dut: SimHandleBase, cycles: int = 3) -> None:
    """Start ``clk_i`` and pulse the asynchronous active-low reset ``rst_ni``."""
    Clock(dut.clk_i, CLK_PERIOD_NS, unit="ns").start()
    await reset(dut, cycles)


async def reset(dut: SimHandleBase, cycles: int = 3) -> None:
    """Assert ``rst_ni`` between clock edges (it is asynchronous), release it likewise."""
    await Timer(CLK_PERIOD_NS // 4, unit="ns")
    dut.rst_ni.value = 0
    await ClockCycles(dut.clk_i, cycles)
    await Timer(CLK_PERIOD_NS // 4, unit="ns")
    dut.rst_ni.value = 1
    await RisingEdge(dut.clk_i)


# ---- stimulus ----------------------------------------------------------------------------

def random_coefficients(rng: np.random.Generator, cfg: PipelineConfig, h: int, w: int,
                        bad_fraction: float = 0.05) -> np.ndarray:
    """Random coefficient words over the full gain and offset code ranges."""
    g = rng.integers(0, 1 << cfg.gain_bits, size=(h, w), dtype=np.int64)
    half = 1 << (cfg.offset_bits - 1)
    o = rng.integers(-half, half, size=(h, w), dtype=np.int64)
    bad = rng.random((h, w)) < bad_fraction
    return pack_words(g, o, bad, cfg)


def unity_coefficients(cfg: PipelineConfig, gain: np.ndarray | float, offset: np.ndarray | float,
                       bad: np.ndarray) -> np.ndarray:
    """Words with gain/offset given as real values (rounded to the code grid, clipped)."""
    g = np.clip(np.rint(np.asarray(gain, dtype=float) * (1 << cfg.gain_frac_bits)),
                0, (1 << cfg.gain_bits) - 1).astype(np.int64)
    half = 1 << (cfg.offset_bits - 1)
    o = np.clip(np.rint(np.asarray(offset, dtype=float) * (1 << cfg.offset_frac_bits)),
                -half, half - 1).astype(np.int64)
    g, o = np.broadcast_arrays(g, o)
    g = np.broadcast_to(g, bad.shape)
    o = np.broadcast_to(o, bad.shape)
    return pack_words(g, o, bad, cfg)


# ---- expected values and mismatch reports ------------------------------------------------

@dataclass
class Frame:
    """One frame of stimulus and its golden output."""

    raw: np.ndarray     # (H, W) raw codes
    words: np.ndarray   # (H, W) uint64 coefficient words
    expected: np.ndarray = field(default_factory=lambda: np.zeros(0))


def golden_frame(raw: np.ndarray, words: np.ndarray, gcfg: PipelineConfig) -> Frame:
    return Frame(raw=raw, words=words, expected=nuc_dpc_top(raw, words, gcfg).astype(np.int64))


def record(**metrics: object) -> None:
    """Append one JSON line of metrics for the suite runner (``irnuc.cosim.suite``), if it
    asked for them (``$IRNUC_TB_METRICS``)."""
    path = os.environ.get(METRICS_ENV)
    if path:
        with open(path, "a") as fh:
            fh.write(json.dumps(metrics, default=int) + "\n")


def check_frames(frames: list[Frame], got: list[tuple[int, ...]], gcfg: PipelineConfig,
                 max_report: int = 10) -> ScoreResult:
    """In-order check of the output stream (data, sof, eol) against the golden frames,
    with the one scoreboard of irnuc (``irnuc.cosim.TopScoreboard``); the result is also
    recorded for the suite runner."""
    sb = TopScoreboard(gcfg, max_report=max_report)
    for fr in frames:
        sb.expect_frames(fr.raw, fr.words, fr.expected)
    for d, sof, eol in got:
        sb.observe(data=d, sof=sof, eol=eol)
    res = sb.result()
    record(compared=res.compared, errors=res.errors, mismatches=res.mismatches,
           missing=res.missing, extra=res.extra, lines=res.lines[:10])
    return res


def assert_no_mismatch(res: ScoreResult, log) -> None:
    if not res.passed:
        for line in res.lines:
            log.error(line)
        raise AssertionError(res.report())


# ---- the per-cycle stream engine ---------------------------------------------------------

class Source:
    """A valid/ready source driving rows of ``values`` onto ``data`` handles."""

    def __init__(self, valid: SimHandleBase, ready: SimHandleBase | None,
                 data: list[SimHandleBase], values: np.ndarray, idle: float = 0.0) -> None:
        self.valid, self.ready, self.data = valid, ready, data
        self.values = [[int(v) for v in row] for row in np.asarray(values).reshape(len(values), -1)]
        self.idle = idle
        self.idx = 0          # next item to send
        self.driving = False  # valid is high this cycle
        self.held = False     # valid was high at the last edge and the item was not taken
        self.last: list[int] = [-1] * len(data)
        valid.value = 0

    @property
    def done(self) -> bool:
        return self.idx >= len(self.values)


class Sink:
    """A valid/ready sink collecting ``data`` handles (with random backpressure)."""

    def __init__(self, valid: SimHandleBase, ready: SimHandleBase,
                 data: list[SimHandleBase], backpressure: float = 0.0) -> None:
        self.valid, self.ready, self.data = valid, ready, data
        self.bp = backpressure
        self.got: list[tuple[int, ...]] = []
        self.ready_now = False
        self.first_cycle = -1
        self.last_cycle = -1
        ready.value = 0


async def run_streams(dut: SimHandleBase, sources: list[Source], sink: Sink, n_out: int,
                      rng: np.random.Generator, max_cycles: int | None = None) -> int:
    """Drive the sources and collect ``n_out`` outputs; return the cycles used.

    Raises AssertionError if the outputs do not arrive within ``max_cycles``.
    """
    clk = dut.clk_i
    limit = max_cycles if max_cycles is not None else 20 * (n_out + 100) + 50_000
    block = 4096
    cycle = 0
    rand = rng.random((block, len(sources) + 1))
    edge = RisingEdge(clk)
    while len(sink.got) < n_out:
        if cycle >= limit:
            raise AssertionError(f"timeout: {len(sink.got)} of {n_out} outputs after "
                                 f"{cycle} cycles")
        r = rand[cycle % block]
        if cycle % block == block - 1:
            rand = rng.random((block, len(sources) + 1))
        # drive this cycle; an offered item stays offered until it is taken (AXI-Stream
        # rule, checked by the RTL's assertions): idle gaps only between items
        for i, src in enumerate(sources):
            want = not src.done and (src.held or src.idle == 0.0 or r[i] >= src.idle)
            if want:
                row = src.values[src.idx]
                for h, v, old in zip(src.data, row, src.last, strict=True):
                    if v != old:
                        h.value = v
                src.last = row
            if want != src.driving:
                src.valid.value = int(want)
                src.driving = want
        rdy = sink.bp == 0.0 or r[-1] >= sink.bp
        if rdy != sink.ready_now:
            sink.ready.value = int(rdy)
            sink.ready_now = rdy
        await edge
        cycle += 1
        # transfers at this edge
        for src in sources:
            fired = src.driving and (src.ready is None or bool(src.ready.value))
            if fired:
                src.idx += 1
            src.held = src.driving and not fired
        if sink.ready_now and sink.valid.value:
            sink.got.append(tuple(int(h.value) for h in sink.data))
            if sink.first_cycle < 0:
                sink.first_cycle = cycle
            sink.last_cycle = cycle
    for src in sources:
        if src.driving:
            src.valid.value = 0
            src.driving = False
            src.held = False
    sink.ready.value = 0
    sink.ready_now = False
    return cycle


# ---- top-level helpers ---------------------------------------------------------------------

def top_sources(dut: SimHandleBase, frames: list[Frame], idle_pix: float = 0.0,
                idle_coef: float = 0.0) -> tuple[Source, Source]:
    """Pixel and coefficient sources of ``nuc_dpc_top`` for a list of frames."""
    pix_rows, coef_rows = [], []
    for fr in frames:
        h, w = fr.raw.shape
        ys, xs = np.mgrid[0:h, 0:w]
        pix_rows.append(np.stack([fr.raw.ravel(), ((ys == 0) & (xs == 0)).ravel(),
                                  (xs == w - 1).ravel()], axis=1))
        coef_rows.append(fr.words.ravel().astype(object)[:, None])
    pix = Source(dut.s_pix_valid_i, dut.s_pix_ready_o,
                 [dut.s_pix_data_i, dut.s_pix_sof_i, dut.s_pix_eol_i],
                 np.concatenate(pix_rows), idle_pix)
    coef = Source(dut.s_coef_valid_i, dut.s_coef_ready_o, [dut.s_coef_data_i],
                  np.concatenate(coef_rows), idle_coef)
    return pix, coef


def top_sink(dut: SimHandleBase, backpressure: float = 0.0) -> Sink:
    return Sink(dut.m_pix_valid_o, dut.m_pix_ready_i,
                [dut.m_pix_data_o, dut.m_pix_sof_o, dut.m_pix_eol_o], backpressure)


async def run_top_frames(dut: SimHandleBase, frames: list[Frame], rng: np.random.Generator,
                         idle_pix: float = 0.0, idle_coef: float = 0.0,
                         backpressure: float = 0.0) -> tuple[list[tuple[int, ...]], int, Sink]:
    """Stream frames (all of one size) through ``nuc_dpc_top``; return outputs and cycles."""
    h, w = frames[0].raw.shape
    dut.frame_width_i.value = w
    dut.frame_height_i.value = h
    pix, coef = top_sources(dut, frames, idle_pix, idle_coef)
    sink = top_sink(dut, backpressure)
    n = sum(f.raw.size for f in frames)
    cycles = await run_streams(dut, [pix, coef], sink, n, rng)
    return sink.got, cycles, sink


def dut_widths(dut: SimHandleBase) -> dict[str, int]:
    """Port widths read back from the DUT."""
    return {name: len(getattr(dut, name)) for name in
            ("s_pix_data_i", "s_coef_data_i", "m_pix_data_o", "frame_width_i",
             "frame_height_i") if hasattr(dut, name)}


def check_top_widths(dut: SimHandleBase, cfg: PipelineConfig) -> None:
    """The DUT's port widths agree with the configuration's derived widths."""
    w = dut_widths(dut)
    assert w["s_pix_data_i"] == cfg.adc_bits, w
    assert w["s_coef_data_i"] == cfg.word_bits, w
    assert w["m_pix_data_o"] == cfg.out_bits, w


def golden_dpc(y: np.ndarray, bad: np.ndarray, cfg: PipelineConfig) -> np.ndarray:
    return dpc_core(y, bad, cfg).astype(np.int64)
