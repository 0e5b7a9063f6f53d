"""HTML of the report and of the ``irnuc precision`` page: Jinja2 templates
(``templates/*.html.j2``) and ONE stylesheet (``templates/irnuc.css``), inlined, so each page
is one self-contained file (PNG figures embedded as base64)."""

from __future__ import annotations

import base64
from collections.abc import Mapping
from functools import cache
from typing import Any

from irnuc.reports.report.base import Report
from irnuc.reports.report.config import REPORT_DIR

TEMPLATES = REPORT_DIR / "templates"
STYLESHEET = TEMPLATES / "irnuc.css"

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


def fmt(v: Any, digits: int = 4) -> str:
    """A number for a table cell: integers as they are, floats to ``digits`` significant."""
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
    return str(v)


def b64(png: bytes) -> str:
    return base64.b64encode(png).decode()


@cache
def environment():
    import jinja2

    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(TEMPLATES)),
                             autoescape=True, trim_blocks=True, lstrip_blocks=True,
                             undefined=jinja2.StrictUndefined)
    env.filters["fmt"] = fmt
    env.filters["b64"] = b64
    env.globals["stylesheet"] = lambda: STYLESHEET.read_text()
    return env


def paper_context(p: Mapping[str, Any]) -> dict[str, Any]:
    """The numbers the paper section's prose quotes (computed here, written by the template)."""
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
        items.append({"variant": v["variant"], "values": ", ".join(f"{x:.4f}" for x in v["residual_nu"]),
                      "change": f"{100 * worst:+.1f} %", "why": _VARIANT_WHY.get(v["key"], "")})
    head = ["case", "t (K)"] + [f"f = {b}" for b in bits] + ["float NU"]
    rows = [["paper reference implementation", 350.0, *p["reference_nu"], None],
            ["2^-f/√12 (uniform rounding)", None, *p["uniform_rounding_model"], None]]
    for v in p["variants"]:
        rows.append([v["variant"], v["t_eval"], *v["residual_nu"], v["float_nu"]])
    return {
        "head": head, "rows": rows, "items": items,
        "model": ", ".join(f"{v:.4f}" for v in p["uniform_rounding_model"]),
        "bits": ", ".join(map(str, bits)), "floor": fmt(main["float_nu"]),
        "radial": " to ".join(f"{100 * v:.0f} %" for v in (min(main["radial_fraction"]),
                                                         max(main["radial_fraction"]))),
        "irnuc": ", ".join(f"{v:.4f}" for v in main["residual_nu"]),
        "ref": ", ".join(f"{v:.4f}" for v in p["reference_nu"]),
        "ratio": ", ".join(f"{v:.2f}" for v in p["ratio_to_reference"]),
        "physics": f"{100 * physics:.1f} %", "seed": f"{100 * seed:.1f} %", "between": between,
        "grange": f"gains {gl:.3f} to {gh:.3f}",
        "steps": " and ".join(f"{(gh - gl) * 2 ** b:.1f}" for b in bits[:2]),
        "intbits": ", ".join(main["labels"]),
    }


def status_line(summary: Mapping[str, Any]) -> str:
    """The run's two outcomes on one line, apart: the regression status and the sign-off
    verdict with its reason ("regression: pass · sign-off: not met (...)")."""
    so = summary["signoff"]
    return f"regression: {summary['status']} · sign-off: {so['verdict']} ({so['reason']})"


