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

import warnings

# cocotbext-axi 0.1.28's AXI4-Lite master reads cocotb 2's deprecated Event.data.
warnings.filterwarnings("ignore", message="The data field will be removed",
                        category=DeprecationWarning)

import cocotb  # noqa: E402
import numpy as np  # noqa: E402
from cocotb.triggers import ClockCycles, RisingEdge  # noqa: E402

from irnuc.cocotb_tests import streams, tb_lib  # noqa: E402
from irnuc.cocotb_tests.axis_bench import Bench, export, make_bench, sample  # noqa: E402
from irnuc.cocotb_tests.streams import reset  # noqa: E402
from irnuc.cosim import coverage  # noqa: E402
from irnuc.nuc_fixed import regmap  # noqa: E402
from irnuc.nuc_fixed.axis import (  # noqa: E402
    EVENTS,
    FrameSettings,
    coef_beats,
    video_beats,
)
from irnuc.nuc_fixed.config import BASE_METHODS  # noqa: E402

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
    bench = await make_bench(dut, 0)
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
    export()


@cocotb.test()
async def register_read_write(dut) -> None:
    """Random writes (full words and contiguous byte lanes) to every register and to
    offsets outside the map: every response and every read-back as the model says; a frame
    size of 0 or above FRAME_MAX is refused; W1C bits that are 0 stay 0; a shadowed write
    raises STATUS.pending until a frame starts."""
    bench = await make_bench(dut, 1)
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
            sample("axis.register_access", "write_slverr_value")
        await bench.check("FRAME_SIZE")
    # A field's high byte lane alone: the size it makes keeps the old low byte (5, legal),
    # while the written word's field (cocotbext-axi drives unwritten lanes 0) would be 0.
    await bench.write("FRAME_SIZE", 5 | (5 << 16))
    for strb in (0x2, 0x8):
        assert await bench.write("FRAME_SIZE", 0, strb) == regmap.OKAY, f"strobes {strb:04b}"
        await bench.check("FRAME_SIZE")
    export()


@cocotb.test()
async def reads_and_writes_alternate(dut) -> None:
    """A read and a write that wait together are taken in turn (docs/regmap.md): the read
    unless the last request was a read. Their addresses and data are offered in one cycle
    after reset, after a read and after a write; the first response must be the predicted
    direction's, both as the register model says."""
    from cocotbext.axi.axil_channels import (
        AxiLiteARTransaction,
        AxiLiteAWTransaction,
        AxiLiteWTransaction,
    )

    bench = await make_bench(dut, 14)
    m = bench.model
    wif, rif = bench.axil.write_if, bench.axil.read_if
    enable, ident = m.map["IRQ_ENABLE"].offset, m.map["ID"].offset
    last = None  # the direction of the last request the register file took
    for before in (None, "read", "write", "write", "read"):
        if before == "read":
            await bench.check("ID")
            last = "read"
        elif before == "write":
            await bench.write("IRQ_ENABLE", int(bench.rng.integers(0, 2**32, dtype=np.uint64)))
            last = "write"
        want = "write" if last == "read" else "read"
        value = int(bench.rng.integers(0, 2**32, dtype=np.uint64))
        first: list[str] = []

        async def watch(first: list[str]) -> None:
            while not first:
                await RisingEdge(dut.clk_i)
                for name, valid in (("read", dut.s_axil_rvalid), ("write", dut.s_axil_bvalid)):
                    if int(valid.value):
                        first.append(name)

        async with bench.wlock, bench.rlock:
            await RisingEdge(dut.clk_i)
            seen = cocotb.start_soon(watch(first))
            await rif.ar_channel.send(AxiLiteARTransaction(araddr=ident, arprot=0))
            await wif.aw_channel.send(AxiLiteAWTransaction(awaddr=enable, awprot=0))
            await wif.w_channel.send(AxiLiteWTransaction(wdata=value, wstrb=0xF))
            b = await wif.b_channel.recv()
            r = await rif.r_channel.recv()
            await seen
        assert first[:1] == [want], (
            f"after {before or 'reset'}: a read and a write waiting together, the "
            f"{first[0] if first else 'no'} response came first, expected the {want}'s")
        assert len(first) == 1, f"after {before or 'reset'}: both responses in one cycle"
        assert int(b.bresp) == m.write(enable, value, 0xF)
        want_resp, want_data = m.read(ident)
        assert (int(r.rresp), int(r.rdata)) == (want_resp, want_data), (
            f"ID read with a write waiting: {int(r.rresp)}, 0x{int(r.rdata):08x}")
        await bench.check("IRQ_ENABLE")
        last = "read"
    export()


