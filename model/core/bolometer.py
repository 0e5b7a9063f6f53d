"""Kernels for the bolometer electro-thermal readout (paper eq. 14-19).

Resistance (eq. 17): R(T) = R_ref exp(B (1/T - 1/T_ref)), with B = Ea / k (K) and the
temperature coefficient of resistance at T_ref alpha = -B / T_ref^2 (B > 0: negative TCR).

The pixel temperature that the integrator sees is T = T_s + dT with

    dT = a + b R(T_s + dT),   a = Q f_Q / g,   b = I^2 f / g,

where f = 1 - (1 - e^(-u)) / u, u = t_int / tau, tau = C / g, is the time average of the
heating transient 1 - e^(-t/tau) over the integration window (eq. 19), and f_Q is f in the
``paper`` variant (scene power switched on together with the bias) and 1 in the default
``equilibrium`` variant (the pixel has long been in equilibrium with the scene; only the
bias heating is a transient).

For B > 0 (negative TCR) h(dT) = dT - a - b R(T_s + dT) is strictly increasing: exactly one
root, bracketed by [a, a + b R(T_s + a)], found by Newton's method safeguarded by bisection.
For B < 0 (positive TCR) the electro-thermal feedback is positive and h may have up to three
roots. The physical equilibrium is the lowest one (h < 0 below it, so it is stable: the
loop gain b |dR/dT| is <= 1 there). R(T) ~ exp(-|B|/T) is convex below T = |B|/2 and
concave above, so h is concave and then convex: the lowest root is found by Newton from
the left on the concave part (monotone, no overshoot) and, if the concave part holds none,
by a bracketed Newton on the convex part, where h(T_max) > 0 brackets exactly one root.
The pixel is a thermal runaway only when h < 0 all the way to the runaway temperature,
i.e. when no equilibrium exists below it.
"""

import math

import numpy as np
from numba import njit, prange


def activation_temperature(tcr, T_ref):
    """B = E_a / k, K, from the TCR alpha (1/K) at T_ref (K): alpha = -B / T_ref^2 (eq. 17)."""
    return -tcr * T_ref * T_ref


STATUS_OK = 0
STATUS_NO_CONVERGENCE = 1
STATUS_RUNAWAY = 2
STATUS_INVALID = 3  # the temperature would be <= 0 K

#: Absolute floor of the Newton stop tests, K: only so that a root at exactly 0 ends. The
#: tests are relative (|step| <= rtol |dT|): a rise of a microkelvin is solved to the same
#: relative accuracy as one of tens of kelvin (a floor of rtol * 1e-3 K left microkelvin
#: rises 1e-9 relative off at rtol 1e-12).
ROOT_ATOL = 1e-300



#: Taylor coefficients of f(u) = sum_{k>=1} (-1)^(k+1) u^k / (k+1)!, for u < 0.25.
_SH_COEF = tuple((-1.0) ** (k + 1) / math.factorial(k + 1) for k in range(1, 15))


@njit(cache=True)
def self_heating_factor(u):
    """f(u) = 1 + (e^(-u) - 1) / u for u = t_int / tau >= 0, without cancellation.

    Small u: the alternating Taylor series u/2 - u^2/6 + u^3/24 - ... in Horner form (no
    cancellation), with as many terms as u needs: n terms leave a relative remainder below
    2 u^n / (n+2)!, under 1e-18 for (u < 1e-3, n = 5), (u < 0.03, n = 8), (u < 0.25, n = 13).
    Otherwise expm1, which keeps e^(-u) - 1 exact to rounding. f(0) = 0, f(inf) = 1.
    """
    if u < 0.25:
        c = _SH_COEF
        n = 5 if u < 1e-3 else (8 if u < 0.03 else 13)
        s = c[n - 1]
        for k in range(n - 2, -1, -1):
            s = s * u + c[k]
        return s * u
    if u == math.inf:
        return 1.0
    return 1.0 + math.expm1(-u) / u


@njit(cache=True)
def self_heating_factor_naive(u):
    """The reference implementation's form 1 + tau/t (e^(-t/tau) - 1): cancels for large tau."""
    return 1.0 + (math.exp(-u) - 1.0) / u


@njit(cache=True)
def resistance(T, R_ref, B, T_ref):
    """Bolometer resistance at temperature T (eq. 17), ohm."""
    return R_ref * math.exp(B * (1.0 / T - 1.0 / T_ref))