def headline(rep: Report, summary: Mapping[str, Any]) -> list[tuple[str, str]]:
    rows = [("regression · sign-off", status_line(summary))]
    s = rep.sections
    if "calibration" in s:
        d = s["calibration"]["detection"]
        rows.append(("bad-pixel detection precision / recall", f"{d['precision']:.3f} / {d['recall']:.3f}"))
    if "sweep" in s:
        r = s["sweep"].get("recommended")
        tol = s["sweep"]["tolerance"]
        if r:
            text = (f"{r['gain_format']} gain, {r['offset_format']} offset: "
                    f"{r['bits_per_pixel']} bit/pixel, "
                    f"{tol['metric']} {fmt(r['error'])}")
            if r.get("synth"):
                x = r["synth"]["xc7"]
                text += (f"; Fmax {r['synth']['fmax_mhz']:.1f} MHz, xc7 {x['lut']} LUT, {x['ff']} FF, "
                         f"{x['dsp']} DSP")
            if r.get("cosim"):
                c = r["cosim"]
                text += (f"; co-simulation {c['passed']}/{c['passed'] + c['failed']} passed, "
                         f"{c['pixels']} pixels, {c['mismatches']} mismatches")
            if r.get("edges"):
                text += " — ON THE EDGE of the swept grid"
        else:
            text = "none in the sweep"
        rows.append((f"recommended coefficient widths ({tol['metric']} ≤ {tol['max_error']:g})", text))
    if s.get("temperature"):
        rows.append(temperature_headline(s["temperature"]))
    if "paper" in s:
        p = s["paper"]
        rows.append(("residual NU at 350 K, f = " + ", ".join(map(str, p["frac_bits"])),
                     "irnuc " + ", ".join(f"{v:.4f}" for v in p["variants"][0]["residual_nu"])
                     + " · paper " + ", ".join(f"{v:.4f}" for v in p["reference_nu"])))
    if "cosim" in s:
        c = s["cosim"]
        rows.append(("co-simulation", f"{c['passed']}/{c['tests']} passed, {c['failed']} failed, "
                     f"{c['error']} errors, {c.get('timeout', 0)} timed out"
                     + (" (partial)" if c.get("partial") else "")))
    cov = (s.get("cosim") or {}).get("coverage")
    if cov:
        f = cov["functional"]
        rows.append(("functional coverage (tests this report ran)",
                     f"{f['hit']} / {f['total']} bins ({f['percent']:g} %) over "
                     + ", ".join(cov["functional"]["configurations"])))
    mut = (s.get("cosim") or {}).get("mutation")
    if mut:
        rows.append(("RTL mutants killed (irnuc mutate)",
                     f"{mut['killed']} of {mut['killed'] + mut['survived']} non-equivalent "
                     f"(score {100 * mut['score']:.1f} %), {mut['equivalent']} equivalent, "
                     f"{mut['survived']} survived"
                     + ("" if mut.get("complete", True) else
                        f" (partial: {len(mut.get('missing') or [])} not run on this RTL)")))
    auto = (s.get("cosim") or {}).get("mutation_auto")
    if auto:
        rows.append(("automatic RTL mutants killed (irnuc mutate --auto)",
                     f"{auto['killed']} of {auto['killed'] + auto['survived']} not proved "
                     f"equivalent (score {100 * auto['score']:.1f} %), {auto['equivalent']} "
                     f"proved equivalent, {auto['survived']} survived"
                     + ("" if auto.get("complete", True) else
                        f" (partial: {len(auto.get('missing') or [])} drawn not run, "
                        f"{len(auto.get('not_drawn') or [])} modules not drawn)")))
    fv = (s.get("cosim") or {}).get("formal")
    if fv:
        rows.append(("formal proofs (irnuc formal)",
                     f"{fv['proved']} proved, {fv['bounded']} bounded, {len(fv['not_ok'])} "
                     f"not holding; {fv['detected']} of {fv['detected'] + len(fv['missed'])} "
                     "planted faults detected"
                     + ("" if fv.get("complete", True) else
                        f" (partial: {len(fv.get('missing') or [])} proofs and faults "
                        "without a result on these sources)")))
    if "precision" in s:
        pr = s["precision"]
        rows.append(("work-precision defaults on the Pareto front",
                     f"{sum(v['default_on_front'] for v in pr['components'].values())} of "
                     f"{len(pr['components'])} components"))
    return rows


