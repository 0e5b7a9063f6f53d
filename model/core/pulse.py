"""Kernels of the bias pulse train (``bolometer.pulse = "integrated"``, the default).

Per pixel, with theta = T - T_s the rise over the substrate (paper eq. 14 in time):

    C dtheta/dt = I^2 R(T_s + theta) + Q - g theta                during the bias pulse
    C dtheta/dt = Q - g theta - C dT_s/dt                          between two pulses

Every frame period P the pixel is pulsed once, for t_int. Between pulses the equation is
linear and is advanced exactly (:func:`relax_ramp`: the substrate linear in time, a first-
order hold). The pulse is integrated by the classical Runge-Kutta method in ``n`` equal
steps (chosen per sensor, :func:`choose_steps`), together with

* the mean of I R(T) over the pulse (the voltage the integrator integrates) and of theta;
* the variational equation y' = (df/dtheta) y, y(0) = 1: y(t_int) = d theta_end / d
  theta_0, and the voltage's sensitivity S = d <I R> / d theta_0 = (I / t_int) int R'(T)
  y dt (the derivative of the discrete map itself: a Runge-Kutta method commutes with
  differentiation), used by the periodic solve (Newton) and the thermal-fluctuation noise.

The resistance of a stage is R_b exp(B (1/T - 1/T_b)) from the step's first stage (R_b,
T_b) by a degree-9 polynomial (|exponent| <= ZMAX: relative error < 3e-13), so the loops
carry no call and the compiler vectorizes them. A pixel whose exponent leaves that range,
whose temperature leaves (0, T_max], or that is not finite, is integrated again by the
adaptive time-domain integrator of :mod:`model.core.transient` (``auto``, rtol 1e-9),
which handles stiffness, the tau -> 0 limit and runaways.

Steady state of the pulse train (:func:`periodic_frames`): theta_0 = theta_eq + (theta_end(
theta_0) - theta_eq) d, d = exp(-(P - t_int) g / C), theta_eq = Q / g, solved per pixel by
Newton's method on G = (theta_0 - theta_eq)(1 - d) - (theta_end - theta_0) d (derivative
(1 - d) - d (y - 1)), every difference formed without cancellation (1 - d by expm1, the
pulse's rise and y - 1 accumulated as such), so a pixel whose time constant is 1e90 times
the frame period (g -> 0) still finds the state where its pulses' heat balances its
losses. Thermal memory (:func:`lagged_frames`): the state goes from frame to frame by the
exact relaxation theta + (theta_eq' - theta)(1 - d), theta_eq' = theta_eq - tau dT_s/dt.
"""

import math

import numpy as np
from numba import njit, prange

from irnuc.model.core.bolometer import (
    STATUS_INVALID,
    STATUS_NO_CONVERGENCE,
    STATUS_OK,
    STATUS_RUNAWAY,
    resistance,
)
from irnuc.model.core.constants import K_BOLTZMANN as K_B
from irnuc.model.core.rng import normal_row
from irnuc.model.core.transient import M_AUTO, relax_ramp
from irnuc.model.core.transient import pulse as _adaptive_pulse
from irnuc.model.core.warmstart import _exp_poly

#: Largest |exponent| of a stage's resistance update by the degree-9 polynomial
#: (:func:`model.core.warmstart._exp_poly`: relative error below ZMAX^10 / 10! < 3e-13).
ZMAX = 0.25
#: Newton iterations of the periodic solve before a pixel goes to the slow path.
PERIODIC_MAX_IT = 12
#: Convergence of the periodic solve: |step| <= PERIODIC_RTOL (|theta_0| + 1 mK).
PERIODIC_RTOL = 1e-12
#: A Newton step this small (K) ends the fast periodic solve: the outputs are moved by it
#: linearly (y, S), leaving second-order errors of about |d^2 G/d theta^2| step^2 / 2 in
#: theta_0 and |d^2 v/d theta^2| step^2 / 2 in the voltage: below 1e-11 K and 1e-11 V on
#: the default sensor (1e-4 codes).
PERIODIC_LINEAR = 1e-4
#: Tolerance of the adaptive integrator of the slow path.
SLOW_RTOL = 1e-9
SLOW_MAX_SUB = 200_000


