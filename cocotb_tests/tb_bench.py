"""Per-cycle Python driver benchmark: one frame from an .npz file through nuc_dpc_top.

Driven by ``benchmarks/bench_cosim.py``: env ``IRNUC_BENCH_IN`` (npz with raw, words,
expected) and ``IRNUC_BENCH_OUT`` (JSON written here: pixels, seconds, mismatches).

The driver is the testbenches' own engine (``streams.run_streams``: one coroutine, one
``await RisingEdge`` per cycle, the pixel and coefficient sources and a sink found by
prefix), at full rate; the outputs are compared with the golden model in numpy at the end
(every code, sof and eol, bit for bit). Port access is cocotb's public API only; the build
makes only the top module's signals visible to VPI (``cosim._cocotb_adapter``).

One Python wake-up per cycle caps any such driver near 250 k cycles/s (an ``await`` alone
costs about 4 us); it is the reference of the batched driver ``tb_batch.py``, which wakes
once per window of cycles and is the benchmark's ``per_cycle`` figure.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Any

import cocotb
import numpy as np
from cocotb.handle import SimHandleBase

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.streams import run_streams
from irnuc.cosim.scoreboard import TopScoreboard


async def stream_engine(dut: SimHandleBase, raw: np.ndarray, words: np.ndarray
                        ) -> tuple[np.ndarray, int, int]:
    """Stream one (H, W) frame through ``nuc_dpc_top`` at full rate with the testbenches'
    engine (:func:`~irnuc.cocotb_tests.streams.run_streams`, no pause, no backpressure).

    Returns (outputs as an (N, 3) int64 array of code, sof, eol; cycles; first output
    cycle). Raises AssertionError on a timeout.
    """
    frame = tb_lib.Frame(raw=raw, words=words)
    pix, coef = tb_lib.top_sources(dut, [frame])
    sink = tb_lib.top_sink(dut, expect=raw.size)
    cycles = await run_streams(dut, [pix, coef], sink)
    out = sink.outputs()
    return np.stack([out["data"], out["sof"], out["eol"]], axis=1), cycles, sink.first_cycle


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
    got, cycles, first = await stream_engine(dut, raw, words)
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
        sb = TopScoreboard(cfg)
        sb.expect_frames(raw, words, expected)
        sb.observe_arrays(data=got[:, 0], sof=got[:, 1], eol=got[:, 2])
        tb_lib.assert_passed(sb.result())
    assert int(dut.frame_err_o.value) == 0, "frame_err_o set on a well-formed stream"
