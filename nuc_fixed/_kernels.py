"""numba kernels of the NUC and DPC datapaths (docs/datapath.md); no input checks here.

Every formula of the datapath is written once, as a scalar kernel:
:func:`round_code` (ROUND_F; :func:`round_with` with the constants of :func:`round_consts`
in a loop), :func:`out_code` (OUT, saturate or wrap; :func:`out_with`), :func:`nuc_pixel`
(the whole NUC of one pixel), :func:`field` (a coefficient-word field) and
:func:`good_neighbours` (the DPC neighbourhood). The array kernels loop over them; the
exact-arithmetic tests check these same functions. All arithmetic is int64. The API layer
(``nuc``, ``dpc``, ``top``, ``fixed``) validates the arguments and passes the constants in.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange


@njit(cache=True, inline="always")
def round_consts(frac, mode):
    """(add, odd) of ROUND_F with ``frac`` fraction bits in mode ``mode`` (0 floor, 1 half
    up, 2 half even): ROUND_F(s) = (s + add + ((s >> frac) & odd)) >> frac
    (:func:`round_with`). Floor adds nothing; half up adds half an LSB; half even adds
    half an LSB less one, plus one when the quotient is odd (a tie goes up to the even
    neighbour, any other fraction as half up). ``frac = 0`` is the identity in every mode.
    """
    if frac == 0 or mode == 0:
        return np.int64(0), np.int64(0)
    half = np.int64(1) << (frac - 1)
    if mode == 1:
        return half, np.int64(0)
    return half - 1, np.int64(1)


@njit(cache=True, inline="always")
def round_with(s, frac, add, odd):
    """ROUND_F(s) with the constants of :func:`round_consts` (no branch: a loop over
    pixels vectorizes)."""
    return (s + add + ((s >> frac) & odd)) >> frac


@njit(cache=True, inline="always")
def round_code(s, frac, mode):
    """ROUND_F(s): remove ``frac`` fraction bits; mode 0 floor, 1 half up, 2 half even.

    ``frac = 0`` is the identity in every mode.
    """
    add, odd = round_consts(frac, mode)
    return round_with(s, frac, add, odd)


@njit(cache=True, inline="always")
def out_mask(wrap, ymax):
    """The mask of :func:`out_with`: ymax = 2^B - 1 to wrap, all ones to saturate."""
    return ymax if wrap else np.int64(-1)


@njit(cache=True, inline="always")
def out_with(r, mask, ymax):
    """OUT(r) with the mask of :func:`out_mask`: the low B bits (wrap: then in range), then
    saturated to [0, ymax] (no branch)."""
    return min(max(r & mask, np.int64(0)), ymax)


@njit(cache=True, inline="always")
def out_code(r, wrap, ymax):
    """OUT(r): saturate to [0, ymax] or keep the low bits (ymax = 2^B - 1)."""
    return out_with(r, out_mask(wrap, ymax), ymax)


@njit(cache=True, inline="always")
def nuc_pixel(x, g, o, gsh, osh, frac, mode, wrap, ymax):
    """The NUC of one pixel: (p, s, r, y) of docs/datapath.md."""
    p = x * g
    s = (p << gsh) + (o << osh)
    r = round_code(s, frac, mode)
    return p, s, r, out_code(r, wrap, ymax)


@njit(cache=True, inline="always")
def field(word, lsb, width, signed):
    """Field ``[lsb + width - 1 : lsb]`` of a coefficient word, sign-extended if ``signed``."""
    v = (word >> lsb) & ((np.int64(1) << width) - 1)
    if signed:
        sign = np.int64(1) << (width - 1)
        v = (v ^ sign) - sign
    return v


@njit(cache=True, inline="always")
def good_neighbours(vals, bad, row, c):
    """Sum and count of the good in-frame 8-neighbours of (row, c) (no padding)."""
    h, w = bad.shape
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
            acc += np.int64(vals[rr, cc])
            n += 1
    return acc, n


@njit(cache=True)
def round_codes(s, frac, mode, out):
    """:func:`round_code` of every element of the int64 array ``s`` into ``out``."""
    flat_s = s.ravel()
    flat_o = out.ravel()
    for i in range(flat_s.size):
        flat_o[i] = round_code(flat_s[i], frac, mode)


@njit(cache=True)
def round_out_codes(s, frac, mode, wrap, ymax, r_out, y_out):
    """ROUND_F then OUT of every element of the int64 array ``s`` (the methods' cores)."""
    flat_s = s.ravel()
    flat_r = r_out.ravel()
    flat_y = y_out.ravel()
    for i in range(flat_s.size):
        r = round_code(flat_s[i], frac, mode)
        flat_r[i] = r
        flat_y[i] = out_code(r, wrap, ymax)


@njit(cache=True, parallel=True)
def nuc_flat(x, g, o, out, gsh, osh, frac, mode, wrap, ymax):
    """NUC of ``x`` (n_frames, n_pix) with per-pixel ``g``, ``o`` (n_pix,) into ``out``."""
    n_frames, n_pix = x.shape
    for i in prange(n_pix):
        gi = np.int64(g[i])
        oi = np.int64(o[i])
        for f in range(n_frames):
            out[f, i] = nuc_pixel(np.int64(x[f, i]), gi, oi, gsh, osh, frac, mode, wrap,
                                  ymax)[3]


@njit(cache=True, parallel=True)
def nuc_flat_intermediates(x, g, o, p, s, r, y, gsh, osh, frac, mode, wrap, ymax):
    """As :func:`nuc_flat`, also storing the product p, aligned sum s and rounded r."""
    n_frames, n_pix = x.shape
    for i in prange(n_pix):
        gi = np.int64(g[i])
        oi = np.int64(o[i])
        for f in range(n_frames):
            p[f, i], s[f, i], r[f, i], y[f, i] = nuc_pixel(np.int64(x[f, i]), gi, oi, gsh, osh,
                                                           frac, mode, wrap, ymax)


@njit(cache=True, parallel=True)
def dpc_inplace(out, bad):
    """Replace the bad pixels of ``out`` (N, H, W) by the rounded mean of good neighbours.

    In place is exact: a replacement reads only good pixels, which are never written.
    """
    n_frames, h, w = out.shape
    for k in prange(n_frames * h):
        f = k // h
        row = k - f * h
        frame = out[f]
        for c in range(w):
            if bad[row, c]:
                acc, n = good_neighbours(frame, bad, row, c)
                if n > 0:
                    frame[row, c] = (2 * acc + n) // (2 * n)


@njit(cache=True, parallel=True)
def neighbour_counts(bad, counts):
    """Number of good in-frame neighbours of every pixel of ``bad`` (H, W) into ``counts``."""
    h, w = bad.shape
    for row in prange(h):
        for c in range(w):
            counts[row, c] = good_neighbours(bad, bad, row, c)[1]


@njit(cache=True, parallel=True)
def nuc_words(raw, words, out, gain_f, offset_f, gsh, osh, frac, mode, wrap, ymax):
    """NUC of ``raw`` (N, H, W) with coefficient words (H, W) into ``out``.

    ``gain_f`` and ``offset_f`` are the (lsb, width) of the word fields.
    """
    n_frames, h, w = raw.shape
    for k in prange(n_frames * h):
        f = k // h
        row = k - f * h
        for c in range(w):
            wd = np.int64(words[row, c])
            g = field(wd, gain_f[0], gain_f[1], False)
            o = field(wd, offset_f[0], offset_f[1], True)
            out[f, row, c] = nuc_pixel(np.int64(raw[f, row, c]), g, o, gsh, osh, frac, mode,
                                       wrap, ymax)[3]
