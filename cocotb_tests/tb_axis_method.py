"""cocotb tests of ``irnuc_axis_top`` built around ``method_dpc_top`` (a base method other
than two_point; run by ``cocotb_tests/test_axis_top.py``).

The drivers, the register model and the framing model are ``tb_axis``'s (:class:`Bench`);
the coefficient words are the method's (``irnuc.cosim.stream.frame_drive`` of a random
calibration, ``method_stim``) and the method's registers (GAIN, LEVEL, T_REF, READING) are
written through AXI4-Lite. The expected pixels come from ``nuc_fixed.method_top`` on the
calibration and reading each frame was given, through the one in-order scoreboard
(``MethodScoreboard``), bit for bit. Small frames: each test runs in a few seconds.
"""

from __future__ import annotations

import cocotb

from irnuc.cocotb_tests.axis_bench import Bench, export, make_bench, sample
from irnuc.cocotb_tests.method_stim import random_coefficients, random_raw, random_reading
from irnuc.cosim.stream import coef_stream_bits, frame_drive
from irnuc.nuc_fixed.axis import FrameSettings, coef_beats, frame_word, video_beats
from irnuc.nuc_fixed.config import BASE_METHODS
from irnuc.nuc_fixed.method_top import MethodCoefficients

#: Frame size of these tests (lines, pixels): small, past the DPC's 3 x 3 window.
H, W = 4, 7


async def _calibration(bench: Bench, h: int = H, w: int = W) -> MethodCoefficients:
    """A random calibration of the frame size; its registers (GAIN, LEVEL, T_REF) written
    through AXI4-Lite."""
    cfg = bench.cfg
    await bench.frame_size(h, w)
    c = random_coefficients(cfg, h, w, bench.rng, bad_fraction=0.2)
    for name, value in c.registers.items():
        await bench.write_method_register(name, value)
    return c


def _reading(bench: Bench, c: MethodCoefficients) -> int | dict[str, int] | None:
    """The frame's readings: the FPA's (tc_offset, table_interp), or the FPA's and the
    housing's, each drawn on its own (tc_housing: the housing moves apart from the FPA)."""
    return random_reading(bench.cfg, c, bench.rng)


def _registers_reading(regs: dict[str, object]) -> int | dict[str, int] | None:
    """The readings a frame takes from the method's registers (READING, HOUSING_READING)."""
    if "housing_reading" in regs:
        return {"fpa": int(regs["reading"]), "housing": int(regs["housing_reading"])}  # type: ignore[call-overload]
    return regs.get("reading")  # type: ignore[return-value]


def _blind_sum(bench: Bench, c: MethodCoefficients) -> int:
    """A frame's blind sum (BLIND_SUM, blind_drift): near the calibration's BLIND_REF
    (a small drift code, either sign), equal to it (no drift), or anywhere in the
    register's range (the drift code saturates)."""
    top = (1 << bench.cfg.blind_sum_bits) - 1
    ref = int(c.registers["blind_ref"])
    kind = int(bench.rng.integers(0, 3))
    if kind == 0:
        return int(bench.rng.integers(0, top + 1))
    step = int(bench.rng.integers(-4096, 4097)) if kind == 1 else 0
    return min(max(ref + step, 0), top)


async def _set_frame_registers(bench: Bench, reading: int | dict[str, int] | None,
                       c: MethodCoefficients | None = None) -> None:
    """The per-frame registers: READING (tc_offset; with tc_housing also HOUSING_READING,
    the host's write of each frame), and with blind_drift a new BLIND_SUM (of ``c``'s
    calibration) for the next frame."""
    if isinstance(reading, dict):
        await bench.write_method_register("reading", reading["fpa"])
        await bench.write_method_register("housing_reading", reading["housing"])
        sample("axis.housing.reading", "between_frames")
    elif reading is not None:
        await bench.write_method_register("reading", reading)
    if c is not None and bench.cfg.has("blind_drift"):
        await bench.write_method_register("blind_sum", _blind_sum(bench, c))
        sample("axis.drift.blind_sum", "between_frames")


def _as_registers(reading: dict[str, int]) -> dict[str, int]:
    return {"reading": reading["fpa"], "housing_reading": reading["housing"]}


@cocotb.test()
async def method_registers(dut) -> None:
    """After reset every register reads as the model says (the method's registers
    present, the others reserved); CONFIG names the method and the width of its
    coefficient word (irnuc.cosim.stream's layout, a second derivation); the method's
    registers read back what was written, and only from a frame start on do they reach
    the core (STATUS.pending)."""
    bench = await make_bench(dut, 20)
    m, cfg = bench.model, bench.cfg
    for r in m.map.registers:
        await bench.check(r.offset)
    config = await bench.read("CONFIG")
    got = {f.name: (config & f.mask) >> f.lsb for f in m.map["CONFIG"].fields}
    assert got["method"] == BASE_METHODS.index(cfg.base_method), got
    assert got["word_bits"] == coef_stream_bits(cfg), got
    for name, r in cfg.registers.items():
        if r.count != 1:
            continue
        value = int(bench.rng.integers(0, 1 << r.width))
        await bench.write_method_register(name, value)
        for reg in bench.slot(name):
            await bench.check(reg)
        assert bench.method_registers()[name] == value
    await bench.check("STATUS")
    export()


