"""Phases 3-4: the coefficient bit-width sweep with the hardware cost of every point, the
Pareto fronts and the recommended widths.

``sweep``: error of every point (:mod:`irnuc.reports.studies.sweep`) and its coefficient
memory for the configured frame (bits per pixel, block RAMs or external memory).

``synth`` (with a ``[synth]`` section): ``irnuc synth`` of a few points at the corners of
the swept word widths and of the cheapest candidates, a linear cost model fitted on the
corners (its error stated against every synthesized point), the datapath cost of every
point, the fronts of error against memory and against LUT+DSP, and the recommendation:
the cheapest point meeting the tolerance, synthesized, its edges on the swept grid named.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from irnuc.reports.report.base import Report, left_out, progress
from irnuc.reports.report.phases.calibration import sensor_overrides
from irnuc.reports.report.sections import Recommendation, SweepSection, SynthCheck, thaw

#: LUTs one DSP48E1 counts for on the datapath axis (an 18 x 25 multiplier in fabric).
DSP_LUT_EQUIVALENT = 200.0
#: Synthesized points the cost model is fitted on, and cheapest candidates synthesized
#: before it picks (the full run's defaults; ``synth.fit_points``, ``synth.candidates``).
FIT_POINTS = 4
CANDIDATES = 3
SWEPT_AXES = ("gain_frac_bits", "offset_frac_bits", "gain_int_bits", "offset_int_bits")


def sweep_specs(s: Mapping[str, Any]):
    from irnuc.reports.studies.sweep import SensorSpec, SweepAxes

    sensor = SensorSpec(preset=s["preset"], overrides=sensor_overrides(s), seed=s["seed"],
                        t_low=float(s["t_low"]), t_high=float(s["t_high"]),
                        t_eval=tuple(float(t) for t in s["t_eval"]), repeats=s["repeats"])
    axes = SweepAxes(
        gain_frac_bits=tuple(s["gain_frac_bits"]), offset_frac_bits=tuple(s["offset_frac_bits"]),
        gain_int_bits=tuple(s.get("gain_int_bits", ["auto"])),
        offset_int_bits=tuple(s.get("offset_int_bits", ["auto"])),
        rounding=tuple(s.get("rounding", [None])),
        coeff_rounding=tuple(s.get("coeff_rounding", ["half_even"])), pipeline=s["pipeline"])
    return sensor, axes


def check_sweep(s: Mapping[str, Any], source: str) -> None:
    """The sweep's specification, before any work (the ADC of the sensor against the
    pipeline's, the axes)."""
    from irnuc.reports.studies.sweep import check_sweep_memory, check_widths

    sensor, axes = sweep_specs(s)
    sensor.check()
    axes.check()
    check_widths(sensor, axes, sensor_name=f"{source}: sweep.preset",
                 pipeline_name="sweep.pipeline")
    workers = int(s.get("workers", 2))
    check_sweep_memory(sensor, axes, workers, f"{source}: the sweep (sweep.workers = "
                       f"{workers})", "use a smaller frame, fewer frames or fewer workers")


#: The fields of a point's record (``SweepPoint.record``) the recommended entry repeats.
_POINT_FIELDS = ("index", "label", "gain_format", "offset_format", "gain_bits", "offset_bits",
                 "gain_int_bits", "gain_frac_bits", "offset_int_bits", "offset_frac_bits",
                 "adc_bits", "out_bits", "rounding", "coeff_rounding", "bits_per_pixel",
                 "err_max_lsb", "memory")


def recommended_config(point: Any, rows: int, cols: int, recommended: bool = False):
    """The pipeline configuration of a sweep point (a ``SweepPoint``) for the configured
    frame (line buffers of ``cols`` pixels, frames of up to ``rows`` lines)."""
    g, o = point.formats()
    cfg = point.config(rows, cols)
    return cfg.replace(
        name="recommended" if recommended else f"sweep{point.index}",
        max_width=cols, max_height=rows,
        description=(f"{g} gain, {o} offset, from the bit-width sweep of irnuc report "
                     f"({cfg.word_bits} bits per pixel)"))