def render_report(rep: Report, summary: Mapping[str, Any]) -> str:
    sections = rep.sections
    ctx = {
        "rep": rep, "summary": summary, "s": sections, "prov": summary["provenance"],
        "figures": rep.figures, "headline": headline(rep, summary),
        "paper": paper_context(sections["paper"]) if "paper" in sections else None,
        "times": [[k, f"{v:.2f} s"] for k, v in summary["phases"].items()]
        + [["total", f"{sum(summary['phases'].values()):.2f} s"]],
        "cal": calibration_rows(sections["calibration"]) if "calibration" in sections else None,
        "sw": sweep_rows(sections["sweep"]) if "sweep" in sections else None,
        "sy": (synth_rows(sections["sweep"]["synth"])
               if (sections.get("sweep") or {}).get("synth") else None),
        "co": cosim_rows(sections["cosim"]) if "cosim" in sections else None,
        "pr": precision_rows(sections["precision"]) if "precision" in sections else None,
        "tm": temperature_rows(sections["temperature"]) if "temperature" in sections else None,
        "prov_rows": provenance_rows(summary["provenance"], summary, bool(rep.config.get("quick"))),
        "bl": baseline_rows(summary["baseline"]) if "baseline" in summary else None,
        "nav": [k for k in ("calibration", "sweep", "synth", "paper", "temperature", "cosim",
                            "formal", "precision")
                if k in sections or (k == "synth" and (sections.get("sweep") or {}).get("synth"))
                or (k == "formal" and (sections.get("cosim") or {}).get("formal"))]
        + (["baseline"] if "baseline" in summary else []),
    }
    return environment().get_template("report.html.j2").render(**ctx)


def render_precision_page(result: Mapping[str, Any]) -> str:
    """The ``irnuc precision`` page: per component the two log-log diagrams, the table of
    points and the failed settings."""
    from irnuc.reports.studies.precision import failure_label, figures

    figs = figures(dict(result))
    comps = [{"c": c, "caption": cap, "png": png,
              "failed": [{**m, "label": failure_label(m["reason"])} for m in c["missing"]]}
             for c, (cap, png) in zip(result["components"], figs, strict=True)]
    return environment().get_template("precision.html.j2").render(result=result, comps=comps)


def temperature_headline(t: Mapping[str, Any]) -> tuple[str, str]:
    """The headline row of the Temperature section."""
    r = t.get("recommended")
    title = (f"drifting camera: method, widths, FFC policy on {len(t.get('scenarios') or {})} "
             f"thermal scenarios (residual ≤ {t['tolerance']})")
    if not r:
        return title, "no valid point in the sweep"
    text = (f"{r['config']} ({r['method']}), {r['frac_bits']} fraction bits"
            + (f", FFC {r['ffc_policy_text']}" if r.get("ffc_policy") else "")
            + f": {r['worst_fpn_mK']:.3g} mK worst residual"
            + (f" (on {r['worst_scenario']})" if r.get("worst_scenario") else "")
            + f", {r['memory_bits']} bit/pixel, {r['bandwidth_MBps']:.0f} MB/s"
            + (f", {r['dead_time_pct']:.2g} % dead time, {r['ffc_per_hour']:.3g} FFC/h"
               if r.get("ffc_policy") else ""))
    if not r["meets_tolerance"]:
        text += " — NO POINT MEETS THE TOLERANCE (lowest residual shown"
        text += f"; broken by {', '.join(r['breaks'])})" if r.get("breaks") else ")"
    if r.get("synth") and r["synth"].get("error"):
        text += f"; {r['synth']['top']} not placed and routed"
    elif r.get("synth") and r["synth"].get("fmax_mhz") is None:
        text += f"; {r['synth']['top']} synthesized for area, not placed"
    elif r.get("synth"):
        text += f"; {r['synth']['top']} Fmax {r['synth']['fmax_mhz']:.1f} MHz{seeds_text(r['synth'])}"
    c = r.get("cosim")
    if c and not c.get("not_run"):
        text += (f"; co-simulated on {c['frames']} frames of {c['shape'][1]} × {c['shape'][0]}: "
                 f"{c['pixels_compared']} pixels, {c['mismatches']} mismatches")
    elif c:
        text += "; not co-simulated"
    if r.get("edges"):
        text += " — ON THE EDGE of the swept grid"
    return title, text