@njit(cache=True)
def exp_small(z):
    """e^z, by a 5-term Taylor series when |z| < 1e-3 (error < 1e-17), else math.exp."""
    if abs(z) < 1e-3:
        return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z * (1.0 / 24.0))))
    return math.exp(z)


@njit(cache=True)
def newton_negative_tcr(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, x0):
    """Root of h(x) = x - a - b R(T_s + x) for B > 0. Returns (x, status, iterations, R(x)).

    h is increasing and concave, so Newton steps from below never overshoot the root; the
    bracket [lo, hi] (hi computed only when a step would leave it) guards the rest.
    """
    return newton_negative_tcr_warm(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, x0, math.nan)


@njit(cache=True)
def newton_negative_tcr_warm(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, x0, e0):
    """:func:`newton_negative_tcr` with e0 = exp(B (1/(T_s + x0) - 1/T_ref)) known.

    A neighbour's solution gives both x0 and e0 (its R over its R_ref), so the first Newton
    step needs no exponential.
    """
    atol = ROOT_ATOL
    inv_Tref = 1.0 / T_ref
    lo = a
    hi = math.inf
    if x0 > lo:
        x = x0
    else:
        hi = a + b * resistance(T_s + a, R_ref, B, T_ref)
        x = 0.5 * (lo + hi)
    for it in range(1, max_iter + 1):
        T = T_s + x
        inv_T = 1.0 / T
        if it == 1 and x == x0 and e0 > 0.0:
            R = R_ref * e0
        else:
            R = R_ref * math.exp(B * (inv_T - inv_Tref))
        h = x - a - b * R
        if h > 0.0:
            hi = x
        elif h < 0.0:
            lo = x
        else:
            return x, STATUS_OK, it, R
        bRB = b * R * B * inv_T * inv_T  # -d(b R)/dT > 0
        dh = 1.0 + bRB
        inv_dh = 1.0 / dh
        step = h * inv_dh
        xn = x - step
        bisected = not (lo < xn < hi)
        if bisected:
            if hi == math.inf:
                hi = a + b * resistance(T_s + a, R_ref, B, T_ref)
            xn = 0.5 * (lo + hi)
            step = x - xn
        tol = rtol * abs(xn) + atol
        done = abs(step) <= tol
        if not done and not bisected and abs(step) < 1e-4 * (abs(x) + 1.0):
            # Quadratic regime (Newton steps only: a bisection step says nothing about
            # it): the error after this step is about K step^2 with
            # K = |h''| / (2 h'), h'' = -b R (B^2/T^4 + 2B/T^3).
            K = abs(bRB * (B * inv_T + 2.0) * inv_T) * 0.5 * inv_dh
            done = K * step * step <= 0.01 * tol
        if done:
            Tn = T_s + xn
            return xn, STATUS_OK, it, R * exp_small(B * step / (T * Tn))
        x = xn
    return x, STATUS_NO_CONVERGENCE, max_iter, resistance(T_s + x, R_ref, B, T_ref)


@njit(cache=True)
def solve_delta_t(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, x0, T_max):
    """Root dT of dT = a + b R(T_s + dT). Returns (dT, status, iterations).

    x0 is an initial guess (NaN for none); it is used only if it lies inside the bracket.
    Convergence: |last Newton step| <= rtol |dT| (+ ROOT_ATOL).

    T_s + a <= 0 (the unbiased equilibrium below 0 K: a net emitter on a vanishing g): for
    B > 0 and b > 0 the biased pixel still has exactly one equilibrium above 0 K (R grows
    without bound as T -> 0), found by :func:`solve_cold_start`; otherwise there is none
    and the result is STATUS_INVALID with dT = -T_s (the pixel at 0 K, the bound it falls to).
    """
    Ta = T_s + a
    if not Ta > 0.0:
        if B > 0.0 and b > 0.0:
            return solve_cold_start(a, b, R_ref, B, T_ref, T_s, rtol, max_iter)
        return -T_s, STATUS_INVALID, 0
    if b == 0.0:
        return a, STATUS_OK, 0
    if B == 0.0:
        return a + b * R_ref, STATUS_OK, 0
    if B > 0.0:
        x, status, it, _ = newton_negative_tcr(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, x0)
        return x, status, it
    return solve_positive_tcr(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, T_max)


