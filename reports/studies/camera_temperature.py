"""Study: a camera whose housing temperature changes (the paper repository's test_tcomp.py).

The housing (optics, shutter) warms, cools or stays at a temperature while the FPA stays
at the calibration's reference temperature and the camera looks at a uniform 330 K scene.
Every frame is corrected with ``two_point`` alone and with ``two_point + blind_drift``
(``typical14`` and ``drift14``, calibrated on the same plan; blind_drift's coupling
measured over housing temperatures at the reference FPA temperature). Per frame: the level
error of the corrected image (its mean minus the scene's calibrated level) and the fixed
pattern left, in mK, beside the NETD.

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
    fpn,
    frames_at,
    netd_mK,
    pyplot,
    responsivity,
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
    r_out = responsivity(c2.targets, plan["scene"])(scene_K)
    target = float(np.interp(scene_K, plan["scene"], c2.targets))
    good = ~(c2.bad | cd.bad)
    profs = profiles(n, *cam_range)
    temps = sorted({float(t) for p in profs.values() for t in p})
    frames: dict[float, tuple[np.ndarray, np.ndarray]] = {}
    for i, tc in enumerate(temps):
        frames[tc] = frames_at(sensor, fpa_ref, tc, [scene_K])
        if progress:
            progress(i + 1, len(temps))
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    out: dict[str, Any] = {}
    for pname, cams in profs.items():
        raw = np.concatenate([frames[float(t)][0] for t in cams])
        blind = np.concatenate([frames[float(t)][1] for t in cams])
        rec: dict[str, Any] = {"T_cam_K": cams.tolist()}
        for label, c in (("two_point", c2), ("two_point+blind_drift", cd)):
            y = method_top(raw, c.coeffs, FrameInputs(blind_codes=blind)).y.astype(np.float64)
            level = [(float(f[good].mean()) - target) / r_out * 1e3 for f in y]
            pattern = [fpn(f, good) / r_out * 1e3 for f in y]
            rec[label] = {"level_error_mK": level, "fpn_mK": pattern,
                          "worst_level_error_mK": float(np.max(np.abs(level))),
                          "worst_fpn_mK": float(np.max(pattern))}
        out[pname] = rec
    netd = netd_mK(sensor, fpa_ref, scene_K, r_out, out_per_adc=2.0 ** (c2.cfg.out_bits - c2.cfg.adc_bits))
    return {
        "study": NAME, "title": TITLE, "quick": quick,
        "sensor": {"preset": str(sensor.preset), "rows": sensor.rows, "cols": sensor.cols,
                   "seed": sensor.seed, "overrides": dict(sensor.overrides)},
        "scene_K": scene_K, "fpa_K": fpa_ref, "plan": {k: list(v) if isinstance(v, tuple) else v
                                                        for k, v in plan.items()},
        "drift_coupling": cd.summary["drift_coupling"],
        "drift_coupling_source": cd.summary["drift_coupling_source"],
        "responsivity_codes_per_K": r_out, "netd_mK": netd, "profiles": out,
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
    axes[1].axhline(result["netd_mK"], color="k", ls=":", lw=1, label="NETD")
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