def temperature_rows(t: Mapping[str, Any]) -> dict[str, Any]:
    """Tables of the Temperature section: the points, the fraction-bit table per method,
    the 3D noise, the camera-temperature test, the recommendation's cost."""
    fr = t["fronts"]
    on_m = set(fr["memory_bits"]["overall"])
    on_d = set((fr.get("datapath_cost") or {}).get("overall") or [])
    on_own = {i for ids in fr["memory_bits"]["per_method"].values() for i in ids}
    head = ["point", "method", "f", "FFC policy", "worst mK", "level mK", "worst on", "FFC/h",
            "dead %", "worst LSB", "bit/px", "read bit/px", "MB/s", "xc7 LUT", "DSP", "Fmax MHz",
            "cost from", "LUT+DSP", "meets", "front"]
    rows = []
    for p in t["points"]:
        if not p.get("valid"):
            rows.append([p["key"], p["method"], p["frac_bits"], None, None, None, None, None,
                         None, None, None, None, None, None, None, None,
                         p.get("reason", "invalid"), None, None, ""])
            continue
        hw = p.get("hw") or {}
        rows.append([p["key"], p["method"], p["frac_bits"], p.get("ffc_policy_text"),
                     p["worst_fpn_mK"], p.get("worst_level_error_mK"), p.get("worst_scenario"),
                     p.get("ffc_per_hour"), p.get("dead_time_pct"), p["worst_fpn_lsb"],
                     p["memory_bits"],
                     p["read_bits_per_frame"], p.get("bandwidth_MBps"), hw.get("xc7.lut"),
                     hw.get("xc7.dsp"), hw.get("fmax_mhz"), hw.get("source"),
                     p.get("datapath_cost"), p.get("meets_tolerance"),
                     ("M" if p["index"] in on_m else "") + ("D" if p["index"] in on_d else "")
                     + ("m" if p["index"] in on_own else "")])
    bits = sorted({p["frac_bits"] for p in t["points"]})
    table: dict[str, dict[int, float | None]] = {}
    for p in t["points"]:
        name = p["config"] + (f" (FFC {p['ffc_policy_text']})" if p.get("ffc_policy")
                              else f" (FFC {p['ffc_period_min']:g} min)"
                              if p.get("ffc_period_min") is not None else "")
        table.setdefault(name, {})[p["frac_bits"]] = p["worst_fpn_mK"] if p.get("valid") else None
    bit_rows = [[n, *[v.get(b) for b in bits]] for n, v in table.items()]
    n3 = [[k, c["meaning"], c["sigma_mK"], c["sigma_se_mK"], c["naive_mK"]]
          for k, c in t["noise_3d"]["components"].items()]
    cam = []
    for prof, rec in t["camera_temperature"]["profiles"].items():
        for label in ("two_point", "two_point+blind_drift"):
            cam.append([prof, label, rec[label]["worst_level_error_mK"], rec[label]["worst_fpn_mK"]])
    r = t.get("recommended")
    cost = []
    if r:
        m = r["memory"]
        xc7_fit = _fits(m["xc7_fits"], m["xc7_device"], m["xc7_bram36_available"])
        ecp5_fit = _fits(m["ecp5_fits"], m["ecp5_device"], m["ecp5_dp16kd_available"])
        cost = [["coefficient words", ", ".join(f"{k} {v}" for k, v in r["widths"].items())],
                ["memory per pixel", f"{r['memory_bits']} bits ({r['calibration_bits']} calibration, "
                 f"{r['runtime_bits']} runtime)"],
                ["per frame", f"{m['pixels']} pixels: {m['bits_per_frame'] / 8 / 1024:.1f} KiB; "
                 f"{m['xc7_bram36']} RAMB36E1 ({xc7_fit}), {m['ecp5_dp16kd']} DP16KD ({ecp5_fit})"],
                ["external memory", f"{r['read_bits_per_frame']} bits read per pixel per frame: "
                 f"{r['bandwidth_MBps']:.1f} MB/s at {m['frame_rate_hz']:g} frames/s; the RTL's "
                 f"coefficient stream {r['stream']['stream_bits_per_pixel']} bits per pixel"]]
        if r.get("synth") and r["synth"].get("error"):
            cost.append(["synthesized top", f"{r['synth']['top']}: {r['synth']['error']}"])
        elif r.get("synth"):
            sy = r["synth"]
            x, e = sy["xc7"], sy["ecp5"]
            cost += [["synthesized top", f"{sy['top']}: {sy['why']}"],
                     ["xc7", f"{x['lut']} LUT, {x['ff']} FF, {x['dsp']} DSP48E1, {x['bram36']} RAMB36"],
                     ["ECP5", f"{e['lut4']} LUT4, {e['ff']} FF, {e['mult18']} MULT18, {e['dp16kd']} DP16KD"],
                     ["Fmax (nextpnr-ecp5)", f"not run: {sy['not_placed']}"]
                     if sy.get("fmax_mhz") is None else
                     ["Fmax (nextpnr-ecp5)", f"{sy['fmax_mhz']:.1f} MHz on {sy['device']} speed "
                      f"{sy['speed']} (aiming at {sy['target_mhz']:g} MHz){seeds_text(sy, True)}"]]
            if sy.get("wrapper_overhead"):
                c = sy["core"]
                cost.append(["the bare core", f"{c['top']}: {c['xc7']['lut']} LUT, "
                             f"{c['xc7']['ff']} FF (xc7), {c['fmax_mhz']:.1f} MHz; the wrapper "
                             "adds " + ", ".join(f"{k} {fmt(v)}"
                                                 for k, v in sy["wrapper_overhead"].items())])
            if sy.get("prediction_error"):
                pe = sy["prediction_error"]
                cost.append(["cost model at this point", "predicted − synthesized "
                             f"({sy.get('core', {}).get('top', sy['top'])}): "
                             + ", ".join(f"{k} {fmt(v)}" for k, v in pe.items())])
    scen = [[n, sc.get("description", ""), f"{sc['duration_s']:g} s at {sc['frame_rate']:g} Hz",
             f"{sc['fpa_span_K'][0]:g}–{sc['fpa_span_K'][1]:g}",
             f"{sc['housing_minus_fpa_K'][0]:g}–{sc['housing_minus_fpa_K'][1]:g}", sc["nodes"]]
            for n, sc in (t.get("scenarios") or {}).items()]
    breaking = [[b["key"], b["worst_fpn_mK"], ", ".join(b["breaks"]) or "meets on every scenario"]
                for b in (r or {}).get("breaking", [])]
    return {"scenarios": scen, "breaking": breaking,
            "head": head, "rows": rows, "bits_head": ["configuration", *[f"f = {b}" for b in bits]],
            "bits": bit_rows, "noise3d": n3, "cam": cam, "cost": cost}


