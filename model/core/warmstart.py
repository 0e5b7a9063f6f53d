"""Kernels of the predicted (warm-started) electro-thermal solve and of the thermal memory.

The steady solve of :mod:`model.core.bolometer` finds, per pixel, the root x = dT of

    h(x) = x - a - b R(T_s + x),   a = Q f_Q / g,   b = I^2 f / g

by a safeguarded Newton iteration that starts from a neighbour's solution. A configured
sensor solves the same pixels frame after frame, and its pixels differ from frame to frame
only by the scene power and the substrate temperature. So each pixel keeps one converged
*reference* solution (x_r, R_r at a_r, T_r) and a new solve starts from its first-order
prediction: with D = b R B / T^2 = -b dR/dT at the reference (D > 0 for B > 0),

    x0 = x_r + (a - a_r) / (1 + D) - D (T_s - T_r) / (1 + D)

and e0 = R(T_s + x0) / R_ref = e_r exp(B (1/(T_s + x0) - 1/(T_r + x_r))), by the small-
argument series of :func:`model.core.bolometer.exp_small` when the prediction is close. The
same safeguarded Newton iteration (:func:`model.core.bolometer.newton_negative_tcr_warm`)
then runs to the same tolerance, usually in one step and without a call to ``exp``; the
start point only decides how many steps it takes, never the tolerance. Every start is a
function of the pixel's own inputs and the fixed reference, so the result does not depend
on what was solved before. Positive-TCR pixels, and pixels whose reference solve failed,
take the bracketed solver of :func:`model.core.bolometer.solve_delta_t`, as before.

The thermal memory kernels advance the pixel's pre-pulse temperature rise between frames
by the exact solution of the unbiased heat balance C dtheta/dt = Q - g theta.
"""

import math

import numpy as np
from numba import njit, prange

from irnuc.model.core.bolometer import (
    STATUS_INVALID,
    STATUS_OK,
    STATUS_RUNAWAY,
    exp_small,
    newton_negative_tcr_warm,
    resistance,
    self_heating_factor,
    solve_delta_t,
)
from irnuc.model.core.transient import relax


@njit(cache=True)
def coefficients(g, C, I, t_int, variant, fq_out, b_out):
    """Per-pixel coefficients of the solve: f_Q (1; written only for the ``paper`` variant,
    1 otherwise) and b = I^2 f / g (K/ohm).

    The same expressions, in the same order, as :func:`model.core.bolometer.solve_row`, so
    a = Q f_Q (1/g) and b carry the same bits.
    """
    rows, cols = g.shape
    for i in range(rows):
        for j in range(cols):
            gj = g[i, j]
            inv_g = 1.0 / gj
            f = self_heating_factor(t_int * gj / C[i, j])
            if variant == 1:
                fq_out[i, j] = f
            b_out[i, j] = I * I * f * inv_g


@njit(cache=True)
def _rise(Q, fq, g, i, j, variant):
    """a = Q f_Q / g (K) of pixel (i, j) with the rounding of
    :func:`model.core.bolometer.solve_row` (``fq`` is read only for the paper variant)."""
    inv_g = 1.0 / g[i, j]
    return Q * (fq[i, j] if variant == 1 else 1.0) * inv_g


@njit(cache=True)
def reference_state(Q, fq, g, variant, b, R_ref, B, T_s, dT, v, status, I, c_out, s_out,
                    ds_out, e_out, inv_T_out):
    """Predictor of every pixel from a converged solve at substrate temperature T_s (K).

    Q (W), dT (K), v (V) and status: (rows, cols) of the reference solve. Writes (float32)
    s = 1/(1 + D), ds = D/(1 + D), c = x - s a - ds T_s so that the prediction is
    x0 = c + s a - ds T_s', and (float64) e = R/R_ref and 1/T (1/K) of the reference, e
    NaN where the pixel is not predicted (positive TCR, no bias, a failed reference solve).
    """
    rows, cols = Q.shape
    for i in range(rows):
        for j in range(cols):
            x = dT[i, j]
            bb = b[i, j]
            e = math.nan
            s = 0.0
            ds = 0.0
            c = 0.0
            if status[i, j] == STATUS_OK and B > 0.0 and bb > 0.0 and I > 0.0:
                T = T_s + x
                R = v[i, j] / I
                D = bb * R * B / (T * T)
                if math.isfinite(D) and R > 0.0:
                    s = 1.0 / (1.0 + D)
                    ds = D / (1.0 + D)
                    c = x - s * _rise(Q[i, j], fq, g, i, j, variant) + ds * T_s
                    e = R / R_ref[i, j]
            c_out[i, j] = c
            inv_T_out[i, j] = 1.0 / (T_s + x)
            s_out[i, j] = s
            ds_out[i, j] = ds
            e_out[i, j] = e


