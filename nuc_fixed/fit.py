"""Calibration of every method over scene and FPA temperature (docs/methods.md).

:func:`calibrate_points` takes the frames of a calibration plan (:class:`PointFrames`)
and, for the configuration's method:

1. takes the per-pixel mean of each (FPA, scene) point and the bad-pixel map over all
   points (the response checks of ``badpix`` at every FPA point, lowest and highest scene,
   OR-ed; offset outliers of the reference point's two-point offsets);
2. sets the targets T_s (output codes of scene s): the mean over pre-good pixels at the
   reference FPA point, times 2^(B - A), the same at every FPA point (so a corrected
   pixel reads the same whatever the FPA temperature);
3. fits the method's float coefficients by least squares (``fit_<method>`` below),
   quantizing the global registers and the coefficients other fits depend on first, so
   the dependent ones absorb that quantization;
4. quantizes every coefficient to its format (rounding of the format, or ``rounding``;
   saturating) and flags the pixels whose coefficient saturates (GAIN_RANGE,
   OFFSET_RANGE, COEFF_RANGE); refuses a format too narrow for the fitted range (more
   than ``max_saturated`` of the pre-good pixels saturate) in one line;
5. gives flagged pixels the median code of the good pixels, field by field;
6. reports the needed range and saturation per coefficient, and the residual of the
   quantized method and of its float fit at every calibration point.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from irnuc.common.errors import UserError
from irnuc.nuc_fixed.badpix import (
    DetectionThresholds,
    Reason,
    detect_offset_outliers,
    detect_response,
    load_thresholds,
    stack_stats,
)
from irnuc.nuc_fixed.config import ROUNDING_MODES, ConfigError, PipelineConfig
from irnuc.nuc_fixed.dpc import uncorrectable
from irnuc.nuc_fixed.fixed import FixedFormat
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, method_top
from irnuc.nuc_fixed.plan import PlanError, PointFrames
from irnuc.nuc_fixed.validate import InputError, as_config, check_frame_shape

_NOT_CALIBRATABLE = (Reason.STUCK | Reason.RAIL | Reason.EQUAL_RESPONSE | Reason.UNRESPONSIVE
                     | Reason.OVER_RESPONSIVE)


class FormatRangeError(UserError):
    """A coefficient format is too narrow for the range calibration fitted."""


@dataclass(frozen=True)
class MethodCalibration:
    """Result of :func:`calibrate_points`.

    Attributes
    ----------
    coeffs : MethodCoefficients
        Quantized codes (flagged pixels filled) and registers: what the memory image holds.
    reasons : (H, W) uint16
        :class:`~irnuc.nuc_fixed.badpix.Reason` bits (0 = good).
    floats : dict
        The unquantized fit, ``"memory.field"`` -> (H, W) float64, and the registers.
    targets : (S,) float64
        Output level of each scene, output codes.
    summary : dict
        JSON-ready report (ranges, saturation, residuals, bad pixels).
    """

    coeffs: MethodCoefficients
    reasons: np.ndarray
    floats: dict[str, Any]
    targets: np.ndarray
    summary: dict[str, Any] = field(default_factory=dict)

    @property
    def cfg(self) -> PipelineConfig:
        return self.coeffs.cfg

    @property
    def bad(self) -> np.ndarray:
        return self.coeffs.bad


# ---- least-squares pieces ---------------------------------------------------------------

def _targets(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    tt = np.asarray(t, dtype=np.float64)
    return tt.reshape(-1, *([1] * (x.ndim - 1))) if tt.ndim == 1 else tt


def ls_line(x: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per-pixel least-squares line t = g x + o over the first axis (x (S, H, W); t (S,)
    or per pixel (S, H, W)).

    Two points: the two-point formula. A pixel whose x does not vary gets g = 0.
    """
    tt = _targets(t, x)
    xm = x.mean(axis=0)
    tm = tt.mean(axis=0)
    sxx = ((x - xm) ** 2).sum(axis=0)
    sxt = ((x - xm) * (tt - tm)).sum(axis=0)
    g = np.divide(sxt, sxx, out=np.zeros_like(sxx), where=sxx > 0)
    return g, tm - g * xm


def ls_fixed_gain(x: np.ndarray, t: np.ndarray, g: np.ndarray | float) -> np.ndarray:
    """Least-squares offset for a fixed gain: mean over the first axis of t - g x."""
    return (_targets(t, x) - g * x).mean(axis=0)


