"""Speed of the sensor model: one VGA frame, against per-pixel scipy.optimize.fsolve.

Measures, after JIT warm-up (minimum of several runs: the machine is shared):

* ``frame_ms``: one uniform-scene frame of the default preset (640 x 480 plus rings) from a
  configured sensor (``model.Pipeline``): radiance, absorbed power, electro-thermal solve,
  skimming, integrator, defects, ADC;
* ``first_frame_ms``: one call of ``model.simulate``, which also draws the per-pixel
  parameters and defects and computes the optics;
* ``batch_frame_ms``: the time per frame within a batch of 16 frames (static stages shared);
* ``solve_ms``: the electro-thermal solve of that frame alone, started from each pixel's
  prediction (:mod:`model.core.warmstart`, what the pipeline does), and ``cold_solve_ms``:
  the same frame by the neighbour-started solve (:func:`model.core.bolometer.solve_frames`,
  the pipeline's solve before), with ``solve_speedup`` their ratio and
  ``max_rel_diff_vs_cold`` the largest relative difference of the temperature rises (both
  meet rtol 1e-12);
* the same equation solved pixel by pixel with ``scipy.optimize.fsolve`` (the reference
  implementation's method) on a crop, per pixel, extrapolated to the frame:
  ``speedup_vs_fsolve`` = fsolve time per frame / ``frame_ms``; the crop's solutions are
  compared with irnuc's (``max_rel_diff_vs_fsolve``);
* ``cold_start_s``: a fresh ``irnuc frames`` process on a small array (numba cache warm).

The last line is one JSON object.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.optimize import fsolve

from irnuc import model
from irnuc.model.core import bolometer as kb
from irnuc.model.core import warmstart as kw
from irnuc.model.pipeline import Pipeline
from irnuc.model.stages import BOLOMETER_VARIANTS


def best_of(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    cfg = model.load_preset("default")
    sensor = Pipeline(cfg, seed=1)
    for _ in range(5):  # JIT warm-up, static products, the allocator's steady state
        sensor.simulate([300.0])
    frame = best_of(lambda: sensor.simulate([300.0]), 30)  # min of many: a shared machine
    first = best_of(lambda: model.simulate(cfg, [300.0], seed=1), 5)
    temps = np.linspace(300.0, 400.0, 16)
    batch = best_of(lambda: model.simulate(cfg, temps, seed=1), 3) / temps.size

    v = sensor.run(np.array([300.0]), ["Q", "params", "dT", "solve_coef", "solve_reference"])
    Q, p = v["Q"], v["params"]
    b, env = cfg["bolometer"], cfg["environment"]
    B = kb.activation_temperature(b["tcr"], b["T_ref"])
    args = (B, b["T_ref"], env["T_substrate"], b["bias_current"], b["t_int"],
            BOLOMETER_VARIANTS[b["variant"]], b["rtol"], b["max_iter"], b["runaway_temperature"])
    shape = Q.shape
    outs = (np.empty(shape), np.empty(shape), np.empty(shape, np.uint8), np.empty(shape, np.int32))
    cold_solve = best_of(lambda: kb.solve_frames(Q, p["R_ref"], p["g"], p["C"], *args, *outs),
                         7)
    coef, ref = v["solve_coef"], v["solve_reference"]
    pred = kw.empty_solution(shape)

    def predicted() -> None:
        kw.solve_frames_predicted(Q, Q, False, p["R_ref"], p["g"], coef["fq"], coef["variant"],
                                  coef["b"], B, b["T_ref"], np.array([env["T_substrate"]]),
                                  b["bias_current"], b["rtol"], b["max_iter"],
                                  b["runaway_temperature"], ref["inv_T"], ref["e"], ref["c"],
                                  ref["s"], ref["ds"], *pred)

    solve = best_of(predicted, 7)
    diff_cold = float(np.max(np.abs(pred[0] - outs[0]) / np.abs(outs[0])))

    # Baseline: fsolve per pixel on a crop, same equation, same per-pixel parameters.
    crop = (slice(100, 120), slice(200, 220))
    I, t_int, T_s, T_ref = b["bias_current"], b["t_int"], env["T_substrate"], b["T_ref"]
    ours = v["dT"][0][crop]

    def fsolve_crop() -> np.ndarray:
        out = np.empty(ours.shape)
        for (i, j), _ in np.ndenumerate(ours):
            r, g, c = (p[k][crop][i, j] for k in ("R_ref", "g", "C"))
            u = t_int * g / c
            f = 1.0 + math.expm1(-u) / u
            q = Q[0][crop][i, j]

            def h(x, r=r, g=g, f=f, q=q):
                T = T_s + x[0]
                return [x[0] - q / g - I * I * f / g * r * math.exp(B * (1 / T - 1 / T_ref))]

            out[i, j] = fsolve(h, [0.0], xtol=1e-12)[0]
        return out

    t0 = time.perf_counter()
    ref = fsolve_crop()
    fsolve_per_pixel = (time.perf_counter() - t0) / ours.size
    n_pixels = shape[1] * shape[2]
    fsolve_frame = fsolve_per_pixel * n_pixels

    with tempfile.TemporaryDirectory() as tmp:
        cmd = [str(Path(sys.executable).with_name("irnuc")), "frames", "--set",
               "fpa.active_rows=32", "--set", "fpa.active_cols=32", "--out",
               str(Path(tmp) / "f.npz")]
        subprocess.run(cmd, check=True, capture_output=True)  # fill the numba cache
        cold = best_of(lambda: subprocess.run(cmd, check=True, capture_output=True), 3)

    result = {
        "benchmark": "bench_model",
        "array": [int(shape[1]), int(shape[2])],
        "frame_ms": round(frame * 1e3, 2),
        "first_frame_ms": round(first * 1e3, 2),
        "batch_frame_ms": round(batch * 1e3, 2),
        "solve_ms": round(solve * 1e3, 2),
        "cold_solve_ms": round(cold_solve * 1e3, 2),
        "solve_speedup": round(cold_solve / solve, 1),
        "max_rel_diff_vs_cold": diff_cold,
        "goal_frame_ms": 10.0,
        "fsolve_us_per_pixel": round(fsolve_per_pixel * 1e6, 2),
        "fsolve_frame_s": round(fsolve_frame, 2),
        "speedup_vs_fsolve": round(fsolve_frame / frame, 1),
        "speedup_vs_fsolve_batch": round(fsolve_frame / batch, 1),
        "max_rel_diff_vs_fsolve": float(np.max(np.abs(ref - ours) / np.abs(ours))),
        "cold_start_s": round(cold, 3),
    }
    print(f"one VGA frame: {result['frame_ms']} ms (first {result['first_frame_ms']} ms, "
          f"{result['batch_frame_ms']} ms/frame in a "
          f"batch); solve {result['solve_ms']} ms ({result['solve_speedup']}x the cold "
          f"solve); fsolve: {result['fsolve_us_per_pixel']} us/pixel; "
          f"speed-up {result['speedup_vs_fsolve']}x; cold start {result['cold_start_s']} s")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
