"""Work-precision measurements of every numerical method of the model.

For each component, every method is run over a range of settings (series tolerance or
terms, Newton tolerance or iteration cap, integrator steps or tolerance). A point is the
error (max relative over the sample, against an independent reference), the run time
(minimum of a few runs after a warm-up that includes the JIT compilation) and the work
(series terms, Newton iterations or integrator substeps: a second axis free of timing
noise). A method that fails at a setting (an error, a solver status other than OK, a
non-finite value) is a failed point with its reason and the time it took to fail. The
default setting of each component is marked and checked against the Pareto front.

References, all independent of the code under test and kept as double-double values (a
float64 pair) so that errors far below float64 resolution stay measurable:

* band radiance: the tail series summed in mpmath at 80 digits (no underflow);
* electro-thermal solve: mpmath ``findroot`` at 40 digits per sampled pixel;
* transient: every pulse by quadrature in the phase variable at 60 digits
  (:func:`reference_transient_exact`), the relaxations in closed form. scipy's Radau
  (:func:`reference_transient`) agrees to ~1e-15 and is the tests' second opinion.

Each component reports its reference's own error estimate (the same reference at fewer
digits); it is many orders of magnitude below every plotted error.

Stable API for reports: :func:`run_precision` (JSON-ready dict), :func:`figures`
(caption, PNG bytes) and :func:`summarize` (compact metrics).
"""

from __future__ import annotations

import contextlib
import io
import math
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

#: A point dominates another only if it is faster (or cheaper) by this factor and more
#: accurate by ERROR_MARGIN: run-time noise on a shared machine must not decide the front.
TIME_MARGIN = 1.5
ERROR_MARGIN = 4.0
#: Errors below this are "exact to double precision" and compare equal.
ERROR_FLOOR = 1e-15
#: A timed call is repeated only while the repeats together stay below this, s.
TIME_BUDGET = 0.6
#: Substep budget per pulse and pixel of the transient studies: beyond, a failed point.
TRANSIENT_BUDGET = 10_000


@dataclass
class Point:
    """One measurement.

    ``error`` is None for a failed point (``failed`` set, ``reason`` the message);
    ``time_s`` is then the time the failing call took and ``work`` the work done until it
    failed, when known (None for a refusal before any step).
    """

    method: str
    setting_name: str
    setting: float
    error: float | None
    time_s: float | None
    work: float | None = None
    reason: str | None = None
    default: bool = False
    on_front: bool | None = None
    on_front_work: bool | None = None
    failed: bool = False


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


def best_time(fn: Callable[[], Any], repeats: int, first: float | None = None) -> float:
    """Minimum wall time of up to ``repeats`` calls of ``fn``, s; ``first`` is the time of
    a call already made (the warm-up). Slow calls are not repeated past TIME_BUDGET."""
    best = math.inf if first is None else first
    spent = 0.0 if first is None else first
    for _ in range(repeats):
        if spent > TIME_BUDGET and best < math.inf:
            break
        t0 = time.perf_counter()
        fn()
        dt = time.perf_counter() - t0
        best = min(best, dt)
        spent += dt
    return best


def _dominates(p: Point, q: Point, axis: str) -> bool:
    if p.error is None or q.error is None:
        return False
    cp, cq = (p.time_s, q.time_s) if axis == "time" else (p.work, q.work)
    if cp is None or cq is None:
        return False
    ep = max(p.error, ERROR_FLOOR)
    eq = max(q.error, ERROR_FLOOR)
    return cp * TIME_MARGIN <= cq and ep * ERROR_MARGIN <= eq


def dominates(p: Point, q: Point) -> bool:
    """True if ``p`` is clearly both faster and more accurate than ``q``."""
    return _dominates(p, q, "time")


def mark_front(points: list[Point]) -> None:
    """Set ``on_front`` (by run time) and ``on_front_work`` (by work, among the points of
    the same work unit: the whole component) of every measured point; None if failed."""
    for q in points:
        ok = q.error is not None
        q.on_front = not any(_dominates(p, q, "time") for p in points) if ok else None
        q.on_front_work = (not any(_dominates(p, q, "work") for p in points)
                           if ok and q.work is not None else None)


Runner = tuple[Callable[[], Any], Callable[[Any], tuple[float, float]]]


class SettingFailed(RuntimeError):
    """A method did not deliver a result at this setting (the reason is the message).

    ``work`` is the work done before it failed, when known.
    """

    def __init__(self, message: str, work: float | None = None) -> None:
        super().__init__(message)
        self.work = work


