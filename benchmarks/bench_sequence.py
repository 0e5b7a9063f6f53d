"""Speed and memory of a VGA drift sequence streamed to disk, with the camera's thermal
network and every noise source on (issue 35).

The sequence: the ambient ramps at 2 K/min from 293 K and drives the camera's thermal
network (housing 15 min, FPA 2 min, 3 K and 6 K of self-heating), the scene holds at
300 K, the shutter closes for 4 frames every 10 s, frames at 30 Hz on the default preset
(640 x 480 plus rings) with ``noise.enabled = true`` (Johnson, 1/f, the pixels' thermal
fluctuation, the skimming references' noise, readout noise), the thermal model chosen by
``auto`` (``lagged``: the shutter's steps are remembered). It is written by
:func:`model.sequence.write_sequence`, the path of ``irnuc frames --sequence``, to an
uncompressed frame file in a temporary folder.

Each measurement runs in a fresh child process, so its peak resident memory (``ru_maxrss``,
everything included: Python, numpy, numba and LLVM) is its own:

* ``sequence``: 1000 frames (``frames_per_s``, ``peak_rss_MiB``, ``file_MB``) and the same
  sequence with 250 frames (``peak_rss_250_MiB``): the memory does not grow with the
  length;
* ``baseline``: what a drift sequence took before sequences existed: per frame, a sensor
  configured for that frame's FPA and housing temperatures (``model.simulate`` with the
  frame's environment, its static stages made again), the frames kept in memory and saved
  with ``numpy.savez_compressed`` as ``irnuc frames`` did; on a short sequence
  (``baseline_frames``), frames per second.

``speedup_vs_baseline`` = frames_per_s / baseline_frames_per_s. Goals (issues 18, 35): at
least 50 frames/s and at most 1.5 GiB peak on this 2-core machine. The last line is one
JSON object.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def sequence(frames: int):
    """The benchmark's drift sequence (module docstring), ``frames`` frames long."""
    from irnuc.model.sequence import sequence_from_dict

    return sequence_from_dict({"sequence": {
        "frame_rate": 30.0, "duration": frames / 30.0,
        "ambient": {"profile": "ramp", "start": 293.0, "rate": 2.0},
        "network": {"start": 293.0, "housing_tau": 900.0, "fpa_tau": 120.0,
                    "housing_self_heating": 3.0, "fpa_self_heating": 6.0},
        "scene": {"profile": "constant", "value": 300.0},
        "shutter": {"every": 10.0, "frames": 4}}})


#: The sensor: the default preset with every noise source on.
NOISE = {"noise.enabled": True}


GOAL_FPS = 50.0
GOAL_RSS_MIB = 1536.0


def _peak_rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def child_sequence(frames: int, folder: Path) -> dict:
    from irnuc import model
    from irnuc.model.sequence import prepare, write_sequence

    seq = sequence(frames)
    cfg = model.load_preset("default", NOISE)
    # JIT warm-up (numba cache) on a tiny sequence of the same kind, not timed.
    small = model.load_preset("default", {"fpa.active_rows": 8, "fpa.active_cols": 8, **NOISE})
    write_sequence(prepare(small, seq, seed=1), folder / "warm.npz")
    t0 = time.perf_counter()
    run = prepare(cfg, seq, seed=1)
    fr = write_sequence(run, folder / "frames.npz")
    elapsed = time.perf_counter() - t0
    return {"frames": frames, "seconds": elapsed, "frames_per_s": frames / elapsed,
            "peak_rss_MiB": _peak_rss_mib(), "thermal": run.thermal,
            "file_MB": (folder / "frames.npz").stat().st_size / 1e6,
            "clipped": fr.diagnostics["clipped_low"] + fr.diagnostics["clipped_high"]}


def child_baseline(frames: int, folder: Path) -> dict:
    import numpy as np

    from irnuc import model

    sched = sequence(frames).schedule()
    model.simulate(model.load_preset("default", {"fpa.active_rows": 8, "fpa.active_cols": 8,
                                                 **NOISE}), [300.0], seed=1)  # JIT warm-up
    t0 = time.perf_counter()
    codes = []
    for n in range(frames):
        cfg = model.load_preset("default", {"environment.T_substrate": float(sched.fpa_K[n]),
                                            "environment.T_cam": float(sched.T_cam_K[n]),
                                            **NOISE})
        codes.append(model.simulate(cfg, [float(sched.scene_K[n])], seed=1).codes[0])
    np.savez_compressed(folder / "frames.npz", codes=np.stack(codes), temps=sched.scene_K)
    elapsed = time.perf_counter() - t0
    return {"frames": frames, "seconds": elapsed, "frames_per_s": frames / elapsed,
            "peak_rss_MiB": _peak_rss_mib()}


def run_child(kind: str, frames: int) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run([sys.executable, __file__, "--child", kind, "--frames",
                              str(frames), "--folder", tmp], check=True, capture_output=True,
                             text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--child", choices=("sequence", "baseline"))
    p.add_argument("--frames", type=int, default=1000)
    p.add_argument("--folder")
    p.add_argument("--baseline-frames", type=int, default=20)
    args = p.parse_args()
    if args.child:
        fn = child_sequence if args.child == "sequence" else child_baseline
        print(json.dumps(fn(args.frames, Path(args.folder))))
        return
    new = run_child("sequence", args.frames)
    short = run_child("sequence", max(args.frames // 4, 1))
    base = run_child("baseline", args.baseline_frames)
    result = {
        "benchmark": "bench_sequence",
        "array": [480, 640],
        "frames": new["frames"],
        "thermal": new["thermal"],
        "network": True, "noise": "every source",
        "frames_per_s": round(new["frames_per_s"], 1),
        "seconds": round(new["seconds"], 2),
        "peak_rss_MiB": round(new["peak_rss_MiB"], 1),
        "peak_rss_250_MiB": round(short["peak_rss_MiB"], 1),
        "file_MB": round(new["file_MB"], 1),
        "baseline_frames": base["frames"],
        "baseline_frames_per_s": round(base["frames_per_s"], 2),
        "speedup_vs_baseline": round(new["frames_per_s"] / base["frames_per_s"], 1),
        "goal_frames_per_s": GOAL_FPS,
        "goal_peak_rss_MiB": GOAL_RSS_MIB,
        "meets_goals": bool(new["frames_per_s"] >= GOAL_FPS
                            and new["peak_rss_MiB"] <= GOAL_RSS_MIB),
    }
    print(f"{result['frames']} VGA frames ({result['thermal']}): {result['frames_per_s']} "
          f"frames/s, peak {result['peak_rss_MiB']} MiB ({result['peak_rss_250_MiB']} MiB for "
          f"{short['frames']} frames), file {result['file_MB']} MB; baseline "
          f"{result['baseline_frames_per_s']} frames/s ({result['speedup_vs_baseline']}x)")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