def ls_poly(v: np.ndarray, y: np.ndarray, regressors: np.ndarray) -> np.ndarray:
    """Per-pixel least squares y_p = sum_k c_k r_k(v_p) (y (P, H, W), regressors (P, K)).

    Returns (K, H, W). ``numpy.linalg.lstsq`` on all pixels at once.
    """
    p = y.shape[0]
    sol = np.linalg.lstsq(regressors, y.reshape(p, -1), rcond=None)[0]
    return sol.reshape(regressors.shape[1], *y.shape[1:])


def piecewise_fit(x: np.ndarray, t: np.ndarray, knee: np.ndarray | None = None,
                  level: float | None = None) -> tuple[Any, Any, np.ndarray, np.ndarray]:
    """Two least-squares segments through the knee (x (S, H, W) increasing with s, t (S,)).

    The knee is the middle scene's code x[S // 2] (the paper repository's middle point)
    and its output the middle target, unless given (calibration passes their quantized
    values). Each segment's gain is the least-squares slope through the knee of the scenes
    on its side: with three scenes, the two-point gain of each pair.
    """
    mid = len(t) // 2
    k = x[mid] if knee is None else knee
    lv = float(t[mid]) if level is None else float(level)
    gains = []
    for sel in (slice(0, mid), slice(mid + 1, None)):
        dx = x[sel] - k
        dt = (np.asarray(t, dtype=np.float64)[sel] - lv).reshape(-1, *([1] * (x.ndim - 1)))
        sxx = (dx * dx).sum(axis=0)
        gains.append(np.divide((dx * dt).sum(axis=0), sxx, out=np.zeros_like(sxx),
                               where=sxx > 0))
    return k, lv, gains[0], gains[1]


def quadratic_fit(x: np.ndarray, t: np.ndarray, adc_bits: int) -> tuple[np.ndarray, ...]:
    """Per-pixel least squares t = q xi^2 + b xi + c, xi = x / 2^A (x (S, H, W)).

    Returns (q, g = b / 2^A, c). Three scenes: the quadratic through the three points.
    """
    xi = x / float(1 << adc_bits)
    s = x.shape[0]
    a = np.stack([xi**2, xi, np.ones_like(xi)], axis=-1)          # (S, H, W, 3)
    a = np.moveaxis(a, 0, -2)                                      # (H, W, S, 3)
    ata = a.swapaxes(-1, -2) @ a                                   # (H, W, 3, 3)
    atb = a.swapaxes(-1, -2) @ np.broadcast_to(np.asarray(t, float), (*x.shape[1:], s))[..., None]
    ok = np.abs(np.linalg.det(ata)) > 1e-300
    sol = np.zeros((*x.shape[1:], 3))
    sol[ok] = np.linalg.solve(ata[ok], atb[ok])[..., 0]
    return sol[..., 0], sol[..., 1] / float(1 << adc_bits), sol[..., 2]


# ---- the method fits: float coefficients, quantized in dependency order -------------------

class _Q:
    """Quantizes coefficients and registers to their formats, recording overflow."""

    def __init__(self, cfg: PipelineConfig, rounding: str | None) -> None:
        self.cfg = cfg
        self.rounding = rounding
        self.codes: dict[str, np.ndarray] = {}
        self.over: dict[str, np.ndarray] = {}
        self.floats: dict[str, Any] = {}
        self.regs: dict[str, Any] = {}

    def fmt(self, name: str) -> tuple[FixedFormat, str]:
        f = self.cfg.format(name)
        rnd = self.rounding or (f.rounding if name not in ("gain", "offset") else "half_even")
        return FixedFormat(f.int_bits, f.frac_bits, f.signed), rnd

    def field(self, key: str, fmt_name: str, values: np.ndarray) -> np.ndarray:
        """Quantize a per-pixel field; return the value of its codes (float)."""
        ff, rnd = self.fmt(fmt_name)
        v = np.nan_to_num(np.asarray(values, dtype=np.float64))
        codes, over = ff.quantize(v, rnd)
        self.codes[key], self.over[key], self.floats[key] = codes, over, v
        return ff.to_value(codes)

    def register(self, name: str, fmt_name: str | None, value: float | list[float],
                 bits: int = 0) -> Any:
        """Quantize a register (an unsigned integer of ``bits`` when ``fmt_name`` is None)."""
        vals = np.atleast_1d(np.asarray(value, dtype=np.float64))
        if fmt_name is None:
            ff, rnd = FixedFormat(bits, 0, False), "half_even"
        else:
            ff, rnd = self.fmt(fmt_name)
        codes, over = ff.quantize(vals, rnd)
        if over.any():
            raise FormatRangeError(
                f"pipeline {self.cfg.name!r}: register {name} = {vals[over][0]:.6g} does not "
                f"fit its format {ff}" + (f" (formats.{fmt_name})" if fmt_name else ""))
        self.floats[name] = vals.tolist() if np.ndim(value) else float(vals[0])
        out = tuple(int(c) for c in codes) if np.ndim(value) else int(codes[0])
        self.regs[name] = out
        return ff.to_value(codes) if np.ndim(value) else float(ff.to_value(codes)[0])


