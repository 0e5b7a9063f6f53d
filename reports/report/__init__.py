"""``irnuc report``: the hardware team's regression report (``docs/reports.md``).

Phases, each run only when the configuration (``reports/report_<name>.toml``) has its
section and, for the optional parts, when the code it needs exists:

1. ``frames``       sensor frames with injected defects (``model``)
2. ``calibration``  golden-model calibration and bad-pixel detection, scored against the
                    model's ground truth; NUC + DPC of the evaluation frames
3. ``sweep``        coefficient bit-width sweep (:mod:`reports.sweep`)
4. ``paper``        the paper's Table 2 and Table 1 grids and the comparison with its
                    reference implementation
5. ``cosim``        the RTL co-simulation regression (``pytest cocotb_tests`` in a
                    subprocess, a fast subset) or an ingested JUnit XML (``--junit``)
6. ``precision``    the numerical-fidelity summary of ``reports/precision.py``, if present

Outputs (atomically written): ``index.html`` (one self-contained file, PNG figures as
base64), ``summary.json`` (validated against ``reports/summary.schema.json`` when
``jsonschema`` is installed) and ``junit.xml`` (the co-simulation results, when there are
any). ``--baseline`` compares every metric with an earlier ``summary.json``; the exit
status is 1 on a regression or a failing co-simulation test.

Only the standard library, numpy and the project's own packages are imported; matplotlib
is imported when the figures are drawn; jsonschema and dask are optional.
"""

from __future__ import annotations

import base64
import copy
import datetime as _dt
import hashlib
import html
import importlib
import importlib.metadata
import importlib.util
import json
import math
import os
import platform
import subprocess
import sys
import time
import tomllib
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.common.errors import UserError

REPORTS_DIR = Path(__file__).resolve().parent
REPO_ROOT = REPORTS_DIR.parent
SCHEMA_PATH = REPORTS_DIR / "summary.schema.json"
SCHEMA_VERSION = 1
PRECISION_FUNCTIONS = ("report_summary", "summary_for_report", "precision_summary", "summary")

# Default tolerances of the baseline comparison (docs/reports.md): the pipeline is
# deterministic (same config + seed -> same bits), so counts must match exactly and float
# metrics within what a different numpy summation order could change.
FLOAT_REL_TOL = 1e-6
FLOAT_ABS_TOL = 1e-9


class _Skip(Exception):
    """A phase cannot run here (its tools are missing); recorded as a note."""


class ReportError(UserError):
    """A report configuration or input is invalid (names the field and the allowed values)."""


# ---------------------------------------------------------------------------------------
# Configuration
# ---------------------------------------------------------------------------------------
def _set_dotted(d: dict[str, Any], dotted: str, value: Any) -> None:
    keys = dotted.split(".")
    cur = d
    for k in keys[:-1]:
        if not isinstance(cur.get(k), dict):
            raise ReportError(f"quick override {dotted!r}: {k!r} is not a table of the configuration")
        cur = cur[k]
    cur[keys[-1]] = value


def load_report_config(name_or_path: str = "default", quick: bool = False) -> dict[str, Any]:
    """The report configuration: an embedded name (``default``, ``small``) or a TOML path.

    With ``quick``, the dotted overrides of its ``[quick]`` table are applied.
    """
    path = REPORTS_DIR / f"report_{name_or_path}.toml"
    if not path.is_file():
        path = Path(name_or_path)
        if not path.is_file():
            known = sorted(p.stem.removeprefix("report_") for p in REPORTS_DIR.glob("report_*.toml"))
            raise ReportError(f"--config {name_or_path!r} is neither an embedded configuration "
                              f"({', '.join(known)}) nor a TOML file")
    with path.open("rb") as fh:
        try:
            cfg = tomllib.load(fh)
        except tomllib.TOMLDecodeError as exc:
            raise ReportError(f"--config {path}: {exc}") from None
    quick_over = cfg.pop("quick", {}) or {}
    if quick:
        for k, v in quick_over.items():
            _set_dotted(cfg, k, v)
    cfg.setdefault("name", path.stem.removeprefix("report_"))
    cfg["quick"] = bool(quick)
    _check_config(cfg)
    return cfg


def _need(section: Mapping[str, Any], where: str, key: str, kind: type | tuple, lo: float | None = None,
          hi: float | None = None) -> Any:
    if key not in section:
        raise ReportError(f"{where}.{key} is missing")
    v = section[key]
    if kind in (int, float, (int, float)) and isinstance(v, bool):
        raise ReportError(f"{where}.{key} = {v!r} must be a number")
    if not isinstance(v, kind):
        raise ReportError(f"{where}.{key} = {v!r} has the wrong type (expected {kind})")
    if lo is not None and not (lo <= v <= (hi if hi is not None else math.inf)):
        raise ReportError(f"{where}.{key} = {v!r} is outside the allowed range {lo}..{hi}")
    return v


def _check_config(cfg: Mapping[str, Any]) -> None:
    """Check the fields every phase reads, before any work."""
    num = (int, float)
    for sec in ("sensor", "sweep"):
        if sec in cfg:
            s = cfg[sec]
            _need(s, sec, "preset", str)
            _need(s, sec, "seed", int, 0, 2**63 - 1)
            _need(s, sec, "rows", int, 3, 4096)
            _need(s, sec, "cols", int, 3, 4096)
            _need(s, sec, "repeats", int, 1, 1000)
            _need(s, sec, "t_low", num, 1.0, 1e4)
            _need(s, sec, "t_high", num, 1.0, 1e4)
            _need(s, sec, "t_eval", list)
            _need(s, sec, "pipeline", str)
    if "sweep" in cfg:
        s = cfg["sweep"]
        for key in ("gain_frac_bits", "offset_frac_bits"):
            _need(s, "sweep", key, list)
        _need(s, "sweep", "max_error", num, 1e-12, 1e12)
        _need(s, "sweep", "workers", int, 0, 256)
    if "paper" in cfg:
        p = cfg["paper"]
        _need(p, "paper", "preset", str)
        _need(p, "paper", "seed", int, 0, 2**63 - 1)
        _need(p, "paper", "rows", int, 3, 4096)
        _need(p, "paper", "cols", int, 3, 4096)
        fb = _need(p, "paper", "frac_bits", list)
        ref = _need(p, "paper", "reference_nu", list)
        if len(ref) != len(fb):
            raise ReportError(f"paper.reference_nu has {len(ref)} values but paper.frac_bits has {len(fb)}")
        _need(p, "paper", "grid_temps", list)
        if "table1" in p:
            t1 = p["table1"]
            for key in ("temps", "tolerances", "skimming"):
                _need(t1, "paper.table1", key, list)
            for sk in t1["skimming"]:
                if sk not in ("row", "column", "none"):
                    raise ReportError(f"paper.table1.skimming holds {sk!r}, not one of row, column, none")
    if "cosim" in cfg:
        _need(cfg["cosim"], "cosim", "k", str)
        _need(cfg["cosim"], "cosim", "timeout", num, 1.0, 86400.0)


def config_hash(cfg: Mapping[str, Any]) -> str:
    return hashlib.sha256(json.dumps(cfg, sort_keys=True, default=str).encode()).hexdigest()[:16]


