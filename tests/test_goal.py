"""Issue 36's goal study (reports/studies/goal.py): the fixed-pattern estimator under noise,
the FFC's offset noise against N, the noise streams' frame offsets, and the lens's
emission (level, not pattern) — each against an independent reference (numpy draws, the
statistics' closed forms), never the code's own formula."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc import model
from irnuc.nuc_fixed import load_pipeline
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, method_top
from irnuc.reports.studies import drift_common as dc
from irnuc.reports.studies import goal


def test_fixed_pattern_removes_the_temporal_bias():
    """Drawn fixed pattern (known std) plus temporal noise 2x larger, 16 frames: the
    estimate matches the drawn pattern's std; the frame average's plain std does not."""
    rng = np.random.default_rng(7)
    h, w, m = 64, 80, 16
    pattern = rng.normal(0.0, 0.7, (h, w))
    y = 1000.0 + pattern + rng.normal(0.0, 1.5, (m, h, w))
    good = np.ones((h, w), bool)
    good[0, :3] = False
    fixed, temporal = goal.fixed_pattern(y, good)
    want = pattern[good].std()
    assert fixed == pytest.approx(want, rel=0.03)
    assert temporal == pytest.approx(1.5, rel=0.02)
    naive = y.mean(axis=0)[good].std()
    assert naive > want * 1.08  # what the estimator takes out: sqrt(0.7^2 + 1.5^2 / 16)
    with pytest.raises(ValueError, match="at least 2"):
        goal.fixed_pattern(y[:1], good)


def _unit_ffc(n: int, h: int, w: int) -> MethodCoefficients:
    """ffc14 with unit gain and zero offset: the output is the raw code plus the FFC term."""
    cfg = load_pipeline("ffc14").replace(ffc_frames=n)
    z = np.zeros((h, w), np.int64)
    return MethodCoefficients(cfg, {"coeffs": {"gain": z + (1 << 14), "offset": z,
                                               "bad": z.astype(bool)}}, {})


@pytest.mark.parametrize("n", [4, 16, 64])
def test_ffc_offset_noise_falls_as_one_over_sqrt_n(n):
    """The FFC's offsets from N noisy shutter frames differ from the noise-free ones by
    sigma / sqrt(N) (sigma: the frames' temporal std, measured by numpy on the draws)."""
    rng = np.random.default_rng(100 + n)
    h, w, sigma = 48, 64, 3.0
    base = 6000.0 + rng.uniform(-40.0, 40.0, (h, w))  # each pixel's expected code
    noisy = np.rint(base + rng.normal(0.0, sigma, (n, h, w))).astype(np.int64)
    c = _unit_ffc(n, h, w)
    off = method_top(noisy, c, FrameInputs(shutter=np.ones(n, bool))).ffc_offset
    frac = next(f for f in c.cfg.formats if f.name == "ffc").frac_bits
    # a noise-free frame corrected: base + offset (unit gain); its spatial std is the
    # pattern the FFC's averaging leaves
    got = (base + off.astype(np.float64) / 2**frac).std()
    want = np.sqrt(noisy.astype(np.float64).var(axis=0, ddof=1).mean() / n)
    assert got == pytest.approx(want, rel=0.08)


def test_first_frame_draws_independent_noise_of_the_same_pixels():
    cfg = dc.StudySensor(rows=12, cols=16, seed=5).config(300.0, 300.0, noise=True)
    a = model.simulate(cfg, [300.0], seed=5, repeats=4).codes.astype(np.float64)
    a0 = model.simulate(cfg, [300.0], seed=5, repeats=4, first_frame=0).codes
    b = model.simulate(cfg, [300.0], seed=5, repeats=4, first_frame=1000).codes
    assert np.array_equal(a, a0)
    quiet = dc.StudySensor(rows=12, cols=16, seed=5).config(300.0, 300.0)
    mean = model.simulate(quiet, [300.0], seed=5).codes[0].astype(np.float64)
    da, db = (a - mean).ravel(), (b.astype(np.float64) - mean).ravel()
    assert abs(np.corrcoef(da, db)[0, 1]) < 0.1  # independent draws
    assert da.std() == pytest.approx(db.std(), rel=0.15)  # the same noise level
    with pytest.raises(model.ConfigError, match="first_frame"):
        model.simulate(cfg, [300.0], seed=5, first_frame=-1)


def test_plan_points_draw_independent_noise():
    """Two calibration points of a noisy plan: their frames' noise is uncorrelated (it was
    the same draw at every point before)."""
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan

    s = dc.StudySensor(rows=12, cols=16, seed=2)
    p = CalibrationPlan(scene=(300.0, 330.0), fpa=(300.0, 300.5), frames=4)
    pts = run_plan(p, "default", {**s.base_overrides(), "noise.enabled": True}, seed=2)
    d0 = pts.codes[0, 0] - pts.codes[0, 0].mean(axis=0)
    d1 = pts.codes[1, 0] - pts.codes[1, 0].mean(axis=0)
    assert abs(np.corrcoef(d0.ravel(), d1.ravel())[0, 1]) < 0.1


def test_lens_emission_moves_the_level_not_the_pattern():
    """The lens's emission fills the scene's own cone with the scene's cos^4: per pixel its
    raw change is a fixed multiple of a scene change (the ratio's spread tiny); the
    housing's (outside the cone) is not."""
    cam = goal.Camera(dc.StudySensor(rows=24, cols=32, seed=3), noise=False)
    base, _ = cam.frames(300.0, 300.0, [320.0])
    hot, _ = cam.frames(300.0, 300.0, [330.0])
    lens, _ = cam.frames(300.0, 300.0, [320.0], lens_K=280.0)
    housing, _ = cam.frames(300.0, 295.0, [320.0])
    b = base[0].astype(np.float64)
    scene = hot[0] - b
    ok = scene > 100.0
    r_lens = (lens[0] - b)[ok] / scene[ok]
    r_house = (housing[0] - b)[ok] / scene[ok]
    assert abs(r_lens.mean()) > 0.02  # the lens 20 K colder moves the level
    assert r_lens.std() / abs(r_lens.mean()) < 0.01  # measured 0.5 %: a uniform scene shift
    assert r_house.std() / abs(r_house.mean()) > 0.05  # measured 13 %: a pattern


def test_configs_compose_ffc_with_tc_housing_and_keep_the_codes():
    cfgs = goal.configs(("tchousing14+ffc", "tcffc14", "tchousing14+tc_gain"), 12, 12, 32)
    assert cfgs["tchousing14+ffc"].method == "tc_housing+ffc"
    assert cfgs["tchousing14+ffc"].tc_gain and cfgs["tchousing14+ffc"].ffc_frames == 32
    assert cfgs["tcffc14"].ffc_frames == 32 and cfgs["tcffc14"].reading_range_bits == 12
    base = load_pipeline("tcffc14")
    assert (cfgs["tcffc14"].to_dict()["formats"]["tc1"]["int_bits"]
            == base.to_dict()["formats"]["tc1"]["int_bits"] + 1)
    m = goal.cost(cfgs["tchousing14+tc_gain"])
    assert m["memory_bits"] == sum(x.word_bits for x in cfgs["tchousing14+tc_gain"]
                                   .memories.values())


def test_an_ffc_without_the_housing_does_not_follow_it_on_the_warm_up():
    """The warm-up's housing falls behind the FPA between two FFCs of the Lepton policy:
    tc_offset + ffc (FPA only) is left with hundreds of mK, tc_housing + ffc is not; the
    dead time is (N + 1) frames per FFC over the run's 36000 frames."""
    s = dc.StudySensor(rows=12, cols=16, seed=3)
    setup = goal.Setup(labels=("tcffc14", "tchousing14+ffc"),
                       policies=(("Lepton", 180.0, 1.5),), cal_frames=1, ffc_frames=(4,),
                       repeats=1, peaks=2, states=3, fpa_points=3, noise=False)
    r = goal.scenario("power_on_warmup", s, setup)
    runs = {x["method"]: x for x in r["runs"]}
    assert r["housing_sensor_node"] == "housing"
    assert runs["tcffc14"]["worst_fpn_mK"] > 200.0
    assert runs["tchousing14+ffc"]["worst_fpn_mK"] < 0.2 * runs["tcffc14"]["worst_fpn_mK"]
    for x in runs.values():
        ffcs = x["ffc_per_hour"] * 1200.0 / 3600.0
        assert ffcs == pytest.approx(round(ffcs)) and ffcs >= 7  # 20 min, 1.5 K / 3 min
        assert x["dead_time_pct"] == pytest.approx(100.0 * ffcs * 5 / 36000)


def test_curvature_core_fit_is_the_per_pixel_least_squares():
    """The float what-if core's batched normal equations against numpy.linalg.lstsq on the
    design matrix written out by hand, pixel by pixel (random codes, 4 x 3 points x 3
    scenes), and its correction at a point against the hand-built features."""
    from types import SimpleNamespace

    rng = np.random.default_rng(5)
    p_n, s_n, m, h, w = 6, 3, 2, 3, 4
    codes = rng.integers(3000, 12000, (p_n, s_n, m, h, w)).astype(np.uint16)
    reading = np.repeat(rng.integers(7000, 9000, p_n)[:, None, None], s_n * m, 1).reshape(
        p_n, s_n, m)
    hread = np.repeat(rng.integers(7000, 9000, p_n)[:, None, None], s_n * m, 1).reshape(
        p_n, s_n, m)
    pts = SimpleNamespace(codes=codes, reading=reading, housing_reading=hread, reference=2)
    targets = np.array([4000.0, 8000.0, 12000.0])
    core = goal.CurvatureCore.fit(pts, targets, np.ones((h, w), bool), 0.01, 0.02)
    t0, h0 = float(reading[2, 0, 0]), float(hread[2, 0, 0])
    for i, j in ((0, 0), (2, 3)):
        rows, b = [], []
        for p in range(p_n):
            v = (reading[p, 0, 0] - t0) * 0.01 / 10.0
            u = (hread[p, 0, 0] - h0) * 0.02 / 10.0
            for s in range(s_n):
                x = codes[p, s, :, i, j].mean() / 8192.0 - 1.0
                rows.append([x, x * v, x * v * v, x * x, 1.0, v, v * v, u, v * u, u * u])
                b.append(targets[s])
        want = np.linalg.lstsq(np.asarray(rows), np.asarray(b), rcond=None)[0]
        np.testing.assert_allclose(core.coef[:, i, j], want, rtol=1e-6, atol=1e-6)
        y = core.correct(codes[4, 1, :1], int(reading[4, 0, 0]), int(hread[4, 0, 0]))
        v = (reading[4, 0, 0] - t0) * 0.01 / 10.0
        u = (hread[4, 0, 0] - h0) * 0.02 / 10.0
        x = codes[4, 1, 0, i, j] / 8192.0 - 1.0
        f = np.array([x, x * v, x * v * v, x * x, 1.0, v, v * v, u, v * u, u * u])
        np.testing.assert_allclose(y[0, i, j], f @ want, rtol=1e-9, atol=1e-6)


def test_piecewise_core_corrects_with_the_nearest_window():
    """Each window's core is the CurvatureCore of its three FPA points (fitted apart here),
    and a frame is corrected by the window whose middle reading is nearest its own."""
    from types import SimpleNamespace

    rng = np.random.default_rng(8)
    fpa = np.repeat([280.0, 290.0, 300.0, 310.0], 2)
    hk = fpa + np.tile([-3.0, 0.0], 4)
    n_p, s_n, m, h, w = fpa.size, 3, 1, 2, 3
    codes = rng.integers(3000, 12000, (n_p, s_n, m, h, w)).astype(np.uint16)
    rd = np.broadcast_to(np.rint(fpa * 100)[:, None, None], (n_p, s_n, m)).astype(np.int64)
    hr = np.broadcast_to(np.rint(hk * 100)[:, None, None], (n_p, s_n, m)).astype(np.int64)
    pts = SimpleNamespace(codes=codes, reading=rd, housing_reading=hr, fpa_K=fpa,
                          housing_K=hk, reference=0)
    t = np.array([4000.0, 8000.0, 12000.0])
    good = np.ones((h, w), bool)
    pw = goal.PiecewiseCore.fit(pts, t, good, 0.01, 0.01)
    np.testing.assert_array_equal(pw.centres, [29000.0, 30000.0])
    # the window of FPA 290, 300, 310 K; its reference FPA 300 K at housing = FPA
    sub = SimpleNamespace(codes=codes[2:8], reading=rd[2:8], housing_reading=hr[2:8],
                          reference=3)
    want = goal.CurvatureCore.fit(sub, t, good, 0.01, 0.01)
    raw = codes[5, :, 0]
    np.testing.assert_allclose(pw.correct(raw, 30100, 30000),
                               want.correct(raw, 30100, 30000), rtol=1e-12)
    with pytest.raises(ValueError, match="at least 3"):
        goal.PiecewiseCore.fit(SimpleNamespace(**{**vars(pts), "fpa_K": np.full(n_p, 300.0)}),
                               t, good, 0.01, 0.01)
