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

import itertools
import json
import os
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import numpy as np
from cocotb.clock import Clock
from cocotb.handle import SimHandleBase
from cocotb.triggers import ClockCycles, RisingEdge, Timer

from irnuc.cosim import coverage
from irnuc.cosim.scoreboard import ScoreResult, TopScoreboard
from irnuc.cosim.suite import METRICS_ENV
from irnuc.nuc_fixed import PipelineConfig, dpc_core, nuc_dpc_top, pack_words, unpack_words

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
    if res.passed and gcfg == config_from_env() and coverage.enabled():
        cov = coverage.model("nuc_dpc_top", gcfg)
        for fr in frames:
            g, o, bad = unpack_words(fr.words, gcfg)
            cov.sample_nuc(fr.raw, g, o)
            cov.sample_dpc(bad)
        coverage.export()
    return res


def assert_no_mismatch(res: ScoreResult, log) -> None:
    if not res.passed:
        for line in res.lines:
            log.error(line)
        raise AssertionError(res.report())


# ---- the per-cycle stream engine ---------------------------------------------------------

def pause_pattern(name: str, rng: np.random.Generator) -> Iterator[bool]:
    """An endless pause generator (True = pause this cycle), as cocotbext-axi's
    ``set_pause_generator``: ``none``, ``random`` (30 % of the cycles), ``bursty`` (runs of
    4-24 active cycles and 1-12 pauses) or ``alternate`` (every other cycle)."""
    if name == "none":
        return itertools.repeat(False)
    if name == "alternate":
        return itertools.cycle((False, True))
    if name == "random":
        def rand() -> Iterator[bool]:
            while True:
                yield from (rng.random(4096) < 0.3).tolist()
        return rand()
    if name == "bursty":
        def bursts() -> Iterator[bool]:
            while True:
                yield from itertools.repeat(False, int(rng.integers(4, 25)))
                yield from itertools.repeat(True, int(rng.integers(1, 13)))
        return bursts()
    raise ValueError(f"unknown pause pattern {name!r}; known: {coverage.IDLE_PATTERNS}")


def _pause(value: float | str, rng: np.random.Generator) -> tuple[str, Iterator[bool]]:
    """A pattern name or a pause probability (0.0 = never) -> (coverage name, generator)."""
    if isinstance(value, str):
        return value, pause_pattern(value, rng)
    if value == 0.0:
        return "none", itertools.repeat(False)

    def rand() -> Iterator[bool]:
        while True:
            yield from (rng.random(4096) < value).tolist()
    return "random", rand()


class Source:
    """A valid/ready source driving rows of ``values`` onto ``data`` handles.

    ``idle`` is a pause pattern name (:func:`pause_pattern`) or a pause probability; an
    item once offered stays offered, with its data, until it is taken (AXI-Stream rule).
    The input monitor: ``taken`` holds the cycle of every transfer.
    """

    def __init__(self, valid: SimHandleBase, ready: SimHandleBase | None,
                 data: list[SimHandleBase], values: np.ndarray, idle: float | str = 0.0,
                 rng: np.random.Generator | None = None) -> None:
        self.valid, self.ready, self.data = valid, ready, data
        self.values = [[int(v) for v in row] for row in np.asarray(values).reshape(len(values), -1)]
        self.pattern, self.pause = _pause(idle, rng or np.random.default_rng(0))
        self.idx = 0          # next item to send
        self.driving = False  # valid is high this cycle
        self.held = False     # valid was high at the last edge and the item was not taken
        self.last: list[int] = [-1] * len(data)
        self.taken: list[int] = []
        valid.value = 0

    @property
    def done(self) -> bool:
        return self.idx >= len(self.values)


class Sink:
    """A valid/ready sink collecting ``data`` handles, with a pause pattern (backpressure).

    ``first_cycle``/``last_cycle`` bracket the outputs; ``stalls`` counts the cycles from
    the first output to the last one in which the sink's ready was low.
    """

    def __init__(self, valid: SimHandleBase, ready: SimHandleBase,
                 data: list[SimHandleBase], backpressure: float | str = 0.0,
                 rng: np.random.Generator | None = None) -> None:
        self.valid, self.ready, self.data = valid, ready, data
        self.pattern, self.pause = _pause(backpressure, rng or np.random.default_rng(1))
        self.got: list[tuple[int, ...]] = []
        self.ready_now = False
        self.first_cycle = -1
        self.last_cycle = -1
        self.stalls = 0
        self._stalls_running = 0
        ready.value = 0

    def check_throughput(self, n: int | None = None) -> None:
        """No cycle lost inside the DUT: from the first output to the last, every cycle
        delivered an output or the sink stalled (``AssertionError`` otherwise)."""
        n = len(self.got) if n is None else n
        span = self.last_cycle - self.first_cycle + 1
        assert span == n + self.stalls, (
            f"{n} outputs took {span} cycles with {self.stalls} stalled cycles of the sink "
            f"({self.pattern}): {span - n - self.stalls} cycle(s) lost inside the DUT")


