"""Transient bolometer model: against closed forms and scipy.integrate.solve_ivp."""

from __future__ import annotations

import math

import numpy as np
import pytest

from irnuc import model
from irnuc.model import transient as tr
from irnuc.model.core.bolometer import STATUS_OK, STATUS_RUNAWAY
from irnuc.model.validate import ConfigError
from irnuc.reports.studies.precision import reference_transient, transient_problem

INTEGRATORS = list(tr.INTEGRATORS)
T_INT = 60e-6
FRAME = 1.0 / 30.0


def _closed_form(theta0, Q, I, R, g, C, t):
    """Independent closed form of C theta' = I^2 R + Q - g theta (R constant)."""
    eq = (I * I * R + Q) / g
    tau = C / g
    end = eq + (theta0 - eq) * math.exp(-t / tau)
    mean = eq + (theta0 - eq) * tau / t * (1.0 - math.exp(-t / tau))
    return end, mean


def _integrate(Q, **kw):
    base = dict(T_s=300.0, R_ref=1e5, g=1e-8, C=1e-10, tcr=-0.025, T_ref=300.0,
                bias_current=1.5e-5, t_int=T_INT)
    base.update(kw)
    return tr.integrate_pixels(np.asarray(Q, float), **base)


@pytest.mark.parametrize("integrator", INTEGRATORS)
@pytest.mark.parametrize("case", ["tcr0", "no_bias"])
def test_linear_cases_match_closed_form(integrator, case):
    # TCR = 0 or zero bias: the heat balance is linear, solved exactly in closed form.
    Q = np.array([[2e-9, 5e-9, -1e-9]])
    I = 1.5e-5 if case == "tcr0" else 0.0
    tcr = 0.0 if case == "tcr0" else -0.025
    C = np.array([1e-8, 1e-10, 3e-12])  # tau = 10 ms, 100 us, 3 us against a 60 us pulse
    r = _integrate(Q, C=C, g=1e-6, tcr=tcr, bias_current=I,
                   settings={"integrator": integrator, "initial": "substrate"})
    for k in range(3):
        end, mean = _closed_form(0.0, Q[0, k], I, 1e5, 1e-6, C[k], T_INT)
        assert r.status[0, k] == STATUS_OK
        assert r.dT_end[0, k] == pytest.approx(end, rel=1e-8, abs=1e-12)
        assert r.dT_mean[0, k] == pytest.approx(mean, rel=1e-8, abs=1e-12)
        assert r.v_bolo[0, k] == pytest.approx(I * 1e5, rel=1e-12, abs=1e-300)


def test_exponential_is_exact_for_the_linear_part_in_one_step():
    Q = np.array([[3e-9]])
    for C in (1e-8, 1e-13):  # non-stiff and 6e5 times stiffer than the pulse
        r = _integrate(Q, C=C, g=1e-6, tcr=0.0, settings={
            "integrator": "exponential", "steps": 1, "rtol": None, "initial": "substrate"})
        end, mean = _closed_form(0.0, 3e-9, 1.5e-5, 1e5, 1e-6, C, T_INT)
        assert r.dT_end[0, 0] == pytest.approx(end, rel=1e-13)
        assert r.dT_mean[0, 0] == pytest.approx(mean, rel=1e-13)


def _reference_for(prob, pix, **kw):
    cfg, Q, Ts, p = prob["cfg"], prob["Q"], prob["T_s"], prob["params"]
    b = cfg["bolometer"]
    i, j = pix
    args = dict(tcr=b["tcr"], T_ref=b["T_ref"], bias_current=b["bias_current"], t_int=b["t_int"],
                frame_period=FRAME, pulse_start=0.0, theta0=Q[0, i, j] / p["g"][i, j])
    args.update(kw)
    return reference_transient(Q[:, i, j], Ts, p["R_ref"][i, j], p["g"][i, j], p["C"][i, j],
                               **args)


