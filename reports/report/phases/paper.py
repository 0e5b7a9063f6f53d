"""Phase: the paper's Table 2 and Table 1 grids, the comparison with its reference
implementation's numbers and the ablations that explain the difference."""

from __future__ import annotations

import base64
import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.reports.report.base import Report, left_out
from irnuc.reports.report.sections import Section

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


def paper_cache_file(p: Mapping[str, Any]) -> Path:
    """Where the phase's results for the paper settings ``p`` are kept: keyed by ``p``, the
    ablations and the sources that make them (the model, the golden model, the studies and
    this file, presets included) and the numpy/matplotlib versions that draw the figures."""
    import matplotlib

    from irnuc import model, nuc_fixed
    from irnuc.common.cache import cache_dir
    from irnuc.common.digest import digest, named_files_digest, package_files
    from irnuc.reports import studies

    files = [f for pkg, tag in ((model, "model"), (nuc_fixed, "nuc_fixed"), (studies, "studies"))
             for f in package_files(pkg, tag, ("*.py", "*.toml"))]
    code = named_files_digest([*files, ("paper.py", Path(__file__))])
    key = digest({"code": code, "paper": p, "variants": PAPER_VARIANTS,
                  "numpy": np.__version__, "matplotlib": matplotlib.__version__})
    return cache_dir("paper") / f"{key}.json"


def _json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    raise TypeError(f"not JSON: {type(o).__name__}")


def _stored(path: Path) -> dict[str, Any] | None:
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        return None  # absent or damaged: measured again
    return data if isinstance(data, dict) and data.get("format") == 1 else None


def quick_notes(rep: Report) -> None:
    """Name the paper's frame ``--quick`` made smaller (its residuals are of that frame)."""
    from irnuc.reports.report.config import quick_replaced

    p = rep.config["paper"]
    cut = [quick_replaced(rep.config, f"paper.{k}") for k in ("rows", "cols")]
    if any(c for c, _ in cut):
        full = [v if c else p[k] for (c, v), k in zip(cut, ("rows", "cols"), strict=True)]
        left_out(rep, "paper", f"Table 2 and its ablations at the full run's {full[0]} x "
                 f"{full[1]} frame; run at {p['rows']} x {p['cols']} (residuals of this "
                 "frame, compared with quick runs only)", "paper.rows, paper.cols")


def phase_paper(rep: Report, progress: bool) -> None:
    """The paper's tables, from the cache when this code made them with these settings
    (a warm report), else computed and kept (:func:`paper_cache_file`). A fresh run goes
    through the same JSON as a stored one, so both give the same section, metrics and
    figures."""
    from irnuc.common.io import write_text_atomic

    p = rep.config["paper"]
    bits = [int(b) for b in p["frac_bits"]]
    ref_nu = [float(v) for v in p["reference_nu"]]
    quick_notes(rep)
    with rep.phase("paper"):
        path = paper_cache_file(p)
        out = _stored(path)
        if out is None:
            made = _compute_paper(p, bits)
            text = json.dumps({"format": 1, **made}, default=_json_default)
            write_text_atomic(path, text + "\n")
            out = json.loads(text)
        else:
            rep.say(f"paper: read from the cache ({path.name})")
        for caption, png in out["figures"]:
            rep.figure("paper", caption, base64.b64decode(png))
        rep.notes.extend(out["notes"])
    rows, table1 = out["rows"], out["table1"]
    main = rows[0]
    ratio = [a / b for a, b in zip(main["residual_nu"], ref_nu, strict=True)]
    slope = [main["residual_nu"][i] / main["residual_nu"][i + 1] for i in range(len(bits) - 1)]
    rep.sections["paper"] = Section.of({
        "preset": p["preset"], "frame": [p["rows"], p["cols"]], "seed": p["seed"],
        "frac_bits": bits, "reference_nu": ref_nu, "variants": rows,
        "ratio_to_reference": ratio, "halving_ratio": slope,
        "uniform_rounding_model": [2.0**-b / math.sqrt(12.0) for b in bits],
        "table1": table1,
    })
    for b, v in zip(bits, main["residual_nu"], strict=True):
        rep.metric(f"paper.residual_nu.f{b}", v, "lower")
    rep.metric("paper.float_nu", main["float_nu"], "lower")


