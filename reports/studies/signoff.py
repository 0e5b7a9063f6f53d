"""Study: the sign-off sweep of a drifting camera: correction method x coefficient widths x
FFC policy, each point judged on the shipped thermal scenarios (issue 37), against memory,
bandwidth, datapath, dead time and FFCs per hour.

The scenarios (``scenarios``, default every scenario of ``model/scenarios``): each point is
corrected along each scenario's thermal world (:mod:`irnuc.reports.studies.scenarios`: the
housing, the FPA and the shutter as the thermal network moves them, the FPA and housing
sensors' readings at the full frame rate, FFC policies closed loop) and its figures are the
worst over the scenarios (``scenarios`` per point: each one's worst, when, FFCs per hour,
dead time and a trace). The FFC policies: every period of ``ffc_periods_min``, every FPA
change of ``ffc_changes_K`` and every (period, change) pair of ``ffc_either`` (the Lepton's
3 min or 1.5 K); a change trigger needs the FPA reading, so a configuration whose build has
none (ffc14, quadffc14: READING reserved) gets no change-triggered point. The methods: every
14-bit configuration of the registry (``pipelines.toml``), so a method added there joins the
sweep. The calibration plan covers the FPA and housing span of the scenarios it judges
(a camera is calibrated over its operating range): its FPA points run evenly from the
coldest to the warmest FPA of ``fpa_K`` and every scenario (rounded out to 0.5 K, spaced
at most half of ``fpa_K``'s span apart, the middle one the reference), its housing
offsets from ``housing_offset_K`` widened to every scenario's housing - FPA difference
(:func:`scenario_envelope`, :meth:`SignoffSpec.plan`); the methods that read the FPA
(housing) sensor get the reading range that holds the plan's span around its reference
(:meth:`SignoffSpec.range_bits`, the coefficients' integer bits grown with it:
:func:`method_bits.with_range_bits`), so no scenario's FPA is read past the calibration.

Below: the pre-issue-37 description of the FPA-ramp grid, kept for the functions that
remain (:func:`ffc_events`, :func:`sawtooth_segments`) and the fields of the spec.

Every method of ``methods`` is calibrated at every fraction width of ``frac_bits`` (every
coefficient's fraction set to f, integer widths as shipped: :func:`method_bits.with_frac_bits`)
on one calibration plan of the study sensor, then corrects uniform scenes (``scene_K``) over
the FPA range ``fpa_K`` sampled every ``fpa_step_K``. The FPA follows a ramp of
``ramp_K_per_min`` (time = (T - T_low) / ramp); the frames are the model's steady state at
each temperature, the housing at the FPA temperature (as :mod:`methods_range`).

A shutter method (a configuration with the ``ffc`` stage) is swept over ``ffc_periods_min``
too: a shutter event every period, i.e. every ``ramp * period`` kelvin from T_low; at each
event the method accumulates ``ffc_frames`` shutter frames (a uniform source at the housing
temperature) and refreshes its offsets; the frames after it, up to and including the frame
on which the shutter next closes, are corrected with that refresh (the FFC sawtooth).

Per point: the worst residual fixed pattern over the range (spatial std of a corrected
uniform scene over the good pixels) in output LSB and in mK through the corrected image's
local responsivity at each FPA temperature and scene, and the worst level error (mK):
:func:`metrics.residuals_mK`, the one conversion; the coefficient memory (bits
per pixel, calibration and runtime), and the external-memory read bandwidth at
``frame_rate_hz`` for a ``bandwidth_frame`` array. :func:`recommend` picks the cheapest
point meeting a tolerance, :func:`grid_edges` says where it sits on the swept grid, and
:func:`fronts` gives the Pareto fronts per method and overall.

Also measured on the same sensor (for the report's Temperature section): the closed-form
NETD (a 300 K scene, the sensor's F-number and frame rate, with the pixels' spread) and the
NVESD 3D noise of raw frames of that scene at the middle of the range, the raw and corrected
images at both ends, and the camera-temperature test (:mod:`camera_temperature`).

:func:`cached_signoff` keeps the whole result in the irnuc cache
(``temperature/<digest>.json``), keyed by the specification and the code it measured (the
model, the golden model and these studies' sources).
"""

from __future__ import annotations

import concurrent.futures as cf
import dataclasses
import functools
import hashlib
import json
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.reports.studies import drift_common as dc

