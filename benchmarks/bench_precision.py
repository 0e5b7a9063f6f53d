"""Run time of the work-precision study (``irnuc precision``), full and quick.

Measures the whole study in this process (references, every method and setting, figures
not included), on one numba thread as the study itself runs, and a fixed calibration
workload measured in the same run (a numba-free numpy loop of ~0.2 s) so that a reader can
tell a slow machine from a slow study: ``full_over_calibration``. The target is 180 s for
the full study on the project's 2-core machine (``target_s``); the issue measured 13 minutes
before this version.

``{quick,full}_worst_time_per_work_over_median`` shows that no point is slowed by JIT
compilation (a few at most; compilation counted would give hundreds).

``--quick`` measures only the quick study. The last line is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from irnuc.reports.studies.precision import run_precision, summarize


def calibration() -> float:
    """Minimum time of a fixed numpy workload, s (three runs)."""
    rng = np.random.default_rng(0)
    a = rng.standard_normal((200, 200))
    best = float("inf")
    for _ in range(3):
        t = time.perf_counter()
        for _ in range(100):
            a = np.tanh(a @ a.T / 200.0)
        best = min(best, time.perf_counter() - t)
    return best


def worst_time_per_work(res: dict) -> float:
    """The largest ratio, over every measured point, of its seconds per unit of work to the
    median of its method's points: compilation drawn on the time axis would show as a
    ratio of hundreds (the study drew 3.63 s against 4e-4 s before its warm-up was
    untimed); scheduling noise stays within a few."""
    import statistics

    worst = 1.0
    for c in res["components"]:
        by: dict[str, list[float]] = {}
        for p in c["points"]:
            if p["time_s"] and p["work"]:
                by.setdefault(p["method"], []).append(p["time_s"] / p["work"])
        for rates in by.values():
            worst = max(worst, max(rates) / statistics.median(rates))
    return worst


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="measure only the quick study")
    args = ap.parse_args()
    cal = calibration()
    result: dict = {"benchmark": "bench_precision", "calibration_s": round(cal, 4),
                    "target_s": 180.0}
    runs = [True] if args.quick else [True, False]
    for quick in runs:
        t = time.perf_counter()
        res = run_precision(quick=quick)
        wall = time.perf_counter() - t
        s = summarize(res)
        key = "quick" if quick else "full"
        result[f"{key}_s"] = round(wall, 1)
        result[f"{key}_over_calibration"] = round(wall / cal, 1)
        result[f"{key}_all_defaults_on_front"] = s["all_defaults_on_front"]
        result[f"{key}_worst_time_per_work_over_median"] = round(worst_time_per_work(res), 2)
        result[f"{key}_per_component_s"] = {c["name"]: round(c["seconds"], 1)
                                           for c in res["components"]}
        print(f"{key} study: {wall:.1f} s ({wall / cal:.0f}x the calibration workload); "
              f"every default on its front: {s['all_defaults_on_front']}")
    if "full_s" in result:
        result["full_within_target"] = result["full_s"] <= result["target_s"]
        result["full_over_target"] = round(result["full_s"] / result["target_s"], 2)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