# ---------------------------------------------------------------------------------------
# Collected results
# ---------------------------------------------------------------------------------------
@dataclass
class Report:
    """Everything a run collects: sections, metrics, figures and phase times."""

    config: dict[str, Any]
    sections: dict[str, Any] = field(default_factory=dict)
    metrics: dict[str, dict[str, Any]] = field(default_factory=dict)
    figures: dict[str, list[tuple[str, bytes]]] = field(default_factory=dict)
    phases: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def metric(self, name: str, value: float | int | None, better: str, unit: str = "",
               abs_tol: float | None = None, rel_tol: float | None = None) -> None:
        """Record one metric; ``better`` is lower, higher, equal or info (never compared)."""
        if value is not None:
            value = int(value) if isinstance(value, bool | np.bool_) else value
            value = float(value) if isinstance(value, float | np.floating) else int(value)
            if isinstance(value, float) and not math.isfinite(value):
                value = None
        exact = isinstance(value, int)
        self.metrics[name] = {
            "value": value, "better": better, "unit": unit,
            "abs_tol": float(abs_tol if abs_tol is not None else (0.0 if exact else FLOAT_ABS_TOL)),
            "rel_tol": float(rel_tol if rel_tol is not None else (0.0 if exact else FLOAT_REL_TOL)),
        }

    def figure(self, section: str, caption: str, png: bytes) -> None:
        self.figures.setdefault(section, []).append((caption, png))

    @contextmanager
    def phase(self, name: str) -> Iterator[None]:
        t0 = time.perf_counter()
        print(f"irnuc report: {name} ...", file=sys.stderr, flush=True)
        try:
            yield
        finally:
            self.phases[name] = round(time.perf_counter() - t0, 3)


def _progress(label: str, enabled: bool) -> Callable[[int, int], None] | None:
    if not enabled:
        return None
    from irnuc.common.progress import ProgressBar

    return ProgressBar(label)


# ---------------------------------------------------------------------------------------
# Phases 1-2: frames, calibration, bad-pixel detection
# ---------------------------------------------------------------------------------------
def _sensor_overrides(s: Mapping[str, Any]) -> dict[str, Any]:
    return {"fpa.active_rows": s["rows"], "fpa.active_cols": s["cols"], **dict(s.get("overrides", {}))}


def phase_frames_and_calibration(rep: Report) -> None:
    from irnuc import model
    from irnuc.model.config import config_digest
    from irnuc.model.defects import DefectKind
    from irnuc.nuc_fixed import load_pipeline, nuc_dpc_top
    from irnuc.nuc_fixed.calibrate import calibrate
    from irnuc.nuc_fixed.dpc import uncorrectable
    from irnuc.reports.studies import figures
    from irnuc.reports.studies.metrics import nonuniformity, precision_recall

    s = rep.config["sensor"]
    with rep.phase("frames"):
        mcfg = model.load_preset(s["preset"], _sensor_overrides(s))
        pipe = model.Pipeline(mcfg, seed=s["seed"])
        m = s["repeats"]
        stacks = pipe.simulate([s["t_low"], s["t_high"]], repeats=m)
        ev = pipe.simulate([float(t) for t in s["t_eval"]])
    truth = stacks.defect_kind
    with rep.phase("calibration"):
        base = load_pipeline(s["pipeline"])
        h, w = truth.shape
        pcfg = base.replace(max_width=max(base.max_width, w), max_height=max(base.max_height, h))
        cal = calibrate(stacks.codes[:m], stacks.codes[m:], pcfg)
        pr = precision_recall(cal.bad, truth > 0)
        per_kind = {}
        for kind in DefectKind:
            sel = truth == kind
            if kind == DefectKind.GOOD or not sel.any():
                continue
            per_kind[kind.name] = {"pixels": int(sel.sum()), "found": int(cal.bad[sel].sum()),
                                   "recall": float(cal.bad[sel].mean())}
        out = nuc_dpc_top(ev.codes, cal.words(), pcfg)
        unc = uncorrectable(cal.bad)
        ok = ~unc
        evals = []
        for i, t in enumerate(ev.temps):
            evals.append({"t_eval": float(t),
                          "raw_nu": nonuniformity(ev.codes[i], ~cal.bad),
                          "residual_nu_dpc": nonuniformity(out[i], ok),
                          "residual_nu_good": nonuniformity(out[i], ~cal.bad),
                          "residual_std_dpc_lsb": float(np.asarray(out[i], float)[ok].std())})
    summ = cal.summary
    rep.sections["calibration"] = {
        "sensor_preset": s["preset"], "frame": [int(h), int(w)], "seed": s["seed"],
        "model_config_digest": config_digest(mcfg), "pipeline": pcfg.name,
        "pipeline_digest": pcfg.digest(), "frames_per_temperature": m,
        "t_low": s["t_low"], "t_high": s["t_high"],
        "diagnostics": stacks.diagnostics,
        "defects_injected": int((truth > 0).sum()),
        "bad_pixels": int(cal.bad.sum()), "uncorrectable": int(unc.sum()),
        "detection": pr, "per_kind": per_kind, "reasons": summ["reasons"],
        "gain_saturated": summ["gain_saturated"], "offset_saturated": summ["offset_saturated"],
        "gain_needed": summ["gain"], "offset_needed": summ["offset"],
        "residual_at_calibration": summ["residual"], "evaluation": evals,
    }
    rep.metric("calibration.precision", pr["precision"], "higher")
    rep.metric("calibration.recall", pr["recall"], "higher")
    rep.metric("calibration.false_positives", pr["false_positives"], "lower")
    rep.metric("calibration.false_negatives", pr["false_negatives"], "lower")
    rep.metric("calibration.uncorrectable", int(unc.sum()), "lower")
    rep.metric("calibration.gain_saturated", summ["gain_saturated"], "lower")
    rep.metric("calibration.offset_saturated", summ["offset_saturated"], "lower")
    for e in evals:
        t = f"{e['t_eval']:g}K"
        rep.metric(f"calibration.residual_nu_dpc.{t}", e["residual_nu_dpc"], "lower")
        rep.metric(f"calibration.raw_nu.{t}", e["raw_nu"], "info")
    for name, k in per_kind.items():
        rep.metric(f"calibration.recall.{name}", k["recall"], "higher")
    rep.figure("calibration", f"Evaluation frame at {ev.temps[0]:g} K: raw, golden NUC + DPC "
               "(typical pipeline), and detection against the model's ground truth",
               figures.bad_pixel_maps(truth > 0, cal.bad, ev.codes[0], out[0]))


# ---------------------------------------------------------------------------------------
# Phase 3: bit-width sweep
# ---------------------------------------------------------------------------------------
def _point_key(p: Mapping[str, Any]) -> str:
    return (f"U{p['gain_int_bits']}.{p['gain_frac_bits']}_S{p['offset_int_bits']}.{p['offset_frac_bits']}"
            f"_A{p['adc_bits']}_B{p['out_bits']}_{p['rounding']}_{p['coeff_rounding']}")


def sweep_specs(s: Mapping[str, Any]):
    from irnuc.reports.studies.sweep import SensorSpec, SweepAxes

    sensor = SensorSpec(preset=s["preset"], overrides=_sensor_overrides(s), seed=s["seed"],
                        t_low=float(s["t_low"]), t_high=float(s["t_high"]),
                        t_eval=tuple(float(t) for t in s["t_eval"]), repeats=s["repeats"])
    axes = SweepAxes(
        gain_frac_bits=tuple(s["gain_frac_bits"]), offset_frac_bits=tuple(s["offset_frac_bits"]),
        gain_int_bits=tuple(s.get("gain_int_bits", ["auto"])),
        offset_int_bits=tuple(s.get("offset_int_bits", ["auto"])),
        adc_bits=tuple(s.get("adc_bits", [None])), out_bits=tuple(s.get("out_bits", [None])),
        rounding=tuple(s.get("rounding", [None])),
        coeff_rounding=tuple(s.get("coeff_rounding", ["half_even"])), pipeline=s["pipeline"])
    return sensor, axes