#: The pulse's loops let the compiler fuse a multiply and an add (``contract``, no other
#: fast-math liberty): the same bits run after run on one machine, 20 % less time.
FM = {"contract"}


#: e^k for k = -8 .. 8 (the integer part of an exponent, :func:`_exp_vec`).
_EXP_INT = np.exp(np.arange(-8.0, 9.0))


@njit(cache=True, error_model="numpy", fastmath=FM)
def _exp_vec(z, tab):
    """e^z for |z| <= 8.5 without a call (so a loop of it vectorizes): e^k e^(z - k),
    k = round(z) from ``tab``, e^r (|r| <= 1/2) by its degree-13 Taylor polynomial (relative
    error < 1e-15)."""
    k = math.floor(z + 0.5)
    r = z - k
    p = 1.0 / 6227020800.0
    p = p * r + 1.0 / 479001600.0
    p = p * r + 1.0 / 39916800.0
    p = p * r + 1.0 / 3628800.0
    p = p * r + 1.0 / 362880.0
    p = p * r + 1.0 / 40320.0
    p = p * r + 1.0 / 5040.0
    p = p * r + 1.0 / 720.0
    p = p * r + 1.0 / 120.0
    p = p * r + 1.0 / 24.0
    p = p * r + 1.0 / 6.0
    p = p * r + 0.5
    p = p * r + 1.0
    p = p * r + 1.0
    return tab[np.int64(k) + 8] * p


@njit(cache=True, error_model="numpy", fastmath=FM)
def _start_row(th0, Ts, R_ref, B, inv_Tref, Rb, ib):
    big = 0
    for j in range(th0.shape[0]):
        inv = 1.0 / (Ts + th0[j])
        ib[j] = inv
        z = B * (inv - inv_Tref)
        ok = abs(z) <= 8.0
        Rb[j] = R_ref[j] * _exp_vec(z if ok else 0.0, _EXP_INT)
        big += 0 if ok else 1
    if big:
        for j in range(th0.shape[0]):
            z = B * (ib[j] - inv_Tref)
            if not abs(z) <= 8.0:
                Rb[j] = R_ref[j] * math.exp(z)


@njit(cache=True, error_model="numpy", fastmath=FM)
def _stage(a, wt, first, th0, dth, ym1, fp, dp, Ts, B, ib, Rb, kc, qc, gc, accR, accT, accS,
           sf, sd, bad):
    """One Runge-Kutta stage over a row: theta = th0 + dth + a fp, y = 1 + ym1 + a dp; writes
    the stage's slopes into fp and dp, adds wt times the stage's values to the accumulators;
    the first stage of a step also moves the resistance's base to its own point."""
    for j in range(th0.shape[0]):
        t = th0[j] + (dth[j] + a * fp[j])
        yy = 1.0 + (ym1[j] + a * dp[j])
        T = Ts + t
        iT = 1.0 / T
        z = B * (iT - ib[j])
        R = Rb[j] * _exp_poly(z)
        f = kc[j] * R + qc[j] - gc[j] * t
        dR = -R * B * iT * iT  # dR/dT
        d = (kc[j] * dR - gc[j]) * yy
        fp[j] = f
        dp[j] = d
        accR[j] += wt * R
        accT[j] += wt * t
        accS[j] += wt * dR * yy
        sf[j] += wt * f
        sd[j] += wt * d
        bad[j] |= (abs(z) > ZMAX) | (not T > 0.0)
        if first:
            Rb[j] = R
            ib[j] = iT


