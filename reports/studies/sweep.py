"""Coefficient bit-width sweeps of the two-point NUC (``irnuc sweep``; ``docs/reports.md``).

Flow
----
1. :func:`prepare` simulates the sensor once per distinct ADC width (``model``): a stack of
   ``repeats`` frames at ``t_low`` and at ``t_high`` and one frame per evaluation
   temperature. It runs the golden model's :func:`nuc_fixed.calibrate.calibrate` with a
   wide reference format, which gives the unquantized (float) gain and offset per pixel
   and the bad-pixel map. This is a :class:`CalibrationSet`; it holds plain arrays.
2. Every sweep point (:class:`SweepPoint`: gain and offset formats, ADC and output bits,
   rounding) quantizes those float coefficients with ``FixedFormat.quantize``
   (saturating), runs the bit-exact :func:`nuc_fixed.nuc_core` on the evaluation frames
   and measures it against the float NUC (:func:`evaluate_point`).
3. Points are independent tasks submitted to a ``concurrent.futures``-style executor: a
   ``ProcessPoolExecutor`` (default, 2 workers), an in-process executor (``workers=0``) or
   a Dask cluster (``scheduler=ADDRESS``: ``distributed.Client(address).get_executor()``).
   The same :func:`run_points` submits and collects in every case. The calibration set is
   passed to the workers as arrays (pickled with each task for processes; scattered once
   to every worker for Dask), never regenerated there.

Bad pixels (the reference calibration's map) are excluded from every metric; DPC is not
applied, so the figures measure the coefficient precision alone.
"""

from __future__ import annotations

import concurrent.futures as cf
import itertools
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from irnuc.common.errors import UserError
from irnuc.common.executor import ExecutorHandle, open_executor


class SweepError(UserError):
    """A sweep specification is invalid (names the field, the value and the allowed range)."""


ROUNDINGS = ("truncate", "half_up", "half_even")
# The reference calibration's wide formats: no good pixel's coefficient saturates there.
_REF_GAIN = (8, 20)
_REF_OFFSET_EXTRA = 10  # offset integer bits = ADC bits + this (|gain * x| < 2^(A + 8))


# ---- specification ------------------------------------------------------------------------
@dataclass(frozen=True)
class SensorSpec:
    """Which frames a sweep calibrates on and evaluates.

    Parameters
    ----------
    preset : str
        Model preset (``default``, ``paper``) or a sensor TOML file.
    overrides : dict
        Dotted-key overrides of the preset (e.g. ``{"fpa.active_rows": 120}``).
    seed : int
        Seed of every random draw of the model (per-pixel spread, defects, noise).
    t_low, t_high : float
        Calibration blackbody temperatures, K.
    t_eval : tuple of float
        Evaluation temperatures, K; those equal to ``t_low`` / ``t_high`` are marked as
        calibration points and left out of the headline metrics.
    repeats : int
        Frames averaged per calibration temperature.
    """

    preset: str = "default"
    overrides: Mapping[str, Any] = field(default_factory=dict)
    seed: int = 0
    t_low: float = 300.0
    t_high: float = 400.0
    t_eval: tuple[float, ...] = (350.0,)
    repeats: int = 4

    def check(self) -> None:
        if not isinstance(self.seed, int) or self.seed < 0:
            raise SweepError(f"sensor.seed = {self.seed!r} is outside the allowed range 0..2^63-1")
        if not isinstance(self.repeats, int) or not 1 <= self.repeats <= 10_000:
            raise SweepError(f"sensor.repeats = {self.repeats!r} is outside the allowed range 1..10000")
        for name in ("t_low", "t_high"):
            v = getattr(self, name)
            if not isinstance(v, int | float) or not 0 < v < 1e5:
                raise SweepError(f"sensor.{name} = {v!r} K is outside the allowed range (0, 1e5)")
        if not self.t_low < self.t_high:
            raise SweepError(f"sensor.t_low = {self.t_low} K must be below sensor.t_high = {self.t_high} K")
        if not self.t_eval:
            raise SweepError("sensor.t_eval is empty; give at least one evaluation temperature (K)")
        for t in self.t_eval:
            if not isinstance(t, int | float) or not 0 < t < 1e5:
                raise SweepError(f"sensor.t_eval holds {t!r} K, outside the allowed range (0, 1e5)")

    def model_config(self, adc_bits: int | None = None) -> dict[str, Any]:
        from irnuc import model

        ov = dict(self.overrides)
        if adc_bits is not None:
            ov["adc.bits"] = adc_bits
        if self.preset.endswith(".toml") or "/" in self.preset:
            return model.load_config(self.preset, ov)
        return model.load_preset(self.preset, ov)


