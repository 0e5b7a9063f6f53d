"""Kernels of the transient (time-domain) bolometer heat balance (paper eq. 14).

Per pixel, with theta = T - T_s the rise over the substrate:

    C dtheta/dt = I^2 R(T_s + theta) + Q - g theta            (bias pulse on)
    C dtheta/dt = Q - g theta                                   (bias off)

R(T) = R_ref exp(B (1/T - 1/T_ref)) as in :mod:`model.core.bolometer`. Q (W) is the absorbed
power (scene, housing, optional emission) of the frame. Between pulses the equation is
linear and is advanced exactly; during the pulse one of four integrators advances it, and
the same step also accumulates the integrals of the bolometer voltage I R(T) and of theta
over the window (their means are the frame's outputs).

Integrator codes (see :data:`model.transient.INTEGRATORS`):

0 ``rk4``: classical explicit Runge-Kutta (order 4). Step-limited automatically: every
  substep satisfies h |lambda| <= RK4_STABILITY, lambda = df/dtheta the local Jacobian, so
  it can never blow up; a pixel that would need more than ``max_sub`` substeps per pulse
  (or any substep at all with ``refuse_unstable``) stops with STATUS_STEP_LIMIT and the API
  raises instead of returning a frame.
1 ``backward_euler``: implicit, L-stable, order 1; Newton on every step.
2 ``trapezoidal``: implicit, A-stable, order 2; Newton on every step.
3 ``exponential``: exponential Rosenbrock-Euler, order 2, exact whenever the right-hand side
  is linear in theta (TCR = 0 or zero bias): theta+ = theta + h phi1(h J) f(theta).

An implicit step whose Newton iteration fails (no convergence, the residual derivative not
positive, T <= 0) is retried with half the step; so is an exponential step that would grow
by more than e^EXP_MAX_GROWTH. A pixel that needs more than ``max_sub`` substeps per pulse
stops with STATUS_NO_CONVERGENCE. A pixel whose temperature passes ``T_max`` stops with
STATUS_RUNAWAY. Failed pixels stay failed for the rest of the sequence (their state is no
longer physical); their outputs hold the last finite values.
"""

import math

import numpy as np
from numba import njit, prange

from model.core.bolometer import (
    STATUS_INVALID,
    STATUS_NO_CONVERGENCE,
    STATUS_OK,
    STATUS_RUNAWAY,
)

#: The explicit method needed more substeps than allowed (the API refuses the run).
STATUS_STEP_LIMIT = 4

#: RK4 is stable for h lambda in [-2.785, 0] on the real axis; keep a margin.
RK4_STABILITY = 2.5
#: Largest growth exponent h J of one exponential step before it is split.
EXP_MAX_GROWTH = 20.0
#: Newton iterations per implicit step before the step is halved.
NEWTON_MAX_ITER = 60
#: Newton convergence: |dx| <= NEWTON_RTOL |x| + NEWTON_ATOL (K).
NEWTON_RTOL = 1e-14
NEWTON_ATOL = 1e-15

M_RK4 = 0
M_BACKWARD_EULER = 1
M_TRAPEZOIDAL = 2
M_EXPONENTIAL = 3


@njit(cache=True)
def _resistance(T, R_ref, B, T_ref):
    return R_ref * math.exp(B * (1.0 / T - 1.0 / T_ref))


@njit(cache=True)
def phi1(z):
    """(e^z - 1) / z, stable for every z (1 at z = 0)."""
    if abs(z) < 1e-5:
        return 1.0 + z * (0.5 + z / 6.0)
    return math.expm1(z) / z


@njit(cache=True)
def phi2(z):
    """(e^z - 1 - z) / z^2, stable for every z (1/2 at z = 0)."""
    if abs(z) < 1.0:
        # sum_k z^k / (k + 2)!: 20 terms reach 1e-19 for |z| < 1.
        term = 0.5
        s = term
        for k in range(1, 20):
            term *= z / (k + 2)
            s += term
        return s
    return (math.expm1(z) - z) / (z * z)


@njit(cache=True)
def relax(theta, Q, g, C, dt):
    """Exact solution of C theta' = Q - g theta over dt >= 0 (no bias)."""
    if dt <= 0.0:
        return theta
    eq = Q / g
    return eq + (theta - eq) * math.exp(-dt * g / C)


@njit(cache=True)
def _rhs(theta, Ts, Q, I2, R_ref, B, T_ref, g, C):
    """(f, R, dR/dT) at theta: f = (I^2 R + Q - g theta) / C."""
    T = Ts + theta
    R = _resistance(T, R_ref, B, T_ref)
    return (I2 * R + Q - g * theta) / C, R, -B * R / (T * T)