@njit(cache=True, error_model="numpy", fastmath=FM)
def _stage_plain(a, wt, first, th0, dth, fp, Ts, B, ib, Rb, kc, qc, gc, accR, accT, sf, bad):
    """:func:`_stage` without the variational equation (the lagged model's pulses after the
    first: nothing reads y or S there)."""
    for j in range(th0.shape[0]):
        t = th0[j] + (dth[j] + a * fp[j])
        T = Ts + t
        iT = 1.0 / T
        z = B * (iT - ib[j])
        R = Rb[j] * _exp_poly(z)
        f = kc[j] * R + qc[j] - gc[j] * t
        fp[j] = f
        accR[j] += wt * R
        accT[j] += wt * t
        sf[j] += wt * f
        bad[j] |= (abs(z) > ZMAX) | (not T > 0.0)
        if first:
            Rb[j] = R
            ib[j] = iT


@njit(cache=True, error_model="numpy", fastmath=FM)
def pulse_row(th0, Ts, Q, R_ref, g, C, B, inv_Tref, I, t_int, n, T_max,
              v_out, m_out, dth_out, ym1_out, s_out, bad, w, sens=True):
    """One bias pulse of every pixel of a row from theta_0 = th0 (K) at substrate Ts (K).

    Writes the mean voltage <I R> (V), the mean rise (K), the pulse's rise theta_end -
    theta_0 (K), and with ``sens`` y - 1 = d theta_end / d theta_0 - 1 and S = d<I R>/d
    theta_0 (V/K; without: 0); ``bad`` (bool) marks the pixels the fast path cannot vouch
    for (to be done by :func:`slow_pulse`). ``w``: scratch (14, cols).
    """
    cols = th0.shape[0]
    dth, ym1, Rb, ib, kc, qc, gc = w[0], w[1], w[2], w[3], w[4], w[5], w[6]
    accR, accT, accS, sf, sd, fp, dp = w[7], w[8], w[9], w[10], w[11], w[12], w[13]
    I2 = I * I
    for j in range(cols):
        ci = 1.0 / C[j]
        kc[j] = I2 * ci
        qc[j] = Q[j] * ci
        gc[j] = g[j] * ci
        dth[j] = 0.0
        ym1[j] = 0.0
        accR[j] = 0.0
        accT[j] = 0.0
        accS[j] = 0.0
        bad[j] = False
    _start_row(th0, Ts, R_ref, B, inv_Tref, Rb, ib)
    h = t_int / n
    for _ in range(n):
        for j in range(cols):
            sf[j] = 0.0
            sd[j] = 0.0
            fp[j] = 0.0
            dp[j] = 0.0
        if sens:
            _stage(0.0, 1.0, True, th0, dth, ym1, fp, dp, Ts, B, ib, Rb, kc, qc, gc, accR, accT,
                   accS, sf, sd, bad)
            _stage(0.5 * h, 2.0, False, th0, dth, ym1, fp, dp, Ts, B, ib, Rb, kc, qc, gc, accR,
                   accT, accS, sf, sd, bad)
            _stage(0.5 * h, 2.0, False, th0, dth, ym1, fp, dp, Ts, B, ib, Rb, kc, qc, gc, accR,
                   accT, accS, sf, sd, bad)
            _stage(h, 1.0, False, th0, dth, ym1, fp, dp, Ts, B, ib, Rb, kc, qc, gc, accR, accT,
                   accS, sf, sd, bad)
        else:
            _stage_plain(0.0, 1.0, True, th0, dth, fp, Ts, B, ib, Rb, kc, qc, gc, accR, accT,
                         sf, bad)
            _stage_plain(0.5 * h, 2.0, False, th0, dth, fp, Ts, B, ib, Rb, kc, qc, gc, accR,
                         accT, sf, bad)
            _stage_plain(0.5 * h, 2.0, False, th0, dth, fp, Ts, B, ib, Rb, kc, qc, gc, accR,
                         accT, sf, bad)
            _stage_plain(h, 1.0, False, th0, dth, fp, Ts, B, ib, Rb, kc, qc, gc, accR, accT,
                         sf, bad)
        for j in range(cols):
            dth[j] += (h / 6.0) * sf[j]
            ym1[j] += (h / 6.0) * sd[j]
    inv6n = 1.0 / (6.0 * n)
    for j in range(cols):
        v_out[j] = I * accR[j] * inv6n
        m_out[j] = accT[j] * inv6n
        dth_out[j] = dth[j]
        ym1_out[j] = ym1[j]
        s_out[j] = I * accS[j] * inv6n
        e = th0[j] + dth[j]
        bad[j] |= (not abs(e) < 1e300) | (not Ts + e <= T_max) | (not v_out[j] >= 0.0)


