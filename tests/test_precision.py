"""Work-precision study: references, Pareto marking, a quick run, figures and the CLI."""

from __future__ import annotations

import json
import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad

from irnuc.cli import precision as R
from irnuc.model.core.constants import C2, RADIANCE_PREFACTOR
from irnuc.reports.studies import precision as P
from irnuc.reports.studies.precision import references as PR
from irnuc.reports.studies.precision import studies as PS


def test_mpmath_reference_matches_scipy_quad():
    # The radiance reference itself against an independent quadrature of Planck's law.
    for T in (80.0, 300.0, 3000.0):
        x1, x2 = C2 / (8e-6 * T), C2 / (14e-6 * T)
        val, _ = quad(lambda t: t**3 / math.expm1(t), x2, x1, epsabs=0, epsrel=1e-13)
        assert P.band_radiance_mp(T) == pytest.approx(RADIANCE_PREFACTOR * T**4 * val, rel=1e-11)


def test_exact_transient_reference_agrees_with_radau():
    # Two independent references: phase-variable quadrature in mpmath and scipy's Radau.
    prob = P.transient_problem("stiff_1e3")
    Q, Ts, p = prob["Q"], prob["T_s"], prob["params"]
    b = prob["cfg"]["bolometer"]
    kw = dict(tcr=b["tcr"], T_ref=b["T_ref"], bias_current=b["bias_current"], t_int=b["t_int"],
              frame_period=1 / 30, pulse_start=0.0, theta0=Q[0, 2, 3] / p["g"][2, 3])
    args = (Q[:, 2, 3], Ts, p["R_ref"][2, 3], p["g"][2, 3], p["C"][2, 3])
    v, m, e, est = P.reference_transient_exact(*args, **kw)
    rv, rm, re = P.reference_transient(*args, rtol=1e-12, **kw)
    assert est < 1e-30
    np.testing.assert_allclose(v[0] + v[1], rv, rtol=1e-12)
    np.testing.assert_allclose(m[0] + m[1], rm, rtol=1e-12)
    np.testing.assert_allclose(e[0] + e[1], re, rtol=1e-12)


def test_exact_transient_reference_linear_case_closed_form():
    # TCR = 0: theta relaxes exponentially to (I^2 R + Q) / g; the mean is closed form.
    Q, I, R, g, C, t = 3e-9, 1.5e-5, 1e5, 1e-6, 1e-12, 6e-5
    v, m, e, _ = P.reference_transient_exact([Q], [300.0], R, g, C, tcr=0.0, T_ref=300.0,
                                             bias_current=I, t_int=t, frame_period=1e-3,
                                             pulse_start=0.0, theta0=0.0)
    with mp.workdps(40):
        eq = (mp.mpf(I) ** 2 * R + mp.mpf(Q)) / g
        u = mp.mpf(t) * g / C
        end = eq * (1 - mp.exp(-u))
        mean = eq * (1 + mp.expm1(-u) / u)
        assert abs((mp.mpf(e[0][0]) + e[1][0] - end) / end) < 1e-25
        assert abs((mp.mpf(m[0][0]) + m[1][0] - mean) / mean) < 1e-25
    assert v[0][0] == pytest.approx(I * R, rel=1e-15)


def test_double_double_error_resolves_below_float64():
    ref = np.array([[1.0], [1e-20]])
    assert P.rel_error_dd(np.array([1.0]), ref)[0] == pytest.approx(1e-20)


def _pt(method, err, t, default=False, work=None):
    return P.Point(method, "s", 1.0, err, t, work, default=default)


def test_pareto_marking_uses_margins_and_skips_failed():
    pts = [_pt("a", 1e-6, 1.0, default=True, work=10), _pt("b", 1e-9, 0.1, work=100),
           _pt("c", 1e-12, 0.9, work=5),
           P.Point("d", "s", 1.0, None, 0.5, reason="failed", failed=True)]
    P.mark_front(pts)
    assert [p.on_front for p in pts] == [False, True, True, None]
    # By work c (5) dominates a (10: not 1.5x cheaper... 5 * 1.5 <= 10) and b.
    assert [p.on_front_work for p in pts] == [False, False, True, None]
    close = [_pt("a", 1e-6, 1.0), _pt("b", 0.5e-6, 0.8)]
    P.mark_front(close)
    assert all(p.on_front for p in close)


