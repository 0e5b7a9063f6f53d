"""Kernels for the in-band blackbody radiance (paper eq. 2-4).

With x = hc / (lambda k T), the radiance between 0 and lambda is
``RADIANCE_PREFACTOR * T**4 * I(x)`` where I(x) is the upper tail
``int_x^inf t^3 / (e^t - 1) dt = sum_n e^(-n x) (x^3/n + 3x^2/n^2 + 6x/n^3 + 6/n^4)``
(the paper's series, eq. 3). The band (lambda1, lambda2) is ``I(x2) - I(x1)`` with
x1 = hc/(lambda1 k T) > x2 (eq. 4).

The tail series converges like e^(-n x): fast for cold scenes, slowly and with cancellation
between the two tails for hot ones (x -> 0). For x below ``X_SWITCH`` the lower integral
``J(x) = int_0^x t^3/(e^t-1) dt = sum_k B_k x^(k+3) / (k! (k+3))`` (Bernoulli numbers B_k,
convergent for x < 2 pi) is used instead, so the band never subtracts two nearly equal
tails. Both series stop at the first term count whose rigorous remainder bound is below
the requested relative tolerance.

Two regimes bypass the series (``hybrid`` only for the first; both methods for the second):

* **Narrow bands** (x1 - x2 <= ``QUAD_MAX_WIDTH``): the band is integrated directly,
  ``int_x2^x1 t^3 / expm1(t) dt`` by Gauss-Legendre quadrature on panels of width <= 1,
  with x1 - x2 formed from the wavelength difference (no cancellation at all). The
  integrand is analytic except at t = 2 pi i k (k != 0), at least 2 pi from every panel,
  so ``GL_NODES`` nodes reach far below 1e-16 (Bernstein-ellipse bound, rho = 10).
* **Underflow** (x2 > ``X_UNDERFLOW``): only the first tail term matters (the next is
  e^-600 smaller) and the radiance is evaluated in log space,
  ``exp(ln P + 4 ln T + 3 ln x2 - x2 + ln(1 + 3/x2 + 6/x2^2 + 6/x2^3) + ln(1 - r))`` with
  r = I(x1)/I(x2) from ``exp(-(x1 - x2)) (x1/x2)^3 ...``: exactly 0 where the radiance is
  below float64 (subnormal just above), never 0 * inf = NaN for T -> 0.

The scalar kernel :func:`band_radiance_one` returns the radiance itself (W m^-2 sr^-1 of a
blackbody), so the API never forms T^4 times an underflowed or overflowed integral.
"""

import math
from fractions import Fraction

import numpy as np
from numba import njit, prange

from irnuc.model.core.constants import C2, PI4_OVER_15, RADIANCE_PREFACTOR

#: Below this x the lower (Bernoulli) series replaces the tail series.
X_SWITCH = 2.0
#: Largest number of tail-series terms before giving up (status 1).
MAX_TERMS = 1_000_000
#: Above this x2 the radiance is the first tail term, evaluated in log space (underflow).
X_UNDERFLOW = 600.0
#: Bands narrower than this in x = hc / (lambda k T) are integrated directly (hybrid).
QUAD_MAX_WIDTH = 2.0
#: Gauss-Legendre nodes per panel of width <= 1 (error bound below 1e-20 relative).
GL_NODES = 12
_GL_X, _GL_W = np.polynomial.legendre.leggauss(GL_NODES)
GL_X = np.ascontiguousarray(_GL_X)
GL_W = np.ascontiguousarray(_GL_W)
_LOG_PREFACTOR = math.log(RADIANCE_PREFACTOR)


def _bernoulli_coefficients(n: int) -> np.ndarray:
    """c_k = B_k / (k! (k + 3)) for k < n, with B_1 = -1/2 (exact rationals, then float)."""
    b = [Fraction(1)]
    for m in range(1, n):
        b.append(-sum(math.comb(m + 1, j) * b[j] for j in range(m)) / (m + 1))
    return np.array([float(b[k] / (math.factorial(k) * (k + 3))) for k in range(n)])


#: Coefficients of the lower series; |c_k| x^k decays like (x / 2pi)^k.
BERNOULLI_COEF = _bernoulli_coefficients(80)


@njit(cache=True)
def tail_term(x, n):
    """Term n (>= 1) of the tail series I(x)."""
    rn = 1.0 / n
    return math.exp(-n * x) * rn * (x * x * x + rn * (3.0 * x * x + rn * (6.0 * x + 6.0 * rn)))


