"""cocotb tests of ``irnuc_axis_top`` (run by ``cocotb_tests/test_axis_top.py``).

The AXI ports are driven by cocotbext-axi: ``AxiStreamSource`` on ``s_axis_video`` and
``s_axis_coef``, ``AxiStreamSink`` on ``m_axis_video`` (one pixel or word per beat:
``byte_lanes=1``), ``AxiLiteMaster`` on ``s_axil``; every bus is found by its prefix.
Expected values come from the golden models: the register file's
(:class:`irnuc.nuc_fixed.regmap.RegisterModel`: every address, reset value, response and
read-back) and the framing's (:func:`irnuc.nuc_fixed.axis.axis_framer`: the frames the core
gets, the counted events), then the core's through the one in-order scoreboard
(:class:`irnuc.cosim.TopScoreboard`, bit for bit). The RTL's AXI protocol assertions are
on in every build.
"""

from __future__ import annotations

import logging
import warnings

# cocotbext-axi 0.1.28's AXI4-Lite master reads cocotb 2's deprecated Event.data.
warnings.filterwarnings("ignore", message="The data field will be removed",
                        category=DeprecationWarning)

import cocotb  # noqa: E402
import numpy as np  # noqa: E402
from cocotb.triggers import (  # noqa: E402
    ClockCycles,
    Lock,
    RisingEdge,
    SimTimeoutError,
    with_timeout,
)
from cocotbext.axi import (  # noqa: E402
    AxiLiteBus,
    AxiLiteMaster,
    AxiStreamBus,
    AxiStreamFrame,
    AxiStreamSink,
    AxiStreamSource,
)

from irnuc.cocotb_tests import tb_lib  # noqa: E402
from irnuc.cocotb_tests.streams import CLK_PERIOD_NS, pause_pattern, reset  # noqa: E402
from irnuc.cosim import coverage  # noqa: E402
from irnuc.cosim.axis_coverage import drift_delta_class  # noqa: E402
from irnuc.cosim.methods import MethodScoreboard, golden_frames  # noqa: E402
from irnuc.cosim.scoreboard import TopScoreboard  # noqa: E402
from irnuc.cosim.stages import StageScoreboard, drift_frame_from_sum  # noqa: E402
from irnuc.nuc_fixed import regmap  # noqa: E402
from irnuc.nuc_fixed.axis import (  # noqa: E402
    EVENTS,
    FramerResult,
    FrameSettings,
    axis_framer,
    coef_beats,
    frame_method_inputs,
    frame_word,
    video_beats,
)
from irnuc.nuc_fixed.config import BASE_METHODS  # noqa: E402
from irnuc.nuc_fixed.cores import code_range  # noqa: E402

TOP = "irnuc_axis_top"


def _sample(name: str, value: object) -> None:
    if coverage.enabled():
        coverage.model(TOP, tb_lib.config_from_env()).sample(name, value)


def _export() -> None:
    """Write the coverage sampled so far (at the end of each test that passed)."""
    if coverage.enabled():
        coverage.export()