def _compute_paper(p: Mapping[str, Any], bits: list[int]) -> dict[str, Any]:
    """The phase's work: rows of the variants, Table 1, the figures (base64 PNG) and the
    notes, as plain data."""
    from irnuc.reports.studies import figures
    from irnuc.reports.studies.sweep import (
        SweepAxes,
        open_executor,
        quantized_nuc,
        resolve_points,
        run_points,
    )

    ref_nu = [float(v) for v in p["reference_nu"]]
    figs: list[tuple[str, bytes]] = []
    notes: list[str] = []
    # The paper preset as shipped, then one change at a time (ablations) to show what
    # moves irnuc's numbers.
    variants = PAPER_VARIANTS
    rows = []
    main_set = None
    main_points = None
    # A variant that changes only the coefficients' rounding reuses the frames of the
    # one before it (the same model, overrides and seed: the same bits).
    last: tuple[str, Any] = ("", None)
    with open_executor(0) as handle:
        for key, label, over, crnd, dseed in variants:
            same = json.dumps([over, dseed], sort_keys=True)
            try:
                if last[0] != same:
                    last = ("", None)  # the previous set's memory goes first
                    last = (same, _paper_sets(p, over, dseed))
                sensor, cs = last[1]
            except ValueError as exc:  # a model that does not offer this option
                notes.append(f"paper ablation {label!r} skipped: {exc}")
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
                         "int_bits": [[q["gain_int_bits"], q["offset_int_bits"]] for q in pts],
                         "labels": [q["label"] for q in pts]})
            if main_set is None:
                main_set, main_points, main_sensor = cs, tasks, sensor
    # Table 2 images: uncorrected and each fraction width at every grid temperature.
    cs = main_set
    ys = [quantized_nuc(cs, pt)[0] for pt, _ in main_points]
    good = cs.good
    from irnuc.reports.studies.metrics import nonuniformity

    imgs, cell_notes = [], []
    for i in range(len(cs.t_eval)):
        row = [cs.raw_eval[i]] + [y[i] for y in ys]
        imgs.append(row)
        cell_notes.append([f"NU {nonuniformity(im, good):.4f}" for im in row])
    figs.append(("The paper's Table 2 regenerated: uncorrected and corrected frames with "
               f"{', '.join(map(str, bits))} fraction bits in gain and offset, calibrated at "
               f"{main_sensor.t_low:g}/{main_sensor.t_high:g} K (each image stretched to its own "
               "0.5-99.5 % range; NU = std/mean)",
               figures.image_grid(imgs, [f"{t:g} K" for t in cs.t_eval],
                                  ["uncorrected"] + [f"{b} bits" for b in bits], cell_notes)))
    main = rows[0]
    figs.append(("Residual non-uniformity at the evaluation temperature against "
               "fraction bits: irnuc and the paper's reference implementation",
               figures.paper_comparison(bits, main["residual_nu"], ref_nu, main["float_nu"])))
    table1 = _paper_table1(figs, p)
    return {"rows": rows, "table1": table1, "notes": notes,
            "figures": [[c, base64.b64encode(png).decode("ascii")] for c, png in figs]}


def _paper_table1(figs: list[tuple[str, bytes]], p: Mapping[str, Any]) -> dict[str, Any] | None:
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
    figs.append(("The paper's Table 1 regenerated: raw frames of the paper preset at "
               "blackbody temperatures (rows) and tolerances of R, g and C (columns), with row and "
               "column skimming (each image stretched to its own range)",
               figures.image_grid(images, labels, [f"tol {t:g}" for t in tols], notes, cell=1.5,
                                  dpi=60)))
    return {"temps": temps, "tolerances": tols, "skimming": list(t1["skimming"]),
            "frame": [t1["rows"], t1["cols"]], "raw_nu": nu}
