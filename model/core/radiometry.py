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
"""

import math
from fractions import Fraction

import numpy as np
from numba import njit, prange

from irnuc.model.core.constants import PI4_OVER_15

#: Below this x the lower (Bernoulli) series replaces the tail series.
X_SWITCH = 2.0
#: Largest number of tail-series terms before giving up (status 1).
MAX_TERMS = 1_000_000


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
def _band_integral_one(x1, x2, rtol, coef, method, n_fixed):
    if method == 0:
        v, n = band_integral(x1, x2, rtol, coef)
        return v, n, 0
    return band_series_paper(x1, x2, rtol, n_fixed)


@njit(cache=True)
def band_integral_serial(x1, x2, rtol, coef, method, n_fixed, out, terms, status):
    """Band integrals over flat arrays (method 0 hybrid, 1 paper series), one thread."""
    for i in range(x1.shape[0]):
        out[i], terms[i], status[i] = _band_integral_one(x1[i], x2[i], rtol, coef, method,
                                                         n_fixed)


@njit(cache=True, parallel=True)
def band_integral_parallel(x1, x2, rtol, coef, method, n_fixed, out, terms, status):
    """As :func:`band_integral_serial`, over threads (for per-pixel scenes)."""
    for i in prange(x1.shape[0]):
        out[i], terms[i], status[i] = _band_integral_one(x1[i], x2[i], rtol, coef, method,
                                                         n_fixed)


#: Below this many temperatures, waking the thread pool costs more than it saves.
PARALLEL_MIN = 256


def band_integral_batch(x1, x2, rtol, coef, method, n_fixed, out, terms, status):
    """Batch dispatcher: serial for a few temperatures, parallel for many."""
    kernel = band_integral_parallel if x1.shape[0] >= PARALLEL_MIN else band_integral_serial
    kernel(x1, x2, rtol, coef, method, n_fixed, out, terms, status)