async def run_streams(dut: SimHandleBase, sources: list[Source], sink: Sink, n_out: int,
                      rng: np.random.Generator, max_cycles: int | None = None,
                      stop: Callable[[int], bool] | None = None) -> int:
    """Drive the sources and collect ``n_out`` outputs; return the cycles used.

    One coroutine, one ``await RisingEdge`` per cycle: each source drives its next item
    unless its pause generator says pause (an item already offered stays offered), the
    sink's ready follows its own pause generator; transfers are read after the edge.
    ``stop(cycle)``, asked after every edge, ends the run early (the valids and the ready
    go low). Raises AssertionError if the outputs do not arrive within ``max_cycles``.
    """
    clk = dut.clk_i
    limit = max_cycles if max_cycles is not None else 20 * (n_out + 100) + 50_000
    cycle = 0
    edge = RisingEdge(clk)
    for src in sources:
        coverage_sample("stream.idle", src.pattern)
    coverage_sample("stream.backpressure", sink.pattern)
    while len(sink.got) < n_out:
        if cycle >= limit:
            raise AssertionError(f"timeout: {len(sink.got)} of {n_out} outputs after "
                                 f"{cycle} cycles")
        # drive this cycle; an offered item stays offered until it is taken (AXI-Stream
        # rule, checked by the RTL's assertions): pauses only between items
        for src in sources:
            want = not src.done and (src.held or not next(src.pause))
            if want:
                row = src.values[src.idx]
                for h, v, old in zip(src.data, row, src.last, strict=True):
                    if v != old:
                        h.value = v
                src.last = row
            if want != src.driving:
                src.valid.value = int(want)
                src.driving = want
        rdy = not next(sink.pause)
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
                src.taken.append(cycle)
            src.held = src.driving and not fired
        if sink.ready_now:
            if sink.valid.value:
                sink.got.append(tuple(int(h.value) for h in sink.data))
                if sink.first_cycle < 0:
                    sink.first_cycle = cycle
                sink.last_cycle = cycle
                sink.stalls = sink._stalls_running
        elif sink.first_cycle >= 0:
            sink._stalls_running += 1
        if stop is not None and stop(cycle):
            break
    for src in sources:
        if src.driving:
            src.valid.value = 0
            src.driving = False
            src.held = False
    sink.ready.value = 0
    sink.ready_now = False
    return cycle


def coverage_sample(name: str, value: object) -> None:
    """Sample a coverpoint of the DUT's model (``$IRNUC_CONFIG_JSON``, ``$COCOTB_TOPLEVEL``)."""
    top = os.environ.get("COCOTB_TOPLEVEL", "")
    if top in ("nuc_core", "dpc_core", "nuc_dpc_top"):
        coverage.model(top, config_from_env()).sample(name, value)


# ---- top-level helpers ---------------------------------------------------------------------

def top_sources(dut: SimHandleBase, frames: list[Frame], idle_pix: float | str = 0.0,
                idle_coef: float | str = 0.0, rng: np.random.Generator | None = None
                ) -> tuple[Source, Source]:
    """Pixel and coefficient sources of ``nuc_dpc_top`` for a list of frames.

    A pixel item is ``(raw, sof, eol, width, height)``: the frame size ports travel with
    the pixels, so a new size is applied together with its frame's first pixel (docs/rtl.md,
    frame size rule) and frames of different sizes can follow each other back to back.
    """
    pix_rows, coef_rows = [], []
    for fr in frames:
        h, w = fr.raw.shape
        ys, xs = np.mgrid[0:h, 0:w]
        pix_rows.append(np.stack([fr.raw.ravel(), ((ys == 0) & (xs == 0)).ravel(),
                                  (xs == w - 1).ravel(), np.full(h * w, w),
                                  np.full(h * w, h)], axis=1))
        coef_rows.append(fr.words.ravel().astype(object)[:, None])
    pix = Source(dut.s_pix_valid_i, dut.s_pix_ready_o,
                 [dut.s_pix_data_i, dut.s_pix_sof_i, dut.s_pix_eol_i, dut.frame_width_i,
                  dut.frame_height_i], np.concatenate(pix_rows), idle_pix, rng)
    coef = Source(dut.s_coef_valid_i, dut.s_coef_ready_o, [dut.s_coef_data_i],
                  np.concatenate(coef_rows), idle_coef, rng)
    return pix, coef


def top_sink(dut: SimHandleBase, backpressure: float | str = 0.0,
             rng: np.random.Generator | None = None) -> Sink:
    return Sink(dut.m_pix_valid_o, dut.m_pix_ready_i,
                [dut.m_pix_data_o, dut.m_pix_sof_o, dut.m_pix_eol_o], backpressure, rng)


def sample_transitions(sizes: list[tuple[int, int]], taken: list[int]) -> None:
    """Frame transitions seen by the input monitor (sizes of consecutive frames and the
    cycles their pixels were taken)."""
    ends = np.cumsum([h * w for h, w in sizes])
    gaps = [taken[int(e)] - taken[int(e) - 1] - 1 for e in ends[:-1] if int(e) < len(taken)]
    top = os.environ.get("COCOTB_TOPLEVEL", "")
    if top in ("dpc_core", "nuc_dpc_top") and coverage.enabled():
        coverage.model(top, config_from_env()).sample_frames(sizes, gaps)


async def run_top_frames(dut: SimHandleBase, frames: list[Frame], rng: np.random.Generator,
                         idle_pix: float | str = 0.0, idle_coef: float | str = 0.0,
                         backpressure: float | str = 0.0
                         ) -> tuple[list[tuple[int, ...]], int, Sink]:
    """Stream frames (of any sizes, back to back unless the sources pause) through
    ``nuc_dpc_top``; return the outputs, the cycles and the sink."""
    h, w = frames[0].raw.shape
    dut.frame_width_i.value = w
    dut.frame_height_i.value = h
    pix, coef = top_sources(dut, frames, idle_pix, idle_coef, rng)
    sink = top_sink(dut, backpressure, rng)
    n = sum(f.raw.size for f in frames)
    cycles = await run_streams(dut, [pix, coef], sink, n, rng)
    sample_transitions([f.raw.shape for f in frames], pix.taken)
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