def _run_problem(prob, **settings):
    cfg, Q, Ts, p = prob["cfg"], prob["Q"], prob["T_s"], prob["params"]
    b = cfg["bolometer"]
    return tr.integrate_pixels(Q, Ts, p["R_ref"], p["g"], p["C"], tcr=b["tcr"], T_ref=b["T_ref"],
                               bias_current=b["bias_current"], t_int=b["t_int"],
                               runaway_temperature=b["runaway_temperature"], settings=settings)


@pytest.fixture(scope="module")
def nonstiff():
    prob = transient_problem("nonstiff")
    prob["refs"] = {pix: _reference_for(prob, pix) for pix in [(0, 0), (5, 7)]}
    return prob


@pytest.fixture(scope="module")
def stiff():
    prob = transient_problem("stiff")
    prob["refs"] = {pix: _reference_for(prob, pix) for pix in [(4, 4)]}
    return prob


def _max_rel(res, refs):
    err = 0.0
    for (i, j), (v, m, e) in refs.items():
        err = max(err, float(np.max(np.abs(res.v_bolo[:, i, j] - v) / np.abs(v))),
                  float(np.max(np.abs(res.dT_mean[:, i, j] - m) / np.abs(m))),
                  float(np.max(np.abs(res.dT_end[:, i, j] - e) / np.abs(e))))
    return err


@pytest.mark.parametrize("integrator,rtol,tol", [
    ("rk4", 1e-9, 1e-9), ("exponential", 1e-7, 1e-9), ("trapezoidal", 1e-6, 1e-9),
    ("backward_euler", 1e-4, 1e-6)])
def test_nonstiff_against_solve_ivp(nonstiff, integrator, rtol, tol):
    r = _run_problem(nonstiff, integrator=integrator, rtol=rtol)
    assert (r.status == STATUS_OK).all()
    assert _max_rel(r, nonstiff["refs"]) < tol


@pytest.mark.parametrize("integrator,rtol,tol", [
    ("rk4", 1e-9, 1e-10), ("exponential", 1e-6, 1e-9),
    # trapezoidal is A- but not L-stable: its stiff error decays slowly (as (-1)^n).
    ("trapezoidal", 1e-6, 1e-6), ("backward_euler", 1e-3, 1e-7)])
def test_stiff_tau_far_below_pulse_with_scene_steps(stiff, integrator, rtol, tol):
    b = stiff["cfg"]["bolometer"]
    tau = float(np.median(stiff["params"]["C"] / stiff["params"]["g"]))
    assert b["t_int"] / tau > 300  # the problem is stiff
    r = _run_problem(stiff, integrator=integrator, rtol=rtol)
    assert (r.status == STATUS_OK).all()
    assert np.isfinite(r.v_bolo).all()
    assert _max_rel(r, stiff["refs"]) < tol


@pytest.mark.parametrize("integrator,order", [("rk4", 4), ("exponential", 3),
                                              ("trapezoidal", 2), ("backward_euler", 1)])
def test_fixed_step_order_of_convergence(nonstiff, integrator, order):
    errs = [_max_rel(_run_problem(nonstiff, integrator=integrator, steps=n, rtol=None),
                     nonstiff["refs"]) for n in (8, 16)]
    observed = math.log2(errs[0] / errs[1])
    assert abs(observed - order) < 0.35
    assert tr.INTEGRATOR_ORDER[integrator] == order


def test_explicit_refuses_stiff_problem_with_a_clear_message(stiff):
    with pytest.raises(tr.StiffnessError, match=r"rk4.*refuses.*exponential"):
        _run_problem(stiff, integrator="rk4", steps=8, rtol=None, explicit_policy="refuse")
    with pytest.raises(tr.StiffnessError, match="max_substeps = 50"):
        _run_problem(stiff, integrator="rk4", rtol=None, max_substeps=50)


