"""Extreme-case suite: every case ends in a correct finite result or a clear error.

The table of cases is docs/extreme_cases.md; ``test_every_documented_case_has_a_test``
keeps it true (each row names its test here).
"""

from __future__ import annotations

import math
import re
import tracemalloc
import warnings
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from irnuc import model
from irnuc.model.adc import NonFiniteVoltageError, adc_convert
from irnuc.model.core.bolometer import (
    STATUS_INVALID,
    STATUS_OK,
    STATUS_RUNAWAY,
    self_heating_factor,
    self_heating_factor_naive,
)
from irnuc.model.fpa import SPREAD_DISTRIBUTIONS, ArrayLayout, draw_pixel_parameters
from irnuc.model.validate import ConfigError
from irnuc.reports.studies.precision import band_radiance_mp

DOC = Path(__file__).resolve().parents[1] / "docs" / "extreme_cases.md"
SMALL = {"fpa.active_rows": 8, "fpa.active_cols": 10}


def _cfg(**over):
    return model.load_preset("default", {**SMALL, **over})


def _sim(cfg, temps=(300.0, 400.0), **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # solver-failure warnings
        return model.simulate(cfg, list(temps), **kw)


# ---- temperatures --------------------------------------------------------------------

TEMPS = [1e-300, 1e-100, 1e-5, 1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 100.0, 300.0, 1000.0, 3000.0,
         5000.0, 10000.0, 1e6, 1e9]
FLOAT64_TINY = 2.2250738585072014e-308  # smallest normal float64


def test_radiance_1e_300K_to_1e9K_against_mpmath():
    # Relative tolerance 1e-12 (no absolute slack) wherever the true radiance is a normal
    # float64; below it 0 or the right subnormal, never NaN. Reference: 80-digit mpmath
    # series, which does not underflow (its polylog form lost the main term below 15 K).
    L = model.band_radiance(np.array(TEMPS))
    assert np.isfinite(L).all() and (L >= 0).all()
    for T, got in zip(TEMPS, L, strict=True):
        ref = band_radiance_mp(T, as_mpf=True)
        if ref >= FLOAT64_TINY:
            assert abs((mp.mpf(float(got)) - ref) / ref) < 1e-12, T
        else:
            assert abs(mp.mpf(float(got)) - ref) <= 1e-323, T


def test_near_zero_scene_reads_the_low_end_not_a_runaway_rail():
    # A scene at 1e-200 K radiates nothing: the frame is finite, no pixel fails, no
    # runaway warning, and it reads below a 300 K scene.
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        fr = model.simulate(_cfg(), [1e-200, 300.0], outputs=("codes", "status"))
    assert (fr.outputs["status"] == STATUS_OK).all()
    assert fr.codes[0].mean() < fr.codes[1].mean()


def test_radiance_hotter_than_1e9K_is_a_clear_error():
    with pytest.raises(ConfigError, match=r"^T = 1e\+10 K .*allowed range \(0, 1e\+09\]"):
        model.band_radiance(1e10)


@pytest.mark.parametrize("band", [(8e-6 - 1e-12, 8e-6 + 1e-12), (7.999e-6, 8.001e-6)])
def test_narrow_band_radiance_relative_error(band):
    for T in (30.0, 300.0, 3000.0):
        ref = band_radiance_mp(T, band, as_mpf=True)
        got = mp.mpf(float(model.band_radiance(T, band=band)))
        assert abs((got - ref) / ref) < 1e-12, (band, T)


def _ulps_above(x, n):
    for _ in range(n):
        x = np.nextafter(x, 1.0)
    return float(x)


COLD_BANDS = {"one ulp": (8e-6, _ulps_above(8e-6, 1)), "1e-15 m": (8e-6, 8e-6 + 1e-15),
              "8 um +- 1 pm": (8e-6 - 1e-12, 8e-6 + 1e-12), "1 nm": (8e-6, 8.001e-6)}


@pytest.mark.parametrize("band", list(COLD_BANDS.values()), ids=list(COLD_BANDS))
def test_narrow_band_in_the_cold_branch_against_mpmath(band):
    # x = hc/(lambda k T) near and above 600, where the radiance is the first tail term in
    # log space: 1e-12 relative to the 80-digit mpmath series (was 2.5e-4 for one ulp and
    # 1.5e-11 for 1e-15 m at 2.99 K: logs of ratios rounded near 1).
    for T in (2.99, 2.9975, 3.0, 2.5, 1.8):
        ref = band_radiance_mp(T, band, as_mpf=True)
        got = mp.mpf(float(model.band_radiance(T, band=band)))
        if ref >= FLOAT64_TINY:
            assert abs((got - ref) / ref) < 1e-12, (band, T)
        else:
            assert abs(got - ref) <= 1e-323, (band, T)


def test_narrow_bands_random_cold_scan_against_mpmath():
    # Seeded draws: bands of 1-40 ulps, 1e-15..1e-6 and 1e-6..3 relative width at 3-20 um,
    # the temperature set so that x2 spans 100..710 (both sides of the log-space branch).
    rng = np.random.default_rng(19)
    worst = 0.0
    for _ in range(60):
        lam1 = 10 ** rng.uniform(math.log10(3e-6), math.log10(20e-6))
        kind = int(rng.integers(0, 3))
        lam2 = (_ulps_above(lam1, int(rng.integers(1, 40))) if kind == 0
                else lam1 * (1 + 10 ** rng.uniform(-15, -6) if kind == 1
                             else 1 + 10 ** rng.uniform(-6, 0.5)))
        T = 0.014387768775039337 / (lam2 * rng.uniform(100.0, 710.0))
        ref = band_radiance_mp(T, (lam1, lam2), as_mpf=True)
        if ref < FLOAT64_TINY:
            continue
        got = mp.mpf(float(model.band_radiance(T, band=(lam1, lam2))))
        worst = max(worst, float(abs((got - ref) / ref)))
    assert worst < 1e-12


@pytest.mark.parametrize("T", [1e-313, 1e-315, 5e-324])
def test_subnormal_temperatures_give_zero_radiance_and_frames(T, tmp_path):
    # T in (0, 1e9] is legal: a subnormal T is a scene at 0 K, never a ZeroDivisionError
    # (lambda * T underflowed to 0 inside the kernel) in the radiance, the steady and the
    # transient model or `irnuc frames`.
    from irnuc.cli import main
    from irnuc.model.transient import simulate_transient

    assert model.band_radiance(T) == 0.0
    assert model.band_radiance(T, band=COLD_BANDS["one ulp"]) == 0.0
    cfg = _cfg(**{"fpa.active_rows": 3, "fpa.active_cols": 4})
    cold = _sim(cfg, [T, 1e-200]).codes
    assert (cold[0] == cold[1]).all()  # both scenes radiate nothing
    tf = simulate_transient(cfg, [T, 300.0])
    assert np.isfinite(tf.codes).all() and tf.codes.shape == (2, 3, 4)
    assert main(["frames", "-q", "--temps", f"{T!r}", "--set", "fpa.active_rows=3",
                 "--set", "fpa.active_cols=4", "--out", str(tmp_path / "f")]) == 0


@pytest.mark.parametrize("bad", [0.0, -5.0, math.nan, math.inf, -math.inf])
def test_bad_temperatures_are_clear_errors(bad):
    with pytest.raises(ConfigError, match=r"^T = .*allowed range|^T = .*not finite"):
        model.band_radiance(np.array([300.0, bad]))
    with pytest.raises(ConfigError, match="temps"):
        model.simulate(_cfg(), [300.0, bad])
    with pytest.raises(ConfigError, match="T_substrate"):
        model.load_preset("default", {"environment.T_substrate": bad})


# ---- tolerances ------------------------------------------------------------------------

@pytest.mark.parametrize("dist", sorted(SPREAD_DISTRIBUTIONS))
def test_tolerance_up_to_one_never_gives_nonpositive_parameters(dist):
    lay = ArrayLayout(200, 200)
    p = draw_pixel_parameters(lay, {"R_ref": 1e5, "g": 1e-8, "C": 1e-10},
                              {"R_ref": 1.0, "g": 1.0, "C": 1.0}, seed=5, distribution=dist)
    for v in p.values():
        assert np.isfinite(v).all() and (v > 0).all()


def test_tolerance_one_gives_finite_frames():
    cfg = _cfg(**{"fpa.tolerance": {"R_ref": 1.0, "g": 1.0, "C": 1.0}})
    fr = _sim(cfg)
    assert fr.codes.dtype == np.uint16 and fr.codes.max() < 2**14
    with pytest.raises(ConfigError, match=r"fpa\.tolerance\.g"):
        _cfg(**{"fpa.tolerance": {"g": 1.5}})


# ---- self-heating factor: tau -> 0 and tau -> inf --------------------------------------

def _f_mp(u):
    # Digits enough for the cancellation in 1 - (1 - e^-u)/u at u down to 1e-300.
    with mp.workdps(50 + max(0, int(-math.log10(u)) if u > 0 else 0)):
        um = mp.mpf(u)
        return float(1 + mp.expm1(-um) / um)


@pytest.mark.parametrize("u", [1e-300, 1e-16, 1e-12, 1e-8, 1e-4, 0.01, 0.2499, 0.25, 1.0,
                               30.0, 1e4, 1e12, 1e300])
def test_self_heating_factor_stable_for_every_tau(u):
    assert self_heating_factor(u) == pytest.approx(_f_mp(u), rel=1e-14)


def test_naive_self_heating_factor_cancels_where_ours_does_not():
    # tau = 1e6 t_int (u = 1e-6): the naive 1 + (e^-u - 1)/u loses ~10 digits, and at
    # u = 1e-17 it is not even positive; the expm1 form stays at full precision.
    for u in (1e-6, 1e-9):
        naive = self_heating_factor_naive(u)
        assert abs(naive - _f_mp(u)) / _f_mp(u) > 1e-8
        assert self_heating_factor(u) == pytest.approx(_f_mp(u), rel=1e-14)
    # u = 1e-17: e^-u rounds to 1 and the naive form returns 1 instead of 5e-18.
    assert abs(self_heating_factor_naive(1e-17) - _f_mp(1e-17)) > 1e3 * _f_mp(1e-17)
    assert self_heating_factor(1e-17) == pytest.approx(_f_mp(1e-17), rel=1e-14)
    assert self_heating_factor(0.0) == 0.0 and self_heating_factor(math.inf) == 1.0


@pytest.mark.parametrize("C", [1e-30, 1e30])
def test_tau_extremes_give_finite_frames(C):
    fr = _sim(_cfg(**{"bolometer.C": C}), outputs=("codes", "status"))
    assert np.isfinite(fr.codes).all()
    assert (fr.outputs["status"] == STATUS_OK).all()


def _tau_zero_limit(Q, Ts, p, b):
    """Per frame and pixel, the equilibrium of the biased pixel, I^2 R + Q = g theta (the
    tau -> 0 limit of a pulse), by scipy's brentq: (voltage I R, theta)."""
    from scipy.optimize import brentq

    B = -b["tcr"] * b["T_ref"] ** 2
    I2 = b["bias_current"] ** 2
    v = np.empty(Q.shape)
    th = np.empty(Q.shape)
    for n, i, j in np.ndindex(*Q.shape):
        g, R0, q, ts = p["g"][i, j], p["R_ref"][i, j], Q[n, i, j], Ts[n]

        def R(x, R0=R0, ts=ts):
            return R0 * math.exp(B * (1 / (ts + x) - 1 / b["T_ref"]))

        lo = q / g  # unbiased: the heat balance is >= 0 here and <= 0 at hi (R falls)
        root = brentq(lambda x, R=R, q=q, g=g: I2 * R(x) + q - g * x, lo, lo + I2 * R(lo) / g,
                      xtol=1e-300, rtol=8.9e-16, maxiter=500)
        v[n, i, j], th[n, i, j] = b["bias_current"] * R(root), root
    return v, th


@pytest.mark.parametrize("C", [1e-24, 1e-26, 1e-30, 1e-40, 1e-60, 1e-100])
def test_any_accepted_C_is_solved_by_default_in_the_tau_to_zero_limit(C):
    # C down to 1e-100 J/K (the accepted range): the default integrator gives the tau -> 0
    # limit (the biased pixel's equilibrium, brentq) to 1e-12 (its rtol is 1e-9) or 10/stiffness,
    # whichever is larger; from stiffness 1e18 it takes that limit directly (1 solve per
    # pulse). Was: C = 1e-60 left most pulses unconverged at the top code; C = 1e-40 needed
    # 21,014 substeps.
    from irnuc.model import transient as tr
    from irnuc.reports.studies.precision import transient_problem

    prob = transient_problem("nonstiff")
    cfg, Q, Ts, p = prob["cfg"], prob["Q"], prob["T_s"], prob["params"]
    b = cfg["bolometer"]
    r = tr.integrate_pixels(Q, Ts, p["R_ref"], p["g"], C, tcr=b["tcr"], T_ref=b["T_ref"],
                            bias_current=b["bias_current"], t_int=b["t_int"])
    assert (r.status == STATUS_OK).all()
    v, th = _tau_zero_limit(Q, Ts, p, b)
    stiffness = float((p["g"] * b["t_int"] / C).min())
    err = max(float(np.max(np.abs(r.v_bolo - v) / v)), float(np.max(np.abs(r.dT_end - th) / th)))
    assert err <= max(1e-12, 10.0 / stiffness), err
    if stiffness >= 1e18:
        assert r.integrators_used() == {"quasi_static": Q.size} and (r.substeps == 1).all()
    else:
        assert r.substeps.max() < 700


def test_tiny_C_frames_equal_the_steady_model():
    # simulate_transient(cfg, [300, 310]) at C = 1e-60 (the audit's call): every pulse
    # solved, no pixel at the top code, the codes of the steady model (whose self-heating
    # factor is 1 in this limit).
    from irnuc.model.transient import simulate_transient

    cfg = _cfg(**{"bolometer.C": 1e-60})
    tf = simulate_transient(cfg, [300.0, 310.0], outputs=("codes", "status"))
    assert (tf.outputs["status"] == STATUS_OK).all()
    assert tf.codes.max() < 2**14 - 1
    np.testing.assert_array_equal(tf.codes, _sim(cfg, [300.0, 310.0]).codes)


def test_transient_error_at_g_1e_100_names_what_the_caller_gave():
    # The default initial state is the unbiased equilibrium T_s + Q/g; for net emitters on
    # g = 1e-100 it lies below 0 K. The error names transient.initial and bolometer.g (it
    # named theta0, which the caller never passed); with initial = 'substrate' it runs.
    from irnuc.model.transient import simulate_transient

    cfg = _cfg(**{"bolometer.g": 1e-100})
    with pytest.raises(ConfigError, match=r"^transient\.initial = 'equilibrium'.*bolometer\.g") as e:
        simulate_transient(cfg, [300.0])
    assert "theta0" not in str(e.value)
    tf = simulate_transient(cfg, [300.0], settings={"initial": "substrate"},
                            outputs=("codes", "status"))
    assert np.isfinite(tf.codes).all() and (tf.outputs["status"] == STATUS_OK).all()


def test_integration_time_zero_is_an_error():
    with pytest.raises(ConfigError, match=r"bolometer\.t_int = 0"):
        _cfg(**{"bolometer.t_int": 0.0})
    from irnuc.model.transient import integrate_pixels

    with pytest.raises(ConfigError, match=r"bolometer\.t_int"):
        integrate_pixels(np.ones((1, 1)) * 1e-9, 300.0, 1e5, 1e-8, 1e-10, tcr=-0.02,
                         T_ref=300.0, bias_current=1e-5, t_int=0.0)


@pytest.mark.parametrize("g", [1e-15, 1e-30])
def test_g_to_zero_reports_failed_pixels_not_garbage(g):
    # Q / g grows without bound: pixels past the runaway temperature (or below 0 K for a
    # net emitter) are reported per pixel; the frames stay finite codes.
    fr = _sim(_cfg(**{"bolometer.g": g}), outputs=("codes", "status", "temperature_rise"))
    s = fr.outputs["status"]
    T = 300.0 + fr.outputs["temperature_rise"]
    ok = s == STATUS_OK
    assert (T[ok] <= 1000.0).all()
    assert fr.diagnostics["solver_failures"]["runaway"] + \
        fr.diagnostics["solver_failures"]["invalid"] == int((~ok).sum()) > 0
    assert np.isfinite(fr.codes).all()


def _root_mp(a, b, R_ref, B, T_ref, T_s):
    """The root of x = a + b R(T_s + x) (B > 0, b > 0) by bisection in mpmath at 50 digits
    on ln(x - a) = ln(b R(T_s + x)), increasing in x, bracketed by max(a, -T_s) (-inf
    there) and max(a, 0) + b R(T_s + max(a, 0)) (>= 0 there: R falls with x)."""
    with mp.workdps(50):
        a, b, R_ref, B, T_ref, T_s = (mp.mpf(float(v)) for v in (a, b, R_ref, B, T_ref, T_s))

        def F(x):
            return mp.log(x - a) - mp.log(b * R_ref) - B * (1 / (T_s + x) - 1 / T_ref)

        lo = max(a, -T_s)
        top = max(a, mp.mpf(0))
        hi = top + b * R_ref * mp.exp(B * (1 / (T_s + top) - 1 / T_ref))
        while hi - lo > mp.mpf(10) ** -44 * abs(hi):
            m = (lo + hi) / 2
            lo, hi = (m, hi) if F(m) < 0 else (lo, m)
        return (lo + hi) / 2


def test_g_1e_100_every_output_finite_and_the_biased_equilibrium_right():
    # g = 1e-100 W/K (the bottom of the accepted range): pixels whose unbiased equilibrium
    # T_s + Q/g lies below 0 K (net emitters) still have exactly one biased equilibrium
    # above 0 K (R grows without bound as T -> 0); it is solved (40-digit mpmath root to
    # 1e-12), and no output holds NaN (temperature_rise and bolometer_voltage were NaN,
    # the pixels reported invalid).
    # (the self-heating-factor pulse model's solver; the pulse train's: the test below)
    b = _cfg()["bolometer"]
    cfg = _cfg(**{"bolometer.g": 1e-100, "bolometer.pulse": "self_heating"})
    fr = _sim(cfg, [300.0], outputs=("codes", "status", "temperature_rise",
                                      "bolometer_voltage", "params", "power"))
    dT, v = fr.outputs["temperature_rise"][0], fr.outputs["bolometer_voltage"][0]
    assert np.isfinite(dT).all() and np.isfinite(v).all()
    p, Q = fr.outputs["params"], fr.outputs["power"][0]
    Ts, I = cfg["environment"]["T_substrate"], cfg["bolometer"]["bias_current"]
    a = Q / p["g"]
    s = fr.outputs["status"][0]
    assert (s[Ts + a <= 0] == STATUS_OK).all() and (s != STATUS_INVALID).all()
    assert (s[a > 1e3] == STATUS_RUNAWAY).all()  # absorbers: Q/g of 1e76 K
    cold = np.argwhere(Ts + a <= 0)
    assert cold.size  # the case under test occurs
    B = -b["tcr"] * b["T_ref"] ** 2
    for i, j in cold[:6]:
        f = _f_mp(b["t_int"] * p["g"][i, j] / p["C"][i, j])
        ref = _root_mp(a[i, j], I * I * f / p["g"][i, j], p["R_ref"][i, j], B, b["T_ref"], Ts)
        assert abs((dT[i, j] - ref) / ref) < 1e-12
        assert 0 < Ts + dT[i, j] < Ts


def test_g_1e_100_pulse_train_runs_away_where_no_periodic_state_exists():
    # The integrated pulse train at g = 1e-100 W/K: between pulses a pixel loses only what
    # it absorbs less than it emits, |Q| P per period (Q < 0), while each pulse leaves at
    # least I^2 R_min t_int (R_min = R_ref exp(-B / T_ref), R of a negative TCR at T -> inf).
    # Where I^2 R_min t_int > -Q P no periodic state exists: the pixel runs away (counted,
    # high rail, every output finite).
    b = _cfg()["bolometer"]
    cfg = _cfg(**{"bolometer.g": 1e-100})
    fr = _sim(cfg, [300.0], outputs=("codes", "status", "temperature_rise",
                                      "bolometer_voltage", "power"))
    for k in ("temperature_rise", "bolometer_voltage"):
        assert np.isfinite(fr.outputs[k]).all()
    B = -b["tcr"] * b["T_ref"] ** 2
    r_min = b["R_ref"] * math.exp(-B / b["T_ref"])
    period = 1.0 / cfg["readout"]["frame_rate"]
    Q = fr.outputs["power"][0]
    no_state = b["bias_current"] ** 2 * r_min * b["t_int"] > -Q * period
    s = fr.outputs["status"][0]
    assert no_state.all() and (s[no_state] == STATUS_RUNAWAY).all()
    assert fr.diagnostics["solver_failures"]["runaway"] == s.size
    assert (fr.codes == 2**14 - 1).all()


def test_no_equilibrium_above_0K_is_invalid_with_the_values_at_0K():
    # Without bias nothing holds a net emitter above 0 K: status invalid, the pixel at the
    # bound it falls to (temperature_rise = -T_substrate) and 0 V (no current), never NaN.
    cfg = _cfg(**{"bolometer.g": 1e-100, "bolometer.bias_current": 0.0})
    fr = _sim(cfg, [300.0], outputs=("codes", "status", "temperature_rise", "bolometer_voltage"))
    s = fr.outputs["status"]
    assert (s == STATUS_INVALID).any()
    Ts = cfg["environment"]["T_substrate"]
    assert (fr.outputs["temperature_rise"][s == STATUS_INVALID] == -Ts).all()
    assert (fr.outputs["bolometer_voltage"][s == STATUS_INVALID] == 0.0).all()
    assert fr.diagnostics["solver_failures"]["invalid"] == int((s == STATUS_INVALID).sum())


def test_microkelvin_rise_to_full_relative_accuracy():
    # The Newton stop tests are relative: a rise of ~3 uK (bias 10 nA) comes back to 1e-12
    # of the 40-digit root, as a rise of kelvins does (an absolute floor of 1e-15 K left it
    # 1e-9 off).
    from irnuc.model.core.bolometer import solve_delta_t

    B = 0.025 * 300.0**2
    for a, bb in ((0.0, 3e-11), (1e-7, 1e-11), (-1e-6, 3e-11), (0.0, 3e-20)):
        x, st, _ = solve_delta_t(a, bb, 1e5, B, 300.0, 300.0, 1e-12, 100, math.nan, 1000.0)
        ref = _root_mp(a, bb, 1e5, B, 300.0, 300.0)
        assert st == STATUS_OK and abs((x - ref) / ref) < 1e-12, (a, bb, x, ref)
    fr = _sim(_cfg(**{"bolometer.bias_current": 1e-8}), [300.0],
              outputs=("codes", "temperature_rise"))
    assert 1e-7 < np.median(fr.outputs["temperature_rise"]) < 1e-4


def test_positive_tcr_runaway_detected_per_pixel():
    cfg = _cfg(**{"bolometer.tcr": 0.02, "bolometer.bias_current": 1e-4})
    with pytest.warns(RuntimeWarning, match="runaway"):
        fr = model.simulate(cfg, [300.0], outputs=("codes", "status"))
    assert (fr.outputs["status"] == STATUS_RUNAWAY).all()
    assert fr.diagnostics["solver_failures"]["runaway"] == fr.outputs["status"].size
    assert (fr.codes == 2**14 - 1).all()  # the high rail, never NaN


def test_positive_tcr_stable_root_past_unit_loop_gain_is_not_a_runaway():
    # TCR +0.0063/K, 75 uA: on the way up the loop gain exceeds 1, then falls again above
    # |B|/2 = 283 K; the stable equilibrium is at ~889 K, below the runaway limit of 1000 K.
    # The old fixed point called every pixel a runaway. Reference: grid scan + brentq.
    from scipy.optimize import brentq

    # (the self-heating-factor pulse model; the pulse train at a positive TCR:
    # tests/test_pulse.py against solve_ivp)
    cfg = _cfg(**{"bolometer.tcr": 0.0063, "bolometer.bias_current": 7.5e-5,
                  "fpa.tolerance": {"R_ref": 0.0, "g": 0.0, "C": 0.0}, "fpa.defects": {},
                  "bolometer.pulse": "self_heating"})
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        fr = model.simulate(cfg, [300.0], outputs=("codes", "status", "temperature_rise",
                                                    "power"))
    assert (fr.outputs["status"] == STATUS_OK).all()
    b = cfg["bolometer"]
    u = b["t_int"] * b["g"] / b["C"]
    f = float(1 + mp.expm1(-mp.mpf(u)) / u)
    q = float(fr.outputs["power"][0, 5, 5])
    a, bb, B = q / b["g"], b["bias_current"] ** 2 * f / b["g"], -b["tcr"] * 300.0**2

    def h(x):
        return x - a - bb * b["R_ref"] * np.exp(B * (1 / (300.0 + x) - 1 / 300.0))

    xs = np.linspace(a, 700.0, 20001)
    k = int(np.flatnonzero(h(xs) >= 0)[0])
    ref = brentq(h, xs[k - 1], xs[k], xtol=1e-300, rtol=8.9e-16)
    assert fr.outputs["temperature_rise"][0, 5, 5] == pytest.approx(ref, rel=1e-11)
    T = 300.0 + xs[:k]
    gain = -bb * b["R_ref"] * np.exp(B * (1 / T - 1 / 300.0)) * B / T**2
    assert gain.max() > 1.0 > gain[-1]
    assert fr.codes.max() < 2**14 - 1


# ---- ADC and calibration -----------------------------------------------------------------

def test_adc_rails_and_nan():
    codes = adc_convert(np.array([-1e30, -1.0, 0.0, 1.65, 3.3, 1e30]), 14, 0.0, 3.3)
    assert codes.dtype == np.uint16
    assert codes.tolist() == [0, 0, 0, 8192, 2**14 - 1, 2**14 - 1]
    huge = adc_convert(np.array([1e18, 1e19, 1e300, -1e300]), 14, 0.0, 3.3)
    assert huge.tolist() == [2**14 - 1] * 3 + [0]
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(NonFiniteVoltageError, match="non-finite"):
            adc_convert(np.array([1.0, bad]), 14, 0.0, 3.3)


def test_calibration_with_equal_frames_flags_pixels_without_inf():
    nf = pytest.importorskip("irnuc.nuc_fixed.calibrate")
    rng = np.random.default_rng(1)
    lo = rng.integers(3000, 3100, (4, 6, 8))
    hi = lo + 1500 + rng.integers(-20, 20, (4, 6, 8))
    hi[:, 2, 3] = lo[:, 2, 3]  # the same frames at both temperatures
    cal = nf.calibrate(lo, hi, "typical14")
    assert cal.bad[2, 3]
    assert np.isfinite(cal.gain).all() and np.isfinite(cal.offset).all()
    from irnuc.nuc_fixed.badpix import Reason

    assert cal.reasons[2, 3] & (Reason.EQUAL_RESPONSE | Reason.STUCK | Reason.UNRESPONSIVE)


def test_calibration_coefficient_overflow_is_saturated_and_counted():
    nf = pytest.importorskip("irnuc.nuc_fixed.calibrate")
    lo = np.full((4, 6, 8), 3000)
    hi = np.full((4, 6, 8), 4500)
    hi[:, 1, 1] = 3001  # a response 1500 times weaker: its gain overflows U2.14
    cal = nf.calibrate(lo, hi, "typical14")
    assert cal.summary["gain_saturated_all"] >= 1
    assert cal.bad[1, 1]
    gmax = (1 << (cal.cfg.gain_int_bits + cal.cfg.gain_frac_bits)) - 1
    assert 0 <= cal.gain_code.max() <= gmax


# ---- frame sizes ---------------------------------------------------------------------------

@pytest.mark.parametrize("shape", [(1, 1), (1, 7), (7, 1)])
def test_tiny_frames(shape):
    cfg = _cfg(**{"fpa.active_rows": shape[0], "fpa.active_cols": shape[1],
                  "fpa.defects": {}})
    fr = _sim(cfg)
    assert fr.codes.shape == (2, *shape) and fr.codes.min() > 0
    from irnuc.model.transient import simulate_transient

    tf = simulate_transient(cfg, [300.0, 400.0])
    assert tf.codes.shape == (2, *shape)


#: Stated memory bound of one 4096 x 4096 frame (plus rings) through the steady pipeline:
#: measured peak 2.0 GB (tracemalloc), about 15 full-array float64 products of 134 MB.
HUGE_MEMORY_BOUND = 3.0e9


def test_huge_frame_4096_within_memory_bound():  # ~12 s: under the 20 s "slow" limit
    cfg = model.load_preset("default", {"fpa.active_rows": 4096, "fpa.active_cols": 4096})
    tracemalloc.start()
    try:
        fr = _sim(cfg, [320.0])
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert fr.codes.shape == (1, 4096, 4096)
    assert peak < HUGE_MEMORY_BOUND, f"peak {peak / 1e9:.2f} GB"


# ---- fuzzing --------------------------------------------------------------------------------

FUZZ_FIELDS = {
    "bolometer.tcr": st.floats(-2.0, 2.0),
    "bolometer.g": st.floats(-1e-8, 1e-6),
    "bolometer.C": st.floats(-1e-10, 1e-8),
    "bolometer.bias_current": st.floats(-1e-5, 5e-5),
    "bolometer.t_int": st.floats(-1e-5, 1e-3),
    "environment.T_substrate": st.floats(-10.0, 500.0),
    "environment.T_cam": st.floats(-10.0, 500.0),
    "fpa.fill_factor": st.floats(-0.1, 1.2),
    "readout.gain": st.floats(-1.0, 200.0),
    "adc.bits": st.integers(-2, 30),
    "fpa.tolerance": st.fixed_dictionaries({"g": st.floats(-0.5, 1.5)}),
    "radiometry.rtol": st.floats(0.0, 0.2),
}


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.dictionaries(st.sampled_from(sorted(FUZZ_FIELDS)), st.none(), max_size=4).flatmap(
    lambda keys: st.fixed_dictionaries({k: FUZZ_FIELDS[k] for k in keys})))
