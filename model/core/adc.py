"""Kernel of the ADC: rails, scaling, rounding and clamping in one pass."""

import math

from numba import njit


@njit(cache=True)
def convert(v, rail_low, rail_high, v_low, scale, top, nearest, out):
    """Codes of a flat voltage array; returns the number of non-finite values.

    v is first clipped to the integrator rails [rail_low, rail_high], then scaled by
    ``scale`` = 2^bits / (v_high - v_low), rounded (half up when ``nearest``, else floor)
    and clamped to [0, top].
    """
    bad = 0
    # One thread: a single streaming pass is cheaper than waking the pool.
    for i in range(v.shape[0]):
        x = v[i]
        if not math.isfinite(x):
            bad += 1  # the caller locates them
            out[i] = 0
            continue
        x = min(max(x, rail_low), rail_high)
        c = (x - v_low) * scale
        # Clamp first: numba's math.floor returns int64, which wraps beyond 9.2e18.
        c = min(max(c, -1.0), top + 1.0)
        c = math.floor(c + 0.5) if nearest else math.floor(c)
        out[i] = int(min(max(c, 0.0), top))
    return bad
