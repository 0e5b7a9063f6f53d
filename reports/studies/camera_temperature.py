"""Study: a camera whose housing temperature changes (the paper repository's test_tcomp.py).

The housing (optics, shutter) warms, cools or stays at a temperature while the FPA stays
at the calibration's reference temperature and the camera looks at a uniform 330 K scene.
Every frame is corrected with ``two_point`` alone and with ``two_point + blind_drift``
(``typical14`` and ``drift14``, calibrated on the same plan; blind_drift's coupling
measured over housing temperatures at the reference FPA temperature). Per frame: the level
error of the corrected image (the scene its mean reads on the calibration's scale, minus
the scene) and the fixed pattern left through the image's local responsivity
(:func:`metrics.residuals_mK`), in mK, beside the NETD (300 K scene).

test_tcomp.py subtracts the change of the boundary-pixel average from the corrected
frames; blind_drift subtracts the calibrated multiple of it from the raw codes, before
the gain (docs/methods.md).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from irnuc.reports.studies.drift_common import (
    PLAN,
    StudySensor,
    calibrate_methods,
    netd,
    pyplot,
    residuals,
    scale,
    slope_frames,
)

NAME = "camera_temperature"
TITLE = "Camera (housing) temperature drift: two_point with and without blind_drift"
METHODS = ("typical14", "drift14")


def profiles(frames: int, lo: float, hi: float) -> dict[str, np.ndarray]:
    """Housing temperature per frame, K: rising, falling and three constants (test_tcomp)."""
    up = np.linspace(lo, hi, frames)
    return {"rising": up, "falling": up[::-1], "constant_low": np.full(frames, lo),
            "constant_mid": np.full(frames, up[frames // 2]), "constant_high": np.full(frames, hi)}


def run(quick: bool = False, sensor: StudySensor | None = None, scene_K: float = 330.0,
        cam_range: tuple[float, float] = (298.0, 318.0),
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """Residual per frame of each housing profile and method (JSON-ready)."""
    import time

    t0 = time.perf_counter()
    sensor = sensor or StudySensor(rows=24 if quick else 48, cols=32 if quick else 64)
    n = 6 if quick else 21
    plan = dict(PLAN)
    fpa_ref = plan["fpa"][len(plan["fpa"]) // 2]
    cal = calibrate_methods(sensor, METHODS, plan,
                            drift_cam=(fpa_ref - 5.0, fpa_ref + 5.0, fpa_ref + 10.0))
    c2, cd = cal["cal"]["typical14"], cal["cal"]["drift14"]
    sc = scale(sensor, c2.targets, plan["scene"])
    good = ~(c2.bad | cd.bad)
    profs = profiles(n, *cam_range)
    temps = sorted({float(t) for p in profs.values() for t in p})
    frames: dict[float, tuple[np.ndarray, np.ndarray]] = {}
    for i, tc in enumerate(temps):
        frames[tc] = slope_frames(sensor, fpa_ref, tc, [scene_K])
        if progress:
            progress(i + 1, len(temps))
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    out: dict[str, Any] = {}
    resp: list[float] = []
    for pname, cams in profs.items():
        raw = np.concatenate([frames[float(t)][0] for t in cams])
        blind = np.concatenate([frames[float(t)][1] for t in cams])
        rec: dict[str, Any] = {"T_cam_K": cams.tolist()}
        for label, c in (("two_point", c2), ("two_point+blind_drift", cd)):
            y = method_top(raw, c.coeffs, FrameInputs(blind_codes=blind)).y
            res = [residuals(y[3 * k:3 * k + 3], good, [scene_K], sc)[0] for k in range(len(cams))]
            level = [r["level_error_mK"] for r in res]
            pattern = [r["fpn_mK"] for r in res]
            resp += [r["responsivity_codes_per_K"] for r in res]
            rec[label] = {"level_error_mK": level, "fpn_mK": pattern,
                          "responsivity_codes_per_K": [r["responsivity_codes_per_K"] for r in res],
                          "worst_level_error_mK": float(np.max(np.abs(level))),
                          "worst_fpn_mK": float(np.max(pattern))}
        out[pname] = rec
    nd = netd(sensor, fpa_ref)
    return {
        "study": NAME, "title": TITLE, "quick": quick,
        "sensor": {"preset": str(sensor.preset), "rows": sensor.rows, "cols": sensor.cols,
                   "seed": sensor.seed, "overrides": dict(sensor.overrides)},
        "scene_K": scene_K, "fpa_K": fpa_ref, "plan": {k: list(v) if isinstance(v, tuple) else v
                                                        for k, v in plan.items()},
        "drift_coupling": cd.summary["drift_coupling"],
        "drift_coupling_source": cd.summary["drift_coupling_source"],
        "responsivity_codes_per_K": {"min": float(min(resp)), "max": float(max(resp))},
        "netd_mK": nd.netd_K * 1e3, "netd": nd.as_dict(), "profiles": out,
        "seconds": time.perf_counter() - t0,
    }


def figure(result: dict[str, Any]) -> bytes:
    """Level error and fixed pattern per frame, per profile, both methods."""
    from irnuc.reports.studies.figures import png

    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for i, (pname, rec) in enumerate(result["profiles"].items()):
        for label, ls in (("two_point", "-"), ("two_point+blind_drift", "--")):
            d = rec[label]
            axes[0].plot(np.abs(d["level_error_mK"]), ls, color=f"C{i}",
                         label=f"{pname} {label}")
            axes[1].plot(d["fpn_mK"], ls, color=f"C{i}")
    axes[1].axhline(result["netd_mK"], color="k", ls=":", lw=1, label="NETD (300 K scene)")
    axes[0].set_ylabel("|level error|, mK")
    axes[1].set_ylabel("residual fixed pattern, mK")
    for ax in axes:
        ax.set_yscale("log")
    for ax in axes:
        ax.set_xlabel("frame")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6, ncol=2)
    axes[1].legend(fontsize=7)
    fig.suptitle(f"{TITLE}\nFPA {result['fpa_K']:g} K, scene {result['scene_K']:g} K; solid: "
                 "two_point, dashed: + blind_drift", fontsize=9)
    return png(fig)
