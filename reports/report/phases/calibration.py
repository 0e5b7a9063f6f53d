"""Phases 1-2: sensor frames with injected defects, golden-model calibration and bad-pixel
detection scored against the model's ground truth, NUC + DPC of the evaluation frames."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from irnuc.reports.report.base import Report
from irnuc.reports.report.sections import Section


def sensor_overrides(s: Mapping[str, Any]) -> dict[str, Any]:
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
        mcfg = model.load_preset(s["preset"], sensor_overrides(s))
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
    rep.sections["calibration"] = Section.of({
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
    })
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