@njit(cache=True)
def solve_cold_start(a, b, R_ref, B, T_ref, T_s, rtol, max_iter):
    """Root dT of dT = a + b R(T_s + dT) for B > 0, b > 0 and T_s + a <= 0, in K.

    h(x) = x - a - b R(T_s + x) is increasing, -> -inf as T -> 0+ and >= 0 at
    x_hi = b R(T_s) (R falls with T and x_hi - a >= b R(T_s)), so the one root lies in
    T = T_s + x in (0, T_s + x_hi]. The bracket is first narrowed by bisection in ln T (the
    root may be kelvins or far less), then Newton safeguarded by the bracket finishes.
    Returns (dT, status, iterations).
    """
    lo_T = 0.0
    hi_T = T_s + b * resistance(T_s, R_ref, B, T_ref)
    it = 0
    T = hi_T
    while it < max_iter:
        it += 1
        T = 0.5 * hi_T if lo_T == 0.0 else math.sqrt(lo_T * hi_T)
        if lo_T > 0.0 and hi_T - lo_T <= 1e-3 * hi_T:
            break
        e = B * (1.0 / T - 1.0 / T_ref)
        h = (T - T_s) - a - (b * R_ref * math.exp(e) if e < 700.0 else math.inf)
        if h < 0.0:
            lo_T = T
        else:
            hi_T = T
        if lo_T == 0.0 and not T > 0.0:
            return -T_s, STATUS_INVALID, it  # no positive T left in floating point
    x, st, k = bracketed_newton(lo_T - T_s, hi_T - T_s, T - T_s, a, b, R_ref, B, T_ref, T_s,
                                rtol, max_iter)
    return x, st, it + k


@njit(cache=True)
def _h_positive(x, a, b, R_ref, B, T_ref, T_s):
    """(h in K, dh/dx dimensionless) of h(x) = x - a - b R(T_s + x), x in K (either sign
    of B; named for the positive TCR, its first user)."""
    T = T_s + x
    bR = b * resistance(T, R_ref, B, T_ref)
    return x - a - bR, 1.0 + bR * B / (T * T)


@njit(cache=True)
def bracketed_newton(lo, hi, x, a, b, R_ref, B, T_ref, T_s, rtol, max_iter):
    """Root of h in [lo, hi] (K) with h(lo) < 0 <= h(hi) and exactly one root between:
    Newton from x (K), bisection whenever a step leaves the bracket. It stops on a Newton
    step below rtol |x| (the error after it is of order its square), or on a bracket of
    two neighbouring floats; never on a bisection step, whose error is its own size.

    a (K), b (K/ohm), R_ref (ohm), B (K, either sign), T_ref and T_s (K) as in
    :func:`solve_delta_t`. Returns (x in K, status, iterations).
    """
    for it in range(1, max_iter + 1):
        h, dh = _h_positive(x, a, b, R_ref, B, T_ref, T_s)
        if h == 0.0:
            return x, STATUS_OK, it
        if h < 0.0:
            lo = x
        else:
            hi = x
        xn = x - h / dh if dh != 0.0 else math.nan
        if lo < xn < hi:
            if abs(xn - x) <= rtol * abs(xn) + ROOT_ATOL:
                return xn, STATUS_OK, it
        else:
            xn = 0.5 * (lo + hi)
            if xn == lo or xn == hi:
                return xn, STATUS_OK, it
        x = xn
    return x, STATUS_NO_CONVERGENCE, max_iter