@cocotb.test()
async def method_register_traffic(dut) -> None:
    """Constrained-random register traffic on the method's wrapper
    (cocotb_tests.axil_traffic): the method's registers among the shadowed ones, the other
    methods' reserved; frames of a random calibration streamed with traffic."""
    from irnuc.cocotb_tests.axil_traffic import register_traffic as traffic

    bench = await make_bench(dut, 25)

    def frames(b: Bench, h: int, w: int):
        c = random_coefficients(b.cfg, h, w, b.rng, bad_fraction=0.2)
        raw = random_raw(b.cfg, h, w, b.rng)
        # The READING the frame takes (its register as the model holds it).
        reading = _registers_reading(b.method_registers())
        return video_beats([raw]), coef_beats([frame_drive(c, reading).words])

    await traffic(bench, frames)
    export()


@cocotb.test()
async def method_frames_between(dut) -> None:
    """Frames one after the other, each with its own FPA reading written through AXI4-Lite
    between frames (tc_offset; the other methods their registers), under idle and
    backpressure, then one frame with NUC and DPC off (the neutral word and frame word):
    bit for bit against nuc_fixed.method_top."""
    bench = await make_bench(dut, 21)
    c = await _calibration(bench)
    patterns = ("none", "random", "bursty", "alternate")
    results = []
    for k in range(4):
        reading = _reading(bench, c)
        await _set_frame_registers(bench, reading, c)
        raw = random_raw(bench.cfg, H, W, bench.rng)
        words = frame_drive(c, reading).words
        res = await bench.run(video_beats([raw]), coef_beats([words]), [bench.settings()],
                              idle=patterns[k], coef_idle=patterns[(k + 1) % 4],
                              bp=patterns[(k + 2) % 4], label=f"reading {reading}")
        assert res.frames[0].frame_word == bench.settings().frame_word
        results.append(res)
    ctrl = bench.model.map["CTRL"]
    await bench.write("CTRL", 1 << ctrl.field("coef_sync").lsb)
    raw = random_raw(bench.cfg, H, W, bench.rng)
    words = frame_drive(c, _reading(bench, c)).words
    res = await bench.run(video_beats([raw]), coef_beats([words]), [bench.settings()],
                          label="nuc and dpc off")
    results.append(res)
    await bench.check_counts(results)
    export()


@cocotb.test()
async def method_reading_mid_frame(dut) -> None:
    """The method's registers written in the middle of a frame (READING, T_REF, GAIN or
    LEVEL) change only the frames that start after the write: three frames back to back,
    a write in frame 0 and one in frame 1."""
    bench = await make_bench(dut, 22)
    cfg = bench.cfg
    c = await _calibration(bench)
    names = [n for n, r in cfg.registers.items() if r.count == 1]
    readings = [_reading(bench, c) for _ in range(3)]
    await _set_frame_registers(bench, readings[0], c)
    s0 = bench.settings()
    raws = [random_raw(cfg, H, W, bench.rng) for _ in range(3)]
    new = [{n: int(bench.rng.integers(0, 1 << cfg.registers[n].width)) for n in names}
           for _ in range(2)]
    # Each frame's words for the reading it takes (table_interp: its pair of tables).
    readings[1:] = [_registers_reading({**_as_registers(r), **v}) if isinstance(r, dict)
                    else v.get("reading", r) for v, r in zip(new, readings[1:], strict=True)]
    words = [frame_drive(c, r).words for r in readings]
    settings = [s0]
    regs = dict(bench.method_registers())
    for v in new:
        regs |= v
        settings.append(FrameSettings(W, H, frame_word=frame_word(cfg, regs)))

    def writer(v):
        async def write() -> None:
            for n, value in v.items():
                await bench.write_method_register(n, value)
            if "blind_sum" in v:
                sample("axis.drift.blind_sum", "mid_frame")
            if "housing_reading" in v:
                sample("axis.housing.reading", "mid_frame")
        return write

    res = await bench.run(video_beats(raws), coef_beats(words), settings,
                          actions=[(H * W // 4, writer(new[0])),
                                   (H * W + H * W // 4, writer(new[1]))],
                          idle="random", coef_idle="random", bp="random",
                          label="registers mid frame")
    assert [f.frame_word for f in res.frames] == [s.frame_word for s in settings]
    sample("stream.back_to_back", "frames")  # three frames in one stream
    export()


@cocotb.test()
async def method_tiny_frames(dut) -> None:
    """Frames of one pixel back to back at full rate, then under idle and backpressure
    (blind_drift: a blind item and a drift code per frame, each frame waiting for its
    own): bit for bit."""
    bench = await make_bench(dut, 23)
    cfg = bench.cfg
    c = await _calibration(bench, 1, 1)
    reading = _reading(bench, c)
    await _set_frame_registers(bench, reading, c)
    results = []
    for idle, bp in (("none", "none"), ("random", "bursty")):
        raws = [random_raw(cfg, 1, 1, bench.rng) for _ in range(6)]
        words = [frame_drive(c, reading).words] * len(raws)
        res = await bench.run(video_beats(raws), coef_beats(words),
                              [bench.settings()] * len(raws), idle=idle, coef_idle=idle,
                              bp=bp, label=f"one-pixel frames, {idle} / {bp}")
        assert len(res.frames) == len(raws)
        results.append(res)
    await bench.check_counts(results)
    export()