@njit(cache=True)
def _slow_once(th0, Ts, Q, R_ref, g, C, B, T_ref, I, t_int, T_max):
    """(v, mean rise, theta_end, status) of one pulse by the adaptive integrator."""
    e, iV, iT, st, _, _ = _adaptive_pulse(th0, Ts, Q, I, R_ref, B, T_ref, g, C, t_int, M_AUTO,
                                          4, SLOW_MAX_SUB, T_max, False, SLOW_RTOL)
    return iV / t_int, iT / t_int, e, st


@njit(cache=True)
def slow_pulse(th0, Ts, Q, R_ref, g, C, B, T_ref, I, t_int, T_max):
    """One pulse of one pixel by the adaptive integrator. Returns (v, mean, theta_end -
    theta_0, y - 1, S, status); y and S from the pulse's mean temperature (exact for a zero
    TCR or no bias; they serve Newton's derivative and the thermal noise of the few pixels
    the fast path leaves)."""
    if not (Ts + th0 > 0.0 and abs(th0) < 1e300):
        return 0.0, -Ts, 0.0, 0.0, 0.0, STATUS_INVALID
    v, m, e, st = _slow_once(th0, Ts, Q, R_ref, g, C, B, T_ref, I, t_int, T_max)
    if st != STATUS_OK or not Ts + m > 0.0:
        return v, m, e - th0, 0.0, 0.0, st
    T = Ts + m
    dR = -B * resistance(T, R_ref, B, T_ref) / (T * T)
    ym1 = math.expm1((I * I * dR - g) * t_int / C)
    return v, m, e - th0, ym1, I * dR * (1.0 + 0.5 * ym1), st


@njit(cache=True)
def _newton_step(th0, eq, d, omd, dth, ym1, Ts):
    """(step, ok) of Newton on G = (theta_0 - eq)(1 - d) - (theta_end - theta_0) d; the new
    point is kept above 0 K (half-way there at most)."""
    G = (th0 - eq) * omd - dth * d
    den = omd - d * ym1
    if not den > 0.0:  # the pulse heats faster than the pixel cools: no periodic state
        return 0.0, False
    step = G / den
    if not abs(step) < 1e300:
        return 0.0, False
    if not Ts + (th0 - step) > 0.0:
        step = 0.5 * (Ts + th0)
    return step, True


@njit(cache=True)
def slow_periodic(eq, d, omd, Ts, Q, R_ref, g, C, B, T_ref, I, t_int, T_max, guess):
    """The periodic state of one pixel by the slow path: Newton with the finite-difference
    y. Returns (theta_0, v, mean, rise, y - 1, S, status, iterations)."""
    th0 = guess if Ts + guess > 0.0 and abs(guess) < 1e300 else 0.0
    toward_zero = 0
    for it in range(4 * PERIODIC_MAX_IT):
        v, m, dth, ym1, S, st = slow_pulse(th0, Ts, Q, R_ref, g, C, B, T_ref, I, t_int, T_max)
        if st != STATUS_OK and toward_zero >= 3:
            st = STATUS_INVALID  # falling towards 0 K, where no pulse holds it
        if st == STATUS_INVALID:
            return -Ts, 0.0, -Ts, 0.0, 0.0, 0.0, STATUS_INVALID, it + 1
        if st != STATUS_OK:
            return th0, v, m, dth, ym1, S, st, it + 1
        step, ok = _newton_step(th0, eq, d, omd, dth, ym1, Ts)
        if not ok:
            return th0, v, m, dth, ym1, S, STATUS_RUNAWAY, it + 1
        toward_zero = toward_zero + 1 if step == 0.5 * (Ts + th0) else 0
        if toward_zero >= 8:  # T halved eight times: no periodic state above 0 K
            return -Ts, 0.0, -Ts, 0.0, 0.0, 0.0, STATUS_INVALID, it + 1
        if abs(step) <= PERIODIC_RTOL * (abs(th0) + 1e-3):
            return th0, v, m, dth, ym1, S, STATUS_OK, it + 1
        th0 -= step
        if not Ts + th0 <= T_max:
            return th0, v, m, dth, ym1, S, STATUS_RUNAWAY, it + 1
    return th0, v, m, dth, ym1, S, STATUS_NO_CONVERGENCE, 4 * PERIODIC_MAX_IT