@njit(cache=True)
def tail_remainder_bound(x, n):
    """Upper bound of the tail-series remainder after n terms (terms n+1, n+2, ...).

    Every factor of term m decreases with m, so the remainder is at most term n+1 times the
    geometric sum of e^(-x): ``term(n+1) / (1 - e^(-x))``.
    """
    return tail_term(x, n + 1) / -math.expm1(-x)


@njit(cache=True)
def band_series_paper(x1, x2, rtol, n_fixed):
    """I(x2) - I(x1) by the paper's tail series (eq. 4), both tails summed together.

    Returns (value, terms used, status): status 0 converged, 1 hit MAX_TERMS. With
    ``n_fixed > 0`` exactly that many terms are summed (the reference implementation used 100).
    """
    s2 = 0.0
    s1 = 0.0
    n = 0
    limit = n_fixed if n_fixed > 0 else MAX_TERMS
    while n < limit:
        n += 1
        s2 += tail_term(x2, n)
        s1 += tail_term(x1, n)
        if n_fixed <= 0:
            bound = tail_remainder_bound(x2, n) + tail_remainder_bound(x1, n)
            if bound <= rtol * 0.25 * (s2 - s1):
                return s2 - s1, n, 0
    return s2 - s1, n, 0 if n_fixed > 0 else 1


@njit(cache=True)
def tail_series(x, rtol):
    """I(x) by the tail series to relative tolerance rtol: (value, terms)."""
    s = 0.0
    n = 0
    while n < MAX_TERMS:
        n += 1
        s += tail_term(x, n)
        if tail_remainder_bound(x, n) <= rtol * 0.25 * s:
            break
    return s, n


@njit(cache=True)
def lower_series(x, rtol, coef):
    """J(x) = int_0^x t^3/(e^t-1) dt for 0 <= x < 2 pi: (value, terms).

    Stops when two successive even-k terms are below rtol/8 of the sum: the terms alternate
    and shrink geometrically by (x/2pi)^2 per even step, so the rest is smaller still.
    """
    x3 = x * x * x
    s = x3 * coef[0] + x3 * x * coef[1]
    p = x3  # x^(k+3) for the even k of the loop; odd k > 1 have B_k = 0
    k = 2
    while k < coef.shape[0]:
        p *= x * x
        term = p * coef[k]
        s += term
        k += 2
        if abs(term) <= rtol * 0.125 * abs(s):
            break
    return s, k


@njit(cache=True)
def band_integral(x1, x2, rtol, coef):
    """I(x2) - I(x1) (x1 > x2 >= 0), choosing the series that avoids cancellation.

    Returns (value, terms used).
    """
    if x2 >= X_SWITCH:
        v, n, _ = band_series_paper(x1, x2, rtol, 0)
        return v, n
    j2, n2 = lower_series(x2, rtol * 0.5, coef)
    if x1 < X_SWITCH:
        j1, n1 = lower_series(x1, rtol * 0.5, coef)
    else:
        i1, n1 = tail_series(x1, rtol * 0.1)
        j1 = PI4_OVER_15 - i1
    return j1 - j2, n1 + n2


@njit(cache=True)
def band_quadrature(x2, dx, gx, gw):
    """int_x2^(x2+dx) t^3 / (e^t - 1) dt by Gauss-Legendre on ceil(dx) equal panels.

    Returns (value, integrand evaluations). dx > 0 is passed separately so that a narrow
    band never forms x1 - x2 from two rounded numbers.
    """
    panels = max(1, math.ceil(dx))
    h = dx / panels
    s = 0.0
    for k in range(panels):
        mid = x2 + (k + 0.5) * h
        p = 0.0
        for j in range(gx.shape[0]):
            t = mid + 0.5 * h * gx[j]
            p += gw[j] * (t * t * t / math.expm1(t))
        s += 0.5 * h * p
    return s, panels * gx.shape[0]


@njit(cache=True)
def _poly_over_cube(x):
    """(x^3 + 3x^2 + 6x + 6) / x^3: the first tail term over x^3 e^-x."""
    r = 1.0 / x
    return 1.0 + r * (3.0 + r * (6.0 + 6.0 * r))