def _measure(points: list[Point], method: str, name: str, setting: float, runner: Runner,
             repeats: int, default: bool = False) -> None:
    """``runner = (call, evaluate)``: ``evaluate(call())`` gives (error, work) or raises
    :class:`SettingFailed`; only ``call`` is timed (the first call is the warm-up)."""
    call, evaluate = runner
    t0 = time.perf_counter()
    try:
        out = call()
        first = time.perf_counter() - t0
        err, work = evaluate(out)
        if not math.isfinite(err):
            raise SettingFailed("non-finite result")
        t = best_time(call, repeats, first if first > TIME_BUDGET else None)
        points.append(Point(method, name, setting, float(err), t, work, None, default))
    except Exception as exc:  # a failing setting is a failed point, with its reason
        spent = time.perf_counter() - t0
        points.append(Point(method, name, setting, None, spent, getattr(exc, "work", None),
                            f"{type(exc).__name__}: {exc}"[:300], default, failed=True))


def _component(name: str, title: str, problem: str, reference: str, reference_error: float,
               metric: str, work_name: str, points: list[Point], default: dict[str, Any],
               seconds: float, **extra: Any) -> dict[str, Any]:
    mark_front(points)
    d = [p for p in points if p.default]
    dp = d[0] if d else None
    return {
        "name": name,
        "title": title,
        "problem": problem,
        "reference": reference,
        "reference_error": reference_error,
        "error_metric": metric,
        "work_name": work_name,
        "points": [asdict(p) for p in points],
        "missing": [{"method": p.method, "setting_name": p.setting_name, "setting": p.setting,
                     "reason": p.reason} for p in points if p.failed],
        "default": {**default,
                    "error": dp.error if dp else None,
                    "time_s": dp.time_s if dp else None,
                    "work": dp.work if dp else None,
                    "failed": bool(dp is None or dp.failed),
                    "reason": dp.reason if dp else "default not measured",
                    "on_pareto_front": bool(dp and dp.on_front),
                    "on_front_work": bool(dp and dp.on_front_work)},
        "seconds": seconds,
        **extra,
    }


def _dd(x: Any) -> tuple[float, float]:
    """An mpf as a double-double pair (hi, lo), hi = float(x), lo = float(x - hi)."""
    hi = float(x)
    return hi, float(x - hi)