def test_explicit_step_limit_keeps_stiff_frames_finite_and_right(stiff):
    # One requested step for a pulse 600 tau long: stability limiting adds substeps.
    r = _run_problem(stiff, integrator="rk4", steps=1, rtol=None)
    assert r.substeps.min() > 100
    assert np.isfinite(r.v_bolo).all() and (r.status == STATUS_OK).all()
    assert _max_rel(r, stiff["refs"]) < 1e-3


def _feedback_problem(c):
    """Positive TCR 0.02/K, tau = 0.1 us, I^2 R_ref / g = c (K).

    With R = R_ref exp(1800 (1/300 - 1/T)) the equilibrium x = c exp(6 x / (300 + x)) exists
    up to c of about 22.5 K: c = 22.4 K has its root at x = 67.6 K with an electro-thermal
    loop gain I^2 R' / g = 0.9 (the pixel responds ten times slower than tau); c = 45 K
    has no equilibrium at all (thermal runaway).
    """
    tcr, R, g, C = 0.02, 1e5, 1e-5, 1e-12
    return dict(tcr=tcr, R_ref=R, g=g, C=C, bias_current=math.sqrt(c * g / R))


def test_strong_feedback_near_runaway_against_solve_ivp():
    kw = _feedback_problem(22.4)
    Q = np.array([[1e-9], [5e-9]])
    Ts = np.array([300.0, 300.0])
    ref_v, _ref_m, ref_e = reference_transient(Q[:, 0], Ts, kw["R_ref"], kw["g"], kw["C"],
                                              tcr=kw["tcr"], T_ref=300.0,
                                              bias_current=kw["bias_current"], t_int=T_INT,
                                              frame_period=FRAME, pulse_start=0.0,
                                              theta0=Q[0, 0] / kw["g"])
    for integrator, rtol, tol in (("rk4", 1e-9, 1e-8), ("exponential", 1e-7, 1e-8),
                                  ("backward_euler", 1e-4, 1e-5)):
        r = tr.integrate_pixels(Q, Ts, kw["R_ref"], kw["g"], kw["C"], tcr=kw["tcr"], T_ref=300.0,
                                bias_current=kw["bias_current"], t_int=T_INT,
                                settings={"integrator": integrator, "rtol": rtol})
        assert (r.status == STATUS_OK).all(), integrator
        assert ref_e[0] > 60.0  # the pixel settles close to the runaway limit
        np.testing.assert_allclose(r.v_bolo[:, 0], ref_v, rtol=tol)
        np.testing.assert_allclose(r.dT_end[:, 0], ref_e, rtol=tol)


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_runaway_is_detected_per_pixel_not_a_nan_frame(integrator):
    kw = _feedback_problem(45.0)
    Q = np.zeros((2, 3))
    I = np.array([kw["bias_current"]])
    # Only the middle pixel runs away: the others have a tenth of the conductance's gain.
    g = np.array([10 * kw["g"], kw["g"], 10 * kw["g"]])
    r = tr.integrate_pixels(Q, 300.0, kw["R_ref"], g, kw["C"] * g / kw["g"], tcr=kw["tcr"],
                            T_ref=300.0, bias_current=float(I[0]), t_int=T_INT,
                            settings={"integrator": integrator,
                                      "rtol": 1e-4 if integrator == "backward_euler" else 1e-9})
    assert r.status[:, 1].tolist() == [STATUS_RUNAWAY, STATUS_RUNAWAY]
    assert (r.status[:, [0, 2]] == STATUS_OK).all()
    assert np.isfinite(r.v_bolo).all() and np.isfinite(r.dT_mean).all()