def check_readings(cfg: PipelineConfig, readings: list[int], reference: int, source: str,
                   sensor: str = "the FPA sensor") -> None:
    """:class:`PlanError` when the FPA readings of the calibration points (one per FPA
    point, ``reference`` the index of the reference point) cannot calibrate ``cfg``'s
    method (``MethodSpec.check_readings``: tc_offset needs ``tc_order`` + 1 distinct
    readings within ``reading_range_bits`` of the reference one, table_interp one distinct
    reading per table); a reading beyond ``reading_bits`` (:func:`check_reading_codes`).

    Run before the simulation on the readings the plan's temperatures give, and on the
    frames' readings before the fit.
    """
    cfg.base.check_readings(cfg, list(readings), reference, source, sensor)


def check_reading_codes(cfg: PipelineConfig, readings: list[int], need: int, what: str,
                        source: str, sensor: str) -> None:
    """The readings within ``reading_bits`` (:class:`FormatRangeError`), and at least
    ``need`` distinct ones (:class:`PlanError` saying ``what`` the method fits)."""
    top = (1 << int(cfg.reading_bits or 1)) - 1
    if max(readings) > top or min(readings) < 0:
        raise FormatRangeError(f"{source}: {sensor} reads {readings} at the FPA points; pipeline "
                        f"{cfg.name!r} has reading_bits = {cfg.reading_bits} (0..{top}): "
                        "use a pipeline whose reading_bits holds the sensor's readings")
    distinct = len(set(readings))
    if distinct < need:
        raise PlanError(f"{source}: {sensor} reads {readings} at the FPA points ({distinct} "
                        f"distinct); {what}: the sensor is too coarse for these temperatures "
                        "(a smaller fpa_sensor.lsb_K, or FPA points farther apart)")


def _fit(cfg: PipelineConfig, pts: PointFrames, means: np.ndarray, t: np.ndarray,
         good: np.ndarray, q: _Q) -> None:
    """Fit and quantize the base method's coefficients (``MethodSpec.fit``), then the
    stages' registers (``StageSpec.fit``: blind_drift's)."""
    cfg.base.fit(cfg, pts, means, t, q)
    for stage in cfg.parts[1:]:
        stage.fit(cfg, pts, means, good, q)


# ---- the float evaluation of a fit (for residuals and studies) ---------------------------

def float_correct(cal: MethodCalibration, x: np.ndarray,
                  reading: int | Mapping[str, int] | None = None,
                  blind_mean_change: float = 0.0) -> np.ndarray:
    """The method's real-valued output (output codes, unrounded, unclipped) for raw ``x``
    with the unquantized fit: the method's error without fixed point
    (``MethodSpec.float_correct`` on ``x`` less blind_drift's coupling times the change of
    the blind mean)."""
    from irnuc.nuc_fixed import methods

    cfg, f = cal.cfg, cal.floats
    xf = np.asarray(x, dtype=np.float64) - (f.get("drift_coupling", 0.0) * blind_mean_change
                                            if cfg.has("blind_drift") else 0.0)
    return cfg.base.float_correct(cfg, f, xf, methods.frame(cfg, reading))


# ---- the calibration ----------------------------------------------------------------------

def _needed(ff: FixedFormat, values: np.ndarray) -> dict[str, Any]:
    if values.size == 0:
        return {"min": None, "max": None, "int_bits_needed": None}
    lo, hi = float(values.min()), float(values.max())
    bits = None if (not ff.signed and lo < 0) else ff.bits_needed(lo, hi)
    return {"min": lo, "max": hi, "int_bits_needed": bits}


