"""Study: residual against coefficient fraction bits for every method (the paper's Table 2).

For f = 3..16 every fraction width of a method (gain, offset and every format in
``formats``) is set to f, integer widths as shipped; the method is calibrated on one plan
(the frames simulated once) and corrects uniform scenes between the calibration scenes
at the plan's FPA temperatures. Per method and f: the residual non-uniformity (spatial std
over mean, the paper's measure) at the reference FPA temperature (the paper's table is at
one temperature) and over every FPA point, the worst fixed pattern in LSB and mK, and the
same for the float fit (the floor fraction bits cannot go below: the unquantized
coefficients, given the quantized ones they depend on).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from irnuc.reports.studies.drift_common import (
    PLAN,
    StudySensor,
    pyplot,
    residuals,
    scale,
    slope_frames,
)

NAME = "method_bits"
TITLE = "Residual against fraction bits per method (the paper's Table 2 for every method)"
METHODS = ("onepoint14", "typical14", "piecewise14", "quadratic14", "tcoffset14", "tcgain14",
           "table14")


def with_frac_bits(cfg: Any, f: int) -> Any:
    """``cfg`` with every coefficient's fraction width set to ``f`` (None if illegal)."""
    from irnuc.common.errors import UserError

    try:
        return cfg.replace(gain_frac_bits=f, offset_frac_bits=f,
                           formats={x.name: {"frac_bits": f} for x in cfg.formats})
    except UserError:
        return None


#: Per coefficient of a temperature polynomial: the reading whose range it spans (``ts``:
#: the FPA reading's ``reading_range_bits``, ``hs``: the housing's ``housing_range_bits``)
#: and the power of it (the integer bits it gains per bit of range: v = u / 2^Ts halves as
#: Ts grows by one, so a coefficient per unit v doubles, its square term quadruples).
RANGE_GROWTH = {"tc1": {"ts": 1}, "tc2": {"ts": 2}, "tg1": {"ts": 1}, "tg2": {"ts": 2},
                "th1": {"hs": 1}, "thx": {"ts": 1, "hs": 1}, "th2": {"hs": 2}}


def range_bits_for(span_codes: float) -> int:
    """Bits of a reading's range that hold +-``span_codes`` around its reference (the clamp
    at 2^bits - 1 codes)."""
    return int(np.ceil(np.log2(float(span_codes) + 2.0)))


def with_range_bits(cfg: Any, reading_range_bits: int | None = None,
                    housing_range_bits: int | None = None) -> Any:
    """``cfg`` with its FPA (housing) reading's range widened to at least
    ``reading_range_bits`` (``housing_range_bits``) and each temperature-polynomial
    coefficient's integer bits grown with it (:data:`RANGE_GROWTH`); a range already as
    wide, or a method that does not read that sensor, is left as shipped (never
    narrowed)."""
    grow = {}
    ch: dict[str, Any] = {}
    for key, tag, want in (("reading_range_bits", "ts", reading_range_bits),
                           ("housing_range_bits", "hs", housing_range_bits)):
        have = getattr(cfg, key)
        if want is None or have is None or int(want) <= int(have):
            continue
        grow[tag] = int(want) - int(have)
        ch[key] = int(want)
    if not ch:
        return cfg
    fm = {}
    for f in cfg.formats:
        extra = sum(k * grow.get(tag, 0) for tag, k in RANGE_GROWTH.get(f.name, {}).items())
        if extra:
            fm[f.name] = {"int_bits": f.int_bits + extra}
    return cfg.replace(**ch, formats=fm)


