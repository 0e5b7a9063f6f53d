"""Speed of the golden model's correction methods on VGA frames (``method_top``).

Each method configuration corrects a sequence of VGA frames (random codes, random
coefficient codes of its formats, per-frame inputs: the FPA reading changing every frame,
blind codes, an FFC in the middle) twice: with the fused kernels (``nuc_fixed.fused``, the
default) and with the reference functions (``method_top(..., reference=True)``), whose
outputs must be equal. The baseline measured in the same run is the two-point
``nuc_dpc_top`` (numba, fused NUC + DPC) on the same frames, timed right before each
method (the machine's load changes within a run). Printed: ms per frame, the
ratio of the fused path to the baseline (goal: <= 3 for every method, issue 41) and its
speedup over the reference path; the last line is one JSON object.
"""

from __future__ import annotations

import argparse
import json

import numpy as np
from bench_golden import best_time  # the median of timed runs after a warm-up

from irnuc.nuc_fixed import load_pipeline, nuc_dpc_top, pack_words, pipeline_names
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, method_top

#: Issue 41: every method within this many times the two-point kernel per VGA frame.
GOAL = 3.0


def random_coefficients(cfg, shape, rng) -> MethodCoefficients:
    """Codes in every field's range (realistic gains near 1), registers in range."""
    bad = rng.random(shape) < 0.01
    fields = {}
    for m in cfg.memories.values():
        if m.source != "calibration":
            continue
        vals = {}
        for f in m.fields:
            if f.name == "bad":
                vals[f.name] = bad
                continue
            lo = -(1 << (f.width - 1)) if f.signed else 0
            vals[f.name] = rng.integers(lo, lo + (1 << f.width), shape)
        fields[m.name] = vals
    regs = {}
    for r in cfg.registers.values():
        if r.source != "calibration":
            continue
        if r.count > 1:
            regs[r.name] = tuple(6000 + 1000 * i for i in range(r.count))
        elif r.signed:
            regs[r.name] = 1 << (r.width - 12)
        else:
            regs[r.name] = min(7000, (1 << r.width) - 1) if r.name != "blind_ref" else 0
    return MethodCoefficients(cfg, fields, regs)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=16)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    h, w = 480, 640
    rng = np.random.default_rng(args.seed)
    n = args.frames
    raw = rng.integers(0, 2**14, (n, h, w)).astype(np.uint16)
    inputs = FrameInputs(reading=6000 + 100 * np.arange(n), blind_codes=rng.integers(0, 2**14, (n, 200)),
                         shutter=np.r_[np.zeros(2, bool), np.ones(8, bool), np.zeros(n - 10, bool)])
    base = load_pipeline("typical14")
    g = rng.integers(0, 2**base.gain_bits, (h, w))
    o = rng.integers(-(2 ** (base.offset_bits - 1)), 2 ** (base.offset_bits - 1), (h, w))
    words = pack_words(g, o, rng.random((h, w)) < 0.01, base)
    def base_time() -> float:
        return best_time(lambda: nuc_dpc_top(raw, words, base), args.repeats) / n

    times: dict[str, tuple[str, float, float, float]] = {}
    for name in pipeline_names(method=None):
        cfg = load_pipeline(name)
        if cfg.plain and name != "typical14":
            continue
        c = random_coefficients(cfg, (h, w), rng)
        fused = method_top(raw, c, inputs)
        ref = method_top(raw, c, inputs, reference=True)
        if not np.array_equal(fused.y, ref.y):
            raise SystemExit(f"{name}: the fused path differs from the reference path")
        # The baseline right before each method (the shared machine's load changes
        # within a run): each ratio is to the baseline measured beside it.
        t_b = base_time()
        t = best_time(lambda c=c: method_top(raw, c, inputs), args.repeats) / n
        t_ref = best_time(lambda c=c: method_top(raw, c, inputs, reference=True),
                          args.repeats) / n
        times[name] = (cfg.method, t, t_ref, t_b)
    out: dict[str, object] = {"frame": [h, w], "frames": n,
                              "baseline": "nuc_dpc_top typical14 (numba, fused)",
                              "baseline_ms_per_frame": 1e3 * float(np.median(
                                  [v[3] for v in times.values()])),
                              "goal_ratio": GOAL, "methods": {}}
    for name, (method, t, t_ref, t_base) in times.items():
        out["methods"][name] = {"method": method, "ms_per_frame": 1e3 * t,
                                "baseline_ms_per_frame": 1e3 * t_base,
                                "ratio_to_baseline": t / t_base,
                                "within_goal": t / t_base <= GOAL,
                                "reference_ms_per_frame": 1e3 * t_ref,
                                "reference_ratio_to_baseline": t_ref / t_base,
                                "speedup_vs_reference": t_ref / t}
        print(f"{name:12s} {method:22s} {1e3 * t:8.2f} ms/frame  x{t / t_base:5.2f}"
              f"{'' if t / t_base <= GOAL else ' (over the goal)'}  reference "
              f"{1e3 * t_ref:7.2f} ms/frame (fused {t_ref / t:5.1f}x faster)")
    ratios = [m["ratio_to_baseline"] for m in out["methods"].values()]
    out["max_ratio_to_baseline"] = max(ratios)
    out["all_within_goal"] = max(ratios) <= GOAL
    print(f"baseline nuc_dpc_top {out['baseline_ms_per_frame']:.2f} ms/frame (median); worst "
          f"method x{max(ratios):.2f} "
          f"(goal <= {GOAL})")
    print(json.dumps(out))


if __name__ == "__main__":
    main()