@dataclass(frozen=True)
class SweepAxes:
    """The values swept; the points are their Cartesian product.

    ``gain_int_bits`` / ``offset_int_bits`` entries may be ``"auto"``: the fewest integer
    bits (offset: sign included) that hold every good pixel's coefficient at the point's
    fraction bits, so no good coefficient saturates. ``offset_frac_bits`` entries may be
    ``"same"`` (equal to the gain fraction bits, as in the paper). ``adc_bits`` ``None`` is
    the pipeline's ADC (the sensor's must match it); ``out_bits`` ``None`` is the pipeline's
    output width; ``rounding``
    ``None`` is the base pipeline's datapath rounding. ``coeff_rounding`` is the rounding
    of the float coefficients to codes.
    """

    gain_frac_bits: tuple[int, ...] = (4, 6, 8, 10, 12, 14)
    offset_frac_bits: tuple[int | str, ...] = (0, 2, 4)
    gain_int_bits: tuple[int | str, ...] = ("auto",)
    offset_int_bits: tuple[int | str, ...] = ("auto",)
    adc_bits: tuple[int | None, ...] = (None,)
    out_bits: tuple[int | None, ...] = (None,)
    rounding: tuple[str | None, ...] = (None,)
    coeff_rounding: tuple[str, ...] = ("half_even",)
    pipeline: str = "typical14"

    def check(self) -> None:
        def ints(name: str, values: Sequence[Any], lo: int, hi: int, extra: tuple = ()) -> None:
            if not values:
                raise SweepError(f"axes.{name} is empty; give at least one value")
            for v in values:
                if v in extra and not isinstance(v, int | float):
                    continue
                if not isinstance(v, int) or isinstance(v, bool) or not lo <= v <= hi:
                    allowed = f"{lo}..{hi}" + (f" or {', '.join(map(repr, extra))}" if extra else "")
                    raise SweepError(f"axes.{name} holds {v!r}, outside the allowed range {allowed}")

        ints("gain_frac_bits", self.gain_frac_bits, 0, 32)
        ints("offset_frac_bits", self.offset_frac_bits, 0, 32, ("same",))
        ints("gain_int_bits", self.gain_int_bits, 0, 16, ("auto",))
        ints("offset_int_bits", self.offset_int_bits, 1, 32, ("auto",))
        ints("adc_bits", self.adc_bits, 1, 24, (None,))
        ints("out_bits", self.out_bits, 1, 24, (None,))
        for name in ("rounding", "coeff_rounding"):
            values = getattr(self, name)
            if not values:
                raise SweepError(f"axes.{name} is empty; give at least one value")
            for v in values:
                if v not in ROUNDINGS and not (v is None and name == "rounding"):
                    raise SweepError(f"axes.{name} holds {v!r}, not one of {list(ROUNDINGS)}")
        from irnuc.nuc_fixed import load_pipeline

        try:
            load_pipeline(self.pipeline)
        except ValueError as exc:
            raise SweepError(f"axes.pipeline: {exc}") from None

    def n_points(self) -> int:
        n = 1
        for name in ("gain_frac_bits", "offset_frac_bits", "gain_int_bits", "offset_int_bits",
                     "adc_bits", "out_bits", "rounding", "coeff_rounding"):
            n *= len(getattr(self, name))
        return n


