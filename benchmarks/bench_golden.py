"""Speed of the golden model: NUC + DPC on VGA frames (goal <= 2 ms/frame, >= 150 Mpix/s).

Baselines measured in the same run: a plain numpy int64 implementation of the same
datapath (checked bit-equal first) and a memory-copy floor (copy the raw frame to the
output and the coefficient words to a scratch buffer: the least traffic any pass needs).
The last line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import os
import time

import numpy as np

from irnuc.nuc_fixed import load_pipeline, nuc_dpc_top, pack_words
from irnuc.nuc_fixed.fixed import gain_format, offset_format


def numpy_reference(raw: np.ndarray, words: np.ndarray, cfg) -> np.ndarray:
    """Plain vectorised numpy int64 NUC + DPC of one (H, W) frame."""
    gw, ow = cfg.gain_bits, cfg.offset_bits
    w = words.astype(np.int64)
    g = w & ((1 << gw) - 1)
    o = (((w >> gw) & ((1 << ow) - 1)) ^ (1 << (ow - 1))) - (1 << (ow - 1))
    bad = ((w >> (gw + ow)) & 1).astype(bool)
    f = cfg.frac_bits
    s = ((raw.astype(np.int64) * g) << (f - cfg.gain_frac_bits)) + (o << (f - cfg.offset_frac_bits))
    if f == 0:
        r = s
    elif cfg.rounding == "truncate":
        r = s >> f
    elif cfg.rounding == "half_up":
        r = (s + (1 << (f - 1))) >> f
    else:
        r = (s + (1 << (f - 1)) - 1 + ((s >> f) & 1)) >> f
    top = (1 << cfg.out_bits) - 1
    y = r & top if cfg.overflow == "wrap" else np.clip(r, 0, top)
    h, wd = y.shape
    good = np.zeros((h + 2, wd + 2), dtype=np.int64)
    good[1:-1, 1:-1] = ~bad
    yp = np.zeros((h + 2, wd + 2), dtype=np.int64)
    yp[1:-1, 1:-1] = y * ~bad
    acc = np.zeros((h, wd), dtype=np.int64)
    n = np.zeros((h, wd), dtype=np.int64)
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            if dr or dc:
                acc += yp[1 + dr:h + 1 + dr, 1 + dc:wd + 1 + dc]
                n += good[1 + dr:h + 1 + dr, 1 + dc:wd + 1 + dc]
    fix = bad & (n > 0)
    out = y.copy()
    out[fix] = (2 * acc[fix] + n[fix]) // (2 * n[fix])
    return out.astype(np.uint16 if cfg.out_bits <= 16 else np.uint32)


def best_time(fn, repeats: int) -> float:
    """Median wall time of ``fn()`` in seconds over ``repeats`` runs (after one warm-up)."""
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", default="typical14")
    ap.add_argument("--repeats", type=int, default=50)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    cfg = load_pipeline(args.config)
    h, w = 480, 640
    rng = np.random.default_rng(args.seed)
    raw = rng.integers(0, 2**cfg.adc_bits, (h, w)).astype(np.uint16)
    gfmt, ofmt = gain_format(cfg), offset_format(cfg)
    gain = gfmt.to_code(rng.normal(1.0, 0.05, (h, w)))
    offset = ofmt.to_code(rng.normal(0.0, 50.0, (h, w)))
    bad = rng.random((h, w)) < 0.01
    bad[100:103, 200:203] = True  # a cluster
    bad[300, :] = True  # a whole row
    words = pack_words(gain, offset, bad, cfg)

    want = numpy_reference(raw, words, cfg)
    got = nuc_dpc_top(raw, words, cfg)
    if not np.array_equal(got, want):
        raise SystemExit("golden model and numpy baseline disagree")

    out = np.empty_like(raw)
    scratch = np.empty_like(words)

    def floor() -> None:
        np.copyto(out, raw)
        np.copyto(scratch, words)

    t_golden = best_time(lambda: nuc_dpc_top(raw, words, cfg), args.repeats)
    t_numpy = best_time(lambda: numpy_reference(raw, words, cfg), max(5, args.repeats // 5))
    t_floor = best_time(floor, args.repeats)
    stack = np.stack([raw] * 8)
    t_stack = best_time(lambda: nuc_dpc_top(stack, words, cfg), max(5, args.repeats // 5)) / 8
    mpix = h * w / t_golden / 1e6
    result = {
        "bench": "bench_golden",
        "config": cfg.name,
        "frame": [h, w],
        "bad_fraction": round(float(bad.mean()), 4),
        "threads": int(os.environ.get("NUMBA_NUM_THREADS", 0)) or os.cpu_count(),
        "golden_ms_per_frame": round(t_golden * 1e3, 4),
        "golden_mpix_per_s": round(mpix, 1),
        "golden_stack8_ms_per_frame": round(t_stack * 1e3, 4),
        "numpy_int64_ms_per_frame": round(t_numpy * 1e3, 4),
        "memcopy_floor_ms_per_frame": round(t_floor * 1e3, 4),
        "speedup_vs_numpy": round(t_numpy / t_golden, 2),
        "ratio_vs_memcopy_floor": round(t_golden / t_floor, 2),
        "goal_ms_per_frame": 2.0,
        "meets_goal": bool(t_golden <= 2e-3),
    }
    print(f"NUC+DPC {cfg.name} VGA: {result['golden_ms_per_frame']} ms/frame "
          f"({result['golden_mpix_per_s']} Mpix/s); numpy {result['numpy_int64_ms_per_frame']} "
          f"ms; copy floor {result['memcopy_floor_ms_per_frame']} ms")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
