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
    ROOT_ATOL,
    STATUS_INVALID,
    STATUS_OK,
    STATUS_RUNAWAY,
    exp_small,
    newton_negative_tcr_warm,
    resistance,
    self_heating_factor,
    solve_delta_t,
)
from irnuc.model.core.transient import relax_ramp


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
            inv_T_out[i, j] = 1.0 / (T_s + x) if T_s + x > 0.0 else math.nan
            s_out[i, j] = s
            ds_out[i, j] = ds
            e_out[i, j] = e


@njit(cache=True)
def _solve_pixel(a, b, R_ref, B, T_ref, Ts, rtol, max_iter, T_max, I, x0, e_r, inv_Tr):
    """One pixel the branch-free path left: the safeguarded Newton iteration of
    :func:`model.core.bolometer.newton_negative_tcr_warm` from the prediction x0 (K) and
    R(T_s + x0)/R_ref from the reference, or the bracketed solver of
    :func:`model.core.bolometer.solve_delta_t` when the pixel has no reference (e_r NaN).
    Returns (x, v, status, iterations)."""
    st = STATUS_OK
    if e_r > 0.0 and Ts + a > 0.0 and Ts + x0 > 0.0:
        e0 = e_r * exp_small(B * (1.0 / (Ts + x0) - inv_Tr))
        x, st, it, R = newton_negative_tcr_warm(a, b, R_ref, B, T_ref, Ts, rtol, max_iter, x0,
                                                e0)
        v = I * R
    else:
        x, st, it = solve_delta_t(a, b, R_ref, B, T_ref, Ts, rtol, max_iter, math.nan, T_max)
        if st == STATUS_INVALID:
            v = 0.0  # at 0 K, where it fell (as solve_row)
        else:
            v = I * resistance(Ts + x, R_ref, B, T_ref)
    if st == STATUS_OK and not Ts + x <= T_max:
        st = STATUS_RUNAWAY  # hotter than the runaway limit: not OK (as solve_row)
    return x, v, st, it


#: Largest |exponent| the branch-free path evaluates by its polynomial: the degree-9
#: Taylor polynomial of e^z has a relative error below |z|^10/10! < 2.6e-19 there.
POLY_EXP_MAX = 1.0 / 16.0


@njit(cache=True, error_model="numpy", fastmath={"contract"})
def _exp_poly(z):
    """e^z by its degree-9 Taylor polynomial (Horner), for |z| <= POLY_EXP_MAX (a multiply
    and an add may fuse: ``contract``, no other fast-math liberty)."""
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


#: Largest |exponent| of a Newton step's resistance update by the degree-4 polynomial
#: (relative error below |z|^5/120 < 1e-17).
STEP_EXP_MAX = 1e-3


@njit(cache=True, error_model="numpy")
def _newton_lane(x, inv_T, a, b, R, B, rtol, atol):
    """One Newton step of h(x) = x - a - b R(T_s + x) at x (K), with inv_T = 1/(T_s + x)
    and R = R(T_s + x) (ohm), and the convergence test of
    :func:`model.core.bolometer.newton_negative_tcr_warm`.

    Returns (xn, R(T_s + xn), 1/(T_s + xn), converged, exponent of the R update).
    """
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
    # 1/T_n = 1/(T - step) = inv_T / (1 - step inv_T); R at xn from exp(B (1/T_n - 1/T)).
    u = step * inv_T
    inv_Tn = inv_T / (1.0 - u)
    z = B * u * inv_Tn
    E = 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z * (1.0 / 24.0))))
    return xn, R * E, inv_Tn, conv, z


#: ``done`` codes of :func:`_predict_row`: not taken (solve the pixel again), or the Newton
#: steps taken; PENDING: valid after one step, but not yet converged.
PENDING = 3


