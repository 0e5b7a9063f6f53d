"""Per-cycle Python driver benchmark: one frame from an .npz file through nuc_dpc_top.

Driven by ``benchmarks/bench_cosim.py``: env ``IRNUC_BENCH_IN`` (npz with raw, words,
expected) and ``IRNUC_BENCH_OUT`` (JSON written here: pixels, seconds, mismatches).
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import cocotb
import numpy as np

from cocotb_tests import tb_lib


@cocotb.test()
async def vga_frame(dut) -> None:
    data = np.load(os.environ["IRNUC_BENCH_IN"])
    raw, words, expected = data["raw"], data["words"], data["expected"]
    rng = np.random.default_rng(tb_lib.seed_from_env())
    await tb_lib.start_clock_and_reset(dut)
    frame = tb_lib.Frame(raw=raw, words=words, expected=expected)
    t0 = time.perf_counter()
    got, cycles, _ = await tb_lib.run_top_frames(dut, [frame], rng)
    t1 = time.perf_counter()
    g = np.asarray(got, dtype=np.int64)
    h, w = raw.shape
    ys, xs = np.mgrid[0:h, 0:w]
    mism = int(((g[:, 0] != expected.ravel()) | (g[:, 1] != ((ys == 0) & (xs == 0)).ravel())
                | (g[:, 2] != (xs == w - 1).ravel())).sum())
    t2 = time.perf_counter()
    out = Path(os.environ["IRNUC_BENCH_OUT"])
    tmp = out.with_suffix(".tmp")
    tmp.write_text(json.dumps({"pixels": int(raw.size), "cycles": cycles,
                               "sim_seconds": t1 - t0, "check_seconds": t2 - t1,
                               "mismatches": mism}))
    os.replace(tmp, out)
    assert mism == 0, f"{mism} mismatching pixels"
