"""Speed and memory of a VGA drift sequence streamed to disk.

The sequence is the example of issue 18 on the default preset (640 x 480 plus rings): the
FPA ramps at 2 K/min, housing and scene constant, the shutter closed for 4 frames every
10 s, frames at 30 Hz, the thermal model chosen by ``auto`` (``lagged``: the pixels'
10 ms time constant leaves 4 % of a change in the next frame). It is written by
:func:`model.sequence.write_sequence`, the path of ``irnuc frames --sequence``, to an
uncompressed frame file in a temporary folder.

Each measurement runs in a fresh child process, so its peak resident memory (``ru_maxrss``,
everything included: Python, numpy, numba and LLVM) is its own:

* ``sequence``: 1000 frames (``frames_per_s``, ``peak_rss_MiB``, ``file_MB``) and the same
  sequence with 250 frames (``peak_rss_250_MiB``): the memory does not grow with the
  length;
* ``baseline``: what a drift sequence took before sequences existed: per frame, a sensor
  configured for that frame's FPA temperature (``model.simulate`` with the
  ``environment.T_substrate`` of the frame, its static stages made again), the frames
  kept in memory and saved with ``numpy.savez_compressed`` as ``irnuc frames`` did; on a
  short sequence (``baseline_frames``), frames per second.

``speedup_vs_baseline`` = frames_per_s / baseline_frames_per_s. Goals (issue 18): at least
50 frames/s and at most 1.5 GiB peak on this 2-core machine. The last line is one JSON
object.
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
    """The drift sequence of the example of issue 18, ``frames`` frames long."""
    from irnuc.model.sequence import sequence_from_dict

    return sequence_from_dict({"sequence": {
        "frame_rate": 30.0, "duration": frames / 30.0,
        "fpa": {"profile": "ramp", "start": 293.0, "rate": 2.0},
        "housing": {"profile": "constant", "value": 293.0},
        "scene": {"profile": "constant", "value": 300.0},
        "shutter": {"every": 10.0, "frames": 4}}})


GOAL_FPS = 50.0
GOAL_RSS_MIB = 1536.0


def _peak_rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def child_sequence(frames: int, folder: Path) -> dict:
    from irnuc import model
    from irnuc.model.sequence import prepare, write_sequence

    seq = sequence(frames)
    cfg = model.load_preset("default")
    # JIT warm-up (numba cache) on a tiny sequence of the same kind, not timed.
    small = model.load_preset("default", {"fpa.active_rows": 8, "fpa.active_cols": 8})
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
    model.simulate(model.load_preset("default", {"fpa.active_rows": 8, "fpa.active_cols": 8}),
                   [300.0], seed=1)  # JIT warm-up
    t0 = time.perf_counter()
    codes = []
    for n in range(frames):
        cfg = model.load_preset("default", {"environment.T_substrate": float(sched.fpa_K[n]),
                                            "environment.T_cam": float(sched.T_cam_K[n])})
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