@njit(cache=True, error_model="numpy")
def _predict_row(src, p1, p2, R_ref, b, B, Ts, rtol, T_max, inv_Tr, e_r, c_r, s_r, ds_r,
                 x_out, R_out, inv_T, done_out):
    """Prediction and up to two Newton steps of one row, a = src p1 p2 (K), written without
    branches (and with IEEE division, ``error_model='numpy'``) so that the compiler
    vectorizes it; the second step only when some pixel of the row needs it. ``done_out``
    (the Newton steps taken, 0 for none) marks the pixels that met the tolerance with
    every exponent inside its polynomial's range and the iterate inside the bracket
    (a, inf); the others are solved again by :func:`_solve_pixel`. ``inv_T``: scratch."""
    atol = ROOT_ATOL
    pending = 0
    for j in range(x_out.shape[0]):
        a = src[j] * p1[j] * p2[j]
        x0 = np.float64(c_r[j]) + np.float64(s_r[j]) * a - np.float64(ds_r[j]) * Ts
        T0 = Ts + x0
        inv_T0 = 1.0 / T0
        z0 = B * (inv_T0 - inv_Tr[j])
        R0 = R_ref[j] * (e_r[j] * _exp_poly(z0))
        x1, R1, inv_T1, c1, z1 = _newton_lane(x0, inv_T0, a, b[j], R0, B, rtol, atol)
        # For h concave and increasing, every Newton step lands at or left of the root:
        # after the first one the iteration climbs to it and stays in the bracket.
        valid = ((abs(z0) <= POLY_EXP_MAX) & (abs(z1) <= STEP_EXP_MAX) & (e_r[j] > 0.0)
                 & (Ts + a > 0.0) & (T0 > 0.0) & (x1 > a))
        x_out[j] = x1
        R_out[j] = R1
        inv_T[j] = inv_T1
        code = (1 if Ts + x1 <= T_max else 0) if c1 else PENDING
        done_out[j] = code if valid else 0
        pending += 1 if valid and not c1 else 0
    if pending == 0:
        return
    for j in range(x_out.shape[0]):
        a = src[j] * p1[j] * p2[j]
        x2, R2, _, c2, z2 = _newton_lane(x_out[j], inv_T[j], a, b[j], R_out[j], B, rtol, atol)
        ok = c2 & (abs(z2) <= STEP_EXP_MAX) & (Ts + x2 <= T_max)
        second = done_out[j] == PENDING
        x_out[j] = x2 if second else x_out[j]
        R_out[j] = R2 if second else R_out[j]
        done_out[j] = (2 if ok else 0) if second else done_out[j]


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
    # Row by row, all frames of the chunk: a row's per-pixel maps stay in cache.
    for i in prange(rows):
        R_row = np.empty(cols)
        inv_T = np.empty(cols)
        p1 = np.empty(cols)
        p2 = np.empty(cols)
        done = np.empty(cols, np.uint8)
        _row_scale(g[i], fq[i] if fq_row else fq[0], variant, use_A, p1, p2)
        for n in range(n_frames):
            Ts = T_s[n]
            _predict_row(A[n, i] if use_A else Q[n, i], p1, p2, R_ref[i], b[i], B, Ts, rtol,
                         T_max, inv_Tr[i], e_r[i], c_r[i], s_r[i], ds_r[i], dT_out[n, i],
                         R_row, inv_T, done)
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
                x0 = (np.float64(c_r[i, j]) + np.float64(s_r[i, j]) * a
                      - np.float64(ds_r[i, j]) * Ts)
                x, v, st, it = _solve_pixel(a, b[i, j], R_ref[i, j], B, T_ref, Ts, rtol,
                                            max_iter, T_max, I, x0, e_r[i, j], inv_Tr[i, j])
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
        th = theta_prev[i].copy()
        for n in range(n_frames):
            start = has_prev or n > 0
            dTs = (T_prev - T_s[0]) if n == 0 else (T_s[n - 1] - T_s[n])
            for j in range(cols):
                eq = Q[n, i, j] * 1.0 * (1.0 / g[i, j])
                if start:
                    th[j] = eq + (th[j] + dTs - eq) * decay[i, j]
                else:
                    th[j] = eq
                theta_out[n, i, j] = th[j]


@njit(cache=True, parallel=True)
def relax_after_pulse(theta_end, Q, g, C, after, rate, failed, out):
    """Rise (K) at the end of a frame from the rise at the end of its pulse (relative to the
    substrate at mid-pulse): the unbiased relaxation over ``after`` seconds while the
    substrate warms at ``rate`` K/s (:func:`model.core.transient.relax_ramp`), the operation
    :func:`model.core.transient.integrate_frames` does at the end of a frame, so a sequence
    split into chunks gives the same bits. A failed pixel restarts from 0 (its frames are
    railed; the caller keeps its status)."""
    for p in prange(theta_end.shape[0]):
        out[p] = 0.0 if failed[p] else relax_ramp(theta_end[p], Q[p], g[p], C[p], after, rate)


def empty_solution(shape):
    """Outputs (dT, v, status, iterations) of :func:`solve_frames_predicted`."""
    return (np.empty(shape), np.empty(shape), np.empty(shape, np.uint8),
            np.empty(shape, np.int32))
