"""Batched per-cycle driver: one frame through nuc_dpc_top inside the ``nuc_dpc_batch``
transactor (``cosim/hdl/nuc_dpc_batch.sv``), Python waking once per window of
``Batch`` cycles instead of once per cycle.

Same interface as ``tb_bench.py`` (env ``IRNUC_BENCH_IN``: npz with raw, words, expected;
``IRNUC_BENCH_OUT``: JSON result), plus ``IRNUC_BATCH_PAUSE`` = ``"pix,coef,sink"``, the
percent of cycles each input source pauses and the sink back-pressures (default 0,0,0),
drawn from ``IRNUC_SEED``. The handshakes stay cycle exact: each window's command carries
per-cycle pause masks, and the transactor's sources hold valid and data until ready.

Per window Python reads one response word (outputs taken, their data and markers, items
consumed) and writes one command word (up to ``Batch`` pixel items and coefficient words
pushed into the transactor's FIFOs, the pause masks); the clock is cocotb's GPI clock and
the wake-up a single ``Timer`` of ``Batch`` periods, mid-cycle so no edge ordering matters.
Every output code, sof and eol is compared with the golden model in numpy at the end.
Port access is cocotb's public API only (``handle.value``).
"""

from __future__ import annotations

import os
import time

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.handle import SimHandleBase
from cocotb.triggers import RisingEdge, Timer

from irnuc.cocotb_tests import tb_bench, tb_lib

#: Offset of the testbench's wake-ups after a rising edge (ns): mid-cycle.
_PHASE_NS = 3


