"""Per-cycle Python driver benchmark: one frame from an .npz file through nuc_dpc_top.

Driven by ``benchmarks/bench_cosim.py``: env ``IRNUC_BENCH_IN`` (npz with raw, words,
expected) and ``IRNUC_BENCH_OUT`` (JSON written here: pixels, seconds, mismatches).

The driver is the lean form of ``tb_lib.run_streams``: one coroutine, one
``await RisingEdge`` per cycle, two valid/ready sources (pixels with their markers,
coefficient words) and a sink that takes every valid output (ready = 1), the stimulus
converted to Python ints beforehand, and the outputs collected in lists and compared with
the golden model in numpy at the end (every code, sof and eol, bit for bit). Port access
goes through :func:`fast_reader` / :func:`fast_writer`.
"""

from __future__ import annotations

import functools
import json
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import cocotb
import numpy as np
from cocotb.handle import SimHandleBase
from cocotb.triggers import RisingEdge

from irnuc.cocotb_tests import tb_lib


def _gpi(handle: SimHandleBase):
    """The GPI object behind a handle, when the cheap direct path may be used.

    cocotb 2.x writes a deposit through to the simulator at once when
    ``COCOTB_TRUST_INERTIAL_WRITES=1`` (the Verilator runner sets it); a direct GPI call
    is then the same write without the Python conversion layers (about 1-2 us saved per
    access). Without that setting, or on another cocotb, or with
    ``IRNUC_BENCH_PUBLIC_API=1`` (to measure the difference), ``None``: use the public API.
    """
    gpi = getattr(handle, "_handle", None)
    if (os.environ.get("COCOTB_TRUST_INERTIAL_WRITES") != "1" or gpi is None
            or os.environ.get("IRNUC_BENCH_PUBLIC_API") == "1"):
        return None
    if not all(hasattr(gpi, f) for f in ("get_signal_val_long", "set_signal_val_int",
                                         "set_signal_val_binstr")):
        return None
    return gpi


def fast_reader(handle: SimHandleBase) -> Callable[[], int]:
    """A function returning the unsigned value of a port.

    The GPI integer path is signed 32-bit: used up to 31 bits, the public API above.
    """
    gpi = _gpi(handle)
    if gpi is not None and len(handle) <= 31:
        return gpi.get_signal_val_long
    return lambda: int(handle.value)  # Logic and LogicArray both convert


def port_writer(handle: SimHandleBase) -> tuple[Callable[[Any], None], Callable[[int], Any]]:
    """``(write, encode)``: ``write(encode(v))`` deposits the unsigned int ``v`` on a port.

    Stimulus lists can be encoded once before the loop (a binary string above 31 bits on
    the fast path, where the GPI integer call is signed 32-bit).
    """
    gpi = _gpi(handle)
    if gpi is None:
        def write(v: int) -> None:
            handle.value = v
        return write, int
    if len(handle) <= 31:
        return functools.partial(gpi.set_signal_val_int, 0), int  # 0: GPI deposit
    fmt = f"0{len(handle)}b"
    return functools.partial(gpi.set_signal_val_binstr, 0), lambda v: format(v, fmt)


def fast_writer(handle: SimHandleBase) -> Callable[[int], None]:
    """A function depositing an unsigned int on a port."""
    write, encode = port_writer(handle)
    return write if encode is int else (lambda v: write(encode(v)))


async def check_fast_access(dut: SimHandleBase, values: dict[str, int]) -> None:
    """The fast path writes and reads what the public API writes and reads.

    Writes are inertial (seen after the current evaluation), hence one edge in between.
    """
    edge = RisingEdge(dut.clk_i)
    for name, v in values.items():
        fast_writer(getattr(dut, name))(v)
    await edge
    for name, v in values.items():
        pub = int(getattr(dut, name).value)
        assert pub == v, f"{name}: fast write of {v}, public read {pub}"
        getattr(dut, name).value = v ^ 1
    await edge
    for name, v in values.items():
        got = fast_reader(getattr(dut, name))()
        assert got == v ^ 1, f"{name}: public write of {v ^ 1}, fast read {got}"