def _field_reason(fname: str) -> Reason:
    if fname.startswith("gain"):
        return Reason.GAIN_RANGE
    if fname == "offset":
        return Reason.OFFSET_RANGE
    return Reason.COEFF_RANGE


def calibrate_points(points: PointFrames, cfg: PipelineConfig | str,
                     thresholds: DetectionThresholds | None = None, rounding: str | None = None,
                     max_saturated: float = 0.01) -> MethodCalibration:
    """Fit, quantize and check the configuration's method on calibration points.

    Parameters
    ----------
    points : PointFrames
        Frames at every (FPA, scene) point (:func:`irnuc.nuc_fixed.plan.run_plan`).
    cfg : PipelineConfig or str
    thresholds : DetectionThresholds, optional
        Bad-pixel detection thresholds (default ``nuc_fixed/detection.toml``).
    rounding : {"truncate", "half_up", "half_even"}, optional
        Rounding of every stored coefficient; default each format's own (gain and offset:
        half_even).
    max_saturated : float
        Largest fraction of pre-good pixels whose coefficient may saturate (they are then
        flagged bad); more is a :class:`FormatRangeError` naming the format to widen.
    """
    cfg = as_config(cfg)
    if rounding is not None and rounding not in ROUNDING_MODES:
        raise ConfigError(f"rounding = {rounding!r} is not one of {sorted(ROUNDING_MODES)}")
    th = thresholds if thresholds is not None else load_thresholds()
    # A method that does not read the housing is fitted at the points where the housing is
    # where it assumes (the reference point's offset from the FPA); the residual covers
    # them all. One that reads it (tc_housing) is fitted on every point.
    every_point = points
    if "housing" not in cfg.base.readings:
        points = points.fpa_points()
    if points.adc_bits != cfg.adc_bits:
        raise InputError(f"{points.source}: the frames have adc_bits = {points.adc_bits} but "
                         f"pipeline {cfg.name!r} expects {cfg.adc_bits}")
    n_p, n_s, n_m, h, w = points.codes.shape
    check_frame_shape("calibration frames", (h, w), cfg)
    need_s = cfg.base.scenes
    if n_s < need_s:
        raise PlanError(f"{points.source}: method {cfg.method!r} needs at least {need_s} scene "
                        f"temperatures; the plan has {n_s}")
    codes = points.codes
    means = codes.mean(axis=2, dtype=np.float64)          # (P, S, H, W)
    reasons = np.zeros((h, w), np.uint16)
    for p in range(n_p):
        r, _ = detect_response(stack_stats(codes[p, 0], codes[p, -1], cfg.adc_bits), th)
        reasons |= r
    pre_good = reasons == 0
    if not pre_good.any():
        raise InputError(f"{points.source}: every pixel failed the response checks")
    ref = points.reference
    scale = 2.0 ** (cfg.out_bits - cfg.adc_bits)
    t = np.array([means[ref, s][pre_good].mean() for s in range(n_s)]) * scale
    top = float(2**cfg.out_bits - 1)
    if not ((t >= 0) & (t <= top)).all():
        raise InputError(f"{points.source}: targets {t.round(3).tolist()} lie outside the "
                         f"output range [0, {top:g}]")
    q = _Q(cfg, rounding)
    _fit(cfg, points, means, t, pre_good, q)

    calibratable = (reasons & int(_NOT_CALIBRATABLE)) == 0
    coeff_report: dict[str, Any] = {}
    for key in q.codes:
        mem, fname = key.split(".")
        fmt_name = "gain" if fname.startswith("gain") else fname
        ff, _ = q.fmt(fmt_name)
        over = q.over[key]
        frac = float(over[pre_good].mean())
        rep = {"format": str(ff), "int_bits": ff.int_bits, "frac_bits": ff.frac_bits,
               "calibratable": _needed(ff, q.floats[key][calibratable]),
               "saturated": int((over & calibratable).sum()), "saturated_all": int(over.sum()),
               "saturated_fraction": frac}
        coeff_report[key] = rep
        if frac > max_saturated:
            need = rep["calibratable"]["int_bits_needed"]
            fix = (f"widen formats.{fmt_name}.int_bits to {need}" if fmt_name not in
                   ("gain", "offset") else f"widen {fmt_name}_int_bits to {need}")
            raise FormatRangeError(
                f"pipeline {cfg.name!r}: coefficient {key} saturates on {100 * frac:.2f} % of "
                f"the pixels (more than {100 * max_saturated:g} %): its fitted range "
                f"[{rep['calibratable']['min']:.6g}, {rep['calibratable']['max']:.6g}] needs "
                f"{need} integer bits at {ff.frac_bits} fraction bits but the format is {ff}"
                + ("" if need is None else f"; {fix}"))
        reasons[over & calibratable] |= np.uint16(_field_reason(fname))
    # Offset outliers: the two-point offsets at the reference point (a hot or cold pixel
    # stands out there for every method).
    o_ref = ls_line(means[ref], t)[1]
    outl, off_sigma, off_limit = detect_offset_outliers(o_ref, reasons == 0, th,
                                                        float(2**cfg.out_bits))
    reasons[outl & calibratable] |= np.uint16(Reason.OFFSET_OUTLIER)
    bad = reasons != 0
    good = ~bad
    if not good.any():
        raise InputError(f"{points.source}: every pixel was flagged bad")
    fields: dict[str, dict[str, np.ndarray]] = {}
    for key, codes_ in q.codes.items():
        mem, fname = key.split(".")
        fill = int(np.median(codes_[good]))
        fields.setdefault(mem, {})[fname] = np.where(bad, fill, codes_).astype(np.int64)
    for mem in fields:
        fields[mem]["bad"] = bad
    layout = [m.name for m in cfg.memories.values() if m.source == "calibration"]
    fields = {m: {f.name: fields[m][f.name] for f in cfg.memories[m].fields} for m in layout}
    coeffs = MethodCoefficients(cfg=cfg, fields=fields, registers=dict(q.regs))
    coeffs.check()
    cal = MethodCalibration(coeffs=coeffs, reasons=reasons, floats=q.floats, targets=t)
    residual = point_residuals(cal, every_point)
    counts = {r.name: int(((reasons & int(r)) != 0).sum()) for r in Reason}
    summary: dict[str, Any] = {
        "config": cfg.name,
        "method": cfg.method,
        "reads_housing": "housing" in cfg.base.readings,
        "frame": [h, w],
        "points": {"scene_K": points.scene_K.tolist(), "fpa_K": points.fpa_K.tolist(),
                   "frames": int(n_m), "reference_fpa_K": float(points.fpa_K[ref]),
                   "readings": [points.point_reading(p) for p in range(n_p)],
                   "housing_K": None if points.housing_K is None else points.housing_K.tolist(),
                   "housing_offset_K": _offsets(every_point),
                   "all_points": len(every_point.fpa_K)},
        "targets": t.tolist(),
        "rounding": rounding or "per format",
        "thresholds": th.to_dict(),
        "coefficients": coeff_report,
        "registers": {k: {"code": v, "value": q.floats.get(k)} for k, v in q.regs.items()},
        "drift_coupling": q.floats.get("drift_coupling"),
        "drift_coupling_source": q.floats.get("drift_coupling_source"),
        "offset_local_sigma": off_sigma,
        "offset_outlier_limit": off_limit,
        "bad_pixels": int(bad.sum()),
        "bad_fraction": float(bad.mean()),
        "uncorrectable": int(uncorrectable(bad).sum()),
        "reasons": counts,
        "residual": residual,
        "max_saturated": max_saturated,
    }
    return MethodCalibration(coeffs=coeffs, reasons=reasons, floats=q.floats, targets=t,
                             summary=summary)


