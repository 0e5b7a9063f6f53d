"""cocotb tests of ``irnuc_axis_top`` built around ``method_ffc_top`` (an FFC composition:
ffc14, quadffc14, tcffc14; run by ``cocotb_tests/test_axis_top.py``).

The drivers, the register model and the framing model are ``tb_axis``'s (:class:`Bench`),
with cocotbext-axi sources on ``s_axis_foff`` and ``s_axis_acc`` and sinks on
``m_axis_acc`` and ``m_axis_foff``. The host's sequence: frames run, ``FFC_CTRL`` is
written (start, frames) in the middle of a frame, the shutter frames follow from the next
frame start. With tc_offset the calibration's T_REF is written first and each frame's FPA
reading (READING) during the frame before it (the core latches it at the frame start).
Which frames are shutter frames and which carry words on each FFC stream come from the
wrapper's golden model (``nuc_fixed.axis.ffc_shutter_flags`` and ``ffc_framing``); the
words themselves (the offsets and accumulators the host feeds, the written-back ones
expected) and the output pixels from ``cosim.stages.ffc_run`` (one run of
``nuc_fixed.method_top`` with those readings), bit for bit, frame by frame (tlast on each
frame's last word). ``FFC_STATUS`` and ``IRQ_STATUS.ffc_done`` against the register model.
``ffc_refresh_idle_backpressure`` makes every register access of the sequence through the
firmware's driver (:mod:`irnuc.cosim.driver`, the Python twin of ``firmware/irnuc_driver.c``)
over the register model peakrdl-python generates from the map: bring-up, calibration,
interrupt enables, FFC start, the wait for its end, the status.
The FFC coverpoints (``cosim.axis_coverage``) are sampled from each sequence that passed.
Small frames.
"""

from __future__ import annotations

import dataclasses
import logging

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, SimTimeoutError, with_timeout
from cocotbext.axi import AxiStreamBus, AxiStreamFrame, AxiStreamSink, AxiStreamSource

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.axis_bench import TOP, Bench, export, make_bench, sample
from irnuc.cocotb_tests.method_stim import ffc_calibration, ffc_raws, random_reading
from irnuc.cocotb_tests.streams import CLK_PERIOD_NS, pause_pattern
from irnuc.cosim import coverage, driver
from irnuc.cosim.axis_coverage import ffc_axis_classes
from irnuc.cosim.stages import FfcRun, StageScoreboard, ffc_run
from irnuc.nuc_fixed import MethodCoefficients
from irnuc.nuc_fixed.axis import (
    axis_framer,
    coef_beats,
    ffc_framing,
    ffc_shutter_flags,
    video_beats,
)

#: Frame size of these tests (lines, pixels): past the DPC's 3 x 3 window.
H, W = 4, 6


class FfcStreams:
    """The four FFC streams of the DUT: sources ``foff``, ``acc``; sinks ``acc_out``,
    ``foff_out`` (one word per beat)."""

    def __init__(self, bench: Bench) -> None:
        dut = bench.dut
        clk, rst = dut.clk_i, dut.rst_ni
        kw = {"reset_active_level": False, "byte_lanes": 1}
        self.foff = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s_axis_foff"), clk, rst,
                                    **kw)
        self.acc = AxiStreamSource(AxiStreamBus.from_prefix(dut, "s_axis_acc"), clk, rst,
                                   **kw)
        self.acc_out = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m_axis_acc"), clk, rst,
                                     **kw)
        self.foff_out = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m_axis_foff"), clk, rst,
                                      **kw)
        for drv in (self.foff, self.acc, self.acc_out, self.foff_out):
            drv.log.setLevel(logging.WARNING)
        self.bench = bench

    def patterns(self, idle: str, bp: str) -> None:
        for drv, name in ((self.foff, idle), (self.acc, idle), (self.acc_out, bp),
                          (self.foff_out, bp)):
            if name == "none":
                drv.clear_pause_generator()
                drv.pause = False
            else:
                drv.set_pause_generator(pause_pattern(name, self.bench.rng))
        sample("stream.idle", idle)
        sample("stream.backpressure", bp)


async def _stall_log(bench: Bench, out: dict[str, list[int]]) -> None:
    """Fill ``out`` with the cycles (Bench's count) in which an AXI4-Stream port was idle
    (``<port> idle``: tvalid 0) or stalled (``<port> stall``: tvalid 1, tready 0): triage
    of a throughput check."""
    dut = bench.dut
    edge = RisingEdge(dut.clk_i)
    while True:
        await edge
        for port in ("s_axis_video", "s_axis_coef", "s_axis_foff", "s_axis_acc",
                     "m_axis_video"):
            v = int(getattr(dut, f"{port}_tvalid").value)
            r = int(getattr(dut, f"{port}_tready").value)
            if not v or not r:
                out.setdefault(f"{port} {'stall' if v else 'idle'}", []).append(bench.cycle)


class WordMonitor:
    """Monitor of an AXI4-Stream port: the words taken (tvalid and tready at a rising edge)
    in its current frame (``words``) and the frames ended (tlast taken, ``frames``)."""

    def __init__(self, bench: Bench, port: str) -> None:
        dut = bench.dut
        self.valid = getattr(dut, f"{port}_tvalid")
        self.ready = getattr(dut, f"{port}_tready")
        self.last = getattr(dut, f"{port}_tlast")
        self.words = self.frames = 0
        cocotb.start_soon(self._run(dut.clk_i))

    async def _run(self, clk) -> None:
        edge = RisingEdge(clk)
        while True:
            await edge
            if int(self.valid.value) and int(self.ready.value):
                if int(self.last.value):
                    self.words, self.frames = 0, self.frames + 1
                else:
                    self.words += 1

    def waiting(self) -> bool:
        """A word offered and not taken (tvalid 1, tready 0)."""
        return bool(int(self.valid.value) and not int(self.ready.value))