def phase_sweep(rep: Report, scheduler: str | None, progress: bool) -> None:
    from irnuc.reports.studies import figures
    from irnuc.reports.studies.sweep import run_sweep

    s = rep.config["sweep"]
    metric = s.get("error_metric", "err_max_lsb")
    with rep.phase("sweep"):
        sensor, axes = sweep_specs(s)
        res = run_sweep(sensor, axes, workers=s["workers"], scheduler=scheduler,
                        progress=_progress("sweep", progress))
        d = res.to_dict(max_error=float(s["max_error"]), metric=metric)
        front = res.pareto(metric)
    rep.sections["sweep"] = d
    pts = res.points
    sm = d["smallest"]
    rep.metric("sweep.points", len(pts), "info")
    rep.metric("sweep.best_err_max_lsb", min(p["err_max_lsb"] for p in pts), "lower", "LSB")
    rep.metric("sweep.best_residual_nu", min(p["residual_nu"] for p in pts), "lower")
    rep.metric("sweep.smallest_bits_per_pixel", sm["bits_per_pixel"], "lower", "bit")
    for p in pts:
        k = _point_key(p)
        rep.metric(f"sweep.point.{k}.err_max_lsb", p["err_max_lsb"], "lower", "LSB")
        rep.metric(f"sweep.point.{k}.err_rms_lsb", p["err_rms_lsb"], "lower", "LSB")
        rep.metric(f"sweep.point.{k}.residual_nu", p["residual_nu"], "lower")
        rep.metric(f"sweep.point.{k}.radial_rms_lsb", p["radial_rms_lsb"], "lower", "LSB")
    rep.figure("sweep", "Error of the fixed-point NUC against the float NUC, worst over the "
               "evaluation temperatures, against gain fraction bits (one line per offset "
               "fraction width)", figures.error_vs_bits(pts, metric, float(s["max_error"])))
    rep.figure("sweep", f"Pareto front of {metric} against coefficient memory; the star is the "
               f"smallest memory meeting {metric} <= {s['max_error']:g}",
               figures.pareto(pts, front, metric, sm))


# ---------------------------------------------------------------------------------------
# Phase 4: the paper's tables and its reference numbers
# ---------------------------------------------------------------------------------------
# (key, label, model overrides, coefficient rounding, seed offset): the paper preset as
# shipped, then one change at a time, to show what moves irnuc's numbers.
PAPER_VARIANTS: tuple[tuple[str, str, dict[str, Any], str, int], ...] = (
    ("paper", "irnuc, paper preset", {}, "half_even", 0),
    ("truncate", "coefficients truncated (floor) instead of half-to-even", {}, "truncate", 0),
    # Equilibrium responds ~1/f = 11x more to the scene: the integrator gain is scaled down
    # by the same factor so that 400 K stays on the ADC.
    ("equilibrium", "equilibrium bolometer variant (integrator gain 450)",
     {"bolometer.variant": "equilibrium", "readout.gain": 450.0}, "half_even", 0),
    ("f_number", "cone from the F-number instead of the FOV",
     {"optics.cone_method": "f_number"}, "half_even", 0),
    ("normal", "truncated-normal spread instead of lognormal",
     {"fpa.spread": "normal_truncated"}, "half_even", 0),
    ("seed", "another seed (per-pixel draws)", {}, "half_even", 1),
)


def _paper_sets(p: Mapping[str, Any], overrides: Mapping[str, Any], seed_offset: int = 0):
    from irnuc.reports.studies.sweep import SensorSpec, simulate_set

    temps = tuple(float(t) for t in p["grid_temps"])
    sensor = SensorSpec(preset=p["preset"], overrides={"fpa.active_rows": p["rows"],
                        "fpa.active_cols": p["cols"], **overrides}, seed=p["seed"] + seed_offset,
                        t_low=float(p.get("t_low", 300.0)), t_high=float(p.get("t_high", 400.0)),
                        t_eval=temps, repeats=1)
    sensor.check()
    return sensor, simulate_set(sensor, None, None)


def phase_paper(rep: Report, progress: bool) -> None:
    from irnuc.reports.studies import figures
    from irnuc.reports.studies.sweep import (
        SweepAxes,
        open_executor,
        quantized_nuc,
        resolve_points,
        run_points,
    )

    p = rep.config["paper"]
    bits = [int(b) for b in p["frac_bits"]]
    ref_nu = [float(v) for v in p["reference_nu"]]
    with rep.phase("paper"):
        # The paper preset as shipped, then one change at a time (ablations) to show what
        # moves irnuc's numbers.
        variants = PAPER_VARIANTS
        rows = []
        main_set = None
        main_points = None
        with open_executor(0) as handle:
            for key, label, over, crnd, dseed in variants:
                try:
                    sensor, cs = _paper_sets(p, over, dseed)
                except ValueError as exc:  # a model that does not offer this option
                    rep.notes.append(f"paper ablation {label!r} skipped: {exc}")
                    continue
                axes = SweepAxes(gain_frac_bits=tuple(bits), offset_frac_bits=("same",),
                                 coeff_rounding=(crnd,), pipeline="typical14")
                tasks = resolve_points(axes, {(None, None): cs})
                pts = run_points(handle, tasks, {(None, None): cs})
                mid = [i for i, c in enumerate(cs.is_cal) if not c]
                k = mid[0] if mid else 0
                nu = [q["per_temp"][k]["residual_nu"] for q in pts]
                rows.append({"key": key, "variant": label, "overrides": over, "seed": p["seed"] + dseed,
                             "coeff_rounding": crnd,
                             "t_eval": float(cs.t_eval[k]), "residual_nu": nu,
                             "float_nu": pts[0]["per_temp"][k]["float_nu"],
                             "raw_nu": pts[0]["per_temp"][k]["raw_nu"],
                             "err_max_lsb": [q["per_temp"][k]["err_max_lsb"] for q in pts],
                             "radial_fraction": [q["per_temp"][k]["radial_fraction"] for q in pts],
                             "gain_range": list(cs.coefficient_range()["gain"]),
                             "int_bits": [[q["gain_int_bits"], q["offset_int_bits"]] for q in pts]})
                if main_set is None:
                    main_set, main_points, main_sensor = cs, tasks, sensor
        # Table 2 images: uncorrected and each fraction width at every grid temperature.
        cs = main_set
        ys = [quantized_nuc(cs, pt)[0] for pt, _ in main_points]
        good = cs.good
        from irnuc.reports.studies.metrics import nonuniformity

        imgs, notes = [], []
        for i in range(len(cs.t_eval)):
            row = [cs.raw_eval[i]] + [y[i] for y in ys]
            imgs.append(row)
            notes.append([f"NU {nonuniformity(im, good):.4f}" for im in row])
        rep.figure("paper", "The paper's Table 2 regenerated: uncorrected and corrected frames with "
                   f"{', '.join(map(str, bits))} fraction bits in gain and offset, calibrated at "
                   f"{main_sensor.t_low:g}/{main_sensor.t_high:g} K (each image stretched to its own "
                   "0.5-99.5 % range; NU = std/mean)",
                   figures.image_grid(imgs, [f"{t:g} K" for t in cs.t_eval],
                                      ["uncorrected"] + [f"{b} bits" for b in bits], notes))
        main = rows[0]
        rep.figure("paper", "Residual non-uniformity at the evaluation temperature against "
                   "fraction bits: irnuc and the paper's reference implementation",
                   figures.paper_comparison(bits, main["residual_nu"], ref_nu, main["float_nu"]))
        table1 = _paper_table1(rep, p)
    ratio = [a / b for a, b in zip(main["residual_nu"], ref_nu, strict=True)]
    slope = [main["residual_nu"][i] / main["residual_nu"][i + 1] for i in range(len(bits) - 1)]
    rep.sections["paper"] = {
        "preset": p["preset"], "frame": [p["rows"], p["cols"]], "seed": p["seed"],
        "frac_bits": bits, "reference_nu": ref_nu, "variants": rows,
        "ratio_to_reference": ratio, "halving_ratio": slope,
        "uniform_rounding_model": [2.0**-b / math.sqrt(12.0) for b in bits],
        "table1": table1,
    }
    for b, v in zip(bits, main["residual_nu"], strict=True):
        rep.metric(f"paper.residual_nu.f{b}", v, "lower")
    rep.metric("paper.float_nu", main["float_nu"], "lower")