@dataclass(frozen=True)
class SweepPoint:
    """One fully resolved point: a pipeline configuration plus the coefficient rounding."""

    index: int
    adc_bits: int
    out_bits: int
    gain_int_bits: int
    gain_frac_bits: int
    offset_int_bits: int
    offset_frac_bits: int
    rounding: str
    coeff_rounding: str
    pipeline: str

    def config(self, height: int, width: int):  # -> nuc_fixed.PipelineConfig
        from irnuc.nuc_fixed import load_pipeline

        base = load_pipeline(self.pipeline)
        return base.replace(
            name=f"sweep{self.index}", adc_bits=self.adc_bits, out_bits=self.out_bits,
            gain_int_bits=self.gain_int_bits, gain_frac_bits=self.gain_frac_bits,
            offset_int_bits=self.offset_int_bits, offset_frac_bits=self.offset_frac_bits,
            rounding=self.rounding, max_width=max(base.max_width, width),
            max_height=max(base.max_height, height),
            description="bit-width sweep point")

    def formats(self):  # -> tuple[nuc_fixed.FixedFormat, nuc_fixed.FixedFormat]
        """The gain and offset formats of the point (unsigned gain, signed offset: what
        ``nuc_fixed.gain_format`` / ``offset_format`` give for its configuration)."""
        from irnuc.nuc_fixed import FixedFormat

        return (FixedFormat(self.gain_int_bits, self.gain_frac_bits, signed=False),
                FixedFormat(self.offset_int_bits, self.offset_frac_bits, signed=True))

    def label(self) -> str:
        """``U2.14 / S12.4``: the formats as ``FixedFormat`` writes them."""
        g, o = self.formats()
        return f"{g} / {o}"

    def key(self) -> str:
        """The point's name in metric keys: formats, ADC and output widths, roundings."""
        g, o = self.formats()
        return f"{g}_{o}_A{self.adc_bits}_B{self.out_bits}_{self.rounding}_{self.coeff_rounding}"

    def record(self) -> dict[str, Any]:
        """The point as the JSON fields every result of it carries (summary.schema.json,
        ``point``): its fields, label, key, formats and the widths its configuration
        derives. Whatever shows a point reads these, never re-deriving them."""
        cfg = self.config(1, 1)
        g, o = self.formats()
        return {**asdict(self), "label": f"{g} / {o}", "key": self.key(),
                "gain_format": str(g), "offset_format": str(o), "gain_bits": cfg.gain_bits,
                "offset_bits": cfg.offset_bits, "bits_per_pixel": cfg.word_bits}


# ---- calibration set (frames + float NUC), built once in the parent ----------------------
@dataclass
class CalibrationSet:
    """Frames and the float two-point NUC of one (ADC bits, output bits) pair.

    Attributes
    ----------
    raw_eval : (N, H, W) uint
        One raw frame per evaluation temperature.
    t_eval : (N,) float
        Evaluation temperatures, K.
    is_cal : (N,) bool
        True where the evaluation temperature is a calibration temperature.
    gain, offset : (H, W) float64
        Unquantized coefficients (output codes per ADC code, output codes).
    bad : (H, W) bool
        Bad-pixel map of the reference calibration (excluded from the metrics).
    truth : (H, W) uint8
        The model's injected defect kinds (0 = good).
    """

    adc_bits: int
    out_bits: int
    raw_eval: np.ndarray
    t_eval: np.ndarray
    is_cal: np.ndarray
    gain: np.ndarray
    offset: np.ndarray
    bad: np.ndarray
    truth: np.ndarray
    summary: dict[str, Any]

    @property
    def good(self) -> np.ndarray:
        return ~self.bad

    def coefficient_range(self) -> dict[str, tuple[float, float]]:
        g = self.good
        return {"gain": (float(self.gain[g].min()), float(self.gain[g].max())),
                "offset": (float(self.offset[g].min()), float(self.offset[g].max()))}