class Bench:
    """The DUT with its AXI drivers and monitors and the register model (made after
    reset): ``vid``, ``coef`` (sources), ``out`` (sink), ``axil`` (master), ``model``."""

    def __init__(self, env: tb_lib.Env) -> None:
        dut = self.dut = env.dut
        self.env, self.cfg, self.rng = env, env.cfg, env.rng
        clk, rst = dut.clk_i, dut.rst_ni
        self.vid = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s_axis_video"), clk, rst,
                                   reset_active_level=False, byte_lanes=1)
        self.coef = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s_axis_coef"), clk, rst,
                                    reset_active_level=False, byte_lanes=1)
        self.out = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m_axis_video"), clk, rst,
                                 reset_active_level=False, byte_lanes=1)
        self.axil = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axil"), clk, rst,
                                  reset_active_level=False)
        for drv in (self.vid, self.coef, self.out, self.axil.write_if, self.axil.read_if):
            drv.log.setLevel(logging.WARNING)
        self.model = regmap.RegisterModel(env.cfg)
        # One write and one read open at a time per channel, whoever issues them (the
        # random traffic of axil_traffic drives the master's channels itself).
        self.wlock, self.rlock = Lock(), Lock()
        self.cycle = 0
        self.beats_in = 0
        self.out_cycles: list[int] = []
        cocotb.start_soon(self._monitor())

    async def _monitor(self) -> None:
        """Cycle count, video beats taken, cycles of the output transfers."""
        dut = self.dut
        edge = RisingEdge(dut.clk_i)
        while True:
            await edge
            self.cycle += 1
            if int(dut.s_axis_video_tvalid.value) and int(dut.s_axis_video_tready.value):
                self.beats_in += 1
            if int(dut.m_axis_video_tvalid.value) and int(dut.m_axis_video_tready.value):
                self.out_cycles.append(self.cycle)

    # ---- registers -----------------------------------------------------------------------
    async def write(self, reg: str | int, value: int, strb: int = 0xF) -> int:
        """Write a register (by name or byte offset) through AXI4-Lite; the response must be
        the model's. Byte enables ``strb`` must be contiguous."""
        off = self.model.map[reg].offset if isinstance(reg, str) else int(reg)
        lanes = [i for i in range(4) if strb >> i & 1]
        assert lanes == list(range(lanes[0], lanes[-1] + 1)), f"strobes {strb:04b}"
        data = int(value).to_bytes(4, "little")[lanes[0]:lanes[-1] + 1]
        async with self.wlock:
            resp = await self.axil.write(off + lanes[0], data)
        want = self.model.write(off, int(value), strb)
        kind = ("write_reserved" if want == regmap.OKAY and self.model.map.at(off) is not None
                and not self.model.present(self.model.map.at(off)) else
                "write_okay" if want == regmap.OKAY else "write_slverr")
        _sample("axis.register_access", kind if strb == 0xF or want != regmap.OKAY
                else "write_partial")
        assert int(resp.resp) == want, (
            f"write 0x{int(value):08x} (strb {strb:04b}) at 0x{off:03x}: response "
            f"{regmap.RESP_NAMES[int(resp.resp)]}, the model says {regmap.RESP_NAMES[want]}")
        return want

    async def read(self, reg: str | int) -> int:
        """Read a register; the response must be the model's. The data read."""
        off = self.model.map[reg].offset if isinstance(reg, str) else int(reg)
        async with self.rlock:
            r = await self.axil.read(off, 4)
        want, _ = self.model.read(off)
        reg_def = self.model.map.at(off)
        _sample("axis.register_access",
                "read_slverr" if want != regmap.OKAY else
                "read_reserved" if reg_def is not None and not self.model.present(reg_def)
                else "read_okay")
        assert int(r.resp) == want, (
            f"read at 0x{off:03x}: response {regmap.RESP_NAMES[int(r.resp)]}, the model says "
            f"{regmap.RESP_NAMES[want]}")
        return int.from_bytes(bytes(r.data), "little")

    async def check(self, reg: str | int) -> None:
        """A register reads what the model holds."""
        off = self.model.map[reg].offset if isinstance(reg, str) else int(reg)
        got = await self.read(off)
        _, want = self.model.read(off)
        name = self.model.map.at(off).name if self.model.map.at(off) else f"0x{off:03x}"
        assert got == want, f"{name} reads 0x{got:08x}, the model says 0x{want:08x}"

    def _array(self, name: str) -> list[str]:
        """The registers of a method register array (table_readings: TABLE_READING_k),
        entry k at k, the configured entries only."""
        regs = sorted((r for r in self.model.map.registers
                       if r.config_register == name and r.index is not None),
                      key=lambda r: r.index)
        return [r.name for r in regs[:self.cfg.registers[name].count]]

    def method_registers(self) -> dict[str, object]:
        """The pending values of the method's registers (GAIN, LEVEL, READING, T_REF, ...) by
        their configuration name, as the model holds them (an array as a tuple)."""
        out: dict[str, object] = {}
        for name, r in self.cfg.registers.items():
            if r.count == 1:
                lo = self.model.get(f"{name.upper()}_LO")
                out[name] = lo | (self.model.get(f"{name.upper()}_HI") << 32)
            else:
                out[name] = tuple(self.model.get(n) for n in self._array(name))
        return out

    async def write_method_register(self, name: str, value: object) -> None:
        """Write a method register (configuration name) through its LO (and HI) words, or
        an array's values (a sequence) entry by entry."""
        if self.cfg.registers[name].count != 1:
            for reg, v in zip(self._array(name), value, strict=True):  # type: ignore[call-overload]
                await self.write(reg, int(v))
            return
        await self.write(f"{name.upper()}_LO", int(value) & 0xFFFF_FFFF)  # type: ignore[call-overload]
        if self.cfg.registers[name].width > 32:
            await self.write(f"{name.upper()}_HI", int(value) >> 32)  # type: ignore[call-overload]

    def settings(self) -> FrameSettings:
        """What a frame starting now takes (the pending CTRL, FRAME_SIZE and method
        registers)."""
        m = self.model
        return FrameSettings(m.get("FRAME_SIZE", "width"), m.get("FRAME_SIZE", "height"),
                             bool(m.get("CTRL", "nuc_en")), bool(m.get("CTRL", "dpc_en")),
                             bool(m.get("CTRL", "coef_sync")),
                             frame_word(self.cfg, self.method_registers()))

    async def frame_size(self, h: int, w: int) -> None:
        await self.write("FRAME_SIZE", w | (h << 16))

    # ---- streams -------------------------------------------------------------------------
    def patterns(self, idle: str = "none", coef_idle: str = "none", bp: str = "none") -> None:
        """Pause generators (cocotb_tests.streams.pause_pattern) of the three streams."""
        for drv, name in ((self.vid, idle), (self.coef, coef_idle), (self.out, bp)):
            if name == "none":
                drv.clear_pause_generator()
                drv.pause = False  # the generator may have stopped it paused
            else:
                drv.set_pause_generator(pause_pattern(name, self.rng))
        _sample("stream.idle", idle)
        _sample("stream.backpressure", bp)
        _sample("axis.video_idle", idle)
        _sample("axis.coef_idle", coef_idle)
        _sample("axis.backpressure", bp)

    def send(self, data, sof, eol, words, last) -> None:
        """Queue video beats (an AxiStreamFrame per tlast) and coefficient words."""
        eol = np.asarray(eol, bool)
        last = np.asarray(last, bool)
        assert eol[-1] and last[-1], "each stream ends with a tlast"
        start = 0
        for k in np.flatnonzero(eol):
            self.vid.send_nowait(AxiStreamFrame(
                [int(v) for v in data[start:k + 1]],
                tuser=[int(v) for v in np.asarray(sof[start:k + 1], int)]))
            start = k + 1
        start = 0
        for k in np.flatnonzero(last):
            self.coef.send_nowait(AxiStreamFrame([int(v) for v in words[start:k + 1]]))
            start = k + 1

    async def receive(self, n: int, limit_cycles: int) -> dict[str, np.ndarray]:
        """The next ``n`` output beats (data, sof = tuser[0], eol = tlast), then a quiet
        check: no further beat comes in 4 W cycles."""
        data: list[int] = []
        sof: list[int] = []
        eol: list[int] = []
        while len(data) < n:
            try:
                frame = await with_timeout(self.out.recv(compact=False),
                                           limit_cycles * CLK_PERIOD_NS, "ns")
            except SimTimeoutError:
                counts = {reg: await self.read(reg) for reg in (
                    "STATUS", "FRAMES_IN", "FRAMES_OUT", "PIXELS_IN", "PIXELS_OUT")}
                raise AssertionError(
                    f"timeout after {limit_cycles} cycles: {len(data)} of {n} output beats; "
                    f"{self.beats_in} video beats taken; "
                    + ", ".join(f"{k} 0x{v:x}" for k, v in counts.items())) from None
            data += [int(v) for v in frame.tdata]
            sof += [int(v) & 1 for v in frame.tuser]
            eol += [0] * (len(frame.tdata) - 1) + [1]
        await ClockCycles(self.dut.clk_i, 4 * min(self.cfg.max_width, 64) + 40)
        extra = self.out.count()
        assert extra == 0 and not self.out.active, (
            f"{len(data) - n} beats and {extra} lines more than the {n} expected")
        assert len(data) == n, f"{len(data)} output beats, {n} expected"
        return {"data": np.array(data, np.int64), "sof": np.array(sof, np.int64),
                "eol": np.array(eol, np.int64)}

    async def run(self, video, coef, settings: list[FrameSettings], *, actions=(),
                  idle: str = "none", coef_idle: str = "none", bp: str = "none",
                  label: str = "") -> FramerResult:
        """Stream ``video`` (data, sof, eol) and ``coef`` (words, last) through the DUT
        with the given pause patterns; ``actions``: (input beat, coroutine function) pairs,
        each awaited once that many video beats were taken. The output must be the golden
        model's for ``settings`` (one per frame), bit for bit; returns the framer model's
        result (the counts to check)."""
        fr = axis_framer(*video, *coef, settings, self.env.golden)
        assert not fr.open_frame, "the stimulus leaves a frame open"
        n = sum(f.raw.size for f in fr.frames)
        self.patterns(idle, coef_idle, bp)
        self.send(*video, *coef)
        pending = [cocotb.start_soon(self._act(beat, fn)) for beat, fn in actions]
        got = await self.receive(n, limit_cycles=40 * (len(video[0]) + n) + 2000)
        for task in pending:
            await task
        sb = self._scoreboard(fr)
        sb.observe_arrays(**got)
        res = sb.result()
        tb_lib.record(label=label, compared=res.compared, errors=res.errors,
                      lines=res.lines[:10])
        tb_lib.assert_passed(res)
        if coverage.enabled():
            cov = coverage.model(TOP, self.cfg)
            for f in fr.frames:
                cov.sample("axis.enables", f"nuc{int(f.settings.nuc_en)}_dpc"
                                           f"{int(f.settings.dpc_en)}")
            for ev in EVENTS:
                if fr.counts[ev]:
                    cov.sample("axis.marker", ev)
        return fr

    def _scoreboard(self, fr: FramerResult):
        """The in-order scoreboard expecting the frames the framer model handed to the core:
        the two-point core's (TopScoreboard), or the method's (MethodScoreboard: each frame's
        words and frame word read back as a calibration and a reading, corrected by
        nuc_fixed.method_top)."""
        golden = self.env.golden
        if self.cfg.method == "two_point":
            top = TopScoreboard(golden)
            for f in fr.frames:
                top.expect_frames(f.raw, f.words)
            return top
        if self.cfg.has("blind_drift"):
            # The stage scoreboard: its triage line shows the frame's drift code.
            sb = StageScoreboard(golden)
            lo, hi = code_range(self.cfg, "drift")
            for f in fr.frames:
                coeffs, inputs = frame_method_inputs(f, self.cfg)
                df = drift_frame_from_sum(coeffs, f.raw, inputs, golden=golden)
                sb.expect_frame(df)
                _sample("axis.drift.delta", drift_delta_class(df.delta, lo, hi))
                if not f.settings.nuc_en:
                    _sample("axis.drift.nuc_off", "neutral")
            return sb
        sb = MethodScoreboard(golden)
        for f in fr.frames:
            coeffs, inputs = frame_method_inputs(f, self.cfg)
            reading = None if inputs.reading is None else int(inputs.reading[0])
            for mf in golden_frames(coeffs, [f.raw], [reading], golden=golden):
                sb.expect_frame(mf)
        return sb

    async def _act(self, beat: int, fn) -> None:
        edge = RisingEdge(self.dut.clk_i)
        while self.beats_in < beat:
            await edge
        await fn()

    async def check_counts(self, results: list[FramerResult]) -> None:
        """Counters, STATUS error bits and IRQ_STATUS against the framer model's counts
        (summed over ``results``, since reset or the last clear)."""
        total = {k: sum(r.counts[k] for r in results) for k in results[0].counts}
        frames = sum(len(r.frames) for r in results)
        pixels = sum(f.raw.size for r in results for f in r.frames)
        m = self.model
        for reg, value in (("FRAMES_IN", total["frames_in"]), ("FRAMES_OUT", frames),
                           ("PIXELS_IN", total["beats"]), ("PIXELS_OUT", pixels),
                           ("DROPPED", total["dropped"]), ("PADDED", total["padded"])):
            m.set_live(reg, "count", value)
        for reg, kind in (("SOF_ERRORS", "sof"), ("EOL_ERRORS", "eol"),
                          ("COEF_ERRORS", "coef")):
            for when in ("early", "late"):
                m.set_live(reg, when, total[f"{kind}_{when}"] & 0xFFFF)
        for ev in EVENTS:
            m.set_live("STATUS", ev, int(total[ev] > 0))
        m.set_live("IRQ_STATUS", "error", int(any(total[ev] for ev in EVENTS)))
        m.set_live("IRQ_STATUS", "frame_done", int(frames > 0))
        m.frame_start()  # the frames started: every shadowed write took effect
        for reg in ("FRAMES_IN", "FRAMES_OUT", "PIXELS_IN", "PIXELS_OUT", "DROPPED", "PADDED",
                    "SOF_ERRORS", "EOL_ERRORS", "COEF_ERRORS", "STATUS", "IRQ_STATUS"):
            await self.check(reg)

    async def clear_status(self) -> None:
        """W1C every error and interrupt bit and clear the counters."""
        await self.write("STATUS", 0xFFFF_FFFF)
        await self.write("IRQ_STATUS", 0xFFFF_FFFF)
        await self.write("COMMAND", 1 << self.model.map["COMMAND"].field("clear_counters").lsb)