NAME = "signoff"
TITLE = "Sign-off sweep: method x widths x FFC period over the FPA range"
#: The methods of the issue-35 sign-off (before the registry was iterated): kept for
#: reference; the default is :func:`registry_methods`.
METHODS: tuple[str, ...] = ("onepoint14", "typical14", "piecewise14", "quadratic14", "tcoffset14",
                            "tcgain14", "table14", "drift14", "ffc14", "tcffc14", "quadffc14")
#: The ADC width of the camera the sign-off compares configurations for.
SIGNOFF_ADC_BITS = 14


def registry_methods(adc_bits: int = SIGNOFF_ADC_BITS) -> tuple[str, ...]:
    """Every configuration of the registry's ``pipelines.toml`` for an ``adc_bits`` camera,
    in file order: a method added to the registry with its configuration joins the
    sign-off without an edit here."""
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.config import pipeline_names

    return tuple(n for n in pipeline_names(method=None) if load_pipeline(n).adc_bits == adc_bits)


def scenario_default() -> tuple[str, ...]:
    from irnuc.model.sequence import scenario_names

    return tuple(scenario_names())


@functools.cache
def scenario_envelope(name: str) -> dict[str, float]:
    """A shipped scenario's span at the full frame rate: the FPA's coldest and warmest
    (``fpa_lo``, ``fpa_hi``, K) and the housing's least and greatest difference to the FPA
    (``dh_lo``, ``dh_hi``, K), and its sensors' LSBs (K per code)."""
    from irnuc.model.sequence import load_sequence

    seq = load_sequence(name)
    sched = dataclasses.replace(seq, record_every=1).schedule()
    fpa, dh = np.asarray(sched.fpa_K), np.asarray(sched.T_cam_K) - np.asarray(sched.fpa_K)
    return {"fpa_lo": float(fpa.min()), "fpa_hi": float(fpa.max()),
            "dh_lo": float(dh.min()), "dh_hi": float(dh.max()),
            "fpa_lsb_K": float(seq.fpa_sensor.lsb_K),
            "housing_lsb_K": float(seq.housing_sensor.lsb_K)}


def _out(x: float, up: bool, step: float = 0.5) -> float:
    """``x`` rounded outward to a multiple of ``step``."""
    return (math.ceil if up else math.floor)(x / step - 1e-9 * (1 if up else -1)) * step