def _paper_table1(rep: Report, p: Mapping[str, Any]) -> dict[str, Any] | None:
    from irnuc import model
    from irnuc.reports.studies import figures
    from irnuc.reports.studies.metrics import nonuniformity

    t1 = p.get("table1")
    if not t1:
        return None
    temps = [float(t) for t in t1["temps"]]
    tols = [float(t) for t in t1["tolerances"]]
    images: list[list[np.ndarray]] = []
    notes: list[list[str]] = []
    labels: list[str] = []
    nu: dict[str, list[list[float]]] = {}
    frames: dict[tuple[str, float], np.ndarray] = {}
    for sk in t1["skimming"]:
        for tol in tols:
            cfg = model.load_preset(p["preset"], {
                "fpa.active_rows": t1["rows"], "fpa.active_cols": t1["cols"],
                "readout.skimming": sk, "fpa.tolerance": {"R_ref": tol, "g": tol, "C": tol}})
            fr = model.Pipeline(cfg, seed=p["seed"]).simulate(temps)
            for i in range(len(temps)):
                frames[(sk, tol, i)] = fr.codes[i]
    for i, t in enumerate(temps):
        for sk in t1["skimming"]:
            labels.append(f"{t:g} K, {sk}s" if sk != "none" else f"{t:g} K, none")
            row = [frames[(sk, tol, i)] for tol in tols]
            images.append(row)
            ones = np.ones(row[0].shape, bool)
            notes.append([f"NU {nonuniformity(im, ones):.3g}" for im in row])
            nu.setdefault(sk, []).append([nonuniformity(im, ones) for im in row])
    rep.figure("paper", "The paper's Table 1 regenerated: raw frames of the paper preset at "
               "blackbody temperatures (rows) and tolerances of R, g and C (columns), with row and "
               "column skimming (each image stretched to its own range)",
               figures.image_grid(images, labels, [f"tol {t:g}" for t in tols], notes, cell=1.5,
                                  dpi=60))
    return {"temps": temps, "tolerances": tols, "skimming": list(t1["skimming"]),
            "frame": [t1["rows"], t1["cols"]], "raw_nu": nu}