def test_runaway_in_frames_reads_the_high_rail_and_is_counted():
    cfg = model.load_preset("default", {"fpa.active_rows": 4, "fpa.active_cols": 5,
                                        "bolometer.tcr": 0.02, "bolometer.g": 1e-5,
                                        "bolometer.C": 1e-12, "bolometer.bias_current": 1e-4,
                                        "fpa.defects": {}})
    with pytest.warns(RuntimeWarning, match="failed"):
        fr = tr.simulate_transient(cfg, [300.0], outputs=("codes", "status"))
    assert fr.diagnostics["solver_failures"]["runaway"] > 0
    assert fr.diagnostics["transient"]["runaway_pixels"] > 0
    top = (1 << cfg["adc"]["bits"]) - 1
    assert (fr.codes == top).all()


def test_frames_like_the_steady_model_at_low_bias():
    # Small self-heating and a pixel in the periodic state of its pulse train (the pulse
    # at the end of the configuration's frame period, warm-up frames to the periodic
    # state): the time average of I R(T(t)) equals the steady model's (its pulse
    # integrated by a few Runge-Kutta steps) to 1e-7.
    over = {"fpa.active_rows": 5, "fpa.active_cols": 6, "bolometer.bias_current": 1e-6}
    cfg = model.load_preset("default", over)
    period = 1.0 / cfg["readout"]["frame_rate"]
    st = model.simulate(cfg, [320.0], outputs=("codes", "bolometer_voltage"))
    fr = tr.simulate_transient(cfg, [320.0], outputs=("codes", "bolometer_voltage"),
                               settings={"frame_period": period, "warmup_frames": 40,
                                         "pulse_start": period - T_INT})
    assert fr.codes.shape == st.codes.shape and fr.codes.dtype == st.codes.dtype
    np.testing.assert_allclose(fr.outputs["bolometer_voltage"], st.outputs["bolometer_voltage"],
                               rtol=1e-7)
    assert np.abs(fr.codes.astype(int) - st.codes.astype(int)).max() <= 1
    np.testing.assert_array_equal(fr.defect_kind, st.defect_kind)


def test_a_substrate_ramp_through_the_frame_keeps_the_temperature_continuous():
    # No bias: theta = T - T_s relaxes towards Q/g while the substrate warms linearly through
    # frame 1 (300 -> 301 K over the frame period), so C theta' = Q - g theta - C r with
    # r = 1 K / P: theta = (eq - r tau) + (theta_0 - eq + r tau) exp(-t / tau), the exact
    # solution (independent of the kernel); the kernel holds the substrate at its mid-pulse
    # value during the pulse, an error below r t_int^2 / tau. T is continuous (no jump at
    # the frame start: a step would leave theta 1 K low there).
    Q = np.full((2, 1), 2e-9)
    C, g = 1e-10, 1e-8
    tau, ps = C / g, 1e-3
    r = _integrate(Q, T_s=np.array([300.0, 301.0]), bias_current=0.0, C=C, g=g,
                   settings={"integrator": "exponential", "pulse_start": ps})
    eq = 2e-9 / g
    rate = 1.0 / FRAME
    t_end = ps + T_INT
    exact = (eq - rate * tau) + (eq - eq + rate * tau) * math.exp(-t_end / tau)
    # dT_end is over the substrate at mid-pulse, half a pulse's ramp below the end's
    assert r.dT_end[1, 0] == pytest.approx(exact + 0.5 * rate * T_INT,
                                           abs=rate * T_INT**2 / tau)
    assert r.dT_end[0, 0] == pytest.approx(eq, rel=1e-12)
    assert abs(r.dT_end[1, 0] - eq) < 0.05  # the substrate's 1 K did not jump into theta


def test_deterministic_and_integrators_agree_on_frames():
    cfg = model.load_preset("default", {"fpa.active_rows": 4, "fpa.active_cols": 6})
    a = tr.simulate_transient(cfg, [300.0, 360.0], seed=3, substrate=[300.0, 300.5])
    b = tr.simulate_transient(cfg, [300.0, 360.0], seed=3, substrate=[300.0, 300.5])
    np.testing.assert_array_equal(a.codes, b.codes)
    c = tr.simulate_transient(cfg, [300.0, 360.0], seed=3, substrate=[300.0, 300.5],
                              settings={"integrator": "exponential", "rtol": 1e-8})
    assert np.abs(a.codes.astype(int) - c.codes.astype(int)).max() <= 1