@njit(cache=True, error_model="numpy")
def periodic_row(Q, Ts, R_ref, g, C, omd, guess, B, T_ref, I, t_int, n, T_max,
                 th0_out, v_out, m_out, dth_out, ym1_out, s_out, status, iters, w, tmp):
    """The periodic state of the pulse train for a row: theta_0 (K, before the pulse) with
    theta_0 = Q/g + (theta_end(theta_0) - Q/g) d, Newton from ``guess`` (K) with the fast
    pulse; the pixels it cannot vouch for by :func:`slow_periodic`. The outputs are those of
    the last pulse, moved to the converged theta_0 by the last (tiny) Newton step.

    ``tmp``: scratch (6, cols)."""
    cols = Q.shape[0]
    inv_Tref = 1.0 / T_ref
    th0 = tmp[0]
    v, m, dth, ym1, s = tmp[1], tmp[2], tmp[3], tmp[4], tmp[5]
    pending = np.ones(cols, np.bool_)
    bad = np.zeros(cols, np.bool_)
    for j in range(cols):
        gs = guess[j]
        th0[j] = gs if Ts + gs > 0.0 and abs(gs) < 1e300 else 0.0
        iters[j] = 0
    for it in range(PERIODIC_MAX_IT):
        if n > 0:
            pulse_row(th0, Ts, Q, R_ref, g, C, B, inv_Tref, I, t_int, n, T_max, v, m, dth, ym1,
                      s, bad, w)
        else:
            for j in range(cols):
                bad[j] = True
        left = 0
        for j in range(cols):
            if not pending[j]:
                continue
            if bad[j]:
                pending[j] = False
                iters[j] = -1  # the slow path below
                continue
            step, ok = _newton_step(th0[j], Q[j] / g[j], 1.0 - omd[j], omd[j], dth[j], ym1[j],
                                    Ts)
            if not ok:
                pending[j] = False
                iters[j] = -1
                continue
            if abs(step) <= PERIODIC_LINEAR:
                pending[j] = False
                iters[j] = it + 1
                th0_out[j] = th0[j] - step
                v_out[j] = v[j] - s[j] * step
                m_out[j] = m[j] - (1.0 + 0.5 * ym1[j]) * step
                dth_out[j] = dth[j] - ym1[j] * step
                ym1_out[j] = ym1[j]
                s_out[j] = s[j]
                status[j] = STATUS_OK
                continue
            th0[j] -= step
            left += 1
        if left == 0:
            break
    for j in range(cols):
        if pending[j] or iters[j] < 0:
            r = slow_periodic(Q[j] / g[j], 1.0 - omd[j], omd[j], Ts, Q[j], R_ref[j], g[j], C[j], B,
                              T_ref,
                              I, t_int, T_max, guess[j])
            th0_out[j], v_out[j], m_out[j], dth_out[j], ym1_out[j], s_out[j] = r[:6]
            status[j] = r[6]
            iters[j] = PERIODIC_MAX_IT + r[7]


@njit(cache=True, error_model="numpy")
def _guess(Q, Ts, g, excess, slope, teq, out):
    """First guess of theta_0 (K): Q/g plus the periodic excess of the sensor's reference,
    moved by its slope d(excess)/d(T_s + Q/g) = d (y - 1) / (1 - d y) times the change of the
    unbiased equilibrium temperature from the reference's ``teq``."""
    for j in range(Q.shape[0]):
        eq = Q[j] / g[j]
        out[j] = eq + excess[j] + slope[j] * (Ts + eq - teq[j])