# ---------------------------------------------------------------------------------------
# Phase 5: co-simulation regression (JUnit)
# ---------------------------------------------------------------------------------------
def parse_junit(path: str | Path) -> dict[str, Any]:
    """Counts and per-test results of a JUnit XML file (pytest's or any xunit2 writer)."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as exc:
        raise ReportError(f"--junit {path}: not a readable JUnit XML file ({exc})") from None
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    if root.tag not in ("testsuite", "testsuites"):
        raise ReportError(f"--junit {path}: root element is <{root.tag}>, "
                          "expected <testsuites> or <testsuite>")
    cases = []
    for suite in suites:
        for tc in suite.iter("testcase"):
            status, message = "passed", ""
            for tag in ("failure", "error", "skipped"):
                el = tc.find(tag)
                if el is not None:
                    status = {"failure": "failed", "error": "error", "skipped": "skipped"}[tag]
                    message = (el.get("message") or el.text or "").strip()[:500]
                    break
            cases.append({"name": tc.get("name", ""), "classname": tc.get("classname", ""),
                          "time": float(tc.get("time", 0) or 0), "status": status, "message": message})
    counts = {k: sum(c["status"] == k for c in cases) for k in ("passed", "failed", "error", "skipped")}
    return {"tests": len(cases), **counts, "time": round(sum(c["time"] for c in cases), 3), "cases": cases}


def run_cosim(cfg: Mapping[str, Any], junit_out: Path) -> dict[str, Any] | None:
    """Run the fast co-simulation subset under pytest; None when cocotb_tests is absent."""
    tests = REPO_ROOT / "cocotb_tests"
    if not tests.is_dir() or not any(tests.glob("test_*.py")):
        return None
    if importlib.util.find_spec("pytest") is None:
        # A plain `pip install -e .` has no test runner: the phase is left out, with a note.
        raise _Skip("co-simulation skipped: pytest is not installed "
                    "(pip install -e '.[dev]' to run the cocotb regression)")
    junit_out.parent.mkdir(parents=True, exist_ok=True)
    tmp = junit_out.with_name(f".{junit_out.name}.{os.getpid()}.tmp")
    cmd = [sys.executable, "-m", "pytest", str(tests), "-q", "-p", "no:cacheprovider",
           f"--junitxml={tmp}", "-k", cfg["k"]]
    try:
        proc = subprocess.run(cmd, cwd=REPO_ROOT, capture_output=True, text=True, timeout=cfg["timeout"])
    except subprocess.TimeoutExpired:
        tmp.unlink(missing_ok=True)
        return {"command": " ".join(cmd), "returncode": None, "tests": 0, "passed": 0, "failed": 0,
                "error": 1, "skipped": 0, "time": cfg["timeout"], "cases": [],
                "note": f"timed out after {cfg['timeout']} s"}
    if not tmp.is_file():
        return {"command": " ".join(cmd), "returncode": proc.returncode, "tests": 0, "passed": 0,
                "failed": 0, "error": 1, "skipped": 0, "time": 0.0, "cases": [],
                "note": (proc.stdout + proc.stderr)[-2000:]}
    os.replace(tmp, junit_out)
    res = parse_junit(junit_out)
    res.update(command=" ".join(cmd), returncode=proc.returncode, tail=proc.stdout[-1500:])
    return res


def phase_cosim(rep: Report, out: Path, junit: str | None, no_cosim: bool) -> None:
    from irnuc.common.io import write_atomic

    res = None
    with rep.phase("cosim"):
        if junit:
            res = parse_junit(junit)
            data = Path(junit).read_bytes()
            if Path(junit).resolve() != (out / "junit.xml").resolve():
                write_atomic(out / "junit.xml", lambda fh: fh.write(data))
            res["source"] = str(junit)
        elif not no_cosim and "cosim" in rep.config:
            try:
                res = run_cosim(rep.config["cosim"], out / "junit.xml")
            except _Skip as exc:
                rep.notes.append(str(exc))
            if res is not None:
                res["source"] = "pytest subprocess"
    if res is None:
        del rep.phases["cosim"]
        return
    rep.sections["cosim"] = res
    rep.metric("cosim.tests", res["tests"], "info")
    rep.metric("cosim.passed", res["passed"], "info")
    rep.metric("cosim.failed", res["failed"], "lower")
    rep.metric("cosim.errors", res["error"], "lower")


# ---------------------------------------------------------------------------------------
# Phase 6: numerical fidelity
# ---------------------------------------------------------------------------------------
def _flatten(prefix: str, obj: Any, out: dict[str, float | int]) -> None:
    if isinstance(obj, Mapping):
        for k, v in obj.items():
            _flatten(f"{prefix}.{k}", v, out)
    elif isinstance(obj, bool):
        out[prefix] = int(obj)
    elif isinstance(obj, int | float) and math.isfinite(obj):
        out[prefix] = obj


def phase_precision(rep: Report) -> None:
    if "precision" not in rep.config or importlib.util.find_spec("irnuc.cli.precision") is None:
        return
    mod = importlib.import_module("irnuc.cli.precision")
    fn = next((getattr(mod, n) for n in PRECISION_FUNCTIONS if callable(getattr(mod, n, None))), None)
    if fn is None:
        rep.notes.append("reports/precision.py offers no summary function "
                         f"({', '.join(PRECISION_FUNCTIONS)}); numerical-fidelity section left out")
        return
    with rep.phase("precision"):
        try:
            data = fn(quick=bool(rep.config["precision"].get("quick", True)))
        except TypeError:
            data = fn()
        data = json.loads(json.dumps(data, default=_json_default))
    rep.sections["precision"] = data
    flat: dict[str, float | int] = {}
    _flatten("precision", data, flat)
    for k, v in flat.items():
        # Direction unknown in general: recorded, not compared, except errors (lower).
        better = "lower" if ("error" in k.lower() and "time" not in k.lower()) else "info"
        rep.metric(k, v, better, rel_tol=1e-3 if better == "lower" else None)


# ---------------------------------------------------------------------------------------
# Provenance, baseline comparison
# ---------------------------------------------------------------------------------------
def _version(dist: str) -> str | None:
    try:
        return importlib.metadata.version(dist)
    except importlib.metadata.PackageNotFoundError:
        return None


def _git(*args: str) -> str | None:
    if not (REPO_ROOT / ".git").exists():
        return None
    try:
        return subprocess.run(["git", *args], cwd=REPO_ROOT, capture_output=True, text=True,
                              timeout=20, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return None


def verilator_version() -> str | None:
    try:
        from irnuc.cosim import rtl

        return str(rtl.verilator_version())
    except Exception:
        pass
    exe = Path(sys.executable).with_name("verilator-cli")
    try:
        out = subprocess.run([str(exe), "--version"], capture_output=True, text=True, timeout=30)
        return out.stdout.strip() or None
    except (OSError, subprocess.SubprocessError):
        return _version("verilator")


def provenance(cfg: Mapping[str, Any], argv: list[str]) -> dict[str, Any]:
    status = _git("status", "--porcelain", "--untracked-files=no")
    seeds = {sec: cfg[sec]["seed"] for sec in ("sensor", "sweep", "paper") if sec in cfg}
    return {
        "git_commit": _git("rev-parse", "HEAD"),
        "git_dirty": None if status is None else bool(status),
        "versions": {
            "python": platform.python_version(),
            "irnuc": _version("irnuc"), "numpy": _version("numpy"), "numba": _version("numba"),
            "scipy": _version("scipy"), "matplotlib": _version("matplotlib"),
            "cocotb": _version("cocotb"), "verilator": verilator_version(),
        },
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "config_name": cfg.get("name"),
        "config_hash": config_hash(cfg),
        "config": cfg,
        "seeds": seeds,
        "command": "irnuc report " + " ".join(argv),
        "generated": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
    }


def compare_baseline(metrics: Mapping[str, Mapping[str, Any]],
                     baseline: Mapping[str, Mapping[str, Any]]) -> dict[str, Any]:
    """Compare metrics with a baseline's, direction-aware (docs/reports.md).

    A metric regresses when it moved the wrong way by more than
    ``max(abs_tol, rel_tol * |baseline|)`` (the current run's tolerances); ``equal``
    metrics regress on any move beyond it; a value that became null (e.g. no width meets
    the error bound any more) regresses. ``info`` metrics are not compared. Metrics of a
    phase that did not run are listed as missing, not as regressions.
    """
    out: dict[str, Any] = {"compared": 0, "regressions": [], "improvements": [], "missing": [], "new": []}
    for name, m in metrics.items():
        if m["better"] == "info":
            continue
        b = baseline.get(name)
        if b is None:
            out["new"].append(name)
            continue
        out["compared"] += 1
        v, bv = m["value"], b.get("value")
        entry = {"metric": name, "value": v, "baseline": bv, "better": m["better"], "unit": m.get("unit", "")}
        if v is None and bv is None:
            continue
        if v is None:
            out["regressions"].append({**entry, "reason": "value lost"})
            continue
        if bv is None:
            out["improvements"].append({**entry, "reason": "value appeared"})
            continue
        tol = max(m["abs_tol"], m["rel_tol"] * abs(bv))
        delta = v - bv
        entry["delta"] = delta
        entry["tolerance"] = tol
        if m["better"] == "lower":
            worse, better = delta > tol, delta < -tol
        elif m["better"] == "higher":
            worse, better = delta < -tol, delta > tol
        else:
            worse, better = abs(delta) > tol, False
        if worse:
            out["regressions"].append(entry)
        elif better:
            out["improvements"].append(entry)
    out["missing"] = sorted(n for n, b in baseline.items()
                            if n not in metrics and b.get("better") != "info")
    return out


def load_baseline(path: str | Path) -> dict[str, Any]:
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError) as exc:
        raise ReportError(f"--baseline {path}: not a readable summary.json ({exc})") from None
    if not isinstance(data, dict) or not isinstance(data.get("metrics"), dict):
        raise ReportError(f"--baseline {path}: no 'metrics' object; is it an irnuc summary.json?")
    return data


def validate_summary(summary: Mapping[str, Any]) -> str:
    """Validate against the shipped schema with jsonschema if installed; return what was done."""
    try:
        import jsonschema
    except ImportError:
        return "not validated (jsonschema not installed)"
    schema = json.loads(SCHEMA_PATH.read_text())
    jsonschema.validate(summary, schema)
    return f"valid against {SCHEMA_PATH.name} (jsonschema {_version('jsonschema')})"


# ---------------------------------------------------------------------------------------
# HTML
# ---------------------------------------------------------------------------------------
_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:2em auto;max-width:1100px;
color:#222;line-height:1.4;padding:0 1em}
h1{margin-bottom:.2em}h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:1.8em}
table{border-collapse:collapse;margin:.6em 0;font-size:.88em}td,th{border:1px solid #ccc;padding:.25em .5em;
text-align:right}th{background:#f3f3f3}td.l,th.l{text-align:left}
.ok{color:#156f15;font-weight:bold}.bad{color:#b00;font-weight:bold}.muted{color:#777}
.banner{padding:.7em 1em;border-radius:6px;margin:1em 0;font-size:1.1em}
.banner.ok{background:#e5f5e5}.banner.bad{background:#fbe3e3}
figure{margin:1em 0}figcaption{font-size:.85em;color:#444;max-width:900px}img{max-width:100%}
code{background:#f4f4f4;padding:0 .2em}details{margin:.5em 0}
"""


def _fmt(v: Any, digits: int = 4) -> str:
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if v == 0:
            return "0"
        if abs(v) >= 1e5 or abs(v) < 1e-3:
            return f"{v:.{digits - 1}e}"
        return f"{v:.{digits}g}"
    return html.escape(str(v))


def _table(headers: list[str], rows: list[list[Any]], left: int = 1) -> str:
    h = "".join(f"<th class='l'>{html.escape(x)}</th>" if i < left else f"<th>{html.escape(x)}</th>"
                for i, x in enumerate(headers))
    body = []
    for r in rows:
        cells = []
        for i, v in enumerate(r):
            cls = " class='l'" if i < left else ""
            cells.append(f"<td{cls}>{v if isinstance(v, _Raw) else _fmt(v)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><tr>{h}</tr>{''.join(body)}</table>"


class _Raw(str):
    """Already-escaped HTML in a table cell."""


def _figures(rep: Report, section: str) -> str:
    parts = []
    for caption, data in rep.figures.get(section, []):
        b64 = base64.b64encode(data).decode()
        parts.append(f"<figure><img alt='{html.escape(caption)}' src='data:image/png;base64,{b64}'>"
                     f"<figcaption>{html.escape(caption)}</figcaption></figure>")
    return "".join(parts)


def _html_calibration(rep: Report) -> str:
    c = rep.sections["calibration"]
    d = c["detection"]
    rows = [[k, v["pixels"], v["found"], v["recall"]] for k, v in c["per_kind"].items()]
    ev = [[f"{e['t_eval']:g} K", e["raw_nu"], e["residual_nu_good"], e["residual_nu_dpc"],
           e["residual_std_dpc_lsb"]] for e in c["evaluation"]]
    return (
        "<h2 id='calibration'>Sensor frames, calibration and bad-pixel detection</h2>"
        f"<p>Preset <code>{html.escape(c['sensor_preset'])}</code>, {c['frame'][1]} × {c['frame'][0]} "
        f"pixels, seed {c['seed']}, {c['frames_per_temperature']} frames at {c['t_low']:g} K and "
        f"{c['t_high']:g} K; golden-model pipeline <code>{html.escape(c['pipeline'])}</code>. "
        f"{c['defects_injected']} defective pixels injected, {c['bad_pixels']} flagged, "
        f"{c['uncorrectable']} uncorrectable by DPC.</p>"
        + _table(["detection", "precision", "recall", "true pos.", "false pos.", "false neg."],
                 [["all kinds", d["precision"], d["recall"], d["true_positives"], d["false_positives"],
                   d["false_negatives"]]])
        + _table(["defect kind", "pixels", "found", "recall"], rows)
        + _table(["evaluation", "raw NU", "NUC NU (good pixels)", "NUC+DPC NU", "NUC+DPC std (LSB)"], ev)
        + f"<p>Saturated coefficients of calibratable pixels: gain {c['gain_saturated']}, offset "
        f"{c['offset_saturated']}. Needed gain range [{_fmt(c['gain_needed']['min'])}, "
        f"{_fmt(c['gain_needed']['max'])}] ({c['gain_needed']['int_bits_needed']} integer bits), "
        f"offset [{_fmt(c['offset_needed']['min'])}, {_fmt(c['offset_needed']['max'])}] "
        f"({c['offset_needed']['int_bits_needed']} integer bits incl. sign).</p>"
        + _figures(rep, "calibration"))


def _html_sweep(rep: Report) -> str:
    s = rep.sections["sweep"]
    sm = s.get("smallest", {})
    pts = {p["index"]: p for p in s["points"]}
    metric = s["pareto"]["metric"]
    if sm.get("found"):
        best = pts[sm["best"]]
        choice = (f"<p class='ok'>Smallest coefficient memory with {metric} ≤ {sm['max_error']:g}: "
                  f"<b>{sm['bits_per_pixel']} bits per pixel</b> — gain U{best['gain_int_bits']}."
                  f"{best['gain_frac_bits']}, offset S{best['offset_int_bits']}.{best['offset_frac_bits']} "
                  f"({best['bits_per_frame'] / 8 / 1024:.1f} KiB per {s['frame'][1]} × {s['frame'][0]} "
                  f"frame); {len(sm['points'])} width combination(s) at that cost meet it.</p>")
    else:
        choice = (f"<p class='bad'>No swept width meets {metric} ≤ {sm.get('max_error')}; "
                  "widen the sweep.</p>")
    front = set(s["pareto"]["indices"])
    cols = ["gain", "offset", "bit/px", "max |e| LSB", "rms LSB", "PSNR dB", "NU", "NU (ADC LSB)",
            "radial rms LSB", "radial frac.", "sat. gain", "sat. offset", "Pareto"]
    rows = []
    for p in s["points"]:
        rows.append([f"U{p['gain_int_bits']}.{p['gain_frac_bits']}",
                     f"S{p['offset_int_bits']}.{p['offset_frac_bits']}", p["bits_per_pixel"],
                     p["err_max_lsb"], p["err_rms_lsb"], p["psnr_db"], p["residual_nu"],
                     p["residual_nu_adc_lsb"], p["radial_rms_lsb"], p["radial_fraction"],
                     p["gain_saturated_fraction"], p["offset_saturated_fraction"],
                     "★" if p["index"] in front else ""])
    sen = s["sensor"]
    return (
        "<h2 id='sweep'>Coefficient bit-width sweep</h2>"
        f"<p>Preset <code>{html.escape(sen['preset'])}</code>, {s['frame'][1]} × {s['frame'][0]} pixels, "
        f"seed {sen['seed']}; float two-point NUC from {sen['repeats']} frames at {sen['t_low']:g} K and "
        f"{sen['t_high']:g} K; evaluated at {', '.join(f'{t:g}' for t in sen['t_eval'])} K (worst case "
        f"reported). {s['n_points']} points on {html.escape(s['executor'])}. Bad pixels excluded, no DPC. "
        "Errors are against the unquantized float NUC in output LSB.</p>" + choice
        + _figures(rep, "sweep")
        + f"<details><summary>All {len(rows)} points</summary>{_table(cols, rows, left=2)}</details>")


_PAPER_WHY = """
<p><b>Why the numbers halve per bit.</b> With gain and offset both quantized to f fraction
bits, the fixed-point output differs from the float NUC by e = Δg·x + Δo, the rounding errors
Δg and Δo being at most half an LSB of 2<sup>−f</sup>. The offset term is a fraction of an
output code; the gain term multiplies the raw code x (thousands of codes) and dominates. When
the gains spread over several LSB, Δg is nearly uniform with standard deviation
2<sup>−f</sup>/√12, so std(y)/mean(y) ≈ (2<sup>−f</sup>/√12)·x̄/ȳ, with x̄/ȳ ≈ 1 because the
calibration targets are the frame means: {model} for f = {bits}. Both the paper's reference
implementation and irnuc follow this law; the float NUC's own residual ({floor}) is far below
it. Because the gain is mostly a function of the distance from the optical axis (cos⁴
falloff), so is its rounding error: {radial} of the error variance is radial, which is the
ring pattern of the paper's Table 2.</p>
<p><b>Where irnuc differs, and why.</b> irnuc gives {irnuc} against the reference's {ref}
(ratios {ratio}). The table above changes one thing at a time:</p>
<ul>{items}</ul>
<p>So the sensor physics that irnuc models differently from the paper (camera equation,
bolometer variant, spread distribution) moves the result by at most {physics}: the residual is
set by the coefficient LSB relative to the signal, not by the sensor; other per-pixel draws
(the seed row) move it by {seed}. What remains is systematic: (1) the <b>rounding of the
coefficients</b> ({between}); (2) at 3-4 bits the gains span only {steps} LSB ({grange}), so the
rounding error is far from uniform and its spread depends on where the gain distribution sits
on the LSB grid — which the calibration targets set (irnuc's gain is 1 at the frame mean; a
reference that normalizes the output differently shifts every gain against the grid, most
likely the main cause of the ±5 % at 3-4 bits, and the reason the deviation changes sign
between 3 and 4 bits); (3) the <b>metric</b>: irnuc's NU is the population std over the mean of
the good pixels of the integer (rounded, clipped) output of one frame of the active area; the
reference's exact definition (region, float or integer output) is not published.
<b>Integer bits</b> are chosen so that no good coefficient saturates ({intbits}); a narrower
integer part would clip the outer rings and raise the error.</p>
"""

_VARIANT_WHY = {
    "truncate": "floor rounding biases every gain and offset down by half an LSB on average and "
                "widens the error distribution",
    "equilibrium": "the scene power is on before the bias pulse (irnuc's default), so the response "
                   "per kelvin is ~11× larger; with the integrator gain scaled to match, the gain "
                   "map hardly changes",
    "f_number": "irnuc's default cone (sin θ = 1/2N) changes the optical power level, not the "
                "relative cos⁴ map that sets the gain spread",
    "normal": "at tolerance 1e-5 the spread of R, g and C is far too small for its distribution "
              "to matter",
    "seed": "other per-pixel draws and a different noise-free fixed pattern",
}


def _html_paper(rep: Report) -> str:
    p = rep.sections["paper"]
    main = p["variants"][0]
    bits = p["frac_bits"]
    gl, gh = main["gain_range"]
    items, physics, seed = [], 0.0, 0.0
    trunc = next((v for v in p["variants"] if v["key"] == "truncate"), None)
    if trunc is not None:
        pairs = list(zip(trunc["residual_nu"], main["residual_nu"], strict=True))
        inside = [min(a, b) <= r <= max(a, b) for a, b, r in
                  zip(main["residual_nu"], trunc["residual_nu"], p["reference_nu"], strict=True)]
        between = ("the reference's number lies between irnuc's half-to-even and truncated rows at f = "
                   + (", ".join(str(b) for b, i in zip(bits, inside, strict=True) if i) or "none")
                   + "; truncation alone changes irnuc's numbers by up to "
                   + f"{100 * max(abs(t / m - 1) for t, m in pairs):.0f} %")
    else:
        between = "not measured"
    for v in p["variants"][1:]:
        rel = [a / b - 1.0 for a, b in zip(v["residual_nu"], main["residual_nu"], strict=True)]
        worst = max(rel, key=abs)
        if v["key"] in ("equilibrium", "f_number", "normal"):
            physics = max(physics, max(abs(r) for r in rel))
        if v["key"] == "seed":
            seed = max(abs(r) for r in rel)
        items.append(f"<li><b>{html.escape(v['variant'])}</b>: "
                     + ", ".join(f"{x:.4f}" for x in v["residual_nu"])
                     + f" (largest change {100 * worst:+.1f} %) — {_VARIANT_WHY.get(v['key'], '')}.</li>")
    text = _PAPER_WHY.format(
        model=", ".join(f"{v:.4f}" for v in p["uniform_rounding_model"]),
        bits=", ".join(map(str, bits)), floor=_fmt(main["float_nu"]),
        radial=" to ".join(f"{100 * v:.0f} %" for v in (min(main["radial_fraction"]),
                                                         max(main["radial_fraction"]))),
        irnuc=", ".join(f"{v:.4f}" for v in main["residual_nu"]),
        ref=", ".join(f"{v:.4f}" for v in p["reference_nu"]),
        ratio=", ".join(f"{v:.2f}" for v in p["ratio_to_reference"]),
        items="".join(items), physics=f"{100 * physics:.1f} %", seed=f"{100 * seed:.1f} %",
        between=between,
        grange=f"gains {gl:.3f} to {gh:.3f}",
        steps=" and ".join(f"{(gh - gl) * 2 ** b:.1f}" for b in bits[:2]),
        intbits=", ".join(f"U{g}.{b}/S{o}.{b}" for (g, o), b in zip(main["int_bits"], bits, strict=True)))
    head = ["case", "t (K)"] + [f"f = {b}" for b in bits] + ["float NU"]
    rows = [["paper reference implementation", 350.0, *p["reference_nu"], None],
            ["2^-f/√12 (uniform rounding)", None, *p["uniform_rounding_model"], None]]
    for v in p["variants"]:
        rows.append([v["variant"], v["t_eval"], *v["residual_nu"], v["float_nu"]])
    return ("<h2 id='paper'>The paper's Tables 1 and 2, and its reference numbers</h2>"
            f"<p>Preset <code>{html.escape(p['preset'])}</code>, {p['frame'][1]} × {p['frame'][0]} "
            f"pixels, seed {p['seed']}; gain and offset both with f fraction bits; residual "
            "non-uniformity std/mean at the temperature not used for calibration.</p>"
            + _table(head, rows, left=1) + text + _figures(rep, "paper"))


def _html_cosim(rep: Report) -> str:
    c = rep.sections["cosim"]
    ok = c["failed"] == 0 and c["error"] == 0 and c["tests"] > 0
    cls = "ok" if ok else "bad"
    bad = [[x["classname"] + "::" + x["name"], x["status"], _Raw(html.escape(x["message"][:300]))]
           for x in c["cases"] if x["status"] in ("failed", "error")]
    allrows = [[x["classname"] + "::" + x["name"], x["status"], x["time"]] for x in c["cases"]]
    out = ("<h2 id='cosim'>RTL co-simulation regression</h2>"
           f"<p class='{cls}'>{c['passed']} passed, {c['failed']} failed, {c['error']} errors, "
           f"{c['skipped']} skipped of {c['tests']} ({c['time']:.1f} s of simulation; source: "
           f"{html.escape(str(c.get('source', '')))}).</p>")
    if c.get("command"):
        out += f"<p class='muted'>Command: <code>{html.escape(c['command'])}</code></p>"
    if c.get("note"):
        out += f"<pre>{html.escape(str(c['note']))}</pre>"
    if bad:
        out += _table(["test", "status", "message"], bad)
    out += f"<details><summary>All tests</summary>{_table(['test', 'status', 'seconds'], allrows)}</details>"
    return out


def _html_precision(rep: Report) -> str:
    flat: dict[str, float | int] = {}
    _flatten("precision", rep.sections["precision"], flat)
    rows = [[k.removeprefix("precision."), v] for k, v in flat.items()]
    return ("<h2 id='precision'>Numerical fidelity (work-precision summary)</h2>"
            + _table(["quantity", "value"], rows)
            + "<details><summary>JSON</summary><pre>"
            + html.escape(json.dumps(rep.sections["precision"], indent=1)[:20000]) + "</pre></details>")


def _html_baseline(summary: Mapping[str, Any]) -> str:
    b = summary["baseline"]
    cls = "bad" if b["regressions"] else "ok"
    out = (f"<h2 id='baseline'>Comparison with the baseline</h2><p class='{cls}'>{len(b['regressions'])} "
           f"regression(s), {len(b['improvements'])} improvement(s) among {b['compared']} compared "
           f"metrics; baseline <code>{html.escape(b['path'])}</code> (commit "
           f"{html.escape(str(b.get('git_commit')))}).</p>")
    for key, title in (("regressions", "Regressions"), ("improvements", "Improvements")):
        if b[key]:
            rows = [[e["metric"], e["baseline"], e["value"], e.get("delta"), e.get("tolerance"), e["better"]]
                    for e in b[key]]
            head = ["metric", "baseline", "now", "delta", "tolerance", "better"]
            out += f"<h3>{title}</h3>" + _table(head, rows)
    if b["missing"]:
        out += ("<p class='muted'>In the baseline but not in this run (phase not run): "
                + html.escape(", ".join(b["missing"][:50]))
                + ("…" if len(b["missing"]) > 50 else "") + "</p>")
    return out


def render_html(rep: Report, summary: Mapping[str, Any]) -> str:
    prov = summary["provenance"]
    status = summary["status"]
    ok = status == "pass"
    reasons = summary.get("status_reasons", [])
    banner = (f"<div class='banner {'ok' if ok else 'bad'}'>Status: <b>{status.upper()}</b>"
              + (" — " + html.escape("; ".join(reasons)) if reasons else "") + "</div>")
    nav = " · ".join(f"<a href='#{s}'>{s}</a>" for s in
                     ("calibration", "sweep", "paper", "cosim", "precision", "baseline")
                     if s in rep.sections or (s == "baseline" and "baseline" in summary))
    key_rows = []
    if "calibration" in rep.sections:
        d = rep.sections["calibration"]["detection"]
        key_rows.append(["bad-pixel detection precision / recall",
                         f"{d['precision']:.3f} / {d['recall']:.3f}"])
    if "sweep" in rep.sections:
        sm = rep.sections["sweep"].get("smallest", {})
        key_rows.append([f"smallest coefficient word meeting {sm.get('metric')} ≤ {sm.get('max_error')}",
                         f"{sm['bits_per_pixel']} bit/pixel" if sm.get("found") else "none in the sweep"])
    if "paper" in rep.sections:
        p = rep.sections["paper"]
        key_rows.append(["residual NU at 350 K, f = " + ", ".join(map(str, p["frac_bits"])),
                         "irnuc " + ", ".join(f"{v:.4f}" for v in p["variants"][0]["residual_nu"])
                         + " · paper " + ", ".join(f"{v:.4f}" for v in p["reference_nu"])])
    if "cosim" in rep.sections:
        c = rep.sections["cosim"]
        key_rows.append(["co-simulation", f"{c['passed']}/{c['tests']} passed, {c['failed']} failed, "
                         f"{c['error']} errors"])
    v = prov["versions"]
    prov_rows = [["git commit", f"{prov['git_commit']}" + (" (modified)" if prov["git_dirty"] else "")],
                 ["configuration", f"{prov['config_name']} (hash {prov['config_hash']})"
                  + (" --quick" if rep.config.get("quick") else "")],
                 ["seeds", ", ".join(f"{k} {s}" for k, s in prov["seeds"].items())],
                 ["versions", ", ".join(f"{k} {x}" for k, x in v.items())],
                 ["platform", f"{prov['platform']}, {prov['cpu_count']} CPU(s)"],
                 ["generated", prov["generated"]], ["command", prov["command"]],
                 ["summary.json", summary.get("schema_validation", "")]]
    times = [[k, f"{x:.2f} s"] for k, x in summary["phases"].items()]
    times.append(["total", f"{sum(summary['phases'].values()):.2f} s"])
    parts = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        "<meta name='viewport' content='width=device-width, initial-scale=1'>",
        f"<title>irnuc report — {html.escape(str(prov['config_name']))}</title>",
        f"<style>{_CSS}</style></head><body>",
        "<h1>irnuc regression report</h1>",
        f"<p class='muted'>{html.escape(prov['generated'])} · commit {html.escape(str(prov['git_commit']))}"
        f" · {nav}</p>", banner,
        _table(["headline", "value"], key_rows, left=2) if key_rows else "",
    ]
    for note in rep.notes:
        parts.append(f"<p class='muted'>Note: {html.escape(note)}</p>")
    if "calibration" in rep.sections:
        parts.append(_html_calibration(rep))
    if "sweep" in rep.sections:
        parts.append(_html_sweep(rep))
    if "paper" in rep.sections:
        parts.append(_html_paper(rep))
    if "cosim" in rep.sections:
        parts.append(_html_cosim(rep))
    if "precision" in rep.sections:
        parts.append(_html_precision(rep))
    if "baseline" in summary:
        parts.append(_html_baseline(summary))
    parts.append("<h2 id='provenance'>Provenance and run time</h2>" + _table(["", ""], prov_rows, left=2)
                 + _table(["phase", "time"], times, left=1) + _figures(rep, "times"))
    parts.append("</body></html>")
    return "\n".join(parts)


# ---------------------------------------------------------------------------------------
# Driver
# ---------------------------------------------------------------------------------------
def _json_default(o: Any) -> Any:
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o) if math.isfinite(o) else None
    if isinstance(o, np.bool_):
        return bool(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"{type(o).__name__} is not JSON serializable")