def rel_error_dd(got: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """|got - ref| / |ref| for a (2, ...) double-double reference: got - hi is exact when
    the two agree to a factor of 2 (Sterbenz), so errors below 1e-16 stay resolved."""
    hi, lo = ref[0], ref[1]
    return np.abs((got - hi) - lo) / np.abs(hi)


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


def _radiance_reference(temps: np.ndarray, band: tuple[float, float]
                        ) -> tuple[np.ndarray, float]:
    """Double-double references and their error estimate (80 against 60 digits)."""
    ref = np.array([_dd(band_radiance_mp(t, band, as_mpf=True)) for t in temps]).T
    import mpmath as mp

    est = 0.0
    for t in temps[:: max(1, temps.size // 4)]:
        a = band_radiance_mp(t, band, as_mpf=True)
        b = band_radiance_mp(t, band, dps=60, as_mpf=True)
        est = max(est, float(abs((a - b) / a)))
    return ref, max(est, float(mp.mpf(10) ** -REFERENCE_DPS))


def _radiance_component(name: str, title: str, band: tuple[float, float], quick: bool,
                        repeats: int) -> dict[str, Any]:
    from irnuc.model.radiometry import band_radiance_detailed

    start = time.perf_counter()
    temps = np.geomspace(20.0, 10000.0, 16 if quick else 48)
    ref, ref_err = _radiance_reference(temps, band)
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
        _measure(points, "hybrid", "rtol", rt, runner(method="hybrid", rtol=rt), repeats,
                 default=rt == 1e-12)
        _measure(points, "series", "rtol", rt, runner(method="series", rtol=rt), repeats)
    for n in ([5, 20, 100] if quick else [1, 2, 5, 10, 20, 50, 100, 200, 500]):
        _measure(points, "series (fixed terms)", "n_terms", n,
                 runner(method="series", n_terms=n), repeats)
    return _component(
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

def _electro_problem(quick: bool) -> dict[str, Any]:
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


def _brentq_reference(prob: dict[str, Any], idx: np.ndarray) -> np.ndarray:
    """The root per sampled pixel by scipy's brentq (float64; a bracket for mpmath)."""
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


def _mp_reference(prob: dict[str, Any], idx: np.ndarray, dps: int = 40
                  ) -> tuple[np.ndarray, float]:
    """Roots in mpmath (Newton from brentq's root) as double-double pairs, and the error
    estimate from the same roots at dps - 10 digits."""
    import mpmath as mp

    b = prob["cfg"]["bolometer"]
    R = np.broadcast_to(prob["p"]["R_ref"], prob["Q"].shape).ravel()
    a, bb = prob["a"].ravel(), prob["b"].ravel()
    start = _brentq_reference(prob, idx)
    out = np.empty((2, idx.size))
    est = 0.0
    for k, i in enumerate(idx):
        roots = []
        for d in (dps, dps - 10):
            with mp.workdps(d):
                B, T_ref, T_s = (mp.mpf(v) for v in (prob["B"], b["T_ref"], prob["T_s"]))
                ai, bi, Ri = mp.mpf(a[i]), mp.mpf(bb[i]), mp.mpf(R[i])
                roots.append(mp.findroot(
                    lambda x, ai=ai, bi=bi, Ri=Ri, B=B, T_ref=T_ref, T_s=T_s:
                    x - ai - bi * Ri * mp.exp(B * (1 / (T_s + x) - 1 / T_ref)),
                    mp.mpf(start[k])))
        with mp.workdps(dps):
            out[:, k] = _dd(roots[0])
            est = max(est, float(abs((roots[0] - roots[1]) / roots[0])))
    return out, est


def electro_thermal_study(quick: bool = False, repeats: int = 3) -> dict[str, Any]:
    from irnuc.model.core import bolometer as kb
    from irnuc.model.core import solve32 as k32

    start = time.perf_counter()
    prob = _electro_problem(quick)
    b = prob["cfg"]["bolometer"]
    Q, p = prob["Q"], prob["p"]
    n_all = Q.size
    rng = np.random.default_rng(6)
    idx = np.sort(rng.choice(n_all, size=min(n_all, 60 if quick else 200), replace=False))
    ref, ref_err = _mp_reference(prob, idx)
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
        f"mpmath findroot at 40 digits on {idx.size} sampled pixels (double-double)", ref_err,
        "max relative error of the temperature rise dT", "Newton iterations per pixel",
        points, {"method": "newton float64", "setting_name": "rtol", "setting": b["rtol"]},
        time.perf_counter() - start)


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
    from scipy.integrate import solve_ivp

    from irnuc.model.core import bolometer as kb

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


def _pulse_exact_mp(th0: Any, q: Any, ts: Any, I: Any, R_ref: Any, B: Any, T_ref: Any, g: Any,
                    C: Any, t_int: Any) -> tuple[Any, Any, Any, Any]:
    """One bias pulse of the autonomous heat balance theta' = f(theta) in mpmath.

    theta moves monotonically from th0 towards the nearest root theta* of f in the
    direction of f(th0). With u = |theta* - theta| and w = ln u, dt = -(u / |f|) dw, whose
    integrand tends to 1 / |f'(theta*)| as u -> 0: smooth, however stiff the pixel. So
    t_int = int_{w_end}^{w0} u/|f| dw fixes w_end (a root in w), and the pulse integrals are
    int V dt = int I R(theta(w)) u/|f| dw and int theta dt = int theta(w) u/|f| dw.

    Returns (theta_end, int V dt, int theta dt, error estimate): the estimate is the sum of
    mpmath's quadrature error estimates relative to the integrals.
    """
    import mpmath as mp

    def R(th: Any) -> Any:
        return R_ref * mp.exp(B * (1 / (ts + th) - 1 / T_ref))

    def f(th: Any) -> Any:
        return (I * I * R(th) + q - g * th) / C

    f0 = f(th0)
    if f0 == 0:
        return th0, I * R(th0) * t_int, th0 * t_int, mp.mpf(0)
    sgn = 1 if f0 > 0 else -1
    # theta*: the first sign change of f from th0 in the direction of motion (a scan with
    # steps growing by 1.2 up to 0.5 K: two roots of a positive-TCR pixel closer than that
    # would be missed; the study's problems have them tens of kelvin apart).
    step = mp.mpf("1e-3") * (1 + abs(th0))
    a = th0
    while True:
        b = a + sgn * step
        if not ts + b > 0:
            raise ValueError("reference: the pixel would cool below 0 K")
        if f(b) * sgn <= 0:
            break
        a = b
        step = min(step * mp.mpf("1.2"), mp.mpf("0.5"))
        if abs(b - th0) > 1e4:
            raise ValueError("reference: no equilibrium within 1e4 K (runaway)")
    star = mp.findroot(f, (a, b), solver="anderson")
    u0 = abs(star - th0)
    w0 = mp.log(u0)

    def theta(w: Any) -> Any:
        return star - sgn * mp.exp(w)

    def phi(w: Any) -> Any:  # dt/dw along the approach
        u = mp.exp(w)
        return u / abs(f(star - sgn * u))

    T_star = ts + star
    lam = abs((I * I * (-B * R(star) / (T_star * T_star)) - g) / C)  # |f'(theta*)|
    # Below w0 - 60 (u < 1e-26 u0) theta = theta* and dt/dw = 1/lam to 26 digits: those
    # pieces are exact in closed form; above, quadrature (theta keeps its digits at 60).
    cut = w0 - 60

    def integral(fn: Any, const: Any, w: Any) -> tuple[Any, Any]:
        """int_w^w0 fn dw; ``const`` is fn's value below the cut."""
        if w >= cut:
            return mp.quad(fn, [w, w0], error=True)
        v, e = mp.quad(fn, [cut, w0], error=True)
        return v + const * (cut - w), e

    top, _ = integral(phi, 1 / lam, cut)
    if top <= t_int:  # the pulse ends below the cut: w_end in closed form
        w_end = cut - (t_int - top) * lam
    else:
        w_end = mp.findroot(lambda w: integral(phi, 1 / lam, w)[0] - t_int, (cut, w0),
                            solver="anderson")
    t_got, e_t = integral(phi, 1 / lam, w_end)
    iV, e_v = integral(lambda w: I * R(theta(w)) * phi(w), I * R(star) / lam, w_end)
    iT, e_th = integral(lambda w: theta(w) * phi(w), star / lam, w_end)
    err = abs(t_got - t_int) / t_int + abs(e_t) / t_int + abs(e_v / iV) + abs(e_th / iT)
    return (theta(w_end) if w_end >= cut else star), iV, iT, err


def reference_transient_exact(Q: Sequence[float], T_s: Sequence[float], R_ref: float,
                              g: float, C: float, *, tcr: float, T_ref: float,
                              bias_current: float, t_int: float, frame_period: float,
                              pulse_start: float, theta0: float, dps: int = 60
                              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """One pixel's frame sequence in mpmath, independent of the model and of any ODE
    solver: the relaxations between pulses in closed form, every pulse by quadrature in the
    phase variable (:func:`_pulse_exact_mp`), at ``dps`` digits.

    Returns the mean voltage (V), the mean rise and the rise at the end of each pulse (K),
    each as a (2, N) array of double-double pairs (value = row 0 + row 1, so errors far
    below float64 resolution stay measurable), and the largest relative error estimate of
    the quadratures over the frames.
    """
    import mpmath as mp

    with mp.workdps(dps):
        m = mp.mpf
        B = -m(tcr) * m(T_ref) ** 2
        Rr, gg, CC, I, ti = m(R_ref), m(g), m(C), m(bias_current), m(t_int)
        th = m(theta0)
        v, mean, ends = [], [], []
        err = mp.mpf(0)

        def relax(th: Any, q: Any, length: Any) -> Any:
            eq = q / gg
            return eq + (th - eq) * mp.exp(-length * gg / CC)

        for n in range(len(Q)):
            q = m(Q[n])
            if n:
                th += m(T_s[n - 1]) - m(T_s[n])
            th = relax(th, q, m(pulse_start))
            th, iV, iT, e = _pulse_exact_mp(th, q, m(T_s[n]), I, Rr, B, m(T_ref), gg, CC, ti)
            v.append(_dd(iV / ti))
            mean.append(_dd(iT / ti))
            ends.append(_dd(th))
            err = max(err, e)
            th = relax(th, q, m(frame_period) - m(pulse_start) - ti)
        return np.array(v).T, np.array(mean).T, np.array(ends).T, float(err)


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
                _measure(points, f"{name} (fixed)", "steps", n,
                         runner(integrator=name, steps=n, rtol=None), repeats)
        for rt in tols:
            _measure(points, f"{name} (adaptive)", "rtol", rt,
                     runner(integrator=name, rtol=rt, steps=tr.DEFAULT_STEPS), repeats,
                     default=name == tr.DEFAULT_INTEGRATOR and rt == tr.DEFAULT_RTOL)
    tau = float(np.median(p["C"] / p["g"]))
    return _component(
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


# ---- figures -------------------------------------------------------------------------------

#: Short labels of failure reasons on the figures.
_REASONS = (("budget", "budget"), ("StiffnessError", "stiff"), ("did not converge", "no conv."),
            ("non-finite", "non-finite"))


def failure_label(reason: str | None) -> str:
    for key, label in _REASONS:
        if reason and key in reason:
            return label
    return "failed"


def figure_png(component: dict[str, Any]) -> bytes:
    """One component: error against run time (left) and against work (right), log-log.

    Failed settings are crosses in the method's colour, one row per failing method above
    the data, at the time (work) they took to fail (refusals before any work at the left
    edge), each row labelled with the method and the reasons; the default is a large star;
    the dashed line is 100 times the reference's own error estimate (if within view).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts = component["points"]
    ok = [p for p in pts if p["error"] is not None]
    errs = [max(p["error"], 1e-17) for p in ok] or [1.0]
    top = max(errs) * 20
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 5.2), sharey=True)
    methods = list(dict.fromkeys(p["method"] for p in pts))
    color = {m: f"C{k % 10}" for k, m in enumerate(methods)}
    marker = {m: "osD^v<>ph*"[k % 10] for k, m in enumerate(methods)}
    failing = [m for m in methods if any(p["failed"] for p in pts if p["method"] == m)]
    for ax, key, xlabel in ((axes[0], "time_s", "run time, s (min of runs, 1 thread)"),
                            (axes[1], "work", component.get("work_name", "work"))):
        xs = [p[key] for p in pts if p[key]]
        left = min(xs) / 2 if xs else 1.0
        for m in methods:
            good = [p for p in pts if p["method"] == m and p["error"] is not None and p[key]]
            if good:
                ax.loglog([p[key] for p in good], [max(p["error"], 1e-17) for p in good],
                          marker=marker[m], ms=4, lw=1, color=color[m], label=m)
        for k, m in enumerate(failing):
            bad = [p for p in pts if p["method"] == m and p["failed"]]
            y = top * 4.0**k
            ax.plot([p[key] or left for p in bad], [y] * len(bad), ls="none", marker="X",
                    ms=6, color=color[m])
            reasons = ", ".join(dict.fromkeys(failure_label(p["reason"]) for p in bad))
            ax.text(0.01, y * 1.3, f"{m} failed: {reasons} ({len(bad)})", fontsize=6,
                    color=color[m], transform=ax.get_yaxis_transform())
        d = [p for p in pts if p["default"] and p["error"] is not None and p[key]]
        if d:
            ax.loglog([d[0][key]], [max(d[0]["error"], 1e-17)], marker="*", ms=16,
                      mfc="none", mec="k", mew=1.5, ls="none", label="default")
        ref = 100 * component.get("reference_error", 0.0)
        if ref >= 1e-17:
            ax.axhline(ref, color="grey", ls="--", lw=0.8, label="100 x reference error")
        if failing:
            ax.axhline(top / 2, color="red", lw=0.5, alpha=0.4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("max relative error (above the red line: failed)")
    handles, labels = axes[1].get_legend_handles_labels()
    # Below the axes: inside, it would hide the points near the best errors.
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=7, frameon=False)
    fig.suptitle(component["title"], fontsize=10)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    return buf.getvalue()


def figures(result: dict[str, Any]) -> list[tuple[str, bytes]]:
    """(caption, PNG bytes) per component, for the regression report (matplotlib Agg)."""
    out = []
    for c in result["components"]:
        d = c["default"]
        state = ("failed" if d["failed"] else
                 f"error {d['error']:.2g}, {d['time_s']:.2g} s, {d['work']:.3g} work, "
                 f"{'on' if d['on_pareto_front'] else 'NOT on'} the front")
        caption = (f"{c['title']}: error against run time and against "
                   f"{c.get('work_name', 'work')}; default {d['method']} "
                   f"{d['setting_name']} = {d['setting']:g} ({state}); "
                   f"{len(c['missing'])} failed setting(s) drawn as crosses in their "
                   "method's colour above the curves.")
        out.append((caption, figure_png(c)))
    return out