@njit(cache=True)
def _step_rk4(th, h, Ts, Q, I, R_ref, B, T_ref, g, C):
    """One RK4 step of (theta, int V, int theta). Returns (theta+, dV, dth)."""
    I2 = I * I
    k1, R1, _ = _rhs(th, Ts, Q, I2, R_ref, B, T_ref, g, C)
    t2 = th + 0.5 * h * k1
    k2, R2, _ = _rhs(t2, Ts, Q, I2, R_ref, B, T_ref, g, C)
    t3 = th + 0.5 * h * k2
    k3, R3, _ = _rhs(t3, Ts, Q, I2, R_ref, B, T_ref, g, C)
    t4 = th + h * k3
    k4, R4, _ = _rhs(t4, Ts, Q, I2, R_ref, B, T_ref, g, C)
    new = th + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    dV = h / 6.0 * I * (R1 + 2.0 * R2 + 2.0 * R3 + R4)
    dth = h / 6.0 * (th + 2.0 * t2 + 2.0 * t3 + t4)
    return new, dV, dth


@njit(cache=True)
def _step_implicit(th, f0, R0, h, c, Ts, Q, I, R_ref, B, T_ref, g, C):
    """theta+ = theta + h ((1 - c) f(theta) + c f(theta+)), c = 1 (BE) or 1/2 (TR).

    Returns (theta+, f(theta+), R(theta+), ok).
    """
    I2 = I * I
    base = th + h * (1.0 - c) * f0
    x = th
    for _ in range(NEWTON_MAX_ITER):
        T = Ts + x
        if not T > 0.0:
            return x, 0.0, 0.0, False
        f, R, dR = _rhs(x, Ts, Q, I2, R_ref, B, T_ref, g, C)
        r = x - base - h * c * f
        dr = 1.0 - h * c * (I2 * dR - g) / C
        if not dr > 0.0:
            return x, 0.0, 0.0, False  # step too long for a unique root: halve it
        dx = r / dr
        x -= dx
        if not math.isfinite(x):
            return x, 0.0, 0.0, False
        if abs(dx) <= NEWTON_RTOL * abs(x) + NEWTON_ATOL:
            if not Ts + x > 0.0:
                return x, 0.0, 0.0, False
            f, R, _ = _rhs(x, Ts, Q, I2, R_ref, B, T_ref, g, C)
            return x, f, R, True
    return x, 0.0, 0.0, False


@njit(cache=True)
def pulse(th, Ts, Q, I, R_ref, B, T_ref, g, C, t_int, method, steps, max_sub, T_max,
          refuse_unstable):
    """Integrate one bias pulse of length t_int from theta = th.

    Returns (theta_end, int V dt, int theta dt, status, substeps).
    """
    I2 = I * I
    h_nom = t_int / steps
    iV = 0.0
    iT = 0.0
    sub = 0
    f0, R0, dR0 = _rhs(th, Ts, Q, I2, R_ref, B, T_ref, g, C)
    for _ in range(steps):
        rem = h_nom
        hs = h_nom
        while rem > 0.0:
            new = th
            dV = 0.0
            dT = 0.0
            if sub >= max_sub:
                st = STATUS_STEP_LIMIT if method == M_RK4 else STATUS_NO_CONVERGENCE
                return th, iV, iT, st, sub
            if method == M_RK4:
                lam = abs((I2 * dR0 - g) / C)
                m = math.ceil(rem * lam / RK4_STABILITY)
                if m > 1 and (refuse_unstable or m > max_sub - sub):
                    return th, iV, iT, STATUS_STEP_LIMIT, sub + m
                hs = rem / m if m > 1 else rem
                new, dV, dT = _step_rk4(th, hs, Ts, Q, I, R_ref, B, T_ref, g, C)
                ok = math.isfinite(new) and Ts + new > 0.0
                if ok:
                    f0, R0, dR0 = _rhs(new, Ts, Q, I2, R_ref, B, T_ref, g, C)
            elif method == M_EXPONENTIAL:
                hs = min(hs, rem)
                J = (I2 * dR0 - g) / C
                z = hs * J
                ok = z <= EXP_MAX_GROWTH
                if ok:
                    p1 = phi1(z)
                    p2 = phi2(z)
                    new = th + hs * p1 * f0
                    ok = math.isfinite(new) and Ts + new > 0.0
                if ok:
                    f1, R1, dR1 = _rhs(new, Ts, Q, I2, R_ref, B, T_ref, g, C)
                    # int theta of the linearised trajectory is exact; V is taken linear
                    # in theta between the step's ends (the secant), exact when R is.
                    dT = hs * th + hs * hs * p2 * f0
                    w = p2 / p1
                    dV = hs * I * (R0 + (R1 - R0) * w)
                    f0, R0, dR0 = f1, R1, dR1
            else:
                hs = min(hs, rem)
                c = 1.0 if method == M_BACKWARD_EULER else 0.5
                new, f1, R1, ok = _step_implicit(th, f0, R0, hs, c, Ts, Q, I, R_ref, B,
                                                 T_ref, g, C)
                if ok:
                    if method == M_BACKWARD_EULER:
                        dV = hs * I * R1
                        dT = hs * new
                    else:
                        dV = 0.5 * hs * I * (R0 + R1)
                        dT = 0.5 * hs * (th + new)
                    f0, R0 = f1, R1
                    dR0 = -B * R1 / ((Ts + new) * (Ts + new))
            sub += 1
            if not ok:
                if method == M_RK4:
                    return th, iV, iT, STATUS_STEP_LIMIT, sub
                hs *= 0.5
                continue
            th = new
            iV += dV
            iT += dT
            rem -= hs
            if rem <= 1e-12 * h_nom:
                rem = 0.0
            if method != M_RK4 and hs < rem:
                hs *= 2.0  # grow back after a halving
            if not Ts + th <= T_max:
                return th, iV, iT, STATUS_RUNAWAY, sub
    return th, iV, iT, STATUS_OK, sub