async def _bench(dut, salt: int) -> Bench:
    env = await tb_lib.setup(dut, salt)
    return Bench(env)


# ---- stimulus ----------------------------------------------------------------------------------

def _frames(bench: Bench, n: int, h: int, w: int, bad_fraction: float = 0.05
            ) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """n random raw frames and n coefficient images of (H, W) over the full code ranges."""
    cfg, rng = bench.cfg, bench.rng
    raws = [rng.integers(0, 1 << cfg.adc_bits, size=(h, w), dtype=np.int64) for _ in range(n)]
    words = [tb_lib.random_coefficients(rng, cfg, h, w, bad_fraction) for _ in range(n)]
    return raws, words


def _size(bench: Bench, h: int, w: int) -> tuple[int, int]:
    return min(bench.cfg.max_height, h), min(bench.cfg.max_width, w)


# ---- registers -----------------------------------------------------------------------------------

@cocotb.test()
async def register_map_reset(dut) -> None:
    """After reset every word of the 4 KiB window answers as the model says: the reset
    value of each register (the configuration's widths and modes in CONFIG, FORMAT,
    FRAME_MAX; reserved registers of other methods 0, OKAY) and SLVERR with data 0 for
    every offset outside the map."""
    bench = await _bench(dut, 0)
    m, cfg = bench.model, bench.cfg
    for off in range(0, m.map.size, 4):
        await bench.check(off)
    # The configuration as the RTL reports it, field by field, against PipelineConfig.
    config = await bench.read("CONFIG")
    fields = m.map["CONFIG"]
    got = {f.name: (config & f.mask) >> f.lsb for f in fields.fields}
    assert got["adc_bits"] == cfg.adc_bits and got["out_bits"] == cfg.out_bits
    assert got["word_bits"] == cfg.word_bits and got["method"] == BASE_METHODS.index("two_point")
    assert (await bench.read("FRAME_MAX")) == cfg.max_width | (cfg.max_height << 16)
    assert (await bench.read("ID")) == int.from_bytes(b"IRNC", "big")
    _export()


