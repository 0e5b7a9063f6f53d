"""numba kernels of the fused golden path: a method's frames in one pass (no input checks).

Row by row: the frame's coefficients into a row buffer (the stored ones copied, the
computed ones evaluated by :func:`coefs_row`: a method's ``MethodSpec.frame_expressions``,
compiled to integer tables by ``nuc_fixed.fused``), then per pixel the core of the method's
kind (:func:`core_sum`: lin, quad, pwl), the FFC term, ROUND_F and OUT (``_kernels``'
:func:`round_with` / :func:`out_with`, the datapath's own formulas without a branch, so the
loops over a row vectorize); then DPC of the bad pixels, the rounded mean of their good
neighbours (``_kernels.good_neighbours``, as ``_kernels.dpc_inplace``). All arithmetic is
int64, as the reference functions' numpy int64.

Tables:

* ``fields``: a tuple of ``fused.FIELD_SLOTS`` flat int64 arrays (n_pix,), the per-pixel
  codes the expressions read (the callers' arrays themselves where they are int64 and
  contiguous: no copy per call), padded with a one-element array;
* ``terms`` (n_terms, 3): field row (-1: the constant 1), factor, left shift (the
  factors of each frame in ``muls``, the rest shared by the frames of a call);
* ``coefs`` (n_coefs, 7): first term, end term, base field row (-1: none), round bits,
  rounding mode (0 floor, 1 half up, 2 half even), lower and upper clamp;
* ``direct`` (4,): per coefficient, the field row it is as stored (one term, nothing
  applied), else -1 (computed by :func:`coefs_row`).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from irnuc.nuc_fixed._kernels import good_neighbours, out_mask, out_with, round_consts, round_with


@njit(cache=True, inline="always")
def core_sum(kind, x, c0, c1, c2, c3, k0, k1, k2, k3, k4):
    """The aligned sum of the core of kind ``kind`` (0 lin, 1 quad, 2 pwl) on input ``x``
    with the pixel's coefficients ``c0..c3`` (``cores.CORE_INPUTS``) and the shifts
    ``k0..k4`` (``cores.kernel_shifts``).

    lin: (x*g << k0) + (o << k1); quad: + ((q * ((x*x) >> k2)) << k3) >> k4 (one of k3, k4
    is 0: the alignment of QPf to F); pwl: d = (x << k0) - (knee << k1), g = g_lo if
    d <= 0 else g_hi, (d*g << k2) + (level << k3).
    """
    if kind == 2:
        d = (x << k0) - (c2 << k1)
        g = c0 if d <= 0 else c1
        return ((d * g) << k2) + (c3 << k3)
    s = ((x * c0) << k0) + (c1 << k1)
    if kind == 1:
        s += ((c2 * ((x * x) >> k2)) << k3) >> k4
    return s


@njit(cache=True, inline="always")
def coefs_row(fields, p0, p1, terms, muls, coefs, direct, rowc):
    """The computed coefficients (``direct[j] < 0``) of the pixels p0 .. p1 - 1 into
    ``rowc`` (4, p1 - p0): CLAMP(base + ROUND_k(sum of field*mul << shift), lo, hi)
    (``muls``: the frame's factor of each term). Up to three field terms in one pass over
    the row (a missing one reads row 0 times 0; the constants summed first); more, a term
    at a time."""
    for j in range(coefs.shape[0]):
        if direct[j] >= 0:
            continue
        rc = rowc[j]
        t0, t1 = coefs[j, 0], coefs[j, 1]
        rb, lo, hi = coefs[j, 3], coefs[j, 5], coefs[j, 6]
        add, odd = round_consts(rb, coefs[j, 4])
        cst = np.int64(0)
        nf = 0
        for t in range(t0, t1):
            if terms[t, 0] < 0:
                cst += muls[t] << terms[t, 2]
            else:
                nf += 1
        base = fields[max(coefs[j, 2], 0)][p0:p1]
        bm = np.int64(1) if coefs[j, 2] >= 0 else np.int64(0)
        if nf <= 3:
            rows = np.zeros(3, np.int64)
            ms = np.zeros(3, np.int64)
            ss = np.zeros(3, np.int64)
            q = 0
            for t in range(t0, t1):
                if terms[t, 0] >= 0:
                    rows[q], ms[q], ss[q] = terms[t, 0], muls[t], terms[t, 2]
                    q += 1
            a0 = fields[rows[0]][p0:p1]
            a1 = fields[rows[1]][p0:p1]
            a2 = fields[rows[2]][p0:p1]
            m0, m1, m2, s0, s1, s2 = ms[0], ms[1], ms[2], ss[0], ss[1], ss[2]
            for i in range(rc.shape[0]):
                acc = (((a0[i] * m0) << s0) + ((a1[i] * m1) << s1) + ((a2[i] * m2) << s2)
                       + cst)
                rc[i] = min(max(round_with(acc, rb, add, odd) + bm * base[i], lo), hi)
            continue
        rc[:] = cst
        for t in range(t0, t1):
            row, mul, sh = terms[t, 0], muls[t], terms[t, 2]
            if row >= 0:
                src = fields[row][p0:p1]
                for i in range(rc.shape[0]):
                    rc[i] += (src[i] * mul) << sh
        for i in range(rc.shape[0]):
            rc[i] = min(max(round_with(rc[i], rb, add, odd) + bm * base[i], lo), hi)


@njit(cache=True, inline="always")
def _row_out(kind, xrow, orow, frow, rowc, xsh, d, k0, k1, k2, k3, k4, csh, frac, add, odd,
             mask, ymax):
    # One frame's row: OUT(ROUND_F(core sum + FFC term)) of input (x << xsh) - d.
    for i in range(xrow.shape[0]):
        s = core_sum(kind, (np.int64(xrow[i]) << xsh) - d, rowc[0, i], rowc[1, i], rowc[2, i],
                     rowc[3, i], k0, k1, k2, k3, k4)
        orow[i] = out_with(round_with(s + (frow[i] << csh), frac, add, odd), mask, ymax)


@njit(cache=True, inline="always")
def _row_sum(kind, xrow, srow, rowc, k0, k1, k2, k3, k4):
    for i in range(xrow.shape[0]):
        srow[i] = core_sum(kind, xrow[i], rowc[0, i], rowc[1, i], rowc[2, i], rowc[3, i], k0,
                           k1, k2, k3, k4)


@njit(cache=True, inline="always")
def _direct_row(fields, p0, p1, direct, rowc):
    for j in range(4):
        if direct[j] >= 0:
            rowc[j, :] = fields[direct[j]][p0:p1]


@njit(cache=True, parallel=True)
def method_frames(x, fields, terms, muls, new, coefs, direct, kind, k, delta, xsh, ffc, csh,
                  bad_idx, bad, width, frac, mode, wrap, ymax, out):
    """Correct the frames ``x`` (n, n_pix) into ``out`` (n, n_pix), DPC included, on frames
    of ``width`` columns. The frames share their tables but for the terms' factors
    ``muls`` (n, n_terms); ``new[f]``: frame f's differ from frame f - 1's (its computed
    coefficients are evaluated again).

    The input of the core is ``(x << xsh) - delta[f]`` (blind_drift: xsh = Df; else 0 and
    delta 0); ``ffc`` (n_pix,) is the FFC correction (zeros: none), added as
    ``ffc << csh``; ``k`` (5,) the core's shifts. One pass over the rows (each row's
    coefficients, then its outputs in every frame), then DPC of the bad pixels ``bad_idx``
    (flat indices of ``bad`` (n_pix,)): the rounded mean of the good in-frame neighbours,
    whose outputs are final.
    """
    n, n_pix = x.shape
    height = n_pix // width
    k0, k1, k2, k3, k4 = k[0], k[1], k[2], k[3], k[4]
    add, odd = round_consts(frac, mode)
    mask = out_mask(wrap, ymax)
    for row in prange(height):
        p0 = row * width
        p1 = p0 + width
        rowc = np.zeros((4, width), np.int64)
        _direct_row(fields, p0, p1, direct, rowc)
        frow = ffc[p0:p1]
        for f in range(n):
            if new[f]:
                coefs_row(fields, p0, p1, terms, muls[f], coefs, direct, rowc)
            xrow = x[f, p0:p1]
            orow = out[f, p0:p1]
            # The kind as a constant in each loop (the compiler drops the others' code).
            if kind == 0:
                _row_out(0, xrow, orow, frow, rowc, xsh, delta[f], k0, k1, k2, k3, k4, csh,
                         frac, add, odd, mask, ymax)
            elif kind == 1:
                _row_out(1, xrow, orow, frow, rowc, xsh, delta[f], k0, k1, k2, k3, k4, csh,
                         frac, add, odd, mask, ymax)
            else:
                _row_out(2, xrow, orow, frow, rowc, xsh, delta[f], k0, k1, k2, k3, k4, csh,
                         frac, add, odd, mask, ymax)
    _dpc(out, bad, bad_idx, height, width)


@njit(cache=True)
def _dpc(out, bad, bad_idx, height, width):
    # DPC of the bad pixels (a few per cent of a frame: one thread, no second parallel
    # region to wait for).
    n = out.shape[0]
    bad2 = bad.reshape(height, width)
    for b in range(bad_idx.shape[0]):
        p = bad_idx[b]
        row = p // width
        col = p - row * width
        for f in range(n):
            acc, cnt = good_neighbours(out[f].reshape(height, width), bad2, row, col)
            if cnt > 0:
                out[f, p] = (2 * acc + cnt) // (2 * cnt)


@njit(cache=True, parallel=True)
def method_sums(x, fields, terms, muls, coefs, direct, kind, k, width, s_out):
    """The core's aligned sum of every pixel of ``x`` (n_pix,) int64 into ``s_out[m]``
    (m, n_pix) with the terms' factors ``muls[m]`` (m, n_terms): the FFC mean and refresh
    passes on the accumulator (no FFC term, no drift), both in one parallel pass when
    their frames share the tables but for the factors (tc_offset's u, u²)."""
    k0, k1, k2, k3, k4 = k[0], k[1], k[2], k[3], k[4]
    for row in prange(x.shape[0] // width):
        p0 = row * width
        p1 = p0 + width
        rowc = np.zeros((4, width), np.int64)
        _direct_row(fields, p0, p1, direct, rowc)
        xrow = x[p0:p1]
        for m in range(muls.shape[0]):
            if m == 0 or (muls[m] != muls[m - 1]).any():
                coefs_row(fields, p0, p1, terms, muls[m], coefs, direct, rowc)
            srow = s_out[m, p0:p1]
            if kind == 0:
                _row_sum(0, xrow, srow, rowc, k0, k1, k2, k3, k4)
            elif kind == 1:
                _row_sum(1, xrow, srow, rowc, k0, k1, k2, k3, k4)
            else:
                _row_sum(2, xrow, srow, rowc, k0, k1, k2, k3, k4)


@njit(cache=True)
def accumulate(acc, x):
    """acc += x, element by element (the FFC accumulator; the caller checked the codes)."""
    a = acc.reshape(-1)
    b = x.reshape(-1)
    for i in range(a.shape[0]):
        a[i] += b[i]


@njit(cache=True)
def good_rounded_sum(s, lsh, k, mode, bad):
    """Sum and count over the good pixels of ROUND_k(s << lsh) (``s``, ``bad`` flat): the
    FFC mean pass's target before its division."""
    add, odd = round_consts(k, mode)
    total = np.int64(0)
    n = np.int64(0)
    for i in range(s.shape[0]):
        if not bad[i]:
            total += round_with(s[i] << lsh, k, add, odd)
            n += 1
    return total, n


@njit(cache=True)
def ffc_refresh_codes(s, t_sh, s_sh, k, mode, lo, hi, wrap, out):
    """``ffc_refresh`` of the sums ``s`` (flat): OVF_C(ROUND_k(t_sh - (s << s_sh))) into
    ``out``, with ``t_sh`` the target already shifted (saturate to [lo, hi] or wrap)."""
    add, odd = round_consts(k, mode)
    span = hi - lo + 1
    for i in range(s.shape[0]):
        r = round_with(t_sh - (s[i] << s_sh), k, add, odd)
        if wrap:
            out[i] = ((r - lo) & (span - 1)) + lo
        else:
            out[i] = min(max(r, lo), hi)