@njit(cache=True)
def radiance_underflow(T, lam1, lam2):
    """Blackbody band radiance (W m^-2 sr^-1) for x2 = hc/(lam2 k T) > X_UNDERFLOW.

    Log space: every factor is a logarithm, so T -> 0 gives exp(-inf) = 0, never
    0 * inf (and no product of T with the wavelengths, which underflows to 0 for a
    subnormal T). Relative to the first tail terms the rest is below e^-600. The ratio
    r = I(x1)/I(x2) of the first terms, ln r = -(x1 - x2) + 3 ln(x1/x2) + ln(P1/P2), is
    formed from exact differences with log1p: for a band of a few ulps every log of a ratio
    rounded near 1 would lose the whole band.
    """
    ln_x2 = math.log(C2 / lam2) - math.log(T)
    x2 = (C2 / lam2) / T
    x1 = (C2 / lam1) / T
    d = (lam2 - lam1) / lam1  # x1 / x2 = 1 + d, from the exact wavelength difference
    dx = (C2 / T) * ((lam2 - lam1) / (lam1 * lam2))  # x1 - x2
    u1 = 1.0 / x1
    u2 = 1.0 / x2
    # P(x) = 1 + 3u + 6u^2 + 6u^3 (u = 1/x); P1 - P2 = (u1 - u2)(3 + 6(u1 + u2) + 6(u1^2 +
    # u1 u2 + u2^2)) with u1 - u2 = -d u1.
    dp = -d * u1 * (3.0 + 6.0 * (u1 + u2) + 6.0 * (u1 * u1 + u1 * u2 + u2 * u2))
    ln_r = -dx + 3.0 * math.log1p(d) + math.log1p(dp / _poly_over_cube(x2))
    ln_band = -math.expm1(ln_r)  # 1 - r without cancellation for narrow bands
    if not ln_band > 0.0:
        return 0.0
    ln_L = (_LOG_PREFACTOR + 4.0 * math.log(T) + 3.0 * ln_x2 - x2
            + math.log(_poly_over_cube(x2)) + math.log(ln_band))
    return math.exp(ln_L)


@njit(cache=True)
def band_radiance_one(T, lam1, lam2, rtol, coef, method, n_fixed):
    """Blackbody radiance between lam1 < lam2 (m) at T (K), W m^-2 sr^-1 (eq. 2-4).

    ``method`` 0: hybrid (narrow bands by quadrature, else the cancellation-free series);
    1: the paper's eq. 4 (difference of two tail series; ``n_fixed`` > 0 fixes the terms).
    Both use the log-space first term where the radiance underflows.

    Returns (radiance, terms or integrand evaluations, status): status 1 if the paper's
    series did not converge within MAX_TERMS.
    """
    x2 = (C2 / lam2) / T  # never lam * T: it underflows to 0 for a subnormal T
    if x2 > X_UNDERFLOW:
        return radiance_underflow(T, lam1, lam2), 1, 0
    x1 = (C2 / lam1) / T
    scale = RADIANCE_PREFACTOR * T * T * T * T
    if method == 1:
        v, n, st = band_series_paper(x1, x2, rtol, n_fixed)
        return scale * v, n, st
    dx = C2 * (lam2 - lam1) / (lam1 * lam2 * T)
    if dx <= QUAD_MAX_WIDTH:
        v, n = band_quadrature(x2, dx, GL_X, GL_W)
        return scale * v, n, 0
    v, n = band_integral(x1, x2, rtol, coef)
    return scale * v, n, 0


@njit(cache=True)
def band_radiance_serial(T, lam1, lam2, rtol, coef, method, n_fixed, out, terms, status):
    """:func:`band_radiance_one` over a flat array of temperatures, one thread."""
    for i in range(T.shape[0]):
        out[i], terms[i], status[i] = band_radiance_one(T[i], lam1, lam2, rtol, coef, method,
                                                        n_fixed)


@njit(cache=True, parallel=True)
def band_radiance_parallel(T, lam1, lam2, rtol, coef, method, n_fixed, out, terms, status):
    """As :func:`band_radiance_serial`, over threads (for per-pixel scenes)."""
    for i in prange(T.shape[0]):
        out[i], terms[i], status[i] = band_radiance_one(T[i], lam1, lam2, rtol, coef, method,
                                                        n_fixed)


#: Below this many temperatures, waking the thread pool costs more than it saves.
PARALLEL_MIN = 256


def band_radiance_batch(T, lam1, lam2, rtol, coef, method, n_fixed, out, terms, status):
    """Batch dispatcher: serial for a few temperatures, parallel for many."""
    kernel = band_radiance_parallel if T.shape[0] >= PARALLEL_MIN else band_radiance_serial
    kernel(T, lam1, lam2, rtol, coef, method, n_fixed, out, terms, status)