@cocotb.test()
async def register_read_write(dut) -> None:
    """Random writes (full words and contiguous byte lanes) to every register and to
    offsets outside the map: every response and every read-back as the model says; a frame
    size of 0 or above FRAME_MAX is refused; W1C bits that are 0 stay 0; a shadowed write
    raises STATUS.pending until a frame starts."""
    bench = await _bench(dut, 1)
    m, rng = bench.model, bench.rng
    strobes = [0xF, 0x1, 0x2, 0x4, 0x8, 0x3, 0xC, 0x6, 0x7, 0xE]
    holes = m.reserved_offsets()
    targets = [r.offset for r in m.map.registers]
    targets += [int(o) for o in rng.choice(holes, size=12, replace=False)]
    for rnd in range(3):
        for off in rng.permutation(targets):
            strb = strobes[int(rng.integers(len(strobes)))] if rnd else 0xF
            value = int(rng.integers(0, 2**32, dtype=np.uint64))
            await bench.write(int(off), value, strb)
            await bench.check(int(off))
            await bench.check("STATUS")
    # Frame sizes at and beyond their limits.
    cfg = bench.cfg
    for w, h in ((1, 1), (cfg.max_width, cfg.max_height), (0, 5), (5, 0),
                 (cfg.max_width + 1, 5), (5, cfg.max_height + 1), (0xFFFF, 0xFFFF)):
        resp = await bench.write("FRAME_SIZE", (w & 0xFFFF) | ((h & 0xFFFF) << 16))
        legal = 1 <= w <= cfg.max_width and 1 <= h <= cfg.max_height
        assert (resp == regmap.OKAY) == legal, (w, h, resp)
        if not legal:
            _sample("axis.register_access", "write_slverr_value")
        await bench.check("FRAME_SIZE")
    # A field's high byte lane alone: the size it makes keeps the old low byte (5, legal),
    # while the written word's field (cocotbext-axi drives unwritten lanes 0) would be 0.
    await bench.write("FRAME_SIZE", 5 | (5 << 16))
    for strb in (0x2, 0x8):
        assert await bench.write("FRAME_SIZE", 0, strb) == regmap.OKAY, f"strobes {strb:04b}"
        await bench.check("FRAME_SIZE")
    _export()