@njit(cache=True, parallel=True)
def integrate_frames(Q, Ts, R_ref, g, C, theta0, B, T_ref, I, t_int, frame_period,
                     pulse_start, warmup, method, steps, max_sub, T_max, refuse_unstable,
                     v_out, dT_out, dTend_out, status_out, sub_out):
    """A sequence of frames for a flat array of pixels.

    Parameters: Q (N, P) W, Ts (N,) K, R_ref, g, C, theta0 (P,) (theta0 relative to Ts[0],
    at the start of the first frame, before any warm-up frame). Every frame: relax
    (no bias) until pulse_start, one bias pulse of t_int, relax until frame_period. The
    substrate temperature steps at frame starts (T continuous, theta jumps). ``warmup``
    copies of frame 0 run first without output.

    Writes per frame and pixel: the mean bolometer voltage over the pulse (V), the mean
    rise over the pulse and the rise at its end (K), the status and the substeps used.
    """
    n_frames = Q.shape[0]
    n_pix = Q.shape[1]
    after = frame_period - pulse_start - t_int
    for p in prange(n_pix):
        th = theta0[p]
        Rp = R_ref[p]
        gp = g[p]
        Cp = C[p]
        st = STATUS_OK
        th_end = th
        nsub = 0
        last_v = I * _resistance(Ts[0] + th, Rp, B, T_ref) if Ts[0] + th > 0.0 else 0.0
        last_mean = th
        for k in range(warmup + n_frames):
            n = k - warmup if k >= warmup else 0
            if k > warmup:
                th += Ts[n - 1] - Ts[n]  # T is continuous across a substrate step
            if st == STATUS_OK:
                q = Q[n, p]
                th = relax(th, q, gp, Cp, pulse_start)
                th_end, iV, iT, st_p, nsub = pulse(th, Ts[n], q, I, Rp, B, T_ref, gp, Cp,
                                                   t_int, method, steps, max_sub, T_max,
                                                   refuse_unstable)
                if st_p == STATUS_OK:
                    last_v = iV / t_int
                    last_mean = iT / t_int
                    th = relax(th_end, q, gp, Cp, after)
                else:
                    st = st_p
                    if math.isfinite(th_end) and Ts[n] + th_end > 0.0:
                        last_v = I * _resistance(Ts[n] + th_end, Rp, B, T_ref)
                        last_mean = th_end
            else:
                nsub = 0
            if k >= warmup:
                v_out[n, p] = last_v
                dT_out[n, p] = last_mean
                dTend_out[n, p] = th_end if st == STATUS_OK else last_mean
                status_out[n, p] = st
                sub_out[n, p] = nsub


@njit(cache=True)
def rhs_jacobian(theta, Ts, Q, I, R_ref, B, T_ref, g, C):
    """f(theta) and df/dtheta during the pulse (for the reference solver and tests)."""
    f, R, dR = _rhs(theta, Ts, Q, I * I, R_ref, B, T_ref, g, C)
    return f, (I * I * dR - g) / C, R


def empty_outputs(shape):
    """Output arrays of :func:`integrate_frames` for a (N, P) problem."""
    return (np.empty(shape), np.empty(shape), np.empty(shape), np.empty(shape, np.uint8),
            np.empty(shape, np.int64))