def calibration_rows(c: Mapping[str, Any]) -> dict[str, Any]:
    return {
        "kinds": [[k, v["pixels"], v["found"], v["recall"]] for k, v in c["per_kind"].items()],
        "evals": [[f"{e['t_eval']:g} K", e["raw_nu"], e["residual_nu_good"], e["residual_nu_dpc"],
                   e.get("residual_std_dpc_lsb")] for e in c["evaluation"]],
    }


def sweep_rows(s: Mapping[str, Any]) -> dict[str, Any]:
    front_m = set(s.get("pareto_memory") or s["pareto"]["indices"])
    front_d = set(s.get("pareto_datapath") or [])
    rows = []
    for p in s["points"]:
        hw = p.get("hw") or {}
        m = p["memory"]
        rows.append([p["label"], p["bits_per_pixel"], p["err_max_lsb"], p["err_rms_lsb"],
                     p["residual_nu"], p["radial_fraction"], m["xc7_bram36"], m["ecp5_dp16kd"],
                     hw.get("xc7.lut"), hw.get("xc7.ff"), hw.get("xc7.dsp"), hw.get("fmax_mhz"),
                     hw.get("source"), p.get("datapath_cost"),
                     ("M" if p["index"] in front_m else "") + ("D" if p["index"] in front_d else ""),
                     p["gain_saturated_fraction"], p["offset_saturated_fraction"]])
    head = ["gain / offset", "bit/px", "max |e| LSB", "rms LSB", "NU", "radial frac.", "RAMB36",
            "DP16KD", "xc7 LUT", "FF", "DSP", "Fmax MHz", "cost from", "LUT+DSP", "front",
            "sat. gain", "sat. offset"]
    r = s.get("recommended")
    rec = None
    if r:
        m = r["memory"]
        mem = [["gain word", r["gain_format"], f"{r['gain_bits']} bits"],
               ["offset word", r["offset_format"], f"{r['offset_bits']} bits"],
               ["bad-pixel flag", "", "1 bit"],
               ["coefficient word", "", f"{r['bits_per_pixel']} bits per pixel"],
               ["per frame", f"{m['pixels']} pixels",
                f"{m['bits_per_frame']} bits = {m['bits_per_frame'] / 8 / 1024:.1f} KiB"],
               ["on chip, xc7", f"{m['xc7_bram36']} RAMB36E1",
                _fits(m["xc7_fits"], m["xc7_device"], m["xc7_bram36_available"])],
               ["on chip, ECP5", f"{m['ecp5_dp16kd']} DP16KD",
                _fits(m["ecp5_fits"], m["ecp5_device"], m["ecp5_dp16kd_available"])],
               ["external memory", f"{m['external_bytes_per_pixel']} B per pixel on the bus",
                f"{m['external_bytes_per_frame'] / 2**20:.2f} MiB per frame, "
                f"{m['external_mbyte_per_s']:.1f} MB/s at {m['frame_rate_hz']:g} frames/s"]]
        dp = []
        if r.get("synth"):
            x, e = r["synth"]["xc7"], r["synth"]["ecp5"]
            dp = [["xc7 (synth_xilinx)", f"{x['lut']} LUT, {x['ff']} FF, {x['dsp']} DSP48E1, "
                   f"{x['bram18']} RAMB18, {x['bram36']} RAMB36, {x['lutram']} LUTRAM"],
                  ["ECP5 (synth_ecp5)", f"{e['lut4']} LUT4, {e['ccu2c']} CCU2C, {e['ff']} FF, "
                   f"{e['mult18']} MULT18X18D, {e['dp16kd']} DP16KD, {e['lutram']} DPR16X4"],
                  ["Fmax (nextpnr-ecp5)", f"{r['synth']['fmax_mhz']:.1f} MHz on {r['synth']['device']} "
                   f"speed {r['synth']['speed']} (aiming at {r['synth']['target_mhz']:g} MHz); one pixel "
                   f"per clock: {r['synth']['fmax_mhz'] / (m['pixels'] / 1e6):.0f} frames/s of "
                   f"{m['pixels']} pixels"]]
        rec = {"r": r, "memory": mem, "datapath": dp}
    return {"head": head, "rows": rows, "rec": rec}