@cocotb.test()
async def register_traffic(dut) -> None:
    """Constrained-random register traffic (cocotb_tests.axil_traffic): random strobes,
    BREADY / RREADY held low, read-only, reserved and unmapped offsets, reads and writes
    while pixels stream (W1C clears racing the stream's framing errors, counters read mid
    frame), a frame at the reset size where it is small: every response and read as the
    register model says."""
    from irnuc.cocotb_tests.axil_traffic import register_traffic as traffic

    bench = await _bench(dut, 9)

    def frames(b: Bench, h: int, w: int):
        raws, words = _frames(b, 1, h, w)
        return video_beats(raws), coef_beats(words)

    await traffic(bench, frames)
    _export()


# ---- frames ---------------------------------------------------------------------------------------

@cocotb.test()
async def frames_idle_backpressure(dut) -> None:
    """Frames of several sizes under every idle pattern of the video and coefficient
    streams and every backpressure pattern: bit for bit; the counters agree."""
    bench = await _bench(dut, 2)
    cfg = bench.cfg
    sizes = [_size(bench, 6, 9), (1, 1), _size(bench, 1, 7), _size(bench, 5, 1),
             (2, cfg.max_width), _size(bench, 3, 2)]
    patterns = coverage.IDLE_PATTERNS
    results = []
    for i, (h, w) in enumerate(sizes):
        await bench.frame_size(h, w)
        raws, words = _frames(bench, 2, h, w, bad_fraction=0.2)
        res = await bench.run(video_beats(raws), coef_beats(words), [bench.settings()],
                              idle=patterns[i % 4], coef_idle=patterns[(i + 1) % 4],
                              bp=patterns[(i + 2) % 4], label=f"sizes {h}x{w}")
        results.append(res)
        _sample("axis.frame_transition", "size_change")
    await bench.check_counts(results)
    _export()


