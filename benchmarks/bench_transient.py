"""Speed of the transient model's default (``auto``) on stiff pixels, against RK4.

Problems: the work-precision study's transient problems (default preset, 4 x 6 active
pixels plus rings = 120 pixels, the first frame: a 300 K scene, pulse 60 us) with
C = 1e-14 and 1e-15 J/K (stiffness t_int |df/dtheta| ~1.2e5 and ~1.2e6) and the default
preset itself (stiffness 0.24). For each: the default at its default tolerance (rtol 1e-9)
and the baseline, adaptive RK4 at the same tolerance, measured in the same run (minimum
of several runs after the JIT warm-up, one numba thread), with their substeps per pulse
and their errors against the 60-digit phase-variable quadrature reference on two pixels.
RK4 refuses the C = 1e-15 problem (StiffnessError), which is recorded.

The last line is one JSON object: per problem ``auto_ms``, ``rk4_ms``,
``speedup_vs_rk4`` (rk4_ms / auto_ms), substeps and errors.
"""

from __future__ import annotations

import json
import time

import numba
import numpy as np

from irnuc.model import transient as tr
from irnuc.reports.studies.precision import reference_transient_exact, transient_problem


def best_of(fn, repeats: int, budget: float = 5.0) -> float:
    best, spent = float("inf"), 0.0
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        dt = time.perf_counter() - t
        best, spent = min(best, dt), spent + dt
        if spent > budget:
            break
    return best


def measure(kind: str) -> dict:
    prob = transient_problem(kind)
    cfg, p = prob["cfg"], prob["params"]
    Q, Ts = prob["Q"][:1], prob["T_s"][:1]
    b = cfg["bolometer"]
    pix = [(3, 4), (6, 7)]
    refs = []
    for i, j in pix:
        v = reference_transient_exact(Q[:, i, j], Ts, p["R_ref"][i, j], p["g"][i, j],
                                      p["C"][i, j], tcr=b["tcr"], T_ref=b["T_ref"],
                                      bias_current=b["bias_current"], t_int=b["t_int"],
                                      frame_period=1 / 30, pulse_start=0.0,
                                      theta0=Q[0, i, j] / p["g"][i, j])[0]
        refs.append(v)
    out: dict = {}
    for name in ("auto", "rk4"):
        def run(name=name):
            return tr.integrate_pixels(Q, Ts, p["R_ref"], p["g"], p["C"], tcr=b["tcr"],
                                       T_ref=b["T_ref"], bias_current=b["bias_current"],
                                       t_int=b["t_int"],
                                       settings={"integrator": name, "max_substeps": 10**6})
        try:
            r = run()
        except tr.StiffnessError as exc:
            out[f"{name}_ms"] = None
            out[f"{name}_refused"] = str(exc)[:120]
            continue
        out[f"{name}_ms"] = round(best_of(run, 5) * 1e3, 3)
        out[f"{name}_substeps"] = float(r.substeps.mean())
        out[f"{name}_error"] = max(float(abs((r.v_bolo[0, i, j] - v[0, 0]) - v[1, 0]) / v[0, 0])
                                   for (i, j), v in zip(pix, refs, strict=True))
        if name == "auto":
            out["auto_integrators"] = r.integrators_used()
    if out.get("rk4_ms"):
        out["speedup_vs_rk4"] = round(out["rk4_ms"] / out["auto_ms"], 1)
    return out


def main() -> None:
    numba.set_num_threads(1)
    result = {"benchmark": "bench_transient", "pixels": 120, "frames": 1, "rtol": tr.DEFAULT_RTOL}
    for kind, label in (("nonstiff", "default_preset"), ("stiff_1e5", "stiff_C1e-14"),
                        ("stiff_1e6", "stiff_C1e-15")):
        result[label] = measure(kind)
        r = result[label]
        print(f"{label}: auto {r['auto_ms']} ms ({r['auto_substeps']:.0f} substeps, error "
              f"{r['auto_error']:.2g}); rk4 "
              + (f"{r['rk4_ms']} ms ({r['rk4_substeps']:.0f} substeps, error "
                 f"{r['rk4_error']:.2g}), speed-up {r['speedup_vs_rk4']}x"
                 if r.get("rk4_ms") else "refuses (StiffnessError)"))
    print(json.dumps(result))


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