@dataclass(frozen=True)
class SignoffSpec:
    """What the sign-off sweep simulates and sweeps (K, K/min, min, Hz)."""

    preset: str = "default"
    seed: int = 4
    rows: int = 24
    cols: int = 32
    fpa_K: tuple[float, float] = (288.0, 308.0)
    fpa_step_K: float = 1.0
    scene_K: tuple[float, ...] = (280.0, 330.0, 380.0)
    ramp_K_per_min: float = 2.0
    methods: tuple[str, ...] = field(default_factory=registry_methods)
    frac_bits: tuple[int, ...] = (6, 8, 10, 12, 14)
    ffc_periods_min: tuple[float, ...] = (0.5, 1.0, 2.0, 4.0)
    ffc_changes_K: tuple[float, ...] = (0.1, 0.5, 1.5)
    ffc_either: tuple[tuple[float, float], ...] = ((3.0, 1.5),)
    scenarios: tuple[str, ...] = field(default_factory=scenario_default)
    node_K: float = 0.5
    node_max_s: float = 120.0
    max_peaks: int = 24
    housing_offset_K: tuple[float, ...] = (-5.0, 0.0, 5.0)
    frame_rate_hz: float = 60.0
    bandwidth_frame: tuple[int, int] = (480, 640)
    noise_frames: int = 16
    overrides: Mapping[str, Any] = field(default_factory=dict)

    def sensor(self) -> dc.StudySensor:
        return dc.StudySensor(preset=self.preset, rows=self.rows, cols=self.cols, seed=self.seed,
                              overrides=dict(self.overrides))

    def fpa_grid(self) -> np.ndarray:
        """The FPA temperatures evaluated, K (T_low to T_high every ``fpa_step_K``, both ends)."""
        lo, hi = self.fpa_K
        n = math.floor((hi - lo) / self.fpa_step_K + 1e-9)
        grid = lo + self.fpa_step_K * np.arange(n + 1)
        return np.unique(np.round(np.append(grid, hi), 9))

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        return {k: ([list(x) if isinstance(x, tuple) else x for x in v]
                    if isinstance(v, tuple) else v) for k, v in d.items()}

    def plan_span(self) -> dict[str, Any]:
        """The span the calibration plan covers: ``fpa_K`` and every scenario's FPA (K,
        rounded out to 0.5 K), ``housing_offset_K`` and every scenario's housing - FPA
        difference; the FPA points evenly over it, at most half of ``fpa_K``'s span apart,
        an odd number of them (the middle one the reference)."""
        env = [scenario_envelope(n) for n in self.scenarios]
        lo = _out(min([self.fpa_K[0], *(e["fpa_lo"] for e in env)]), up=False)
        hi = _out(max([self.fpa_K[1], *(e["fpa_hi"] for e in env)]), up=True)
        step = max((self.fpa_K[1] - self.fpa_K[0]) / 2.0, 1.0)
        n = 2 * max(1, math.ceil((hi - lo) / (2.0 * step) - 1e-9)) + 1
        fpa = tuple(round(float(x), 3) for x in np.linspace(lo, hi, n))
        off = sorted(set(self.housing_offset_K))
        if env:
            off[0] = min(off[0], _out(min(e["dh_lo"] for e in env), up=False))
            off[-1] = max(off[-1], _out(max(e["dh_hi"] for e in env), up=True))
        return {"fpa_K": fpa, "housing_offset_K": tuple(float(x) for x in off),
                "scenarios": {n: dict(e) for n, e in zip(self.scenarios, env, strict=True)}}

    def plan(self) -> Any:
        """The calibration plan: the plan scenes, the FPA points and housing offsets of
        :meth:`plan_span` (the scenarios' FPA and housing span)."""
        from irnuc.nuc_fixed.plan import CalibrationPlan

        span = self.plan_span()
        return CalibrationPlan(scene=tuple(dc.PLAN["scene"]), fpa=span["fpa_K"],
                               frames=int(dc.PLAN["frames"]),
                               housing_offset=span["housing_offset_K"])

    def range_bits(self) -> dict[str, int]:
        """The reading ranges (bits, ``reading_range_bits`` / ``housing_range_bits``) that
        hold the plan's FPA and housing span around its reference point, with the plan's
        sensors' LSBs (the methods' readings clamp beyond them)."""
        from irnuc.reports.studies.method_bits import range_bits_for

        plan = self.plan()
        fpa, off = plan.fpa, plan.housing_offset or (0.0,)
        ref = fpa[len(fpa) // 2]
        t_span = max(ref - fpa[0], fpa[-1] - ref) / plan.fpa_sensor.lsb_K
        h_span = max(ref - (fpa[0] + min(off)), fpa[-1] + max(off) - ref) \
            / plan.housing_sensor.lsb_K
        return {"reading_range_bits": range_bits_for(t_span),
                "housing_range_bits": range_bits_for(h_span)}

    def policies(self) -> list[Any]:
        from irnuc.reports.studies.scenarios import policies

        return policies(self.ffc_periods_min, self.ffc_changes_K, self.ffc_either)


def ffc_events(lo: float, hi: float, step_K: float) -> list[float]:
    """FPA temperatures of the shutter events of a ramp from ``lo`` to ``hi``: one every
    ``step_K`` kelvin from ``lo`` (the first at the start), K."""
    n = math.floor((hi - lo) / step_K + 1e-9)
    return [round(lo + k * step_K, 9) for k in range(n + 1)]


def sawtooth_segments(grid: Sequence[float], events: Sequence[float], hi: float
                      ) -> list[tuple[int, list[float]]]:
    """For each shutter event k: the FPA temperatures corrected with its refresh, from the
    event up to and including the next event (the frame on which the shutter closes again;
    the range's end for the last). ``grid`` and ``events`` in K."""
    out = []
    for k, t0 in enumerate(events):
        t1 = events[k + 1] if k + 1 < len(events) else hi
        temps = sorted({t0, t1, *[t for t in grid if t0 <= t <= t1]})
        out.append((k, temps))
    return out


# ---------------------------------------------------------------------------------------
# One method at every width (a worker task)
# ---------------------------------------------------------------------------------------
def method_points(spec_d: Mapping[str, Any], name: str, pts: Any, trajs: Mapping[str, Any],
                  starts: Mapping[tuple[str, str, int], list[int]],
                  ranges: Mapping[str, int] | None = None) -> list[dict[str, Any]]:
    """Every (fraction width[, FFC policy]) point of one method, judged on every scenario
    (JSON-ready records; :mod:`irnuc.reports.studies.scenarios`).

    ``trajs``: scenario name -> :class:`scenarios.Trajectory`; ``starts``: (scenario, policy
    tag, shutter frames) -> the FFC start frames of that policy, closed loop; ``ranges``:
    the reading ranges the plan needs (:meth:`SignoffSpec.range_bits`), given to the
    methods that read those sensors (the point's ``range_bits`` says so when widened).
    """
    import numba

    from irnuc.common.errors import UserError
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.reports.studies import scenarios as scn
    from irnuc.reports.studies.method_bits import with_frac_bits, with_range_bits

    # One thread per worker: the golden model's kernels on frames this small spend more
    # on starting threads than on pixels (and the sweep's workers are the parallelism).
    numba.set_num_threads(1)
    spec = spec_from_dict(spec_d)
    scenes = spec.scene_K
    base = load_pipeline(name)
    out: list[dict[str, Any]] = []
    for f in spec.frac_bits:
        cfg = with_frac_bits(base, f)
        head: dict[str, Any] = {"config": name, "method": base.method, "frac_bits": int(f)}
        if cfg is None:
            out.append({**head, "valid": False, "reason": "illegal fraction width"})
            continue
        try:
            wide = with_range_bits(cfg, **dict(ranges or {}))
        except UserError as exc:
            out.append({**head, "valid": False, "reason": str(exc).splitlines()[0][:200]})
            continue
        if wide is not cfg:
            head["range_bits"] = {k: int(getattr(wide, k)) for k in
                                  ("reading_range_bits", "housing_range_bits")
                                  if getattr(wide, k) != getattr(cfg, k)}
            cfg = wide
        try:
            cal = calibrate_points(pts, cfg)
        except UserError as exc:
            out.append({**head, "valid": False, "reason": str(exc).splitlines()[0][:200]})
            continue
        good = ~cal.bad
        sc = dc.scale(spec.sensor(), cal.targets, sorted(set(pts.scene_K.tolist())))
        mem = dc.memory_bits(cfg)
        rec0 = {**head, "valid": True, **mem,
                "memory_bits": mem["calibration_bits"] + mem["runtime_bits"],
                "bad_fraction": float(cal.bad.mean()),
                "gain_bits": cfg.gain_bits, "offset_bits": cfg.offset_bits,
                "formats": {k: v["format"] for k, v in cal.summary["coefficients"].items()}}
        pols: list[Any] = [None]
        if cfg.has("ffc"):
            reads = "fpa" in cfg.base.readings
            pols = [p for p in spec.policies() if reads or p.change_K is None]
        n_ffc = int(cfg.ffc_frames or 1)
        # per scenario, the frames and refreshes this calibration corrected: the policies
        # share them (the power-on FFC, a period's multiples)
        memos: dict[str, dict[str, Any]] = {sname: {} for sname in trajs}
        for pol in pols:
            per = {}
            for sname, tr in trajs.items():
                st = None if pol is None else starts[sname, pol.tag, n_ffc]
                per[sname] = scn.evaluate(cal, tr, scenes, sc, good, pol, st, spec.max_peaks,
                                          memo=memos[sname])
            rec = {**rec0, "ffc_policy": None if pol is None else pol.tag,
                   "ffc_policy_text": "no shutter" if pol is None else pol.describe(),
                   "ffc_period_min": None if pol is None else pol.period_min,
                   "ffc_change_K": None if pol is None else pol.change_K,
                   **scn.worst_over(per)}
            lost = [k for k, v in per.items()
                    if not (math.isfinite(v["worst_fpn_mK"])
                            and math.isfinite(v["worst_level_error_mK"]))]
            if lost:
                # The corrected image stops answering the scene (saturated: no local
                # responsivity, or a level off the temperature scale): no residual in mK.
                v = per[lost[0]]
                out.append({**head, "ffc_policy": rec["ffc_policy"], "valid": False,
                            "ffc_period_min": rec["ffc_period_min"],
                            "reason": f"the corrected image loses its response on {lost[0]} "
                                      f"(at {v['worst_at_s']:.0f} s: no finite residual in mK; "
                                      "saturated output)"})
                continue
            rec["traces"] = {k: {"trace": v.pop("trace"), "ffc_s": v.pop("ffc_s")}
                             for k, v in per.items()}
            rec["scenarios"] = per
            out.append(rec)
    return out


def spec_from_dict(d: Mapping[str, Any]) -> SignoffSpec:
    keys = SignoffSpec.__dataclass_fields__
    kw = {k: (tuple(tuple(x) if isinstance(x, list) else x for x in v)
              if isinstance(v, list) else v) for k, v in d.items() if k in keys}
    return SignoffSpec(**kw)


# ---------------------------------------------------------------------------------------
# The whole study
# ---------------------------------------------------------------------------------------
def _task(spec_d: dict[str, Any], name: str, pts: Any, trajs: dict, starts: dict,
          ranges: dict[str, int]) -> list:
    return method_points(spec_d, name, pts, trajs, starts, ranges)


def run(spec: SignoffSpec, *, workers: int = 2, scheduler: str | None = None,
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The sweep over the scenarios and the sensor figures of the Temperature section
    (JSON-ready)."""
    from irnuc import model
    from irnuc.common.executor import open_executor
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.plan import run_plan
    from irnuc.reports.studies import camera_temperature
    from irnuc.reports.studies import scenarios as scn

    t0 = time.perf_counter()
    sensor = spec.sensor()
    plan = spec.plan()
    ranges = spec.range_bits()
    pts = run_plan(plan, sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    trajs = {n: scn.trajectory(n, sensor, spec.scene_K, spec.node_K, spec.node_max_s)
             for n in spec.scenarios}
    n_ffcs = {int(load_pipeline(n).ffc_frames or 1) for n in spec.methods
              if load_pipeline(n).has("ffc")}
    starts = {(sn, p.tag, nf): scn.ffc_starts(tr, p, nf)
              for sn, tr in trajs.items() for p in spec.policies() for nf in n_ffcs}
    t_frames = time.perf_counter() - t0
    spec_d = spec.to_dict()
    points: list[dict[str, Any]] = []
    # The shutter methods (a point per FFC policy) cost several times the others: started
    # first, so that no worker is left with one at the end while the other idles; the
    # points are kept in the methods' order.
    npol = len(spec.policies())
    order = sorted(range(len(spec.methods)), key=lambda i: (
        -(npol if load_pipeline(spec.methods[i]).has("ffc") else 1), i))
    with open_executor(workers, scheduler) as handle:
        futs = {i: handle.executor.submit(_task, spec_d, spec.methods[i], pts, trajs, starts,
                                       ranges)
                for i in order}
        done = 0
        for f in cf.as_completed(futs.values()):
            f.result()  # a failure at once
            done += 1
            if progress is not None:
                progress(done, len(futs))
        for i in range(len(spec.methods)):
            points.extend(futs[i].result())
    for i, p in enumerate(points):
        p["index"] = i
        p["key"] = point_key(p)
    t_sweep = time.perf_counter() - t0 - t_frames
    lo, hi = spec.fpa_K
    mid_fpa = 0.5 * (lo + hi)
    # the sensor's noise where datasheets quote it: a 300 K scene, every noise source on
    from irnuc.model.noise_metrics import NETD_SCENE_K

    netd = dc.netd(sensor, mid_fpa)
    cube, _ = dc.frames_at(sensor, mid_fpa, mid_fpa, [NETD_SCENE_K],
                           repeats=spec.noise_frames, noise=True)
    n3 = model.noise_3d(cube)
    scale = 1e3 / netd.responsivity_codes_per_K
    cam = camera_temperature.run(quick=True, sensor=sensor)
    return {
        "study": NAME, "title": TITLE, "spec": spec_d,
        "plan": {"scene": list(plan.scene), "fpa": list(plan.fpa), "frames": plan.frames,
                 "housing_offset": list(plan.housing_offset), "range_bits": ranges,
                 "scenarios": spec.plan_span()["scenarios"]},
        "scenarios": {n: scn.summary(tr) for n, tr in trajs.items()},
        "policies": [{"tag": p.tag, "text": p.describe()} for p in spec.policies()],
        "points": points,
        "netd": netd.as_dict(), "netd_mK": float(netd) * 1e3,
        "noise_3d": {"frame": [spec.noise_frames, spec.rows, spec.cols], "fpa_K": mid_fpa,
                     "scene_K": NETD_SCENE_K, "mean_codes": n3.mean,
                     "components": n3.as_dict(scale=scale, unit="mK")},
        "camera_temperature": cam,
        "seconds": {"frames": round(t_frames, 3), "sweep": round(t_sweep, 3),
                    "total": round(time.perf_counter() - t0, 3)},
    }


def point_key(p: Mapping[str, Any]) -> str:
    """The point's name in metric keys: ``<config>_f<bits>[_p<period min>]``."""
    k = f"{p['config']}_f{p['frac_bits']}"
    if p.get("ffc_policy"):
        k += f"_{p['ffc_policy']}"
    elif p.get("ffc_period_min") is not None:
        k += f"_p{p['ffc_period_min']:g}"
    return k


def code_digest() -> str:
    """Hash of the code a stored result measured: the physics model, the golden model and
    the studies this module runs."""
    from irnuc import model, nuc_fixed
    from irnuc.common.digest import named_files_digest, package_files
    from irnuc.reports.studies import camera_temperature, method_bits

    files: list[tuple[str, Path]] = []
    for pkg, tag in ((model, "model"), (nuc_fixed, "nuc_fixed")):
        files += package_files(pkg, tag, ("*.py", "*.toml"))
    from irnuc.reports.studies import scenarios as scn

    for mod in (dc, camera_temperature, method_bits, scn):
        files.append((f"studies/{Path(mod.__file__).name}", Path(mod.__file__)))
    files.append(("studies/signoff.py", Path(__file__)))
    return named_files_digest(files)


def cache_file(spec: SignoffSpec, digest: str | None = None) -> Path:
    from irnuc.common.cache import cache_dir

    key = hashlib.sha256(json.dumps(spec.to_dict(), sort_keys=True).encode()).hexdigest()[:16]
    return cache_dir("temperature") / f"{digest or code_digest()}-{key}.json"


def cached_signoff(spec: SignoffSpec, *, workers: int = 2, scheduler: str | None = None,
                   progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """:func:`run` of the current code, from the cache when stored, else run and stored
    (atomically); ``cached`` says which."""
    from irnuc.common.io import write_text_atomic

    d = code_digest()
    path = cache_file(spec, d)
    if path.is_file():
        try:
            data = json.loads(path.read_text())
            if data.get("code_digest") == d and data.get("spec") == spec.to_dict():
                return {**data, "cached": True}
        except (OSError, json.JSONDecodeError):
            pass  # a damaged entry is measured again
    result = {**run(spec, workers=workers, scheduler=scheduler, progress=progress),
              "code_digest": d}
    write_text_atomic(path, json.dumps(result) + "\n")
    return {**result, "cached": False}


# ---------------------------------------------------------------------------------------
# Choosing: tolerance, recommendation, edges, fronts
# ---------------------------------------------------------------------------------------
def recommend(points: Sequence[Mapping[str, Any]], tolerance_mK: float,
              datapath: Mapping[int, float] | None = None) -> dict[str, Any]:
    """The cheapest valid point whose worst residual (worst over the scenarios) is at most
    ``tolerance_mK``.

    Cheapest: fewest coefficient memory bits per pixel (calibration + runtime: the store
    that dominates a VGA camera's cost), then the lowest read bandwidth bits, then the
    lowest datapath cost (``datapath``: index -> cost), then the least dead time (the
    shutter's frames lost, worst scenario; no shutter: 0), then the fewest FFCs per hour,
    then the lowest residual, then the index. Returns ``{found, index, candidates}``
    (candidates: every point meeting the tolerance, cheapest first).
    """
    dp = datapath or {}
    ok = [p for p in points if p.get("valid") and p["worst_fpn_mK"] <= tolerance_mK]

    def cost(p: Mapping[str, Any]) -> tuple:
        return (p["memory_bits"], p["read_bits_per_frame"], dp.get(p["index"], 0.0),
                p.get("dead_time_pct") or 0.0, p.get("ffc_per_hour") or 0.0,
                p["worst_fpn_mK"], p["index"])

    ok.sort(key=cost)
    if not ok:
        return {"found": False, "index": None, "candidates": []}
    return {"found": True, "index": ok[0]["index"], "candidates": [p["index"] for p in ok]}


def grid_edges(point: Mapping[str, Any], points: Sequence[Mapping[str, Any]],
               periods: Sequence[float], meets: bool = True) -> list[dict[str, str]]:
    """Where ``point`` sits on the swept grid of its method, and which way to widen.

    A point meeting the tolerance (``meets``) at the smallest valid swept fraction width
    may also meet it with fewer bits; at the largest, only the widest meets (more bits may
    buy margin); at the longest swept FFC period a longer one may also meet; at the
    shortest (of several) only the shortest meets. A point that does not meet it (the
    lowest residual) at the largest width or the shortest period may do better beyond.
    """
    bits = sorted({p["frac_bits"] for p in points
                   if p["config"] == point["config"] and p.get("valid")})
    out = []
    f = point["frac_bits"]
    per = point.get("ffc_period_min")

    def edge(axis: str, side: str, widen: str) -> None:
        out.append({"axis": axis, "edge": side, "widen": widen})

    if meets:
        if bits and f == bits[0]:
            edge("frac_bits", "bottom", f"add frac_bits below {f} (fewer bits may also meet)")
        if bits and f == bits[-1]:
            edge("frac_bits", "top", f"add frac_bits above {f} (only the widest swept width meets)")
        if per is not None and periods and per == max(periods):
            edge("ffc_periods_min", "top", f"add FFC periods above {per:g} min (a longer one "
                 "may also meet)")
        if per is not None and len(periods) > 1 and per == min(periods):
            edge("ffc_periods_min", "bottom", f"add FFC periods below {per:g} min (only the "
                 "shortest meets)")
        return out
    if bits and f == bits[-1]:
        edge("frac_bits", "top", f"add frac_bits above {f} (more bits may lower the residual)")
    if per is not None and periods and per == min(periods):
        edge("ffc_periods_min", "bottom", f"add FFC periods below {per:g} min (a shorter one "
             "may lower the residual)")
    return out


def fronts(points: Sequence[Mapping[str, Any]], cost_key: str = "memory_bits"
           ) -> dict[str, Any]:
    """Pareto fronts of worst residual (mK) against ``cost_key``, both minimised: over every
    valid point (``overall``) and per configuration (``per_method``); point indices."""
    from irnuc.reports.studies.metrics import pareto_front

    valid = [p for p in points if p.get("valid") and p.get(cost_key) is not None]

    def front(ps: Sequence[Mapping[str, Any]]) -> list[int]:
        if not ps:
            return []
        idx = pareto_front([p[cost_key] for p in ps], [p["worst_fpn_mK"] for p in ps])
        return [int(ps[i]["index"]) for i in idx]

    per = {}
    for name in dict.fromkeys(p["config"] for p in valid):
        per[name] = front([p for p in valid if p["config"] == name])
    return {"cost": cost_key, "overall": front(valid), "per_method": per}


def bandwidth_MBps(read_bits: int, frame: Sequence[int], rate_hz: float) -> float:
    """External-memory read bandwidth of ``read_bits`` per pixel per frame, 10^6 bytes/s."""
    return round(read_bits * int(frame[0]) * int(frame[1]) * rate_hz / 8e6, 3)


def figures(result: Mapping[str, Any], rec: Mapping[str, Any] | None,
            images: Mapping[str, Any] | None) -> list[tuple[str, bytes]]:
    """The Temperature section's figures: per scenario, the residual against time of each
    configuration (its cheapest point meeting the tolerance, else its best) with its FFC
    events marked, and the housing-FPA difference beside it; the fronts against memory,
    datapath and dead time; the images at the recommendation's worst frame."""
    from irnuc.reports.studies.figures import png

    plt = dc.pyplot()
    pts = [p for p in result["points"] if p.get("valid")]
    tol = result["tolerance_mK"]
    netd = result["netd_mK"]
    out = []
    shown = [p for p in representative(pts, tol) if p.get("traces")]
    scen = result.get("scenarios") or {}
    if shown and scen:
        fig, axes = plt.subplots(len(scen), 2, figsize=(12, 3.3 * len(scen)), squeeze=False,
                                 gridspec_kw={"width_ratios": [2.2, 1]})
        for row, (name, sc) in zip(axes, scen.items(), strict=True):
            ax, ax2 = row
            for i, p in enumerate(shown):
                tr = p["traces"].get(name)
                if not tr or not tr["trace"]:
                    continue
                ts, mk, _ = zip(*tr["trace"], strict=True)
                ls = "-" if i < 10 else "--"
                ax.plot(np.asarray(ts) / 60.0, mk, ls, lw=1.0, color=f"C{i % 10}",
                        label=f"{p['key']}" + (" (recommended)" if rec and rec["key"] == p["key"]
                                               else ""))
                ev = tr.get("ffc_s") or []
                if ev and len(ev) <= 400:  # the FFC events as ticks at the bottom
                    ax.plot(np.asarray(ev) / 60.0, np.full(len(ev), 0.0), "|", ms=6,
                            color=f"C{i % 10}", transform=ax.get_xaxis_transform(), clip_on=False)
            ax.axhline(tol, color="k", ls="--", lw=1, label=f"tolerance {tol:.3g} mK")
            ax.axhline(netd, color="k", ls=":", lw=1, label=f"NETD {netd:.3g} mK")
            ax.set_yscale("log")
            ax.set_xlabel("time, min (ticks at the bottom: FFC events)")
            ax.set_ylabel("worst residual, mK")
            ax.set_title(f"{name}: {sc.get('description', '')}", fontsize=8)
            ax.grid(alpha=0.3)
            c = sc["curve"]
            tm = np.asarray(c["t_s"]) / 60.0
            ax2.plot(tm, np.asarray(c["housing_K"]) - np.asarray(c["fpa_K"]), "k-", lw=1.2,
                     label="housing - FPA")
            ax2.set_ylabel("housing - FPA, K")
            ax2.set_xlabel("time, min")
            ax3 = ax2.twinx()
            ax3.plot(tm, c["fpa_K"], "C3-", lw=0.8, label="FPA")
            ax3.plot(tm, c["housing_K"], "C0-", lw=0.8, label="housing")
            ax3.set_ylabel("K", fontsize=7)
            ax2.grid(alpha=0.3)
            h1, l1 = ax2.get_legend_handles_labels()
            h2, l2 = ax3.get_legend_handles_labels()
            ax2.legend(h1 + h2, l1 + l2, fontsize=6)
        axes[0][0].legend(fontsize=6, ncol=2)
        fig.tight_layout()
        out.append(("Residual fixed pattern against time on each thermal scenario, one line "
                    "per configuration (its cheapest point meeting the tolerance on every "
                    "scenario, else its lowest residual), its FFC events as ticks; beside it "
                    "the housing-FPA difference the scenario drives (and both temperatures)",
                    png(fig)))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    fr = result.get("fronts") or {}
    for ax, key, label in ((axes[0], "memory_bits", "coefficient memory, bits per pixel"),
                           (axes[1], "datapath_cost", "datapath cost, xc7 LUT + DSP equivalent"),
                           (axes[2], "dead_time_pct", "dead time (shutter), % of frames, "
                                                      "worst scenario")):
        cfgs = list(dict.fromkeys(p["config"] for p in pts))
        for i, c in enumerate(cfgs):
            ps = [p for p in pts if p["config"] == c and p.get(key) is not None]
            ax.scatter([p[key] for p in ps], [p["worst_fpn_mK"] for p in ps], s=10,
                       color=f"C{i % 10}", marker="o" if i < 10 else "^", label=c)
        front = (fr.get(key) or {}).get("overall") or []
        byi = {p["index"]: p for p in pts}
        fp = [byi[i] for i in front if i in byi and byi[i].get(key) is not None]
        if fp:
            ax.step([p[key] for p in fp], [p["worst_fpn_mK"] for p in fp], "k-", where="post",
                    lw=0.8, label="front")
        if rec and rec.get(key) is not None:
            ax.plot([rec[key]], [rec["worst_fpn_mK"]], "r*", ms=12, label="recommended")
        ax.axhline(tol, color="k", ls="--", lw=0.8)
        ax.set_yscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel("worst residual over the scenarios, mK")
        ax.grid(alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(fontsize=6, ncol=2)
    fig.tight_layout()
    out.append(("Pareto fronts of the worst residual over the scenarios against coefficient "
                "memory (left), the datapath cost (middle) and the shutter's dead time "
                "(right); the star is the recommendation, the dashed line the tolerance",
                png(fig)))
    if images:
        keys = list(images)
        fig, axes = plt.subplots(1, 2 * len(keys), figsize=(12 * len(keys), 4.4), squeeze=False)
        for j, k in enumerate(keys):
            im = images[k]
            for i, (what, arr) in enumerate((("raw", im["raw"]), ("corrected", im["corrected"]))):
                a = np.asarray(arr, dtype=np.float64)
                ax = axes[0][2 * j + i]
                h = ax.imshow(a, cmap="gray")
                fig.colorbar(h, ax=ax, fraction=0.04)
                ax.set_title(f"{what}: {im.get('scenario', '')} t = {im.get('time_s', 0):.0f} s, "
                             f"FPA {im['fpa_K']:.2f} K, housing {im.get('housing_K', 0):.2f} K, "
                             f"scene {im['scene_K']:g} K\n(std "
                             f"{a[np.asarray(im['good'])].std():.3g} codes)", fontsize=7)
                ax.set_xticks([])
                ax.set_yticks([])
        out.append(("Raw and corrected images of a uniform scene at the recommendation's worst "
                    "frame (its worst scenario; each image on its own grey scale)", png(fig)))
    return out


def representative(points: Sequence[Mapping[str, Any]], tol: float) -> list[Mapping[str, Any]]:
    """One point per configuration: its cheapest meeting ``tol``, else its lowest residual."""
    out = []
    for name in dict.fromkeys(p["config"] for p in points):
        ps = [p for p in points if p["config"] == name]
        r = recommend(ps, tol)
        if r["found"]:
            out.append(next(p for p in ps if p["index"] == r["index"]))
        else:
            out.append(min(ps, key=lambda p: (p["worst_fpn_mK"], p["index"])))
    return out