def _clean(o: Any) -> Any:
    """NaN and inf become null (JSON has neither)."""
    if isinstance(o, float) and not math.isfinite(o):
        return None
    if isinstance(o, dict):
        return {k: _clean(v) for k, v in o.items()}
    if isinstance(o, list | tuple):
        return [_clean(v) for v in o]
    return o


def build_report(config: Mapping[str, Any], *, out: Path, junit: str | None = None, no_cosim: bool = False,
                 scheduler: str | None = None, progress: bool = True) -> Report:
    """Run every phase the configuration asks for (see the module docstring)."""
    rep = Report(config=copy.deepcopy(dict(config)))
    if "sensor" in config:
        phase_frames_and_calibration(rep)
    if "sweep" in config:
        phase_sweep(rep, scheduler, progress)
    if "paper" in config:
        phase_paper(rep, progress)
    phase_cosim(rep, out, junit, no_cosim)
    phase_precision(rep)
    return rep


def make_summary(rep: Report, argv: list[str], baseline: Mapping[str, Any] | None,
                 baseline_path: str | None) -> dict[str, Any]:
    for name, sec in rep.phases.items():
        rep.metric(f"time.{name}", sec, "info", "s")
    summary: dict[str, Any] = {
        "schema_version": SCHEMA_VERSION,
        "tool": "irnuc report",
        "provenance": provenance(rep.config, argv),
        "phases": dict(rep.phases),
        "sections": rep.sections,
        "metrics": rep.metrics,
        "notes": rep.notes,
    }
    reasons = []
    if baseline is not None:
        cmp = compare_baseline(rep.metrics, baseline["metrics"])
        cmp["path"] = str(baseline_path)
        cmp["git_commit"] = (baseline.get("provenance") or {}).get("git_commit")
        summary["baseline"] = cmp
        if cmp["regressions"]:
            reasons.append(f"{len(cmp['regressions'])} metric(s) regressed against the baseline")
    c = rep.sections.get("cosim")
    if c is not None and (c["failed"] or c["error"]):
        reasons.append(f"co-simulation: {c['failed']} failed, {c['error']} errors")
    summary["status"] = "fail" if reasons else "pass"
    summary["status_reasons"] = reasons
    return _clean(json.loads(json.dumps(summary, default=_json_default)))


