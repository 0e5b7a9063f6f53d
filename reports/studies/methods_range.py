"""Study: every method over an FPA temperature range, against its memory and bandwidth.

Each method is calibrated on the same plan (scenes 290/330/370 K at FPA 288/298/308 K)
and corrects uniform scenes over a grid of FPA temperatures (288-308 K) and scene
temperatures (280-380 K), inside and between the calibration points. Per method: the
worst residual fixed pattern over the grid (LSB and mK through the local responsivity) and
the worst level error (mK), the coefficient memory (bits per
pixel) and the memory bandwidth at 60 frames/s for a VGA (640 x 480) array; per FPA
temperature, the worst over the scenes.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from irnuc.reports.studies.drift_common import (
    METHOD_CONFIGS,
    PLAN,
    StudySensor,
    calibrate_methods,
    memory_bits,
    netd,
    pyplot,
    residuals,
    scale,
    slope_frames,
)

NAME = "methods_range"
TITLE = "Methods over FPA 288-308 K and scenes 280-380 K: residual against memory"
FRAME_RATE = 60.0
VGA = (480, 640)


def run(quick: bool = False, sensor: StudySensor | None = None,
        fpa_K: tuple[float, ...] | None = None, scene_K: tuple[float, ...] | None = None,
        names: tuple[str, ...] = METHOD_CONFIGS,
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """Worst residual of every method over the grid, with its memory cost (JSON-ready)."""
    import time

    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    t0 = time.perf_counter()
    sensor = sensor or StudySensor(rows=24 if quick else 48, cols=32 if quick else 64)
    fpa = fpa_K or ((288.0, 298.0, 308.0) if quick else (288.0, 293.0, 298.0, 303.0, 308.0))
    scenes = scene_K or ((280.0, 330.0, 380.0) if quick else (280.0, 305.0, 330.0, 355.0, 380.0))
    cal = calibrate_methods(sensor, names, PLAN)
    first = cal["cal"][names[0]]
    sc = scale(sensor, first.targets, PLAN["scene"])
    good = ~np.logical_or.reduce([c.bad for c in cal["cal"].values()])
    sensor_read = cal["plan"].fpa_sensor
    grid: dict[float, tuple[np.ndarray, np.ndarray, int]] = {}
    for i, tf in enumerate(fpa):
        raw, blind = slope_frames(sensor, tf, tf, scenes)
        grid[tf] = (raw, blind, int(sensor_read.read(tf)[0]))
        if progress:
            progress(i + 1, len(fpa))
    methods: dict[str, Any] = {}
    for name in names:
        c = cal["cal"][name]
        per_fpa = []
        worst_lsb, worst_mk, worst_level = 0.0, 0.0, 0.0
        for tf in fpa:
            raw, blind, rd = grid[tf]
            y = method_top(raw, c.coeffs, FrameInputs(reading=np.full(len(raw), rd),
                                                      blind_codes=blind)).y
            res = residuals(y, good, scenes, sc)
            lsb = [r["fpn_lsb"] for r in res]
            mk = [r["fpn_mK"] for r in res]
            lev = [r["level_error_mK"] for r in res]
            per_fpa.append({"fpa_K": tf, "fpn_lsb": lsb, "fpn_mK": mk, "level_error_mK": lev,
                            "responsivity_codes_per_K": [r["responsivity_codes_per_K"]
                                                         for r in res]})
            worst_lsb, worst_mk = max(worst_lsb, *lsb), max(worst_mk, *mk)
            worst_level = max(worst_level, *(abs(v) for v in lev))
        mem = memory_bits(c.cfg)
        bw = mem["read_bits_per_frame"] * VGA[0] * VGA[1] * FRAME_RATE / 8e6
        methods[name] = {"method": c.cfg.method, "worst_fpn_lsb": worst_lsb,
                         "worst_fpn_mK": worst_mk, "worst_level_error_mK": worst_level, **mem,
                         "bandwidth_MB_per_s_vga60": bw, "per_fpa": per_fpa,
                         "coefficients": {k: v["format"] for k, v in
                                          c.summary["coefficients"].items()}}
    nd = netd(sensor, PLAN["fpa"][1])
    return {
        "study": NAME, "title": TITLE, "quick": quick,
        "sensor": {"preset": str(sensor.preset), "rows": sensor.rows, "cols": sensor.cols,
                   "seed": sensor.seed, "overrides": dict(sensor.overrides)},
        "plan": {k: list(v) if isinstance(v, tuple) else v for k, v in PLAN.items()},
        "fpa_K": list(fpa), "scene_K": list(scenes), "frame_rate": FRAME_RATE,
        "bandwidth_frame": list(VGA), "methods": methods, "netd_mK": nd.netd_K * 1e3,
        "netd": nd.as_dict(), "seconds": time.perf_counter() - t0,
    }


def figure(result: dict[str, Any]) -> bytes:
    """Worst residual against memory (bandwidth in the labels); residual per FPA point."""
    from irnuc.reports.studies.figures import png

    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for i, (name, m) in enumerate(result["methods"].items()):
        axes[0].scatter(m["calibration_bits"], m["worst_fpn_mK"], color=f"C{i}", s=30)
        axes[0].annotate(f"{name}\n{m['bandwidth_MB_per_s_vga60']:.0f} MB/s",
                         (m["calibration_bits"], m["worst_fpn_mK"]), fontsize=6,
                         xytext=(4, 2), textcoords="offset points")
        axes[1].plot([p["fpa_K"] for p in m["per_fpa"]],
                     [max(p["fpn_mK"]) for p in m["per_fpa"]], "o-", ms=3, color=f"C{i}",
                     label=f"{name} ({m['method']})")
    for ax in axes:
        ax.axhline(result["netd_mK"], color="k", ls=":", lw=1, label="NETD (300 K scene)")
        ax.set_yscale("log")
        ax.grid(alpha=0.3)
        ax.set_ylabel("worst residual fixed pattern, mK")
    axes[0].set_xlabel("coefficient memory, bits per pixel (label: read bandwidth, VGA 60 Hz)")
    axes[1].set_xlabel("FPA temperature, K (worst over the scenes)")
    axes[1].legend(fontsize=6)
    fig.suptitle(TITLE, fontsize=9)
    return png(fig)