@njit(cache=True)
def solve_positive_tcr(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, T_max):
    """Lowest root x (K) of h(x) = x - a - b R(T_s + x) with T_s + x <= T_max (K), for
    B < 0 (positive TCR); a (K), b (K/ohm), R_ref (ohm), B (K), T_ref, T_s (K) as in
    :func:`solve_delta_t` (paper eq. 16-19).

    h(a) < 0. Concave part (T_s + x < |B|/2): Newton from the left never overshoots; a
    derivative <= 0 there (loop gain >= 1) proves h < 0 up to the inflection point, and a
    Newton step past it is checked against h at the inflection point. Convex part: h < 0
    at its left end, so exactly one root if h(x_max) > 0 (Newton bracketed), else none:
    STATUS_RUNAWAY. Returns (x, status, iterations).
    """
    x_max = T_max - T_s
    if not a < x_max:
        return a, STATUS_RUNAWAY, 0
    atol = ROOT_ATOL
    x_inf = -0.5 * B - T_s  # inflection of R(T_s + x)
    x = a
    it = 0
    if x_inf > a:
        e = min(x_inf, x_max)
        while it < max_iter:
            it += 1
            h, dh = _h_positive(x, a, b, R_ref, B, T_ref, T_s)
            if h >= 0.0:
                return x, STATUS_OK, it
            if dh <= 0.0:
                break  # loop gain >= 1: h decreases up to the inflection point, no root
            xn = x - h / dh
            if xn >= e:
                he, _ = _h_positive(e, a, b, R_ref, B, T_ref, T_s)
                if he >= 0.0:  # the one root of the concave part lies in (x, e]
                    xr, st, k = bracketed_newton(x, e, 0.5 * (x + e), a, b, R_ref, B, T_ref,
                                                 T_s, rtol, max_iter)
                    return xr, st, it + k
                break  # tangent above h and negative up to e: no root in the concave part
            if xn - x <= rtol * abs(xn) + atol:
                return xn, STATUS_OK, it
            x = xn
        else:
            return x, STATUS_NO_CONVERGENCE, it
        if x_inf >= x_max:
            return x_max, STATUS_RUNAWAY, it
        x = x_inf
    hm, _ = _h_positive(x_max, a, b, R_ref, B, T_ref, T_s)
    if not hm > 0.0:
        return x_max, STATUS_RUNAWAY, it + 1  # h < 0 up to T_max: no equilibrium below it
    # Convex part: Newton from the right converges monotonically; the bracket guards.
    xr, st, k = bracketed_newton(x, x_max, x_max, a, b, R_ref, B, T_ref, T_s, rtol, max_iter)
    return xr, st, it + 1 + k


#: Independent warm-start chains per row: pixel j starts from pixel j - WARM_CHAINS, so the
#: CPU can overlap that many pixels instead of waiting for each left neighbour.
WARM_CHAINS = 4


@njit(cache=True)
def solve_row(Q, R_ref, g, C, B, T_ref, T_s, I, t_int, variant, rtol, max_iter, T_max,
              dT_out, v_out, status_out, iters_out):
    """Solve one row of pixels; pixel j starts from the solution of pixel j - WARM_CHAINS."""
    x0s = np.full(WARM_CHAINS, math.nan)
    e0s = np.full(WARM_CHAINS, math.nan)
    for j in range(Q.shape[0]):
        slot = j % WARM_CHAINS
        x0 = x0s[slot]
        e0 = e0s[slot]
        gj = g[j]
        inv_g = 1.0 / gj
        f = self_heating_factor(t_int * gj / C[j])
        fq = f if variant == 1 else 1.0
        a = Q[j] * fq * inv_g
        b = I * I * f * inv_g
        if B > 0.0 and T_s + a > 0.0 and b > 0.0:
            x, st, it, R = newton_negative_tcr_warm(a, b, R_ref[j], B, T_ref, T_s, rtol,
                                                    max_iter, x0, e0)
            v_out[j] = I * R
            e0 = R / R_ref[j]
        else:
            x, st, it = solve_delta_t(a, b, R_ref[j], B, T_ref, T_s, rtol, max_iter, x0, T_max)
            e0 = math.nan
            if st == STATUS_INVALID:
                # At 0 K, where it fell: no current (b = 0) or no resistance (B < 0) there.
                v_out[j] = 0.0
            else:
                v_out[j] = I * resistance(T_s + x, R_ref[j], B, T_ref)
        if st == STATUS_OK and not T_s + x <= T_max:
            st = STATUS_RUNAWAY  # hotter than the runaway limit (e.g. g -> 0): not OK
        dT_out[j] = x
        status_out[j] = st
        iters_out[j] = it
        x0s[slot] = x if st == STATUS_OK else math.nan
        e0s[slot] = e0 if st == STATUS_OK else math.nan


@njit(cache=True, parallel=True)
def solve_frames(Q, R_ref, g, C, B, T_ref, T_s, I, t_int, variant, rtol, max_iter, T_max,
                 dT_out, v_out, status_out, iters_out):
    """Batch over frames and rows: Q (N, rows, cols) W; parameters (rows, cols).

    Writes the temperature rise dT (K), the bolometer voltage I R(T) (V), the status and
    the iteration count of every pixel of every frame.
    """
    n_frames, rows, _ = Q.shape
    for k in prange(n_frames * rows):
        n = k // rows
        i = k - n * rows
        solve_row(Q[n, i], R_ref[i], g[i], C[i], B, T_ref, T_s, I, t_int, variant, rtol,
                  max_iter, T_max, dT_out[n, i], v_out[n, i], status_out[n, i],
                  iters_out[n, i])
