"""Per-cycle Python driver benchmark: one frame from an .npz file through nuc_dpc_top.

Driven by ``benchmarks/bench_cosim.py``: env ``IRNUC_BENCH_IN`` (npz with raw, words,
expected) and ``IRNUC_BENCH_OUT`` (JSON written here: pixels, seconds, mismatches).

The driver is the lean form of ``tb_lib.run_streams``: one coroutine, one
``await RisingEdge`` per cycle, two valid/ready sources (pixels with their markers,
coefficient words) and a sink that takes every valid output (ready = 1), the stimulus
converted to Python ints beforehand, and the outputs collected in lists and compared with
the golden model in numpy at the end (every code, sof and eol, bit for bit). Port access
is cocotb's public API only (``handle.value``); the build makes only the top module's
signals visible to VPI (``cosim._cocotb_adapter``), not every signal.

One Python wake-up per cycle caps any such driver near 250 k cycles/s (an ``await`` alone
costs about 4 us); it is the reference of the batched driver ``tb_batch.py``, which wakes
once per window of cycles and is the benchmark's ``per_cycle`` figure.
"""

from __future__ import annotations

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


def reader(handle: SimHandleBase) -> Callable[[], int]:
    """The unsigned value of a port, as a bound callable for the cycle loop (``handle.value``)."""
    return lambda: int(handle.value)  # Logic and LogicArray both convert


def writer(handle: SimHandleBase) -> Callable[[int], None]:
    """Deposit an unsigned int on a port, as a bound callable (``handle.value = v``)."""
    def write(v: int) -> None:
        handle.value = v
    return write


async def stream_lean(dut: SimHandleBase, raw: np.ndarray, words: np.ndarray
                      ) -> tuple[np.ndarray, int, int]:
    """Stream one (H, W) frame through ``nuc_dpc_top`` at full rate.

    Returns (outputs as an (N, 3) int64 array of code, sof, eol; cycles; first output
    cycle). Raises AssertionError on a timeout.
    """
    h, w = raw.shape
    n = raw.size
    set_pix, set_coef = writer(dut.s_pix_data_i), writer(dut.s_coef_data_i)
    pix = raw.ravel().tolist()
    coef = words.ravel().tolist()
    pos = np.arange(n)
    marks = (((pos == 0).astype(np.int64) << 1) | (pos % w == w - 1)).tolist()  # sof, eol
    dut.frame_width_i.value = w
    dut.frame_height_i.value = h
    set_sof, set_eol = writer(dut.s_pix_sof_i), writer(dut.s_pix_eol_i)
    set_pv, set_cv = writer(dut.s_pix_valid_i), writer(dut.s_coef_valid_i)
    pix_ready, coef_ready = reader(dut.s_pix_ready_o), reader(dut.s_coef_ready_o)
    out_valid, out_data = reader(dut.m_pix_valid_o), reader(dut.m_pix_data_o)
    out_sof, out_eol = reader(dut.m_pix_sof_o), reader(dut.m_pix_eol_o)
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
    t0 = time.perf_counter()
    got, cycles, first = await stream_lean(dut, raw, words)
    t1 = time.perf_counter()
    w = raw.shape[1]
    pos = np.arange(raw.size)
    bad = ((got[:, 0] != expected.ravel()) | (got[:, 1] != (pos == 0))
           | (got[:, 2] != (pos % w == w - 1)))
    mism = int(bad.sum())
    t2 = time.perf_counter()
    finish(dut, cfg, {"pixels": int(raw.size), "cycles": cycles, "first_out_cycle": first,
                      "sim_seconds": t1 - t0, "check_seconds": t2 - t1, "mismatches": mism},
           raw, words, expected, got)


def finish(dut: SimHandleBase, cfg: Any, info: dict[str, Any], raw: np.ndarray,
           words: np.ndarray, expected: np.ndarray, got: np.ndarray) -> None:
    """Write the run's figures to ``$IRNUC_BENCH_OUT`` (whole, by rename), then fail with
    the scoreboard's triage lines when an output differs (``info["mismatches"]``)."""
    out = Path(os.environ["IRNUC_BENCH_OUT"])
    tmp = out.with_suffix(".tmp")
    tmp.write_text(json.dumps(info))
    os.replace(tmp, out)
    if info["mismatches"]:
        frame = tb_lib.Frame(raw=raw, words=words, expected=expected)
        rows = [tuple(int(v) for v in r) for r in got]
        tb_lib.assert_no_mismatch(tb_lib.check_frames([frame], rows, cfg), dut._log)
    assert int(dut.frame_err_o.value) == 0, "frame_err_o set on a well-formed stream"
