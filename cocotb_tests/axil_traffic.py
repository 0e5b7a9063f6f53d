"""Constrained-random AXI4-Lite traffic on ``irnuc_axis_top`` (issue 39), shared by the
wrapper's testbenches (``tb_axis``, ``tb_axis_method``, ``tb_axis_ffc``): every
configuration the suite wraps runs it.

The register model of the map's one source (:class:`irnuc.nuc_fixed.regmap.RegisterModel`)
predicts every response and every read:

* writes with random byte strobes (all sixteen, the empty and the non-contiguous ones), the
  address and the data handshakes in either order and apart, to every register, to read-only
  ones, to reserved ones (a method's register the configuration lacks; a reserved read-only
  one answers SLVERR like any read-only one) and to offsets outside the map; reads of all of
  them (the write-only COMMAND answers SLVERR); the responses by address, access and value
  as docs/regmap.md says, from the model;
* a write and a read issued in the same cycle (the register file takes one transaction at a
  time: the other waits, its handshake held, and both are answered as the model says);
* BREADY and RREADY held low for random stretches (the response must wait, unchanged: the
  RTL's protocol checker irnuc_axil_assert is on in every build);
* reads and writes while pixels stream (the registers a frame does not take: W1C clears of
  STATUS and IRQ_STATUS racing the framing-error events, IRQ_ENABLE, read-only and unmapped
  offsets), the live registers then checked against what can be known from outside: each
  counter between its last value read and the frames' totals, an error bit set only for a
  cause the stimulus has; exactly once the stream is quiet;
* a frame at the reset size, with no FRAME_SIZE written since reset (where that frame is
  small enough to simulate).

The AXI4-Lite channels are cocotbext-axi's (the master's own write and read channels, driven
at transaction level: its high-level calls cannot make every strobe); a write and a read may
be issued at once (the bench's locks keep one of each). Coverage: the coverpoints of
:class:`irnuc.cosim.axis_coverage.TrafficCoverageModel`.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, RisingEdge
from cocotbext.axi.axil_channels import (
    AxiLiteARTransaction,
    AxiLiteAWTransaction,
    AxiLiteWTransaction,
)

from irnuc.cosim import coverage
from irnuc.cosim.axis_coverage import RESET_SIZE_PIXELS, TRAFFIC_TOP
from irnuc.nuc_fixed import regmap

#: Registers whose fields the hardware drives (read-back checked against bounds while
#: pixels stream, exactly once they are quiet).
COUNTERS = regmap.register_map().counters
# Computed by the core from other registers and the frames, not modelled here: table_interp's
# pair, the FFC request's state (tb_axis_ffc's request tests check those frame by frame).
_LEVELS = ("TABLE_SEL", "FFC_TRIGGER", "FFC_REF")
# IRQ_STATUS bits raised by unmodelled state (random FFC_PERIOD / FFC_THRESHOLD values make
# FFC requests at frame starts): not compared here, cleared by the W1C like the others.
_UNMODELLED_IRQ = ("ffc_request",)


def _sample(bench, name: str, value: str) -> None:
    if coverage.enabled():
        coverage.model(TRAFFIC_TOP, bench.cfg).sample(name, value)


def _strobe_class(strb: int) -> str:
    if strb == 0xF:
        return "full"
    if strb == 0:
        return "none"
    lanes = [i for i in range(4) if strb >> i & 1]
    return "partial" if lanes == list(range(lanes[0], lanes[-1] + 1)) else "noncontiguous"


def _holds(rng: np.random.Generator):
    """A pause generator: ready high, with random stretches of 1 to 12 cycles low."""
    while True:
        for _ in range(int(rng.integers(0, 12))):
            yield False
        for _ in range(int(rng.integers(1, 13))):
            yield True


class Traffic:
    """Random register traffic on a :class:`~irnuc.cocotb_tests.axis_bench.Bench` (its
    model, its AXI4-Lite master's channels, its locks)."""

    def __init__(self, bench) -> None:
        self.bench, self.model, self.rng = bench, bench.model, bench.rng
        wif, rif = bench.axil.write_if, bench.axil.read_if
        self.aw, self.w, self.b = wif.aw_channel, wif.w_channel, wif.b_channel
        self.ar, self.r = rif.ar_channel, rif.r_channel
        m = self.model
        self.offsets = [r.offset for r in m.map.registers]
        holes = m.reserved_offsets()
        self.holes = [int(o) for o in self.rng.choice(holes, size=min(8, len(holes)),
                                                      replace=False)]
        self.last: dict[tuple[str, str], int] = {}  # a counter field's last value read
        self.streaming = False
        self.bounds: dict[tuple[str, str], int] = {}  # a counter field's most while streaming
        self.causes: set[str] = set()  # error causes the streamed frames have
        self.frames_possible = False
        self.paused = False  # stream_ops waits (a sequence's access that must land in time)
        self._pauses = 0  # the pauses in force (pause)

    # ---- the channels --------------------------------------------------------------------
    def pause(self, on: bool = True) -> None:
        """Hold the random accesses of :meth:`stream_ops` (and BREADY / RREADY high) while
        a sequence makes an access that must land in time (the register file takes one
        transaction at a time), or resume them. Pauses nest (two sequences may hold the
        traffic at once): the accesses resume when every pause is resumed."""
        self._pauses = max(0, self._pauses + (1 if on else -1))
        if self.paused != (self._pauses > 0):
            self.paused = self._pauses > 0
            self.hold_readies(not self.paused)

    def hold_readies(self, on: bool = True) -> None:
        """BREADY and RREADY low for random stretches (or always high)."""
        for ch in (self.b, self.r):
            if on:
                ch.set_pause_generator(_holds(self.rng))
            else:
                ch.clear_pause_generator()
                ch.pause = False

    async def _held(self, signal_ready, signal_valid) -> bool:
        """Whether the response waited with its ready low (sampled until it is taken)."""
        dut, held = self.bench.dut, False
        while True:
            await RisingEdge(dut.clk_i)
            if int(signal_valid.value):
                if not int(signal_ready.value):
                    held = True
                else:
                    return held

    async def write(self, off: int, data: int, strb: int) -> int:
        """One write (AW and W in random order, up to 3 cycles apart); its response must be
        the model's (which then follows the write)."""
        dut = self.bench.dut
        async with self.bench.wlock:
            aw = AxiLiteAWTransaction(awaddr=off, awprot=0)
            w = AxiLiteWTransaction(wdata=data & 0xFFFF_FFFF, wstrb=strb)
            first, second = (self.aw, aw), (self.w, w)
            if self.rng.integers(2):
                first, second = second, first
            watch = cocotb.start_soon(self._held(dut.s_axil_bready, dut.s_axil_bvalid))
            await first[0].send(first[1])
            gap = int(self.rng.integers(0, 4))
            if gap:
                await ClockCycles(dut.clk_i, gap)
            await second[0].send(second[1])
            b = await self.b.recv()
            held = await watch
        resp = int(b.bresp)
        want = self.model.write(off, data, strb)
        where = self.model.map.at(off)
        kind = ("unmapped_write" if where is None else
                "reserved_ro_write" if not self.model.present(where) and not where.writable
                else "reserved_write" if not self.model.present(where) else
                "ro_write" if not where.writable else "write")
        assert resp == want, (
            f"write 0x{data:08x} (strb {strb:04b}) at 0x{off:03x}: response "
            f"{regmap.RESP_NAMES[resp]}, the model says {regmap.RESP_NAMES[want]}")
        _sample(self.bench, "axil.traffic.strobe", _strobe_class(strb))
        _sample(self.bench, "axil.traffic.address", kind)
        if held:
            _sample(self.bench, "axil.traffic.ready_held", "bready")
        if self.streaming:
            _sample(self.bench, "axil.traffic.streaming",
                    "w1c_clear" if where is not None and where.name in ("STATUS", "IRQ_STATUS")
                    else "write")
        return resp

    async def read(self, off: int) -> tuple[int, int]:
        """One read; its response must be the model's. (response, data)."""
        dut = self.bench.dut
        async with self.bench.rlock:
            watch = cocotb.start_soon(self._held(dut.s_axil_rready, dut.s_axil_rvalid))
            await self.ar.send(AxiLiteARTransaction(araddr=off, arprot=0))
            r = await self.r.recv()
            held = await watch
        resp, data = int(r.rresp), int(r.rdata)
        want, _ = self.model.read(off)
        where = self.model.map.at(off)
        assert resp == want, (f"read at 0x{off:03x}: response {regmap.RESP_NAMES[resp]}, the "
                              f"model says {regmap.RESP_NAMES[want]}")
        _sample(self.bench, "axil.traffic.address",
                "unmapped_read" if where is None else
                "wo_read" if not where.readable else
                "reserved_read" if not self.model.present(where) else "read")
        if held:
            _sample(self.bench, "axil.traffic.ready_held", "rready")
        if self.streaming:
            _sample(self.bench, "axil.traffic.streaming", "read")
        return resp, data

    # ---- the checks of a read ----------------------------------------------------------------
    def check_read(self, off: int, data: int, live: bool | None = None) -> None:
        """A read's data against the model: exact for the registers software owns; for the
        live ones while streaming (``live``), what can be known (bounds, causes)."""
        m = self.model
        live = self.streaming if live is None else live
        r = m.map.at(off)
        if r is None or not m.present(r) or r.name in _LEVELS:
            if r is None or not m.present(r):
                assert data == 0, f"0x{off:03x} (outside the map or reserved) reads 0x{data:x}"
            return
        if live and r.name == "FFC_STATUS":  # a run may end while pixels stream
            return
        if not live or r.name not in (*COUNTERS, "STATUS", "IRQ_STATUS"):
            _, want = m.read(off)
            mask = 0xFFFF_FFFF
            if r.name == "STATUS":  # a level (the frame in progress) settles once quiet
                mask &= ~r.field("in_frame").mask
            if r.name == "IRQ_STATUS":
                for f in r.fields:
                    if f.name in _UNMODELLED_IRQ:
                        mask &= ~f.mask
            assert (data ^ want) & mask == 0, (
                f"{r.name} reads 0x{data:08x}, the model says 0x{want:08x}")
            return
        for f in r.fields:
            v = (data & f.mask) >> f.lsb
            key = (r.name, f.name)
            if r.name in COUNTERS:
                assert self.last.get(key, 0) <= v <= self.bounds[key], (
                    f"{r.name}.{f.name} reads {v} while streaming: below its last value "
                    f"{self.last.get(key, 0)} or above the frames' total {self.bounds[key]}")
                self.last[key] = v
            elif f.access == "w1c" and v and f.name not in _UNMODELLED_IRQ:
                run = m.present("FFC_STATUS") and (m.get("FFC_STATUS", "busy")
                                                   or m.get("FFC_STATUS", "done"))
                cause = {"error": bool(self.causes), "frame_done": self.frames_possible,
                         "ffc_done": bool(m.get(r.name, f.name) or run)}.get(
                             f.name, f.name in self.causes or bool(m.get(r.name, f.name)))
                assert cause, f"{r.name}.{f.name} reads 1 with no cause in the stimulus"

    # ---- sequences -------------------------------------------------------------------------------
    def _value(self, off: int) -> int:
        v = int(self.rng.integers(0, 2**32, dtype=np.uint64))
        r = self.model.map.at(off)
        if r is not None and r.name == "FFC_CTRL":  # no FFC run from random data
            v &= ~r.field("start").mask
        if r is not None and r.name == "FRAME_SIZE" and self.rng.integers(3):
            # mostly legal sizes (a write of a random word is almost always refused)
            v = (int(self.rng.integers(1, self.bench.cfg.max_width + 1))
                 | int(self.rng.integers(1, self.bench.cfg.max_height + 1)) << 16)
        return v

    async def quiet_ops(self, n: int) -> None:
        """``n`` random accesses to every kind of address with no pixel streaming: every read
        exact (STATUS.pending follows the shadowed writes)."""
        # Every address once (every register, some offsets outside the map) with a random
        # byte strobe (the four strobe classes first), each read back, then ``n`` accesses
        # at random.
        strobes = [0xF, 0x5, 0x0, 0x3]
        for k, off in enumerate([*self.offsets, *self.holes]):
            strb = strobes[k] if k < len(strobes) else int(self.rng.integers(0, 16))
            await self.write(off, self._value(off), strb)
            _, data = await self.read(off)
            self.check_read(off, data)
        await self.size_strobes()
        await self.overlapped(4)
        for _ in range(n):
            off = int(self.rng.choice(self.offsets + self.holes))
            if self.rng.integers(3):
                await self.write(off, self._value(off), int(self.rng.integers(0, 16)))
            _, data = await self.read(off)
            self.check_read(off, data)
            if self.rng.integers(4) == 0:
                _, data = await self.read(self.model.map["STATUS"].offset)
                self.check_read(self.model.map["STATUS"].offset, data)

    async def size_strobes(self) -> None:
        """FRAME_SIZE's byte lanes one by one: for each of the sixteen strobes, a write whose
        written lanes carry a legal size (each field's unwritten lanes those it holds) and
        whose unwritten lanes carry poison (each byte with its top bit set: taken, it would
        put a field above FRAME_MAX), which must be answered OKAY and read back as the
        merged size; then a write whose written lanes carry the top bit of a field's high
        byte (or a zero field), which the value check must refuse (SLVERR, size kept). The
        random traffic's FRAME_SIZE data is a legal size (no bit in a field's high byte) or
        a random word (refused whatever the strobes): neither tells a strobe bit that is
        taken from an unwritten lane, or dropped from a written one (the generated block's
        bit enables). Every read exact (no pixel streams); a random draw of its own (a
        spawned generator: the rest of the traffic draws as before)."""
        m = self.model
        r = m.map["FRAME_SIZE"]
        off = r.offset
        rng = self.rng.spawn(1)[0]
        fields = [(r.field("width"), self.bench.cfg.max_width),
                  (r.field("height"), self.bench.cfg.max_height)]
        for strb in range(16):
            lanes = sum(0xFF << (8 * i) for i in range(4) if strb >> i & 1)
            old = m.get("FRAME_SIZE")
            data = 0
            for f, top in fields:
                # A legal value of the field equal to the held one in its unwritten lanes.
                keep = (lanes & f.mask) ^ f.mask
                vals = np.arange(1, top + 1, dtype=np.int64) << f.lsb
                vals = vals[(vals & keep) == (old & keep)]
                data |= int(rng.choice(vals))
            poison = sum((0x80 | int(rng.integers(0, 0x80))) << (8 * i)
                         for i in range(4) if not strb >> i & 1)
            data = (data & lanes) | poison
            resp = await self.write(off, data, strb)
            if resp == regmap.OKAY:
                for i in range(4):
                    if not strb >> i & 1 and (data ^ old) >> (8 * i) & 0xFF:
                        _sample(self.bench, "axil.traffic.size_strobe", f"ignored_lane{i}")
            _, got = await self.read(off)
            self.check_read(off, got)
            if strb == 0:
                continue
            # Refused: the top bit of each written high lane set, low lanes 0.
            bad = 0
            for f, _ in fields:
                high = 8 * ((f.lsb + f.bits) // 8 - 1)
                if lanes >> high & 0xFF:
                    bad |= (0x80 | int(rng.integers(0, 0x80))) << high
            data = bad | int(rng.integers(0, 2**32, dtype=np.uint64)) & ~lanes
            resp = await self.write(off, data, strb)
            if resp != regmap.OKAY:
                _sample(self.bench, "axil.traffic.size_strobe", "refused")
            _, got = await self.read(off)
            self.check_read(off, got)

    async def overlapped(self, n: int) -> None:
        """``n`` times a write and a read issued in the same cycle: the write to IRQ_ENABLE
        (no other register's read depends on it), the read of any other offset. The register
        file takes one at a time; each response must be the model's, the read exact."""
        m = self.model
        enable = m.map["IRQ_ENABLE"].offset
        others = [o for o in self.offsets + self.holes if o != enable]
        for _ in range(n):
            off = int(self.rng.choice(others))
            value = self._value(enable)
            wr = cocotb.start_soon(self.write(enable, value, 0xF))
            rd = cocotb.start_soon(self.read(off))
            await wr
            _, data = await rd
            self.check_read(off, data)
            _, data = await self.read(enable)
            self.check_read(enable, data)
            _sample(self.bench, "axil.traffic.overlap", "write_and_read")

    async def restore(self, h: int | None = None, w: int | None = None) -> None:
        """Every shadowed register back to its reset value (the frame size to h x w when
        given), so that the frames that follow take known settings."""
        m = self.model
        for r in m.map.registers:
            if r.shadowed and m.present(r):
                v = m.reset_value(r)
                if r.name == "FRAME_SIZE" and h is not None:
                    v = w | (h << 16)
                await self.write(r.offset, v, 0xF)

    async def stream_ops(self, safe: tuple[str, ...], stop: list[bool]) -> None:
        """Random accesses while pixels stream (until ``stop[0]``): reads anywhere, writes to
        the registers in ``safe`` (W1C and enables no frame takes), to read-only registers,
        to reserved ones and outside the map."""
        m = self.model
        ro = [r.offset for r in m.map.registers if m.present(r) and not r.writable]
        reserved = [r.offset for r in m.map.registers if not m.present(r)]
        writes = [m.map[n].offset for n in safe] + ro + reserved[:4] + self.holes[:2]
        # A W1C clear of STATUS and a read first (the stream has just begun), then at random.
        status = m.map["STATUS"].offset
        await self.write(status, self._value(status), 0xF)
        _, data = await self.read(status)
        self.check_read(status, data)
        while not stop[0]:
            if self.paused:
                await RisingEdge(self.bench.dut.clk_i)
                continue
            if self.rng.integers(2):
                off = int(self.rng.choice(writes))
                await self.write(off, self._value(off), int(self.rng.integers(0, 16)))
            else:
                off = int(self.rng.choice(self.offsets + self.holes))
                _, data = await self.read(off)
                self.check_read(off, data)

    def expect_stream(self, results) -> None:
        """The bounds of the live registers over frames about to stream (the framer model's
        ``results``, added to what the model holds now)."""
        m = self.model
        total = {k: sum(r.counts[k] for r in results) for k in results[0].counts}
        frames = sum(len(r.frames) for r in results)
        pixels = sum(f.raw.size for r in results for f in r.frames)
        add = {("FRAMES_IN", "count"): total["frames_in"], ("FRAMES_OUT", "count"): frames,
               ("PIXELS_IN", "count"): total["beats"], ("PIXELS_OUT", "count"): pixels,
               ("DROPPED", "count"): total["dropped"], ("PADDED", "count"): total["padded"]}
        for reg, kind in (("SOF_ERRORS", "sof"), ("EOL_ERRORS", "eol"),
                          ("COEF_ERRORS", "coef")):
            for when in ("early", "late"):
                add[(reg, when)] = total[f"{kind}_{when}"]
        for (reg, f), v in add.items():
            now = m.get(reg, f)
            self.bounds[(reg, f)] = now + v
            self.last[(reg, f)] = now
        self.causes = {ev for ev in regmap_events() if total[ev]} | {
            f.name for f in m.map["STATUS"].fields if f.access == "w1c" and m.get("STATUS", f.name)}
        self.frames_possible = frames > 0 or bool(m.get("IRQ_STATUS", "frame_done"))

    async def settle(self, results) -> None:
        """After the stream: the counters exact (the frames' totals), the W1C bits set only
        for causes the stimulus had; then cleared and read 0; the model follows."""
        m = self.model
        for (reg, f), v in self.bounds.items():
            m.set_live(reg, f, v & ((1 << m.map[reg].field(f).bits) - 1))
        m.frame_start()
        for reg in COUNTERS:
            off = m.map[reg].offset
            _, data = await self.read(off)
            _, want = m.read(off)
            assert data == want, f"{reg} reads 0x{data:08x} once quiet, expected 0x{want:08x}"
        for reg in ("STATUS", "IRQ_STATUS"):
            off = m.map[reg].offset
            _, data = await self.read(off)
            self.check_read(off, data, live=True)  # a bit only with a cause
            for f in m.map[reg].fields:
                if f.access == "w1c":
                    m.set_live(reg, f.name, (data & f.mask) >> f.lsb)
            await self.write(off, 0xFFFF_FFFF, 0xF)
            _, data = await self.read(off)
            _, want = m.read(off)
            assert data == want, f"{reg} reads 0x{data:08x} after the W1C, expected 0x{want:08x}"

    async def pending(self) -> None:
        """After a frame start (STATUS.pending 0): a write to the map's last shadowed
        register the configuration has (the method's last one) raises STATUS.pending."""
        m = self.model
        status = m.map["STATUS"].offset
        last = [r for r in m.map.registers
                if r.shadowed and m.present(r) and m.field_mask(r, ("rw",))][-1]
        _, data = await self.read(status)
        self.check_read(status, data)
        await self.write(last.offset, m.get(last.name), 0xF)
        _, data = await self.read(status)
        self.check_read(status, data)
        assert m.get("STATUS", "pending"), f"{last.name} is not shadowed in the model"


def regmap_events() -> tuple[str, ...]:
    from irnuc.nuc_fixed.axis import EVENTS

    return tuple(EVENTS)


async def register_traffic(bench, frames, safe: tuple[str, ...] = ("STATUS", "IRQ_STATUS",
                                                                   "IRQ_ENABLE")) -> None:
    """The whole sequence on a fresh bench (right after reset): a frame at the reset size
    with traffic (where it has at most RESET_SIZE_PIXELS pixels), random accesses with no
    stream, the shadowed registers restored, then a small frame streamed with random traffic
    (``frames(bench, h, w) -> (video, coef)``), the live registers checked once quiet, and
    STATUS.pending after a shadowed write."""
    t = Traffic(bench)
    cfg = bench.cfg
    t.hold_readies(True)
    if cfg.max_width * cfg.max_height <= RESET_SIZE_PIXELS:
        await _streamed(t, *frames(bench, cfg.max_height, cfg.max_width), safe,
                        label="reset size", coef_idle="none")
        _sample(bench, "axil.traffic.reset_size", "frame")
    await t.quiet_ops(60)
    h, w = min(4, cfg.max_height), min(7, cfg.max_width)
    await t.restore(h, w)
    await _streamed(t, *frames(bench, h, w), safe, label="register traffic",
                    coef_idle="bursty")
    await t.pending()
    t.hold_readies(False)


async def _streamed(t: Traffic, video, coef, safe: tuple[str, ...], label: str,
                    coef_idle: str) -> None:
    """Stream the frame (three beats before it without start of frame) with random traffic
    beside it; the live registers settled once quiet."""
    bench = t.bench
    video = _late(video)
    results = [_framed(bench, video, coef)]
    t.expect_stream(results)
    t.streaming, stop = True, [False]
    task = cocotb.start_soon(t.stream_ops(safe, stop))
    await bench.run(video, coef, [bench.settings()], idle="random", coef_idle=coef_idle,
                    bp="random", label=label)
    stop[0] = True
    await task
    t.streaming = False
    await t.settle(results)


def _late(video):
    """Three beats without start of frame before the video (dropped: STATUS.sof_late, the
    framing-error event the stream's W1C clears race)."""
    data, sof, eol = (np.asarray(v) for v in video)
    return (np.concatenate([[1, 2, 3], data]), np.concatenate([[0, 0, 0], sof]),
            np.concatenate([[0, 0, 1], eol]))


def _framed(bench, video, coef):
    from irnuc.nuc_fixed.axis import axis_framer

    return axis_framer(*video, *coef, [bench.settings()], bench.env.golden)


__all__ = ["Traffic", "register_traffic"]