@cocotb.test()
async def register_traffic(dut) -> None:
    """Constrained-random register traffic (cocotb_tests.axil_traffic): random strobes,
    BREADY / RREADY held low, read-only, reserved and unmapped offsets, reads and writes
    while pixels stream (W1C clears racing the stream's framing errors, counters read mid
    frame), a frame at the reset size where it is small: every response and read as the
    register model says."""
    from irnuc.cocotb_tests.axil_traffic import register_traffic as traffic

    bench = await make_bench(dut, 10)

    def frames(b: Bench, h: int, w: int):
        raws, words = _frames(b, 1, h, w)
        return video_beats(raws), coef_beats(words)

    await traffic(bench, frames)
    export()


# ---- frames ---------------------------------------------------------------------------------------

@cocotb.test()
async def frames_idle_backpressure(dut) -> None:
    """Frames of several sizes under every idle pattern of the video and coefficient
    streams and every backpressure pattern: bit for bit; the counters agree."""
    bench = await make_bench(dut, 2)
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
        sample("axis.frame_transition", "size_change")
    await bench.check_counts(results)
    export()


@cocotb.test()
async def full_rate_back_to_back(dut) -> None:
    """Back-to-back frames of one size at tvalid = tready = 1: one pixel per clock through
    the framer and the core, no bubble between frames (N outputs in N cycles)."""
    bench = await make_bench(dut, 3)
    h, w = _size(bench, 6, 10)
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 3, h, w)
    await bench.run(video_beats(raws), coef_beats(words), [bench.settings()])
    n = 3 * h * w
    span = bench.out_cycles[-1] - bench.out_cycles[-n] + 1
    assert span == n, f"{n} outputs took {span} cycles"
    sample("stream.back_to_back", "frames")
    sample("axis.frame_transition", "same_size")
    export()


