"""Study: the housing away from the FPA (issue 36).

Every temperature-relevant 14-bit configuration corrects uniform scenes with the FPA at
each of several temperatures and the housing at each offset from it (default -5..+5 K in
1 K steps), calibrated two ways:

* ``housing_at_fpa``: today's plan, the housing at the FPA temperature at every point
  (scenes 290/330/370 K x FPA 288/298/308 K, 2 frames); blind_drift without housing points
  takes the paper repository's coupling k = 1;
* ``over_housing``: the same plan over FPA x housing (``housing_offset = [-5, 0, 5]``, 9
  points) with blind_drift's ``drift_cam`` points at the reference FPA and the same
  offsets. The registry fits every method that does not read the housing on the points
  at the reference offset (0 K), so their coefficients are those of ``housing_at_fpa``
  bit for bit (the study checks it: ``same_coefficients``), except blind_drift's coupling,
  which the housing points measure (k = the image's drift per code of the blind mean).
  tc_housing (tchousing14), which reads the housing sensor, is fitted on all 9 points and
  only here (``same_coefficients`` null).

Per configuration, calibration and housing offset: the worst residual fixed pattern over
the FPA temperatures and scenes (mK through the corrected image's local responsivity) and
the worst level error (mK), :func:`metrics.residuals_mK`. The FFC configurations twice:
the refresh at the same FPA temperature with the housing at the FPA's (then the housing
moves by the offset), and the refresh at the state measured (right after it; the shutter
a blackbody at the housing temperature).

:func:`blind_coupling` is the measurement of issue 36 part 4: how the blind (reference)
pixels follow a housing change against the active pixels, globally and per pixel, and what
a global or a per-pixel coupling leaves.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from irnuc.reports.studies import drift_common as dc

NAME = "housing"
TITLE = "Residual against the housing-FPA difference: every temperature method, two calibrations"
#: The temperature-relevant 14-bit configurations (two_point as the baseline).
METHODS = ("typical14", "drift14", "tcoffset14", "tcgain14", "table14", "ffc14", "tcffc14",
           "tchousing14")
#: The housing offsets of the ``over_housing`` plan, K.
PLAN_OFFSETS = (-5.0, 0.0, 5.0)
CALIBRATIONS = {
    "housing_at_fpa": "plan at housing = FPA (scenes x FPA); blind_drift k = 1",
    "over_housing": "plan over FPA x housing offset -5/0/5 K, fitted at offset 0 (the "
                    "registry's methods); blind_drift k measured over the housing",
}
FFC_AT_FPA = "FFC at housing = FPA"
FFC_HERE = "FFC at this housing"


def _plans(offsets: Sequence[float]) -> dict[str, tuple[dict[str, Any], tuple[float, ...]]]:
    """Each calibration's plan and its drift_cam (housing temperatures at the reference FPA)."""
    ref = dc.PLAN["fpa"][len(dc.PLAN["fpa"]) // 2]
    return {"housing_at_fpa": (dict(dc.PLAN), ()),
            "over_housing": ({**dc.PLAN, "housing_offset": tuple(offsets)},
                             tuple(ref + o for o in offsets if o != 0.0))}


def _json_safe(obj: Any) -> Any:
    """``obj`` with every non-finite float None (a responsivity <= 0 gives an infinite mK:
    strict JSON has no Infinity)."""
    if isinstance(obj, dict):
        return {k: _json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_json_safe(v) for v in obj]
    if isinstance(obj, float) and not np.isfinite(obj):
        return None
    return obj


def _same(a: Any, b: Any) -> bool:
    """Whether two calibrations' coefficients are the same codes (every field, register)."""
    if a.coeffs.registers != b.coeffs.registers:
        return False
    return all(np.array_equal(a.coeffs.fields[m][f], b.coeffs.fields[m][f])
               for m in a.coeffs.fields for f in a.coeffs.fields[m])


def run(quick: bool = False, sensor: dc.StudySensor | None = None,
        offsets: Sequence[float] | None = None, fpa_K: Sequence[float] | None = None,
        scene_K: Sequence[float] | None = None, names: Sequence[str] = METHODS,
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """Worst residual and level error per housing offset, per configuration and
    calibration, and the blind pixels' coupling (JSON-ready)."""
    import time

    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    t0 = time.perf_counter()
    sensor = sensor or dc.StudySensor(rows=24 if quick else 48, cols=32 if quick else 64)
    offs = tuple(float(o) for o in (offsets or ((-5.0, -2.0, 0.0, 2.0, 5.0) if quick
                                                else range(-5, 6))))
    fpa_ref = dc.PLAN["fpa"][len(dc.PLAN["fpa"]) // 2]
    fpa = tuple(float(t) for t in (fpa_K or ((fpa_ref,) if quick else
                                             (288.0, 293.0, 298.0, 303.0, 308.0))))
    scenes = tuple(float(s) for s in (scene_K or ((330.0,) if quick else (290.0, 330.0, 370.0))))
    if 0.0 not in offs or fpa_ref not in fpa:
        raise ValueError(f"the offsets must include 0 K and the FPA temperatures "
                         f"{fpa_ref:g} K (the reference): {offs}, {fpa}")
    from irnuc.nuc_fixed import load_pipeline

    cal_names = tuple(dict.fromkeys((*names, "typical14")))
    # A method that reads the housing (tc_housing) is fitted over FPA x housing only: the
    # plan at housing = FPA has one housing reading per FPA point, nothing to fit w' on.
    reads = {n for n in cal_names if "housing" in load_pipeline(n).base.readings}
    cals = {}
    for key, (plan, drift_cam) in _plans(PLAN_OFFSETS).items():
        these = tuple(n for n in cal_names if key == "over_housing" or n not in reads)
        cals[key] = dc.calibrate_methods(sensor, these, plan, drift_cam=drift_cam)
    plan0 = cals["housing_at_fpa"]["plan"]
    good = ~np.logical_or.reduce([c.bad for k in cals for c in cals[k]["cal"].values()])
    states = [(f, o) for f in fpa for o in offs]
    frames: dict[tuple[float, float], tuple[np.ndarray, np.ndarray, int, int]] = {}
    for i, (f, o) in enumerate(states):
        raw, blind = dc.slope_frames(sensor, f, f + o, scenes)
        frames[(f, o)] = (raw, blind, int(plan0.fpa_sensor.read(f)[0]),
                          int(plan0.housing_sensor.read(f + o)[0]))
        if progress:
            progress(i + 1, len(states))
    shutters: dict[tuple[float, float, int], np.ndarray] = {}

    def shutter(f: float, o: float, n: int) -> np.ndarray:
        # the shutter: a uniform blackbody at the housing temperature
        if (f, o, n) not in shutters:
            shutters[(f, o, n)] = dc.frames_at(sensor, f, f + o, [f + o], repeats=n)[0]
        return shutters[(f, o, n)]

    def correct(c: Any, f: float, o: float, ffc_at: float | None) -> np.ndarray:
        raw, blind, rd, hr = frames[(f, o)]
        n = len(raw)
        kw = {}
        if ffc_at is not None:
            nf = int(c.cfg.ffc_frames or 1)
            ref = method_top(shutter(f, ffc_at, nf), c.coeffs, FrameInputs(
                reading=np.full(nf, rd), shutter=np.ones(nf, bool)))
            kw["ffc_offset"] = ref.ffc_offset
        return method_top(raw, c.coeffs, FrameInputs(
            reading=np.full(n, rd), blind_codes=blind, shutter=np.zeros(n, bool),
            housing_reading=np.full(n, hr)), **kw).y

    rows: list[dict[str, Any]] = []
    for name in names:
        for key, cal in cals.items():
            if name not in cal["cal"]:
                continue
            c = cal["cal"][name]
            sc = dc.scale(sensor, c.targets, dc.PLAN["scene"])
            variants: list[tuple[str, float | None]] = (
                [(FFC_AT_FPA, 0.0), (FFC_HERE, None)] if c.cfg.has("ffc") else [("", None)])
            for variant, at in variants:
                per_off = []
                for o in offs:
                    per_fpa = []
                    for f in fpa:
                        ffc_at = None if not c.cfg.has("ffc") else (o if at is None else at)
                        res = dc.residuals(correct(c, f, o, ffc_at), good, scenes, sc)
                        per_fpa.append({"fpa_K": f, "fpn_mK": [r["fpn_mK"] for r in res],
                                        "level_error_mK": [r["level_error_mK"] for r in res],
                                        "fpn_lsb": [r["fpn_lsb"] for r in res]})
                    per_off.append(per_fpa)
                rows.append({
                    "config": name, "method": c.cfg.method, "variant": variant,
                    "calibration": key,
                    "same_coefficients": (_same(c, cals["housing_at_fpa"]["cal"][name])
                                          if name in cals["housing_at_fpa"]["cal"] else None),
                    "drift_coupling": c.summary.get("drift_coupling"),
                    "worst_fpn_mK": [max(v for p in po for v in p["fpn_mK"]) for po in per_off],
                    "worst_level_error_mK": [max(abs(v) for p in po for v in p["level_error_mK"])
                                             for po in per_off],
                    "ref_fpn_mK": [max(p["fpn_mK"]) for po in per_off for p in po
                                   if p["fpa_K"] == fpa_ref],
                    "ref_level_error_mK": [max(abs(v) for v in p["level_error_mK"])
                                           for po in per_off for p in po
                                           if p["fpa_K"] == fpa_ref],
                    "per_offset": [{"offset_K": o, "per_fpa": po}
                                   for o, po in zip(offs, per_off, strict=True)]})
    c2 = cals["over_housing"]["cal"]["typical14"]
    ref_frames = {o: frames[(fpa_ref, o)] for o in offs}
    fpa_frames = {d: dc.frames_at(sensor, fpa_ref + d, fpa_ref, [scenes[len(scenes) // 2]])
                  for d in (-2.0, 2.0)}
    blind = blind_coupling(ref_frames, fpa_frames, scenes, good, c2.floats["coeffs.gain"])
    blind["fpa_K"] = fpa_ref
    blind["drift14_fitted_coupling"] = {k: cals[k]["cal"]["drift14"].summary["drift_coupling"]
                                        for k in cals if "drift14" in cals[k]["cal"]}
    nd = dc.netd(sensor, fpa_ref)
    return _json_safe({
        "study": NAME, "title": TITLE, "quick": quick,
        "sensor": {"preset": str(sensor.preset), "rows": sensor.rows, "cols": sensor.cols,
                   "seed": sensor.seed, "overrides": dict(sensor.overrides)},
        "plan": {k: list(v) if isinstance(v, tuple) else v for k, v in dc.PLAN.items()},
        "plan_housing_offset_K": list(PLAN_OFFSETS), "calibrations": CALIBRATIONS,
        "offset_K": list(offs), "fpa_K": list(fpa), "scene_K": list(scenes),
        "good_pixels": int(good.sum()), "bad_pixels": np.argwhere(~good).tolist(),
        "rows": rows, "blind_pixels": blind,
        "netd_mK": nd.netd_K * 1e3, "netd": nd.as_dict(),
        "seconds": time.perf_counter() - t0,
    })


def blind_coupling(ref_frames: dict[float, tuple[np.ndarray, ...]],
                   fpa_frames: dict[float, tuple[np.ndarray, np.ndarray]],
                   scenes: Sequence[float], good: np.ndarray, gain: np.ndarray
                   ) -> dict[str, Any]:
    """How the blind pixels follow the housing against the active pixels (issue 36 part 4).

    Parameters
    ----------
    ref_frames : {offset K: (raw (3 S, H, W), blind (3 S, K), ...)}
        Frames of :func:`drift_common.slope_frames` at the reference FPA temperature with
        the housing at each offset (0 among them).
    fpa_frames : {FPA change K: (raw (1, H, W), blind (1, K))}
        The middle scene with the FPA moved and the housing at the reference.
    scenes : the S scenes, K; good : (H, W) bool; gain : (H, W) the two-point gains
        (output codes per ADC code) that turn a raw code change into the image's.

    The active pixel i drifts by a_i ADC codes per K of housing, the blind pixels by b_j
    (least-squares slopes over the offsets, middle scene). The global coupling is
    k = mean(a) / mean(b) (what blind_drift fits); the per-pixel one k_i = a_i / mean(b).
    The residual pattern each leaves at an offset o and scene s is the spatial std of
    g_i (dA_i - k dB) (dA, dB: the change from offset 0), in mK through the image's local
    responsivity at offset 0 (k_i fitted at the middle scene, used at every scene), and
    the level error its mean leaves. Also k = 1 (the paper repository's; the ring's change
    subtracted whole) and, with it, a global term after the gain (``two_term``: c_out
    output codes per code of the blind mean, fitted at the middle scene; its pattern is
    k = 1's), and a per-pixel word k_i - k of f fraction bits (its width, and the pattern
    at the fit scene and the ends of the offsets).
    """
    from irnuc.reports.studies.metrics import radial_artefact

    offs = np.asarray(sorted(ref_frames), dtype=np.float64)
    mid = len(scenes) // 2
    A = np.stack([ref_frames[o][0] for o in offs]).astype(np.float64)      # (O, 3S, H, W)
    B = np.stack([ref_frames[o][1] for o in offs]).astype(np.float64)      # (O, 3S, K)
    o0 = int(np.flatnonzero(offs == 0.0)[0])
    a = np.polyfit(offs, A[:, 3 * mid][:, good], 1)[0]                       # (G,)
    b = np.polyfit(offs, B[:, 3 * mid], 1)[0]                                # (K,)
    bm = float(b.mean())
    with np.errstate(divide="ignore", invalid="ignore"):  # a ring that ignores the housing
        k = float(np.float64(a.mean()) / bm)
    k_i = np.zeros(good.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        k_i[good] = a / bm
    g = gain[good]
    # k = 1 before the gain and a global term after it, c_out output codes per code of the
    # blind mean (fitted at the middle scene): the pattern of k = 1, the level of the fit
    dA_m = A[:, 3 * mid][:, good] - A[o0, 3 * mid][good]
    dB_m = B[:, 3 * mid].mean(axis=-1) - B[o0, 3 * mid].mean()
    c_out = float(np.polyfit(dB_m, (g * (dA_m - dB_m[:, None])).mean(axis=1), 1)[0])
    per_scene = []
    for s, ts in enumerate(scenes):
        resp = float((g * (A[o0, 3 * s + 2][good] - A[o0, 3 * s + 1][good])).mean())  # /1 K
        rec: dict[str, Any] = {"scene_K": float(ts), "responsivity_codes_per_K": resp}
        cols: dict[str, list[float]] = {k_: [] for k_ in (
            "none_mK", "global_mK", "global_level_mK", "k1_mK", "k1_level_mK",
            "two_term_level_mK", "per_pixel_mK", "per_pixel_level_mK")}
        for i in range(len(offs)):
            dA = A[i, 3 * s][good] - A[o0, 3 * s][good]
            dB = float(B[i, 3 * s].mean() - B[o0, 3 * s].mean())
            for col, e in (("none", g * dA), ("global", g * (dA - k * dB)),
                           ("k1", g * (dA - dB)), ("per_pixel", g * (dA - k_i[good] * dB))):
                cols[f"{col}_mK"].append(1e3 * float(e.std()) / resp)
                if col != "none":
                    cols[f"{col}_level_mK"].append(1e3 * float(e.mean()) / resp)
            cols["two_term_level_mK"].append(
                1e3 * float((g * (dA - dB)).mean() - c_out * dB) / resp)
        per_scene.append({**rec, **cols})
    # a per-pixel word: k_i - k in two's complement with f fraction bits, at the fit scene
    # and the offsets' ends
    words = {}
    ends = [int(np.argmin(offs)), int(np.argmax(offs))]
    dev = k_i[good] - k
    resp_m = per_scene[mid]["responsivity_codes_per_K"]
    for f in (6, 8, 10, 12):
        q = np.round(dev * 2.0**f)
        bits = int(np.ceil(np.log2(max(np.abs(q).max(), 1.0) + 1.0))) + 1
        kq = k + q / 2.0**f
        words[str(f)] = {"bits": bits, "pattern_mK": [
            1e3 * float((g * (A[i, 3 * mid][good] - A[o0, 3 * mid][good]
                              - kq * float(B[i, 3 * mid].mean() - B[o0, 3 * mid].mean()))
                         ).std()) / resp_m for i in ends]}
    # the FPA: the same slopes with the housing held
    d = np.asarray(sorted(fpa_frames), dtype=np.float64)
    af = np.polyfit(d, np.stack([fpa_frames[x][0][0][good] for x in d]).astype(np.float64), 1)[0]
    bf = float(np.polyfit(d, np.stack([fpa_frames[x][1][0] for x in d]).astype(np.float64),
                          1)[0].mean())
    radial = radial_artefact(np.where(good, k_i - k, 0.0), good)
    return {
        "offset_K": offs.tolist(), "fit_scene_K": float(scenes[mid]),
        "blind_pixels": int(B.shape[-1]),
        "housing": {"active_codes_per_K": float(a.mean()), "blind_codes_per_K": bm,
                    "blind_spread_codes_per_K": float(b.std()),
                    "blind_to_active": bm / float(a.mean())},
        "fpa": {"active_codes_per_K": float(af.mean()), "blind_codes_per_K": bf,
                "blind_to_active": bf / float(af.mean())},
        "global_coupling": k, "two_term_output_codes_per_blind_code": c_out,
        "per_pixel_coupling": {"mean": float(k_i[good].mean()), "std": float(k_i[good].std()),
                               "min": float(k_i[good].min()), "max": float(k_i[good].max()),
                               "relative_spread": float(k_i[good].std() / k_i[good].mean()),
                               "radial_rms": radial[0], "radial_fraction": radial[1],
                               "word_by_frac_bits": words},
        "residual": per_scene,
    }


def _pick(offs: Sequence[float]) -> list[int]:
    """Indices of the offsets a text table shows: the ends, their halves and 0."""
    want = [min(offs), min(offs) / 2, 0.0, max(offs) / 2, max(offs)]
    idx = [min(range(len(offs)), key=lambda i: (abs(offs[i] - w), abs(offs[i]))) for w in want]
    return list(dict.fromkeys(idx))


def _f(v: float | None, spec: str = "7.0f") -> str:
    """A number of the table, or a dash where it is undefined (None)."""
    return format(v, spec) if v is not None else format("-", ">" + spec.split(".")[0])


def table(result: dict[str, Any]) -> str:
    """A short text table: worst residual and level error at a few offsets, per row."""
    offs = result["offset_K"]
    idx = _pick(offs)
    head = " ".join(f"{offs[i]:+6g}K" for i in idx)
    s = result["sensor"]
    preset = s["preset"] if s["preset"] in ("default", "paper") else "from a file"
    lines = [result["title"],
             f"sensor {preset} {s['rows']} x {s['cols']}, seed {s['seed']}; FPA "
             f"{', '.join(f'{t:g}' for t in result['fpa_K'])} K; scenes "
             f"{', '.join(f'{t:g}' for t in result['scene_K'])} K; NETD "
             f"{result['netd_mK']:.1f} mK (300 K scene)",
             ]
    ref = result["blind_pixels"]["fpa_K"]
    for what, fk, lk in ((f"worst over FPA {', '.join(f'{t:g}' for t in result['fpa_K'])} K",
                          "worst_fpn_mK", "worst_level_error_mK"),
                         (f"at the reference FPA {ref:g} K", "ref_fpn_mK",
                          "ref_level_error_mK")):
        lines += ["", f"{what} and the scenes: residual fixed pattern, mK | |level error|, "
                  "mK, per housing - FPA",
                  f"{'configuration':40s} {'calibration':15s} {head} | {head}"]
        for r in result["rows"]:
            label = r["config"] + (f" ({r['variant']})" if r["variant"] else "")
            fp = " ".join(_f(r[fk][i]) for i in idx)
            lv = " ".join(_f(r[lk][i]) for i in idx)
            lines.append(f"{label:40s} {r['calibration']:15s} {fp} | {lv}")
    b = result["blind_pixels"]
    h, f, pp = b["housing"], b["fpa"], b["per_pixel_coupling"]
    lines += ["", f"blind pixels ({b['blind_pixels']}), reference FPA, scene "
              f"{b['fit_scene_K']:g} K: housing {_f(h['blind_codes_per_K'], '+.1f')} "
              f"codes/K vs the image's {_f(h['active_codes_per_K'], '+.1f')} (ratio "
              f"{_f(h['blind_to_active'], '.3f')}); FPA {_f(f['blind_codes_per_K'], '+.1f')}"
              f" vs {_f(f['active_codes_per_K'], '+.1f')} (ratio "
              f"{_f(f['blind_to_active'], '.3f')})",
              f"coupling: global {_f(b['global_coupling'], '.3f')}; per pixel "
              f"{_f(pp['mean'], '.3f')} +- {_f(pp['std'], '.3f')} ({_f(pp['min'], '.3f')}.."
              f"{_f(pp['max'], '.3f')}, radial fraction {_f(pp['radial_fraction'], '.2f')})"]
    lines.append("per-pixel word k_i - k: " + "; ".join(
        f"{w['bits']} bits at 2^-{fb}: {_f(w['pattern_mK'][0], '.1f')} / "
        f"{_f(w['pattern_mK'][-1], '.1f')} mK at the offsets' ends"
        for fb, w in pp["word_by_frac_bits"].items()))
    for rec in b["residual"]:
        j = [int(np.argmin([abs(o - offs[i]) for o in b["offset_K"]])) for i in idx]
        lines.append(f"  scene {rec['scene_K']:g} K, housing {head}: pattern mK | level mK")
        for col, what in (("none", "no correction"), ("global", "global k (pattern, level)"),
                          ("k1", "k = 1"), ("per_pixel", "per-pixel k_i")):
            lv = (" | " + " ".join(_f(rec[col + "_level_mK"][i]) for i in j)
                  if col + "_level_mK" in rec else "")
            lines.append(f"    {what:28s}" + " ".join(_f(rec[col + "_mK"][i]) for i in j) + lv)
        lines.append(f"    {'k = 1 + global after gain':28s}" + " ".join(
            _f(rec["k1_mK"][i]) for i in j) + " | " + " ".join(
            _f(rec["two_term_level_mK"][i]) for i in j))
    return "\n".join(lines) + "\n"


def figure(result: dict[str, Any]) -> bytes:
    """Worst residual and level error against the housing offset; solid: calibrated at
    housing = FPA, dashed: over the housing."""
    from irnuc.reports.studies.figures import png

    plt = dc.pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    labels: dict[str, int] = {}
    for r in result["rows"]:
        label = r["config"] + (f" ({r['variant']})" if r["variant"] else "")
        i = labels.setdefault(label, len(labels))
        ls = "-" if r["calibration"] == "housing_at_fpa" else "--"
        kw = {"label": label} if r["calibration"] == "housing_at_fpa" else {}
        fpn, lev = ([np.nan if v is None else v for v in r[k]]
                    for k in ("worst_fpn_mK", "worst_level_error_mK"))
        axes[0].plot(result["offset_K"], fpn, ls, marker="o", ms=2, color=f"C{i % 10}", **kw)
        axes[1].plot(result["offset_K"], np.maximum(lev, 1e-1), ls, marker="o", ms=2,
                     color=f"C{i % 10}")
    axes[0].axhline(result["netd_mK"], color="k", ls=":", lw=1, label="NETD (300 K scene)")
    axes[0].set_ylabel("worst residual fixed pattern, mK")
    axes[1].set_ylabel("worst |level error|, mK")
    for ax in axes:
        ax.set_yscale("log")
        ax.set_xlabel("housing - FPA, K")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6)
    fig.subplots_adjust(top=0.82)
    fig.suptitle(f"{TITLE}\nsolid: calibrated at housing = FPA; dashed: over FPA x housing "
                 f"(fitted at offset 0); worst over FPA "
                 f"{', '.join(f'{t:g}' for t in result['fpa_K'])} K", fontsize=9)
    return png(fig)
