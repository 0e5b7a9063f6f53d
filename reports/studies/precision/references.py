"""The independent high-precision references of the work-precision study (mpmath, scipy):
band radiance, the electro-thermal root, and the transient pulse sequence."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from irnuc.reports.studies.precision.harness import dd

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


def radiance_reference(temps: np.ndarray, band: tuple[float, float]
                        ) -> tuple[np.ndarray, float]:
    """Double-double references and their error estimate (80 against 60 digits)."""
    ref = np.array([dd(band_radiance_mp(t, band, as_mpf=True)) for t in temps]).T
    import mpmath as mp

    est = 0.0
    for t in temps[:: max(1, temps.size // 4)]:
        a = band_radiance_mp(t, band, as_mpf=True)
        b = band_radiance_mp(t, band, dps=60, as_mpf=True)
        est = max(est, float(abs((a - b) / a)))
    return ref, max(est, float(mp.mpf(10) ** -REFERENCE_DPS))


def brentq_reference(prob: dict[str, Any], idx: np.ndarray) -> np.ndarray:
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


def mp_root_reference(prob: dict[str, Any], idx: np.ndarray, dps: int = 40
                  ) -> tuple[np.ndarray, float]:
    """Roots in mpmath (Newton from brentq's root) as double-double pairs, and the error
    estimate from the same roots at dps - 10 digits."""
    import mpmath as mp

    b = prob["cfg"]["bolometer"]
    R = np.broadcast_to(prob["p"]["R_ref"], prob["Q"].shape).ravel()
    a, bb = prob["a"].ravel(), prob["b"].ravel()
    start = brentq_reference(prob, idx)
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
            out[:, k] = dd(roots[0])
            est = max(est, float(abs((roots[0] - roots[1]) / roots[0])))
    return out, est



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
            v.append(dd(iV / ti))
            mean.append(dd(iT / ti))
            ends.append(dd(th))
            err = max(err, e)
            th = relax(th, q, m(frame_period) - m(pulse_start) - ti)
        return np.array(v).T, np.array(mean).T, np.array(ends).T, float(err)