def pack_chunks(values: np.ndarray, bits: int, k: int) -> list[int]:
    """``values`` (unsigned, < 2^bits, bits <= 64) in chunks of ``k``: item i of a chunk at
    bits [i*bits, (i+1)*bits) of one Python int (the last chunk may be short)."""
    n = values.size
    nch = -(-n // k)
    v = np.zeros(nch * k, dtype=np.uint64)
    v[:n] = values.astype(np.uint64).ravel()
    bit = ((v.reshape(nch, k, 1) >> np.arange(bits, dtype=np.uint64)) & np.uint64(1))
    flat = bit.astype(np.uint8).reshape(nch, k * bits)
    packed = np.packbits(flat, axis=1, bitorder="little")
    return [int.from_bytes(row.tobytes(), "little") for row in packed]


def unpack_items(words: list[int], counts: list[int], bits: int, k: int) -> np.ndarray:
    """Inverse of :func:`pack_chunks` for the response words: the first ``counts[j]``
    items of ``words[j]``, concatenated (int64)."""
    if not words:
        return np.zeros(0, dtype=np.int64)
    nbytes = -(-k * bits // 8)
    buf = b"".join(w.to_bytes(nbytes, "little") for w in words)
    raw = np.frombuffer(buf, dtype=np.uint8).reshape(len(words), nbytes)
    flat = np.unpackbits(raw, axis=1, bitorder="little")[:, :k * bits]
    vals = flat.reshape(len(words), k, bits).astype(np.int64) @ (1 << np.arange(bits,
                                                                               dtype=np.int64))
    keep = np.arange(k)[None, :] < np.asarray(counts)[:, None]
    return vals[keep]


def pause_percent() -> tuple[int, int, int]:
    text = os.environ.get("IRNUC_BATCH_PAUSE", "0,0,0")
    p = tuple(int(x) for x in text.split(","))
    if len(p) != 3 or not all(0 <= x <= 99 for x in p):
        raise ValueError(f"IRNUC_BATCH_PAUSE = {text!r}: expected three percentages 0..99")
    return p  # type: ignore[return-value]


async def stream_batched(dut: SimHandleBase, raw: np.ndarray, words: np.ndarray,
                         adc_bits: int, word_bits: int, out_bits: int,
                         pauses: tuple[int, int, int] = (0, 0, 0), seed: int = 1
                         ) -> tuple[np.ndarray, int]:
    """Stream one (H, W) frame through the transactor; ``dut`` is ``nuc_dpc_batch``.

    Returns (outputs as an (N, 3) int64 array of code, sof, eol; windows run). Raises
    AssertionError on a timeout or a transactor error (late command, FIFO overflow,
    response out of step).
    """
    h, w = raw.shape
    n = raw.size
    k = int(dut.batch_o.value)
    cb = k.bit_length()  # $clog2(k + 1) for a power of two
    depth = 4 * k        # the transactor's FIFO depth
    cmask = (1 << cb) - 1
    pix_off = 1 + 2 * cb + 3 * k
    coef_off = pix_off + k * (adc_bits + 2)
    rsp_items = 3 + 3 * cb
    # Stimulus as K-item chunks: raw code with {sof, eol} above it, and the words.
    pos = np.arange(n)
    items = (raw.ravel().astype(np.int64) | ((pos % w == w - 1).astype(np.int64) << adc_bits)
             | ((pos == 0).astype(np.int64) << (adc_bits + 1)))
    pix_chunks = [c << pix_off for c in pack_chunks(items, adc_bits + 2, k)]
    coef_chunks = [c << coef_off for c in pack_chunks(words.ravel(), word_bits, k)]
    lens = [min(k, n - j * k) for j in range(len(pix_chunks))]
    nch = len(pix_chunks)
    rng = np.random.default_rng(seed)
    bitw = 1 << np.arange(k, dtype=object)

    def mask(pct: int) -> int:
        return int((rng.random(k) * 100 < pct) @ bitw) if pct else 0

    dut.frame_width_i.value = w
    dut.frame_height_i.value = h
    cmd = dut.cmd_i
    rsp = dut.rsp_o
    period = Timer(k * tb_lib.CLK_PERIOD_NS, unit="ns")
    got: list[int] = []
    counts: list[int] = []
    tag = jp = jc = pushed_p = pushed_c = taken_p = taken_c = out_n = windows = 0
    limit = 20 * (n + 100) // k + 1000
    await Timer(_PHASE_NS, unit="ns")
    while True:
        if windows:
            r = int(rsp.value)
            if (r & 1) != tag or r & 6:
                raise AssertionError(f"transactor out of step in window {windows}: tag "
                                     f"{r & 1} (expected {tag}), late {r >> 1 & 1}, "
                                     f"overflow {r >> 2 & 1}")
            cnt = (r >> 3) & cmask
            taken_p += (r >> (3 + cb)) & cmask
            taken_c += (r >> (3 + 2 * cb)) & cmask
            if cnt:
                got.append(r >> rsp_items)
                counts.append(cnt)
                out_n += cnt
                if out_n >= n:
                    break
            if windows > limit:
                raise AssertionError(f"timeout: {out_n} of {n} outputs after {windows} "
                                     f"windows of {k} cycles")
        tag ^= 1
        c = tag
        # Push a chunk when it surely fits (taken_* lags by one window: conservative).
        if jp < nch and pushed_p - taken_p <= depth - k:
            c |= lens[jp] << 1 | pix_chunks[jp]
            pushed_p += lens[jp]
            jp += 1
        if jc < nch and pushed_c - taken_c <= depth - k:
            c |= lens[jc] << (1 + cb) | coef_chunks[jc]
            pushed_c += lens[jc]
            jc += 1
        if pauses[0] or pauses[1] or pauses[2]:
            c |= ((mask(pauses[0]) | mask(pauses[1]) << k | mask(pauses[2]) << 2 * k)
                  << (1 + 2 * cb))
        cmd.value = c
        windows += 1
        await period
    vals = unpack_items(got, counts, out_bits + 2, k)
    out = np.stack([vals & ((1 << out_bits) - 1), vals >> (out_bits + 1) & 1,
                    vals >> out_bits & 1], axis=1)
    return out, windows


@cocotb.test()
async def vga_frame(dut) -> None:
    data = np.load(os.environ["IRNUC_BENCH_IN"])
    raw, words, expected = data["raw"], data["words"], data["expected"]
    cfg = tb_lib.config_from_env()
    word_bits = cfg.word_bits
    dut.cmd_i.value = 0
    Clock(dut.clk_i, tb_lib.CLK_PERIOD_NS, unit="ns", impl="gpi").start()
    await tb_lib.reset(dut)
    await RisingEdge(dut.clk_i)
    t0 = time.perf_counter()
    got, windows = await stream_batched(dut, raw, words, cfg.adc_bits, word_bits,
                                        cfg.out_bits, pause_percent(), tb_lib.seed_from_env())
    t1 = time.perf_counter()
    w = raw.shape[1]
    pos = np.arange(raw.size)
    n_got = min(len(got), raw.size)
    bad = ((got[:n_got, 0] != expected.ravel()[:n_got]) | (got[:n_got, 1] != (pos[:n_got] == 0))
           | (got[:n_got, 2] != (pos[:n_got] % w == w - 1)))
    mism = int(bad.sum()) + abs(len(got) - raw.size)
    t2 = time.perf_counter()
    k = int(dut.batch_o.value)
    tb_bench.finish(dut, cfg, {"pixels": int(raw.size), "outputs": len(got), "batch": k,
                               "windows": windows, "cycles": windows * k,
                               "sim_seconds": t1 - t0, "check_seconds": t2 - t1,
                               "mismatches": mism}, raw, words, expected, got)


@cocotb.test()
async def transactor_flags(dut) -> None:
    """The transactor's own errors are flagged, so a driver that falls behind or overfills
    cannot pass silently: a window without a new command sets ``late``, a push beyond the
    FIFO's room sets ``overflow``; both are sticky and show in the next response."""
    cfg = tb_lib.config_from_env()
    k = int(dut.batch_o.value)
    cb = k.bit_length()
    pix_off = 1 + 2 * cb + 3 * k
    dut.cmd_i.value = 0
    dut.frame_width_i.value = 4
    dut.frame_height_i.value = 4
    Clock(dut.clk_i, tb_lib.CLK_PERIOD_NS, unit="ns", impl="gpi").start()
    await tb_lib.reset(dut)
    await RisingEdge(dut.clk_i)
    period = Timer(k * tb_lib.CLK_PERIOD_NS, unit="ns")
    await Timer(_PHASE_NS, unit="ns")

    def flags() -> tuple[int, int]:
        r = int(dut.rsp_o.value)
        return r >> 1 & 1, r >> 2 & 1

    dut.cmd_i.value = 1  # tag 1, nothing pushed
    await period
    assert flags() == (0, 0), "flags set on a well-behaved window"
    await period  # no new command: the window runs out
    await period
    dut.cmd_i.value = 0  # tag 0: taken, its response carries the flags
    await period
    assert flags()[0] == 1, "late not flagged after a window without a command"
    # Overflow: pixel chunks without coefficient words (the DUT takes a pixel only with
    # its word), more than the FIFO (4 x Batch) and the DUT's input registers hold.
    await tb_lib.reset(dut)
    await RisingEdge(dut.clk_i)
    await Timer(_PHASE_NS, unit="ns")
    chunk = sum(((i % (1 << cfg.adc_bits)) << ((cfg.adc_bits + 2) * i)) for i in range(k))
    tag = 0
    seen = (0, 0)
    for _ in range(7):
        tag ^= 1
        dut.cmd_i.value = tag | (k << 1) | (chunk << pix_off)
        await period
        seen = flags()
    assert seen[1] == 1, "overflow not flagged after pushing 7 x Batch items into 4 x Batch"