async def stream_lean(dut: SimHandleBase, raw: np.ndarray, words: np.ndarray
                      ) -> tuple[np.ndarray, int, int]:
    """Stream one (H, W) frame through ``nuc_dpc_top`` at full rate.

    Returns (outputs as an (N, 3) int64 array of code, sof, eol; cycles; first output
    cycle). Raises AssertionError on a timeout.
    """
    h, w = raw.shape
    n = raw.size
    set_pix, enc_pix = port_writer(dut.s_pix_data_i)
    set_coef, enc_coef = port_writer(dut.s_coef_data_i)
    pix = raw.ravel().tolist()
    coef = words.ravel().tolist()
    if enc_pix is not int:
        pix = [enc_pix(v) for v in pix]
    if enc_coef is not int:
        coef = [enc_coef(v) for v in coef]
    pos = np.arange(n)
    marks = (((pos == 0).astype(np.int64) << 1) | (pos % w == w - 1)).tolist()  # sof, eol
    dut.frame_width_i.value = w
    dut.frame_height_i.value = h
    set_sof, set_eol = fast_writer(dut.s_pix_sof_i), fast_writer(dut.s_pix_eol_i)
    set_pv, set_cv = fast_writer(dut.s_pix_valid_i), fast_writer(dut.s_coef_valid_i)
    pix_ready, coef_ready = fast_reader(dut.s_pix_ready_o), fast_reader(dut.s_coef_ready_o)
    out_valid, out_data = fast_reader(dut.m_pix_valid_o), fast_reader(dut.m_pix_data_o)
    out_sof, out_eol = fast_reader(dut.m_pix_sof_o), fast_reader(dut.m_pix_eol_o)
    dut.m_pix_ready_i.value = 1
    got_d: list[int] = []
    got_s: list[int] = []
    got_e: list[int] = []
    add_d, add_s, add_e = got_d.append, got_s.append, got_e.append
    edge = RisingEdge(dut.clk_i)
    limit = 20 * (n + 100) + 50_000
    # Drive pixel 0 and word 0; markers are written only when they change.
    set_pix(pix[0])
    set_coef(coef[0])
    mark = marks[0]
    set_sof(mark >> 1)
    set_eol(mark & 1)
    set_pv(1)
    set_cv(1)
    pi = ci = cycle = k = 0
    first = -1
    while k < n:
        await edge
        cycle += 1
        # Transfers at this edge (valid is high while items remain).
        if pi < n and pix_ready():
            pi += 1
            if pi < n:
                set_pix(pix[pi])
                m = marks[pi]
                if m != mark:
                    set_sof(m >> 1)
                    set_eol(m & 1)
                    mark = m
            else:
                set_pv(0)
        if ci < n and coef_ready():
            ci += 1
            if ci < n:
                set_coef(coef[ci])
            else:
                set_cv(0)
        if out_valid():
            if first < 0:
                first = cycle
            add_d(out_data())
            add_s(out_sof())
            add_e(out_eol())
            k += 1
        elif cycle > limit:
            raise AssertionError(f"timeout: {len(got_d)} of {n} outputs after {cycle} cycles")
    dut.m_pix_ready_i.value = 0
    return np.array([got_d, got_s, got_e], dtype=np.int64).T, cycle, first


@cocotb.test()
async def vga_frame(dut) -> None:
    data = np.load(os.environ["IRNUC_BENCH_IN"])
    raw, words, expected = data["raw"], data["words"], data["expected"]
    cfg = tb_lib.config_from_env()
    dut.s_pix_valid_i.value = 0
    dut.s_coef_valid_i.value = 0
    dut.m_pix_ready_i.value = 0
    await tb_lib.start_clock_and_reset(dut)
    await check_fast_access(dut, {"s_pix_data_i": (1 << cfg.adc_bits) - 1,
                                  "s_coef_data_i": (1 << cfg.word_bits) - 2,
                                  "s_pix_sof_i": 1})
    t0 = time.perf_counter()
    got, cycles, first = await stream_lean(dut, raw, words)
    t1 = time.perf_counter()
    w = raw.shape[1]
    pos = np.arange(raw.size)
    bad = ((got[:, 0] != expected.ravel()) | (got[:, 1] != (pos == 0))
           | (got[:, 2] != (pos % w == w - 1)))
    mism = int(bad.sum())
    t2 = time.perf_counter()
    out = Path(os.environ["IRNUC_BENCH_OUT"])
    tmp = out.with_suffix(".tmp")
    tmp.write_text(json.dumps({"pixels": int(raw.size), "cycles": cycles,
                               "first_out_cycle": first, "sim_seconds": t1 - t0,
                               "check_seconds": t2 - t1, "mismatches": mism}))
    os.replace(tmp, out)
    if mism:
        frame = tb_lib.Frame(raw=raw, words=words, expected=expected)
        rows = [tuple(int(v) for v in r) for r in got]
        tb_lib.assert_no_mismatch(tb_lib.check_frames([frame], rows, cfg), dut._log)
    assert int(dut.frame_err_o.value) == 0, "frame_err_o set on a well-formed stream"