def _recommended_entry(rep: Report, p: Mapping[str, Any], metric: str, frame: tuple[int, int],
                       axes: Mapping[str, Any], candidates: list[int]) -> Recommendation:
    from irnuc.reports.studies.hwcost import grid_edges

    rows, cols = frame
    cfg = recommended_config(rep.studies["sweep"].sweep_points[p["index"]], rows, cols,
                             recommended=True)
    edges = grid_edges(p, {k: axes[k] for k in SWEPT_AXES if k in axes})
    for e in edges:
        rep.notes.append(f"the recommended widths lie on the {e['edge']} edge of the swept "
                         f"{e['axis']} ({p[e['axis']]}); widen the sweep: {e['widen']}")
    return Recommendation(data={
        **{k: p[k] for k in _POINT_FIELDS},
        "metric": metric, "error": p[metric], "candidates": candidates, "edges": edges,
        "pipeline": cfg.to_dict(), "pipeline_digest": cfg.digest(), "pipeline_toml": cfg.to_toml(),
    })


def phase_sweep(rep: Report, scheduler: str | None, show_progress: bool) -> None:
    from irnuc.reports.studies import figures
    from irnuc.reports.studies.hwcost import FRAME_RATE_HZ, coefficient_memory, recommend
    from irnuc.reports.studies.sweep import run_sweep

    s = rep.config["sweep"]
    metric = s.get("error_metric", "err_max_lsb")
    max_error = float(s["max_error"])
    rate = float(s.get("frame_rate_hz", FRAME_RATE_HZ))
    with rep.phase("sweep"):
        sensor, axes = sweep_specs(s)
        res = run_sweep(sensor, axes, workers=s.get("workers", 2), scheduler=scheduler,
                        progress=progress("sweep", show_progress))
        rep.studies["sweep"] = res
        d = res.to_dict(max_error=max_error, metric=metric)
        rows, cols = res.frame_shape()
        for p in d["points"]:
            p["memory"] = coefficient_memory(p["bits_per_pixel"], rows, cols, rate)
            p["datapath_cost"] = None
            p["hw"] = None
        rec = recommend(d["points"], max_error, metric)
        recommended = None
        if rec["found"]:
            recommended = _recommended_entry(rep, d["points"][rec["index"]], metric,
                                             (rows, cols), d["axes"], rec["candidates"])
        else:
            rep.notes.append(f"no swept width meets {metric} <= {max_error:g}: widen the sweep "
                             "(more fraction bits)")
    rep.sections["sweep"] = SweepSection.of(d, tolerance={"metric": metric,
                                                          "max_error": max_error},
                                            recommended=recommended)
    pts = d["points"]
    sm = d["smallest"]
    rep.metric("sweep.points", len(pts), "info")
    rep.metric("sweep.best_err_max_lsb", min(p["err_max_lsb"] for p in pts), "lower", "LSB")
    rep.metric("sweep.best_residual_nu", min(p["residual_nu"] for p in pts), "lower")
    rep.metric("sweep.smallest_bits_per_pixel", sm["bits_per_pixel"], "lower", "bit")
    for p in pts:
        k = p["key"]
        rep.metric(f"sweep.point.{k}.err_max_lsb", p["err_max_lsb"], "lower", "LSB")
        rep.metric(f"sweep.point.{k}.err_rms_lsb", p["err_rms_lsb"], "lower", "LSB")
        rep.metric(f"sweep.point.{k}.residual_nu", p["residual_nu"], "lower")
        rep.metric(f"sweep.point.{k}.radial_rms_lsb", p["radial_rms_lsb"], "lower", "LSB")
    rep.figure("sweep", "Error of the fixed-point NUC against the float NUC, worst over the "
               "evaluation temperatures, against gain fraction bits (one line per offset "
               "fraction width)", figures.error_vs_bits(pts, metric, max_error))
    if "synth" not in rep.config:
        rep.figure("sweep", f"Pareto front of {metric} against coefficient memory; the star is the "
                   f"smallest memory meeting {metric} <= {max_error:g}",
                   figures.pareto(pts, res.pareto(metric), metric, sm))


def _first_syntheses(rep: Report, scheduler: str | None) -> tuple[list[int], list[int],
                                                                 dict[str, Any]]:
    """What :func:`phase_synth` synthesizes first (the cost model's fit points and the
    cheapest candidates: their indices) and its synthesis options."""
    from irnuc.reports.studies.hwcost import fit_indices, recommend

    sy = rep.config["synth"]
    sweep = rep.sections["sweep"]
    pts = [thaw(p) for p in sweep.points]
    fit = fit_indices(pts, int(sy.get("fit_points", FIT_POINTS)))
    cand = recommend(pts, sweep.tolerance["max_error"], sweep.tolerance["metric"])[
        "candidates"][:int(sy.get("candidates", CANDIDATES))]  # in order of error
    kw = {"workers": int(sy.get("workers", 2)), "scheduler": scheduler,
          "speed": int(sy.get("speed", 6)), "freq_mhz": float(sy.get("freq_mhz", 150.0)),
          "seed": int(sy.get("seed", 1))}
    return fit, cand, kw


