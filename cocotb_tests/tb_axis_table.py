"""cocotb tests of table_interp's per-frame selection in ``irnuc_axis_top`` (TABLE_SEL and
the frame start held while the weight is computed: ``hdl/irnuc_axis_table.sv``; run by
``cocotb_tests/test_axis_top.py`` on table14).

The drivers and models are ``tb_axis``'s (:class:`Bench`). The expected j and weight come
from ``nuc_fixed.tempcomp.interp_weight`` (the golden model of ``interp_weight.sv``), called
here directly, with TABLE_SEL's fields placed by hand from the register map; the frames are
checked bit for bit against ``nuc_fixed.method_top`` through the methods' scoreboard.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import RisingEdge

from irnuc.cocotb_tests.axis_bench import Bench, export, make_bench, sample
from irnuc.cocotb_tests.method_stim import random_coefficients, random_raw, reading_marks
from irnuc.nuc_fixed.axis import FrameSettings, coef_beats, table_pair_words, video_beats
from irnuc.nuc_fixed.tempcomp import interp_weight

H, W = 4, 16  # 64 pixels: a write in a frame's second half ends after the frame


def _sel(bench: Bench, j: int, w: int, error: bool = False) -> int:
    """TABLE_SEL once computed: weight [23:0], j [27:24], valid 28, error 29 (by hand,
    checked against the map)."""
    reg = bench.model.map["TABLE_SEL"]
    assert [(f.name, f.lsb) for f in reg.fields] == [("weight", 0), ("j", 24), ("valid", 28),
                                                     ("error", 29)]
    return w | j << 24 | 1 << 28 | int(error) << 29


async def _settled(bench: Bench, want: int, tries: int = 12) -> int:
    """Read TABLE_SEL until it is valid: every read is 0 (being computed) or ``want``;
    returns how many reads saw it being computed (coverage: what was read and matched)."""
    busy = 0
    one = 1 << bench.cfg.format("weight").frac_bits
    for _ in range(tries):
        got = await bench.read("TABLE_SEL")
        if got == want:
            w, j = want & 0xFF_FFFF, want >> 24 & 0xF
            if want >> 29 & 1:
                sample("axis.table.sel", "error")
            else:
                sample("axis.table.sel", "valid")
                sample("axis.table.j", str(j))
                sample("axis.table.weight", "zero" if w == 0 else "one" if w == one
                        else "between")
            return busy
        assert got == 0, f"TABLE_SEL reads 0x{got:08x}; 0 or 0x{want:08x} expected"
        sample("axis.table.sel", "computing")
        busy += 1
    raise AssertionError(f"TABLE_SEL not valid after {tries} reads (want 0x{want:08x})")


def _readings(bench: Bench) -> tuple[int, ...]:
    """K strictly increasing table readings with gaps of odd and even size."""
    k = int(bench.cfg.tables)
    hi = (1 << int(bench.cfg.reading_bits)) - 1
    gaps = bench.rng.integers(2, hi // (k + 1), size=k - 1)
    start = int(bench.rng.integers(1, hi - int(gaps.sum())))
    return tuple(int(v) for v in start + np.concatenate([[0], np.cumsum(gaps)]))


@cocotb.test()
async def table_sel_readback(dut) -> None:
    """TABLE_SEL after every READING write (the table readings' marks: below the first,
    on each, between, above the last, and random readings) and after table readings are
    rewritten: j and the weight of interp_weight, never a value but 0 (being computed) or
    the expected one; a read straight after a write sees the computation (valid 0). Reset
    value 0 (nothing written yet)."""
    bench = await make_bench(dut, 40)
    cfg = bench.cfg
    assert await bench.read("TABLE_SEL") == 0
    busy, js, ws = 0, set(), set()
    for _ in range(2):
        rs = _readings(bench)
        await bench.write_method_register("table_readings", rs)
        hi = (1 << int(cfg.reading_bits)) - 1
        marks = [int(np.clip(m, 0, hi)) for m in reading_marks(cfg, _Regs(rs))]
        marks += [int(v) for v in bench.rng.integers(0, hi + 1, size=4)]
        for t in marks:
            await bench.write_method_register("reading", t)
            iw = interp_weight(t, rs, cfg)
            js.add(iw.j)
            ws.add(iw.w)
            busy += await _settled(bench, _sel(bench, iw.j, iw.w)) > 0
    assert js == set(range(int(cfg.tables) - 1)), js
    assert {0, 1 << cfg.format("weight").frac_bits} <= ws, ws
    assert busy > 0, "no read saw TABLE_SEL being computed"
    export()


class _Regs:
    """The registers reading_marks reads (the table readings)."""

    def __init__(self, rs: tuple[int, ...]) -> None:
        self.registers = {"table_readings": rs}


@cocotb.test()
async def table_sel_error(dut) -> None:
    """Table readings that do not increase strictly (two equal, then decreasing): TABLE_SEL
    reads error with j = weight = 0 and the frame takes weight 0 (its lower table's words
    unweighted); readings made increasing again clear it."""
    bench = await make_bench(dut, 41)
    cfg = bench.cfg
    await bench.frame_size(H, W)
    c = random_coefficients(cfg, H, W, bench.rng, bad_fraction=0.2)
    results = []
    good = _readings(bench)
    patterns = (("random", "bursty"), ("alternate", "random"))
    for (idle, bp), rs in zip(patterns, ((good[0], good[0], *good[2:]), tuple(reversed(good))),
                              strict=True):
        await bench.write_method_register("table_readings", rs)
        await bench.write_method_register("reading", good[1])
        await _settled(bench, _sel(bench, 0, 0, error=True))
        s = bench.settings()
        assert s.frame_word == 0, s
        raw = random_raw(cfg, H, W, bench.rng)
        results.append(await bench.run(video_beats([raw]),
                                       coef_beats([table_pair_words(c, 0)]), [s],
                                       idle=idle, coef_idle=bp, bp=bp,
                                       label=f"error readings {rs}"))
    await bench.write_method_register("table_readings", good)
    t = (good[0] + good[1]) // 2
    await bench.write_method_register("reading", t)
    iw = interp_weight(t, good, cfg)
    await _settled(bench, _sel(bench, iw.j, iw.w))
    raw = random_raw(cfg, H, W, bench.rng)
    results.append(await bench.run(video_beats([raw]), coef_beats([table_pair_words(c, iw.j)]),
                                   [bench.settings()], idle="bursty", coef_idle="alternate",
                                   bp="alternate", label="increasing again"))
    await bench.check_counts(results)
    export()


@cocotb.test()
async def frame_start_waits(dut) -> None:
    """A frame waiting at full rate does not start before its weight is computed: READING
    written just before it (its third beat, past the input buffer, is taken Wf + 5 or more cycles after the
    write)
    and written in the second half of the frame before it (a gap before the next frame's
    first beat); each frame bit for bit with the weight of its own reading (tables j and
    j + 1 of it, whose words differ)."""
    bench = await make_bench(dut, 42)
    cfg = bench.cfg
    wf = cfg.format("weight").frac_bits
    await bench.frame_size(H, W)
    c = random_coefficients(cfg, H, W, bench.rng, bad_fraction=0.1)
    rs = _readings(bench)
    await bench.write_method_register("table_readings", rs)
    taken: list[int] = []

    async def watch() -> None:
        edge = RisingEdge(dut.clk_i)
        while True:
            await edge
            if int(dut.s_axis_video_tvalid.value) and int(dut.s_axis_video_tready.value):
                taken.append(bench.cycle)

    cocotb.start_soon(watch())
    # Between frames: the write, then the frame at once.
    t0 = (rs[0] + rs[1]) // 2 + 1
    await bench.write_method_register("reading", t0)
    written = bench.cycle
    s0 = bench.settings()
    iw0 = interp_weight(t0, rs, cfg)
    assert s0.frame_word == iw0.w
    raw = random_raw(cfg, H, W, bench.rng)
    await bench.run(video_beats([raw]), coef_beats([table_pair_words(c, iw0.j)]), [s0],
                    label="write just before the frame")
    # s_axis_video's two-entry buffer takes two beats whatever the framer does; the third
    # enters once the framer took the first (the frame started).
    assert taken[2] - written >= wf + 5, (written, taken[:3])
    sample("axis.table.held", "between_frames")
    # In the frame before: frame 1 takes the new reading, after a gap.
    await bench.write_method_register("reading", t0)
    await _settled(bench, _sel(bench, iw0.j, iw0.w))
    t1 = (rs[1] + rs[2]) // 2 if len(rs) > 2 else rs[0]
    iw1 = interp_weight(t1, rs, cfg)
    raws = [random_raw(cfg, H, W, bench.rng) for _ in range(2)]
    words = [table_pair_words(c, iw0.j), table_pair_words(c, iw1.j)]
    settings = [bench.settings(), FrameSettings(W, H, frame_word=iw1.w)]
    taken.clear()

    async def write() -> None:
        await bench.write_method_register("reading", t1)

    await bench.run(video_beats(raws), coef_beats(words), settings,
                    actions=[(bench.beats_in + H * W * 3 // 4, write)],
                    label="write in the frame before")
    # Full rate but for the held start (the buffer takes the next frame's first two beats).
    gaps = np.diff(taken[H * W - 2:H * W + 4])
    assert gaps.max() > 1, f"no gap in the beats around the frame start: {gaps}"
    assert (np.diff(taken[:H * W - 2]) == 1).all(), "gaps inside the first frame"
    sample("axis.table.held", "in_frame_before")
    sample("stream.back_to_back", "frames")
    export()