@njit(cache=True, parallel=True)
def periodic_frames(Q, Ts, R_ref, g, C, omd, excess, slope, teq, B, T_ref, I, t_int, n,
                    T_max, v_out, m_out, status, iters, aux):
    """:func:`periodic_row` for (N, rows, cols) frames at substrate Ts (N,) K, from the
    first guess (:func:`_guess`: the reference's excess, moved linearly). ``aux`` (4, N, rows, cols) receives
    theta_0, the pulse's rise, y - 1 and S; (2, ...) theta_0 and y - 1; (1, ...) theta_0;
    size 0: none."""
    n_frames, rows, cols = Q.shape
    keep = aux.shape[0]
    for k in prange(n_frames * rows):
        f = k // rows
        i = k - f * rows
        w = np.empty((14, cols))
        tmp = np.empty((6, cols))
        scratch = np.empty((4, cols))
        gs = np.empty(cols)
        _guess(Q[f, i], Ts[f], g[i], excess[i], slope[i], teq[i], gs)
        if keep >= 4:
            periodic_row(Q[f, i], Ts[f], R_ref[i], g[i], C[i], omd[i], gs, B, T_ref, I,
                         t_int, n, T_max, aux[0, f, i], v_out[f, i], m_out[f, i], aux[1, f, i],
                         aux[2, f, i], aux[3, f, i], status[f, i], iters[f, i], w, tmp)
        else:
            periodic_row(Q[f, i], Ts[f], R_ref[i], g[i], C[i], omd[i], gs, B, T_ref, I,
                         t_int, n, T_max, scratch[0], v_out[f, i], m_out[f, i], scratch[1],
                         scratch[2], scratch[3], status[f, i], iters[f, i], w, tmp)
            if keep >= 1:
                for j in range(cols):
                    aux[0, f, i, j] = scratch[0, j]
            if keep == 2:
                for j in range(cols):
                    aux[1, f, i, j] = scratch[2, j]


@njit(cache=True, parallel=True)
def thermal_noise_steady(v, m, th0, ym1, s, C, omd, Ts, keys, x_tab, f_tab):
    """Add, in place, the thermal fluctuation of the pixel's temperature before the pulse to
    frames in the periodic state (no memory): a draw of the stationary variance
    (k T^2 / C) (1 - d^2) / (1 - d^2 y^2) through the pulse's sensitivities (linear). The
    standard normal of pixel (i, j) of frame f is that of (keys[f], i cols + j)
    (:mod:`model.core.rng`)."""
    n_frames, rows, cols = v.shape
    for k in prange(n_frames * rows):
        f = k // rows
        i = k - f * rows
        nz = np.empty(cols)
        normal_row(keys[f], np.uint64(i) * np.uint64(cols), nz, x_tab, f_tab)
        for j in range(cols):
            sd = _stationary_sd(omd[i, j], ym1[f, i, j], math.sqrt(K_B / C[i, j]),
                                Ts[f] + th0[f, i, j])
            dl = sd * nz[j]
            v[f, i, j] += s[f, i, j] * dl
            m[f, i, j] += (1.0 + 0.5 * ym1[f, i, j]) * dl


@njit(cache=True)
def _stationary_sd(omd, ym1, sig_eq, T0):
    """RMS of the pre-pulse temperature in the periodic state, K: k T^2 / C relaxed between
    pulses (1 - d^2, d = 1 - omd) and contracted by each pulse (y):
    sqrt((1 - d^2) / (1 - d^2 y^2)), sig_eq = sqrt(k / C)."""
    d = 1.0 - omd
    y = 1.0 + ym1
    one_d2 = omd * (2.0 - omd)
    den = one_d2 + d * d * (1.0 - y) * (1.0 + y)
    if not den > 0.0 or not T0 > 0.0:
        return 0.0
    return sig_eq * T0 * math.sqrt(one_d2 / den)