def prefetch_synth(rep: Report, scheduler: str | None) -> None:
    """:func:`phase_synth`'s first syntheses into the cache on one worker, started in the
    background once the sweep has its points (:meth:`Report.start_background`)."""
    from irnuc.cosim.synth import synth_configs

    fit, cand, kw = _first_syntheses(rep, scheduler)
    rows, cols = rep.sections["sweep"]["frame"]
    typed = rep.studies["sweep"].sweep_points
    synth_configs([recommended_config(typed[i], rows, cols) for i in sorted(set(fit) | set(cand))],
                  **{**kw, "workers": 1})


def _quick_synth_notes(rep: Report) -> None:
    """Name the syntheses ``--quick`` leaves out (fewer fit points: the cost model fitted
    exactly, no held-out check of it; fewer candidates synthesized before the model picks)."""
    from irnuc.reports.report.config import quick_replaced

    sy = rep.config["synth"]
    cut, full = quick_replaced(rep.config, "synth.fit_points")
    if cut:
        n, was = int(sy.get("fit_points", FIT_POINTS)), int(FIT_POINTS if full is None else full)
        left_out(rep, "synth", f"{was - n} of the cost model's {was} fit syntheses: fitted on "
                 f"{n} points" + (" (its 3 coefficients exactly: its error is measured on the "
                                  "other synthesized points only)" if n == 3 else ""),
                 "synth.fit_points")
    cut, full = quick_replaced(rep.config, "synth.candidates")
    if cut:
        n, was = int(sy.get("candidates", CANDIDATES)), int(CANDIDATES if full is None else full)
        left_out(rep, "synth", f"the syntheses of the cheapest candidates past the first {n} "
                 f"(the full run synthesizes {was}); the recommendation is still synthesized",
                 "synth.candidates")


