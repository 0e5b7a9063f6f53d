"""The work-precision studies: one per component (band radiance, the electro-thermal
solve, each transient problem), the component registry and the whole run."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from irnuc.reports.studies.precision.harness import (
    ERROR_MARGIN,
    TIME_MARGIN,
    TRANSIENT_BUDGET,
    Point,
    Runner,
    SettingFailed,
    component,
    measure,
    rel_error_dd,
    single_thread,
)
from irnuc.reports.studies.precision.references import (
    REFERENCE_DPS,
    mp_root_reference,
    radiance_reference,
    reference_transient_exact,
)


def _radiance_component(name: str, title: str, band: tuple[float, float], quick: bool,
                        repeats: int) -> dict[str, Any]:
    from irnuc.model.radiometry import band_radiance_detailed

    start = time.perf_counter()
    temps = np.geomspace(20.0, 10000.0, 16 if quick else 48)
    ref, ref_err = radiance_reference(temps, band)
    tiled = np.tile(temps, 4000 // temps.size)  # time work, not the call overhead
    points: list[Point] = []

    def runner(**kw: Any) -> Runner:
        def evaluate(r: Any) -> tuple[float, float]:
            L = r.radiance[: temps.size]
            return float(np.max(rel_error_dd(L, ref))), float(r.terms.mean())
        return (lambda: band_radiance_detailed(tiled, band, **kw)), evaluate

    tols = [1e-3, 1e-6, 1e-9, 1e-12, 1e-15] if quick else [1e-2, 1e-3, 1e-4, 1e-6, 1e-8,
                                                            1e-10, 1e-12, 1e-13, 1e-14, 1e-15]
    for rt in tols:
        measure(points, "hybrid", "rtol", rt, runner(method="hybrid", rtol=rt), repeats,
                 default=rt == 1e-12)
        measure(points, "series", "rtol", rt, runner(method="series", rtol=rt), repeats)
    for n in ([5, 20, 100] if quick else [1, 2, 5, 10, 20, 50, 100, 200, 500]):
        measure(points, "series (fixed terms)", "n_terms", n,
                 runner(method="series", n_terms=n), repeats)
    return component(
        name, title, f"{temps.size} temperatures log-spaced over 20-10000 K",
        f"tail series in mpmath at {REFERENCE_DPS} digits (double-double)", ref_err,
        "max relative error of the radiance over the temperatures",
        "series terms (or quadrature nodes) per temperature",
        points, {"method": "hybrid", "setting_name": "rtol", "setting": 1e-12},
        time.perf_counter() - start)


def band_radiance_study(quick: bool = False, repeats: int = 3) -> dict[str, Any]:
    """The LWIR band (8-14 um)."""
    return _radiance_component("band_radiance", "In-band radiance (8-14 um)", (8e-6, 14e-6),
                               quick, repeats)


#: The narrow band of the study: 8 um +- 1 pm (the paper's difference of tails cancels).
NARROW_BAND = (8e-6 - 1e-12, 8e-6 + 1e-12)


def band_radiance_narrow_study(quick: bool = False, repeats: int = 3) -> dict[str, Any]:
    """A 2 pm wide band at 8 um."""
    return _radiance_component("band_radiance_narrow", "In-band radiance, 8 um +- 1 pm",
                               NARROW_BAND, quick, repeats)


# ---- electro-thermal solve ---------------------------------------------------------------

def electro_problem(quick: bool) -> dict[str, Any]:
    from irnuc import model
    from irnuc.model.core import bolometer as kb

    cfg = model.load_preset("paper", {"fpa.active_rows": 12 if quick else 32,
                                      "fpa.active_cols": 16 if quick else 40,
                                      "fpa.tolerance": {"R_ref": 0.05, "g": 0.05, "C": 0.05}})
    pipe = model.Pipeline(cfg, 0)
    got = pipe.run(np.array([300.0, 400.0]), ["Q", "params"])
    b = cfg["bolometer"]
    p = got["params"]
    B = kb.activation_temperature(b["tcr"], b["T_ref"])
    Q = np.ascontiguousarray(got["Q"])
    f = np.vectorize(kb.self_heating_factor)(b["t_int"] * p["g"] / p["C"])
    fq = f if b["variant"] == "paper" else 1.0
    a = Q * fq / p["g"]
    bb = np.broadcast_to(b["bias_current"] ** 2 * f / p["g"], Q.shape)
    return {"cfg": cfg, "Q": Q, "p": p, "B": B, "a": a, "b": np.ascontiguousarray(bb),
            "T_s": cfg["environment"]["T_substrate"]}



def electro_thermal_study(quick: bool = False, repeats: int = 3) -> dict[str, Any]:
    from irnuc.model.core import bolometer as kb
    from irnuc.model.core import solve32 as k32

    start = time.perf_counter()
    prob = electro_problem(quick)
    b = prob["cfg"]["bolometer"]
    Q, p = prob["Q"], prob["p"]
    n_all = Q.size
    rng = np.random.default_rng(6)
    idx = np.sort(rng.choice(n_all, size=min(n_all, 60 if quick else 200), replace=False))
    ref, ref_err = mp_root_reference(prob, idx)
    points: list[Point] = []

    def run64(rtol: float, max_iter: int, capped: bool = False) -> Runner:
        def call() -> tuple[np.ndarray, ...]:
            dT = np.empty(Q.shape)
            v = np.empty(Q.shape)
            st = np.empty(Q.shape, np.uint8)
            it = np.empty(Q.shape, np.int32)
            kb.solve_frames(Q, p["R_ref"], p["g"], p["C"], prob["B"], b["T_ref"], prob["T_s"],
                            b["bias_current"], b["t_int"], 1 if b["variant"] == "paper" else 0,
                            rtol, max_iter, b["runaway_temperature"], dT, v, st, it)
            return dT, st, it

        def evaluate(r: tuple[np.ndarray, ...]) -> tuple[float, float]:
            dT, st, it = r
            # With an iteration cap the result after max_iter iterations is the point.
            bad = (st != 0) & ~(capped & (st == kb.STATUS_NO_CONVERGENCE))
            if bad.any():
                raise SettingFailed(f"{int(bad.sum())} pixel(s) did not converge",
                                    float(it.mean()))
            return float(np.max(rel_error_dd(dT.ravel()[idx], ref))), float(it.mean())
        return call, evaluate

    a32 = prob["a"].ravel().astype(np.float32)
    b32 = prob["b"].ravel().astype(np.float32)
    R32 = np.broadcast_to(p["R_ref"], Q.shape).ravel().astype(np.float32)

    def run32(rtol: float) -> Runner:
        def call() -> tuple[np.ndarray, ...]:
            dT = np.empty(a32.shape, np.float32)
            st = np.empty(a32.shape, np.uint8)
            it = np.empty(a32.shape, np.int32)
            k32.solve_flat32(a32, b32, R32, np.float32(prob["B"]), np.float32(b["T_ref"]),
                             np.float32(prob["T_s"]), np.float32(rtol), 100, dT, st, it)
            return dT, st, it

        def evaluate(r: tuple[np.ndarray, ...]) -> tuple[float, float]:
            dT, st, it = r
            if (st != 0).any():
                raise SettingFailed(f"{int((st != 0).sum())} pixel(s) did not converge "
                                    "(tolerance below float32 resolution?)", float(it.mean()))
            return (float(np.max(rel_error_dd(dT[idx].astype(np.float64), ref))),
                    float(it.mean()))
        return call, evaluate

    tols = [1e-3, 1e-6, 1e-9, 1e-12, 1e-15] if quick else [1e-2, 1e-3, 1e-4, 1e-6, 1e-8,
                                                            1e-10, 1e-12, 1e-14, 1e-15]
    for rt in tols:
        measure(points, "newton float64", "rtol", rt, run64(rt, b["max_iter"]), repeats,
                 default=rt == b["rtol"])
        measure(points, "newton float32", "rtol", rt, run32(rt), repeats)
    for cap in ([2, 4, 8] if quick else [1, 2, 3, 4, 6, 8, 12, 16]):
        measure(points, "newton float64 (iteration cap)", "max_iter", cap,
                 run64(1e-15, cap, capped=True), repeats)
    return component(
        "electro_thermal", "Electro-thermal solve (eq. 14-19)",
        f"paper preset, {Q.shape[0]} frames of {Q.shape[1]}x{Q.shape[2]} pixels, "
        "5 % parameter spread",
        f"mpmath findroot at 40 digits on {idx.size} sampled pixels (double-double)", ref_err,
        "max relative error of the temperature rise dT", "Newton iterations per pixel",
        points, {"method": "newton float64", "setting_name": "rtol", "setting": b["rtol"]},
        time.perf_counter() - start)


#: The transient test problems: the default preset (realistic, non-stiff: tau = 10 ms,
#: pulse 60 us) and the stiff set, all with a 300 -> 400 -> 300 K scene step at the frame
#: starts. Stiffness = pulse length times the decay rate |df/dtheta| including the
#: self-heating, at the end of the pulse (reported per problem): about 1e3, 1e5, 1e6 and
#: 1e7 for C = 1e-12 ... 1e-16 J/K with g = 1e-5 W/K and 150 uA of bias (~60 K of
#: self-heating); ``stiff_ptcr`` is a positive-TCR pixel at an electro-thermal loop gain of
#: about 0.8 (close to runaway).
TRANSIENT_PROBLEMS: dict[str, dict[str, Any]] = {
    "nonstiff": {},
    "stiff_1e3": {"bolometer.C": 1e-12, "bolometer.g": 1e-5, "bolometer.bias_current": 1.5e-4},
    "stiff_1e5": {"bolometer.C": 1e-14, "bolometer.g": 1e-5, "bolometer.bias_current": 1.5e-4},
    "stiff_1e6": {"bolometer.C": 1e-15, "bolometer.g": 1e-5, "bolometer.bias_current": 1.5e-4},
    "stiff_1e7": {"bolometer.C": 1e-16, "bolometer.g": 1e-5, "bolometer.bias_current": 1.5e-4},
    "stiff_ptcr": {"bolometer.tcr": 0.02, "bolometer.C": 1e-14, "bolometer.g": 1e-5,
                   "bolometer.bias_current": math.sqrt(21.0 * 1e-5 / 1e5),
                   "fpa.tolerance": {"R_ref": 0.002, "g": 0.002, "C": 0.002}},
}
#: Old name of the first stiff problem (tau = 0.1 us, stiffness ~1e3).
TRANSIENT_PROBLEMS["stiff"] = TRANSIENT_PROBLEMS["stiff_1e3"]


def transient_problem(kind: str) -> dict[str, Any]:
    """Absorbed power, parameters and settings of a transient test problem."""
    from irnuc import model
    from irnuc.model.scenes import Scene
    from irnuc.model.transient import absorbed_power

    ov = {"fpa.active_rows": 4, "fpa.active_cols": 6,
          **TRANSIENT_PROBLEMS[kind]}
    cfg = model.load_preset("default", ov)
    temps = np.array([300.0, 400.0, 300.0])
    Ts = np.full(3, cfg["environment"]["T_substrate"])
    Q, static = absorbed_power(cfg, temps, Scene(), 0, Ts)
    return {"cfg": cfg, "Q": Q, "T_s": Ts, "params": static["params"]}


def _stiffness(prob: dict[str, Any], pix: Sequence[tuple[int, int]],
               ends: Sequence[np.ndarray]) -> float:
    """max over the sampled pixels of t_int |df/dtheta| at the end of the pulses."""
    b = prob["cfg"]["bolometer"]
    p = prob["params"]
    B = -b["tcr"] * b["T_ref"] ** 2
    worst = 0.0
    for (i, j), e in zip(pix, ends, strict=True):
        for k, th in enumerate(e):
            T = prob["T_s"][k] + th
            R = p["R_ref"][i, j] * math.exp(B * (1 / T - 1 / b["T_ref"]))
            lam = abs((b["bias_current"] ** 2 * (-B * R / T**2) - p["g"][i, j]) / p["C"][i, j])
            worst = max(worst, b["t_int"] * lam)
    return worst


def transient_study(kind: str, quick: bool = False, repeats: int = 3) -> dict[str, Any]:
    from irnuc.model import transient as tr

    start = time.perf_counter()
    prob = transient_problem(kind)
    cfg, Q, Ts, p = prob["cfg"], prob["Q"], prob["T_s"], prob["params"]
    b = cfg["bolometer"]
    rows, cols = Q.shape[1:]
    rng = np.random.default_rng(14)
    n_ref = 2 if quick else 4
    pix = [(int(i), int(j)) for i, j in zip(rng.integers(0, rows, n_ref),
                                            rng.integers(0, cols, n_ref), strict=True)]
    frame_period = tr.TransientSettings().frame_period
    kw = dict(tcr=b["tcr"], T_ref=b["T_ref"], bias_current=b["bias_current"], t_int=b["t_int"],
              frame_period=frame_period, pulse_start=0.0)
    refs, ends, ref_err = [], [], 0.0
    for i, j in pix:
        v, _m, e, est = reference_transient_exact(Q[:, i, j], Ts, p["R_ref"][i, j],
                                                  p["g"][i, j], p["C"][i, j],
                                                  theta0=Q[0, i, j] / p["g"][i, j], **kw)
        refs.append(v)
        ends.append(e[0])
        ref_err = max(ref_err, est)
    # The reference's own error: the first pixel again at 45 instead of 60 digits.
    i, j = pix[0]
    low = reference_transient_exact(Q[:, i, j], Ts, p["R_ref"][i, j], p["g"][i, j],
                                    p["C"][i, j], theta0=Q[0, i, j] / p["g"][i, j], dps=45,
                                    **kw)[0]
    # Floor: what a double-double pair resolves.
    ref_err = max(ref_err, float(np.max(np.abs((low[0] - refs[0][0]) + (low[1] - refs[0][1]))
                                        / refs[0][0])), 1e-32)
    stiffness = _stiffness(prob, pix, ends)
    points: list[Point] = []

    def runner(**settings: Any) -> Runner:
        def call() -> Any:
            return tr.integrate_pixels(Q, Ts, p["R_ref"], p["g"], p["C"], tcr=b["tcr"],
                                       T_ref=b["T_ref"], bias_current=b["bias_current"],
                                       t_int=b["t_int"],
                                       runaway_temperature=b["runaway_temperature"],
                                       settings={"max_substeps": TRANSIENT_BUDGET,
                                                 **settings})

        def evaluate(r: Any) -> tuple[float, float]:
            if (r.status != 0).any():
                raise SettingFailed(f"{int((r.status != 0).sum())} pixel pulse(s) failed "
                                    f"(substep budget {TRANSIENT_BUDGET} exceeded)",
                                    float(r.substeps.mean()))
            err = max(float(np.max(rel_error_dd(r.v_bolo[:, i, j], rv)))
                      for (i, j), rv in zip(pix, refs, strict=True))
            return err, float(r.substeps.mean())
        return call, evaluate

    steps = [4, 64, 1024] if quick else [2, 8, 32, 128, 512, 2048]
    tols = [1e-5, 1e-7, 1e-9, 1e-11] if quick else [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9,
                                                    1e-10, 1e-11, 1e-12]
    if tr.DEFAULT_RTOL not in tols:
        tols.append(tr.DEFAULT_RTOL)
    for name in tr.INTEGRATORS:
        if name != "auto":
            for n in steps:
                measure(points, f"{name} (fixed)", "steps", n,
                         runner(integrator=name, steps=n, rtol=None), repeats)
        for rt in tols:
            measure(points, f"{name} (adaptive)", "rtol", rt,
                     runner(integrator=name, rtol=rt, steps=tr.DEFAULT_STEPS), repeats,
                     default=name == tr.DEFAULT_INTEGRATOR and rt == tr.DEFAULT_RTOL)
    tau = float(np.median(p["C"] / p["g"]))
    return component(
        f"transient_{kind}", f"Transient integrators, {kind} (stiffness {stiffness:.2g})",
        f"default preset{'' if kind == 'nonstiff' else ' with ' + _overrides(kind)}, "
        f"{rows}x{cols} pixels, 3 frames (scene 300 -> 400 -> 300 K), tau = {tau:.3g} s, "
        f"pulse {b['t_int']:.3g} s, stiffness t_int |df/dtheta| = {stiffness:.3g}",
        f"phase-variable quadrature in mpmath at 60 digits on {len(pix)} sampled pixels "
        "(double-double)", ref_err,
        "max relative error of the pulse-mean bolometer voltage", "substeps per pulse",
        points, {"method": f"{tr.DEFAULT_INTEGRATOR} (adaptive)", "setting_name": "rtol",
                 "setting": tr.DEFAULT_RTOL}, time.perf_counter() - start,
        stiffness=stiffness)


def _overrides(kind: str) -> str:
    parts = []
    for k, v in TRANSIENT_PROBLEMS[kind].items():
        if isinstance(v, dict):
            continue
        parts.append(f"{k.split('.')[-1]} = {v:.3g}")
    return ", ".join(parts)


# ---- all ---------------------------------------------------------------------------------

def _transient(kind: str) -> Callable[..., dict[str, Any]]:
    def study(quick: bool = False, **kw: Any) -> dict[str, Any]:
        return transient_study(kind, quick, **kw)
    return study


COMPONENTS: dict[str, Callable[..., dict[str, Any]]] = {
    "band_radiance": band_radiance_study,
    "band_radiance_narrow": band_radiance_narrow_study,
    "electro_thermal": electro_thermal_study,
    **{f"transient_{k}": _transient(k) for k in TRANSIENT_PROBLEMS if k != "stiff"},
}
#: Names that stand for several components (``--only transient_stiff``).
GROUPS: dict[str, list[str]] = {
    "transient_stiff": [f"transient_{k}" for k in TRANSIENT_PROBLEMS
                        if k.startswith("stiff_")],
    "transient": [f"transient_{k}" for k in TRANSIENT_PROBLEMS if k != "stiff"],
    "radiance": ["band_radiance", "band_radiance_narrow"],
}


def component_names(components: Sequence[str] | None = None) -> list[str]:
    """Component names with groups expanded, in study order; ConfigError if unknown."""
    if not components:
        return list(COMPONENTS)
    names: list[str] = []
    for c in components:
        if c in GROUPS:
            names += GROUPS[c]
        elif c in COMPONENTS:
            names.append(c)
        else:
            from irnuc.model.validate import ConfigError

            raise ConfigError(f"components: unknown {c!r}; known {sorted(COMPONENTS)} and "
                              f"groups {sorted(GROUPS)}")
    return list(dict.fromkeys(names))


def run_precision(quick: bool = False, components: Sequence[str] | None = None,
                  progress: Callable[[int, int], None] | None = None,
                  repeats: int | None = None) -> dict[str, Any]:
    """Every work-precision study (or ``components``, names or groups); JSON-ready.

    Returns ``{"version": 2, "quick", "time_margin", "error_margin", "threads": 1,
    "seconds", "components": [...]}``; each component has its points (error, time_s,
    work, failed, reason, default, on_front, on_front_work), ``missing`` (the failed
    settings with their reasons), ``default`` (its point and whether it is on the front),
    ``reference`` and ``reference_error`` (the reference's own error estimate).
    """
    names = component_names(components)
    out = []
    reps = repeats if repeats is not None else (2 if quick else 3)
    start = time.perf_counter()
    with single_thread():
        for k, name in enumerate(names):
            out.append(COMPONENTS[name](quick=quick, repeats=reps))
            if progress is not None:
                progress(k + 1, len(names))
    return {"version": 2, "quick": quick, "time_margin": TIME_MARGIN,
            "error_margin": ERROR_MARGIN, "threads": 1,
            "seconds": time.perf_counter() - start, "components": out}


def summarize(result: dict[str, Any]) -> dict[str, Any]:
    """Compact metrics for ``irnuc report``: per component (by name) the default's error,
    time, work and front status, the number of points and failed points, the reference's
    error estimate; and whether every default is on its front."""
    comps = {}
    for c in result["components"]:
        d = c["default"]
        comps[c["name"]] = {
            "default_error": d["error"], "default_time_s": d["time_s"],
            "default_work": d["work"], "default_failed": d["failed"],
            "default_on_front": d["on_pareto_front"],
            "default_on_front_work": d["on_front_work"],
            "points": len(c["points"]), "failed_points": len(c["missing"]),
            "reference_error": c["reference_error"],
        }
    return {
        "quick": result["quick"],
        "seconds": result.get("seconds"),
        "components": comps,
        "all_defaults_on_front": all(v["default_on_front"] for v in comps.values()),
        "all_defaults_on_front_work": all(v["default_on_front_work"] for v in comps.values()),
    }