def reference_config(adc_bits: int, out_bits: int, height: int, width: int, base: str = "typical14"):
    """A wide pipeline configuration for the float reference calibration."""
    from irnuc.nuc_fixed import load_pipeline

    b = load_pipeline(base)
    return b.replace(name="sweep_reference", adc_bits=adc_bits, out_bits=out_bits,
                     gain_int_bits=_REF_GAIN[0], gain_frac_bits=_REF_GAIN[1],
                     offset_int_bits=adc_bits + _REF_OFFSET_EXTRA, offset_frac_bits=_REF_GAIN[1],
                     max_width=max(b.max_width, width), max_height=max(b.max_height, height))


def calibration_set(frames_lo: np.ndarray, frames_hi: np.ndarray, raw_eval: np.ndarray,
                    t_eval: Sequence[float], cal_temps: tuple[float, float], adc_bits: int,
                    out_bits: int, truth: np.ndarray | None = None,
                    pipeline: str = "typical14") -> CalibrationSet:
    """Float two-point NUC and bad-pixel map of two raw stacks (golden-model calibration)."""
    from irnuc.nuc_fixed.calibrate import calibrate

    h, w = frames_lo.shape[-2:]
    ref = reference_config(adc_bits, out_bits, h, w, pipeline)
    cal = calibrate(frames_lo, frames_hi, ref)
    t_eval = np.asarray(t_eval, dtype=np.float64)
    is_cal = np.isin(t_eval, np.asarray(cal_temps, dtype=np.float64))
    return CalibrationSet(
        adc_bits=adc_bits, out_bits=out_bits, raw_eval=np.asarray(raw_eval), t_eval=t_eval,
        is_cal=is_cal, gain=cal.gain, offset=cal.offset, bad=cal.bad,
        truth=np.zeros(cal.bad.shape, np.uint8) if truth is None else np.asarray(truth),
        summary={k: cal.summary[k] for k in ("targets", "median_response", "bad_pixels",
                                             "bad_fraction", "reasons", "gain_good", "offset_good")})


def check_widths(sensor: SensorSpec, axes: SweepAxes, *, sensor_name: str = "the sensor",
                 pipeline_name: str = "pipeline") -> None:
    """The ADC and output widths come from the named pipeline: a sensor whose ADC differs
    from the pipeline's ``adc_bits`` is refused (unless ADC widths are swept explicitly),
    before any frame is simulated."""
    from irnuc.nuc_fixed import load_pipeline

    base = load_pipeline(axes.pipeline)
    if None not in axes.adc_bits:
        return
    a = int(sensor.model_config()["adc"]["bits"])
    if a != base.adc_bits:
        raise SweepError(
            f"{sensor_name} {sensor.preset!r} has a {a}-bit ADC but {pipeline_name} "
            f"{axes.pipeline!r} has adc_bits = {base.adc_bits} (and out_bits = {base.out_bits}); "
            f"use a sensor with a {base.adc_bits}-bit ADC (e.g. --set adc.bits={base.adc_bits}), "
            "a pipeline for this sensor, or sweep ADC widths explicitly (--adc-bits)")


def simulate_set(sensor: SensorSpec, adc_bits: int | None, out_bits: int | None,
                 pipeline: str = "typical14") -> CalibrationSet:
    """Simulate the calibration stacks and evaluation frames and calibrate them (float).

    ``adc_bits`` / ``out_bits`` ``None``: the pipeline's (the sensor's ADC must match it,
    :func:`check_widths`)."""
    from irnuc import model
    from irnuc.nuc_fixed import load_pipeline

    base = load_pipeline(pipeline)
    cfg = sensor.model_config(adc_bits)
    a = int(cfg["adc"]["bits"])
    b = base.out_bits if out_bits is None else int(out_bits)
    pipe = model.Pipeline(cfg, seed=sensor.seed)
    cal = pipe.simulate([sensor.t_low, sensor.t_high], repeats=sensor.repeats)
    ev = pipe.simulate(list(sensor.t_eval))
    m = sensor.repeats
    return calibration_set(cal.codes[:m], cal.codes[m:], ev.codes, sensor.t_eval,
                           (sensor.t_low, sensor.t_high), a, b, cal.defect_kind, pipeline)


