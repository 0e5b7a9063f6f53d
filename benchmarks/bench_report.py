"""Run time of the README's main job, ``irnuc report`` (default configuration), phase by phase.

Runs, each in a subprocess with its own output folder:

1. ``cold``: an empty irnuc cache (``IRNUC_CACHE_DIR`` a fresh folder: Verilator builds,
   syntheses, numba kernels and the work-precision study all made anew), with ``--hog``
   CPU-bound processes running beside it (default 1: a busy loop, as another engineer's
   job would be), to show the report passes on its first run on a loaded machine;
2. ``warm``: the same cache again, no hog (the issue's goal: <= 60 s on 2 cores);
3. ``warm_hog``: the same cache, with the hog;
4. ``baseline`` (measured in the same run): the same configuration with the same cache and
   ``--no-cosim``: the report's compute-only part (frames, calibration, sweep, cached
   syntheses, paper, cached precision), to normalize the co-simulation's share.

Each run's exit status, wall time and the phases of its ``summary.json`` are reported; the
last line printed is one JSON object with ``warm_goal_ratio`` (warm total / 60 s) and
``warm_vs_baseline`` (warm total / baseline total).

Usage: ``python benchmarks/bench_report.py [--config default] [--hog 1] [--keep]``
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

GOAL_WARM_S = 60.0
HOG = "import time\nt = time.time()\nwhile time.time() - t < 3600:\n    sum(i * i for i in range(10000))\n"


def _run(name: str, args: list[str], env: dict[str, str], out: Path, hog: int) -> dict:
    hogs = [subprocess.Popen([sys.executable, "-c", HOG]) for _ in range(hog)]
    try:
        t0 = time.perf_counter()
        proc = subprocess.run([str(Path(sys.executable).with_name("irnuc")), "report", "-q",
                               "--out", str(out), *args], env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
    finally:
        for h in hogs:
            h.kill()
            h.wait()
    rec: dict = {"run": name, "returncode": proc.returncode, "wall_s": round(wall, 1), "hogs": hog}
    summary = out / "summary.json"
    if summary.is_file():
        s = json.loads(summary.read_text())
        rec["status"] = s["status"]
        rec["phases_s"] = {k: round(v, 1) for k, v in s["phases"].items()}
        rec["closing_line"] = proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else ""
        c = s["sections"].get("cosim") or {}
        rec["cosim"] = {k: c.get(k) for k in ("tests", "passed", "failed", "timeout", "pixels",
                                               "mismatches", "build_seconds")}
    else:
        rec["stderr"] = proc.stderr[-2000:]
    print(json.dumps(rec), flush=True)
    return rec


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", default="default")
    ap.add_argument("--hog", type=int, default=1, help="CPU-bound processes beside the cold run")
    ap.add_argument("--keep", action="store_true", help="keep the cache and output folders")
    args = ap.parse_args()
    root = Path(tempfile.mkdtemp(prefix="bench_report_"))
    env = {**os.environ, "IRNUC_CACHE_DIR": str(root / "cache")}
    cfg = ["--config", args.config]
    try:
        cold = _run("cold", cfg, env, root / "cold", args.hog)
        warm = _run("warm", cfg, env, root / "warm", 0)
        warm_hog = _run("warm_hog", cfg, env, root / "warm_hog", args.hog)
        base = _run("baseline", [*cfg, "--no-cosim"], env, root / "baseline", 0)
    finally:
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)
    result = {
        "config": args.config, "cpu_count": os.cpu_count(), "hogs": args.hog,
        "cold_s": cold["wall_s"], "cold_rc": cold["returncode"], "cold_phases_s": cold.get("phases_s"),
        "warm_s": warm["wall_s"], "warm_rc": warm["returncode"], "warm_phases_s": warm.get("phases_s"),
        "warm_hog_s": warm_hog["wall_s"], "warm_hog_rc": warm_hog["returncode"],
        "warm_hog_phases_s": warm_hog.get("phases_s"),
        "baseline_no_cosim_s": base["wall_s"], "baseline_phases_s": base.get("phases_s"),
        "warm_goal_s": GOAL_WARM_S,
        "warm_goal_ratio": round(warm["wall_s"] / GOAL_WARM_S, 3),
        "warm_vs_baseline": round(warm["wall_s"] / base["wall_s"], 3),
    }
    print(json.dumps(result))


if __name__ == "__main__":
    main()
