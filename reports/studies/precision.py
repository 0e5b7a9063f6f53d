"""Work-precision measurements of every numerical method of the model.

For each component, every method is run over a range of settings (series tolerance or
terms, Newton tolerance or iteration cap, integrator steps or tolerance). A point is the
error (max relative over the sample, against an independent reference) and the run time
(minimum of several runs after a warm-up that includes the JIT compilation). A method that
fails at a setting (an error, a solver status other than OK, a non-finite value) is a
missing point with the reason. The default setting of each component is marked and
checked against the Pareto front.

References: band radiance, the closed form of the tail integral with polylogarithms in
mpmath at 40 digits; electro-thermal solve, ``scipy.optimize.brentq`` per sampled pixel;
transient, ``scipy.integrate.solve_ivp`` (Radau, rtol 1e-12) per sampled pixel.
"""

from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

#: A point dominates another only if it is faster by this factor and more accurate by
#: ERROR_MARGIN: run-time noise on a shared machine must not decide the front.
TIME_MARGIN = 1.5
ERROR_MARGIN = 4.0
#: Errors below this are "exact to double precision" and compare equal.
ERROR_FLOOR = 1e-15


@dataclass
class Point:
    """One measurement: ``error`` and ``time_s`` are None for a failed (missing) point."""

    method: str
    setting_name: str
    setting: float
    error: float | None
    time_s: float | None
    work: float | None = None
    reason: str | None = None
    default: bool = False
    on_front: bool | None = None


@contextlib.contextmanager
def single_thread() -> Iterator[None]:
    """Time on one numba thread: on a shared machine, waiting for a second busy core
    would dominate the small problems and make the timings noise."""
    import numba

    old = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        yield
    finally:
        numba.set_num_threads(old)


def best_time(fn: Callable[[], Any], repeats: int) -> float:
    """Minimum wall time of ``repeats`` calls of ``fn`` after one warm-up call, s."""
    fn()
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def dominates(p: Point, q: Point) -> bool:
    """True if ``p`` is clearly both faster and more accurate than ``q``."""
    if p.error is None or q.error is None or p.time_s is None or q.time_s is None:
        return False
    ep = max(p.error, ERROR_FLOOR)
    eq = max(q.error, ERROR_FLOOR)
    return p.time_s * TIME_MARGIN <= q.time_s and ep * ERROR_MARGIN <= eq


def mark_front(points: list[Point]) -> None:
    """Set ``on_front`` of every measured point (None for missing points)."""
    for q in points:
        q.on_front = None if q.error is None else not any(dominates(p, q) for p in points)


Runner = tuple[Callable[[], Any], Callable[[Any], tuple[float, float]]]


def _measure(points: list[Point], method: str, name: str, setting: float, runner: Runner,
             repeats: int, default: bool = False) -> None:
    """``runner = (call, evaluate)``: ``evaluate(call())`` gives (error, work) or raises
    :class:`SettingFailed`; only ``call`` is timed."""
    call, evaluate = runner
    try:
        err, work = evaluate(call())
        if not math.isfinite(err):
            raise FloatingPointError("non-finite result")
        t = best_time(call, repeats)
        points.append(Point(method, name, setting, float(err), t, work, None, default))
    except Exception as exc:  # a failing setting is a missing point, with its reason
        points.append(Point(method, name, setting, None, None, None,
                            f"{type(exc).__name__}: {exc}"[:300], default))


class SettingFailed(RuntimeError):
    """A method did not deliver a result at this setting (the reason is the message)."""


def _component(name: str, title: str, problem: str, reference: str, metric: str,
               points: list[Point], default: dict[str, Any]) -> dict[str, Any]:
    mark_front(points)
    d = [p for p in points if p.default]
    return {
        "name": name,
        "title": title,
        "problem": problem,
        "reference": reference,
        "error_metric": metric,
        "points": [asdict(p) for p in points],
        "missing": [{"method": p.method, "setting": p.setting, "reason": p.reason}
                    for p in points if p.error is None],
        "default": {**default, "error": d[0].error if d else None,
                    "time_s": d[0].time_s if d else None,
                    "on_pareto_front": bool(d and d[0].on_front)},
    }


# ---- band radiance ---------------------------------------------------------------------

#: Working digits of the mpmath references: 80, so that even a 1 pm band (7 digits lost
#: to cancellation) keeps more than 70.
REFERENCE_DPS = 80


