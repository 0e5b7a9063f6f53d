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
3 ``exponential``: the exponential Rosenbrock method exprb32 (order 3, embedded order-2
  error estimate), with the exact Jacobian, applied to theta and the two integrals; exact
  whenever the right-hand side is linear in theta (TCR = 0 or zero bias), so its cost does
  not grow with the stiffness t_int / tau.
4 ``auto`` (the default): RK4 while it is cheapest; per pixel and pulse it switches to
  the exponential method as soon as the local decay rate times the step says the pixel is
  stiff (h |lambda| > AUTO_SWITCH * RK4_STABILITY for the step RK4's accuracy control
  wants, which RK4 would have to cut by that factor), and it never refuses.

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

from irnuc.model.core.bolometer import (
    STATUS_INVALID,
    STATUS_NO_CONVERGENCE,
    STATUS_OK,
    STATUS_RUNAWAY,
    resistance,
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

#: Absolute scale of the temperature error test: rtol (|theta| + THETA_FLOOR), K. Scene
#: signals are millikelvin rises, so the floor is a microkelvin.
THETA_FLOOR = 1e-6

M_RK4 = 0
M_BACKWARD_EULER = 1
M_TRAPEZOIDAL = 2
M_EXPONENTIAL = 3
M_AUTO = 4
#: Reported (never chosen): ``auto`` and ``exponential`` took the pulse in the tau -> 0
#: limit (see :data:`QUASI_STATIC`).
M_QUASI_STATIC = 5

#: Stiffness g t_int / C (a lower bound of t_int |df/dtheta| for a negative TCR) from which
#: ``auto`` and ``exponential`` take the pulse in the tau -> 0 limit: theta jumps to the
#: equilibrium of the biased pixel and stays there. The approach it skips changes the pulse
#: integrals by about |dR/R| |theta0 - theta*| / stiffness (< 5e-17 relative here), while
#: integrating it in floating point costs ever more substeps as the right-hand side
#: (divided by C) grows to 1e40 and beyond and its rounding swamps the error estimate.
QUASI_STATIC = 1e18

#: ``auto`` leaves RK4 for the exponential integrator once RK4's stability limit cuts the
#: step its accuracy control asks for by more than this factor (h |lambda| above
#: AUTO_SWITCH * RK4_STABILITY): from then on the pixel is stiff and RK4 would pay for
#: stability, not accuracy, while the exponential method is exact on the linear part.
AUTO_SWITCH = 4.0


@njit(cache=True)
def _phi_series(z, k):
    """phi_k(z) by its Taylor series; 22 terms reach 1e-21 for |z| < 1."""
    fact = 1.0
    for j in range(2, k + 1):
        fact *= j
    term = 1.0 / fact
    s = term
    for m in range(1, 23):
        term *= z / (m + k)
        s += term
    return s


@njit(cache=True)
def phi_functions(z):
    """(phi1, phi2, phi3, phi4)(z), phi_k(z) = sum_m z^m / (m + k)!, stable for every z.

    |z| < 1: the Taylor series (no cancellation); otherwise the recursion
    phi_(k+1)(z) = (phi_k(z) - 1/k!) / z from phi1 = expm1(z) / z.
    """
    if abs(z) < 1.0:
        return _phi_series(z, 1), _phi_series(z, 2), _phi_series(z, 3), _phi_series(z, 4)
    p1 = math.expm1(z) / z
    p2 = (p1 - 1.0) / z
    p3 = (p2 - 0.5) / z
    p4 = (p3 - 1.0 / 6.0) / z
    return p1, p2, p3, p4


@njit(cache=True)
def relax(theta, Q, g, C, dt):
    """Exact solution of C theta' = Q - g theta over dt >= 0 (no bias)."""
    if dt <= 0.0:
        return theta
    eq = Q / g
    return eq + (theta - eq) * math.exp(-dt * g / C)


@njit(cache=True)
def relax_ramp(theta, Q, g, C, dt, rate):
    """theta (K, over the substrate) after dt >= 0 s without bias while the substrate warms
    at ``rate`` K/s: C theta' = Q - g theta - C rate, exactly (rate 0: :func:`relax`)."""
    if dt <= 0.0:
        return theta
    if rate == 0.0:
        return relax(theta, Q, g, C, dt)
    eq = Q / g - rate * (C / g)
    return eq + (theta - eq) * math.exp(-dt * g / C)


@njit(cache=True)
def _rhs(theta, Ts, Q, I2, R_ref, B, T_ref, g, C):
    """(f, R, dR/dT) at theta: f = (I^2 R + Q - g theta) / C."""
    T = Ts + theta
    R = resistance(T, R_ref, B, T_ref)
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
def _attempt(method, th, f0, R0, dR0, hs, Ts, Q, I, R_ref, B, T_ref, g, C):
    """One step of ``method`` from theta = th (f0, R0, dR0 at th) over hs.

    Returns (theta+, int V, int theta, ok, f+, R+, dR+, err theta, err int V); the error
    estimates are those of the embedded pair (exponential only, else 0).
    """
    I2 = I * I
    new = th
    dV = 0.0
    dT = 0.0
    f1 = f0
    R1 = R0
    dR1 = dR0
    err_th = 0.0
    err_V = 0.0
    ok = True
    if method == M_RK4:
        new, dV, dT = _step_rk4(th, hs, Ts, Q, I, R_ref, B, T_ref, g, C)
        ok = math.isfinite(new) and Ts + new > 0.0
        if ok:
            f1, R1, dR1 = _rhs(new, Ts, Q, I2, R_ref, B, T_ref, g, C)
    elif method == M_EXPONENTIAL:
        # exprb32 (Hochbruck, Ostermann, Schweitzer 2009) on y = (theta, int V, int theta)
        # with F(y) = (f, I R, theta) and its exact Jacobian M = h J3, J3 = [[J, 0, 0],
        # [I R', 0, 0], [1, 0, 0]]. M^k = a^(k-1) M (a = h J), so for any vector v
        # phi_j(M) v = v / j! + v0 phi_(j+1)(a) (a, h I R', h): every phi of the 3x3 matrix
        # is a scalar phi. Order 3, exact when F is linear (TCR = 0 or no bias); the
        # order-2 internal stage gives the error estimate 2 h phi3(M) D.
        J = (I2 * dR0 - g) / C
        a = hs * J
        ok = a <= EXP_MAX_GROWTH
        if ok:
            p1, p2, _p3, p4 = phi_functions(a)
            V0 = I * R0
            bI = hs * I * dR0
            # Stage U = y + h phi1(M) F(y)
            u_th = th + hs * f0 * p1
            u_V = hs * (V0 + f0 * p2 * bI)
            u_T = hs * (th + f0 * p2 * hs)
            ok = math.isfinite(u_th) and Ts + u_th > 0.0
            if ok:
                fu, Ru, _dRu = _rhs(u_th, Ts, Q, I2, R_ref, B, T_ref, g, C)
                d_th = u_th - th
                D0 = fu - f0 - J * d_th
                D1 = I * (Ru - R0) - I * dR0 * d_th
                # y+ = U + 2 h phi3(M) D, phi3(M) D = D / 6 + D0 phi4(a) (a, h I R', h)
                e_th = 2.0 * hs * (D0 / 6.0 + D0 * p4 * a)
                e_V = 2.0 * hs * (D1 / 6.0 + D0 * p4 * bI)
                e_T = 2.0 * hs * (D0 * p4 * hs)
                new = u_th + e_th
                dV = u_V + e_V
                dT = u_T + e_T
                ok = math.isfinite(new) and Ts + new > 0.0
                if ok:
                    f1, R1, dR1 = _rhs(new, Ts, Q, I2, R_ref, B, T_ref, g, C)
                    err_th = e_th
                    err_V = e_V
    else:
        c = 1.0 if method == M_BACKWARD_EULER else 0.5
        new, f1, R1, ok = _step_implicit(th, f0, R0, hs, c, Ts, Q, I, R_ref, B, T_ref, g, C)
        if ok:
            if method == M_BACKWARD_EULER:
                dV = hs * I * R1
                dT = hs * new
            else:
                dV = 0.5 * hs * I * (R0 + R1)
                dT = 0.5 * hs * (th + new)
            dR1 = -B * R1 / ((Ts + new) * (Ts + new))
    return new, dV, dT, ok, f1, R1, dR1, err_th, err_V


@njit(cache=True)
def _order(method):
    if method == M_RK4:
        return 4
    if method == M_BACKWARD_EULER:
        return 1
    if method == M_EXPONENTIAL:
        return 3
    return 2


@njit(cache=True)
def _heat(x, Ts, Q, I2, R_ref, B, T_ref, g):
    """C dtheta/dt during the pulse, W (the sign of the motion); +inf near 0 K."""
    R = resistance(Ts + x, R_ref, B, T_ref)
    return (I2 * R if I2 > 0.0 else 0.0) + Q - g * x


@njit(cache=True)
def quasi_static_pulse(th, Ts, Q, I, R_ref, B, T_ref, g, t_int, T_max):
    """One bias pulse in the tau -> 0 limit: theta reaches at once the equilibrium that the
    motion from ``th`` meets first (the first sign change of the heat balance in the
    direction it drives theta) and stays there.

    The root is bracketed by steps growing by 2 from ``th`` and bisected to the last bit.
    Returns (theta_end, int V dt, int theta dt, status, 1, M_QUASI_STATIC): STATUS_RUNAWAY
    if no equilibrium lies below ``T_max``, STATUS_INVALID if the pixel would cool to 0 K.
    """
    I2 = I * I
    h0 = _heat(th, Ts, Q, I2, R_ref, B, T_ref, g)
    root = th
    if h0 != 0.0:
        s = 1.0 if h0 > 0.0 else -1.0
        a = th
        step = 1e-3 * (1.0 + abs(th))
        while True:
            b = a + s * step
            if s > 0.0 and Ts + b > T_max:
                b = T_max - Ts
                if _heat(b, Ts, Q, I2, R_ref, B, T_ref, g) > 0.0:
                    return b, 0.0, 0.0, STATUS_RUNAWAY, 1, M_QUASI_STATIC
            elif s < 0.0 and not Ts + b > 0.0:
                b = a - 0.5 * (Ts + a)  # halfway to 0 K: T never reaches it
                if not Ts + b > 0.0 or b == a:
                    return a, 0.0, 0.0, STATUS_INVALID, 1, M_QUASI_STATIC
            if _heat(b, Ts, Q, I2, R_ref, B, T_ref, g) * s <= 0.0:
                break
            a = b
            step *= 2.0
        while True:  # bisection: the motion side stays at a, the far side at b
            m = 0.5 * (a + b)
            if m == a or m == b:
                break
            if _heat(m, Ts, Q, I2, R_ref, B, T_ref, g) * s > 0.0:
                a = m
            else:
                b = m
        ha = abs(_heat(a, Ts, Q, I2, R_ref, B, T_ref, g))
        hb = abs(_heat(b, Ts, Q, I2, R_ref, B, T_ref, g))
        root = a if ha <= hb else b
    V = I * resistance(Ts + root, R_ref, B, T_ref)
    return root, V * t_int, root * t_int, STATUS_OK, 1, M_QUASI_STATIC


@njit(cache=True)
def equilibrium_rate(theta, Ts, I, R_ref, B, T_ref, g):
    """C |df/dtheta| at theta, W/K: g - I^2 dR/dT (dR/dT = -B R / T^2)."""
    T = Ts + theta
    return g + I * I * B * resistance(T, R_ref, B, T_ref) / (T * T)


@njit(cache=True)
def pulse(th, Ts, Q, I, R_ref, B, T_ref, g, C, t_int, method, steps, max_sub, T_max,
          refuse_unstable, rtol):
    """Integrate one bias pulse of length t_int from theta = th.

    Fixed steps (rtol <= 0): ``steps`` equal steps, split where stability (RK4) or a failed
    step (others) needs it. Adaptive (rtol > 0): the exponential method uses its embedded
    error estimate, the others step doubling with local Richardson extrapolation. A step is
    accepted when the error estimate is within rtol (theta against |theta| + THETA_FLOOR,
    the voltage integral against itself); ``steps`` sets the first step t_int / steps.
    ``method`` M_AUTO starts with RK4 and switches to M_EXPONENTIAL where the pixel is stiff.

    Returns (theta_end, int V dt, int theta dt, status, substeps, method used last).
    ``auto`` and ``exponential`` take a pulse whose stiffness (g t_int / C, and t_int
    |df/dtheta| at the equilibrium) is at least QUASI_STATIC in the tau -> 0 limit
    (:func:`quasi_static_pulse`).
    """
    if (method == M_AUTO or method == M_EXPONENTIAL) and g * t_int >= QUASI_STATIC * C:
        qs = quasi_static_pulse(th, Ts, Q, I, R_ref, B, T_ref, g, t_int, T_max)
        # Stiff at the equilibrium too (a positive TCR lowers the rate there), or no
        # equilibrium at all (runaway, 0 K): the limit is the answer.
        if qs[3] != STATUS_OK or (equilibrium_rate(qs[0], Ts, I, R_ref, B, T_ref, g) * t_int
                                  >= QUASI_STATIC * C):
            return qs
    I2 = I * I
    iV = 0.0
    iT = 0.0
    sub = 0
    f0, R0, dR0 = _rhs(th, Ts, Q, I2, R_ref, B, T_ref, g, C)
    adaptive = rtol > 0.0
    cur = M_RK4 if method == M_AUTO else method
    p = _order(cur)
    rich = 1.0 / (2.0**p - 1.0)
    fail_status = STATUS_STEP_LIMIT if method == M_RK4 else STATUS_NO_CONVERGENCE
    h_nom = t_int / steps
    hs = h_nom
    t = 0.0
    k_nom = 1  # fixed mode: index of the nominal step being integrated
    settled = not adaptive
    while t < t_int:
        if sub >= max_sub:
            return th, iV, iT, fail_status, sub, cur
        end = t_int if (adaptive or k_nom >= steps) else k_nom * h_nom
        rem = end - t
        hs = min(hs, rem)
        if cur == M_RK4:
            lam = abs((I2 * dR0 - g) / C)
            if lam * hs > RK4_STABILITY:
                m = math.ceil(rem * lam / RK4_STABILITY)
                # Only a step the accuracy control asked for (adaptive: after the first
                # accepted step; fixed: the nominal step) can prove the pixel stiff; the
                # first guess t_int / steps says nothing about accuracy.
                if method == M_AUTO:
                    if settled and lam * hs > AUTO_SWITCH * RK4_STABILITY:
                        # Stiff here: the exponential method takes the step RK4 cannot.
                        cur = M_EXPONENTIAL
                        p = _order(cur)
                        rich = 1.0 / (2.0**p - 1.0)
                    else:  # the fast transient: RK4 at its stability limit resolves it
                        hs = RK4_STABILITY / lam
                else:
                    if method == M_RK4 and (refuse_unstable or m > max_sub - sub):
                        return th, iV, iT, STATUS_STEP_LIMIT, sub + m, cur
                    hs = min(hs, rem / m)
        new, dV, dT, ok, f1, R1, dR1, e_th, e_v = _attempt(cur, th, f0, R0, dR0, hs, Ts, Q,
                                                           I, R_ref, B, T_ref, g, C)
        sub += 1
        hs_next = hs
        if ok and adaptive and cur == M_EXPONENTIAL:
            # Embedded pair: the estimate is that of the order-2 stage (local error h^3).
            err = max(abs(e_th) / (rtol * (abs(new) + THETA_FLOOR)),
                      abs(e_v) / (rtol * abs(dV) + 1e-300))
            fac = min(5.0, max(0.2, 0.9 * (err + 1e-300) ** (-1.0 / 3.0)))
            if err > 1.0:
                hs *= fac
                continue
            hs_next = hs * fac
        elif ok and adaptive:
            hh = 0.5 * hs
            m1, dV1, dT1, ok, fa, Ra, dRa, _, _ = _attempt(cur, th, f0, R0, dR0, hh, Ts, Q, I,
                                                           R_ref, B, T_ref, g, C)
            if ok:
                m2, dV2, dT2, ok, _fb, _Rb, _dRb, _, _ = _attempt(cur, m1, fa, Ra, dRa, hh, Ts,
                                                                  Q, I, R_ref, B, T_ref, g, C)
            sub += 2
            if ok:
                # Local Richardson extrapolation: two half steps plus their error estimate.
                e_th = (m2 - new) * rich
                e_v = (dV1 + dV2 - dV) * rich
                e_test = abs(e_v)
                if cur == M_BACKWARD_EULER:
                    # The right-rectangle voltage integral misses a transient shorter than
                    # the step, and so does step doubling (both halves land on the same
                    # equilibrium); the rectangle's own error h (V1 - V0) / 2 sees it.
                    e_test = max(e_test, 0.5 * hs * I * abs(R1 - R0))
                err = max(abs(e_th) / (rtol * (abs(m2) + THETA_FLOOR)),
                          e_test / (rtol * abs(dV1 + dV2) + 1e-300))
                fac = min(5.0, max(0.2, 0.9 * (err + 1e-300) ** (-1.0 / (p + 1.0))))
                if err > 1.0:
                    hs *= fac
                    continue
                hs_next = hs * fac
                dT = dT1 + dT2 + (dT1 + dT2 - dT) * rich
                dV = dV1 + dV2 + e_v
                new = m2 + e_th
                ok = math.isfinite(new) and Ts + new > 0.0
                if ok:
                    f1, R1, dR1 = _rhs(new, Ts, Q, I2, R_ref, B, T_ref, g, C)
        if not ok:
            if method == M_RK4 and not adaptive:
                return th, iV, iT, STATUS_STEP_LIMIT, sub, cur
            hs *= 0.5
            continue
        if not adaptive:
            hs_next = h_nom if cur == M_RK4 else min(2.0 * hs, h_nom)
        th = new
        f0, R0, dR0 = f1, R1, dR1
        iV += dV
        iT += dT
        t_new = t + hs
        if end - t_new <= 1e-12 * t_int:
            t_new = end
            k_nom += 1
        t = t_new
        hs = hs_next
        settled = True
        if not Ts + th <= T_max:
            return th, iV, iT, STATUS_RUNAWAY, sub, cur
    return th, iV, iT, STATUS_OK, sub, cur


@njit(cache=True, parallel=True)
def integrate_frames(Q, Ts, R_ref, g, C, theta0, B, T_ref, I, t_int, frame_period,
                     pulse_start, warmup, method, steps, max_sub, T_max, refuse_unstable, rtol,
                     v_out, dT_out, dTend_out, status_out, sub_out, meth_out, Ts_before):
    """A sequence of frames for a flat array of pixels.

    Parameters: Q (N, P) W, Ts (N,) K, R_ref, g, C, theta0 (P,) (theta0 relative to the
    substrate at the start of the first frame, before any warm-up frame). Every frame:
    relax (no bias) until pulse_start, one bias pulse of t_int, relax until frame_period.
    Frame n's substrate goes linearly from Ts[n - 1] (``Ts_before`` for frame 0) at its
    start to Ts[n] at its end (a first-order hold: theta = T - T_s relaxes with the forcing
    -C dT_s/dt, exactly); during the pulse it is held at its mid-pulse value. ``warmup``
    copies of frame 0 (the substrate constant at Ts[0]) run first without output.

    Writes per frame and pixel: the mean bolometer voltage over the pulse (V), the mean
    rise over the pulse and the rise at its end (K), the status, the substeps used and the
    integrator code that finished the pulse (``auto`` reports RK4 or exponential).
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
        used = method
        last_v = I * resistance(Ts[0] + th, Rp, B, T_ref) if Ts[0] + th > 0.0 else 0.0
        last_mean = th
        for k in range(warmup + n_frames):
            n = k - warmup if k >= warmup else 0
            if k < warmup:
                t0 = Ts[0]
            elif n == 0:
                t0 = Ts_before
            else:
                t0 = Ts[n - 1]
            rate = (Ts[n] - t0) / frame_period
            T_pulse = t0 + rate * (pulse_start + 0.5 * t_int)  # the substrate at mid-pulse
            shift = 0.5 * rate * t_int
            if st == STATUS_OK:
                q = Q[n, p]
                th = relax_ramp(th, q, gp, Cp, pulse_start, rate) - shift
                th_end, iV, iT, st_p, nsub, used = pulse(th, T_pulse, q, I, Rp, B, T_ref, gp,
                                                         Cp, t_int, method, steps, max_sub,
                                                         T_max, refuse_unstable, rtol)
                if st_p == STATUS_OK:
                    last_v = iV / t_int
                    last_mean = iT / t_int
                    th = relax_ramp(th_end - shift, q, gp, Cp, after, rate)
                else:
                    st = st_p
                    if math.isfinite(th_end) and T_pulse + th_end > 0.0:
                        last_v = I * resistance(T_pulse + th_end, Rp, B, T_ref)
                        last_mean = th_end
            else:
                nsub = 0
            if k >= warmup:
                v_out[n, p] = last_v
                dT_out[n, p] = last_mean
                dTend_out[n, p] = th_end if st == STATUS_OK else last_mean
                status_out[n, p] = st
                sub_out[n, p] = nsub
                meth_out[n, p] = used


def empty_outputs(shape):
    """Output arrays of :func:`integrate_frames` for a (N, P) problem."""
    return (np.empty(shape), np.empty(shape), np.empty(shape), np.empty(shape, np.uint8),
            np.empty(shape, np.int64), np.empty(shape, np.uint8))