def _fits(fits: bool, device: str, blocks: int) -> str:
    return f"fits an {device} ({blocks})" if fits else f"more than an {device} has ({blocks})"


def seeds_text(sy: Mapping[str, Any], detail: bool = False) -> str:
    """What a seed sweep adds to a synthesized Fmax: the best of N placer seeds, the worst
    (and, in ``detail``, every seed's figure); nothing for one placement."""
    sd = sy.get("seeds")
    if not sd:
        return ""
    text = (f" (best of {sd['runs']} placer seeds, seed {sd['best_seed']}; worst "
            f"{sd['worst_mhz']:.1f} MHz, {sd['at_target']} of {sd['runs']} at the target")
    if detail:
        text += "; " + ", ".join(f"seed {k}: {v:.1f}" for k, v in sd["fmax_mhz"].items())
    return text + ")"


def synth_rows(sy: Mapping[str, Any]) -> dict[str, Any]:
    keys = ("xc7.lut", "xc7.ff", "xc7.dsp", "xc7.bram36", "ecp5.lut4", "ecp5.ff", "ecp5.mult18",
            "ecp5.dp16kd", "fmax_mhz")
    rows = []
    for x in sy["synthesized"]:
        got = {"xc7.lut": x["xc7"]["lut"], "xc7.ff": x["xc7"]["ff"], "xc7.dsp": x["xc7"]["dsp"],
               "xc7.bram36": x["xc7"]["bram36"], "ecp5.lut4": x["ecp5"]["lut4"],
               "ecp5.ff": x["ecp5"]["ff"], "ecp5.mult18": x["ecp5"]["mult18"],
               "ecp5.dp16kd": x["ecp5"]["dp16kd"], "fmax_mhz": x["fmax_mhz"]}
        rows.append([x["label"], "fit" if x["used_for_fit"] else "held out",
                     *[f"{fmt(got[k])} ({fmt(round(x['predicted'][k], 1))})" for k in keys],
                     "cached" if x["cached"] else "synthesized"])
    err = []
    for k in keys:
        a = sy["model_error_all"].get(k, {})
        h = sy["model_error_heldout"].get(k, {})
        lo = sy["model"]["leave_one_out"].get(k, {})
        err.append([k, a.get("max_abs"), a.get("max_rel"), h.get("max_abs"), h.get("max_rel"),
                    lo.get("max_abs"), lo.get("max_rel")])
    return {"head": ["point", "role", *keys, ""], "rows": rows, "errors": err}