@njit(cache=True, error_model="numpy")
def _fix_row(th0, Ts, Q, R_ref, g, C, B, T_ref, I, t_int, T_max, bad, v, m, dth, ym1, s,
             status):
    for j in range(th0.shape[0]):
        if bad[j]:
            v[j], m[j], dth[j], ym1[j], s[j], status[j] = slow_pulse(
                th0[j], Ts, Q[j], R_ref[j], g[j], C[j], B, T_ref, I, t_int, T_max)
        else:
            status[j] = STATUS_OK


@njit(cache=True, error_model="numpy")
def _lagged_row(Q, Ts, Ts_prev, R_ref, g, C, omd, excess, slope, teq, state, has_prev, P,
                t_int, B, T_ref, I, n, T_max, keys, v_out, m_out, st_out, it_out, w,
                tmp, base, x_tab, f_tab):
    """Frames of one row with the pixel's temperature carried (``state``: theta at the end
    of the last pulse over the substrate then, K; updated in place); the thermal
    fluctuation's normal of pixel j is that of (keys[frame], base + j)."""
    n_frames, cols = Q.shape
    inv_Tref = 1.0 / T_ref
    th0 = tmp[0]
    dth, ym1, s = tmp[1], tmp[2], tmp[3]
    bad = np.zeros(cols, np.bool_)
    has_noise = keys.shape[0] > 0
    noise = np.empty((n_frames if has_noise else 0, cols))
    for k in range(noise.shape[0]):
        normal_row(keys[k], base, noise[k], x_tab, f_tab)
    gs = np.empty(cols)
    it_buf = np.empty(cols, np.int32)
    for k in range(n_frames):
        Tn = Ts[k]
        Tp = Ts_prev if k == 0 else Ts[k - 1]
        rate = (Tn - Tp) / P
        shift = 0.5 * rate * t_int
        Tpulse = Tn - shift  # the substrate at mid-pulse
        if k == 0 and not has_prev:
            # the first frame of a run starts in the periodic state of its own conditions
            _guess(Q[k], Tpulse, g, excess, slope, teq, gs)
            periodic_row(Q[k], Tpulse, R_ref, g, C, omd, gs, B, T_ref, I, t_int, n, T_max,
                         th0, v_out[k], m_out[k], dth, ym1, s, st_out[k], it_buf, w, tmp[4:10])
            for j in range(cols):
                it_out[k, j] = it_buf[j]
                if has_noise:  # a stationary draw, through the pulse's sensitivities
                    dl = _stationary_sd(omd[j], ym1[j], math.sqrt(K_B / C[j]), Tpulse + th0[j]) \
                        * noise[k, j]
                    v_out[k, j] += s[j] * dl
                    m_out[k, j] += (1.0 + 0.5 * ym1[j]) * dl
                    th0[j] += dl
                    dth[j] += ym1[j] * dl
        else:
            for j in range(cols):
                tau = C[j] / g[j]
                r_eq = Q[k, j] / g[j] - rate * tau
                t0 = state[j] + (r_eq - state[j]) * omd[j] - shift
                if has_noise:
                    T0 = Tpulse + t0
                    if T0 > 0.0:
                        t0 += (math.sqrt(K_B / C[j]) * T0 * math.sqrt(omd[j] * (2.0 - omd[j]))
                               * noise[k, j])
                th0[j] = t0
            if n > 0:
                pulse_row(th0, Tpulse, Q[k], R_ref, g, C, B, inv_Tref, I, t_int, n, T_max,
                          v_out[k], m_out[k], dth, ym1, s, bad, w, False)
            else:
                for j in range(cols):
                    bad[j] = True
            _fix_row(th0, Tpulse, Q[k], R_ref, g, C, B, T_ref, I, t_int, T_max, bad, v_out[k],
                     m_out[k], dth, ym1, s, st_out[k])
            for j in range(cols):
                it_out[k, j] = n if not bad[j] else -1
        for j in range(cols):
            if st_out[k, j] == STATUS_OK:
                state[j] = th0[j] + dth[j] - shift
            else:
                state[j] = 0.0  # a failed pixel restarts from the substrate


