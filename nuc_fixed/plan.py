"""Calibration plans: scene temperatures x FPA (and housing) temperatures x frames.

A plan (TOML, ``docs/methods.md``)::

    [plan]
    scene = [290.0, 330.0, 370.0]     # K, blackbody temperatures
    fpa = [288.0, 298.0, 308.0]       # K, FPA (substrate) temperatures
    housing_offset = [-5.0, 0.0, 5.0] # K, the housing relative to the FPA (optional)
    frames = 4                        # per point

is run on the physics model (:func:`run_plan`: one model configuration per (FPA, housing)
point, the same seed, so the same pixels, at every point) or gathered from frames that carry
the per-frame fields (:func:`points_from_frames`). Either way the result is
:class:`PointFrames`, the input of :func:`irnuc.nuc_fixed.fit.calibrate_points`. Without
``housing_offset`` (or ``cam``) the housing is at the FPA temperature at every point; with
it, every FPA temperature is imaged at every housing offset (every combination).
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.common import schema
from irnuc.common.errors import UserError
from irnuc.model.fpa_sensor import FpaSensor, HousingSensor


class PlanError(UserError):
    """A calibration plan is malformed or cannot be run."""


_SENSOR_FIELDS = {"bits": schema.number(1, 24, integer=True, unit="bits"),
                  "lsb_K": schema.number(0.0, 100.0, lo_open=True, unit="K"),
                  "zero_K": schema.number(0.0, 1000.0, unit="K"),
                  "offset_K": schema.number(-100.0, 100.0, unit="K"),
                  "noise_K": schema.number(0.0, 100.0, unit="K"),
                  "lag_s": schema.number(0.0, 1e8, unit="s")}

def _model_range(key: str) -> dict[str, Any]:
    """The range the sensor model takes for an environment temperature: a plan value the
    model would refuse after the work is refused when the plan is read, named by its key."""
    from irnuc.model.config import SCHEMA

    f = SCHEMA[key]
    return schema.number(f.lo, f.hi, lo_open=f.lo_open, hi_open=f.hi_open, unit="K")


def _temps(items: dict[str, Any]) -> dict[str, Any]:
    return {"type": "array", "minItems": 1, "maxItems": 64, "items": items}


_TEMPS = _temps(schema.number(100.0, 1000.0, unit="K"))
_FPA_TEMPS = _temps(_model_range("environment.T_substrate"))
_CAM_TEMPS = _temps(_model_range("environment.T_cam"))
_HOUSING_FIELDS = {**_SENSOR_FIELDS, "lag_s": schema.number(0.0, 1e8, unit="s"),
                   "node": {"enum": ["housing", "lens", "shutter"]}}

#: The schema of a plan file: [plan] required, [fpa_sensor] optional.
PLAN_SCHEMA: dict[str, Any] = schema.table({
    "plan": schema.table({
        "scene": _TEMPS,
        "fpa": _FPA_TEMPS,
        "frames": schema.number(1, 10000, integer=True, unit="frames"),
        "cam": {**_CAM_TEMPS, "description": "housing temperature per FPA point (default: fpa)"},
        "reference_fpa": _model_range("environment.T_substrate"),
        "drift_cam": {**_CAM_TEMPS, "description": "housing temperatures at the reference FPA "
                      "point, for blind_drift's coupling"},
        "housing_offset": {"type": "array", "minItems": 1, "maxItems": 64,
                           "items": schema.number(-100.0, 100.0, unit="K"),
                           "description": "housing temperatures relative to the FPA, every "
                                          "combination with plan.fpa"},
        "description": {"type": "string"},
    }, required=["scene", "fpa", "frames"]),
    "fpa_sensor": schema.table(_SENSOR_FIELDS),
    "housing_sensor": schema.table(_HOUSING_FIELDS),
}, required=["plan"])


@dataclass(frozen=True)
class CalibrationPlan:
    """Scene temperatures x FPA temperatures x frames per point.

    Attributes
    ----------
    scene : tuple of float
        Blackbody temperatures, K, increasing.
    fpa : tuple of float
        FPA (substrate) temperatures, K, increasing.
    frames : int
        Frames per (scene, FPA) point.
    cam : tuple of float
        Housing temperature at each FPA point, K (default: the FPA temperature).
    reference_fpa : float
        The FPA temperature whose calibration the methods without temperature
        compensation use, and at which the targets are taken; default: the listed FPA
        temperature nearest their mean.
    drift_cam : tuple of float
        Housing temperatures, K, imaged at the reference FPA temperature and the middle
        scene: the points from which blind_drift measures how the image follows the blind
        pixels (without them the coupling is 1, as in the paper repository).
    fpa_sensor : FpaSensor
        The on-die sensor that reads each frame's FPA temperature.
    housing_offset : tuple of float
        Housing temperatures relative to the FPA, K: every FPA temperature is imaged at
        every offset (the points FPA-major); empty: the housing at ``cam`` (or the FPA).
    housing_sensor : HousingSensor
        The sensor that reads each frame's housing temperature.
    """

    scene: tuple[float, ...]
    fpa: tuple[float, ...]
    frames: int
    cam: tuple[float, ...] = ()
    reference_fpa: float | None = None
    drift_cam: tuple[float, ...] = ()
    fpa_sensor: FpaSensor = field(default_factory=FpaSensor)
    source: str = "plan"
    housing_offset: tuple[float, ...] = ()
    housing_sensor: HousingSensor = field(default_factory=HousingSensor)

    def __post_init__(self) -> None:
        for name in ("scene", "fpa", "housing_offset"):
            v = list(getattr(self, name))
            if any(b <= a for a, b in itertools.pairwise(v)):
                raise PlanError(f"{self.source}: plan.{name} = {v} must increase strictly")
        if self.cam and len(self.cam) != len(self.fpa):
            raise PlanError(f"{self.source}: plan.cam has {len(self.cam)} values but plan.fpa "
                            f"has {len(self.fpa)}; one housing temperature per FPA point")
        if self.cam and self.housing_offset:
            raise PlanError(f"{self.source}: plan.cam and plan.housing_offset both set the "
                            "housing; give one of them")
        if self.reference_fpa is not None and self.reference_fpa not in self.fpa:
            raise PlanError(f"{self.source}: plan.reference_fpa = {self.reference_fpa:g} K is "
                            f"not one of plan.fpa ({', '.join(f'{t:g}' for t in self.fpa)})")

    @property
    def cam_K(self) -> tuple[float, ...]:
        """The housing temperature of each FPA point at the reference offset, K."""
        if self.cam:
            return tuple(self.cam)
        return tuple(t + self.reference_offset for t in self.fpa)

    @property
    def reference_offset(self) -> float:
        """The housing offset the methods that do not model the housing calibrate at: 0 if
        listed, else the offset nearest 0 (K)."""
        if not self.housing_offset:
            return 0.0
        return min(self.housing_offset, key=lambda o: (abs(o), o))

    def points(self) -> list[tuple[float, float]]:
        """(FPA, housing) temperature of every point, K, FPA-major."""
        if self.housing_offset:
            return [(f, f + o) for f in self.fpa for o in self.housing_offset]
        return list(zip(self.fpa, self.cam_K, strict=True))

    @property
    def reference_index(self) -> int:
        """Index in ``fpa`` of the reference FPA point."""
        if self.reference_fpa is not None:
            return list(self.fpa).index(self.reference_fpa)
        mean = float(np.mean(self.fpa))
        return int(np.argmin([abs(t - mean) for t in self.fpa]))

    @property
    def reference_point(self) -> int:
        """Index in :meth:`points` of the reference point (reference FPA, reference
        housing offset)."""
        if not self.housing_offset:
            return self.reference_index
        return (self.reference_index * len(self.housing_offset)
                + list(self.housing_offset).index(self.reference_offset))


def load_plan(path: str | Path, flag: str = "--plan") -> CalibrationPlan:
    """Read and check a plan TOML file (unknown keys refused with the nearest name)."""
    doc = schema.read_toml(path, flag)
    src = f"{flag} {path}" if flag else str(path)
    try:
        schema.check(doc, PLAN_SCHEMA, source=src)
    except schema.SchemaError as exc:
        raise PlanError(str(exc)) from None
    p = doc["plan"]
    from irnuc.model.validate import ConfigError

    try:
        sensor = FpaSensor.from_dict(dict(doc.get("fpa_sensor", {})))
        hsensor = HousingSensor.from_dict(dict(doc.get("housing_sensor", {})))
    except ConfigError as exc:
        raise PlanError(f"{src}: {exc}") from None
    return CalibrationPlan(scene=tuple(float(t) for t in p["scene"]),
                           fpa=tuple(float(t) for t in p["fpa"]), frames=int(p["frames"]),
                           cam=tuple(float(t) for t in p.get("cam", ())),
                           reference_fpa=p.get("reference_fpa"),
                           drift_cam=tuple(float(t) for t in p.get("drift_cam", ())),
                           fpa_sensor=sensor, source=src,
                           housing_offset=tuple(float(t) for t in p.get("housing_offset", ())),
                           housing_sensor=hsensor)


@dataclass
class PointFrames:
    """Calibration frames grouped by point: (FPA, housing) point p, scene s, frame m.

    Attributes
    ----------
    codes : (P, S, M, H, W) integer ADC codes
    scene_K : (S,) K; fpa_K : (P,) K
    reading : (P, S, M) int64 FPA sensor readings
    housing_K : (P,) K, the housing temperature of each point (None: at the FPA's)
    housing_reading : (P, S, M) int64 housing sensor readings, or None
    blind_codes : (P, S, M, K) blind pixel codes, or None
    defect_kind : (H, W) the model's planted defects (0 = good), or None
    reference : index of the reference FPA point
    drift_codes, drift_blind : (D, M, H, W) and (D, M, K), the frames of the plan's
        ``drift_cam`` points (reference FPA temperature, middle scene), or None
    drift_cam_K : (D,) their housing temperatures, K
    """

    codes: np.ndarray
    scene_K: np.ndarray
    fpa_K: np.ndarray
    reading: np.ndarray
    adc_bits: int
    reference: int
    blind_codes: np.ndarray | None = None
    defect_kind: np.ndarray | None = None
    source: str = ""
    drift_codes: np.ndarray | None = None
    drift_blind: np.ndarray | None = None
    drift_cam_K: np.ndarray | None = None
    housing_K: np.ndarray | None = None
    housing_reading: np.ndarray | None = None

    @property
    def shape(self) -> tuple[int, int]:
        return tuple(self.codes.shape[-2:])  # type: ignore[return-value]

    def point_reading(self, p: int) -> int:
        """The FPA reading of point p: the rounded mean of its frames' readings."""
        return int(np.floor(float(np.mean(self.reading[p])) + 0.5))

    def point_housing_reading(self, p: int) -> int | None:
        """The housing reading of point p (rounded mean), or None without readings."""
        if self.housing_reading is None:
            return None
        return int(np.floor(float(np.mean(self.housing_reading[p])) + 0.5))

    def fpa_points(self) -> PointFrames:
        """The points a method that does not model the housing calibrates on: one per FPA
        temperature, each at the reference point's housing offset (the housing minus the
        FPA; its own when the plan has none). The housing being where the method assumes
        it, the others are kept for the residuals (and for methods that read the
        housing)."""
        if self.housing_K is None or len(np.unique(np.round(self.fpa_K, 6))) == len(self.fpa_K):
            return self
        off = np.round(self.housing_K - self.fpa_K, 6)
        ref_off = off[self.reference]
        keep = np.flatnonzero(np.isclose(off, ref_off, atol=1e-6))
        if len(np.unique(np.round(self.fpa_K[keep], 6))) != keep.size:
            raise PlanError(f"{self.source}: two points share an FPA temperature and the housing "
                            "offset of the reference point")
        def sel(a: np.ndarray | None) -> np.ndarray | None:
            return None if a is None else a[keep]

        return replace(self, codes=self.codes[keep], fpa_K=self.fpa_K[keep],
                       reading=self.reading[keep], blind_codes=sel(self.blind_codes),
                       housing_K=self.housing_K[keep],
                       housing_reading=sel(self.housing_reading),
                       reference=int(np.flatnonzero(keep == self.reference)[0]))


def sensor_config(sensor: str | Mapping[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    from irnuc import model

    if isinstance(sensor, Mapping):
        from irnuc.model.config import apply_overrides, validate

        return validate(apply_overrides(dict(sensor), overrides), "sensor with plan overrides")
    if str(sensor).endswith(".toml") or "/" in str(sensor):
        return model.load_config(sensor, overrides)
    return model.load_preset(str(sensor), overrides)


def run_plan(plan: CalibrationPlan, sensor: str | Mapping[str, Any] = "default",
             overrides: Mapping[str, Any] | None = None, seed: int = 0) -> PointFrames:
    """Simulate every point of the plan on the physics model.

    Per (FPA, housing) point (:meth:`CalibrationPlan.points`) the sensor configuration gets
    ``environment.T_substrate`` = the FPA temperature and ``environment.T_cam`` = the housing
    temperature (the FPA's plus the offset, ``plan.cam``, or the FPA's); the same ``seed``
    everywhere, so every point images the same pixels. The FPA and housing readings of
    every frame are ``plan.fpa_sensor`` / ``plan.housing_sensor`` of those temperatures
    (their noise seeded by ``seed`` and the frame's index in the plan); the frames' own
    noise (a sensor with ``noise.enabled``) is drawn the same way, each frame of the plan
    at its own index, so no two points share a draw.

    Parameters
    ----------
    sensor : str or dict
        A preset name, a sensor TOML path, or a validated configuration.
    overrides : dict
        Dotted sensor overrides (``fpa.active_rows`` ...); the plan's own fields
        (``environment.T_substrate``, ``environment.T_cam``) may not be among them.
    """
    from irnuc import model

    ov = dict(overrides or {})
    for k in ("environment.T_substrate", "environment.T_cam"):
        if k in ov:
            raise PlanError(f"--set {k}: the plan sets it at every point (plan.fpa / plan.cam)")
    want_blind = "blind_codes" in model.OUTPUTS
    codes, readings, hreadings, blinds = [], [], [], []
    kind = None
    n_pt = len(plan.scene) * plan.frames
    points = plan.points()
    shape = (len(plan.scene), plan.frames)
    for p, (t_fpa, t_cam) in enumerate(points):
        cfg = sensor_config(sensor, {**ov, "environment.T_substrate": t_fpa,
                                      "environment.T_cam": t_cam})
        outputs = ["codes", "blind_codes"] if want_blind else ["codes"]
        # each point its own frame range: independent noise, as the sensors' readings
        fr = model.simulate(cfg, list(plan.scene), seed=seed, repeats=plan.frames,
                            outputs=outputs, first_frame=p * n_pt)
        h, w = fr.codes.shape[-2:]
        codes.append(fr.codes.reshape(*shape, h, w))
        readings.append(plan.fpa_sensor.read(np.full(n_pt, t_fpa), seed=seed,
                                             first_frame=p * n_pt,
                                             warn="plan: the FPA sensor").reshape(shape))
        hreadings.append(plan.housing_sensor.read(np.full(n_pt, t_cam), seed=seed,
                                                  first_frame=p * n_pt,
                                                  warn="plan: the housing sensor").reshape(shape))
        b = getattr(fr, "blind_codes", None)
        if b is not None and np.size(b):
            blinds.append(np.asarray(b).reshape(*shape, -1))
        kind = fr.defect_kind
        adc = int(fr.adc_bits)
    out = PointFrames(codes=np.stack(codes), scene_K=np.asarray(plan.scene),
                      fpa_K=np.asarray([f for f, _ in points]), reading=np.stack(readings),
                      adc_bits=adc, reference=plan.reference_point,
                      blind_codes=np.stack(blinds) if len(blinds) == len(points) else None,
                      defect_kind=kind, source=plan.source,
                      housing_K=np.asarray([c for _, c in points]),
                      housing_reading=np.stack(hreadings))
    if plan.drift_cam and want_blind:
        t_ref = plan.fpa[plan.reference_index]
        mid = plan.scene[len(plan.scene) // 2]
        dc, db = [], []
        for d, t_cam in enumerate(plan.drift_cam):
            cfg = sensor_config(sensor, {**ov, "environment.T_substrate": t_ref,
                                          "environment.T_cam": t_cam})
            fr = model.simulate(cfg, [mid], seed=seed, repeats=plan.frames,
                                outputs=["codes", "blind_codes"],
                                first_frame=len(points) * n_pt + d * plan.frames)
            dc.append(fr.codes)
            db.append(np.asarray(fr.blind_codes))
        out.drift_codes, out.drift_blind = np.stack(dc), np.stack(db)
        out.drift_cam_K = np.asarray(plan.drift_cam)
    return out


def _point_name(point: tuple[float, float]) -> str:
    """'FPA 300 K' (the housing at the FPA), else 'FPA 300 K, housing 305 K'."""
    f, c = point
    return f"FPA {f:g} K" if c == f else f"FPA {f:g} K, housing {c:g} K"


def points_from_frames(data: Mapping[str, Any], source: str = "--frames",
                       reference_fpa: float | None = None) -> PointFrames:
    """Group frames (a frames file's arrays) into calibration points.

    Frames are grouped by their scene temperature (``scene_K``, else ``temps``), FPA
    temperature (``fpa_K``; a file without it is one FPA point) and housing temperature
    (``T_cam_K``); shutter frames are left out. Every scene must be imaged at every (FPA,
    housing) point, and every point must hold the same number of frames
    (:class:`PlanError` naming the points that differ: dropping frames would bias their
    means). ``fpa_reading`` and ``housing_reading`` give the readings (the FPA's needed by
    the temperature methods, which say so). The reference point: the FPA temperature
    nearest the mean (or ``reference_fpa``), at the housing nearest the FPA.
    """
    codes = np.asarray(data["codes"])
    n = codes.shape[0]
    scene = np.asarray(data["scene_K"] if "scene_K" in data else data["temps"], dtype=np.float64)
    fpa = np.asarray(data["fpa_K"], dtype=np.float64) if "fpa_K" in data else np.zeros(n)
    cam = np.asarray(data["T_cam_K"], dtype=np.float64) if "T_cam_K" in data else fpa.copy()
    keep = ~np.asarray(data["shutter"], bool) if "shutter" in data else np.ones(n, bool)
    reading = (np.asarray(data["fpa_reading"], dtype=np.int64) if "fpa_reading" in data
               else np.full(n, -1, np.int64))
    hreading = (np.asarray(data["housing_reading"], dtype=np.int64)
                if "housing_reading" in data else None)
    blind = np.asarray(data["blind_codes"]) if "blind_codes" in data else None
    if blind is not None and (blind.ndim != 2 or blind.shape[1] == 0):
        blind = None  # a file without reference pixels
    s_vals = np.unique(np.round(scene[keep], 6))
    pairs = sorted({(round(float(f), 6), round(float(c), 6))
                    for f, c in zip(fpa[keep], cam[keep], strict=True)})
    groups = {}
    for p, (tf, tc) in enumerate(pairs):
        for s, ts in enumerate(s_vals):
            idx = np.flatnonzero(keep & np.isclose(scene, ts, atol=1e-6)
                                 & np.isclose(fpa, tf, atol=1e-6) & np.isclose(cam, tc, atol=1e-6))
            if idx.size == 0:
                raise PlanError(f"{source}: no frame at scene {ts:g} K with the FPA at "
                                f"{tf:g} K and the housing at {tc:g} K; every scene must be "
                                "imaged at every (FPA, housing) point")
            groups[(p, s)] = idx
    counts = {k: v.size for k, v in groups.items()}
    m = min(counts.values())
    if max(counts.values()) != m:
        (p0, s0), (p1, s1) = min(counts, key=counts.get), max(counts, key=counts.get)
        raise PlanError(f"{source}: {counts[(p1, s1)]} frames at scene {s_vals[s1]:g} K, "
                        f"{_point_name(pairs[p1])} but {m} at scene {s_vals[s0]:g} K, "
                        f"{_point_name(pairs[p0])}; every calibration point needs the same "
                        "number of frames (shutter frames not counted)")
    P, S = len(pairs), len(s_vals)
    sel = np.array([[groups[(p, s)][:m] for s in range(S)] for p in range(P)])
    f_pts = np.array([f for f, _ in pairs])
    c_pts = np.array([c for _, c in pairs])
    f_vals = np.unique(f_pts)
    t_ref = (f_vals[int(np.argmin(np.abs(f_vals - np.mean(f_vals))))] if reference_fpa is None
             else f_vals[int(np.argmin(np.abs(f_vals - reference_fpa)))])
    at_ref = np.flatnonzero(f_pts == t_ref)
    ref = int(at_ref[np.argmin(np.abs(c_pts[at_ref] - t_ref))])
    return PointFrames(codes=codes[sel], scene_K=s_vals, fpa_K=f_pts, reading=reading[sel],
                       adc_bits=int(data["adc_bits"]), reference=ref,
                       blind_codes=None if blind is None else blind[sel],
                       defect_kind=data.get("defect_kind"), source=source,
                       housing_K=c_pts, housing_reading=None if hreading is None else hreading[sel])
