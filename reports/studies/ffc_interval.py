"""Study: how long a shutter refresh (FFC) holds while the FPA temperature ramps.

At FPA temperature ``ffc_fpa`` the shutter closes (a uniform source at the housing
temperature, the housing at the FPA temperature) and the FFC refreshes the offsets from
``ffc_frames`` shutter frames. The FPA then ramps at 0.5 and 2 K/min; the residual fixed
pattern of a uniform scene is measured against the time since that FFC, in mK beside the
NETD, and the longest FFC period that keeps it below the NETD is read off. The frames are
the model's steady state at each FPA temperature, so both ramps share one curve of residual
against FPA change; the rate sets the time axis. Methods: ``two_point + ffc`` (``ffc14``)
and ``tc_offset + ffc`` (``tcffc14``), and, for comparison, ``two_point`` without FFC.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from irnuc.reports.studies import drift_common as dc

NAME = "ffc_interval"
TITLE = "Residual fixed pattern against time since the last FFC, FPA ramping"
METHODS = ("ffc14", "tcffc14")
RATES_K_PER_MIN = (0.5, 2.0)


def longest_period(t_min: np.ndarray, fpn_mK: np.ndarray, netd: float) -> float | None:
    """Minutes from the FFC until the residual first exceeds the NETD (linear between
    samples); None when it stays below over the whole span, 0 when it starts above."""
    above = np.flatnonzero(np.asarray(fpn_mK) > netd)
    if above.size == 0:
        return None
    i = int(above[0])
    if i == 0:
        return 0.0
    t0, t1, f0, f1 = t_min[i - 1], t_min[i], fpn_mK[i - 1], fpn_mK[i]
    return float(t0 + (netd - f0) / (f1 - f0) * (t1 - t0))


def run(quick: bool = False, sensor: dc.StudySensor | None = None, scene_K: float = 330.0,
        ffc_fpa: float = 300.0, max_change_K: float = 6.0,
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """Residual against FPA change after one FFC, for each method and ramp (JSON-ready)."""
    import time

    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    t0 = time.perf_counter()
    sensor = sensor or dc.StudySensor(rows=24 if quick else 48, cols=32 if quick else 64)
    # Dense near the FFC, where a method without temperature compensation crosses the NETD.
    grid = (0.0, 0.1, 0.3, 1.0, 3.0, 6.0) if quick else (
        0.0, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0)
    changes = np.asarray([d for d in grid if d <= max_change_K])
    cal = dc.calibrate_methods(sensor, (*METHODS, "typical14"), dc.PLAN)
    base = cal["cal"]["ffc14"]
    sc = dc.scale(sensor, base.targets, dc.PLAN["scene"])
    good = ~np.logical_or.reduce([c.bad for c in cal["cal"].values()])
    n_ffc = int(base.cfg.ffc_frames or 1)
    shutter_raw, _ = dc.frames_at(sensor, ffc_fpa, ffc_fpa, [ffc_fpa], repeats=n_ffc)
    reading0 = int(cal["plan"].fpa_sensor.read(ffc_fpa)[0])
    scene_raw = []
    readings = []
    for i, d in enumerate(changes):
        raw, _ = dc.slope_frames(sensor, ffc_fpa + d, ffc_fpa + d, [scene_K])
        scene_raw.append(raw)
        readings += [int(cal["plan"].fpa_sensor.read(ffc_fpa + d)[0])] * 3
        if progress:
            progress(i + 1, len(changes))
    scene_raw = np.concatenate(scene_raw)
    n3 = len(readings)
    curves: dict[str, Any] = {}
    levels: dict[str, Any] = {}

    def per_change(y: np.ndarray) -> list[dict[str, float]]:
        return [dc.residuals(y[3 * k:3 * k + 3], good, [scene_K], sc)[0]
                for k in range(len(changes))]

    for name in METHODS:
        c = cal["cal"][name]
        ref = method_top(shutter_raw, c.coeffs, FrameInputs(
            reading=np.full(n_ffc, reading0), shutter=np.ones(n_ffc, bool)))
        y = method_top(scene_raw, c.coeffs, FrameInputs(
            reading=np.asarray(readings), shutter=np.zeros(n3, bool)),
            ffc_offset=ref.ffc_offset).y
        res = per_change(y)
        curves[c.cfg.method] = [r["fpn_mK"] for r in res]
        levels[c.cfg.method] = [r["level_error_mK"] for r in res]
    res = per_change(method_top(scene_raw, cal["cal"]["typical14"].coeffs).y)
    curves["two_point (no FFC)"] = [r["fpn_mK"] for r in res]
    levels["two_point (no FFC)"] = [r["level_error_mK"] for r in res]
    nd = dc.netd(sensor, ffc_fpa)
    netd = nd.netd_K * 1e3
    ramps = {}
    for rate in RATES_K_PER_MIN:
        t_min = changes / rate
        ramps[f"{rate:g} K/min"] = {
            "rate_K_per_min": rate, "t_min": t_min.tolist(),
            "longest_period_min": {m: longest_period(t_min, np.asarray(v), netd)
                                   for m, v in curves.items()},
            "span_min": float(t_min[-1])}
    return {
        "study": NAME, "title": TITLE, "quick": quick,
        "sensor": {"preset": str(sensor.preset), "rows": sensor.rows, "cols": sensor.cols,
                   "seed": sensor.seed, "overrides": dict(sensor.overrides)},
        "scene_K": scene_K, "ffc_fpa_K": ffc_fpa, "ffc_frames": n_ffc,
        "fpa_change_K": changes.tolist(), "fpn_mK": curves, "level_error_mK": levels,
        "ramps": ramps, "netd_mK": netd, "netd": nd.as_dict(),
        "seconds": time.perf_counter() - t0,
    }


def figure(result: dict[str, Any]) -> bytes:
    """Residual against time since the FFC, one panel per ramp, the NETD."""
    from irnuc.reports.studies.figures import png

    plt = dc.pyplot()
    ramps = result["ramps"]
    fig, axes = plt.subplots(1, len(ramps), figsize=(5.2 * len(ramps), 3.8), squeeze=False)
    for ax, (rname, ramp) in zip(axes[0], ramps.items(), strict=True):
        for i, (m, v) in enumerate(result["fpn_mK"].items()):
            lp = ramp["longest_period_min"][m]
            tag = "stays below" if lp is None else f"{lp:.2g} min"
            ax.plot(ramp["t_min"], v, "o-", ms=3, color=f"C{i}", label=f"{m}: {tag}")
        ax.axhline(result["netd_mK"], color="k", ls=":", lw=1,
                   label=f"NETD {result['netd_mK']:.0f} mK (300 K scene)")
        ax.set_yscale("log")
        ax.set_xscale("symlog", linthresh=0.1)
        ax.set_xlim(0.0, ramp["span_min"])
        ax.set_xlabel("time since the FFC, min")
        ax.set_ylabel("residual fixed pattern, mK")
        ax.set_title(f"FPA ramp {rname}", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.subplots_adjust(top=0.8)
    fig.suptitle(f"{TITLE}\nFFC at FPA {result['ffc_fpa_K']:g} K ({result['ffc_frames']} "
                 f"frames), scene {result['scene_K']:g} K", fontsize=9)
    return png(fig)
