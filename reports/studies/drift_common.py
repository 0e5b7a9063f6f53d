"""What the correction-method studies share: a small sensor, its calibration, frames at
given FPA and housing temperatures, responsivity, NETD and the residual metrics.

Units: residuals are the spatial standard deviation of a corrected uniform scene over the
good pixels (the fixed pattern left), in output codes (LSB) and in millikelvin of scene
temperature, ``mK = 1000 * LSB / R``, with R the corrected image's responsivity (output
codes per K) measured from the calibration frames at two scene temperatures. The NETD is
the temporal noise over the same responsivity (:func:`netd_mK`).

Frames come from the physics model in its steady state, one configuration per
(FPA, housing) temperature pair, the same seed (so the same pixels) everywhere. A drift
sequence of the model (``model.sequence``) gives the same frames when its thermal model is
``steady``; the studies take their temperatures as arguments so that either source fits.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: The configurations the studies compare, one per method and the compositions.
METHOD_CONFIGS: tuple[str, ...] = ("onepoint14", "typical14", "piecewise14", "quadratic14",
                                   "tcoffset14", "tcgain14", "table14", "drift14")

#: The default calibration plan of the studies (the issue's plan, 2 frames per point).
PLAN = {"scene": (290.0, 330.0, 370.0), "fpa": (288.0, 298.0, 308.0), "frames": 2}


@dataclass(frozen=True)
class StudySensor:
    """The sensor a study images: a preset with overrides, and the seed of every draw.

    ``rows`` x ``cols`` keeps the studies fast; the methods are per pixel, so the array size
    changes only the statistics.
    """

    preset: str | Mapping[str, Any] = "default"
    rows: int = 48
    cols: int = 64
    seed: int = 3
    overrides: Mapping[str, Any] = field(default_factory=dict)

    def config(self, fpa_K: float, cam_K: float, noise: bool = False) -> dict[str, Any]:
        from irnuc.nuc_fixed.plan import sensor_config

        ov = {"fpa.active_rows": self.rows, "fpa.active_cols": self.cols, **self.overrides,
              "environment.T_substrate": float(fpa_K), "environment.T_cam": float(cam_K)}
        if noise:
            ov["noise.enabled"] = True
        return sensor_config(self.preset, ov)

    def base_overrides(self) -> dict[str, Any]:
        return {"fpa.active_rows": self.rows, "fpa.active_cols": self.cols, **self.overrides}


def frames_at(sensor: StudySensor, fpa_K: float, cam_K: float, scenes: Sequence[float],
              repeats: int = 1, noise: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Raw codes (len(scenes) * repeats, H, W) and blind codes (..., K) of uniform scenes."""
    from irnuc import model

    fr = model.simulate(sensor.config(fpa_K, cam_K, noise), list(scenes), seed=sensor.seed,
                        repeats=repeats, outputs=["codes", "blind_codes"])
    return fr.codes, np.asarray(fr.blind_codes)


def calibrate_methods(sensor: StudySensor, names: Sequence[str], plan: Mapping[str, Any] = PLAN,
                      drift_cam: Sequence[float] = (), reference_fpa: float | None = None,
                      cfg_changes: Mapping[str, Mapping[str, Any]] | None = None
                      ) -> dict[str, Any]:
    """Run one calibration plan on the model and calibrate every named configuration."""
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan

    p = CalibrationPlan(scene=tuple(plan["scene"]), fpa=tuple(plan["fpa"]),
                        frames=int(plan["frames"]), drift_cam=tuple(drift_cam),
                        reference_fpa=reference_fpa)
    pts = run_plan(p, sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    cals = {}
    for n in names:
        cfg = load_pipeline(n)
        if cfg_changes and n in cfg_changes:
            cfg = cfg.replace(**cfg_changes[n])
        cals[n] = calibrate_points(pts, cfg)
    return {"points": pts, "cal": cals, "plan": p}


def responsivity(targets: Sequence[float], scenes: Sequence[float]) -> Callable[[float], float]:
    """R(T), output codes per K of the corrected image: the slope of the calibration
    targets (the corrected level of each scene) between the two scene temperatures
    around T (the end pair outside)."""
    t = np.asarray(targets, dtype=np.float64)
    s = np.asarray(scenes, dtype=np.float64)

    def r(scene_K: float) -> float:
        i = int(np.clip(np.searchsorted(s, scene_K) - 1, 0, len(s) - 2))
        return float((t[i + 1] - t[i]) / (s[i + 1] - s[i]))

    return r


def netd_mK(sensor: StudySensor, fpa_K: float, scene_K: float, resp_out: float,
            frames: int = 16, out_per_adc: float = 1.0) -> float:
    """NETD, mK: the median temporal noise of a pixel over ``frames`` frames of a uniform
    scene (the model's noise switched on), over the responsivity (output codes per K).

    The model's own NETD, when it gives one (``model.netd``), is the hook to use instead.
    """
    from irnuc import model

    hook = getattr(model, "netd", None)
    if callable(hook):  # the drift-sequence work's figure, once it exists
        return float(hook(sensor.config(fpa_K, fpa_K, noise=True), scene_K)) * 1000.0
    codes, _ = frames_at(sensor, fpa_K, fpa_K, [scene_K], repeats=frames, noise=True)
    sd = float(np.median(codes.astype(np.float64).std(axis=0, ddof=1)))
    return 1000.0 * sd * out_per_adc / resp_out


def fpn(y: np.ndarray, good: np.ndarray) -> float:
    """The fixed pattern left in a corrected uniform frame: spatial std over good pixels."""
    return float(np.asarray(y, dtype=np.float64)[good].std())


def memory_bits(cfg: Any) -> dict[str, int]:
    """Coefficient memory per pixel (bits, calibration and runtime) and the bits read per
    pixel per frame (table_interp reads two of its tables, ffc its correction)."""
    cal = sum(m.word_bits for m in cfg.memories.values() if m.source == "calibration")
    run = sum(m.word_bits for m in cfg.memories.values() if m.source == "runtime")
    tables = [m for m in cfg.memories.values() if m.name.startswith("table")]
    read = sum(m.word_bits for m in cfg.memories.values()
               if m.source == "calibration" and not m.name.startswith("table"))
    read += 2 * tables[0].word_bits if tables else 0
    read += sum(m.word_bits for m in cfg.memories.values() if m.name == "ffc_offset")
    return {"calibration_bits": cal, "runtime_bits": run, "read_bits_per_frame": read}


def pyplot() -> Any:
    """matplotlib.pyplot on the Agg backend (no window)."""
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    return plt