def test_jit_warm_up_is_never_timed(monkeypatch):
    # A fake clock: each call advances it by what the call "costs". The first call of a
    # setting compiles (10 s), the others take 1 ms: the point is drawn at 1 ms, a failed
    # setting at the time of a compiled call (the study drew 3.63 s and 7.13 s points
    # where their neighbours took 4e-4 s).
    from types import SimpleNamespace

    from irnuc.reports.studies.precision import harness as H

    clock = [0.0]
    monkeypatch.setattr(H, "time", SimpleNamespace(perf_counter=lambda: clock[0]))

    def runner(cost, fail_call=False, fail_eval=False):
        calls = []

        def call():
            clock[0] += 10.0 if not calls else cost
            calls.append(1)
            if fail_call:
                raise P.SettingFailed("refused")
            return 1

        def evaluate(_):
            if fail_eval:
                raise P.SettingFailed("not converged", work=7.0)
            return 1e-9, 5.0
        return (call, evaluate), calls

    pts = []
    (r, calls) = runner(1e-3)
    H.measure(pts, "m", "s", 1.0, r, repeats=3)
    (r2, calls2) = runner(2e-3, fail_call=True)
    H.measure(pts, "m", "s", 2.0, r2, repeats=3)
    (r3, calls3) = runner(4e-3, fail_eval=True)
    H.measure(pts, "m", "s", 3.0, r3, repeats=3)
    assert [p.time_s for p in pts] == pytest.approx([1e-3, 2e-3, 4e-3], rel=1e-9)
    assert [p.failed for p in pts] == [False, True, True] and pts[2].work == 7.0
    assert (len(calls), len(calls2), len(calls3)) == (4, 2, 2)  # warm-up + timed calls


@pytest.fixture(scope="module")
def quick_result():
    return P.run_precision(quick=True, components=["band_radiance_narrow", "electro_thermal",
                                                   "transient_nonstiff", "transient_stiff_1e5"],
                           repeats=1)


@pytest.mark.slow  # shares a ~9 s quick study
def test_quick_run_structure(quick_result):
    names = [c["name"] for c in quick_result["components"]]
    assert names == ["band_radiance_narrow", "electro_thermal", "transient_nonstiff",
                     "transient_stiff_1e5"]
    for comp in quick_result["components"]:
        name = comp["name"]
        defaults = [p for p in comp["points"] if p["default"]]
        assert len(defaults) == 1, name
        d = comp["default"]
        assert not d["failed"] and d["error"] < 1e-9, name
        # References far tighter than every plotted point.
        best = min(p["error"] for p in comp["points"] if p["error"] is not None)
        assert comp["reference_error"] * 100 < max(best, 1e-17), name
        assert isinstance(d["on_pareto_front"], bool), name
        for p in comp["points"]:
            if p["failed"]:
                assert p["reason"] and p["error"] is None and p["time_s"] is not None
            else:
                assert p["time_s"] > 0 and math.isfinite(p["error"]) and p["work"] > 0
        assert len(comp["missing"]) == sum(p["failed"] for p in comp["points"])
    json.dumps(quick_result)


@pytest.mark.slow  # shares a ~9 s quick study
def test_very_stiff_default_within_1e_9_and_rk4_refuses(quick_result):
    c = {c["name"]: c for c in quick_result["components"]}["transient_stiff_1e5"]
    assert c["stiffness"] > 1e4
    assert c["default"]["error"] < 1e-9
    rk4 = [p for p in c["points"] if p["method"].startswith("rk4")]
    assert rk4 and all(p["failed"] and "StiffnessError" in p["reason"] for p in rk4)
    # The default uses far fewer substeps than the fixed-step RK4 would need (~5e4).
    assert c["default"]["work"] < 2000