@njit(cache=True)
def exp_near(z):
    """e^z for the tiny exponents of a converged Newton step: 1 + z + z^2/2 when
    |z| < 2e-6 (relative error below z^3/6 < 1.4e-18), else
    :func:`model.core.bolometer.exp_small`."""
    if abs(z) < 2e-6:
        return 1.0 + z * (1.0 + 0.5 * z)
    return exp_small(z)


@njit(cache=True)
def _first_step(a, b, R_ref, B, Ts, rtol, x0, e_r, inv_Tr):
    """The first Newton step from the prediction x0 (K), with the convergence test of
    :func:`model.core.bolometer.newton_negative_tcr_warm`.

    e_r = R/R_ref at the reference temperature 1/inv_Tr (K) gives R(T_s + x0) without a
    fresh exponential. Returns (done, x, R): done when the step met the tolerance (x is
    then the root, R its resistance, ohm); otherwise x and R are the step's result for
    the full iteration to go on from, x NaN if the step left the bracket (a, inf).
    """
    atol = rtol * 1e-3
    T = Ts + x0
    inv_T = 1.0 / T
    R = R_ref * (e_r * exp_near(B * (inv_T - inv_Tr)))
    h = x0 - a - b * R
    bRB = b * R * B * inv_T * inv_T  # -d(b R)/dT > 0
    dh = 1.0 + bRB
    inv_dh = 1.0 / dh
    step = h * inv_dh
    xn = x0 - step
    if not (xn > a and (h <= 0.0 or xn < x0)):  # the bracket of the full iteration
        return False, math.nan, R
    tol = rtol * abs(xn) + atol
    done = abs(step) <= tol
    if not done and abs(step) < 1e-4 * (abs(x0) + 1.0):
        K = abs(bRB * (B * inv_T + 2.0) * inv_T) * 0.5 * inv_dh
        done = K * step * step <= 0.01 * tol
    # 1/(T (T - step)) = inv_T^2 (1 + step inv_T) to a relative (step/T)^2: R at xn.
    z = B * step * inv_T * inv_T * (1.0 + step * inv_T)
    return done, xn, R * exp_near(z)


@njit(cache=True)
def _solve_pixel(a, b, R_ref, B, T_ref, Ts, rtol, max_iter, T_max, I, x0, e_r, inv_Tr):
    """One pixel: (x, v, status, iterations) from the prediction x0, or the bracketed
    solver when the pixel has no reference (e_r NaN)."""
    st = STATUS_OK
    if e_r > 0.0 and Ts + a > 0.0 and Ts + x0 > 0.0:
        done, x, R = _first_step(a, b, R_ref, B, Ts, rtol, x0, e_r, inv_Tr)
        it = 1
        if not done:
            # Go on from the step (or from the prediction, if the step left the bracket).
            start = x if math.isfinite(x) else x0
            e_start = R / R_ref if math.isfinite(x) else math.nan
            x, st, it, R = newton_negative_tcr_warm(a, b, R_ref, B, T_ref, Ts, rtol, max_iter,
                                                    start, e_start)
            it += 1
        v = I * R
    else:
        x, st, it = solve_delta_t(a, b, R_ref, B, T_ref, Ts, rtol, max_iter, math.nan, T_max)
        if st == STATUS_INVALID:
            v = math.nan
        else:
            v = I * resistance(Ts + x, R_ref, B, T_ref)
    if st == STATUS_OK and not Ts + x <= T_max:
        st = STATUS_RUNAWAY  # hotter than the runaway limit: not OK (as solve_row)
    return x, v, st, it


#: Largest |exponent| the branch-free path evaluates by its polynomial: the degree-9
#: Taylor polynomial of e^z has a relative error below |z|^10/10! < 2.6e-19 there.
POLY_EXP_MAX = 1.0 / 16.0


@njit(cache=True, error_model="numpy")
def _exp_poly(z):
    """e^z by its degree-9 Taylor polynomial (Horner), for |z| <= POLY_EXP_MAX."""
    p = 1.0 / 362880.0
    p = p * z + 1.0 / 40320.0
    p = p * z + 1.0 / 5040.0
    p = p * z + 1.0 / 720.0
    p = p * z + 1.0 / 120.0
    p = p * z + 1.0 / 24.0
    p = p * z + 1.0 / 6.0
    p = p * z + 0.5
    p = p * z + 1.0
    return p * z + 1.0


