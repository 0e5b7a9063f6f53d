"""Single-precision variant of the electro-thermal solve, for work-precision studies.

The same safeguarded Newton as :func:`model.core.bolometer.solve_delta_t` (negative TCR
only), with every quantity in float32: it shows what single precision (as on a GPU or an
FPGA soft core) costs in accuracy. Tolerances below float32 resolution (~6e-8) cannot be
met and end with STATUS_NO_CONVERGENCE.
"""

import math

import numpy as np
from numba import njit, prange

from irnuc.model.core.bolometer import STATUS_INVALID, STATUS_NO_CONVERGENCE, STATUS_OK

F0 = np.float32(0.0)
F1 = np.float32(1.0)
HALF = np.float32(0.5)
MILLI = np.float32(1e-3)


@njit(cache=True)
def solve_delta_t32(a, b, R_ref, B, T_ref, T_s, rtol, max_iter):
    """Root dT of dT = a + b R(T_s + dT) in float32 (B > 0). Returns (dT, status, iters)."""
    atol = rtol * MILLI
    Ta = T_s + a
    if not Ta > F0:
        return np.float32(math.nan), STATUS_INVALID, 0
    inv_ref = F1 / T_ref
    lo = a
    hi = a + b * R_ref * np.float32(math.exp(B * (F1 / Ta - inv_ref)))
    x = HALF * (lo + hi)
    for it in range(1, max_iter + 1):
        T = T_s + x
        inv_T = F1 / T
        R = R_ref * np.float32(math.exp(B * (inv_T - inv_ref)))
        h = x - a - b * R
        if h > F0:
            hi = x
        elif h < F0:
            lo = x
        else:
            return x, STATUS_OK, it
        xn = x - h / (F1 + b * R * B * inv_T * inv_T)
        if not (lo < xn < hi):
            xn = HALF * (lo + hi)
        if abs(xn - x) <= rtol * abs(xn) + atol:
            return xn, STATUS_OK, it
        x = xn
    return x, STATUS_NO_CONVERGENCE, max_iter


@njit(cache=True, parallel=True)
def solve_flat32(a, b, R_ref, B, T_ref, T_s, rtol, max_iter, dT_out, status_out, iters_out):
    """Batch over flat float32 arrays a, b, R_ref (see :func:`solve_delta_t32`)."""
    for i in prange(a.shape[0]):
        x, st, it = solve_delta_t32(a[i], b[i], R_ref[i], B, T_ref, T_s, rtol, max_iter)
        dT_out[i] = x
        status_out[i] = st
        iters_out[i] = it