@njit(cache=True, parallel=True)
def lagged_frames(Q, Ts, Ts_prev, R_ref, g, C, omd, excess, slope, teq, state, has_prev, P,
                  t_int, B, T_ref, I, n, T_max, keys, v_out, m_out, status, iters,
                  x_tab, f_tab):
    """Frames (N, rows, cols) with thermal memory: before each pulse the pixel has relaxed
    from the last pulse's end over P - t_int, the substrate linear from Ts_prev / the
    previous frame's value to the frame's (K); the pulse at the end of the frame period,
    the substrate held at its mid-pulse value. ``state`` (rows, cols): theta at the end of
    the last pulse (K, over the substrate at the frame's end), read if ``has_prev`` and
    updated. ``keys`` (N,) uint64: the thermal fluctuation's draws of each frame (the normal
    of pixel (i, j) that of (keys[f], i cols + j); empty: none): the equilibrium RMS of the
    pixel's temperature is T sqrt(k_B / C)."""
    rows, cols = Q.shape[1], Q.shape[2]
    for i in prange(rows):
        w = np.empty((14, cols))
        tmp = np.empty((10, cols))
        _lagged_row(Q[:, i], Ts, Ts_prev, R_ref[i], g[i], C[i], omd[i], excess[i],
                    slope[i], teq[i], state[i], has_prev, P, t_int, B, T_ref, I, n, T_max,
                    keys, v_out[:, i], m_out[:, i], status[:, i], iters[:, i],
                    w, tmp, np.uint64(i) * np.uint64(cols), x_tab, f_tab)


@njit(cache=True)
def nominal_steps_error(n, omd, Ts, Q, R_ref, g, C, B, T_ref, I, t_int, T_max):
    """|v(n) - v(2n)| / v of the nominal pixel's periodic state (the estimate of the error
    of n steps is 16/15 of it), or inf where the fast path fails."""
    out = np.empty((2, 1))
    for k in range(2):
        nn = n if k == 0 else 2 * n
        w = np.empty((14, 1))
        tmp = np.empty((6, 1))
        th0, m, e, y, s = np.empty(1), np.empty(1), np.empty(1), np.empty(1), np.empty(1)
        st = np.empty(1, np.uint8)
        it = np.empty(1, np.int32)
        periodic_row(np.array([Q]), Ts, np.array([R_ref]), np.array([g]), np.array([C]),
                     np.array([omd]), np.array([Q / g]), B, T_ref, I, t_int, nn,
                     T_max, th0, out[k], m, e, y, s, st, it, w, tmp)
        if st[0] != STATUS_OK or it[0] > PERIODIC_MAX_IT or it[0] < 0:
            return math.inf
    if out[1, 0] == 0.0:  # no bias: nothing to integrate but the linear relaxation
        return abs(out[0, 0])
    return abs(out[0, 0] - out[1, 0]) / abs(out[1, 0])


@njit(cache=True, parallel=True)
def reference_maps(Q, g, th0, ym1, omd, status, T_s, excess, slope, teq):
    """The periodic solve's first-guess maps from a solved reference frame (rows, cols):
    the excess theta_0 - Q/g (K), its slope with the unbiased equilibrium temperature,
    d (y - 1) / (1 - d y), and that temperature T_s + Q/g (K); 0 where the reference failed
    (single precision: a guess)."""
    rows, cols = Q.shape
    for i in prange(rows):
        for j in range(cols):
            eq = Q[i, j] / g[i, j]
            teq[i, j] = T_s + eq
            excess[i, j] = 0.0
            slope[i, j] = 0.0
            if status[i, j] == STATUS_OK:
                excess[i, j] = th0[i, j] - eq
                d = 1.0 - omd[i, j]
                den = omd[i, j] - d * ym1[i, j]
                if den > 0.0:
                    slope[i, j] = d * ym1[i, j] / den


__all__ = ["lagged_frames", "periodic_frames", "relax_ramp", "resistance", "thermal_noise_steady"]