def point_residuals(cal: MethodCalibration, points: PointFrames) -> list[dict[str, Any]]:
    """Residual of the quantized method and of its float fit at every calibration point.

    The input is each point's per-pixel mean code, rounded (the quantized method) or not
    (the float fit); the error is the output minus the scene's target, over good pixels,
    in output codes: rms, max |e| and the spatial std (the fixed pattern left).
    """
    cfg = cal.cfg
    good = ~cal.bad
    out = []
    n_p, n_s = points.codes.shape[:2]
    means = points.codes.mean(axis=2, dtype=np.float64)
    top = (1 << cfg.adc_bits) - 1
    for p in range(n_p):
        reading = points.point_reading(p) if points.reading.min() >= 0 else None
        hreading = points.point_housing_reading(p)
        xs = np.clip(np.floor(means[p] + 0.5), 0, top).astype(np.int64)
        frame: int | dict[str, int] | None = reading
        if "housing" in cfg.base.readings and reading is not None and hreading is not None:
            frame = {"fpa": reading, "housing": hreading}
        inputs = FrameInputs(reading=np.full(n_s, reading if reading is not None else 0),
                             housing_reading=(None if hreading is None
                                              else np.full(n_s, hreading)),
                             blind_codes=None if points.blind_codes is None else
                             np.floor(points.blind_codes[p].mean(axis=1) + 0.5).astype(np.int64),
                             shutter=np.zeros(n_s, bool))
        y = method_top(xs, cal.coeffs, inputs).y
        bchange = 0.0
        if points.blind_codes is not None and cfg.has("blind_drift"):
            bchange = float(points.blind_codes[p].mean() - points.blind_codes[points.reference].mean())
        for s in range(n_s):
            e = y[s].astype(np.float64)[good] - cal.targets[s]
            ef = float_correct(cal, means[p, s], frame, bchange)[good] - cal.targets[s]
            out.append({"fpa_K": float(points.fpa_K[p]), "scene_K": float(points.scene_K[s]),
                        "housing_K": (None if points.housing_K is None
                                      else float(points.housing_K[p])),
                        "reading": reading, "rms": float(np.sqrt(np.mean(e**2))),
                        "max_abs": float(np.abs(e).max()), "std": float(e.std()),
                        "float_rms": float(np.sqrt(np.mean(ef**2))),
                        "float_std": float(ef.std())})
    return out


