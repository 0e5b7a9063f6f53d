"""Study: the sign-off sweep of a drifting camera: correction method x coefficient widths x
FFC period over an FPA temperature range, against memory and bandwidth.

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
#: Every method the sign-off compares (one configuration each; ``drift14`` and the FFC
#: compositions are stages on a base method).
METHODS: tuple[str, ...] = ("onepoint14", "typical14", "piecewise14", "quadratic14", "tcoffset14",
                            "tcgain14", "table14", "drift14", "ffc14", "tcffc14", "quadffc14")


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
    methods: tuple[str, ...] = METHODS
    frac_bits: tuple[int, ...] = (6, 8, 10, 12, 14)
    ffc_periods_min: tuple[float, ...] = (0.5, 1.0, 2.0, 4.0)
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
        return {k: list(v) if isinstance(v, tuple) else v for k, v in d.items()}


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
def _frames(sensor: dc.StudySensor, temps: Sequence[float], scenes: Sequence[float],
            fpa_sensor: Any) -> dict[float, tuple[np.ndarray, np.ndarray, int]]:
    """FPA temperature -> (raw frames of every scene and 0.5 K either side, blind codes,
    the FPA reading): what :func:`metrics.residuals_mK` needs."""
    out = {}
    for t in temps:
        raw, blind = dc.slope_frames(sensor, t, t, scenes)
        out[float(t)] = (raw, blind, int(fpa_sensor.read(t)[0]))
    return out


def _worst(y: np.ndarray, good: np.ndarray, scenes: Sequence[float],
           sc: Any) -> tuple[float, float, float]:
    """(worst fixed pattern LSB, mK, worst |level error| mK) over the scenes."""
    res = dc.residuals(y, good, scenes, sc)
    return (max(r["fpn_lsb"] for r in res), max(r["fpn_mK"] for r in res),
            max(abs(r["level_error_mK"]) for r in res))


def method_points(spec_d: Mapping[str, Any], name: str, pts: Any,
                  frames: Mapping[float, tuple[np.ndarray, np.ndarray, int]],
                  shutter: Mapping[float, tuple[np.ndarray, np.ndarray, int]]
                  ) -> list[dict[str, Any]]:
    """Every (fraction width[, FFC period]) point of one method (JSON-ready records).

    ``frames``: FPA temperature -> (raw scene frames, blind codes, FPA reading);
    ``shutter``: FPA temperature of a shutter event -> (one shutter frame, blind, reading).
    """
    from irnuc.common.errors import UserError
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top
    from irnuc.reports.studies.method_bits import with_frac_bits

    spec = spec_from_dict(spec_d)
    scenes = spec.scene_K
    grid = [float(t) for t in spec.fpa_grid()]
    lo, hi = spec.fpa_K
    base = load_pipeline(name)
    out: list[dict[str, Any]] = []
    for f in spec.frac_bits:
        cfg = with_frac_bits(base, f)
        head = {"config": name, "method": base.method, "frac_bits": int(f)}
        if cfg is None:
            out.append({**head, "valid": False, "reason": "illegal fraction width"})
            continue
        try:
            cal = calibrate_points(pts, cfg)
        except UserError as exc:
            out.append({**head, "valid": False, "reason": str(exc).splitlines()[0][:200]})
            continue
        good = ~cal.bad
        sc = dc.scale(spec.sensor(), cal.targets, pts.scene_K.tolist())
        mem = dc.memory_bits(cfg)
        rec0 = {**head, "valid": True, **mem,
                "memory_bits": mem["calibration_bits"] + mem["runtime_bits"],
                "bad_fraction": float(cal.bad.mean()),
                "gain_bits": cfg.gain_bits, "offset_bits": cfg.offset_bits,
                "formats": {k: v["format"] for k, v in cal.summary["coefficients"].items()}}
        if not cfg.has("ffc"):
            per = []
            for t in grid:
                raw, blind, rd = frames[t]
                y = method_top(raw, cal.coeffs, FrameInputs(
                    reading=np.full(len(raw), rd), blind_codes=blind)).y
                per.append([t, *_worst(y, good, scenes, sc)])
            out.append({**rec0, "ffc_period_min": None, "ffc_events": 0,
                        "per_fpa": [[p[0], p[2]] for p in per],
                        "worst_fpn_lsb": max(p[1] for p in per),
                        "worst_fpn_mK": max(p[2] for p in per),
                        "worst_level_error_mK": max(p[3] for p in per)})
            continue
        n_ffc = int(cfg.ffc_frames or 1)
        # Shutter events and the frames after them repeat across the periods (every
        # period's events lie on one grid of temperatures): each computed once.
        refs: dict[float, np.ndarray] = {}
        seen: dict[tuple[float, float], tuple[float, float]] = {}
        for period in spec.ffc_periods_min:
            events = ffc_events(lo, hi, spec.ramp_K_per_min * period)
            saw = []  # [time min, FPA K, worst mK]
            worst_lsb = worst_level = 0.0
            for k, temps in sawtooth_segments(grid, events, hi):
                for t in temps:
                    if (events[k], t) not in seen:
                        raw, blind, rd = frames[t]
                        y = method_top(raw, cal.coeffs, FrameInputs(
                            reading=np.full(len(raw), rd), blind_codes=blind,
                            shutter=np.zeros(len(raw), bool)),
                            ffc_offset=_refresh(refs, events[k], shutter, cal, n_ffc)).y
                        seen[events[k], t] = _worst(y, good, scenes, sc)
                    w_lsb, w_mk, w_level = seen[events[k], t]
                    worst_lsb = max(worst_lsb, w_lsb)
                    worst_level = max(worst_level, w_level)
                    saw.append([(t - lo) / spec.ramp_K_per_min, t, w_mk])
            out.append({**rec0, "ffc_period_min": float(period), "ffc_events": len(events),
                        "sawtooth": saw,
                        "per_fpa": _per_fpa_worst(saw),
                        "worst_fpn_lsb": worst_lsb, "worst_fpn_mK": max(s[2] for s in saw),
                        "worst_level_error_mK": worst_level})
    return out


def _refresh(refs: dict[float, np.ndarray], t0: float, shutter: Mapping[float, tuple], cal: Any,
             n: int) -> np.ndarray:
    """The FFC correction after the shutter event at ``t0`` (``n`` shutter frames), kept in
    ``refs``."""
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    if t0 not in refs:
        sraw, sblind, srd = shutter[t0]
        refs[t0] = method_top(np.repeat(sraw, n, axis=0), cal.coeffs, FrameInputs(
            reading=np.full(n, srd), blind_codes=np.repeat(sblind, n, axis=0),
            shutter=np.ones(n, bool))).ffc_offset
    return refs[t0]


def _per_fpa_worst(saw: Sequence[Sequence[float]]) -> list[list[float]]:
    by: dict[float, float] = {}
    for _, t, mk in saw:
        by[t] = max(by.get(t, 0.0), mk)
    return [[t, by[t]] for t in sorted(by)]


def spec_from_dict(d: Mapping[str, Any]) -> SignoffSpec:
    keys = SignoffSpec.__dataclass_fields__
    kw = {k: tuple(v) if isinstance(v, list) else v for k, v in d.items() if k in keys}
    return SignoffSpec(**kw)


# ---------------------------------------------------------------------------------------
# The whole study
# ---------------------------------------------------------------------------------------
def _task(spec_d: dict[str, Any], name: str, pts: Any, frames: dict, shutter: dict) -> list:
    return method_points(spec_d, name, pts, frames, shutter)


def run(spec: SignoffSpec, *, workers: int = 2, scheduler: str | None = None,
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The sweep and the sensor figures of the Temperature section (JSON-ready)."""
    from irnuc import model
    from irnuc.common.executor import open_executor
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan
    from irnuc.reports.studies import camera_temperature

    t0 = time.perf_counter()
    sensor = spec.sensor()
    plan = CalibrationPlan(scene=tuple(dc.PLAN["scene"]), fpa=tuple(dc.PLAN["fpa"]),
                           frames=int(dc.PLAN["frames"]))
    pts = run_plan(plan, sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    grid = [float(t) for t in spec.fpa_grid()]
    lo, hi = spec.fpa_K
    ev = sorted({t for p in spec.ffc_periods_min
                 for t in ffc_events(lo, hi, spec.ramp_K_per_min * p)})
    frames = _frames(sensor, sorted(set(grid) | set(ev)), spec.scene_K, plan.fpa_sensor)
    shutter = {}
    for t in ev:
        raw, blind = dc.frames_at(sensor, t, t, [t])
        shutter[t] = (raw, blind, int(plan.fpa_sensor.read(t)[0]))
    t_frames = time.perf_counter() - t0
    spec_d = spec.to_dict()
    points: list[dict[str, Any]] = []
    with open_executor(workers, scheduler) as handle:
        futs = [handle.executor.submit(_task, spec_d, n, pts, frames, shutter)
                for n in spec.methods]
        for i, fut in enumerate(futs):
            points.extend(fut.result())
            if progress is not None:
                progress(i + 1, len(futs))
    for i, p in enumerate(points):
        p["index"] = i
        p["key"] = point_key(p)
    t_sweep = time.perf_counter() - t0 - t_frames
    mid_fpa = 0.5 * (lo + hi)
    mid_scene = float(np.median(spec.scene_K))
    # the sensor's noise where datasheets quote it: a 300 K scene
    from irnuc.model.noise_metrics import NETD_SCENE_K

    netd = dc.netd(sensor, mid_fpa)
    cube, _ = dc.frames_at(sensor, mid_fpa, mid_fpa, [NETD_SCENE_K],
                           repeats=spec.noise_frames, noise=True)
    n3 = model.noise_3d(cube)
    scale = 1e3 / netd.responsivity_codes_per_K
    cam = camera_temperature.run(quick=True, sensor=sensor)
    ends = {}
    for t in (lo, hi):
        raw, blind, rd = frames[float(t)]
        k = int(np.argmin(np.abs(np.asarray(spec.scene_K) - mid_scene)))
        ends[f"{t:g}"] = {"fpa_K": float(t), "scene_K": float(spec.scene_K[k]),
                          "raw": raw[3 * k].tolist(), "blind": blind[3 * k].tolist(),
                          "reading": rd}
    return {
        "study": NAME, "title": TITLE, "spec": spec_d,
        "plan": {"scene": list(plan.scene), "fpa": list(plan.fpa), "frames": plan.frames},
        "fpa_grid_K": grid, "points": points,
        "netd": netd.as_dict(), "netd_mK": float(netd) * 1e3,
        "noise_3d": {"frame": [spec.noise_frames, spec.rows, spec.cols], "fpa_K": mid_fpa,
                     "scene_K": NETD_SCENE_K, "mean_codes": n3.mean,
                     "components": n3.as_dict(scale=scale, unit="mK")},
        "camera_temperature": cam, "ends": ends,
        "seconds": {"frames": round(t_frames, 3), "sweep": round(t_sweep, 3),
                    "total": round(time.perf_counter() - t0, 3)},
    }


def point_key(p: Mapping[str, Any]) -> str:
    """The point's name in metric keys: ``<config>_f<bits>[_p<period min>]``."""
    k = f"{p['config']}_f{p['frac_bits']}"
    if p.get("ffc_period_min") is not None:
        k += f"_p{p['ffc_period_min']:g}"
    return k


def code_digest() -> str:
    """Hash of the code a stored result measured: the physics model, the golden model and
    the studies this module runs."""
    from irnuc import model, nuc_fixed
    from irnuc.reports.studies import camera_temperature, method_bits

    files: list[tuple[str, Path]] = []
    for pkg, tag in ((model, "model"), (nuc_fixed, "nuc_fixed")):
        root = Path(pkg.__file__).parent
        files += [(f"{tag}/{p.relative_to(root).as_posix()}", p)
                  for p in sorted([*root.rglob("*.py"), *root.rglob("*.toml")])]
    for mod in (dc, camera_temperature, method_bits):
        files.append((f"studies/{Path(mod.__file__).name}", Path(mod.__file__)))
    files.append(("studies/signoff.py", Path(__file__)))
    h = hashlib.sha256()
    for name, path in files:
        h.update(name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


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
    """The cheapest valid point whose worst residual is at most ``tolerance_mK``.

    Cheapest: fewest coefficient memory bits per pixel (calibration + runtime: the store
    that dominates a VGA camera's cost), then the lowest read bandwidth bits, then the
    lowest datapath cost (``datapath``: index -> cost), then the longest FFC period (the
    shutter interrupts the image least; no shutter counts as infinite), then the lowest
    residual, then the index. Returns ``{found, index, candidates}`` (candidates: every
    point meeting the tolerance, cheapest first).
    """
    dp = datapath or {}
    ok = [p for p in points if p.get("valid") and p["worst_fpn_mK"] <= tolerance_mK]

    def cost(p: Mapping[str, Any]) -> tuple:
        period = p.get("ffc_period_min")
        return (p["memory_bits"], p["read_bits_per_frame"], dp.get(p["index"], 0.0),
                -(math.inf if period is None else period), p["worst_fpn_mK"], p["index"])

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
    """The Temperature section's figures: residual against FPA temperature per method (each
    at its cheapest width meeting the tolerance, else its best), the FFC sawtooth, the
    fronts, the raw / corrected images at both ends of the drift."""
    from irnuc.reports.studies.figures import png

    plt = dc.pyplot()
    pts = [p for p in result["points"] if p.get("valid")]
    tol = result["tolerance_mK"]
    netd = result["netd_mK"]
    out = []
    shown = representative(pts, tol)
    fig, ax = plt.subplots(figsize=(8, 4.2))
    for i, p in enumerate(shown):
        xs, ys = zip(*p["per_fpa"], strict=True)
        ax.plot(xs, ys, marker="o", ms=2.5, color=f"C{i % 10}", ls="-" if i < 10 else "--",
                label=f"{p['key']} ({p['memory_bits']} b/px)")
    ax.axhline(tol, color="k", ls="--", lw=1, label=f"tolerance {tol:.3g} mK")
    ax.axhline(netd, color="k", ls=":", lw=1, label=f"NETD {netd:.3g} mK")
    ax.set_yscale("log")
    ax.set_xlabel("FPA temperature, K")
    ax.set_ylabel("worst residual fixed pattern over the scenes, mK")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    out.append(("Residual fixed pattern against FPA temperature, one line per method (its "
                "cheapest point meeting the tolerance, else its lowest residual); FFC methods "
                "at their FFC period, worst between shutter events", png(fig)))
    saw = [p for p in shown if p.get("sawtooth")]
    if saw:
        fig, ax = plt.subplots(figsize=(8, 3.8))
        for i, p in enumerate(saw):
            ts, _, mk = zip(*p["sawtooth"], strict=True)
            ax.plot(ts, mk, "-", lw=1.2, color=f"C{i}", label=p["key"])
        ax.axhline(tol, color="k", ls="--", lw=1, label="tolerance")
        ax.axhline(netd, color="k", ls=":", lw=1, label="NETD")
        ax.set_yscale("log")
        ax.set_xlabel(f"time, min (FPA ramp {result['spec']['ramp_K_per_min']:g} K/min from "
                      f"{result['spec']['fpa_K'][0]:g} K)")
        ax.set_ylabel("worst residual over the scenes, mK")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        out.append(("The FFC sawtooth: residual against time while the FPA ramps; each "
                    "shutter event refreshes the offsets (the drop), the drift between events "
                    "raises the residual again", png(fig)))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    fr = result.get("fronts") or {}
    for ax, key, label in ((axes[0], "memory_bits", "coefficient memory, bits per pixel"),
                           (axes[1], "datapath_cost", "datapath cost, xc7 LUT + DSP equivalent")):
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
        ax.set_ylabel("worst residual, mK")
        ax.grid(alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(fontsize=6, ncol=2)
    out.append(("Pareto fronts of the worst residual against coefficient memory (left) and "
                "against the datapath cost (right); the star is the recommendation, the "
                "dashed line the tolerance", png(fig)))
    if images:
        keys = list(images)
        fig, axes = plt.subplots(2, len(keys), figsize=(4.2 * len(keys), 6), squeeze=False)
        for j, k in enumerate(keys):
            im = images[k]
            for i, (what, arr) in enumerate((("raw", im["raw"]), ("corrected", im["corrected"]))):
                a = np.asarray(arr, dtype=np.float64)
                ax = axes[i][j]
                h = ax.imshow(a, cmap="gray")
                fig.colorbar(h, ax=ax, fraction=0.04)
                ax.set_title(f"{what}, FPA {im['fpa_K']:g} K, scene {im['scene_K']:g} K "
                             f"(std {a[np.asarray(im['good'])].std():.3g} codes)", fontsize=8)
                ax.set_xticks([])
                ax.set_yticks([])
        out.append(("Raw and corrected images of a uniform scene at both ends of the drift "
                    "(the recommendation; each image on its own grey scale)", png(fig)))
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