def cosim_rows(c: Mapping[str, Any]) -> dict[str, Any]:
    cases = []
    for x in c["cases"]:
        cases.append([f"{x.get('classname', '')}::{x['name']}", x["status"], x["time"],
                      x.get("pixels"), (f"{x['detected']} (negative control)"
                                        if x.get("negative_control") else x.get("mismatches")),
                      len(x.get("assertion_failures") or []), x.get("log") or "", x.get("waves") or ""])
    cfgs = [[g["name"], g["adc_bits"], g["out_bits"], g["gain"], g["offset"], g["rounding"],
             f"{g['max_width']} × {g['max_height']}", g["word_bits"], ", ".join(g["tests"])]
            for g in c.get("configurations", [])]
    bad = [x for x in c["cases"] if x["status"] != "passed"]
    triage = [x for x in c["cases"] if x.get("triage")]
    return {"cases": cases, "configs": cfgs, "bad": bad, "triage": triage,
            **coverage_rows(c.get("coverage")), **mutation_rows(c.get("mutation")),
            **auto_mutation_rows(c.get("mutation_auto")), **formal_rows(c.get("formal"))}


def coverage_rows(cov: Mapping[str, Any] | None) -> dict[str, Any]:
    """Tables of the measured coverage: functional per configuration and per coverpoint,
    line and toggle per configuration and module."""
    if not cov:
        return {"fcov": [], "fcov_points": [], "ccov": []}
    fcov, points, ccov = [], [], []
    for label, c in cov["functional"]["configurations"].items():
        more = c["uncovered_count"] - len(c["uncovered"])
        fcov.append([label, ", ".join(c["tops"]), f"{c['hit']} / {c['total']}", c["percent"],
                     ", ".join(c["uncovered"]) + (f" and {more} more" if more > 0 else "")
                     or "none"])
        for name, p in c["coverpoints"].items():
            removed = "; ".join(f"{b}: {why}" for b, why in p["removed"].items())
            points.append([label, name, p["kind"], f"{p['hit']} / {p['total']}", p["percent"],
                           removed])
    for label, mods in cov["code"].items():
        for mod, m in mods.items():
            more = m["missed_count"] - len(m["missed_lines"])
            ccov.append([label, mod, f"{m['line']['hit']} / {m['line']['total']}",
                         m["line"]["percent"], f"{m['toggle']['hit']} / {m['toggle']['total']}",
                         m["toggle"]["percent"],
                         ", ".join(m["missed_lines"]) + (f" and {more} more" if more > 0 else "")])
    return {"fcov": fcov, "fcov_points": points, "ccov": ccov}