def sweep_bytes(cfg: Mapping[str, Any], n_cal: int, n_eval: int, sets: int, workers: int
                ) -> float:
    """Estimated peak memory of a sweep (bytes, above measured peaks, docs/robustness.md):
    the simulation of the calibration frames, then per (ADC, output) set the evaluation
    codes and float coefficients, and per worker process its interpreter
    (:data:`~irnuc.common.executor.WORKER_PROCESS_BYTES`), a copy of a set and the
    fixed-point NUC and metrics of the evaluation frames (in-process: one such copy)."""
    from irnuc.common.executor import WORKER_PROCESS_BYTES
    from irnuc.model.pipeline import simulation_bytes
    from irnuc.nuc_fixed.calibrate import CALIBRATE_WORK_BYTES

    pixels = cfg["fpa"]["active_rows"] * cfg["fpa"]["active_cols"]
    calibration = pixels * (CALIBRATE_WORK_BYTES["per_pixel"]
                            + n_cal * (2 + CALIBRATE_WORK_BYTES["per_code"]))
    per_set = pixels * (2 * n_eval + 64)
    per_worker = per_set + pixels * n_eval * 40
    processes = workers * WORKER_PROCESS_BYTES
    return (max(simulation_bytes(cfg, n_cal), calibration) + sets * per_set
            + max(workers, 1) * per_worker + processes)


def check_sweep_memory(sensor: SensorSpec, axes: SweepAxes, workers: int, what: str,
                       hint: str = "") -> None:
    """:class:`~irnuc.common.memory.ResourceError` when the sweep's estimated peak
    (:func:`sweep_bytes`, the largest over its ADC widths) exceeds the memory there is."""
    from irnuc.common.memory import check_memory

    sets = len(dict.fromkeys(axes.out_bits)) * len(dict.fromkeys(axes.adc_bits))
    need = max(sweep_bytes(sensor.model_config(adc), 2 * sensor.repeats, len(sensor.t_eval),
                           sets, workers)
               for adc in dict.fromkeys(axes.adc_bits))
    check_memory(need, what, hint)


def prepare(sensor: SensorSpec, axes: SweepAxes) -> dict[tuple[int | None, int | None], CalibrationSet]:
    """One calibration set per distinct (ADC bits, output bits) of the axes."""
    sets: dict[tuple[int | None, int | None], CalibrationSet] = {}
    for a, b in itertools.product(dict.fromkeys(axes.adc_bits), dict.fromkeys(axes.out_bits)):
        sets[(a, b)] = simulate_set(sensor, a, b, axes.pipeline)
    return sets


def _auto_int_bits(lo: float, hi: float, frac_bits: int, signed: bool) -> int:
    from irnuc.nuc_fixed import FixedFormat

    fmt = FixedFormat(1, frac_bits, signed)
    if not signed and lo < 0:
        lo = 0.0  # a negative gain is flagged bad by calibration; the format cannot hold it
    return fmt.bits_needed(lo, hi)