@njit(cache=True, error_model="numpy")
def _newton_lane(x, a, b, R, B, Ts, rtol, atol):
    """One Newton step of h(x) = x - a - b R(T_s + x) at x (K) with R = R(T_s + x) (ohm),
    and the convergence test of :func:`model.core.bolometer.newton_negative_tcr_warm`.

    Returns (xn, R(T_s + xn), converged, exponent of the R update).
    """
    T = Ts + x
    inv_T = 1.0 / T
    h = x - a - b * R
    bRB = b * R * B * inv_T * inv_T  # -d(b R)/dT > 0
    dh = 1.0 + bRB
    inv_dh = 1.0 / dh
    step = h * inv_dh
    xn = x - step
    tol = rtol * abs(xn) + atol
    K = abs(bRB * (B * inv_T + 2.0) * inv_T) * 0.5 * inv_dh
    conv = (abs(step) <= tol) | ((abs(step) < 1e-4 * (abs(x) + 1.0))
                                 & (K * step * step <= 0.01 * tol))
    # 1/(T (T - step)) = inv_T^2 (1 + step inv_T + ...): R at xn.
    z = B * step * inv_T * inv_T * (1.0 + step * inv_T + (step * inv_T) ** 2)
    return xn, R * _exp_poly(z), conv, z


@njit(cache=True, error_model="numpy")
def _predict_row(src, p1, p2, R_ref, b, B, Ts, rtol, T_max, inv_Tr, e_r, c_r, s_r, ds_r,
                 x_out, R_out, done_out):
    """Prediction and up to two Newton steps of one row, a = src p1 p2 (K), written without
    branches (and with IEEE division, ``error_model='numpy'``) so that the compiler
    vectorizes it. ``done_out`` (the Newton steps taken, 0 for none) marks the pixels
    that met the tolerance with every
    exponent inside the polynomial's range and the iterate inside the bracket (a, inf);
    the others are solved again by :func:`_solve_pixel`."""
    atol = rtol * 1e-3
    for j in range(x_out.shape[0]):
        a = src[j] * p1[j] * p2[j]
        x0 = np.float64(c_r[j]) + np.float64(s_r[j]) * a - np.float64(ds_r[j]) * Ts
        T0 = Ts + x0
        z0 = B * (1.0 / T0 - inv_Tr[j])
        R0 = R_ref[j] * (e_r[j] * _exp_poly(z0))
        bb = b[j]
        x1, R1, c1, z1 = _newton_lane(x0, a, bb, R0, B, Ts, rtol, atol)
        x2, R2, c2, z2 = _newton_lane(x1, a, bb, R1, B, Ts, rtol, atol)
        # For h concave and increasing, every Newton step lands at or left of the root:
        # after the first one the iteration climbs to it and stays in the bracket.
        valid = ((abs(z0) <= POLY_EXP_MAX) & (abs(z1) <= POLY_EXP_MAX) & (e_r[j] > 0.0)
                 & (Ts + a > 0.0) & (T0 > 0.0) & (x1 > a))
        x = x1 if c1 else x2
        ok = valid & (c1 | ((abs(z2) <= POLY_EXP_MAX) & c2)) & (Ts + x <= T_max)
        x_out[j] = x
        R_out[j] = R1 if c1 else R2
        done_out[j] = (1 if c1 else 2) if ok else 0


@njit(cache=True, error_model="numpy")
def _row_scale(g, fq, variant, use_A, p1, p2):
    """p1 = f_Q, p2 = 1/g of one row (both 1 when the rise is given directly)."""
    for j in range(p1.shape[0]):
        p1[j] = 1.0 if use_A or variant != 1 else fq[j]
        p2[j] = 1.0 if use_A else 1.0 / g[j]


