"""Co-simulation speed: one VGA frame through the RTL (nuc_dpc_top), checked bit for bit.

Two modes:

* ``per_cycle``: cocotb drives and samples every clock from Python (``tb_lib.run_streams``)
  and checks the outputs in numpy; goal >= 100 kpixel/s.
* ``bulk``: a SystemVerilog testbench (``cocotb_tests/hdl/tb_bulk.sv``, a standalone
  Verilator binary) reads the stimulus with ``$readmemh`` and writes the outputs to a file;
  numpy writes the stimulus, parses the results and compares; goal >= 3 Mpixel/s, timed
  end to end (files written, simulation, files parsed, comparison).

Baseline measured in the same run: the golden model (``nuc_fixed.nuc_dpc_top``) on the same
frame. Builds are cached and not timed. The last line printed is one JSON object.

Usage: ``python benchmarks/bench_cosim.py [--config typical14] [--seed 1]``
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from nuc_fixed import (
    load_pipeline,
    nuc_dpc_top,
    pack_words,
    rtl,
)

H, W = 480, 640
#: Verilator options of the bulk binary: full optimisation, no X randomisation.
BULK_ARGS = ("-O3", "--x-assign", "fast", "--x-initial", "fast",
             "-MAKEFLAGS", "OPT_FAST=-O2 OPT_SLOW=-O1")


def _hex_lines(values: np.ndarray, digits: int) -> bytes:
    """Fixed-width lower-case hex lines, vectorized (numpy)."""
    v = values.astype(np.uint64).ravel()
    shifts = np.arange(digits - 1, -1, -1, dtype=np.uint64) * np.uint64(4)
    nib = ((v[:, None] >> shifts[None, :]) & np.uint64(15)).astype(np.uint8)
    chars = np.frombuffer(b"0123456789abcdef", dtype=np.uint8)[nib]
    lines = np.concatenate([chars, np.full((len(v), 1), ord("\n"), np.uint8)], axis=1)
    return lines.tobytes()


def _parse_hex_lines(data: bytes, digits: int) -> np.ndarray:
    arr = np.frombuffer(data, dtype=np.uint8).reshape(-1, digits + 1)[:, :digits]
    lut = np.zeros(256, dtype=np.uint64)
    for i, c in enumerate(b"0123456789abcdef"):
        lut[c] = i
    nib = lut[arr]
    out = np.zeros(len(arr), dtype=np.uint64)
    for k in range(digits):
        out = (out << np.uint64(4)) | nib[:, k]
    return out


def stimulus(cfg, seed: int):
    rng = np.random.default_rng(seed)
    raw = rng.integers(0, 1 << cfg.adc_bits, size=(H, W), dtype=np.int64)
    g = rng.integers(0, 1 << cfg.gain_bits, size=(H, W), dtype=np.int64)
    half = 1 << (cfg.offset_bits - 1)
    o = rng.integers(-half, half, size=(H, W), dtype=np.int64)
    bad = rng.random((H, W)) < 0.01
    return raw, pack_words(g, o, bad, cfg)


def bench_per_cycle(cfg, raw, words, expected, seed: int, work: Path) -> dict:
    bld = rtl.build("nuc_dpc_top", cfg)
    inp, outp = work / "bench_in.npz", work / "bench_out.json"
    np.savez(inp, raw=raw, words=words, expected=expected)
    t0 = time.perf_counter()
    xml = rtl.run(bld, "cocotb_tests.tb_bench", seed=seed,
                  env={"IRNUC_BENCH_IN": str(inp), "IRNUC_BENCH_OUT": str(outp),
                       "IRNUC_SEED": str(seed)},
                  results_xml=work / "bench_per_cycle.xml")
    wall = time.perf_counter() - t0
    res = rtl.read_results(xml)
    info = json.loads(outp.read_text())
    loop = info["sim_seconds"] + info["check_seconds"]
    return {"passed": all(r.passed for r in res.values()), "mismatches": info["mismatches"],
            "cycles": info["cycles"], "seconds": loop, "process_seconds": wall,
            "pixels_per_s": raw.size / loop}


def bench_bulk(cfg, raw, words, expected, work: Path) -> dict:
    bld = rtl.build("tb_bulk", cfg, binary=True, extra_args=BULK_ARGS)
    exe = bld.build_dir / "tb_bulk"
    a, b = cfg.adc_bits, cfg.out_bits
    h, w = raw.shape
    t0 = time.perf_counter()
    ys, xs = np.mgrid[0:h, 0:w]
    sof = ((ys == 0) & (xs == 0)).ravel().astype(np.uint64)
    eol = (xs == w - 1).ravel().astype(np.uint64)
    pix = (sof << np.uint64(a + 1)) | (eol << np.uint64(a)) | raw.ravel().astype(np.uint64)
    (work / "pix.hex").write_bytes(_hex_lines(pix, -(-(a + 2) // 4)))
    (work / "coef.hex").write_bytes(_hex_lines(words, -(-cfg.word_bits // 4)))
    t1 = time.perf_counter()
    proc = subprocess.run(
        [str(exe), f"+pix={work / 'pix.hex'}", f"+coef={work / 'coef.hex'}",
         f"+out={work / 'out.hex'}", f"+n={raw.size}", f"+w={w}", f"+h={h}"],
        capture_output=True, text=True, check=False, cwd=work)
    t2 = time.perf_counter()
    if proc.returncode != 0:
        raise rtl.RtlError(f"tb_bulk failed: {proc.stdout}\n{proc.stderr}")
    out = _parse_hex_lines((work / "out.hex").read_bytes(), -(-(b + 2) // 4))
    data = (out & np.uint64((1 << b) - 1)).astype(np.int64)
    o_eol = ((out >> np.uint64(b)) & np.uint64(1)).astype(np.int64)
    o_sof = ((out >> np.uint64(b + 1)) & np.uint64(1)).astype(np.int64)
    mism = int(len(out) != raw.size) or int(((data != expected.ravel()) | (o_sof != sof)
                                             | (o_eol != eol)).sum())
    t3 = time.perf_counter()
    return {"mismatches": mism, "frame_err": "frame_err_o set" in proc.stdout,
            "seconds": t3 - t0, "sim_seconds": t2 - t1, "io_seconds": (t1 - t0) + (t3 - t2),
            "pixels_per_s": raw.size / (t3 - t0), "sim_pixels_per_s": raw.size / (t2 - t1)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", default="typical14")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    cfg = load_pipeline(args.config)
    if cfg.max_width < W or cfg.max_height < H:
        raise SystemExit(f"config {cfg.name}: max frame {cfg.max_width}x{cfg.max_height} "
                         f"is smaller than VGA {W}x{H}")
    raw, words = stimulus(cfg, args.seed)
    nuc_dpc_top(raw[:4, :4], words[:4, :4], cfg)  # JIT warm-up, not timed
    t0 = time.perf_counter()
    expected = nuc_dpc_top(raw, words, cfg).astype(np.int64)
    golden_s = time.perf_counter() - t0
    golden_rate = raw.size / golden_s
    rtl.OUT_DIR.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory(dir=rtl.OUT_DIR, prefix="bench_cosim.") as tmp:
        work = Path(tmp)
        # Builds first (cached; not part of the timings).
        rtl.build("nuc_dpc_top", cfg)
        rtl.build("tb_bulk", cfg, binary=True, extra_args=BULK_ARGS)
        per = bench_per_cycle(cfg, raw, words, expected, args.seed, work)
        bulk = bench_bulk(cfg, raw, words, expected, work)
    print(f"per-cycle: {per['pixels_per_s'] / 1e3:.1f} kpixel/s, mismatches {per['mismatches']}")
    print(f"bulk:      {bulk['pixels_per_s'] / 1e6:.2f} Mpixel/s end to end "
          f"({bulk['sim_pixels_per_s'] / 1e6:.2f} Mpixel/s simulation only), "
          f"mismatches {bulk['mismatches']}")
    print(f"golden model: {golden_rate / 1e6:.2f} Mpixel/s")
    result = {
        "benchmark": "bench_cosim", "config": cfg.name, "frame": [H, W], "pixels": raw.size,
        "cpu_count": os.cpu_count(),
        "per_cycle_pixels_per_s": round(per["pixels_per_s"]),
        "per_cycle_mismatches": per["mismatches"],
        "per_cycle_goal_ratio": round(per["pixels_per_s"] / 100e3, 3),
        "bulk_pixels_per_s": round(bulk["pixels_per_s"]),
        "bulk_sim_only_pixels_per_s": round(bulk["sim_pixels_per_s"]),
        "bulk_mismatches": bulk["mismatches"],
        "bulk_goal_ratio": round(bulk["pixels_per_s"] / 3e6, 3),
        "golden_model_pixels_per_s": round(golden_rate),
        "bulk_vs_per_cycle": round(bulk["pixels_per_s"] / per["pixels_per_s"], 2),
        "per_cycle_vs_golden": round(per["pixels_per_s"] / golden_rate, 5),
        "bulk_vs_golden": round(bulk["pixels_per_s"] / golden_rate, 4),
    }
    print(json.dumps(result))


if __name__ == "__main__":
    main()