def resolve_points(axes: SweepAxes, sets: Mapping[tuple[int | None, int | None], CalibrationSet]
                   ) -> list[tuple[SweepPoint, tuple[int | None, int | None]]]:
    """Every point of the axes with ``auto`` / ``same`` / ``None`` resolved, validated."""
    from irnuc.nuc_fixed import load_pipeline

    base = load_pipeline(axes.pipeline)
    out: list[tuple[SweepPoint, tuple[int | None, int | None]]] = []
    for a, b, gf, of, gi, oi, rnd, crnd in itertools.product(
            dict.fromkeys(axes.adc_bits), dict.fromkeys(axes.out_bits), axes.gain_frac_bits,
            axes.offset_frac_bits, axes.gain_int_bits, axes.offset_int_bits, axes.rounding,
            axes.coeff_rounding):
        cs = sets[(a, b)]
        rng = cs.coefficient_range()
        of_v = gf if of == "same" else int(of)
        gi_v = _auto_int_bits(*rng["gain"], gf, False) if gi == "auto" else int(gi)
        oi_v = _auto_int_bits(*rng["offset"], of_v, True) if oi == "auto" else int(oi)
        p = SweepPoint(index=len(out), adc_bits=cs.adc_bits, out_bits=cs.out_bits,
                       gain_int_bits=gi_v, gain_frac_bits=gf, offset_int_bits=oi_v,
                       offset_frac_bits=of_v, rounding=rnd or base.rounding,
                       coeff_rounding=crnd, pipeline=axes.pipeline)
        h, w = cs.gain.shape
        try:
            p.config(h, w)
        except ValueError as exc:
            raise SweepError(f"sweep point {p.label()} (ADC {p.adc_bits}, out {p.out_bits}): {exc}") from None
        out.append((p, (a, b)))
    return out


# ---- one point (runs in a worker) --------------------------------------------------------
def quantized_nuc(cs: CalibrationSet, point: SweepPoint) -> tuple[np.ndarray, dict[str, Any]]:
    """Fixed-point NUC output (N, H, W) of the evaluation frames at one point.

    Coefficients are quantized from the float calibration with the point's coefficient
    rounding, saturating, and bad pixels get the median codes of the good pixels: the
    steps of :func:`nuc_fixed.calibrate.calibrate` (``quantize_coefficients``,
    ``fill_flagged``).
    """
    from irnuc.nuc_fixed import nuc_core
    from irnuc.nuc_fixed.calibrate import fill_flagged, quantize_coefficients

    h, w = cs.gain.shape
    cfg = point.config(h, w)
    gcode, ocode, gover, oover = quantize_coefficients(cs.gain, cs.offset, cfg,
                                                       point.coeff_rounding)
    gcode, ocode, _ = fill_flagged(gcode, ocode, cs.bad)
    y = nuc_core(cs.raw_eval, gcode, ocode, cfg)
    good = cs.good
    info = {
        "gain_saturated_fraction": float(gover[good].mean()),
        "offset_saturated_fraction": float(oover[good].mean()),
        "gain_saturated": int(gover[good].sum()),
        "offset_saturated": int(oover[good].sum()),
        "bits_per_frame": cfg.word_bits * h * w,
    }
    return y, info


HEADLINE = ("residual_nu", "residual_nu_adc_lsb", "err_max_lsb", "err_rms_lsb", "psnr_db",
            "radial_rms_lsb", "radial_fraction")


def evaluate_point(cs: CalibrationSet, point: SweepPoint, threads: int | None = None) -> dict[str, Any]:
    """Every metric of one sweep point (a plain dict, JSON-ready).

    ``threads`` limits numba's threads for the duration (1 in pool workers, so two
    workers on two cores do not oversubscribe them).
    """
    from irnuc.reports.studies.metrics import frame_metrics

    old = None
    if threads is not None:
        import numba

        old = numba.get_num_threads()
        numba.set_num_threads(max(1, min(threads, numba.config.NUMBA_NUM_THREADS)))
    try:
        t0 = time.perf_counter()
        y, info = quantized_nuc(cs, point)
        per_temp = []
        for i, t in enumerate(cs.t_eval):
            x = cs.raw_eval[i]
            y_ref = cs.gain * x + cs.offset
            m = frame_metrics(y[i], y_ref, x, cs.good, cs.adc_bits, cs.out_bits)
            per_temp.append({"t_eval": float(t), "calibration_point": bool(cs.is_cal[i]), **m})
    finally:
        if old is not None:
            import numba

            numba.set_num_threads(old)
    headline_from = [r for r in per_temp if not r["calibration_point"]] or per_temp
    rec: dict[str, Any] = {**point.record(), **info}
    for key in HEADLINE:
        vals = [r[key] for r in headline_from]
        if key == "psnr_db":  # worst = lowest; None (zero error) is the best
            finite = [v for v in vals if v is not None]
            rec[key] = min(finite) if finite else None
        else:
            rec[key] = max(vals)
    rec["per_temp"] = per_temp
    rec["seconds"] = time.perf_counter() - t0
    return rec