def _offsets(points: Any) -> list[float] | None:
    """The plan's housing offsets from the FPA (K, sorted) when it sets the housing at more
    than one, else None."""
    if points.housing_K is None:
        return None
    off = sorted({round(float(h - f), 9)
                  for h, f in zip(points.housing_K, points.fpa_K, strict=True)})
    return off if len(off) > 1 else None


def summary_text(cal: MethodCalibration) -> str:
    """A short human-readable report of a method calibration."""
    s = cal.summary
    pts = s["points"]
    lines = [
        f"irnuc calibration, pipeline {s['config']} (method {s['method']}), frame "
        f"{s['frame'][1]} x {s['frame'][0]} (W x H), scenes {pts['scene_K']} K x FPA "
        f"{pts['fpa_K']} K"
        + (f" x housing offset {pts['housing_offset_K']} K" if pts.get("housing_offset_K") else "")
        + f" x {pts['frames']} frames (reference FPA {pts['reference_fpa_K']:g} K)",
        f"targets (output codes): {', '.join(f'{v:.3f}' for v in s['targets'])}",
    ]
    for key, r in s["coefficients"].items():
        c = r["calibratable"]
        if c["min"] is None:
            continue
        lines.append(f"{key}: needed range [{c['min']:.6g}, {c['max']:.6g}] -> "
                     f"{c['int_bits_needed']} integer bits at {r['frac_bits']} fraction bits "
                     f"(format {r['format']}); {r['saturated']} saturated "
                     f"({r['saturated_all']} of all pixels)")
    for k, v in s["registers"].items():
        lines.append(f"register {k} = {v['code']} (value {v['value']})")
    lines.append(f"bad pixels: {s['bad_pixels']} ({100 * s['bad_fraction']:.3f} %), "
                 f"uncorrectable: {s['uncorrectable']}")
    for name, n in s["reasons"].items():
        if n:
            lines.append(f"  {name:16s} {n}")
    worst = max(s["residual"], key=lambda r: r["std"])
    housing = (f", housing {worst['housing_K']:g} K" if worst.get("housing_K") is not None
               and worst["housing_K"] != worst["fpa_K"] else "")
    lines.append(f"residual fixed pattern (std over good pixels): worst {worst['std']:.3f} "
                 f"codes at FPA {worst['fpa_K']:g} K{housing}, scene {worst['scene_K']:g} K "
                 f"(float fit {worst['float_std']:.3f})")
    if (s["points"].get("all_points", 0) > len(s["points"]["fpa_K"])
            and not s.get("reads_housing")):
        lines.append(f"fitted on the {len(s['points']['fpa_K'])} points with the housing at "
                     "the reference offset (no method models the housing); the residual covers "
                     f"all {s['points']['all_points']}")
    return "\n".join(lines) + "\n"
