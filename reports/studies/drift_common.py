"""What the correction-method studies share: a small sensor, its calibration, frames at
given FPA and housing temperatures, responsivity, NETD and the residual metrics.

Units: residuals are the spatial standard deviation of a corrected uniform scene over the
good pixels (the fixed pattern left), in output codes (LSB) and in millikelvin of scene
temperature through the corrected image's own (local) responsivity at that FPA, housing
and scene, with the level error beside it: :func:`irnuc.reports.studies.metrics.residuals_mK`,
the one conversion, on frames at each scene and 0.5 K either side (:func:`slope_frames`).
The NETD beside them is the model's closed form at a 300 K scene, the sensor's F-number and
frame rate, with the pixels' spread (:func:`netd`).

Frames come from the physics model in its steady state, one configuration per
(FPA, housing) temperature pair, the same seed (so the same pixels) everywhere. A drift
sequence of the model (``model.sequence``) gives the same frames when its thermal model is
``steady``; the studies take their temperatures as arguments so that either source fits.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
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


def slope_frames(sensor: StudySensor, fpa_K: float, cam_K: float, scenes: Sequence[float],
                 noise: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Raw codes (3 S, H, W) and blind codes of uniform scenes, each scene followed by its
    neighbours 0.5 K below and above (:func:`metrics.slope_scenes`): what
    :func:`metrics.residuals_mK` needs to convert to mK at this camera state."""
    from irnuc.reports.studies.metrics import slope_scenes

    return frames_at(sensor, fpa_K, cam_K, slope_scenes(scenes), noise=noise)


def scale(sensor: StudySensor, targets: Sequence[float], scenes: Sequence[float]) -> Any:
    """The calibration's temperature scale (:class:`metrics.TemperatureScale`) on the
    sensor's band."""
    from irnuc.reports.studies.metrics import TemperatureScale

    band = sensor.config(300.0, 300.0)["radiometry"]["band"]
    return TemperatureScale(targets, scenes, band)


def residuals(y: np.ndarray, good: np.ndarray, scenes: Sequence[float], sc: Any
              ) -> list[dict[str, float]]:
    """:func:`metrics.residuals_mK` (frames of :func:`slope_frames`, corrected)."""
    from irnuc.reports.studies.metrics import residuals_mK

    return residuals_mK(y, good, scenes, sc)


def netd(sensor: StudySensor, fpa_K: float, cam_K: float | None = None) -> Any:
    """The sensor's closed-form NETD (:func:`model.netd`) at a 300 K scene, its F-number
    and frame rate, the FPA (and housing, default the FPA's) temperature, every noise
    source on: a :class:`model.noise_metrics.Netd` (``netd_K``, its pixels' spread)."""
    from irnuc import model
    from irnuc.model.noise_metrics import NETD_SCENE_K

    cam = fpa_K if cam_K is None else cam_K
    return model.netd(sensor.config(fpa_K, cam, noise=True), NETD_SCENE_K, seed=sensor.seed,
                      T_substrate=float(fpa_K), T_cam=float(cam))


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