# ---- executors: processes, in-process, or Dask through the same submit/collect code ------
def run_points(handle: ExecutorHandle,
               tasks: Sequence[tuple[SweepPoint, tuple[int | None, int | None]]],
               sets: Mapping[tuple[int | None, int | None], CalibrationSet],
               progress: Callable[[int, int], None] | None = None) -> list[dict[str, Any]]:
    """Evaluate every point on the executor; results in point order."""
    shared = {key: handle.share(cs) for key, cs in sets.items()}
    futures = {handle.executor.submit(evaluate_point, shared[key], point, handle.threads): point.index
               for point, key in tasks}
    results: dict[int, dict[str, Any]] = {}
    if progress is not None:
        progress(0, len(futures))
    for fut in cf.as_completed(futures):
        results[futures[fut]] = fut.result()
        if progress is not None:
            progress(len(results), len(futures))
    return [results[i] for i in sorted(results)]


# ---- whole sweep -------------------------------------------------------------------------
ERROR_METRICS = ("err_max_lsb", "err_rms_lsb", "residual_nu", "residual_nu_adc_lsb", "radial_rms_lsb")


@dataclass
class SweepResult:
    """A whole sweep: ``points`` holds each point's results (JSON-ready, the fields of
    :meth:`SweepPoint.record` and the metrics), ``sweep_points`` the typed points of the
    same index (their configurations)."""

    sensor: SensorSpec
    axes: SweepAxes
    points: list[dict[str, Any]]
    sets: dict[tuple[int | None, int | None], CalibrationSet]
    executor: str
    seconds: dict[str, float]
    sweep_points: list[SweepPoint] = field(default_factory=list)

    def frame_shape(self) -> tuple[int, int]:
        return next(iter(self.sets.values())).gain.shape

    def pareto(self, metric: str = "err_max_lsb") -> list[dict[str, Any]]:
        from irnuc.reports.studies.metrics import pareto_front

        check_metric(metric)
        cost = np.array([p["bits_per_pixel"] for p in self.points], dtype=float)
        err = np.array([p[metric] for p in self.points], dtype=float)
        return [self.points[i] for i in pareto_front(cost, err)]

    def smallest(self, max_error: float, metric: str = "err_max_lsb") -> dict[str, Any]:
        return smallest_meeting(self.points, max_error, metric)

    def to_dict(self, max_error: float | None = None, metric: str = "err_max_lsb") -> dict[str, Any]:
        h, w = self.frame_shape()
        d: dict[str, Any] = {
            "sensor": {**asdict(self.sensor), "overrides": dict(self.sensor.overrides),
                       "t_eval": list(self.sensor.t_eval)},
            "axes": asdict(self.axes),
            "frame": [int(h), int(w)],
            "executor": self.executor,
            "seconds": self.seconds,
            "calibration": {f"{cs.adc_bits}/{cs.out_bits}": cs.summary for cs in self.sets.values()},
            "n_points": len(self.points),
            "points": self.points,
            "pareto": {"metric": metric, "indices": [p["index"] for p in self.pareto(metric)]},
        }
        if max_error is not None:
            d["smallest"] = self.smallest(max_error, metric)
        return d


def check_metric(metric: str) -> None:
    if metric not in ERROR_METRICS:
        raise SweepError(f"error metric = {metric!r} is not one of {list(ERROR_METRICS)}")