@pytest.mark.parametrize("kwargs,field", [
    ({"t_int": 0.0}, "bolometer.t_int"),
    ({"C": 0.0}, "bolometer.C"),
    ({"g": -1e-8}, "bolometer.g"),
    ({"T_s": 0.0}, "environment.T_substrate"),
    ({"T_s": math.nan}, "environment.T_substrate"),
    ({"settings": {"integrator": "euler"}}, "transient.integrator"),
    ({"settings": {"steps": 0}}, "transient.steps"),
    ({"settings": {"rtol": 2.0}}, "transient.rtol"),
    ({"settings": {"frame_period": 1e-5}}, "transient.frame_period"),
    ({"settings": {"bogus": 1}}, "bogus"),
])
def test_bad_arguments_name_the_field(kwargs, field):
    with pytest.raises(ConfigError, match=field.replace(".", r"\.")):
        _integrate(np.array([[1e-9]]), **kwargs)


def test_simulate_transient_rejects_bad_substrate_and_outputs():
    cfg = model.load_preset("default", {"fpa.active_rows": 2, "fpa.active_cols": 2})
    with pytest.raises(ConfigError, match="substrate"):
        tr.simulate_transient(cfg, [300.0, 310.0], substrate=[300.0])
    with pytest.raises(ConfigError, match="outputs"):
        tr.simulate_transient(cfg, [300.0], outputs=("nope",))


# ---- the auto default: stiffness detection ---------------------------------------------------

def test_default_is_auto_and_matches_rk4_exactly_on_non_stiff_pixels(nonstiff):
    assert tr.DEFAULT_INTEGRATOR == "auto" and tr.TransientSettings().integrator == "auto"
    a = _run_problem(nonstiff)
    r = _run_problem(nonstiff, integrator="rk4")
    assert a.integrators_used() == {"rk4": a.status.size}
    np.testing.assert_array_equal(a.v_bolo, r.v_bolo)
    np.testing.assert_array_equal(a.substeps, r.substeps)


@pytest.mark.parametrize("C", [1e-14, 1e-15])
def test_very_stiff_pixels_are_solved_by_default(C):
    # Stiffness ~1e5 and ~1e6: RK4 needs 1.5e5 substeps or refuses; the default switches
    # to the exponential integrator after the fast transient. Reference: 60-digit
    # phase-variable quadrature (independent of any ODE solver).
    from irnuc.reports.studies.precision import reference_transient_exact

    g, I = 1e-5, 1.5e-4
    Q = np.array([[1e-9], [3e-9]])
    Ts = np.array([300.0, 300.0])
    v, _m, _e, _ = reference_transient_exact(Q[:, 0], Ts, 1e5, g, C, tcr=-0.025, T_ref=300.0,
                                             bias_current=I, t_int=T_INT, frame_period=FRAME,
                                             pulse_start=0.0, theta0=Q[0, 0] / g)
    r = tr.integrate_pixels(Q, Ts, 1e5, g, C, tcr=-0.025, T_ref=300.0, bias_current=I,
                            t_int=T_INT)
    assert (r.status == STATUS_OK).all()
    assert r.integrators_used() == {"exponential": 2}
    np.testing.assert_allclose(r.v_bolo[:, 0], v[0] + v[1], rtol=1e-9)
    assert r.substeps.max() < 2000
    with pytest.raises(tr.StiffnessError):
        tr.integrate_pixels(Q, Ts, 1e5, g, C, tcr=-0.025, T_ref=300.0, bias_current=I,
                            t_int=T_INT, settings={"integrator": "rk4", "max_substeps": 20000})