def write_outputs(rep: Report, summary: dict[str, Any], out: Path) -> None:
    from irnuc.common.io import write_text_atomic
    from irnuc.reports.studies import figures

    rep.figure("times", "Run time per phase", figures.phase_times(summary["phases"]))
    summary["schema_validation"] = validate_summary(summary)
    write_text_atomic(out / "summary.json", json.dumps(summary, indent=1, sort_keys=False) + "\n")
    write_text_atomic(out / "index.html", render_html(rep, summary))


def run_report(args: Any) -> int:
    """Entry point of ``irnuc report`` (argparse namespace, see :mod:`reports.commands`)."""
    argv = list(getattr(args, "argv", []) or [])
    config = load_report_config(args.config, quick=args.quick)
    baseline = load_baseline(args.baseline) if args.baseline else None
    if args.junit and not Path(args.junit).is_file():
        raise ReportError(f"--junit {args.junit}: no such file")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    rep = build_report(config, out=out, junit=args.junit, no_cosim=args.no_cosim,
                       scheduler=args.scheduler, progress=not args.no_progress)
    summary = make_summary(rep, argv, baseline, args.baseline)
    write_outputs(rep, summary, out)
    total = time.perf_counter() - t0
    times = ", ".join(f"{k} {v:.1f} s" for k, v in rep.phases.items())
    print(f"wrote {out / 'index.html'}, {out / 'summary.json'}"
          + (f", {out / 'junit.xml'}" if "cosim" in rep.sections else "")
          + f" in {total:.1f} s ({times})")
    if summary["status"] != "pass":
        for r in summary["status_reasons"]:
            print(f"irnuc report: FAIL: {r}", file=sys.stderr)
        for e in summary.get("baseline", {}).get("regressions", [])[:20]:
            print(f"  regression: {e['metric']}: {e['baseline']} -> {e['value']} "
                  f"(better {e['better']})", file=sys.stderr)
        return 1
    return 0