def smallest_meeting(points: Sequence[Mapping[str, Any]], max_error: float,
                     metric: str = "err_max_lsb") -> dict[str, Any]:
    """The points of fewest memory bits per pixel whose ``metric`` is at most ``max_error``.

    Exhaustive over ``points``. Returns ``{"max_error", "metric", "found", "bits_per_pixel",
    "points": [indices of every point at that memory cost that meets it], "best": index of
    the lowest error among them}``.
    """
    check_metric(metric)
    if not isinstance(max_error, int | float) or not max_error > 0:
        raise SweepError(f"max_error = {max_error!r} is outside the allowed range (0, inf)")
    ok = [p for p in points if p[metric] is not None and p[metric] <= max_error]
    if not ok:
        return {"max_error": float(max_error), "metric": metric, "found": False,
                "bits_per_pixel": None, "points": [], "best": None}
    least = min(p["bits_per_pixel"] for p in ok)
    tied = sorted((p for p in ok if p["bits_per_pixel"] == least), key=lambda p: (p[metric], p["index"]))
    return {"max_error": float(max_error), "metric": metric, "found": True, "bits_per_pixel": least,
            "points": [p["index"] for p in tied], "best": tied[0]["index"]}


def run_sweep(sensor: SensorSpec, axes: SweepAxes, *, workers: int = 2, scheduler: str | None = None,
              progress: Callable[[int, int], None] | None = None,
              sets: Mapping[tuple[int | None, int | None], CalibrationSet] | None = None) -> SweepResult:
    """Simulate, calibrate (float) and evaluate every point of ``axes``.

    Validation of both specifications happens before any frame is simulated; ``auto``
    integer widths are resolved from the calibration (data-dependent) and then checked.
    ``sets`` reuses calibration sets from an earlier :func:`prepare`.
    """
    sensor.check()
    axes.check()
    check_widths(sensor, axes)
    if axes.n_points() > 100_000:
        raise SweepError(f"the axes give {axes.n_points()} points; the allowed maximum is 100000")
    seconds: dict[str, float] = {}
    # The executor first: a cluster that cannot be reached is an error before any work.
    with open_executor(workers, scheduler) as handle:
        t0 = time.perf_counter()
        sets = dict(sets) if sets is not None else prepare(sensor, axes)
        seconds["frames_and_calibration"] = time.perf_counter() - t0
        tasks = resolve_points(axes, sets)
        t0 = time.perf_counter()
        points = run_points(handle, tasks, sets, progress)
        desc = handle.description
        seconds["points"] = time.perf_counter() - t0
    return SweepResult(sensor=sensor, axes=axes, points=points, sets=dict(sets), executor=desc,
                       seconds=seconds, sweep_points=[p for p, _ in tasks])


#: The most values one list argument may expand to (a sweep of more is a typo).
MAX_LIST = 4096


def parse_int_list(text: str, name: str, extra: tuple[str, ...] = ()) -> tuple[Any, ...]:
    """``"3:6"`` -> (3, 4, 5, 6); ``"0:8:2"``; ``"3,5,auto"``; words in ``extra`` pass through.

    At most :data:`MAX_LIST` values (checked before any list is built).
    """
    out: list[Any] = []
    for part in (s.strip() for s in text.split(",")):
        if not part:
            continue
        if part in extra:
            out.append(part)
            continue
        try:
            if ":" in part:
                bits = [int(v) for v in part.split(":")]
                if len(bits) not in (2, 3) or (len(bits) == 3 and bits[2] <= 0):
                    raise ValueError
                span: range | list[int] = range(bits[0], bits[1] + 1,
                                                bits[2] if len(bits) == 3 else 1)
            else:
                span = [int(part)]
        except ValueError:
            allowed = "integers, LO:HI or LO:HI:STEP" + (f", or {', '.join(extra)}" if extra else "")
            raise SweepError(f"{name} = {text!r}: {part!r} is not one of {allowed}") from None
        if len(out) + len(span) > MAX_LIST:
            raise SweepError(f"{name} = {text!r} gives {len(out) + len(span)} values; at most "
                             f"{MAX_LIST} are allowed")
        out.extend(span)
    if not out:
        raise SweepError(f"{name} = {text!r} gives no value")
    return tuple(out)