@njit(cache=True, parallel=True)
def solve_frames_predicted(Q, A, use_A, R_ref, g, fq, variant, b, B, T_ref, T_s, I, rtol,
                           max_iter, T_max, inv_Tr, e_r, c_r, s_r, ds_r,
                           dT_out, v_out, status_out, iters_out):
    """Solve (N, rows, cols) pixels from their reference predictions.

    Q (N, rows, cols) absorbed power, W, gives a = Q f_Q / g; with ``use_A`` the rise a (K)
    is given directly in A (the thermal-memory model) and Q is not read. T_s (N,) is the
    substrate temperature of each frame, K. Per-pixel maps (rows, cols): R_ref, g, fq and
    b of :func:`coefficients`; inv_Tr, e_r, c_r, s_r, ds_r of :func:`reference_state`.
    Writes dT (K), v = I R (V), status and iterations.

    Each row first takes the branch-free path (:func:`_predict_row`); a pixel it leaves
    undone (a prediction far from the reference, a step short of the tolerance, no
    reference) is solved by :func:`_solve_pixel`, to the same tolerance.
    """
    n_frames, rows, cols = dT_out.shape
    fq_row = fq.shape[0] > 1
    for k in prange(n_frames * rows):
        n = k // rows
        i = k - n * rows
        Ts = T_s[n]
        R_row = np.empty(cols)
        p1 = np.empty(cols)
        p2 = np.empty(cols)
        done = np.empty(cols, np.uint8)
        _row_scale(g[i], fq[i] if fq_row else fq[0], variant, use_A, p1, p2)
        _predict_row(A[n, i] if use_A else Q[n, i], p1, p2, R_ref[i], b[i], B, Ts, rtol,
                     T_max, inv_Tr[i], e_r[i], c_r[i], s_r[i], ds_r[i], dT_out[n, i], R_row,
                     done)
        for j in range(cols):
            if done[j]:
                v_out[n, i, j] = I * R_row[j]
                status_out[n, i, j] = STATUS_OK
                iters_out[n, i, j] = done[j]
                continue
            if use_A:
                a = A[n, i, j]
            else:
                a = _rise(Q[n, i, j], fq, g, i, j, variant)
            x0 = np.float64(c_r[i, j]) + np.float64(s_r[i, j]) * a - np.float64(ds_r[i, j]) * Ts
            x, v, st, it = _solve_pixel(a, b[i, j], R_ref[i, j], B, T_ref, Ts, rtol, max_iter,
                                        T_max, I, x0, e_r[i, j], inv_Tr[i, j])
            dT_out[n, i, j] = x
            v_out[n, i, j] = v
            status_out[n, i, j] = st
            iters_out[n, i, j] = it


@njit(cache=True, parallel=True)
def lagged_rise(Q, g, decay, T_s, T_prev, theta_prev, has_prev, theta_out):
    """Pre-pulse rise theta (K) of each frame through the unbiased heat balance.

    Between two pulses (one frame period apart) a pixel relaxes towards Q/g with its own
    time constant C/g: theta_n = Q_n/g + (theta_{n-1} + T_s,{n-1} - T_s,n - Q_n/g) d,
    d = exp(-period g / C) per pixel (``decay``). The substrate steps at the frame start
    and the pixel temperature is continuous across it, as in :mod:`model.core.transient`.
    Without a previous state (``has_prev`` false) the first frame starts in equilibrium.
    Q (N, rows, cols) W; theta_prev (rows, cols) K and T_prev (K) the state before frame 0;
    writes theta_out (N, rows, cols) K and returns nothing (the caller keeps the last frame).
    """
    n_frames, rows, cols = Q.shape
    for i in prange(rows):
        for j in range(cols):
            ig = 1.0 / g[i, j]
            d = decay[i, j]
            th = theta_prev[i, j]
            Tp = T_prev
            start = has_prev
            for n in range(n_frames):
                eq = Q[n, i, j] * 1.0 * ig
                if start:
                    th = eq + (th + (Tp - T_s[n]) - eq) * d
                else:
                    th = eq
                    start = True
                Tp = T_s[n]
                theta_out[n, i, j] = th


@njit(cache=True, parallel=True)
def carry_theta(theta_end, Q, g, C, after, Ts_last, Ts_next, failed, out):
    """Rise at the start of the next frame from the rise at the end of a pulse (K).

    Relaxes over ``after`` seconds (the rest of the frame), then the substrate step from
    Ts_last to Ts_next: the same operations as :func:`model.core.transient.integrate_frames`
    between two frames, so a sequence split into chunks gives the same bits. A failed pixel
    restarts from 0 (its frames are railed; the caller keeps its status).
    """
    for p in prange(theta_end.shape[0]):
        if failed[p]:
            out[p] = 0.0
        else:
            th = relax(theta_end[p], Q[p], g[p], C[p], after)
            out[p] = th + (Ts_last - Ts_next)


def empty_solution(shape):
    """Outputs (dT, v, status, iterations) of :func:`solve_frames_predicted`."""
    return (np.empty(shape), np.empty(shape), np.empty(shape, np.uint8),
            np.empty(shape, np.int32))
