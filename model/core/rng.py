"""Counter-based standard normal draws: the same numbers whatever the chunking or threads.

Every draw is a pure function of a 64-bit key (one per seed, random stream and frame, made
by :func:`model.noise.frame_key` from ``numpy.random.SeedSequence``) and the draw's index
in the frame (the pixel's flat index, and the attempt for the rare rejected sample). The
64 random bits of (key, index, attempt) are the SplitMix64 finalizer (Steele, Lea and
Flood, OOPSLA 2014: the output function of ``java.util.SplittableRandom``) applied twice,
so neighbouring indices give unrelated bits; the normal deviate is drawn from them by the
ziggurat method (Marsaglia and Tsang, J. Stat. Softw. 5(8), 2000) with 128 layers: one
table look-up and a comparison for 98.8 % of the draws, the wedges and the tail beyond
r = 3.4426 by rejection (exact). The tables are computed here from the method's two
constants.

The kernels fill an (rows, cols) plane in parallel over its rows; a row's draws depend
only on the key and the flat index, so every thread count gives the same bits.
"""

import math

import numpy as np
from numba import njit, prange

#: Ziggurat of 128 layers for f(x) = exp(-x^2 / 2): the start of the tail and the area of
#: every layer (Marsaglia and Tsang 2000, section 3).
ZIG_LAYERS = 128
ZIG_R = 3.442619855899
ZIG_V = 9.91256303526217e-3


def _ziggurat_tables() -> tuple[np.ndarray, np.ndarray]:
    """x[0..N] (x[0] = V / f(R) the base layer's width, x[1] = R, x[N] = 0) and f(x)."""
    n = ZIG_LAYERS
    x = np.empty(n + 1)
    f = np.empty(n + 1)
    x[0] = ZIG_V / math.exp(-0.5 * ZIG_R * ZIG_R)
    x[1] = ZIG_R
    for i in range(1, n - 1):  # equal areas: x[i] (f(x[i+1]) - f(x[i])) = V
        x[i + 1] = math.sqrt(-2.0 * math.log(ZIG_V / x[i] + math.exp(-0.5 * x[i] * x[i])))
    x[n] = 0.0
    f[:] = np.exp(-0.5 * x * x)
    f[0] = 0.0  # the base layer's floor (its y range is [0, f(R)])
    return x, f


ZIG_X, ZIG_F = _ziggurat_tables()

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S30 = np.uint64(30)
_S27 = np.uint64(27)
_S31 = np.uint64(31)
_S11 = np.uint64(11)
_S8 = np.uint64(8)
_MASK7 = np.uint64(127)
_BIT7 = np.uint64(128)
_ZERO = np.uint64(0)
_TWO_M53 = 1.0 / 9007199254740992.0


@njit(cache=True)
def mix64(z):
    """The SplitMix64 output function of a uint64 (a bijection with full avalanche)."""
    z = (z ^ (z >> _S30)) * _M1
    z = (z ^ (z >> _S27)) * _M2
    return z ^ (z >> _S31)


@njit(cache=True)
def bits64(key, index, attempt):
    """64 random bits of (key, draw index, attempt), all uint64."""
    return mix64(mix64(key + _GOLDEN * (index + np.uint64(1))) + attempt)


@njit(cache=True)
def uniform53(bits):
    """A uniform in (0, 1) from the top 53 of 64 bits (never 0, never 1)."""
    return (np.float64(bits >> _S11) + 0.5) * _TWO_M53


@njit(cache=True)
def _normal_slow(key, index, b, x_tab, f_tab):
    """The draws the first layer test rejects (1.2 %): the wedge or the tail, by rejection,
    starting from the bits ``b`` of attempt 0."""
    attempt = np.uint64(1)
    while True:
        i = np.int64(b & _MASK7)
        sign = 1.0 - 2.0 * np.float64((b & _BIT7) >> np.uint64(7))
        x = uniform53(b) * x_tab[i]
        if x < x_tab[i + 1]:  # inside the layer's rectangle under the curve
            return sign * x
        if i == 0:  # the tail beyond R (Marsaglia 1964): exact by rejection
            while True:
                u1 = uniform53(bits64(key, index, attempt))
                u2 = uniform53(bits64(key, index, attempt + np.uint64(1)))
                attempt += np.uint64(2)
                t = -math.log(u1) / x_tab[1]
                if -2.0 * math.log(u2) >= t * t:
                    return sign * (x_tab[1] + t)
        # the wedge between the rectangle and the curve
        y = f_tab[i] + uniform53(bits64(key, index, attempt)) * (f_tab[i + 1] - f_tab[i])
        attempt += np.uint64(1)
        if y < math.exp(-0.5 * x * x):
            return sign * x
        b = bits64(key, index, attempt)
        attempt += np.uint64(1)


@njit(cache=True)
def normal(key, index, x_tab, f_tab):
    """One standard normal deviate of (key, index) by the ziggurat (128 layers)."""
    b = bits64(key, index, _ZERO)
    i = np.int64(b & _MASK7)
    x = uniform53(b) * x_tab[i]
    if x < x_tab[i + 1]:
        return (1.0 - 2.0 * np.float64((b & _BIT7) >> np.uint64(7))) * x
    return _normal_slow(key, index, b, x_tab, f_tab)


@njit(cache=True)
def normal_row(key, base, out, x_tab, f_tab):
    """out[j] = the normal of (key, base + j): the layer test for every draw first (no call
    in the loop), then the rejected 1.2 % through :func:`_normal_slow`."""
    n = out.shape[0]
    slow = 0
    for j in range(n):
        b = bits64(key, base + np.uint64(j), _ZERO)
        i = np.int64(b & _MASK7)
        x = uniform53(b) * x_tab[i]
        ok = x < x_tab[i + 1]
        out[j] = (1.0 - 2.0 * np.float64((b & _BIT7) >> np.uint64(7))) * x if ok else np.nan
        slow += 0 if ok else 1
    if slow:
        for j in range(n):
            if out[j] != out[j]:
                idx = base + np.uint64(j)
                out[j] = _normal_slow(key, idx, bits64(key, idx, _ZERO), x_tab, f_tab)


@njit(cache=True, parallel=True)
def normal_plane(key, out, x_tab, f_tab):
    """Fill ``out`` (rows, cols) with standard normals of ``key``; draw (i, j) has the
    index i cols + j (the same numbers as :func:`normal`)."""
    rows, cols = out.shape
    for i in prange(rows):
        normal_row(key, np.uint64(i) * np.uint64(cols), out[i], x_tab, f_tab)


@njit(cache=True)
def normal_at(key, index, out, x_tab, f_tab):
    """out[k] = the normal of (key, index[k]) (uint64 indices; a few pixels: one thread)."""
    for k in range(index.shape[0]):
        out[k] = normal(key, index[k], x_tab, f_tab)
