"""numba kernels of the NUC and DPC datapaths (docs/datapath.md); no input checks here.

All arithmetic is int64. The API layer (``nuc_fixed.nuc``, ``nuc_fixed.dpc``,
``nuc_fixed.top``) validates the arguments and passes the derived constants in.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange


@njit(cache=True, inline="always")
def _round_sat(s, frac, mode, half, wrap, ymax):
    # mode: 0 floor, 1 half up, 2 half even; the caller maps F = 0 to mode 0 (identity).
    if mode == 0:
        r = s >> frac
    elif mode == 1:
        r = (s + half) >> frac
    else:
        r = (s + half - 1 + ((s >> frac) & 1)) >> frac
    if wrap:
        y = r & ymax
    elif r < 0:
        y = np.int64(0)
    elif r > ymax:
        y = ymax
    else:
        y = r
    return r, y


@njit(cache=True, inline="always")
def _nuc_pixel(x, g, o, gsh, osh, frac, mode, half, wrap, ymax):
    s = ((x * g) << gsh) + (o << osh)
    return _round_sat(s, frac, mode, half, wrap, ymax)[1]


@njit(cache=True, parallel=True)
def nuc_flat(x, g, o, out, gsh, osh, frac, mode, half, wrap, ymax):
    """NUC of ``x`` (n_frames, n_pix) with per-pixel ``g``, ``o`` (n_pix,) into ``out``."""
    n_frames, n_pix = x.shape
    for i in prange(n_pix):
        gi = np.int64(g[i])
        oi = np.int64(o[i])
        for f in range(n_frames):
            out[f, i] = _nuc_pixel(np.int64(x[f, i]), gi, oi, gsh, osh, frac, mode, half, wrap,
                                   ymax)


@njit(cache=True, parallel=True)
def nuc_flat_intermediates(x, g, o, p, s, r, y, gsh, osh, frac, mode, half, wrap, ymax):
    """As :func:`nuc_flat`, also storing the product p, aligned sum s and rounded r."""
    n_frames, n_pix = x.shape
    for i in prange(n_pix):
        gi = np.int64(g[i])
        oi = np.int64(o[i])
        for f in range(n_frames):
            pv = np.int64(x[f, i]) * gi
            sv = (pv << gsh) + (oi << osh)
            rv, yv = _round_sat(sv, frac, mode, half, wrap, ymax)
            p[f, i] = pv
            s[f, i] = sv
            r[f, i] = rv
            y[f, i] = yv


@njit(cache=True, parallel=True)
def dpc_inplace(out, bad):
    """Replace the bad pixels of ``out`` (N, H, W) by the rounded mean of good neighbours.

    In place is exact: a replacement reads only good pixels, which are never written.
    """
    n_frames, h, w = out.shape
    for k in prange(n_frames * h):
        f = k // h
        row = k - f * h
        for c in range(w):
            if bad[row, c]:
                acc = np.int64(0)
                n = np.int64(0)
                for dr in range(-1, 2):
                    rr = row + dr
                    if rr < 0 or rr >= h:
                        continue
                    for dc in range(-1, 2):
                        cc = c + dc
                        if cc < 0 or cc >= w or (dr == 0 and dc == 0) or bad[rr, cc]:
                            continue
                        acc += np.int64(out[f, rr, cc])
                        n += 1
                if n > 0:
                    out[f, row, c] = (2 * acc + n) // (2 * n)


@njit(cache=True, parallel=True)
def top_frames(raw, words, out, gw, gmask, ow, omask, osign, bshift,
               gsh, osh, frac, mode, half, wrap, ymax):
    """NUC + DPC of ``raw`` (N, H, W) with coefficient words (H, W) into ``out``.

    One pass: a bad pixel recomputes the NUC of its good neighbours (a pure function of
    their raw code and word), so rows are independent and run in parallel.
    """
    n_frames, h, w = raw.shape
    for k in prange(n_frames * h):
        f = k // h
        row = k - f * h
        for c in range(w):
            wd = np.int64(words[row, c])
            if (wd >> bshift) & 1:
                acc = np.int64(0)
                n = np.int64(0)
                for dr in range(-1, 2):
                    rr = row + dr
                    if rr < 0 or rr >= h:
                        continue
                    for dc in range(-1, 2):
                        cc = c + dc
                        if cc < 0 or cc >= w or (dr == 0 and dc == 0):
                            continue
                        wn = np.int64(words[rr, cc])
                        if (wn >> bshift) & 1:
                            continue
                        on = (((wn >> gw) & omask) ^ osign) - osign
                        acc += _nuc_pixel(np.int64(raw[f, rr, cc]), wn & gmask, on, gsh, osh,
                                          frac, mode, half, wrap, ymax)
                        n += 1
                if n > 0:
                    out[f, row, c] = (2 * acc + n) // (2 * n)
                    continue
            o = (((wd >> gw) & omask) ^ osign) - osign
            out[f, row, c] = _nuc_pixel(np.int64(raw[f, row, c]), wd & gmask, o, gsh, osh, frac,
                                        mode, half, wrap, ymax)