async def held_refresh_checks(bench: Bench, sink: AxiStreamSink, mon: WordMonitor,
                              frame: int, words: int, holds: list[int], bp: str,
                              seen: list[int]) -> None:
    """FFC_STATUS while the refresh's new offsets are held by backpressure on m_axis_foff.
    For each k of ``holds`` (0 < k < ``words`` - 2; ``words`` the refresh frame's count,
    ``frame`` its index among the port's frames): once k of its words were taken (the
    monitor) the sink (the driver) stops taking them (tready low from the next edge or the
    one after: k or k + 1 taken, never the frame's last); with the next word waiting
    (tvalid 1, tready 0) FFC_STATUS is read over AXI4-Lite against the register model
    (busy 1, done 0: a run ends with the refresh's last new offset, tlast, taken; the
    scoreboard is :meth:`Bench.check`), irq_o must be 0 (IRQ_ENABLE.ffc_done only), and the
    word must still wait after the read. Then ``bp`` again. The word counts held at the
    reads go to ``seen``."""
    dut = bench.dut
    fall = FallingEdge(dut.clk_i)
    m = bench.model
    for k in holds:
        assert 0 < k < words - 2, f"hold after {k} of {words} words"
        while mon.frames < frame or mon.words < k:
            await fall
            assert mon.frames <= frame, f"the refresh frame passed before its hold at word {k}"
        sink.clear_pause_generator()
        sink.pause = True
        for _ in range(200):
            await fall
            if mon.waiting():
                break
        held = mon.words
        assert mon.frames == frame and k <= held < words, (
            f"held after {held} words of frame {mon.frames}, wanted {k} of frame {frame}")
        assert mon.waiting(), f"no refresh word offered in 200 cycles after word {held}"
        m.set_live("FFC_STATUS", "busy", 1)
        m.set_live("FFC_STATUS", "done", 0)
        await bench.check("FFC_STATUS")
        assert int(dut.irq_o.value) == 0, (
            f"irq_o 1 with {held} of the refresh's {words} new offsets taken")
        await fall
        assert (mon.frames, mon.words) == (frame, held) and mon.waiting(), (
            "the held refresh word left (or was withdrawn) during the FFC_STATUS read")
        seen.append(held)
        if bp == "none":
            sink.pause = False
        else:
            sink.set_pause_generator(pause_pattern(bp, bench.rng))


