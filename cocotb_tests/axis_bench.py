"""The test bench of ``irnuc_axis_top`` its testbenches share (``tb_axis``,
``tb_axis_method``, ``tb_axis_table``, ``tb_axis_ffc``): the DUT with its AXI drivers and
monitors (cocotbext-axi, every bus found by its prefix) and the register model
(:class:`Bench`), and the coverage sampling of the wrapper's model.
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
from irnuc.cocotb_tests.streams import CLK_PERIOD_NS, pause_pattern  # noqa: E402
from irnuc.cosim import coverage, driver  # noqa: E402
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
    frame_method_inputs,
    frame_word,
)
from irnuc.nuc_fixed.cores import code_range  # noqa: E402

TOP = "irnuc_axis_top"


def sample(name: str, value: object) -> None:
    if coverage.enabled():
        coverage.model(TOP, tb_lib.config_from_env()).sample(name, value)


def export() -> None:
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
        # One write and one read issued at a time per channel, whoever issues them (the
        # random traffic of axil_traffic drives the master's channels itself); the slave
        # takes one transaction at a time and must hold the other channel's request.
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
        sample("axis.register_access", kind if strb == 0xF or want != regmap.OKAY
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
        sample("axis.register_access",
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
        """The registers of a method register array (table_readings: TABLE_READING[k]),
        entry k at k, the configured entries only."""
        regs = sorted((r for r in self.model.map.registers
                       if r.config_register == name and r.index is not None),
                      key=lambda r: r.index)
        return [r.name for r in regs[:self.cfg.registers[name].count]]

    def registers(self):
        """The register model peakrdl-python generates from the map (irnuc.cosim.driver),
        on this bench's AXI4-Lite master: each access is :meth:`read` / :meth:`write`
        (its response checked against the golden model, which follows the writes)."""
        return driver.registers(self.read, self.write)

    def slot(self, name: str) -> tuple[str, str]:
        """The LO and HI registers of a method register's 64-bit slot (``reading`` ->
        ``READING.LO``, ``READING.HI``), from the map."""
        words = {r.word: r.name for r in self.model.map.registers
                 if r.config_register == name and r.word is not None}
        return words["lo"], words["hi"]

    def method_registers(self) -> dict[str, object]:
        """The pending values of the method's registers (GAIN, LEVEL, READING, T_REF, ...) by
        their configuration name, as the model holds them (an array as a tuple)."""
        out: dict[str, object] = {}
        for name, r in self.cfg.registers.items():
            if r.count == 1:
                lo, hi = self.slot(name)
                out[name] = self.model.get(lo) | (self.model.get(hi) << 32)
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
        lo, hi = self.slot(name)
        await self.write(lo, int(value) & 0xFFFF_FFFF)  # type: ignore[call-overload]
        if self.cfg.registers[name].width > 32:
            await self.write(hi, int(value) >> 32)  # type: ignore[call-overload]

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
        sample("stream.idle", idle)
        sample("stream.backpressure", bp)
        sample("axis.video_idle", idle)
        sample("axis.coef_idle", coef_idle)
        sample("axis.backpressure", bp)

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
        if self.cfg.plain:
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
                sample("axis.drift.delta", drift_delta_class(df.delta, lo, hi))
                if not f.settings.nuc_en:
                    sample("axis.drift.nuc_off", "neutral")
            return sb
        sb = MethodScoreboard(golden)
        for f in fr.frames:
            coeffs, inputs = frame_method_inputs(f, self.cfg)
            reading: int | dict[str, int] | None = (None if inputs.reading is None
                                                    else int(inputs.reading[0]))
            if inputs.housing_reading is not None and reading is not None:
                reading = {"fpa": reading, "housing": int(inputs.housing_reading[0])}
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


async def make_bench(dut, salt: int) -> Bench:
    env = await tb_lib.setup(dut, salt)
    return Bench(env)