def tail_integral_mp(x: Any, dps: int = REFERENCE_DPS) -> Any:
    """I(x) = int_x^inf t^3/(e^t-1) dt in mpmath, independent of the model's series.

    x >= 1: the tail series sum_n e^(-n x) (x^3/n + 3x^2/n^2 + 6x/n^3 + 6/n^4) summed in
    mpmath (whose exponent range is unbounded, so nothing underflows) until a term is below
    10^-(dps+5) of the sum; x < 1: the polylogarithm closed form
    x^3 Li1(q) + 3x^2 Li2(q) + 6x Li3(q) + 6 Li4(q), q = e^-x (Li1(q) = -log1p(-q)).
    """
    import mpmath as mp

    with mp.workdps(dps):
        xm = mp.mpf(x)
        if xm < 1:
            q = mp.exp(-xm)
            return (-xm**3 * mp.log1p(-q) + 3 * xm**2 * mp.polylog(2, q)
                    + 6 * xm * mp.polylog(3, q) + 6 * mp.polylog(4, q))
        s = mp.mpf(0)
        eps = mp.mpf(10) ** (-(dps + 5))
        n = 1
        while True:
            rn = mp.mpf(1) / n
            t = mp.exp(-n * xm) * rn * (xm**3 + rn * (3 * xm**2 + rn * (6 * xm + 6 * rn)))
            s += t
            if t <= eps * s:
                return s
            n += 1


def band_radiance_mp(T: float, band: tuple[float, float] = (8e-6, 14e-6),
                     dps: int = REFERENCE_DPS, as_mpf: bool = False) -> Any:
    """In-band radiance (W m^-2 sr^-1) of a blackbody at T (K): I(x2) - I(x1) in mpmath.

    Returns a float (0.0 where the radiance is below float64), or the mpf with ``as_mpf``.
    """
    import mpmath as mp
    from irnuc.model.core.constants import C2, RADIANCE_PREFACTOR

    with mp.workdps(dps):
        Tm = mp.mpf(T)
        x1 = mp.mpf(C2) / (mp.mpf(band[0]) * Tm)
        x2 = mp.mpf(C2) / (mp.mpf(band[1]) * Tm)
        val = mp.mpf(RADIANCE_PREFACTOR) * Tm**4 * (tail_integral_mp(x2, dps)
                                                     - tail_integral_mp(x1, dps))
        return val if as_mpf else float(val)


def band_radiance_quad_mp(T: float, band: tuple[float, float] = (8e-6, 14e-6),
                          dps: int = 40) -> Any:
    """Planck's law integrated over the band by mpmath quadrature (a second reference)."""
    import mpmath as mp
    from irnuc.model.core.constants import C2, RADIANCE_PREFACTOR

    with mp.workdps(dps):
        Tm = mp.mpf(T)
        x1 = mp.mpf(C2) / (mp.mpf(band[0]) * Tm)
        x2 = mp.mpf(C2) / (mp.mpf(band[1]) * Tm)
        dx = x1 - x2
        # In u = t - x2 (nodes near the ends keep their digits), on panels doubling in
        # width: e^-t decays over unit lengths when cold.
        pts = [mp.mpf(0)]
        w = mp.mpf(1)
        while pts[-1] + w < dx:
            pts.append(pts[-1] + w)
            w *= 2
        pts.append(dx)
        # Scaled by e^x2: mpmath's quad stops on an absolute error estimate.
        val = mp.quad(lambda u: (x2 + u) ** 3 * mp.exp(-u) / -mp.expm1(-(x2 + u)), pts)
        return mp.mpf(RADIANCE_PREFACTOR) * Tm**4 * mp.exp(-x2) * val