def _tiled(c: MethodCoefficients, h: int, w: int) -> MethodCoefficients:
    """The calibration ``c`` on an (h, w) frame: its fields tiled from pixel (0, 0) (the
    same registers, so T_REF holds across a frame-size change)."""
    def tile(v: np.ndarray) -> np.ndarray:
        reps = (-(-h // v.shape[0]), -(-w // v.shape[1]))
        return np.tile(v, reps)[:h, :w].copy()

    return MethodCoefficients(c.cfg, {m: {k: tile(v) for k, v in f.items()}
                                      for m, f in c.fields.items()}, c.registers)


def _joined(a: FfcRun, b: FfcRun) -> FfcRun:
    """Run ``b`` after run ``a`` (``b`` starts with the FFC sequencer at rest: open frames
    after a run without a refresh)."""
    return FfcRun(frames=a.frames + b.frames, shutter=np.concatenate([a.shutter, b.shutter]),
                  held=np.concatenate([a.held, b.held]), foff_in=a.foff_in + b.foff_in,
                  acc_in=a.acc_in + b.acc_in, acc_out=a.acc_out + b.acc_out,
                  foff_out=a.foff_out + b.foff_out, targets=a.targets + b.targets)


async def hold_word(src: AxiStreamSource, mon: WordMonitor, frame: int, word: int,
                    cycles: int) -> None:
    """Hold word ``word`` (> 0) of frame ``frame`` of the source ``src`` (without a pause
    pattern) back for ``cycles`` cycles after the word before it was taken (``mon``: the
    source's port): ``src.pause`` set while that word is offered, so the source drives tvalid
    low after its handshake, and cleared after the wait."""
    assert word > 0
    fall = FallingEdge(src.clock)
    while not (mon.frames == frame and mon.words == word - 1 and int(mon.valid.value)):
        assert (mon.frames, mon.words) <= (frame, word - 1), (
            f"word {word - 1} of frame {frame} taken before its hold")
        await fall
    src.pause = True
    while mon.words < word:
        await fall
    await ClockCycles(src.clock, cycles)
    assert (mon.frames, mon.words) == (frame, word) and not int(mon.valid.value), (
        f"word {word} of frame {frame} not held: {mon.words} words of frame {mon.frames} taken")
    src.pause = False


def _all_bad(c: MethodCoefficients, rng: np.random.Generator
             ) -> tuple[MethodCoefficients, np.ndarray]:
    """The calibration ``c`` with every pixel bad, and random corrections over the ffc
    format's range for the host's memory at the start."""
    cfg = c.cfg
    fields = {m: dict(v) for m, v in c.fields.items()}
    fields["coeffs"]["bad"] = np.ones_like(fields["coeffs"]["bad"], dtype=bool)
    lo = -(1 << (cfg.format("ffc").bits - 1))
    return (MethodCoefficients(cfg, fields, c.registers),
            rng.integers(lo, -lo, size=fields["coeffs"]["bad"].shape))


def _gains_at_least_one(c: MethodCoefficients) -> MethodCoefficients:
    """The calibration ``c`` with its gains (near 1) mirrored above 1: a shutter frame at
    full scale then corrects above the output's range on average."""
    fields = {m: dict(v) for m, v in c.fields.items()}
    co = fields["coeffs"]
    if "gain" in co:
        one = 1 << c.cfg.gain_frac_bits
        co["gain"] = one + np.abs(np.asarray(co["gain"], np.int64) - one)
    return MethodCoefficients(c.cfg, fields, c.registers)


def _check_conditions(run: FfcRun, c: MethodCoefficients, scene: list[np.ndarray],
                      shutter: list[bool], readings: list, golden, start_frame: int,
                      all_bad: bool, bright_second: bool, late_mean_word: bool,
                      start_offset: np.ndarray | None) -> None:
    """The golden model's view of a sequence makes the condition its options ask for
    (:func:`refresh_sequence`), so that a test of them can fail."""
    if start_frame == 0:
        first = shutter.index(False)
        assert first > 0 and not run.held[:first].any(), (
            "the shutter frames before the first open frame are not all shown")
    if all_bad:
        refreshed = [f for f in run.foff_out if f is not None]
        assert run.kept and refreshed and all(np.array_equal(f, start_offset)
                                              for f in refreshed), (
            "the all-bad refresh does not keep the host's corrections")
    if bright_second:
        cfg = c.cfg
        tmax = (1 << (cfg.out_bits + cfg.format("ffc").frac_bits)) - 1
        assert len(run.targets) == 2 and run.targets[1] == tmax > run.targets[0], (
            f"targets {run.targets}: the second not clamped to {tmax}, or the first too")
    if late_mean_word:
        bad = np.asarray(c.fields["coeffs"]["bad"], bool)
        assert not bad[-1, -1], "the mean frame's last pixel is bad"
        fields = {m: dict(v) for m, v in c.fields.items()}
        fields["coeffs"]["bad"] = bad.copy()
        fields["coeffs"]["bad"][-1, -1] = True
        without = ffc_run(MethodCoefficients(c.cfg, fields, c.registers), scene, shutter,
                          readings=readings, golden=golden, offset=start_offset)
        assert without.targets[0] != run.targets[0], (
            f"target {run.targets[0]} with or without the mean frame's last pixel")


def _unsigned(a: np.ndarray, bits: int) -> list[int]:
    return [int(v) & ((1 << bits) - 1) for v in np.asarray(a, np.int64).ravel()]


async def _frames_of(sink: AxiStreamSink, n: int, limit_cycles: int) -> list[list[int]]:
    """The next ``n`` frames (words up to each tlast) of a sink."""
    out = []
    for _ in range(n):
        try:
            fr = await with_timeout(sink.recv(compact=False), limit_cycles * CLK_PERIOD_NS,
                                    "ns")
        except SimTimeoutError:
            raise AssertionError(f"timeout: {len(out)} of {n} write-back frames") from None
        out.append([int(v) for v in fr.tdata])
    return out


async def refresh_sequence(dut, salt: int, frames: int | None, idle: str, bp: str,
                           label: str, ffc_idle: str | None = None,
                           ffc_bp: str | None = None, resize_after_run: bool = False,
                           size: tuple[int, int] = (H, W),
                           resize_in_run: tuple[int, int] | None = None,
                           second_run: int | None = None, traffic: bool = False,
                           firmware: bool = False, hold_refresh: bool = False,
                           start_frame: int = 2, all_bad: bool = False,
                           bright_second: bool = False, late_mean_word: bool = False) -> None:
    """Two open frames, FFC_CTRL written in the middle of the second (start, ``frames``
    shutter frames; None: the configured N), the shutter frames from the third on, then
    three open frames: every stream and the status registers checked. ``idle`` / ``bp``:
    the pause patterns of the video and coefficient inputs / the video output;
    ``ffc_idle`` / ``ffc_bp`` those of the FFC sources / sinks (default the same).
    ``resize_after_run``: FRAME_SIZE written (the same size) in the middle of the first
    frame after the shutter frames, so the framer drains before the next one: its count of
    items in flight must have counted the held frames' items out as they entered the core
    (else the drain never ends). ``size``: the frames' (lines, pixels). ``resize_in_run``:
    FRAME_SIZE written to this other size in the middle of the run's last frame that writes
    back (its last shutter frame, or with N shutter frames its refresh frame); the open
    frames after it have that size, and the run's write-back frames must still end (tlast)
    at the old size: the drain before the new size waits for their words.
    ``second_run``: after the first run and an open frame, IRQ_STATUS.ffc_done cleared and
    FFC_CTRL written again (start, this many shutter frames) early in that open frame: a
    second run, checked like the first (FFC_STATUS busy after its start, done at its end). ``traffic``: random
    register traffic (cocotb_tests.axil_traffic) before the sequence and while it streams
    (W1C clears of STATUS, read-only, reserved and unmapped offsets, reads anywhere).
    ``firmware``: the register accesses are the firmware driver's (irnuc.cosim.driver:
    probe, configure, load_calibration, set_reading, enable_irq, ffc_start, ffc_wait,
    read_status), through the generated register model. ``hold_refresh``: the refresh's
    new offsets held three times by backpressure on m_axis_foff (after its first word, one
    at random and all but its last three), FFC_STATUS read over AXI4-Lite during each hold:
    busy, not done (:func:`held_refresh_checks`). ``start_frame``: the frame the first run
    starts with (2: FFC_CTRL written in the middle of the second open frame; 0: written
    before any frame, so the run's shutter frames come before any open frame was output:
    passed, not held). ``all_bad``: every pixel of the calibration bad and nonzero
    corrections in the host's memory at the start: the mean frame has no good pixel, so
    there is no target and the refresh writes the corrections back unchanged.
    ``bright_second``: the gains at least 1 and the second run's shutter frames at the
    ADC's full scale: its target is clamped to the top of its range, the first run's is
    not (the second refresh needs a new division). ``late_mean_word``: the mean frame's
    last s_axis_acc word held back (:func:`hold_word`) until the frame's other pixels have
    left the pipeline, then the refresh frame's first pixel right behind its last: the
    division must wait for that pixel (the golden targets with and without it differ)."""
    assert not (resize_in_run and (all_bad or bright_second or late_mean_word))
    assert start_frame in (0, 2) and not (start_frame == 0 and traffic)
    assert not bright_second or second_run
    fh, fw = size
    ffc_idle = idle if ffc_idle is None else ffc_idle
    ffc_bp = bp if ffc_bp is None else ffc_bp
    bench = await make_bench(dut, salt)
    cfg, rng = bench.cfg, bench.rng
    s = FfcStreams(bench)
    foff_mon = WordMonitor(bench, "m_axis_foff") if hold_refresh else None
    acc_mon = WordMonitor(bench, "s_axis_acc") if late_mean_word else None
    t = None
    if traffic:
        from irnuc.cocotb_tests.axil_traffic import Traffic

        t = Traffic(bench)
        t.hold_readies(True)
        await t.quiet_ops(40)
        await t.restore()
    regs = bench.registers() if firmware else None
    info = None
    if regs is not None:
        rc, info = await driver.probe(regs)
        assert rc == driver.OK and info is not None, f"driver.probe: {rc}"
        rc = await driver.configure(regs, info, cfg.base_method, fw, fh)
        assert rc == driver.OK, f"driver.configure: {rc}"
    else:
        await bench.frame_size(fh, fw)
    for reg in ("FFC_CTRL", "FFC_STATUS"):
        await bench.check(reg)
    n = int(cfg.ffc_frames or 1)
    count = n if frames is None else frames
    runs = {start_frame: count}
    # The first frame after the run (after its refresh frame with N shutter frames).
    after = start_frame + count + int(count == n)
    if second_run is not None:  # an open frame, then the second run
        runs[after + 1] = second_run
    last_start, last_count = max(runs.items())
    shutter = ffc_shutter_flags(last_start + last_count + 3, runs)
    framing = ffc_framing(cfg, shutter, start=last_start)
    c = ffc_calibration(cfg, fh, fw, rng, "camera")
    start_offset = None
    if all_bad:
        c, start_offset = _all_bad(c, rng)
    if bright_second:
        c = _gains_at_least_one(c)
    if regs is not None:
        await driver.load_calibration(regs, driver.Calibration(**{
            name: int(value) for name, value in c.registers.items()}))
    else:
        for name, value in c.registers.items():  # tc_offset: T_REF
            await bench.write_method_register(name, int(value))
    readings = [random_reading(cfg, c, rng) for _ in shutter]
    sizes = [(fh, fw)] * after + [resize_in_run or (fh, fw)] * (len(shutter) - after)
    golden = bench.env.golden
    if resize_in_run is None:
        scene = ffc_raws(cfg, [int(v) for v in shutter], fh, fw, rng, "camera")
        if bright_second:  # the second run's shutter frames at full scale
            top = (1 << cfg.adc_bits) - 1
            scene = [np.full_like(r, top) if sh and k > after else r
                     for k, (r, sh) in enumerate(zip(scene, shutter, strict=True))]
        run = ffc_run(c, scene, shutter, readings=readings, golden=golden,
                      offset=start_offset)
        _check_conditions(run, c, scene, shutter, readings, golden, start_frame, all_bad,
                          bright_second, late_mean_word, start_offset)
    else:
        run = _joined(*(ffc_run(cc, ffc_raws(cfg, [int(v) for v in sh], *shape, rng, "camera"),
                                sh, readings=rd, golden=golden)
                        for cc, sh, shape, rd in (
                            (c, shutter[:after], (fh, fw), readings[:after]),
                            (_tiled(c, *resize_in_run), shutter[after:], resize_in_run,
                             readings[after:]))))
    assert framing.acc_in == tuple(a is not None for a in run.acc_in)
    assert framing.foff_out == tuple(a is not None for a in run.foff_out)
    raws = [f.raw for f in run.frames]
    starts = np.concatenate([[0], np.cumsum([h * w for h, w in sizes])])  # each frame's first beat
    video = video_beats(raws)
    coef = coef_beats([f.drive.words for f in run.frames])
    fr = axis_framer(*video, *coef,
                     [dataclasses.replace(bench.settings(), height=h, width=w) for h, w in sizes],
                     golden)
    assert [f.raw.tolist() for f in fr.frames] == [r.tolist() for r in raws]

    cbits = cfg.memories["ffc_offset"].word_bits
    done_bit = bench.model.map["IRQ_STATUS"].field("ffc_done")
    if regs is not None:
        await driver.enable_irq(regs, error=1, ffc_done=1)
    else:
        await bench.write("IRQ_ENABLE", 1 << bench.model.map["IRQ_ENABLE"].field("ffc_done").lsb)
    bench.patterns(idle, idle, bp)
    s.patterns(ffc_idle, ffc_bp)

    async def set_reading(value: int) -> None:
        if regs is not None:
            await driver.set_reading(regs, value)
        else:
            await bench.write_method_register("reading", value)

    ctrl = bench.model.map["FFC_CTRL"]
    m = bench.model
    seen: dict[str, int] = {}

    async def write_ffc(frames: int = count, again: bool = False) -> None:
        if again:
            # The first run finished (done): its IRQ_STATUS.ffc_done cleared before the
            # second starts (a clear after a short second run's end would clear its done).
            await bench.write("IRQ_STATUS", done_bit.mask)
            await ClockCycles(dut.clk_i, 2)
            assert int(dut.irq_o.value) == 0, "irq_o stays 1 after the W1C of ffc_done"
            sample("axis.ffc.runs", "second")
        if regs is not None and info is not None:
            assert await driver.ffc_start(regs, info, frames) == driver.OK
        else:
            await bench.write("FFC_CTRL", (1 << ctrl.field("start").lsb)
                              | (frames << ctrl.field("frames").lsb))
        if t is not None:
            t.pause(False)
        seen["write_beat" if not again else "second_beat"] = bench.beats_in
        begin = start_frame if not again else after + 1
        assert bench.beats_in < starts[begin] or bench.beats_in == begin == 0, (
            f"FFC_CTRL written after frame {begin} started ({bench.beats_in} beats taken)")
        await bench.check("FFC_CTRL")
        m.set_live("FFC_STATUS", "busy", 1)
        m.set_live("FFC_STATUS", "done", 0)  # a start clears done
        await bench.check("FFC_STATUS")
        sample("axis.ffc.status", "busy")
        if not again:
            assert int(dut.irq_o.value) == 0, "irq_o (IRQ_ENABLE.ffc_done) before the FFC ran"

    async def write_ffc_again() -> None:
        await write_ffc(second_run, again=True)

    def write_reading(k: int):
        """READING of frame k + 1, written while frame k streams (it must land before
        frame k + 1 starts: the core takes it at that frame start). The random traffic is
        paused for it as for FFC_CTRL: a write waits for the one in flight and, with BREADY
        held low at random, took up to 37 cycles (the register file answers in 6)."""
        async def write() -> None:
            if t is not None:
                t.pause(True)
            await set_reading(int(readings[k + 1]))
            if t is not None:
                t.pause(False)
            assert bench.beats_in < starts[k + 1], (
                f"READING of frame {k + 1} written after that frame started "
                f"({bench.beats_in} beats taken)")
        return write

    if readings[0] is not None:
        await set_reading(readings[0])
    acts = []
    if start_frame == 0:  # before any frame
        await write_ffc()
    bench.send(*video, *coef)
    for k, f in enumerate(run.foff_in):
        assert framing.foff_in[k]
        s.foff.send_nowait(AxiStreamFrame(_unsigned(f, cbits)))
    for a in run.acc_in:
        if a is not None:
            s.acc.send_nowait(AxiStreamFrame([int(v) for v in np.ravel(a)]))
    stalls: dict[str, list[int]] = {}
    stall_task = cocotb.start_soon(_stall_log(bench, stalls))
    if start_frame > 0:  # in the middle of the frame before
        acts.append(cocotb.start_soon(bench._act(starts[start_frame - 1] + fh * fw // 2,
                                                 write_ffc)))
    if late_mean_word:
        assert ffc_idle == "none", "the hold needs the FFC sources without a pause pattern"
        mean = start_frame + count - 1
        assert count == n and run.acc_in[mean] is not None
        acc_frame = sum(a is not None for a in run.acc_in[:mean])
        acts.append(cocotb.start_soon(hold_word(s.acc, acc_mon, acc_frame,
                                                run.acc_in[mean].size - 1, 200)))
    if second_run is not None:
        acts.append(cocotb.start_soon(bench._act(starts[after] + fh * fw // 4,
                                                 write_ffc_again)))
    if t is not None:
        # The random traffic paused from the frame before each run's start until the run is
        # written: FFC_CTRL (and the clear before a second run) must land before the next
        # frame start, and the register file takes one transaction at a time.
        async def quiet() -> None:
            t.pause(True)

        acts += [cocotb.start_soon(bench._act(beat, quiet)) for beat in
                 (fh * fw, *((starts[after],) if second_run is not None else ()))]
    stop = [False]
    if t is not None:
        t.expect_stream([fr])
        t.streaming = True
        traffic_task = cocotb.start_soon(t.stream_ops(("STATUS",), stop))
    if resize_after_run:
        async def resize() -> None:
            await bench.frame_size(fh, fw)
            seen["resize_beat"] = bench.beats_in
            assert bench.beats_in < (start_frame + count + 1) * fh * fw, (
                "FRAME_SIZE written after the frame it should drain behind")

        acts.append(cocotb.start_soon(bench._act((start_frame + count) * fh * fw + fh * fw // 2,
                                                 resize)))
    if resize_in_run is not None:
        async def resize_now() -> None:
            await bench.frame_size(*resize_in_run)
            seen["resize_beat"] = bench.beats_in
            assert starts[after - 1] <= bench.beats_in < starts[after], (
                "FRAME_SIZE not written during the run's last frame")

        acts.append(cocotb.start_soon(bench._act(starts[after - 1] + fh * fw // 4,
                                                 resize_now)))
    if readings[0] is not None:
        acts += [cocotb.start_soon(bench._act(starts[k] + (starts[k + 1] - starts[k]) // 4,
                                              write_reading(k)))
                 for k in range(len(raws) - 1)]
    limit = 40 * (len(video[0]) * 2) + 2000
    want_acc = [[int(v) for v in np.ravel(a)] for a in run.acc_out if a is not None]
    want_foff = [_unsigned(a, cbits) for a in run.foff_out if a is not None]
    held: list[int] = []
    if foff_mon is not None:
        words = len(want_foff[-1])
        holds = [1, int(rng.integers(2, words - 4)), words - 3]
        acts.append(cocotb.start_soon(held_refresh_checks(
            bench, s.foff_out, foff_mon, len(want_foff) - 1, words, holds, ffc_bp, held)))
    acc_task = cocotb.start_soon(_frames_of(s.acc_out, len(want_acc), limit))
    foff_task = cocotb.start_soon(_frames_of(s.foff_out, len(want_foff), limit))
    shown = [f for f, v in zip(run.frames, framing.shown, strict=True) if v]
    got = await bench.receive(sum(f.raw.size for f in shown), limit)
    for act in acts:
        await act
    got_acc, got_foff = await acc_task, await foff_task
    if foff_mon is not None:
        assert len(held) == 3, f"FFC_STATUS read in {len(held)} of 3 refresh holds"
        tb_lib.record(label=label, refresh_holds=held)
    stall_task.cancel()
    if t is not None:  # the counters are the sequence's to check (held frames not out)
        stop[0] = True
        await traffic_task
        t.streaming = False
        t.hold_readies(False)
    await ClockCycles(dut.clk_i, 40)
    assert s.acc_out.empty() and s.foff_out.empty(), "write-back words after the sequence"

    sb = StageScoreboard(bench.env.golden)
    for f in shown:
        sb.expect_frame(f)
    sb.observe_arrays(**got)
    res = sb.result()
    tb_lib.record(label=label, compared=res.compared, errors=res.errors,
                  lines=res.lines[:10])
    tb_lib.assert_passed(res)
    for name, g, w in (("m_axis_acc", got_acc, want_acc), ("m_axis_foff", got_foff, want_foff)):
        assert len(g) == len(w), f"{name}: {len(g)} frames, the golden model's {len(w)}"
        for k, (a, b) in enumerate(zip(g, w, strict=True)):
            bad = [i for i, (x, y) in enumerate(zip(a, b, strict=False)) if x != y]
            assert len(a) == len(b) and not bad, (
                f"{name} frame {k}: {len(a)} words (tlast), {len(b)} expected; "
                f"{len(bad)} differ, first at word {bad[:1]}")
    if (idle, bp, ffc_idle, ffc_bp) == ("none",) * 4:
        # The last two frames are open frames, shown, back to back at the input, after the
        # refresh frame (which may wait for the target's serial division on frames this
        # small): their 2 H W pixels leave in 2 H W cycles (one per clock through the
        # wrapper's fork). Recorded (test_axis_top's throughput check, with the ports' idle
        # and stalled cycles for triage), then checked.
        first, last = bench.out_cycles[-2 * fh * fw], bench.out_cycles[-1]
        window = {k: [c for c in v if first <= c <= last] for k, v in stalls.items()}
        tb_lib.record(throughput="last_two_frames", pixels=2 * fh * fw,
                      cycles=last - first + 1, stalls=window)
        assert last - first + 1 == 2 * fh * fw, (
            f"the last two frames' {2 * fh * fw} pixels took {last - first + 1} cycles; "
            f"idle/stalled cycles by port {window}")
        sample("stream.back_to_back", "frames")

    assert framing.done is not None, "the sequence does not finish the FFC"
    m.set_live("FFC_STATUS", "busy", 0)
    m.set_live("FFC_STATUS", "done", 1)
    m.set_live("IRQ_STATUS", "ffc_done", 1)
    m.set_live("IRQ_STATUS", "frame_done", 1)
    sample("axis.ffc.status", "done")
    assert int(dut.irq_o.value) == 1, "irq_o is 0 with IRQ_STATUS.ffc_done and its enable"
    sample("axis.ffc.irq", "ffc_done")
    if regs is not None:
        # The firmware's end of the run: FFC_STATUS.done polled, IRQ_STATUS.ffc_done
        # cleared, the status read (its sticky bits cleared).
        assert await driver.ffc_wait(regs, 4) == driver.OK
        await bench.check("IRQ_STATUS")
        await ClockCycles(dut.clk_i, 2)
        assert int(dut.irq_o.value) == 0, "irq_o stays 1 after the W1C of ffc_done"
        st = await driver.read_status(regs)
        assert (st.frames_in, st.frames_out) == (len(raws), len(shown)), st
        assert st.irq_status == 1 << bench.model.map["IRQ_STATUS"].field("frame_done").lsb
        assert not st.status & 0x3F and not (st.sof_errors | st.eol_errors | st.coef_errors)
        await bench.check("IRQ_STATUS")
        sample("axis.ffc.irq", "cleared")
    else:
        await bench.check("FFC_STATUS")
        irq = await bench.read("IRQ_STATUS")
        assert (irq & done_bit.mask) >> done_bit.lsb == 1, f"IRQ_STATUS 0x{irq:x}: no ffc_done"
        assert await bench.read("FRAMES_IN") == len(raws)
        assert await bench.read("FRAMES_OUT") == len(shown), "held frames are not output"
        # a start clears done
        await bench.write("IRQ_STATUS", done_bit.mask)
        irq = await bench.read("IRQ_STATUS")
        assert not irq & done_bit.mask, f"IRQ_STATUS 0x{irq:x} after its W1C"
        assert int(dut.irq_o.value) == 0, "irq_o stays 1 after the W1C of ffc_done"
        sample("axis.ffc.irq", "cleared")
    if coverage.enabled():
        pattern_in = idle if idle == ffc_idle else "mixed"
        pattern_out = bp if bp == ffc_bp else "mixed"
        cov = coverage.model(TOP, cfg)
        cov.sample_classes(ffc_axis_classes(framing, n, count, start_frame, seen["write_beat"],
                                            fh * fw, pattern_in, pattern_out,
                                            resize_beat=seen.get("resize_beat"),
                                            resized=resize_in_run is not None))
        coverage.export()


@cocotb.test()
async def ffc_refresh_full_rate(dut) -> None:
    """A refresh through the registers at valid = ready = 1: FFC_CTRL written mid frame
    (start, N frames), the N shutter frames from the next frame start (accumulated on
    m_axis_acc, held), the refresh frame's new offsets on m_axis_foff, FFC_STATUS busy
    then done, IRQ_STATUS.ffc_done."""
    await refresh_sequence(dut, 40, None, "none", "none", "ffc refresh full rate")


@cocotb.test()
async def ffc_refresh_idle_backpressure(dut) -> None:
    """The refresh with idle cycles on every input and backpressure on every output, every
    register access the firmware driver's (irnuc.cosim.driver over the generated register
    model)."""
    await refresh_sequence(dut, 41, None, "random", "random", "ffc refresh idle/bp",
                           firmware=True)


@cocotb.test()
async def ffc_short_run(dut) -> None:
    """FFC_CTRL.frames below N: a run without a refresh (no m_axis_foff words, the offsets
    stay), done when the next open frame starts; bursty idle and alternate backpressure on
    the video streams, alternate idle and bursty backpressure on the FFC streams; a
    FRAME_SIZE write after the (held) shutter frames drains the framer."""
    await refresh_sequence(dut, 42, 2, "bursty", "alternate", "ffc short run",
                           ffc_idle="alternate", ffc_bp="bursty", resize_after_run=True)


@cocotb.test()
async def ffc_resize_in_run(dut) -> None:
    """FRAME_SIZE written to a new width during a short run's last (held) shutter frame,
    with bursty backpressure on the write-back stream: the frames after the run have the new
    size, and the run's m_axis_acc frames still end at the old one (the drain waits for
    their last words, not only for the core's pixels)."""
    await refresh_sequence(dut, 44, 2, "none", "none", "ffc resize in run",
                           ffc_idle="none", ffc_bp="bursty", resize_in_run=(H, W + 2))


@cocotb.test()
async def ffc_resize_in_refresh(dut) -> None:
    """FRAME_SIZE written to a new height during the refresh frame of a full run, with
    bursty backpressure on the write-back streams: the refresh's m_axis_foff frame ends at the
    old size (the drain waits for its last new offset, not only for the frame's pixels)."""
    await refresh_sequence(dut, 45, None, "none", "none", "ffc resize in refresh",
                           ffc_idle="none", ffc_bp="bursty", resize_in_run=(H + 1, W))


@cocotb.test()
async def ffc_second_run(dut) -> None:
    """A second FFC run after the first (a short one, FFC_CTRL.frames 1, written while an
    open frame streams after the first run's refresh): busy again, done at its end; with
    random register traffic before the sequence and while it streams."""
    await refresh_sequence(dut, 46, None, "random", "random", "ffc second run",
                           second_run=1, traffic=True)


@cocotb.test()
async def ffc_refresh_held(dut) -> None:
    """FFC_STATUS read mid-refresh: the refresh frame's new offsets held by backpressure on
    m_axis_foff after its first word, after a random one and before its last three; during
    each hold FFC_STATUS reads busy, not done, and irq_o is 0 (done only with the refresh's
    last word, tlast: the catalogue's ax_ffc_refresh_any_word raises it with the first);
    random idle cycles on the inputs, alternate backpressure on the FFC streams between."""
    await refresh_sequence(dut, 47, None, "random", "none", "ffc refresh held",
                           ffc_idle="none", ffc_bp="alternate", hold_refresh=True)


@cocotb.test()
async def ffc_one_line(dut) -> None:
    """The refresh on frames of one line: the write-back streams' last-line flag holds
    from the frame's first word (tlast on every line's last word, the line is the frame)."""
    await refresh_sequence(dut, 43, None, "random", "random", "ffc one line", size=(1, 16))


@cocotb.test()
async def ffc_one_column(dut) -> None:
    """The refresh on frames of one column (23 x 1) at valid = ready = 1: every write-back
    word ends its line, so the last-line flag is only ever stepped from the row before it
    (height - 2; with two pixels or more per line a word inside the last line sets it
    again, and an idle cycle refreshes it): tlast on exactly the frame's last word of
    m_axis_acc and m_axis_foff. Issue 39: the automatic mutant auto_irnuc_axis_ffc_s1_2,
    bit 7 of height - 2 tied to 1, left tlast off; session 50's draw, bit 2 of height - 1
    flipped where its bit 0 is 0 before height - 2 is taken from it, survived 24 lines
    (23 - 1 is odd), so the height is odd: 22 has bit 0 clear and bit 2 set."""
    await refresh_sequence(dut, 56, None, "none", "none", "ffc one column", size=(23, 1))


@cocotb.test()
async def ffc_tall_frames(dut) -> None:
    """The refresh on frames of 300 x 2 (or the build's largest height) at valid = ready =
    1: the write-back's line count and its last-line compares use the height's bit 8
    (299 = 256 + 43), which the short frames of the other tests leave at 0;
    tlast on exactly each frame's last word of m_axis_acc and m_axis_foff, the words and
    the frames after the refresh against the golden model. Session 51's automatic mutants
    auto_irnuc_axis_ffc_s1_4 (bit 8 of the copied height - 1 tied to 0) survived every
    shorter frame."""
    cfg = tb_lib.config_from_env()
    await refresh_sequence(dut, 57, None, "none", "none", "ffc tall frames",
                           size=(min(cfg.max_height, 300), min(cfg.max_width, 2)))


@cocotb.test()
async def ffc_wide_frames(dut) -> None:
    """The refresh on frames of 2 x 778 (or the build's largest width) at valid = ready =
    1: the write-back's column count through the width's bit 9. Session 51's automatic
    mutant auto_irnuc_axis_ffc_s1_2 (the m_axis_foff column count's next value, bit 8
    flipped where bit 9 is set) counts 511 -> 768 -> 513 -> 770 ...: right on odd words, 256
    high on even ones, so the line's end, stepped from width - 2, is found only where
    width - 2 is odd (777 pixels leave it alive; 778 end the line at word 522)."""
    cfg = tb_lib.config_from_env()
    await refresh_sequence(dut, 58, None, "none", "none", "ffc wide frames",
                           size=(min(cfg.max_height, 2), min(cfg.max_width, 778)))


@cocotb.test()
async def ffc_first_run_all_bad(dut) -> None:
    """FFC_CTRL written before the first frame, on a calibration whose every pixel is bad,
    over nonzero corrections in the host's memory: the run's shutter frames come before any
    open frame was output, so they are shown even where the build holds shutter frames;
    the mean frame has no good pixel, so there is no target and the refresh writes the
    corrections back unchanged (m_axis_foff; a target of 0 would move them); idle cycles
    and backpressure on every stream."""
    await refresh_sequence(dut, 53, None, "random", "random", "ffc first run all bad",
                           start_frame=0, all_bad=True)


@cocotb.test()
async def ffc_bright_second_refresh(dut) -> None:
    """Two full refreshes, the second over a shutter at the ADC's full scale with the gains
    at least 1: its mean lies above the target's range and is clamped to its top, the
    first's is not, so the second refresh needs a division of its own (its refreshed
    offsets and the frames after it against the golden model); random idle cycles on the
    inputs (the second start is written in the open frame between), bursty backpressure."""
    n = int(tb_lib.config_from_env().ffc_frames or 1)
    await refresh_sequence(dut, 54, None, "random", "bursty", "ffc bright second refresh",
                           second_run=n, bright_second=True)


@cocotb.test()
async def ffc_mean_word_late(dut) -> None:
    """The mean frame's last accumulator word held back on s_axis_acc for 200 cycles: the
    frame's other pixels leave the pipeline, then its last pixel enters with the refresh
    frame's first pixel waiting right behind it; the target's division must wait for that
    last pixel (with it and without it the golden targets differ)."""
    await refresh_sequence(dut, 55, None, "none", "alternate", "ffc mean word late",
                           ffc_idle="none", ffc_bp="none", late_mean_word=True)


@cocotb.test()
async def ffc_shutter_past_count(dut) -> None:
    """A run whose FFC_CTRL.frames passes the sequencer's count range: 2^CountBits + N + 1
    shutter frames (CountBits = clog2(N + 1), ffc_ctrl's counter) on 4 x 6 frames. The
    frames after the N-th accumulate nothing and the one mean and refresh follow the
    golden model; a count that kept moving past N would wrap and start a second mean
    (issue 39: the automatic mutant auto_ffc_ctrl_s1_6, its accumulate flag tied to 1)."""
    n = int(tb_lib.config_from_env().ffc_frames or 1)
    frames = 2 ** n.bit_length() + n + 1  # clog2(N + 1) = bit_length(N)
    await refresh_sequence(dut, 57, frames, "none", "none", "ffc shutter past count",
                           size=(4, 6))


# ---- the FFC request (FFC_PERIOD, FFC_THRESHOLD; irnuc_ffc_trigger) ------------------------

#: Frame size of the request sequences: the trigger acts once per frame start, so frames are
#: small (one line and a few pixels past the DPC window's width).
TRIGGER_SIZE = (2, 4)


async def trigger_sequence(dut, salt: int, policy: dict[int, tuple[int, int]],
                           offsets: list[int], starts: set[int], clears: set[int],
                           label: str, bp: str = "none") -> None:
    """Frames sent one at a time (each frame's registers written before it, its state read
    after its start) with the FFC request enabled: ``policy`` maps a frame to the
    (FFC_PERIOD, FFC_THRESHOLD) written before it; ``offsets`` the FPA reading of each frame
    as an offset from a random base reading (tc_offset: READING written before each frame;
    a build without the reading reads 0 there); ``starts`` the frames an FFC_CTRL.start
    (one shutter frame: a short run) is written before; ``clears`` the frames before which
    IRQ_STATUS.ffc_request is cleared (W1C). After each frame start FFC_TRIGGER, FFC_REF,
    IRQ_STATUS.ffc_request and irq_o (IRQ_ENABLE.ffc_request only) must be those of the
    golden policy (nuc_fixed.ffc_policy.ffc_trigger) frame by frame; the pixels, the FFC
    streams and FFC_PERIOD / FFC_THRESHOLD read back are checked against their models."""
    from irnuc.nuc_fixed.ffc_policy import FfcPolicy, ffc_trigger

    fh, fw = TRIGGER_SIZE
    bench = await make_bench(dut, salt)
    cfg, rng, m = bench.cfg, bench.rng, bench.model
    s = FfcStreams(bench)
    await bench.frame_size(fh, fw)
    n_frames = len(offsets)
    shutter = ffc_shutter_flags(n_frames, dict.fromkeys(starts, 1))
    framing = ffc_framing(cfg, shutter)
    c = ffc_calibration(cfg, fh, fw, rng, "camera")
    for name, value in c.registers.items():  # tc_offset: T_REF
        await bench.write_method_register(name, int(value))
    has_reading = random_reading(cfg, c, rng) is not None
    if has_reading:
        top = (1 << int(cfg.reading_bits)) - 1
        base = int(rng.integers(64, top - 64))
        readings: list[int | None] = [int(np.clip(base + d, 0, top)) for d in offsets]
    else:
        readings = [None] * n_frames
    run = ffc_run(c, ffc_raws(cfg, [int(v) for v in shutter], fh, fw, rng, "camera"),
                  shutter, readings=readings, golden=bench.env.golden)
    cbits = cfg.memories["ffc_offset"].word_bits

    # The golden policy, the policy of each frame the one written last before it, on the
    # readings as the RTL sees them (0 without the reading).
    seen = [0 if r is None else r for r in readings]
    pols, pol = [], FfcPolicy()
    for k in range(n_frames):
        pol = FfcPolicy(*policy[k]) if k in policy else pol
        pols.append(pol)
    t = ffc_trigger(seen, starts, pols)
    expect_req = [bool(v) for v in t.request]

    await bench.write("IRQ_ENABLE",
                      1 << m.map["IRQ_ENABLE"].field("ffc_request").lsb)
    bench.patterns("none", "none", bp)
    s.patterns("none", bp)
    ctrl = m.map["FFC_CTRL"]
    rbit = m.map["IRQ_STATUS"].field("ffc_request")
    sticky, cov = False, set()
    last_request: int | None = None
    frame_beats = fh * fw
    for k in range(n_frames):
        if k in policy:
            await bench.write("FFC_PERIOD", policy[k][0])
            await bench.write("FFC_THRESHOLD", policy[k][1])
            await bench.check("FFC_PERIOD")
            await bench.check("FFC_THRESHOLD")
        if k in clears:
            await bench.write("IRQ_STATUS", rbit.mask)
            sticky = False
            got = (await bench.read("IRQ_STATUS") & rbit.mask) >> rbit.lsb
            assert got == 0, f"frame {k}: IRQ_STATUS.ffc_request still 1 after its W1C"
            await ClockCycles(dut.clk_i, 2)
            assert int(dut.irq_o.value) == 0, f"frame {k}: irq_o stays 1 after the W1C"
            cov.add("cleared")
        if readings[k] is not None:
            await bench.write_method_register("reading", int(readings[k]))
        if k in starts:
            await bench.write("FFC_CTRL", (1 << ctrl.field("start").lsb)
                              | (1 << ctrl.field("frames").lsb))
        f = run.frames[k]
        bench.send(*video_beats([f.raw]), *coef_beats([f.drive.words]))
        s.foff.send_nowait(AxiStreamFrame(_unsigned(run.foff_in[k], cbits)))
        if run.acc_in[k] is not None:
            s.acc.send_nowait(AxiStreamFrame([int(v) for v in np.ravel(run.acc_in[k])]))
        target = (k + 1) * frame_beats
        for _ in range(200 * frame_beats):
            if bench.beats_in >= target:
                break
            await ClockCycles(dut.clk_i, 1)
        assert bench.beats_in >= target, f"frame {k}: {bench.beats_in} of {target} beats taken"
        await ClockCycles(dut.clk_i, 8)
        m.set_live("FFC_TRIGGER", "since", int(t.since[k]))
        m.set_live("FFC_TRIGGER", "period", int(t.period_hit[k]))
        m.set_live("FFC_TRIGGER", "threshold", int(t.threshold_hit[k]))
        m.set_live("FFC_REF", "reading", int(t.ref[k]))
        await bench.check("FFC_TRIGGER")
        await bench.check("FFC_REF")
        sticky = sticky or expect_req[k]
        got = (await bench.read("IRQ_STATUS") & rbit.mask) >> rbit.lsb
        assert got == int(sticky), (
            f"frame {k}: IRQ_STATUS.ffc_request {got}, the policy says {int(sticky)} (request "
            f"{expect_req[k]}, since {int(t.since[k])}, ref {int(t.ref[k])}, reading {seen[k]})")
        assert int(dut.irq_o.value) == int(sticky), f"frame {k}: irq_o is not ffc_request"
        if expect_req[k]:
            ph, th = bool(t.period_hit[k]), bool(t.threshold_hit[k])
            cov.add("both" if ph and th else "period" if ph else "threshold")
            if last_request is not None and any(last_request < f_ <= k for f_ in starts):
                cov.add("rearmed")  # a request, an FFC, a request again
            last_request = k
    off = [k for k, p in enumerate(pols) if p == FfcPolicy()]
    if len(off) > 1 and not any(expect_req[k] for k in off):
        cov.add("disabled")  # frames with both triggers 0 (and checked: no request)
    shown = [f for f, v in zip(run.frames, framing.shown, strict=True) if v]
    got_px = await bench.receive(sum(f.raw.size for f in shown), 4000)
    sb = StageScoreboard(bench.env.golden)
    for f in shown:
        sb.expect_frame(f)
    sb.observe_arrays(**got_px)
    res = sb.result()
    tb_lib.record(label=label, compared=res.compared, errors=res.errors, lines=res.lines[:10],
                  requests=[k for k, v in enumerate(expect_req) if v])
    tb_lib.assert_passed(res)
    want_acc = sum(a is not None for a in run.acc_out)
    assert s.acc_out.count() == want_acc, (
        f"{s.acc_out.count()} m_axis_acc frames, the golden model's {want_acc}")
    for b in sorted(cov):
        sample("axis.ffc.request", b)
    export()


@cocotb.test()
async def ffc_request_period(dut) -> None:
    """FFC_PERIOD = 3: requests at frames 3, 8 and 12 (FFCs before frames 5 and 9 restart
    the count), the first two cleared (W1C) before the next; a request after the FFC that
    answered the first one (re-armed)."""
    await trigger_sequence(dut, 50, {0: (3, 0)}, [0] * 14, {5, 9}, {4, 9}, "ffc request period")


@cocotb.test()
async def ffc_request_threshold(dut) -> None:
    """FFC_PERIOD = 7, FFC_THRESHOLD = 20 codes, the reading moving: the threshold alone at
    frame 3 (a change of exactly 20), both at frame 7 (due fell at 5), an FFC before frame
    9, the threshold again at frame 11 against the new reference; under backpressure. On a
    build without the FPA reading (READING reserved, the reading 0) only the period fires."""
    offsets = [0, 5, 12, 20, 30, 10, 0, -22, -5, 3, 6, 45, 40, 2]
    await trigger_sequence(dut, 51, {0: (7, 20)}, offsets, {9}, {5, 10},
                           "ffc request threshold", bp="random")


@cocotb.test()
async def ffc_request_disabled(dut) -> None:
    """Both triggers 0 over six frames with a moving reading and an FFC: no request; then
    FFC_PERIOD = 2 written with the count already past it: a request at the next frame."""
    offsets = [0, 40, -40, 80, 3, 9, 100, 0]
    await trigger_sequence(dut, 52, {0: (0, 0), 6: (2, 0)}, offsets, {3}, set(),
                           "ffc request disabled")