@cocotb.test()
async def registers_mid_frame(dut) -> None:
    """Registers written in the middle of a frame change only the frames that start after
    the write: CTRL (enables) in frame 0 applies from frame 1, FRAME_SIZE in frame 1 from
    frame 2 (which waits until frame 1 has left the core); STATUS.pending shows the write
    until then. Under idle and backpressure."""
    bench = await make_bench(dut, 4)
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
        sample("axis.mid_frame_write", "ctrl")

    async def write_size() -> None:
        await bench.frame_size(h2, w2)
        sample("axis.mid_frame_write", "frame_size")

    s1 = FrameSettings(w, h, nuc_en=False, dpc_en=True, coef_sync=True)
    s2 = FrameSettings(w2, h2, nuc_en=False, dpc_en=True, coef_sync=True)
    res = await bench.run(video, coef, [s0, s1, s2],
                          actions=[((h * w) // 2, write_ctrl), (h * w + (h * w) // 2, write_size)],
                          idle="random", coef_idle="bursty", bp="random", label="mid frame")
    assert seen.get("pending_ctrl") == 1, "STATUS.pending was not 1 after a mid-frame write"
    assert [f.settings for f in res.frames] == [s0, s1, s2]
    await bench.check_counts([res])
    sample("axis.frame_transition", "size_change")
    export()


@cocotb.test()
async def enables(dut) -> None:
    """CTRL.nuc_en and CTRL.dpc_en in all four combinations: with NUC off the core gets
    unity gain and zero offset, with DPC off no bad flag (the words are still taken)."""
    bench = await make_bench(dut, 5)
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
    export()


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
    bench = await make_bench(dut, 6)
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
        sample("axis.irq", "error")
        await bench.clear_status()
        for reg in bench.model.map.counters:
            bench.model.set_live(reg, bench.model.map[reg].fields[0].name, 0)
        await ClockCycles(dut.clk_i, 2)
        assert int(dut.irq_o.value) == 0, f"{name}: irq_o stays 1 after W1C"
        # A clean frame right after is exact.
        raws, words = _frames(bench, 1, h, w)
        res = await bench.run(video_beats(raws), coef_beats(words), [bench.settings()],
                              label=f"after {name}")
        await bench.check_counts([res])
        await bench.clear_status()
    export()


@cocotb.test()
async def coef_sync_off(dut) -> None:
    """With CTRL.coef_sync = 0 the coefficient tlast is ignored: one word per pixel, no
    coefficient error, even with tlast in the middle of a frame."""
    bench = await make_bench(dut, 7)
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
    sample("axis.coef_sync", "off")
    export()


@cocotb.test()
async def frame_done_interrupt(dut) -> None:
    """IRQ_STATUS.frame_done rises with each frame's last output pixel; irq_o follows
    IRQ_ENABLE and falls with the W1C write."""
    bench = await make_bench(dut, 8)
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
    sample("axis.irq", "frame_done")
    export()


@cocotb.test()
async def tallest_frames(dut) -> None:
    """Frames of FRAME_MAX's height, one pixel wide, back to back: FRAMES_OUT counts each
    once and IRQ_STATUS.frame_done rises (the output-row count reaches its largest legal
    value, the height's top bit; the other tests' frames are at most 8 lines tall)."""
    bench = await make_bench(dut, 11)
    h, w = bench.cfg.max_height, 1
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 2, h, w)
    res = await bench.run(video_beats(raws), coef_beats(words), [bench.settings()],
                          label=f"tallest {h}x{w}")
    assert len(res.frames) == 2
    await bench.check_counts([res])
    export()


@cocotb.test()
async def reset_mid_frame(dut) -> None:
    """Reset while a frame streams: the registers are back at their reset values, the
    output is idle, and the next frames are exact."""
    bench = await make_bench(dut, 9)
    h, w = _size(bench, 6, 9)
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 2, h, w)
    bench.patterns("random", "random", "random")
    bench.send(*video_beats(raws), *coef_beats(words))
    while bench.beats_in < h * w // 2:
        await RisingEdge(dut.clk_i)
    await reset(dut, 2)
    assert int(dut.m_axis_video_tvalid.value) == 0, "output valid right after reset"
    sample("axis.reset", "mid_frame")
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
    export()


@cocotb.test()
async def stale_inputs_idled(dut) -> None:
    """A test starts on the signals the one before left: every slave port's valid high
    with junk on its data (a driver that stopped with an item offered: a cocotb test that
    failed mid-stream). The bench's reset idles them (streams.idle_inputs), so no stale word
    is taken at the first edge after reset and the next frames are exact. (A stale
    coefficient word taken there put the coefficient stream one word behind the pixels:
    tcffc14's one-line frames after its failed second run; irnuc_axis_assert's a_reset_idle
    catches a bench that leaves a valid high, test_axis_top's reset test.)"""
    rng = np.random.default_rng(tb_lib.seed_from_env() + 53)
    for name in streams.input_valid_names([h._name for h in dut]):
        getattr(dut, name).value = 1
        data = getattr(dut, name.removesuffix("valid") + "data", None)
        if data is not None:
            data.value = int(rng.integers(0, 1 << min(len(data), 62)))
    bench = await make_bench(dut, 10)
    h, w = _size(bench, 1, 7)
    await bench.frame_size(h, w)
    raws, words = _frames(bench, 2, h, w)
    res = await bench.run(video_beats(raws), coef_beats(words), [bench.settings()],
                          label="after stale inputs")
    await bench.check_counts([res])