def phase_synth(rep: Report, scheduler: str | None, show_progress: bool) -> None:
    """Synthesize a few points, fit the cost model, cost every point, recommend."""
    from irnuc.cosim.synth import synth_configs
    from irnuc.reports.studies import figures
    from irnuc.reports.studies.hwcost import (
        CostModel,
        datapath_cost,
        recommend_synthesized,
        synth_figures,
        widths,
    )
    from irnuc.reports.studies.metrics import pareto_front

    sy = rep.config["synth"]
    sweep = rep.sections["sweep"]
    assert isinstance(sweep, SweepSection)
    # The points as working copies: their hardware figures are set here, then the sweep's
    # section is made anew with them.
    pts: list[dict[str, Any]] = [thaw(p) for p in sweep.points]
    metric = sweep.tolerance["metric"]
    max_error = sweep.tolerance["max_error"]
    rows, cols = sweep["frame"]
    dsp_w = float(sy.get("dsp_lut_equivalent", DSP_LUT_EQUIVALENT))
    _quick_synth_notes(rep)
    with rep.phase("synth"):
        # Started beside the paper phase on one worker: not waited for, the designs it has
        # not finished are shared out on this phase's workers (each design's cache entry
        # is locked while made: none is made twice), then the job is joined.
        fit, cand, synth_kw = _first_syntheses(rep, scheduler)
        typed = rep.studies["sweep"].sweep_points

        def synthesize(indices: list[int], label: str) -> dict[int, dict[str, Any]]:
            cfgs = [recommended_config(typed[i], rows, cols) for i in indices]
            return dict(zip(indices, synth_configs(cfgs, progress=progress(label, show_progress),
                                                   **synth_kw), strict=True))

        synthesized = synthesize(sorted(set(fit) | set(cand)), "synth")
        rep.join_background("sweep syntheses")
        model = CostModel.fit([widths(pts[i]) for i in fit],
                              [synth_figures(synthesized[i]) for i in fit])

        def cost_points() -> dict[int, float]:
            figs = {i: synth_figures(r) for i, r in synthesized.items()}
            for p in pts:
                i = p["index"]
                hw = ({"source": "synthesized", **figs[i]} if i in figs
                      else {"source": "model", **model.predict(widths(p))})
                p["hw"] = hw
                p["datapath_cost"] = round(datapath_cost(hw, dsp_w), 3)
            return {p["index"]: p["datapath_cost"] for p in pts}

        def synthesize_one(i: int) -> None:
            synthesized.update(synthesize([i], "synth (recommendation)"))

        # The recommendation is synthesized even when the model picks a candidate beyond
        # the first ``candidates``.
        rec = recommend_synthesized(pts, max_error, metric, cost_points, synthesized,
                                    synthesize_one)
        todo = sorted(synthesized)
        figs = {i: synth_figures(r) for i, r in synthesized.items()}
        held = [i for i in todo if i not in fit]
        heldout = model.errors([widths(pts[i]) for i in held], [figs[i] for i in held]) if held else {}
        every = model.errors([widths(pts[i]) for i in todo], [figs[i] for i in todo])
        cost = [p["datapath_cost"] for p in pts]
        err = [p[metric] if p[metric] is not None else float("inf") for p in pts]
        front_mem = pareto_front([p["bits_per_pixel"] for p in pts], err).tolist()
        front_dp = pareto_front(cost, err).tolist()
    synth = {
        "frame": [rows, cols], "dsp_lut_equivalent": dsp_w,
        "fit_indices": fit, "synthesized": [
            {"index": i, "label": pts[i]["label"],
             "used_for_fit": i in fit, "fmax_mhz": r["fmax_mhz"], "xc7": r["xc7"], "ecp5": r["ecp5"],
             "predicted": model.predict(widths(pts[i])), "cached": bool(r.get("cached")),
             "seconds": r.get("seconds"), "config_digest": r.get("config_digest")}
            for i, r in sorted(synthesized.items())],
        "model": model.to_dict(), "model_error_heldout": heldout, "model_error_all": every,
        "tools": next(iter(synthesized.values())).get("tools") if synthesized else None,
    }
    recommended = sweep.recommended
    if rec["found"]:
        p = pts[rec["index"]]
        if recommended is None or recommended["index"] != p["index"]:
            recommended = _recommended_entry(rep, p, metric, (rows, cols), sweep["axes"],
                                             rec["candidates"])
        r = synthesized[p["index"]]
        rs = SynthCheck(fmax_mhz=r["fmax_mhz"], xc7=r["xc7"], ecp5=r["ecp5"],
                        device=r.get("device"), speed=r.get("speed"),
                        target_mhz=r.get("target_mhz"),
                        critical_path=tuple(r.get("critical_path", [])[:12]))
        recommended = dataclasses.replace(recommended, synth=rs,
                                          datapath_cost=p["datapath_cost"])
        rep.metric("synth.recommended.fmax_mhz", rs.fmax_mhz, "higher", "MHz", rel_tol=0.05)
        for fam, keys in (("xc7", ("lut", "ff", "dsp", "bram18", "bram36")),
                          ("ecp5", ("lut4", "ff", "mult18", "dp16kd"))):
            for k in keys:
                rep.metric(f"synth.recommended.{fam}.{k}", rs[fam][k], "lower", rel_tol=0.02)
    rep.sections["sweep"] = dataclasses.replace(
        sweep, points=tuple(pts), synth=synth, pareto_memory=tuple(front_mem),
        pareto_datapath=tuple(front_dp), recommended=recommended)
    for key, e in every.items():
        rep.metric(f"synth.model_error.{key}", e["max_abs"], "info")
    rec_i = recommended["index"] if recommended else None
    rep.figure("sweep", f"Pareto fronts of {metric} against coefficient memory (left) and against "
               f"the datapath cost (right: xc7 LUTs + {dsp_w:g} per DSP48E1, synthesized points "
               "squared, the others from the cost model); the star is the recommendation",
               figures.hardware_fronts(pts, metric, max_error, rec_i, front_mem, front_dp))
    names = [x["label"] for x in synth["synthesized"]]
    used = [x["used_for_fit"] for x in synth["synthesized"]]
    rep.figure("synth", "Cost model against synthesis: xc7 LUTs (fit points and held-out "
               "points; the dotted line is exact)",
               figures.cost_model_check(names, [figs[i]["xc7.lut"] for i in todo],
                                        [model.predict(widths(pts[i]))["xc7.lut"] for i in todo],
                                        used, "xc7 LUTs"))