@pytest.mark.slow  # shares a ~9 s quick study
def test_known_failures_are_failed_points_with_reasons(quick_result):
    comps = {c["name"]: c for c in quick_result["components"]}
    et = {(p["method"], p["setting"]): p for p in comps["electro_thermal"]["points"]}
    assert et[("newton float32", 1e-12)]["failed"] or et[("newton float32", 1e-12)]["error"] > 1e-8
    # Backward Euler is first order: its adaptive mode exhausts the substep budget.
    miss = comps["transient_nonstiff"]["missing"]
    assert any(m["method"] == "backward_euler (adaptive)" and "budget" in m["reason"]
               for m in miss)
    br = {(p["method"], p["setting"]): p for p in comps["band_radiance_narrow"]["points"]}
    # The paper's series cancels on a 2 pm band; the hybrid default integrates it directly.
    assert br[("series", 1e-15)]["error"] > 1e4 * br[("hybrid", 1e-12)]["error"]


@pytest.mark.slow  # shares a ~9 s quick study
def test_figures_and_summary(quick_result):
    figs = P.figures(quick_result)
    assert len(figs) == len(quick_result["components"])
    for caption, png in figs:
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and "default" in caption
    s = P.summarize(quick_result)
    assert set(s["components"]) == {c["name"] for c in quick_result["components"]}
    for v in s["components"].values():
        assert v["default_error"] < 1e-9 and v["reference_error"] < 1e-20
    json.dumps(s)


@pytest.mark.slow  # shares a ~9 s quick study
def test_report_files_and_summary(quick_result, tmp_path):
    j, h = R.write_report(quick_result, tmp_path)
    text = h.read_text()
    assert text.count("data:image/png;base64,") == len(quick_result["components"])
    assert "Omitted (failed) settings" in text
    assert json.loads(j.read_text())["components"][0]["name"] == "band_radiance_narrow"
    assert text.count("<style>") == 1 and "{{" not in text  # the report's one stylesheet
    assert not list(tmp_path.glob(".*.tmp"))  # atomic writes leave no temporaries


@pytest.mark.slow  # shares a ~9 s quick study
def test_cached_study_is_reused_for_its_code_only(quick_result, tmp_path, monkeypatch):
    from irnuc.reports.studies import precision_cache as C

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path))
    names = [c["name"] for c in quick_result["components"]]
    with pytest.raises(FileNotFoundError):
        C.cached_precision(True, names, run_if_missing=False)
    C.store_precision(quick_result, names)
    got = C.cached_precision(True, names, run_if_missing=False)
    assert got["cached"] and [c["name"] for c in got["components"]] == names
    assert "transient_stiff_1e5" in P.summarize(got)["components"]
    # Another model code (digest) does not reuse it.
    monkeypatch.setattr(C, "code_digest", lambda: "0" * 16)
    with pytest.raises(FileNotFoundError):
        C.cached_precision(True, names, run_if_missing=False)


def test_groups_expand_and_unknown_names_are_errors():
    assert P.component_names(["transient_stiff"]) == [
        "transient_stiff_1e3", "transient_stiff_1e5", "transient_stiff_1e6",
        "transient_stiff_1e7", "transient_stiff_ptcr"]
    from irnuc.model.validate import ConfigError

    with pytest.raises(ConfigError, match="components"):
        P.component_names(["nope"])


def test_cli_writes_the_report(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    from irnuc.cli import main

    out = tmp_path / "p"
    rc = main(["precision", "-q", "--quick", "--only", "band_radiance", "--out", str(out)])
    assert rc == 0
    assert (out / "precision.html").is_file() and (out / "precision.json").is_file()
    assert sorted(p.name for p in out.iterdir() if p.name != ".irnuc-output") == [
        "precision.html", "precision.json"]
    assert capsys.readouterr().out == ""  # -q
    assert main(["precision", "--quick", "--only", "band_radiance", "--out", str(out)]) == 0
    assert "band_radiance" in capsys.readouterr().out


def test_electro_thermal_reference_is_tighter_than_brentq():
    prob = PS.electro_problem(True)
    idx = np.arange(0, prob["Q"].size, 37)
    ref, est = PR.mp_root_reference(prob, idx)
    br = PR.brentq_reference(prob, idx)
    assert est < 1e-25
    assert np.max(P.rel_error_dd(br, ref)) < 1e-14  # brentq is right to ~1e-16