def mutation_rows(mut: Mapping[str, Any] | None) -> dict[str, Any]:
    """The mutation campaign: one row per mutant, and the equivalent ones' arguments."""
    if not mut:
        return {"mutants": [], "equivalents": []}
    rows = [[m["id"], m["file"], m["what"], m["config"], m["status"], m.get("killed_by") or ""]
            for m in mut.get("mutants", [])]
    return {"mutants": rows, "equivalents": list((mut.get("equivalents") or {}).items())}


def auto_mutation_rows(auto: Mapping[str, Any] | None) -> dict[str, Any]:
    """The automatic mutants: per module, and one row per mutant with its formal verdict."""
    if not auto:
        return {"auto_modules": [], "auto_mutants": []}
    mods = [[mod, r["killed"], r["survived"], r["equivalent"],
             "-" if r["score"] is None else f"{100 * r['score']:.1f} %"]
            for mod, r in (auto.get("per_module") or {}).items()]
    rows = [[m["id"], m["what"], m["config"], m["status"], m.get("killed_by") or "",
             m.get("verdict") or "", m.get("note") or ""] for m in auto.get("mutants", [])]
    return {"auto_modules": mods, "auto_mutants": rows}


def formal_rows(fv: Mapping[str, Any] | None) -> dict[str, Any]:
    """The formal campaign: one row per proof and per planted fault."""
    if not fv:
        return {"proofs": [], "faults": []}
    def depth(p: Mapping[str, Any]) -> str:
        if p["status"] == "not run":
            return ""
        if p["depth"] is None:
            return "unbounded"
        return f"{p['depth']} cycles" + (f" (of {p['wanted']}: the time budget)"
                                         if p.get("wanted") else "")

    proofs = [[p["id"], p["what"], p["engine"], depth(p), p["status"], p.get("cover") or "",
               p.get("asserts"), f"{p['seconds']:.1f}"] for p in fv.get("proofs", [])]
    missing = set(fv.get("missing") or ())
    faults = [[f["id"], f["what"], f["property"],
               "not run" if f["id"] in missing else "detected" if f["detected"] else "MISSED",
               "" if f.get("step") is None else f["step"]] for f in fv.get("faults", [])]
    return {"proofs": proofs, "faults": faults}


def precision_rows(pr: Mapping[str, Any]) -> dict[str, Any]:
    table, failed = [], []
    for name, v in pr["components"].items():
        table.append([name, v["default_error"], v["default_time_s"], v["default_work"],
                      v["default_on_front"], v["default_on_front_work"], v["points"], v["failed_points"]])
        d = (pr.get("details") or {}).get(name, {})
        if d.get("failed"):
            failed.append({"name": name, "rows": [[m["method"], f"{m['setting_name']} = {m['setting']:g}",
                                                   m["label"], m["reason"]] for m in d["failed"]]})
    return {"table": table, "failed": failed}


def provenance_rows(prov: Mapping[str, Any], summary: Mapping[str, Any], quick: bool) -> list:
    return [["git commit", f"{prov['git_commit']}" + (" (modified)" if prov["git_dirty"] else "")],
            ["configuration", f"{prov['config_name']} (hash {prov['config_hash']})"
             + (" --quick" if quick else "")],
            ["seeds", ", ".join(f"{k} {v}" for k, v in prov["seeds"].items())],
            ["versions", ", ".join(f"{k} {v}" for k, v in prov["versions"].items())],
            ["platform", f"{prov['platform']}, {prov['cpu_count']} CPU(s)"],
            ["generated", prov["generated"]], ["command", prov["command"]],
            ["summary.json", summary.get("schema_validation", "")]]


def baseline_rows(b: Mapping[str, Any]) -> dict[str, list]:
    def rows(key: str) -> list:
        return [[e["metric"], e["baseline"], e["value"], e.get("delta"), e.get("tolerance"), e["better"],
                 e.get("reason", "")] for e in b[key]]

    return {"regressions": rows("regressions"), "improvements": rows("improvements")}