def test_auto_near_runaway_positive_tcr_against_reference():
    from irnuc.reports.studies.precision import reference_transient_exact

    kw = _feedback_problem(21.0)
    kw["C"] = 1e-14  # stiff: loop gain 0.72 leaves a decay rate of 2.8e8 /s
    Q = np.array([[1e-9], [5e-9]])
    Ts = np.array([300.0, 300.0])
    v, _m, _e, _ = reference_transient_exact(Q[:, 0], Ts, kw["R_ref"], kw["g"], kw["C"],
                                             tcr=kw["tcr"], T_ref=300.0,
                                             bias_current=kw["bias_current"], t_int=T_INT,
                                             frame_period=FRAME, pulse_start=0.0,
                                             theta0=Q[0, 0] / kw["g"])
    r = tr.integrate_pixels(Q, Ts, kw["R_ref"], kw["g"], kw["C"], tcr=kw["tcr"], T_ref=300.0,
                            bias_current=kw["bias_current"], t_int=T_INT)
    assert (r.status == STATUS_OK).all()
    np.testing.assert_allclose(r.v_bolo[:, 0], v[0] + v[1], rtol=1e-9)


def test_transient_frames_report_stage_counts_and_integrators():
    cfg = model.load_preset("default", {"fpa.active_rows": 4, "fpa.active_cols": 5})
    fr = tr.simulate_transient(cfg, [300.0, 350.0], outputs=("codes",))
    c = fr.counts
    # Housing radiance once (shared by the power and readout), one integration run.
    assert c["env_radiance"] == 1 and c["params"] == 1 and c["transient"] == 1
    assert c["transient_pulses"] == 2 * 10 * 11
    assert c["skimming_row"] == 1 and c["adc"] == 1 and "v_skim" not in c
    assert fr.diagnostics["transient"]["integrators_used"] == {"rk4": 2 * 10 * 11}
    two = tr.simulate_transient(cfg, [300.0, 350.0], substrate=[300.0, 301.0])
    assert two.counts["env_radiance"] == 2  # one configured sensor per substrate temperature


def test_backward_euler_limits_are_as_documented():
    # docs/transient.md: (1) adaptive backward Euler resolves a stiff pixel's fast
    # transient (its rectangle-rule estimate sees it) and meets the tolerance; (2) it is
    # first order, substeps grow ~10x per decade of rtol; (3) fixed steps much longer than
    # 1/lambda skip the transient: an error of ~0.2 / stiffness whatever the step count.
    from irnuc.reports.studies.precision import reference_transient_exact

    g, I, C = 1e-5, 1.5e-4, 1e-15
    Q = np.array([[1e-9]])
    v, _m, _e, _ = reference_transient_exact(Q[:, 0], [300.0], 1e5, g, C, tcr=-0.025,
                                             T_ref=300.0, bias_current=I, t_int=T_INT,
                                             frame_period=FRAME, pulse_start=0.0,
                                             theta0=Q[0, 0] / g)
    ref = v[0] + v[1]

    def run(C=C, **st):
        return tr.integrate_pixels(Q, 300.0, 1e5, g, C, tcr=-0.025, T_ref=300.0,
                                   bias_current=I, t_int=T_INT,
                                   settings={"integrator": "backward_euler", **st})

    ad = run(rtol=1e-3)
    assert ad.status[0, 0] == STATUS_OK
    assert abs(ad.v_bolo[0, 0] - ref[0]) / ref[0] < 1e-9
    for steps in (16, 4096):
        err = abs(run(rtol=None, steps=steps).v_bolo[0, 0] - ref[0]) / ref[0]
        assert 5e-8 < err < 5e-7  # stiffness ~1.2e6
    n3 = run(C=1e-10, rtol=1e-3).substeps[0, 0]
    n4 = run(C=1e-10, rtol=1e-4).substeps[0, 0]
    assert 7 < n4 / n3 < 13