def run(quick: bool = False, sensor: StudySensor | None = None,
        frac_bits: tuple[int, ...] | None = None, names: tuple[str, ...] = METHODS,
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The table of residual against fraction bits (JSON-ready)."""
    import time

    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.fit import calibrate_points, float_correct
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan

    t0 = time.perf_counter()
    sensor = sensor or StudySensor(rows=24 if quick else 48, cols=32 if quick else 64)
    bits = frac_bits or ((4, 8, 12, 16) if quick else tuple(range(3, 17)))
    plan = CalibrationPlan(scene=tuple(PLAN["scene"]), fpa=tuple(PLAN["fpa"]),
                           frames=int(PLAN["frames"]))
    pts = run_plan(plan, sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    scenes = (310.0, 350.0)
    evals = []
    for tf in plan.fpa:
        raw, blind = slope_frames(sensor, tf, tf, scenes)
        evals.append((tf, raw, blind, int(plan.fpa_sensor.read(tf)[0])))
    table: dict[str, Any] = {}
    total = len(names) * len(bits)
    done = 0
    for name in names:
        base = load_pipeline(name)
        rows = []
        floor = None
        for f in bits:
            cfg = with_frac_bits(base, f)
            rec: dict[str, Any] = {"frac_bits": f, "valid": cfg is not None}
            if cfg is not None:
                cal = calibrate_points(pts, cfg, max_saturated=1.0)
                good = ~cal.bad
                sc = scale(sensor, cal.targets, plan.scene)
                worst = {"nu": 0.0, "lsb": 0.0, "mk": 0.0, "float": 0.0, "nu_ref": 0.0,
                         "mk_ref": 0.0}
                for tf, raw, blind, rd in evals:
                    y = method_top(raw, cal.coeffs, FrameInputs(
                        reading=np.full(len(raw), rd), blind_codes=blind)).y
                    yf = np.stack([float_correct(cal, r.astype(np.float64), rd) for r in raw])
                    res, resf = residuals(y, good, scenes, sc), residuals(yf, good, scenes, sc)
                    for k in range(len(scenes)):
                        v = res[k]["fpn_lsb"]
                        nu = v / float(y[3 * k][good].mean())
                        mk = res[k]["fpn_mK"]
                        vals = {"nu": nu, "lsb": v, "mk": mk, "float": resf[k]["fpn_mK"]}
                        if tf == plan.fpa[plan.reference_index]:
                            vals |= {"nu_ref": nu, "mk_ref": mk}
                        worst = {key: max(worst[key], vals.get(key, 0.0)) for key in worst}
                rec |= {"residual_nu": worst["nu"], "worst_fpn_lsb": worst["lsb"],
                        "worst_fpn_mK": worst["mk"], "float_fpn_mK": worst["float"],
                        "reference_fpa_residual_nu": worst["nu_ref"],
                        "reference_fpa_fpn_mK": worst["mk_ref"],
                        "bits_per_pixel": sum(m.word_bits for m in cfg.memories.values()
                                              if m.source == "calibration")}
                floor = worst["float"]  # the fit at the widest valid fractions
            rows.append(rec)
            done += 1
            if progress:
                progress(done, total)
        table[name] = {"method": base.method, "rows": rows, "float_fpn_mK": floor}
    return {
        "study": NAME, "title": TITLE, "quick": quick,
        "sensor": {"preset": str(sensor.preset), "rows": sensor.rows, "cols": sensor.cols,
                   "seed": sensor.seed, "overrides": dict(sensor.overrides)},
        "plan": {k: list(v) if isinstance(v, tuple) else v for k, v in PLAN.items()},
        "eval_scene_K": list(scenes), "eval_fpa_K": list(plan.fpa), "frac_bits": list(bits),
        "methods": table, "seconds": time.perf_counter() - t0,
    }


def figure(result: dict[str, Any]) -> bytes:
    """Worst residual non-uniformity and fixed pattern (mK) against fraction bits."""
    from irnuc.reports.studies.figures import png

    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for i, (name, m) in enumerate(result["methods"].items()):
        rows = [r for r in m["rows"] if r["valid"]]
        f = [r["frac_bits"] for r in rows]
        axes[0].semilogy(f, [r["reference_fpa_residual_nu"] for r in rows], "o-", ms=3,
                         color=f"C{i}", label=name)
        axes[1].semilogy(f, [r["worst_fpn_mK"] for r in rows], "o-", ms=3, color=f"C{i}")
        if m["float_fpn_mK"] is not None:
            axes[1].axhline(m["float_fpn_mK"], color=f"C{i}", ls=":", lw=0.8)
    axes[0].set_ylabel("residual non-uniformity (std / mean), reference FPA")
    axes[1].set_ylabel("worst fixed pattern, all FPA points, mK")
    for ax in axes:
        ax.set_xlabel("fraction bits of every coefficient")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle(f"{TITLE}\n(dotted: the float fit of each method)", fontsize=9)
    return png(fig)
