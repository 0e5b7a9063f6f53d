"""Electro-thermal solve against scipy.optimize.brentq; the self-heating factor against mpmath."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.optimize import brentq

from irnuc.model.core import bolometer as kb

mp.mp.dps = 40


def self_heating_reference(u):
    u = mp.mpf(u)
    return 1 + (mp.exp(-u) - 1) / u


@pytest.mark.parametrize("u", np.concatenate([np.logspace(-14, 4, 37), [0.2499, 0.25, 0.2501]]))
def test_self_heating_factor_matches_mpmath(u):
    got = kb.self_heating_factor(float(u))
    ref = self_heating_reference(u)
    assert abs((mp.mpf(got) - ref) / ref) < 1e-14


def test_self_heating_limits():
    assert kb.self_heating_factor(0.0) == 0.0
    assert kb.self_heating_factor(math.inf) == 1.0


def test_naive_self_heating_cancels_for_long_time_constants():
    # tau = 1e10 t: the reference's form loses every digit, ours keeps them.
    u = 1e-10
    ref = self_heating_reference(u)
    naive = kb.self_heating_factor_naive(u)
    assert abs((mp.mpf(naive) - ref) / ref) > 1e-3
    assert abs((mp.mpf(kb.self_heating_factor(u)) - ref) / ref) < 1e-15


def random_pixels(n, seed, tcr_sign=-1.0):
    rng = np.random.default_rng(seed)
    return [
        dict(
            Q=rng.uniform(-1e-9, 2e-8),
            R_ref=rng.uniform(1e4, 2e6),
            B=-tcr_sign * rng.uniform(0.005, 0.04) * 300.0**2,
            g=rng.uniform(5e-9, 2e-7),
            I=rng.uniform(0.0, 6e-5),
            f=rng.uniform(1e-4, 1.0),
            T_s=rng.uniform(250.0, 350.0),
        )
        for _ in range(n)
    ]


@pytest.mark.parametrize("seed", range(4))
def test_newton_matches_brentq_negative_tcr(seed):
    for p in random_pixels(50, seed):
        a = p["Q"] / p["g"]
        b = p["I"] ** 2 * p["f"] / p["g"]

        def h(x, p=p, a=a, b=b):
            return x - a - b * p["R_ref"] * math.exp(p["B"] * (1 / (p["T_s"] + x) - 1 / 300.0))

        x, status, iters = kb.solve_delta_t(a, b, p["R_ref"], p["B"], 300.0, p["T_s"], 1e-12,
                                            100, math.nan, 1e4)
        assert status == kb.STATUS_OK and iters <= 60
        lo, hi = a, a + b * p["R_ref"] * math.exp(p["B"] * (1 / (p["T_s"] + a) - 1 / 300.0))
        ref = brentq(h, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500) \
            if hi > lo else lo
        assert abs(x - ref) <= 1e-12 * abs(ref) + 1e-14


def test_positive_tcr_small_bias_finds_lowest_root():
    R_ref, B, T_s = 1e3, -0.003 * 300.0**2, 300.0
    a, b = 0.01, 1e-3  # loop gain ~ b R |B| / T^2 ~ 3e-3
    x, status, _ = kb.solve_delta_t(a, b, R_ref, B, 300.0, T_s, 1e-12, 100, math.nan, 1000.0)
    assert status == kb.STATUS_OK
    ref = brentq(lambda d: d - a - b * R_ref * math.exp(B * (1 / (T_s + d) - 1 / 300.0)),
                 a, a + b * R_ref * math.exp(-B / 300.0), xtol=1e-300, rtol=1e-15)
    assert x == pytest.approx(ref, rel=1e-11)


def test_positive_tcr_strong_bias_reports_runaway_not_nan():
    R_ref, B = 1e3, -0.02 * 300.0**2
    x, status, _ = kb.solve_delta_t(0.0, 0.5, R_ref, B, 300.0, 300.0, 1e-12, 100, math.nan, 1000.0)
    assert status == kb.STATUS_RUNAWAY
    assert math.isfinite(x)


def test_unphysical_temperature_is_invalid():
    # The unbiased equilibrium T_s + a is below 0 K. Without bias (b = 0) or with a positive
    # TCR (R -> 0 as T -> 0) nothing holds the pixel above 0 K: invalid, at 0 K.
    for b, B in ((0.0, 2700.0), (1.0, -2700.0)):
        x, status, _ = kb.solve_delta_t(-400.0, b, 1e5, B, 300.0, 300.0, 1e-12, 100, math.nan,
                                        1000.0)
        assert status == kb.STATUS_INVALID and x == -300.0
    # A negative TCR with bias: R grows without bound as T -> 0, so the biased equilibrium
    # exists above 0 K (issue 19; it was called invalid): its residual vanishes.
    x, status, _ = kb.solve_delta_t(-400.0, 1.0, 1e5, 2700.0, 300.0, 300.0, 1e-12, 100,
                                    math.nan, 1000.0)
    T = 300.0 + x
    assert status == kb.STATUS_OK and T > 0.0
    rhs = -400.0 + 1e5 * math.exp(2700.0 * (1 / T - 1 / 300.0))
    assert x == pytest.approx(rhs, rel=1e-12)


def test_variants_differ_only_in_the_scene_term():
    # Zero bias: the equilibrium variant gives Q/g, the paper's eq. 19 gives Q f / g.
    Q, g, C, t = 2e-9, 1e-8, 1e-10, 6e-5
    shape = (1, 1, 1)
    out = {}
    for variant in (0, 1):
        dT = np.empty(shape)
        v = np.empty(shape)
        st = np.empty(shape, np.uint8)
        it = np.empty(shape, np.int32)
        kb.solve_frames(np.full(shape, Q), np.full((1, 1), 1e5), np.full((1, 1), g),
                        np.full((1, 1), C), 1500.0, 300.0, 300.0, 0.0, t, variant, 1e-12, 100,
                        1000.0, dT, v, st, it)
        out[variant] = dT[0, 0, 0]
    f = float(self_heating_reference(t * g / C))
    assert out[0] == pytest.approx(Q / g, rel=1e-14)
    assert out[1] == pytest.approx(Q * f / g, rel=1e-13)


def test_solve_frames_every_pixel_satisfies_the_balance():
    rng = np.random.default_rng(7)
    shape = (2, 5, 6)
    Q = rng.uniform(0, 1e-8, shape)
    R = rng.uniform(9e4, 1.1e5, shape[1:])
    g = rng.uniform(0.9e-8, 1.1e-8, shape[1:])
    C = rng.uniform(0.9e-10, 1.1e-10, shape[1:])
    dT, v = np.empty(shape), np.empty(shape)
    st, it = np.empty(shape, np.uint8), np.empty(shape, np.int32)
    B, I, t = 2250.0, 1.5e-5, 6e-5
    kb.solve_frames(Q, R, g, C, B, 300.0, 300.0, I, t, 0, 1e-12, 100, 1000.0, dT, v, st, it)
    assert (st == kb.STATUS_OK).all()
    for n, i, j in np.ndindex(shape):
        f = float(self_heating_reference(t * g[i, j] / C[i, j]))
        a, b = Q[n, i, j] / g[i, j], I * I * f / g[i, j]
        ref = brentq(lambda x, i=i, j=j, a=a, b=b: x - a - b * R[i, j] * math.exp(
            B * (1 / (300.0 + x) - 1 / 300.0)), a, a + 10 * b * R[i, j], xtol=1e-300, rtol=1e-15)
        assert dT[n, i, j] == pytest.approx(ref, rel=1e-11)
        assert v[n, i, j] == pytest.approx(I * R[i, j] * math.exp(B * (1 / (300 + ref) - 1 / 300)),
                                           rel=1e-11)


def _lowest_root_by_scan(a, bR, B, T_s=300.0, T_max=1000.0):
    """Independent reference: the first sign change of h on a 20001-point grid up to
    T_max, refined by brentq; None if h < 0 everywhere (no equilibrium below T_max)."""
    def h(x):
        return x - a - bR * math.exp(B * (1 / (T_s + x) - 1 / 300.0))

    xs = np.linspace(a, T_max - T_s, 20001)
    hv = xs - a - bR * np.exp(B * (1 / (T_s + xs) - 1 / 300.0))
    up = np.flatnonzero(hv >= 0)
    if up.size == 0:
        return None
    k = up[0]
    return brentq(h, xs[k - 1], xs[k], xtol=1e-300, rtol=8.9e-16) if k else a


def test_positive_tcr_stable_root_beyond_a_loop_gain_of_one_is_not_a_runaway():
    # The loop gain b |R'| exceeds 1 between a and the root, then falls (R ~ exp(-|B|/T)
    # is concave above |B|/2): the old fixed point reported runaway at the first iterate
    # with gain >= 1. The stable equilibrium is at 888 K with a loop gain of 0.42.
    a, bR, B = 4.559087501773518, 166.92007922578986, -566.9835795851737
    x, status, _ = kb.solve_delta_t(a, bR / 1e5, 1e5, B, 300.0, 300.0, 1e-12, 100, math.nan,
                                    1000.0)
    ref = _lowest_root_by_scan(a, bR, B)
    assert status == kb.STATUS_OK
    assert x == pytest.approx(ref, rel=1e-12)
    T = 300.0 + ref
    gain = -bR * math.exp(B * (1 / T - 1 / 300.0)) * B / T**2
    assert 0.3 < gain < 0.5
    xs = np.linspace(a, ref, 1000)
    gains = -bR * np.exp(B * (1 / (300 + xs) - 1 / 300.0)) * B / (300 + xs) ** 2
    assert gains.max() > 1.0  # the case the fixed point got wrong


def test_positive_tcr_random_draws_against_a_scan():
    # 3000 seeded draws of TCR, bias heating and scene heating: the status and the root
    # agree with the grid scan (runaway exactly when no root lies below T_max).
    rng = np.random.default_rng(1)
    n = 3000
    B = -rng.uniform(0.001, 0.05, n) * 300.0**2
    bR = 10 ** rng.uniform(-2, 3, n)
    a = rng.uniform(0, 50, n)
    counts = {"ok": 0, "runaway": 0}
    for i in range(n):
        ref = _lowest_root_by_scan(a[i], bR[i], B[i])
        x, status, _ = kb.solve_delta_t(a[i], bR[i] / 1e5, 1e5, B[i], 300.0, 300.0, 1e-12, 100,
                                        math.nan, 1000.0)
        if ref is None:
            assert status == kb.STATUS_RUNAWAY, i
            counts["runaway"] += 1
        else:
            assert status == kb.STATUS_OK, i
            assert abs(x - ref) <= 1e-11 * abs(ref) + 1e-13, i
            counts["ok"] += 1
    assert min(counts.values()) > 100  # both outcomes are exercised