def band_radiance_study(quick: bool = False, repeats: int = 5) -> dict[str, Any]:
    from irnuc.model.radiometry import band_radiance_detailed

    temps = np.geomspace(50.0, 10000.0, 24 if quick else 120)
    ref = np.array([band_radiance_mp(t) for t in temps])
    tiled = np.tile(temps, 20_000 // temps.size)  # time work, not the call overhead
    points: list[Point] = []

    def runner(**kw: Any) -> Runner:
        def evaluate(r: Any) -> tuple[float, float]:
            L = r.radiance[: temps.size]
            return float(np.max(np.abs(L - ref) / ref)), float(r.terms.mean())
        return (lambda: band_radiance_detailed(tiled, **kw)), evaluate

    tols = [1e-3, 1e-6, 1e-9, 1e-12, 1e-15] if quick else [1e-2, 1e-3, 1e-4, 1e-6, 1e-8,
                                                            1e-10, 1e-12, 1e-13, 1e-14, 1e-15]
    for rt in tols:
        _measure(points, "hybrid", "rtol", rt, runner(method="hybrid", rtol=rt), repeats,
                 default=rt == 1e-12)
        _measure(points, "series", "rtol", rt, runner(method="series", rtol=rt), repeats)
    for n in ([5, 20, 100] if quick else [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000]):
        _measure(points, "series (fixed terms)", "n_terms", n,
                 runner(method="series", n_terms=n), repeats)
    return _component(
        "band_radiance", "In-band radiance (8-14 um)",
        f"{temps.size} temperatures log-spaced over 50-10000 K",
        "polylogarithm closed form of the tail integral, mpmath at 40 digits",
        "max relative error of the radiance over the temperatures",
        points, {"method": "hybrid", "setting_name": "rtol", "setting": 1e-12})


# ---- electro-thermal solve ---------------------------------------------------------------

def _electro_problem(quick: bool) -> dict[str, Any]:
    from irnuc.model.core import bolometer as kb

    from irnuc import model

    cfg = model.load_preset("paper", {"fpa.active_rows": 12 if quick else 40,
                                      "fpa.active_cols": 16 if quick else 48,
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


def _brentq_reference(prob: dict[str, Any], idx: np.ndarray) -> np.ndarray:
    from scipy.optimize import brentq

    b = prob["cfg"]["bolometer"]
    B, T_ref, T_s = prob["B"], b["T_ref"], prob["T_s"]
    R = np.broadcast_to(prob["p"]["R_ref"], prob["Q"].shape).ravel()
    a, bb = prob["a"].ravel(), prob["b"].ravel()
    out = np.empty(idx.size)
    for k, i in enumerate(idx):
        ai, bi, Ri = float(a[i]), float(bb[i]), float(R[i])

        def h(x: float, ai: float = ai, bi: float = bi, Ri: float = Ri) -> float:
            return x - ai - bi * Ri * math.exp(B * (1.0 / (T_s + x) - 1.0 / T_ref))

        hi = ai + bi * Ri * math.exp(B * (1.0 / (T_s + ai) - 1.0 / T_ref))
        out[k] = brentq(h, ai, hi, xtol=1e-300, rtol=8.9e-16, maxiter=1000)
    return out


def electro_thermal_study(quick: bool = False, repeats: int = 5) -> dict[str, Any]:
    from irnuc.model.core import bolometer as kb
    from irnuc.model.core import solve32 as k32

    prob = _electro_problem(quick)
    b = prob["cfg"]["bolometer"]
    Q, p = prob["Q"], prob["p"]
    n_all = Q.size
    rng = np.random.default_rng(6)
    idx = np.sort(rng.choice(n_all, size=min(n_all, 60 if quick else 400), replace=False))
    ref = _brentq_reference(prob, idx)
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
                raise SettingFailed(f"{int(bad.sum())} pixel(s) did not converge")
            return float(np.max(np.abs(dT.ravel()[idx] - ref) / np.abs(ref))), float(it.mean())
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
                                    "(tolerance below float32 resolution?)")
            return (float(np.max(np.abs(dT[idx].astype(np.float64) - ref) / np.abs(ref))),
                    float(it.mean()))
        return call, evaluate

    tols = [1e-3, 1e-6, 1e-9, 1e-12, 1e-15] if quick else [1e-2, 1e-3, 1e-4, 1e-6, 1e-8,
                                                            1e-10, 1e-12, 1e-14, 1e-15]
    for rt in tols:
        _measure(points, "newton float64", "rtol", rt, run64(rt, b["max_iter"]), repeats,
                 default=rt == b["rtol"])
        _measure(points, "newton float32", "rtol", rt, run32(rt), repeats)
    for cap in ([2, 4, 8] if quick else [1, 2, 3, 4, 6, 8, 12, 16]):
        _measure(points, "newton float64 (iteration cap)", "max_iter", cap,
                 run64(1e-15, cap, capped=True), repeats)
    return _component(
        "electro_thermal", "Electro-thermal solve (eq. 14-19)",
        f"paper preset, {Q.shape[0]} frames of {Q.shape[1]}x{Q.shape[2]} pixels, "
        "5 % parameter spread",
        f"scipy.optimize.brentq (rtol 8.9e-16) on {idx.size} sampled pixels",
        "max relative error of the temperature rise dT",
        points, {"method": "newton float64", "setting_name": "rtol", "setting": b["rtol"]})


# ---- transient ---------------------------------------------------------------------------

def reference_transient(Q: Sequence[float], T_s: Sequence[float], R_ref: float, g: float,
                        C: float, *, tcr: float, T_ref: float, bias_current: float,
                        t_int: float, frame_period: float, pulse_start: float, theta0: float,
                        rtol: float = 1e-12, method: str = "Radau"
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One pixel's frame sequence by ``scipy.integrate.solve_ivp`` (independent of the
    model's kernels): every segment (relaxation, pulse, relaxation) in scaled time
    s = t / length in [0, 1], with the two pulse integrals as extra states.

    Returns the mean voltage (V), the mean rise and the rise at the end of each pulse (K).
    """
    from irnuc.model.core import bolometer as kb
    from scipy.integrate import solve_ivp

    B = kb.activation_temperature(tcr, T_ref)
    th = float(theta0)
    means_v, means_t, ends = [], [], []

    def segment(th: float, q: float, ts: float, length: float, bias: float) -> np.ndarray:
        if length <= 0.0:
            return np.array([th, 0.0, 0.0])

        def res(theta: float) -> tuple[float, float]:
            T = ts + theta
            R = R_ref * math.exp(B * (1.0 / T - 1.0 / T_ref))
            return R, -B * R / (T * T)

        def f(_: float, y: np.ndarray) -> list[float]:
            R, _ = res(y[0])
            return [length * (bias * bias * R + q - g * y[0]) / C, bias * R, y[0]]

        def jac(_: float, y: np.ndarray) -> list[list[float]]:
            _R, dR = res(y[0])
            return [[length * (bias * bias * dR - g) / C, 0.0, 0.0], [bias * dR, 0.0, 0.0],
                    [1.0, 0.0, 0.0]]

        sol = solve_ivp(f, (0.0, 1.0), [th, 0.0, 0.0], method=method, jac=jac, rtol=rtol,
                        atol=1e-14 * max(1.0, abs(th)))
        if not sol.success:
            raise RuntimeError(f"reference solve_ivp failed: {sol.message}")
        return sol.y[:, -1]

    for n in range(len(Q)):
        if n:
            th += T_s[n - 1] - T_s[n]
        th = segment(th, Q[n], T_s[n], pulse_start, 0.0)[0]
        y = segment(th, Q[n], T_s[n], t_int, bias_current)
        th = y[0]
        means_v.append(y[1])
        means_t.append(y[2])
        ends.append(th)
        th = segment(th, Q[n], T_s[n], frame_period - pulse_start - t_int, 0.0)[0]
    return np.array(means_v), np.array(means_t), np.array(ends)


#: The two transient test problems: the default (realistic, non-stiff: tau = 10 ms, pulse
#: 60 us) and a stiff one (tau = 0.1 us, 600 times shorter than the pulse, self-heating of
#: about 200 K); both with a 300 -> 400 -> 300 K scene step at the frame starts.
TRANSIENT_PROBLEMS: dict[str, dict[str, Any]] = {
    "nonstiff": {},
    "stiff": {"bolometer.C": 1e-12, "bolometer.g": 1e-5, "bolometer.bias_current": 1.5e-4},
}


def transient_problem(kind: str, quick: bool = False) -> dict[str, Any]:
    """Absorbed power, parameters and settings of a transient test problem."""
    from irnuc.model.scenes import Scene
    from irnuc.model.transient import absorbed_power

    from irnuc import model

    ov = {"fpa.active_rows": 6 if quick else 12, "fpa.active_cols": 8 if quick else 16,
          **TRANSIENT_PROBLEMS[kind]}
    cfg = model.load_preset("default", ov)
    temps = np.array([300.0, 400.0, 300.0])
    Ts = np.full(3, cfg["environment"]["T_substrate"])
    Q, static, _ = absorbed_power(cfg, temps, Scene(), 0, Ts)
    return {"cfg": cfg, "Q": Q, "T_s": Ts, "params": static["params"]}


def transient_study(kind: str, quick: bool = False, repeats: int = 3) -> dict[str, Any]:
    from irnuc.model import transient as tr

    prob = transient_problem(kind, quick)
    cfg, Q, Ts, p = prob["cfg"], prob["Q"], prob["T_s"], prob["params"]
    b = cfg["bolometer"]
    rows, cols = Q.shape[1:]
    rng = np.random.default_rng(14)
    pix = [(int(i), int(j)) for i, j in zip(rng.integers(0, rows, 3 if quick else 6),
                                            rng.integers(0, cols, 3 if quick else 6),
                                            strict=True)]
    frame_period = tr.TransientSettings().frame_period
    refs = [reference_transient(Q[:, i, j], Ts, p["R_ref"][i, j], p["g"][i, j], p["C"][i, j],
                                tcr=b["tcr"], T_ref=b["T_ref"], bias_current=b["bias_current"],
                                t_int=b["t_int"], frame_period=frame_period, pulse_start=0.0,
                                theta0=Q[0, i, j] / p["g"][i, j])[0] for i, j in pix]
    budget = 20_000
    points: list[Point] = []

    def runner(**settings: Any) -> Runner:
        def call() -> Any:
            return tr.integrate_pixels(Q, Ts, p["R_ref"], p["g"], p["C"], tcr=b["tcr"],
                                       T_ref=b["T_ref"], bias_current=b["bias_current"],
                                       t_int=b["t_int"],
                                       runaway_temperature=b["runaway_temperature"],
                                       settings={"max_substeps": budget, **settings})

        def evaluate(r: Any) -> tuple[float, float]:
            if (r.status != 0).any():
                raise SettingFailed(f"{int((r.status != 0).sum())} pixel pulse(s) failed "
                                    f"(substep budget {budget} exceeded)")
            err = max(float(np.max(np.abs(r.v_bolo[:, i, j] - rv) / np.abs(rv)))
                      for (i, j), rv in zip(pix, refs, strict=True))
            return err, float(r.substeps.mean())
        return call, evaluate

    steps = [1, 4, 16, 64] if quick else [1, 2, 4, 8, 16, 32, 64, 128, 256]
    tols = [1e-3, 1e-6, 1e-9] if quick else [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9,
                                             1e-10, 1e-11]
    if tr.DEFAULT_RTOL not in tols:
        tols.append(tr.DEFAULT_RTOL)
    for name in tr.INTEGRATORS:
        for n in steps:
            _measure(points, f"{name} (fixed)", "steps", n, runner(integrator=name, steps=n,
                                                                   rtol=None), repeats)
        for rt in tols:
            _measure(points, f"{name} (adaptive)", "rtol", rt,
                     runner(integrator=name, rtol=rt, steps=tr.DEFAULT_STEPS), repeats,
                     default=name == tr.DEFAULT_INTEGRATOR and rt == tr.DEFAULT_RTOL)
    tau = float(np.median(p["C"] / p["g"]))
    return _component(
        f"transient_{kind}", f"Transient integrators, {kind} problem",
        f"default preset{'' if kind == 'nonstiff' else ' with C, g and bias changed'}, "
        f"{rows}x{cols} pixels, 3 frames (scene 300 -> 400 -> 300 K), tau = {tau:.3g} s, "
        f"pulse {b['t_int']:.3g} s (t_int / tau = {b['t_int'] / tau:.3g})",
        f"scipy.integrate.solve_ivp (Radau, rtol 1e-12) on {len(pix)} sampled pixels",
        "max relative error of the pulse-mean bolometer voltage",
        points, {"method": f"{tr.DEFAULT_INTEGRATOR} (adaptive)", "setting_name": "rtol",
                 "setting": tr.DEFAULT_RTOL})


# ---- all ---------------------------------------------------------------------------------

COMPONENTS: dict[str, Callable[..., dict[str, Any]]] = {
    "band_radiance": band_radiance_study,
    "electro_thermal": electro_thermal_study,
    "transient_nonstiff": lambda quick=False, **kw: transient_study("nonstiff", quick, **kw),
    "transient_stiff": lambda quick=False, **kw: transient_study("stiff", quick, **kw),
}


def run_precision(quick: bool = False, components: Sequence[str] | None = None,
                  progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """Every work-precision study; the JSON-ready result of ``irnuc precision``."""
    names = list(components or COMPONENTS)
    unknown = [n for n in names if n not in COMPONENTS]
    if unknown:
        from irnuc.model.validate import ConfigError

        raise ConfigError(f"components: unknown {unknown}; known {sorted(COMPONENTS)}")
    out = []
    repeats = 3 if quick else 5
    with single_thread():
        for k, name in enumerate(names):
            out.append(COMPONENTS[name](quick=quick, repeats=repeats))
            if progress is not None:
                progress(k + 1, len(names))
    return {"version": 1, "quick": quick, "time_margin": TIME_MARGIN,
            "error_margin": ERROR_MARGIN, "threads": 1, "components": out}


def summarize(result: dict[str, Any]) -> dict[str, Any]:
    """The short summary ``irnuc report`` embeds: per component its default, error, time,
    Pareto status and the number of missing points."""
    return {
        "quick": result["quick"],
        "components": [{"name": c["name"], "title": c["title"],
                        "default": c["default"],
                        "points": len(c["points"]),
                        "missing": len(c["missing"])} for c in result["components"]],
        "all_defaults_on_front": all(c["default"]["on_pareto_front"]
                                     for c in result["components"]),
    }