def test_fuzzed_configs_give_finite_frames_or_name_the_field(over):
    over = {**SMALL, "fpa.active_rows": 3, "fpa.active_cols": 4, **over}
    try:
        cfg = model.load_preset("default", over)
    except ConfigError as exc:
        fields = [k for k in over if k in str(exc)]
        assert fields, f"error {exc} names none of {sorted(over)}"
        return
    fr = _sim(cfg, [280.0, 390.0], outputs=("codes", "status"))
    assert fr.codes.shape == (2, 3, 4)
    assert fr.codes.max() < 2 ** cfg["adc"]["bits"]
    failed = int((fr.outputs["status"] != STATUS_OK).sum())
    assert sum(fr.diagnostics["solver_failures"].values()) == failed
    assert STATUS_INVALID >= 0


# ---- the table in docs/extreme_cases.md ----------------------------------------------------

def test_every_documented_case_has_a_test():
    text = DOC.read_text()
    named = re.findall(r"`((?:test_)\w+)`", text)
    assert len(named) >= 25
    here = {n for n in globals() if n.startswith("test_")}
    others = "".join(p.read_text() for p in Path(__file__).parent.glob("test_*.py"))
    for name in named:
        assert name in here or f"def {name}(" in others, f"{name} is in the table but not a test"
    for name in here:
        if name != "test_every_documented_case_has_a_test":
            assert name in named, f"{name} is not in docs/extreme_cases.md"