@cocotb.test()
async def full_rate_back_to_back(dut) -> None:
    """Back-to-back frames of one size at tvalid = tready = 1: one pixel per clock through
    the framer and the core, no bubble between frames (N outputs in N cycles)."""
    bench = await _bench(dut, 3)
    h, w = _size(bench, 6, 10)
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 3, h, w)
    await bench.run(video_beats(raws), coef_beats(words), [bench.settings()])
    n = 3 * h * w
    span = bench.out_cycles[-1] - bench.out_cycles[-n] + 1
    assert span == n, f"{n} outputs took {span} cycles"
    _sample("stream.back_to_back", "frames")
    _sample("axis.frame_transition", "same_size")
    _export()


@cocotb.test()
async def registers_mid_frame(dut) -> None:
    """Registers written in the middle of a frame change only the frames that start after
    the write: CTRL (enables) in frame 0 applies from frame 1, FRAME_SIZE in frame 1 from
    frame 2 (which waits until frame 1 has left the core); STATUS.pending shows the write
    until then. Under idle and backpressure."""
    bench = await _bench(dut, 4)
    m = bench.model
    h, w = _size(bench, 8, 12)
    h2, w2 = _size(bench, 5, 7)
    await bench.frame_size(h, w)
    s0 = bench.settings()
    raws, words = _frames(bench, 2, h, w, bad_fraction=0.2)
    raw2, word2 = _frames(bench, 1, h2, w2, bad_fraction=0.2)
    video = video_beats([*raws, *raw2])
    coef = coef_beats([*words, *word2])
    ctrl = m.map["CTRL"]
    off_nuc = (1 << ctrl.field("dpc_en").lsb) | (1 << ctrl.field("coef_sync").lsb)
    seen: dict[str, int] = {}

    async def write_ctrl() -> None:
        await bench.write("CTRL", off_nuc)
        seen["pending_ctrl"] = (await bench.read("STATUS") >> m.map["STATUS"].field(
            "pending").lsb) & 1
        _sample("axis.mid_frame_write", "ctrl")

    async def write_size() -> None:
        await bench.frame_size(h2, w2)
        _sample("axis.mid_frame_write", "frame_size")

    s1 = FrameSettings(w, h, nuc_en=False, dpc_en=True, coef_sync=True)
    s2 = FrameSettings(w2, h2, nuc_en=False, dpc_en=True, coef_sync=True)
    res = await bench.run(video, coef, [s0, s1, s2],
                          actions=[((h * w) // 2, write_ctrl), (h * w + (h * w) // 2, write_size)],
                          idle="random", coef_idle="bursty", bp="random", label="mid frame")
    assert seen.get("pending_ctrl") == 1, "STATUS.pending was not 1 after a mid-frame write"
    assert [f.settings for f in res.frames] == [s0, s1, s2]
    await bench.check_counts([res])
    _sample("axis.frame_transition", "size_change")
    _export()


@cocotb.test()
async def enables(dut) -> None:
    """CTRL.nuc_en and CTRL.dpc_en in all four combinations: with NUC off the core gets
    unity gain and zero offset, with DPC off no bad flag (the words are still taken)."""
    bench = await _bench(dut, 5)
    h, w = _size(bench, 5, 8)
    await bench.frame_size(h, w)
    ctrl = bench.model.map["CTRL"]
    for nuc in (1, 0):
        for dpc in (1, 0):
            await bench.write("CTRL", (nuc << ctrl.field("nuc_en").lsb)
                              | (dpc << ctrl.field("dpc_en").lsb)
                              | (1 << ctrl.field("coef_sync").lsb))
            raws, words = _frames(bench, 2, h, w, bad_fraction=0.3)
            res = await bench.run(video_beats(raws), coef_beats(words), [bench.settings()],
                                  idle="bursty", bp="alternate", label=f"nuc {nuc} dpc {dpc}")
            assert all(f.settings.nuc_en == bool(nuc) and f.settings.dpc_en == bool(dpc)
                       for f in res.frames)
    _export()


def _marker_cases(h: int, w: int) -> dict[str, object]:
    """Each error cause alone (and one run of each late/early pair), as a change of the
    well-formed streams of two frames: name -> function(video, coef) -> (video, coef)."""
    n = h * w

    def sof_early(v, c):
        d, s, e = v
        keep = np.r_[0:n - w - 1, n:2 * n]  # frame 0 stops a pixel before its last line
        return (d[keep], s[keep], e[keep]), c

    def sof_late(v, c):
        d, s, e = v
        extra = np.arange(5)  # five stray beats before the first frame and between frames
        return ((np.r_[extra, d[:n], extra, d[n:]], np.r_[[0] * 5, s[:n], [0] * 5, s[n:]],
                 np.r_[[0, 0, 1, 0, 1], e[:n], [0, 0, 0, 0, 1], e[n:]]), c)

    def eol_early(v, c):
        d, s, e = (a.copy() for a in v)
        drop = np.r_[w + 1:w + 3]  # line 1 of frame 0 loses two pixels
        keep = np.setdiff1d(np.arange(2 * n), drop)
        return (d[keep], s[keep], e[keep]), c

    def eol_late(v, c):
        d, s, e = (a.copy() for a in v)
        # line 0 of frame 0 runs three beats long; frame 1's last line too (then done)
        ins0 = np.r_[d[:w], [7, 8, 9], d[w:2 * n], [1, 2]]
        sof = np.r_[s[:w], [0, 0, 0], s[w:2 * n], [0, 0]]
        eol = np.r_[e[:w], [0, 0, 1], e[w:2 * n], [0, 1]]
        eol[w - 1] = 0
        eol[3 + 2 * n - 1] = 0
        return (ins0, sof, eol), c

    def coef_early(v, c):
        words, last = (a.copy() for a in c)
        last[n - 4] = True  # frame 0's image ends four words early: those words are lost
        keep = np.r_[0:n - 3, n:2 * n]
        return v, (words[keep], last[keep])

    def coef_late(v, c):
        words, last = (a.copy() for a in c)
        last[n - 1] = False  # frame 0's image runs three words long
        return v, (np.r_[words[:n], [1, 2, 3], words[n:]], np.r_[last[:n], [0, 0, 1], last[n:]])

    return {"sof_early": sof_early, "sof_late": sof_late, "eol_early": eol_early,
            "eol_late": eol_late, "coef_early": coef_early, "coef_late": coef_late}


@cocotb.test()
async def marker_errors(dut) -> None:
    """Each cause of a framing error alone: the output is the golden model's (padded or
    dropped as docs/integration.md says), the cause's STATUS bit and counter are set,
    IRQ_STATUS.error and irq_o follow, W1C clears them, and the next clean frames are
    exact."""
    bench = await _bench(dut, 6)
    m = bench.model
    h, w = _size(bench, 5, 8)
    await bench.frame_size(h, w)
    await bench.write("IRQ_ENABLE", 1 << m.map["IRQ_ENABLE"].field("error").lsb)
    for name, change in _marker_cases(h, w).items():
        raws, words = _frames(bench, 2, h, w, bad_fraction=0.2)
        video, coef = change(video_beats(raws), coef_beats(words))
        res = await bench.run(video, coef, [bench.settings()], idle="random",
                              coef_idle="random", bp="random", label=name)
        assert res.counts[name] >= 1, f"the {name} stimulus has no {name}"
        others = [ev for ev in EVENTS if ev != name and res.counts[ev]]
        assert not others, f"the {name} stimulus also caused {others}"
        await bench.check_counts([res])
        await ClockCycles(dut.clk_i, 2)
        assert int(dut.irq_o.value) == 1, f"{name}: irq_o is 0 with IRQ_ENABLE.error"
        _sample("axis.irq", "error")
        await bench.clear_status()
        for reg in regmap.COUNTERS:
            bench.model.set_live(reg, bench.model.map[reg].fields[0].name, 0)
        await ClockCycles(dut.clk_i, 2)
        assert int(dut.irq_o.value) == 0, f"{name}: irq_o stays 1 after W1C"
        # A clean frame right after is exact.
        raws, words = _frames(bench, 1, h, w)
        res = await bench.run(video_beats(raws), coef_beats(words), [bench.settings()],
                              label=f"after {name}")
        await bench.check_counts([res])
        await bench.clear_status()
    _export()


@cocotb.test()
async def coef_sync_off(dut) -> None:
    """With CTRL.coef_sync = 0 the coefficient tlast is ignored: one word per pixel, no
    coefficient error, even with tlast in the middle of a frame."""
    bench = await _bench(dut, 7)
    h, w = _size(bench, 4, 6)
    await bench.frame_size(h, w)
    ctrl = bench.model.map["CTRL"]
    await bench.write("CTRL", (1 << ctrl.field("nuc_en").lsb) | (1 << ctrl.field("dpc_en").lsb))
    raws, words = _frames(bench, 2, h, w)
    wd, last = coef_beats(words)
    last[5] = True  # a tlast that coef_sync would call early
    res = await bench.run(video_beats(raws), (wd, last), [bench.settings()], coef_idle="bursty")
    assert res.counts["coef_early"] == 0 and res.counts["coef_late"] == 0
    await bench.check_counts([res])
    _sample("axis.coef_sync", "off")
    _export()


@cocotb.test()
async def frame_done_interrupt(dut) -> None:
    """IRQ_STATUS.frame_done rises with each frame's last output pixel; irq_o follows
    IRQ_ENABLE and falls with the W1C write."""
    bench = await _bench(dut, 8)
    m = bench.model
    h, w = _size(bench, 3, 5)
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 1, h, w)
    await bench.run(video_beats(raws), coef_beats(words), [bench.settings()])
    await ClockCycles(dut.clk_i, 2)
    assert int(dut.irq_o.value) == 0, "irq_o without an enabled cause"
    done = 1 << m.map["IRQ_STATUS"].field("frame_done").lsb
    assert (await bench.read("IRQ_STATUS")) & done
    await bench.write("IRQ_ENABLE", done)
    await ClockCycles(dut.clk_i, 2)
    assert int(dut.irq_o.value) == 1
    await bench.write("IRQ_STATUS", done)
    await ClockCycles(dut.clk_i, 2)
    assert int(dut.irq_o.value) == 0
    _sample("axis.irq", "frame_done")
    _export()


@cocotb.test()
async def reset_mid_frame(dut) -> None:
    """Reset while a frame streams: the registers are back at their reset values, the
    output is idle, and the next frames are exact."""
    bench = await _bench(dut, 9)
    h, w = _size(bench, 6, 9)
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 2, h, w)
    bench.patterns("random", "random", "random")
    bench.send(*video_beats(raws), *coef_beats(words))
    while bench.beats_in < h * w // 2:
        await RisingEdge(dut.clk_i)
    await reset(dut, 2)
    assert int(dut.m_axis_video_tvalid.value) == 0, "output valid right after reset"
    _sample("axis.reset", "mid_frame")
    for drv in (bench.vid, bench.coef, bench.out):
        drv.clear()  # what was queued for the interrupted frames
    bench.patterns()
    bench.model.reset()
    for r in bench.model.map.registers:
        await bench.check(r.offset)
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 2, h, w)
    res = await bench.run(video_beats(raws), coef_beats(words), [bench.settings()])
    await bench.check_counts([res])
    _export()
