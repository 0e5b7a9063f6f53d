"""Co-simulation campaign of the correction methods on a drift sequence of the model.

Every base method (one named configuration each; two_point as ``typical14`` on
``method_dpc_top``) is calibrated on the physics model (one plan: scenes 290/330/370 K x
FPA 288/298/308 K, ``irnuc.cosim.method_drift``), then ``--frames`` frames (default 20) of
``--height`` x ``--width`` (default VGA) with the FPA ramping from 289 K to 307 K and the
scene from 295 K to 360 K are corrected by the RTL (bulk harness of ``method_dpc_top``, 2
processes) and by the golden model (``nuc_fixed.method_top``), every output pixel
compared. The baseline measured in the same run is the golden model's time on the same
frames; printed per method: pixels compared, mismatches, the harness's pixel rate and its
ratio to the golden model's; the last line is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import time

from irnuc.cosim.method_drift import calibrate_methods, drift_sequence, run_campaign
from irnuc.nuc_fixed import load_pipeline

METHODS = ("onepoint14", "typical14", "piecewise14", "quadratic14", "tcoffset14", "tcgain14",
           "table14")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=20)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--only", action="append", default=[], choices=METHODS)
    args = ap.parse_args()
    shape = (args.height, args.width)
    cfgs = [load_pipeline(n) for n in (args.only or METHODS)]
    t0 = time.perf_counter()
    seq = drift_sequence(args.frames, shape, seed=args.seed)
    t_seq = time.perf_counter() - t0
    t0 = time.perf_counter()
    cals = calibrate_methods(cfgs, shape, seed=args.seed)
    t_cal = time.perf_counter() - t0
    runs = run_campaign(cfgs, shape=shape, sequence=seq, coeffs=cals, seed=args.seed)
    out = {"frames": args.frames, "frame": list(shape), "seed": args.seed,
           "fpa_K": [float(seq.fpa_K[0]), float(seq.fpa_K[-1])],
           "model_seconds": round(t_seq, 2), "calibration_seconds": round(t_cal, 2),
           "baseline": "nuc_fixed.method_top on the same frames", "methods": {}}
    for r in runs:
        d = r.to_dict()
        d["ratio_to_golden"] = round(r.golden_seconds / max(r.sim_seconds, 1e-9), 4)
        out["methods"][r.name] = d
        print(f"{r.name:12s} {r.method:13s} {r.compared:9d} px compared, {r.mismatches} "
              f"mismatches, {d['sim_pixels_per_s'] / 1e6:6.2f} Mpixel/s "
              f"(golden {r.pixels / max(r.golden_seconds, 1e-9) / 1e6:6.2f})"
              + ("" if r.passed else "  FAILED"))
    out["pixels_compared"] = sum(r.compared for r in runs)
    out["mismatches"] = sum(r.mismatches + r.missing + r.extra for r in runs)
    out["passed"] = all(r.passed for r in runs)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
