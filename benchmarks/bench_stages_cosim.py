"""Co-simulation of the stage tops on drift sequences of the model, with FFC events.

Each stage configuration (drift14 on ``method_drift_top``; ffc14, quadffc14 and tcffc14 on
``method_ffc_top``) goes through :func:`irnuc.cosim.sequence_bulk.cosim_sequence`: the
method calibrated on the physics model, ``--frames`` frames (default 20) of ``--height``
x ``--width`` (default VGA) with the FPA ramping from 289 K to 307 K, the scene from 295 K
to 360 K, the reference pixels read beside each frame (drift14) and the shutter closed for
8 frames every ``--ffc-every`` frames (default 10: two FFC events in 20 frames), corrected
by the RTL (the C++ bulk harness, which writes the FFC accumulator and corrections back as
the external memory) and by the golden reference of the cocotb stage testbench
(:mod:`irnuc.cosim.stages`), every output compared bit for bit.

The baseline measured in the same run is the golden reference's time on the same frames;
``ratio_golden_to_harness`` is its time over the harness's (above 1: the RTL simulation
is faster than the golden model). The last line is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import sys

from irnuc.common.errors import UserError
from irnuc.cosim.sequence_bulk import cosim_sequence
from irnuc.nuc_fixed import load_pipeline

CONFIGS = ("drift14", "ffc14", "quadffc14", "tcffc14")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    for name, default in (("frames", 20), ("height", 480), ("width", 640), ("seed", 1)):
        ap.add_argument(f"--{name}", type=int, default=default)
    ap.add_argument("--ffc-every", type=int, default=None,
                    help="frames from one shutter closing to the next (default: frames // 2)")
    ap.add_argument("--only", action="append", default=[], choices=CONFIGS)
    args = ap.parse_args()
    out: dict = {"frames": args.frames, "frame": [args.height, args.width], "seed": args.seed,
                 "baseline": "the golden reference (cosim.stages drift_frames / ffc_run) on "
                             "the same frames", "configs": {}}
    try:
        for name in args.only or CONFIGS:
            r = cosim_sequence(load_pipeline(name), args.frames, (args.height, args.width),
                               seed=args.seed, ffc_every=args.ffc_every)
            r["ratio_golden_to_harness"] = round(r["golden_seconds"]
                                                 / max(r["harness_seconds"], 1e-9), 3)
            # Every input pixel is simulated, also those of held frames (no output).
            r["harness_pixels_per_s"] = round(args.frames * args.height * args.width
                                              / max(r["harness_seconds"], 1e-9))
            out["configs"][name] = r
            print(f"{name:10s} {r['top']:16s} {r['pixels_compared']:9d} px + "
                  f"{r['words_compared']:9d} words compared, {r['mismatches']} mismatches, "
                  f"{r['ffc_events']} FFC events, harness {r['harness_seconds']:.2f} s, "
                  f"golden {r['golden_seconds']:.2f} s" + ("" if r["passed"] else "  FAILED"),
                  flush=True)
    except UserError as e:
        print(f"bench_stages_cosim: {e}", file=sys.stderr)
        sys.exit(2)
    runs = list(out["configs"].values())
    out["pixels_compared"] = sum(r["pixels_compared"] for r in runs)
    out["words_compared"] = sum(r["words_compared"] for r in runs)
    out["mismatches"] = sum(r["mismatches"] for r in runs)
    out["ffc_events"] = sum(r["ffc_events"] for r in runs)
    out["harness_seconds"] = round(sum(r["harness_seconds"] for r in runs), 3)
    out["golden_seconds"] = round(sum(r["golden_seconds"] for r in runs), 3)
    out["ratio_golden_to_harness"] = round(out["golden_seconds"]
                                           / max(out["harness_seconds"], 1e-9), 3)
    out["passed"] = bool(runs) and all(r["passed"] for r in runs)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
