"""Phase ``temperature``: the sign-off of a drifting camera (docs/reports.md, "Temperature").

1. The sweep (:mod:`irnuc.reports.studies.signoff`, on the sweep executor, cached): methods
   x coefficient fraction widths x FFC periods over the FPA range, the worst residual fixed
   pattern (mK, LSB) of every point, its coefficient memory and external-memory bandwidth.
2. The datapath cost of every point: ``irnuc synth`` of each method's shipped configuration
   (its own top, cached: the anchors), moved to the point's gain and offset word widths by
   the slopes of the bit-width sweep's cost model (``[synth]``), with that model's stated
   error; the recommendation itself is synthesized and its prediction error stated.
3. The recommendation: the cheapest point meeting the tolerance (``tolerance_mK``, default
   ``tolerance_netd`` x the NETD), its edges on the swept grid; when no point meets it, the
   point of lowest residual, flagged. Synthesized with ``irnuc_axis_top`` when the AXI top
   implements the method (``tops_for``), else with the method's own top.
4. The recommendation co-simulated bit-exact on a drifting model sequence through the bulk
   harness (``irnuc.cosim.sequence_bulk.cosim_sequence``).
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from irnuc.reports.report.base import Report, left_out, progress
from irnuc.reports.report.sections import SignoffCheck, TemperatureSection, Verdict

#: The figures of a synthesis the sign-off keeps per point (dotted: family.resource).
HW_KEYS = ("xc7.lut", "xc7.ff", "xc7.dsp", "xc7.bram36", "ecp5.lut4", "ecp5.ff", "ecp5.mult18",
           "ecp5.dp16kd", "fmax_mhz")
DEFAULTS: dict[str, Any] = {
    "preset": "default", "seed": 4, "rows": 24, "cols": 32, "fpa_K": [288.0, 308.0],
    "fpa_step_K": 1.0, "scene_K": [280.0, 330.0, 380.0], "ramp_K_per_min": 2.0,
    "frac_bits": [6, 8, 10, 12, 14], "ffc_periods_min": [0.25, 0.5, 1.0, 2.0],
    "ffc_changes_K": [0.1, 0.5, 1.5], "ffc_either": [[3.0, 1.5]], "node_K": 0.5,
    "node_max_s": 120.0, "max_peaks": 24, "housing_offset_K": [-5.0, 0.0, 5.0],
    "cosim_scenario": "power_on_warmup", "cosim_min_pixels": 1_000_000,
    "tolerance_netd": 0.5, "frame_rate_hz": 60.0, "bandwidth_frame": [480, 640],
    "noise_frames": 16, "workers": 2, "synth": True, "cosim": True, "cosim_frames": 20,
    "cosim_rows": 480, "cosim_cols": 640, "cosim_seed": 5, "ffc_every": 10,
    "dsp_lut_equivalent": 200.0, "synth_seeds": 4, "anchors": True, "place": True,
}

#: What ``place = false`` (``--quick``) leaves out of the recommendation's synthesis.
NOT_PLACED = ("the recommendation's placement and routing (nextpnr) and its bare core's "
              "synthesis: the wrapper synthesized for area only, no Fmax, no wrapper "
              "overhead")


def anchor_configs(t: Mapping[str, Any]) -> list[Any]:
    """The shipped configurations whose own tops are the cost model's anchors (every method
    of the sweep), or none when the section synthesizes nothing."""
    from irnuc.nuc_fixed import load_pipeline

    if not (setting(t, "synth") and setting(t, "anchors")):
        return []
    return [load_pipeline(n) for n in dict.fromkeys(spec_of(t).methods)]


def prefetch_anchors(t: Mapping[str, Any], scheduler: str | None) -> None:
    """Synthesize the anchors into the cache on one worker (:func:`Report.background`: the
    report starts this while its single-threaded phases use the other core); the phase
    then reads them (:func:`_cost_points`)."""
    from irnuc.cosim.synth import synth_configs

    cfgs = anchor_configs(t)
    if cfgs:
        synth_configs(cfgs, workers=1, scheduler=scheduler)



def setting(t: Mapping[str, Any], key: str) -> Any:
    return t.get(key, DEFAULTS[key])


def spec_of(t: Mapping[str, Any]):
    """The study specification of a ``[temperature]`` section."""
    from irnuc.reports.studies.signoff import SignoffSpec, registry_methods, scenario_default

    return SignoffSpec(
        preset=setting(t, "preset"), seed=int(setting(t, "seed")), rows=int(setting(t, "rows")),
        cols=int(setting(t, "cols")), fpa_K=tuple(float(x) for x in setting(t, "fpa_K")),
        fpa_step_K=float(setting(t, "fpa_step_K")),
        scene_K=tuple(float(x) for x in setting(t, "scene_K")),
        ramp_K_per_min=float(setting(t, "ramp_K_per_min")),
        methods=tuple(t.get("methods") or registry_methods()),
        frac_bits=tuple(int(x) for x in setting(t, "frac_bits")),
        ffc_periods_min=tuple(float(x) for x in setting(t, "ffc_periods_min")),
        ffc_changes_K=tuple(float(x) for x in setting(t, "ffc_changes_K")),
        ffc_either=tuple((float(a), float(b)) for a, b in setting(t, "ffc_either")),
        scenarios=tuple(t.get("scenarios") or scenario_default()),
        node_K=float(setting(t, "node_K")), node_max_s=float(setting(t, "node_max_s")),
        max_peaks=int(setting(t, "max_peaks")),
        housing_offset_K=tuple(float(x) for x in setting(t, "housing_offset_K")),
        frame_rate_hz=float(setting(t, "frame_rate_hz")),
        bandwidth_frame=tuple(int(x) for x in setting(t, "bandwidth_frame")),
        noise_frames=int(setting(t, "noise_frames")), overrides=dict(t.get("overrides") or {}))


def point_config(p: Mapping[str, Any], rows: int | None = None, cols: int | None = None):
    """The pipeline configuration of a sweep point (its method's shipped configuration with
    every fraction width set to the point's), optionally for a ``rows`` x ``cols`` frame."""
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.reports.studies.method_bits import with_frac_bits, with_range_bits

    cfg = with_range_bits(with_frac_bits(load_pipeline(p["config"]), int(p["frac_bits"])),
                          **dict(p.get("range_bits") or {}))
    wide = "".join(f", {k} = {v}" for k, v in (p.get("range_bits") or {}).items())
    ch: dict[str, Any] = {"name": "recommended_temperature",
                          "description": f"{p['config']} with {p['frac_bits']} fraction bits "
                                         f"everywhere{wide}, from the sign-off sweep of irnuc "
                                         "report"}
    if rows and cols:
        ch |= {"max_width": int(cols), "max_height": int(rows)}
    return cfg.replace(**ch)


def _flat(s: Mapping[str, Any]) -> dict[str, float]:
    from irnuc.reports.studies.hwcost import synth_figures

    f = synth_figures(s)
    return {k: f[k] for k in HW_KEYS}


def _slopes(rep: Report) -> tuple[dict[str, tuple[float, float]], dict[str, Any] | None]:
    """Per figure, the bit-width sweep's cost model's (gain bit, offset bit) slopes, and
    that model's stated error (none without a ``[synth]`` phase)."""
    sy = (rep.sections.get("sweep") or {}).get("synth")
    if not sy:
        return {}, None
    coef = sy["model"]["coefficients"]
    slopes = {k: (float(coef[k][1]), float(coef[k][2])) for k in HW_KEYS if k in coef}
    err = {k: (sy["model_error_all"].get(k) or {}).get("max_abs") for k in HW_KEYS}
    return slopes, {"model": sy["model"]["form"], "max_abs_error_at_synthesized_points": err,
                    "from": "the bit-width sweep's cost model ([synth])"}


def predict(anchor: Mapping[str, float], anchor_w: tuple[int, int], w: tuple[int, int],
            slopes: Mapping[str, tuple[float, float]]) -> dict[str, float]:
    """A method's figures at word widths ``w`` = (gain bits, offset bits): its synthesized
    anchor at ``anchor_w`` moved along the cost model's slopes (unmoved without slopes)."""
    out = {}
    dg, do = w[0] - anchor_w[0], w[1] - anchor_w[1]
    for k in HW_KEYS:
        bg, bo = slopes.get(k, (0.0, 0.0))
        v = float(anchor[k]) + bg * dg + bo * do
        out[k] = v if k == "fmax_mhz" else max(0.0, v)
    return out


def datapath_cost(hw: Mapping[str, float], dsp_w: float) -> float:
    from irnuc.reports.studies.hwcost import datapath_cost as dp

    return round(dp(hw, dsp_w), 3)


def fmax_note(sy: Mapping[str, Any]) -> str | None:
    """The report's note when the recommendation's synthesis misses its target frequency
    (a lead should see the miss, not only the number), else None. Over a seed sweep
    (``sy["seeds"]``, :func:`irnuc.cosim.synth.best_of_seeds`): a note when the best
    placement misses, and when only some placements meet the target (closure that hangs
    on the placer's seed)."""
    target = sy.get("target_mhz")
    if not target or sy.get("fmax_mhz") is None:
        return None
    sd = sy.get("seeds")
    head = f"temperature: the recommendation's {sy['top']} reaches"
    if not sd:
        if sy["fmax_mhz"] >= target:
            return None
        return (f"{head} {sy['fmax_mhz']:.1f} MHz, below the {target:g} MHz target, at this "
                f"placer seed (irnuc synth --seeds N tries others)")
    n, ok = sd["runs"], sd["at_target"]
    if sd["best_mhz"] < target:
        return (f"{head} {sd['best_mhz']:.1f} MHz at the best of {n} placer seeds (seed "
                f"{sd['best_seed']}; worst {sd['worst_mhz']:.1f}), below the {target:g} MHz "
                f"target")
    if ok < n:
        return (f"{head} {sd['best_mhz']:.1f} MHz at the best of {n} placer seeds (seed "
                f"{sd['best_seed']}) but {sd['worst_mhz']:.1f} at seed {sd['worst_seed']}: "
                f"{ok} of {n} placements meet the {target:g} MHz target")
    return None


def synth_top(cfg) -> tuple[str, str]:
    """The top the recommendation is synthesized with, and why."""
    from irnuc.cosim.synth import default_top, tops_for

    if "irnuc_axis_top" in tops_for(cfg):
        return "irnuc_axis_top", "the AXI4-Stream/AXI4-Lite top (irnuc_axis_top) implements this method"
    top = default_top(cfg)
    return top, (f"irnuc_axis_top does not implement {cfg.method} yet: synthesized with the "
                 f"method's own top ({top})")


def _cost_points(rep: Report, t: Mapping[str, Any], d: dict[str, Any], scheduler: str | None,
                 show: bool) -> None:
    """Anchors synthesized (cached), every point's predicted datapath, the model's error."""
    from irnuc.cosim.synth import default_top, synth_configs
    from irnuc.nuc_fixed import load_pipeline

    pts = d["points"]
    dsp_w = float(setting(t, "dsp_lut_equivalent"))
    if not setting(t, "synth"):
        d["cost"] = None
        return
    if not setting(t, "anchors"):
        d["cost"] = None
        d["left_out"] = [*d.get("left_out", []), "the methods' anchor syntheses (each shipped "
                         "configuration's own top): no synthesized or modelled datapath per "
                         "point; the recommendation is chosen on memory and bandwidth and is "
                         "still synthesized"]
        left_out(rep, "temperature", d["left_out"][-1], "temperature.anchors = false")
        return
    names = list(dict.fromkeys(p["config"] for p in pts))
    cfgs = [load_pipeline(n) for n in names]
    # The anchors started beside the earlier phases on one worker: the ones it has not
    # finished are shared out on this phase's workers (each design's cache entry is locked
    # while made: none is made twice), then the job is joined.
    res = synth_configs(cfgs, workers=int(setting(t, "workers")), scheduler=scheduler,
                        progress=progress("temperature synth", show))
    rep.join_background("anchors")
    anchors = {}
    for n, c, r in zip(names, cfgs, res, strict=True):
        anchors[n] = {"top": default_top(c), "widths": [c.gain_bits, c.offset_bits],
                      "figures": _flat(r), "cached": bool(r.get("cached")),
                      "frame": [c.max_height, c.max_width]}
    slopes, model = _slopes(rep)
    for p in pts:
        if not p.get("valid"):
            p["hw"], p["datapath_cost"] = None, None
            continue
        a = anchors[p["config"]]
        w = (int(p["gain_bits"]), int(p["offset_bits"]))
        if tuple(a["widths"]) == w and p["frac_bits"] == _shipped_frac(p["config"]):
            hw = {"source": "synthesized", **a["figures"]}
        else:
            hw = {"source": "model", **predict(a["figures"], tuple(a["widths"]), w, slopes)}
        p["hw"] = hw
        p["datapath_cost"] = datapath_cost(hw, dsp_w)
    d["cost"] = {"anchors": anchors, "dsp_lut_equivalent": dsp_w,
                 "model": model or {"model": "the anchor's figures at every width (no [synth] "
                                             "section: no slopes)",
                                    "max_abs_error_at_synthesized_points": None},
                 "note": "the model moves the gain and offset words only; the other formats' "
                         "widths (tc, quad, table, ffc) are not in it"}


def _shipped_frac(name: str) -> int | None:
    from irnuc.nuc_fixed import load_pipeline

    cfg = load_pipeline(name)
    fr = {cfg.gain_frac_bits, cfg.offset_frac_bits, *[f.frac_bits for f in cfg.formats]}
    return fr.pop() if len(fr) == 1 else None


#: Why a design is placed out of context (its ports need more pins than the package has).
OOC_WHY = ("; its ports need more I/O than the package has pins: placed out of context "
           "(nextpnr --out-of-context, the ports on on-chip logic)")


def _misfit_file(cfg: Any, top: str) -> Path:
    """Where a design's "does not fit the package's I/O" is kept: keyed by the design on pins
    (sources, parameters, flow, tool versions), so that a warm report does not place it on
    pins again only to fail the same way."""
    from irnuc.common.cache import cache_dir
    from irnuc.cosim.synth import synth_key

    return cache_dir("temperature") / f"io-misfit-{synth_key(cfg, top=top)}.json"


def _seeds_fitting(cfg: Any, top: str, kw: dict[str, Any],
                   decided: Callable[[bool], None] | None = None) -> tuple[dict[str, Any], bool]:
    """:func:`synth_seeds` of ``top`` on the package's pins, or out of context when its ports
    do not fit them (nextpnr: no BEL left of type TRELLIS_IO; remembered); (result, placed
    out of context). Any other failure is raised. ``decided(out_of_context)`` is called as
    soon as that is known (a remembered misfit: at once; a misfit found: when the first
    placement on pins fails, seconds in; fitting: when placed)."""
    from irnuc.common.io import write_text_atomic
    from irnuc.cosim import synth

    say = decided or (lambda ooc: None)
    misfit = _misfit_file(cfg, top)
    if not misfit.is_file():
        try:
            out = synth.synth_seeds(cfg, top=top, **kw)
        except synth.SynthError as exc:
            if "TRELLIS_IO" not in str(exc):
                say(False)
                raise
            write_text_atomic(misfit, json.dumps({"top": top, "config": cfg.digest(),
                                                  "error": str(exc)[-2000:]}) + "\n")
        else:
            say(False)
            return out, False
    say(True)
    return synth.synth_seeds(cfg, top=top, **{**kw, "out_of_context": True}), True


def _place_both(cfg: Any, top: str, core_top: str, kw: dict[str, Any]
                ) -> tuple[dict[str, Any], bool, dict[str, Any]]:
    """The wrapper (``top``, on pins or out of context) and the bare core placed side by
    side: the core starts as soon as the wrapper's pin question is answered (it is placed
    the same way, for a like-for-like comparison), each on ``workers`` processes, so a
    core is not left idle when the seeds are fewer than the workers (``--quick``: one
    each). (wrapper result, out of context, core result)."""
    import concurrent.futures as cf
    import threading

    from irnuc.cosim import synth

    if core_top == top:
        s, ooc = _seeds_fitting(cfg, top, kw)
        return s, ooc, s
    mode: dict[str, bool] = {}
    ready = threading.Event()

    def decided(ooc: bool) -> None:
        mode["ooc"] = ooc
        ready.set()

    def core() -> dict[str, Any] | None:
        ready.wait()
        if "ooc" not in mode:
            return None
        return synth.synth_seeds(cfg, top=core_top,
                                 **{**kw, **({"out_of_context": True} if mode["ooc"] else {})})

    with cf.ThreadPoolExecutor(max_workers=2, thread_name_prefix="irnuc-place") as pool:
        fut_core = pool.submit(core)
        try:
            s, ooc = _seeds_fitting(cfg, top, kw, decided)
        finally:
            ready.set()  # a wrapper that failed otherwise: the core thread ends
        c = fut_core.result()
    if c is None:  # (not reached: decided() runs before any return)
        c = synth.synth_seeds(cfg, top=core_top,
                              **{**kw, **({"out_of_context": True} if ooc else {})})
    return s, ooc, c


def synth_area(cfg: Any, top: str) -> dict[str, Any]:
    """Area of ``top`` for a configuration without placing it: the xc7 and ECP5 cell
    counts of :func:`irnuc.cosim.synth.synth_netlist` (the same cached netlists that
    ``irnuc synth`` places; no Fmax). ``top``, ``xc7``, ``ecp5``, ``device``."""
    from irnuc.cosim import synth
    from irnuc.cosim.sources import hdl_sources, top_parameters

    _, xc7, ecp5 = synth.synth_netlist(hdl_sources(top), top, top_parameters(top, cfg))
    return {"top": top, "xc7": {k: xc7[k] for k in synth.XC7_KEYS},
            "ecp5": {k: ecp5[k] for k in synth.ECP5_KEYS},
            "device": f"LFE5U-{synth.ECP5_DEVICE.removesuffix('k')}F"}


def _synth_recommended(t: Mapping[str, Any], r: dict[str, Any]) -> None:
    from irnuc.cosim import synth

    cfg = point_config(r)
    top, why = synth_top(cfg)
    if not setting(t, "place"):
        # area only (--quick): the wrapper's netlists, not placed; the fmax check not run
        try:
            a = synth_area(cfg, top)
        except synth.SynthError as exc:
            r["synth"] = {"top": top, "why": why, "error": str(exc).splitlines()[0][:300]}
            return
        r["synth"] = {"top": top, "why": why, "placed": False, "fmax_mhz": None,
                      "xc7": a["xc7"], "ecp5": a["ecp5"], "device": a["device"],
                      "frame": [cfg.max_height, cfg.max_width], "not_placed": NOT_PLACED}
        return
    # Placed at `synth_seeds` placer seeds (in parallel, each cached): the best placement's
    # figures, with the worst and the spread beside them.
    kw: dict[str, Any] = {"seeds": int(setting(t, "synth_seeds")),
                          "workers": int(setting(t, "workers"))}
    # The cost model moves bare cores (the anchors): its error is judged on the bare core
    # at these widths, and what the wrapper adds is stated beside it (best against best).
    core_top = synth.default_top(cfg)
    try:
        # both netlists side by side first (cold), then each one's placements
        synth.prepare_netlists([(cfg, top), (cfg, core_top)] if core_top != top
                               else [(cfg, top)], workers=kw["workers"])
    except synth.SynthError:
        pass  # said below, by the top that fails, as without the preparation
    try:
        # The wrapper's ports may not fit the package's pins (wide coefficient and FFC
        # words): then placed as the IP block it is, its ports meeting on-chip logic
        # (nextpnr --out-of-context, docs/synthesis.md), and said; the bare core the same
        # way, side by side with it.
        s, ooc, core = _place_both(cfg, top, core_top, kw)
    except synth.SynthError as exc:
        r["synth"] = {"top": top, "why": why, "error": str(exc).splitlines()[0][:300]}
        return
    if ooc:
        why += OOC_WHY
        kw["out_of_context"] = True
    fig = _flat(s)
    pred = r.get("hw")
    core_fig = _flat(core)
    r["synth"] = {"top": top, "why": why, "fmax_mhz": s["fmax_mhz"], "seeds": s.get("seeds"),
                  "xc7": s["xc7"],
                  "ecp5": s["ecp5"], "device": s.get("device"), "speed": s.get("speed"),
                  "target_mhz": s.get("target_mhz"), "cached": bool(s.get("cached")),
                  "out_of_context": bool(kw.get("out_of_context")),
                  "frame": [cfg.max_height, cfg.max_width],
                  "critical_path": (s.get("critical_path") or [])[:8],
                  "predicted": ({k: pred[k] for k in HW_KEYS} if pred else None),
                  "core": {"top": core_top, "fmax_mhz": core["fmax_mhz"], "xc7": core["xc7"],
                           "ecp5": core["ecp5"], "seeds": core.get("seeds")},
                  "wrapper_overhead": ({k: round(fig[k] - core_fig[k], 3) for k in HW_KEYS}
                                       if core_top != top else None),
                  "prediction_error": ({k: round(pred[k] - core_fig[k], 3) for k in HW_KEYS}
                                       if pred and pred.get("source") == "model" else None)}


def _cosim(t: Mapping[str, Any], r: dict[str, Any], spec: Any) -> dict[str, Any]:
    """The recommendation co-simulated through ``irnuc_axis_top`` (:mod:`irnuc.cosim.axis_bulk`)
    on frames of a thermal scenario (``cosim_scenario``): ``cosim_rows`` x ``cosim_cols``
    frames of the physics model at times spread over the scenario (the FPA and the housing
    moving, each frame at its own state, the scene sweeping 280-380 K, noise on), the
    sensors' readings of those times written over AXI4-Lite, FFCs where the recommended
    policy's trigger asks on those readings (its period counted in these frames:
    ``ffc_every``), at least ``cosim_min_pixels`` output pixels; cached by digest."""
    import hashlib
    import json

    from irnuc.common.cache import cache_dir
    from irnuc.common.io import write_text_atomic
    from irnuc.cosim.axis_bulk import AXIS_HARNESS, unsupported
    from irnuc.reports.studies.signoff import code_digest

    shape = (int(setting(t, "cosim_rows")), int(setting(t, "cosim_cols")))
    seed = int(setting(t, "cosim_seed"))
    scenario = str(setting(t, "cosim_scenario"))
    cfg = point_config(r, *shape)
    head = {"shape": list(shape), "seed": seed, "scenario": scenario, "top": "irnuc_axis_top",
            "source": "irnuc.cosim.axis_bulk (C++ harness around irnuc_axis_top)"}
    why = unsupported(cfg)
    if why:
        return {**head, "frames": 1, "pixels_compared": 0, "mismatches": None,
                "ffc_events": None, "passed": None, "seconds": 0.0, "not_run": why}
    key_d = {"cfg": cfg.digest(), "spec": spec.to_dict(), "shape": shape, "seed": seed,
             "scenario": scenario, "policy": r.get("ffc_policy"),
             "every": int(setting(t, "ffc_every")), "min": int(setting(t, "cosim_min_pixels")),
             "frames": int(setting(t, "cosim_frames")), "code": code_digest(),
             "harness": hashlib.sha256(AXIS_HARNESS.read_bytes()
                                       + Path(__file__).read_bytes()).hexdigest()[:16]}
    key = hashlib.sha256(json.dumps(key_d, sort_keys=True, default=str).encode()).hexdigest()[:20]
    path = cache_dir("temperature") / f"axis-cosim-{key}.json"
    if path.is_file():
        try:
            return {**json.loads(path.read_text()), "cached": True}
        except (OSError, json.JSONDecodeError):
            pass
    t0 = time.perf_counter()
    out = _cosim_run(t, r, spec, cfg, shape, seed, scenario)
    out = {**head, **out, "seconds": round(time.perf_counter() - t0, 3)}
    if out.get("passed") is not None:
        write_text_atomic(path, json.dumps(out) + "\n")
    return {**out, "cached": False}


def _prefetch_axis_build(t: Mapping[str, Any], r: Mapping[str, Any]) -> None:
    """The Verilator build :func:`_cosim_run` will use (cached), made in the background."""
    from irnuc.cosim.axis_bulk import build_axis, unsupported

    cfg = point_config(r, int(setting(t, "cosim_rows")), int(setting(t, "cosim_cols")))
    if not unsupported(cfg):
        build_axis(cfg)


def _cosim_run(t: Mapping[str, Any], r: Mapping[str, Any], spec: Any, cfg: Any,
               shape: tuple[int, int], seed: int, scenario: str) -> dict[str, Any]:
    import dataclasses
    import math

    import numpy as np

    from irnuc.cosim.axis_bulk import axis_stimulus, build_axis, run_axis
    from irnuc.model.sequence import load_sequence
    from irnuc.nuc_fixed.axis import ffc_framing, ffc_shutter_flags
    from irnuc.nuc_fixed.ffc_policy import FfcPolicy, closed_loop
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.methods import READINGS
    from irnuc.nuc_fixed.plan import run_plan
    from irnuc.reports.studies import drift_common as dc

    sensor = dc.StudySensor(preset=spec.preset, rows=shape[0], cols=shape[1], seed=spec.seed,
                            overrides=dict(spec.overrides))
    plan = spec.plan()
    if not any(READINGS[n].frame_field == "housing_reading" for n in cfg.base.readings
               if n in READINGS):
        plan = dataclasses.replace(plan, housing_offset=())  # the fit uses offset 0 only
    pts = run_plan(plan, sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    cal = calibrate_points(pts, cfg)
    seq = load_sequence(scenario)
    sched = dataclasses.replace(seq, record_every=1).schedule()
    fields = sched.fields(seq.fpa_sensor, seed, seq.housing_sensor)
    px = shape[0] * shape[1]
    nf = int(cfg.ffc_frames or 1)
    ffc = cfg.has("ffc")
    thr = 0
    if ffc and r.get("ffc_change_K"):
        thr = FfcPolicy.from_physical(None, float(r["ffc_change_K"]), seq.frame_rate,
                                      seq.fpa_sensor.lsb_K).threshold
    every = int(setting(t, "ffc_every"))
    n = max(int(setting(t, "cosim_frames")), math.ceil(int(setting(t, "cosim_min_pixels")) / px))
    want = int(setting(t, "cosim_min_pixels"))
    for _ in range(30):  # held shutter frames show nothing: more frames until enough are shown
        idx = np.round(np.linspace(0, sched.fpa_K.size - 1, n)).astype(np.int64)
        rd = np.asarray(fields["fpa_reading"])[idx]
        starts = closed_loop(rd, FfcPolicy(period=every, threshold=thr), nf) if ffc else []
        # the frames shown: the wrapper's framing of these shutter runs (held frames none)
        shown = (sum(ffc_framing(cfg, ffc_shutter_flags(n, {s: nf for s in starts})).shown)
                 if ffc else n)
        if shown * px >= want:
            break
        # the shown share stays about the same as frames are added: scale by it
        n = max(n + 1, math.ceil(n * want / max(shown * px, 1)))
    n = int(idx.size)  # the frames made (the last round's, if the rounds ran out)
    scenes = np.linspace(280.0, 380.0, n)
    raws = []
    for k, i in enumerate(idx):
        raw, _ = dc.frames_at(sensor, float(sched.fpa_K[i]), float(sched.T_cam_K[i]),
                              [float(scenes[k])], noise=True)
        raws.append(raw[0])
    st = axis_stimulus(cal.coeffs, raws, {k: np.asarray(v)[idx] for k, v in fields.items()
                                          if k.endswith("_reading")}, starts)
    bld = build_axis(cfg)
    res = run_axis(bld, st, seed=seed, stall_percent=10, idle_percent=5)
    return {"frames": n, "min_pixels": int(setting(t, "cosim_min_pixels")),
            "ffc_events": st.ffc_events, "ffc_starts": [int(s) for s in starts],
            "registers_written": len(st.writes), "frame_times_s": [
                float(sched.time_s[i]) for i in idx],
            "housing_minus_fpa_K": [float(sched.T_cam_K[i] - sched.fpa_K[i]) for i in idx],
            **res}


def tolerance_mK(t: Mapping[str, Any], netd_mK: float) -> tuple[float, str]:
    """The tolerance (mK) and how it was set."""
    if "tolerance_mK" in t:
        return float(t["tolerance_mK"]), f"{float(t['tolerance_mK']):g} mK (tolerance_mK)"
    k = float(setting(t, "tolerance_netd"))
    return k * netd_mK, f"{k:g} x NETD = {k * netd_mK:.3g} mK (tolerance_netd)"


def choose(pts: list[dict[str, Any]], tol: float, periods: list[float]) -> dict[str, Any]:
    """The recommendation: the cheapest point meeting ``tol`` on every scenario; else the
    lowest residual, flagged ``meets_tolerance: false``, with each configuration's best
    point and the scenarios that break it (``breaking``)."""
    from irnuc.reports.studies.scenarios import breaking
    from irnuc.reports.studies.signoff import grid_edges, recommend, representative

    dp = {p["index"]: p["datapath_cost"] for p in pts if p.get("datapath_cost") is not None}
    rec = recommend(pts, tol, dp)
    valid = [p for p in pts if p.get("valid")]
    if rec["found"]:
        p, meets = pts[rec["index"]], True
    elif valid:
        p, meets = min(valid, key=lambda q: (q["worst_fpn_mK"], q["memory_bits"], q["index"])), False
    else:
        return {"found": False, "point": None, "candidates": []}
    rows = [{"key": q["key"], "worst_fpn_mK": q["worst_fpn_mK"], "breaks": breaking(q, tol)}
            for q in representative(valid, tol)]
    return {"found": True, "meets": meets, "point": p, "candidates": rec["candidates"],
            "edges": grid_edges(p, pts, periods, meets), "breaking": rows}


def _synth_left_out(rep: Report, t: Mapping[str, Any], d: dict[str, Any]) -> None:
    """Name what the recommendation's synthesis leaves out: its placement
    (``place = false``), else the placer seeds past ``synth_seeds``."""
    if not setting(t, "place"):
        d["left_out"] = [*d.get("left_out", []), NOT_PLACED]
        left_out(rep, "temperature", NOT_PLACED, "temperature.place = false")
    elif int(setting(t, "synth_seeds")) < int(DEFAULTS["synth_seeds"]):
        d["left_out"] = [*d.get("left_out", []), (
            f"the recommendation placed at {int(setting(t, 'synth_seeds'))} placer "
            f"seed(s), not {DEFAULTS['synth_seeds']}: its Fmax is one placement's, "
            "no best/worst spread")]
        left_out(rep, "temperature", d["left_out"][-1], "temperature.synth_seeds")


def _judged(res: Mapping[str, Any], spec: Any, tol: float) -> list[dict[str, Any]]:
    """The study's points, each valid one with its bandwidth, whether it meets ``tol`` and
    the scenarios that break it."""
    from irnuc.reports.studies.scenarios import breaking
    from irnuc.reports.studies.signoff import bandwidth_MBps

    pts = res["points"]
    for p in pts:
        if p.get("valid"):
            p["bandwidth_MBps"] = bandwidth_MBps(p["read_bits_per_frame"], spec.bandwidth_frame,
                                                 spec.frame_rate_hz)
            p["meets_tolerance"] = p["worst_fpn_mK"] <= tol
            p["breaks"] = breaking(p, tol)
    return pts


def prefetch_signoff(t: Mapping[str, Any], scheduler: str | None) -> dict[str, bool]:
    """The sign-off's study and, when its choice needs nothing of the earlier phases (no
    anchors: chosen on memory and bandwidth), the recommendation's synthesis beside its
    axis harness build and co-simulation, all into the cache, on one worker
    (:meth:`Report.start_background`, started at the report's start when no anchor is
    synthesized there); the phase then reads them. Which of the study and the
    co-simulation were made here (not read from the cache): ``{"study", "cosim"}``."""
    import concurrent.futures as cf

    from irnuc.reports.studies.signoff import cache_file, cached_signoff

    spec = spec_of(t)
    made = {"study": not cache_file(spec).is_file(), "cosim": False}
    res = cached_signoff(spec, workers=min(1, int(setting(t, "workers"))), scheduler=scheduler)
    if setting(t, "synth") and setting(t, "anchors"):
        return made  # the choice weighs the datapath: the anchors first (the phase)
    tol, _ = tolerance_mK(t, float(res["netd_mK"]))
    pts = [dict(p) for p in res["points"]]
    ch = choose(_judged({"points": pts}, spec, tol), tol, list(spec.ffc_periods_min))
    if not ch["found"]:
        return made
    r = _recommended(ch, tol, float(res["netd_mK"]), spec)

    def cosim() -> None:
        _prefetch_axis_build(t, r)
        made["cosim"] = _cosim(t, r, spec).get("cached") is False

    jobs = []
    with cf.ThreadPoolExecutor(max_workers=2, thread_name_prefix="irnuc-bg-rec") as pool:
        if setting(t, "cosim"):
            jobs.append(pool.submit(cosim))
        if setting(t, "synth"):
            jobs.append(pool.submit(_synth_recommended, t, dict(r)))
        for j in jobs:
            j.result()
    return made


def phase_temperature(rep: Report, scheduler: str | None, show_progress: bool) -> None:
    from irnuc.reports.report.config import quick_replaced
    from irnuc.reports.studies.signoff import (
        cached_signoff,
        figures,
        fronts,
        representative,
    )

    t = rep.config["temperature"]
    t0 = time.perf_counter()
    times: dict[str, float] = {}
    with rep.phase("temperature"):
        spec = spec_of(t)
        # made in the background when nothing else ran there (prefetch_signoff): read
        # from the cache, still this run's own study
        rep.join_background("sign-off")
        made_here = rep.background_value("sign-off") or {}
        res = cached_signoff(spec, workers=int(setting(t, "workers")), scheduler=scheduler,
                             progress=progress("temperature", show_progress))
        if made_here.get("study"):
            res = {**res, "cached": False}
        times["sweep"] = round(time.perf_counter() - t0, 3)
        netd = float(res["netd_mK"])
        tol, tol_text = tolerance_mK(t, netd)
        pts = _judged(res, spec, tol)
        d: dict[str, Any] = {k: res[k] for k in ("spec", "plan", "netd", "netd_mK",
                                                 "noise_3d", "camera_temperature", "scenarios",
                                                 "policies")}
        d |= {"points": pts, "tolerance_mK": tol, "tolerance": tol_text, "cached": res["cached"],
              "study_seconds": res["seconds"]}
        t1 = time.perf_counter()
        _cost_points(rep, t, d, scheduler, show_progress)
        times["anchors"] = round(time.perf_counter() - t1, 3)
        d["fronts"] = {"memory_bits": fronts(pts, "memory_bits"),
                       "datapath_cost": fronts(pts, "datapath_cost") if d.get("cost") else None,
                       "bandwidth_MBps": fronts(pts, "bandwidth_MBps"),
                       "dead_time_pct": fronts(pts, "dead_time_pct")}
        ch = choose(pts, tol, list(spec.ffc_periods_min))
        d["recommended"] = None
        if ch["found"]:
            r = _recommended(ch, tol, netd, spec)
            d["recommended"] = r
            for e in r["edges"]:
                rep.notes.append(f"temperature: the recommendation lies on the {e['edge']} edge of "
                                 f"the swept {e['axis']}: {e['widen']}")
            if not r["meets_tolerance"]:
                rep.notes.append(f"temperature: no swept point meets {tol_text} on every scenario; "
                                 f"the recommendation is the lowest residual, "
                                 f"{r['worst_fpn_mK']:.3g} mK ({r['key']}), broken by "
                                 f"{', '.join(r['breaks'])}")
            if setting(t, "cosim"):
                # the axis harness's Verilator build beside the placements (cached)
                rep.start_background("axis build", _prefetch_axis_build, t, r)
            if setting(t, "synth"):
                t1 = time.perf_counter()
                _synth_left_out(rep, t, d)
                _synth_recommended(t, r)
                times["synth"] = round(time.perf_counter() - t1, 3)
                note = fmax_note(r.get("synth") or {})
                if (r.get("synth") or {}).get("error"):
                    note = f"temperature: the recommendation was not placed: {r['synth']['error']}"
                if note:
                    rep.notes.append(note)
            if setting(t, "cosim"):
                t1 = time.perf_counter()
                cut, full = quick_replaced(rep.config, "temperature.cosim_min_pixels")
                if cut:
                    was = int(DEFAULTS["cosim_min_pixels"] if full is None else full)
                    d["left_out"] = [*d.get("left_out", []), (
                        f"the axis co-simulation's {was:,} pixels: at least "
                        f"{int(setting(t, 'cosim_min_pixels')):,} compared")]
                    left_out(rep, "temperature", d["left_out"][-1], "temperature.cosim_min_pixels")
                rep.join_background("axis build")
                r["cosim"] = _cosim(t, r, spec)
                if made_here.get("cosim") and r["cosim"].get("cached"):
                    r["cosim"]["cached"] = False  # run by this report, in the background
                times["cosim"] = round(time.perf_counter() - t1, 3)
                if r["cosim"].get("not_run"):
                    rep.notes.append(f"temperature: not co-simulated: {r['cosim']['not_run']}")
        else:
            rep.notes.append("temperature: no valid point in the sweep")
        t1 = time.perf_counter()
        d["background"] = {k: dict(v) for k, v in rep.background.items()
                           if k in ("anchors", "sign-off", "axis build")}
        d["images"] = _worst_images(res, d["recommended"])
        # The traces of the points a figure draws (each configuration's representative and
        # the recommendation) stay; the others' are in the study's cache only.
        shown = {p["key"] for p in representative([p for p in pts if p.get("valid")], tol)}
        if d["recommended"]:
            shown.add(d["recommended"]["key"])
        res_fig = {**res, "points": pts, "tolerance_mK": tol, "fronts": d["fronts"]}
        for cap, png in figures(res_fig, d["recommended"], d["images"]):
            rep.figure("temperature", cap, png)
        for p in pts:
            if p.get("key") not in shown:
                p.pop("traces", None)
        _camera_figure(rep, res)
        times["figures"] = round(time.perf_counter() - t1, 3)
        d["seconds"] = times
    rep.sections["temperature"] = TemperatureSection.of(d, verdict=signoff_verdict(d))
    temperature_metrics(rep, d)


#: The verdict when there was no sign-off to judge.
NOT_RUN = Verdict("not run", "no [temperature] section in the configuration: no sign-off")


def _residual_check(d: Mapping[str, Any], r: Mapping[str, Any]) -> SignoffCheck:
    w, tol = float(r["worst_fpn_mK"]), float(d["tolerance_mK"])
    basis = str(d.get("tolerance", "")).split(" = ")[0]  # "0.5 x NETD" or "15 mK (tolerance_mK)"
    n = len(r.get("scenarios") or {})
    over = f" on every one of {n} scenarios" if n else ""
    if r["meets_tolerance"]:
        return SignoffCheck("residual", "met", f"{r['key']}: {w:.3g} mK <= tolerance {tol:.3g} mK "
                                               f"({basis}){over}")
    breaks = r.get("breaks") or []
    by = f", broken by {', '.join(breaks)}" if breaks else ""
    return SignoffCheck("residual", "not met",
                        f"{r['key']}: {w:.3g} mK > tolerance {tol:.3g} mK ({basis}), the lowest "
                        f"residual of the sweep{by}")


def _fmax_check(sy: Mapping[str, Any] | None) -> SignoffCheck:
    if not sy:
        return SignoffCheck("fmax", "not run", "not synthesized ([temperature] synth = false)")
    from irnuc.cosim.synth import TARGET_MHZ

    if sy.get("error"):
        return SignoffCheck("fmax", "not met", f"{sy['top']}: not placed and routed: {sy['error']}")
    if sy.get("placed") is False:
        return SignoffCheck("fmax", "not run", f"{sy['top']} synthesized for area only, not "
                                               "placed and routed (temperature.place = false)")
    target = float(sy.get("target_mhz") or TARGET_MHZ)
    sd = sy.get("seeds")
    best = float(sd["best_mhz"] if sd else sy["fmax_mhz"])
    at = (f"at the best of {sd['runs']} placer seeds (seed {sd['best_seed']})" if sd
          else "at one placer seed")
    ok = best >= target
    return SignoffCheck("fmax", "met" if ok else "not met",
                        f"{sy['top']} {best:.1f} MHz {at} {'>=' if ok else '<'} {target:g} MHz")


def _cosim_check(c: Mapping[str, Any] | None) -> SignoffCheck:
    if not c:
        return SignoffCheck("cosim", "not run", "not co-simulated ([temperature] cosim = false)")
    if c.get("not_run") or c.get("passed") is None:
        return SignoffCheck("cosim", "not run", f"not co-simulated: {c.get('not_run')}")
    top = c.get("top") or "the bulk harness"
    if c["passed"] and not c["mismatches"] and c["pixels_compared"] < int(c.get("min_pixels") or 0):
        return SignoffCheck("cosim", "not met",
                            f"co-simulated through {top}: {c['pixels_compared']} pixels "
                            f"bit-exact, fewer than the {c['min_pixels']} asked")
    if c["passed"] and not c["mismatches"]:
        return SignoffCheck("cosim", "met", f"co-simulated through {top}: {c['pixels_compared']} "
                                            "pixels bit-exact")
    return SignoffCheck("cosim", "not met",
                        f"co-simulated through {top}: {c['mismatches']} mismatch(es) of "
                        f"{c['pixels_compared']} pixels")


def signoff_verdict(d: Mapping[str, Any] | None) -> Verdict:
    """The sign-off verdict of a Temperature section's results ``d`` (None: no sign-off),
    apart from the regression status (docs/reports.md, "The sign-off verdict").

    ``not met`` when the recommendation misses its tolerance, its synthesis misses the
    target frequency at its best placer seed, or its co-simulation mismatches (or when the
    sweep had no valid point); ``met`` otherwise, the checks that did not run named in the
    reason; ``not run`` without a sign-off.
    """
    if d is None:
        return NOT_RUN
    r = d.get("recommended")
    if not r:
        return Verdict("not met", "no valid point in the sweep: nothing to recommend")
    checks = (_residual_check(d, r), _fmax_check(r.get("synth")), _cosim_check(r.get("cosim")))
    missed = [c.detail for c in checks if c.status == "not met"]
    if missed:
        return Verdict("not met", "; ".join(missed), r["key"], checks)
    skipped = [c.name for c in checks if c.status == "not run"]
    reason = checks[0].detail + (f" (not checked: {', '.join(skipped)})" if skipped else "")
    return Verdict("met", reason, r["key"], checks)


def _recommended(ch: Mapping[str, Any], tol: float, netd: float, spec: Any) -> dict[str, Any]:
    from irnuc.cosim.synth import memory_traffic
    from irnuc.reports.studies.hwcost import coefficient_memory

    p = ch["point"]
    cfg = point_config(p)
    keep = ("index", "key", "config", "method", "frac_bits", "ffc_period_min", "ffc_change_K",
            "ffc_policy", "ffc_policy_text", "ffc_per_hour", "dead_time_pct",
            "worst_fpn_mK", "worst_fpn_lsb", "worst_level_error_mK", "worst_scenario",
            "scenarios", "breaks", "traces", "memory_bits", "calibration_bits", "runtime_bits",
            "read_bits_per_frame", "bandwidth_MBps", "gain_bits", "offset_bits", "formats",
            "hw", "datapath_cost", "bad_fraction")
    r = {k: p.get(k) for k in keep}
    if p.get("range_bits"):  # the reading ranges the plan needed (point_config rebuilds them)
        r["range_bits"] = dict(p["range_bits"])
    r |= {"meets_tolerance": ch["meets"], "tolerance_mK": tol, "netd_mK": netd,
          "margin_mK": tol - p["worst_fpn_mK"], "candidates": ch["candidates"][:20],
          "breaking": ch.get("breaking") or [],
          "edges": ch["edges"], "widths": {"gain": f"{cfg.gain_bits} bits", "offset":
                                           f"{cfg.offset_bits} bits", **p["formats"]},
          "memory": coefficient_memory(p["memory_bits"], *spec.bandwidth_frame, spec.frame_rate_hz),
          "stream": memory_traffic(cfg), "pipeline": cfg.to_dict(), "pipeline_toml": cfg.to_toml(),
          "synth": None, "cosim": None}
    return r


def _worst_images(res: Mapping[str, Any], r: Mapping[str, Any] | None) -> dict[str, Any] | None:
    """Raw and corrected (the recommendation, golden model) images of the middle scene at
    the recommendation's worst frame: its worst scenario, at that frame's FPA, housing and
    readings, with the refresh of the FFC before it (made exactly, not interpolated)."""
    if not r or not r.get("worst_scenario"):
        return None
    import dataclasses

    import numpy as np

    from irnuc.model.sequence import load_sequence
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top
    from irnuc.nuc_fixed.plan import run_plan
    from irnuc.reports.studies import drift_common as dc
    from irnuc.reports.studies.signoff import spec_from_dict

    spec = spec_from_dict(res["spec"])
    sensor = spec.sensor()
    name = r["worst_scenario"]
    per = r["scenarios"][name]
    seq = load_sequence(name)
    sched = dataclasses.replace(seq, record_every=1).schedule()
    fields = sched.fields(seq.fpa_sensor, sensor.seed, seq.housing_sensor)
    pts = run_plan(spec.plan(), sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    cal = calibrate_points(pts, point_config(r))
    ffc = cal.cfg.has("ffc")
    i = int(per["worst_frame"])
    scene = float(np.median(spec.scene_K))

    def inputs(idx: list[int], blind: np.ndarray, shutter: bool) -> FrameInputs:
        return FrameInputs(reading=np.asarray(fields["fpa_reading"])[idx],
                           housing_reading=np.asarray(fields["housing_reading"])[idx],
                           blind_codes=blind, shutter=np.full(len(idx), shutter) if ffc else None)

    offset = None
    sref = per.get("worst_refresh_frame")
    if ffc and sref is not None:
        n = int(cal.cfg.ffc_frames or 1)
        sraw, sblind = dc.frames_at(sensor, float(sched.fpa_K[sref]), float(sched.T_cam_K[sref]),
                                    [float(sched.T_shutter_K[sref])], repeats=n)
        idx = [min(sref + k, len(sched.fpa_K) - 1) for k in range(n)]
        offset = method_top(sraw, cal.coeffs, inputs(idx, sblind, True)).ffc_offset
    raw, blind = dc.frames_at(sensor, float(sched.fpa_K[i]), float(sched.T_cam_K[i]), [scene])
    y = method_top(raw, cal.coeffs, inputs([i], blind, False), ffc_offset=offset).y[0]
    return {"worst": {"scenario": name, "time_s": float(sched.time_s[i]),
                      "fpa_K": float(sched.fpa_K[i]), "housing_K": float(sched.T_cam_K[i]),
                      "scene_K": scene, "refresh_s": (None if sref is None
                                                      else float(sched.time_s[sref])),
                      "raw": raw[0].tolist(), "corrected": y.tolist(),
                      "good": (~cal.bad).tolist()}}


def _camera_figure(rep: Report, res: Mapping[str, Any]) -> None:
    from irnuc.reports.studies import camera_temperature

    rep.figure("temperature", "The camera-temperature test (the paper repository's test_tcomp): "
               "the housing warms, cools or holds while the FPA stays at the reference; "
               "two_point with and without blind_drift",
               camera_temperature.figure(res["camera_temperature"]))


def temperature_metrics(rep: Report, d: Mapping[str, Any]) -> None:
    """The section's metrics for ``--baseline`` (docs/reports.md)."""
    rep.metric("temperature.netd_mK", d["netd_mK"], "info", "mK")
    rep.metric("temperature.tolerance_mK", d["tolerance_mK"], "info", "mK")
    rep.metric("temperature.points", len(d["points"]), "info")
    for p in d["points"]:
        if p.get("valid"):
            rep.metric(f"temperature.point.{p['key']}.worst_fpn_mK", p["worst_fpn_mK"], "lower", "mK")
            rep.metric(f"temperature.point.{p['key']}.worst_fpn_lsb", p["worst_fpn_lsb"], "lower",
                       "LSB")
            if p.get("worst_level_error_mK") is not None:
                rep.metric(f"temperature.point.{p['key']}.worst_level_error_mK",
                           p["worst_level_error_mK"], "info", "mK")
    r = d.get("recommended")
    rep.metric("temperature.recommended.meets_tolerance",
               None if r is None else int(r["meets_tolerance"]), "higher")
    if not r:
        return
    rep.metric("temperature.recommended.worst_fpn_mK", r["worst_fpn_mK"], "lower", "mK")
    rep.metric("temperature.recommended.memory_bits", r["memory_bits"], "lower", "bit")
    rep.metric("temperature.recommended.bandwidth_MBps", r["bandwidth_MBps"], "lower", "MB/s")
    if r.get("dead_time_pct") is not None:
        rep.metric("temperature.recommended.dead_time_pct", r["dead_time_pct"], "lower", "%")
        rep.metric("temperature.recommended.ffc_per_hour", r["ffc_per_hour"], "lower", "1/h")
    for name, sc in (r.get("scenarios") or {}).items():
        rep.metric(f"temperature.recommended.scenario.{name}.worst_fpn_mK", sc["worst_fpn_mK"],
                   "lower", "mK")
    if r.get("synth") and not r["synth"].get("error"):
        s = r["synth"]
        if s.get("fmax_mhz") is not None:
            rep.metric("temperature.recommended.synth.fmax_mhz", s["fmax_mhz"], "higher", "MHz",
                       rel_tol=0.05)
        if s.get("seeds"):  # the worst placement moves more with the seeds: shown, not judged
            rep.metric("temperature.recommended.synth.fmax_worst_mhz",
                       s["seeds"]["worst_mhz"], "info", "MHz")
        for k in ("lut", "ff", "dsp"):
            rep.metric(f"temperature.recommended.synth.xc7.{k}", s["xc7"][k], "lower", rel_tol=0.02)
    c = r.get("cosim")
    if c and not c.get("not_run"):
        rep.metric("temperature.recommended.cosim.pixels", c["pixels_compared"], "info")
        rep.metric("temperature.recommended.cosim.mismatches", c["mismatches"], "lower")
        rep.metric("temperature.recommended.cosim.failed", int(not c["passed"]), "lower")
