"""tc_housing (issue 36 part 1): the offset polynomial in the FPA and the housing readings.

The fit against a second derivation (the full least-squares system built by hand and
solved by numpy.linalg.lstsq, on exact synthetic points), the golden polynomial against
exact Python integers, the model's plan over FPA x housing, and the plan it refuses.
"""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.nuc_fixed import load_pipeline
from irnuc.nuc_fixed.fit import calibrate_points
from irnuc.nuc_fixed.plan import CalibrationPlan, PlanError, PointFrames, run_plan
from irnuc.nuc_fixed.tempcomp import tc_coeffs, tc_reading

CFG = "tchousing14"


def _exact_points(seed: int = 0, shape: tuple[int, int] = (4, 5)) -> tuple[PointFrames, dict]:
    """3 FPA x 3 housing points whose readings are 1024 codes apart (with Ts = Hs = 12,
    u^2, u*w and w^2 over 2^12 are exact: the datapath's regressors are the exact v, v^2,
    w', v·w', w'^2), offsets a full quadratic in (v, w') per pixel, a gain per pixel."""
    rng = np.random.default_rng(seed)
    t0, h0 = 6000, 7000
    fpa = [t0 - 1024, t0, t0 + 1024]
    hou = [h0 - 1024, h0, h0 + 1024]
    pts = [(t, h) for t in fpa for h in hou]
    g = 40 * (1 + rng.normal(0, 0.05, shape))
    coef = {k: rng.normal(0, s, shape) for k, s in
            (("c0", 150), ("v", 400), ("v2", 60), ("w", 300), ("vw", 80), ("w2", 40))}
    scene = (290.0, 330.0, 370.0)
    codes = np.empty((9, 3, 1, *shape), np.int64)
    for p, (t, h) in enumerate(pts):
        v, w = (t - t0) / 4096, (h - h0) / 4096
        off = (3000 + coef["c0"] + coef["v"] * v + coef["v2"] * v * v + coef["w"] * w
               + coef["vw"] * v * w + coef["w2"] * w * w)
        for s, ts in enumerate(scene):
            codes[p, s, 0] = np.rint(off + g * (ts - 300))
    reading = np.stack([np.full((3, 1), t) for t, _ in pts]).astype(np.int64)
    housing = np.stack([np.full((3, 1), h) for _, h in pts]).astype(np.int64)
    out = PointFrames(codes=codes, scene_K=np.asarray(scene),
                      fpa_K=np.asarray([288.0 + (t - t0) / 100 for t, _ in pts]),
                      reading=reading, adc_bits=14, reference=4, source="synthetic",
                      housing_K=np.asarray([290.0 + (h - h0) / 100 for _, h in pts]),
                      housing_reading=housing)
    return out, {"fpa": fpa, "housing": hou, "t0": t0, "h0": h0}


def test_fit_is_the_least_squares_polynomial_in_both_readings() -> None:
    pts, d = _exact_points()
    cfg = load_pipeline(CFG).replace(reading_range_bits=12, housing_range_bits=12)
    cal = calibrate_points(pts, cfg)
    assert cal.coeffs.registers["t_ref"] == d["t0"] and cal.coeffs.registers["h_ref"] == d["h0"]
    means = pts.codes.mean(axis=2)
    t = means[pts.reference].reshape(3, -1).mean(axis=1)
    tv = [(int(pts.reading[p, 0, 0]) - d["t0"]) / 4096 for p in range(9)]
    hw = [(int(pts.housing_reading[p, 0, 0]) - d["h0"]) / 4096 for p in range(9)]
    for i, j in ((0, 0), (3, 4), (1, 2)):
        # The common gain: one system over every point and scene, an offset per point.
        rows, rhs = [], []
        for p in range(9):
            for s in range(3):
                rows.append([means[p, s, i, j]] + [1.0 if q == p else 0.0 for q in range(9)])
                rhs.append(t[s])
        sol = np.linalg.lstsq(np.asarray(rows), np.asarray(rhs), rcond=None)[0]
        assert cal.floats["coeffs.gain"][i, j] == pytest.approx(sol[0], rel=1e-9)
        gq = int(cal.coeffs.fields["coeffs"]["gain"][i, j]) / 2**14
        o_p = np.mean(t) - gq * means[:, :, i, j].mean(axis=1)
        a = np.array([[1.0, v, v * v, w, v * w, w * w] for v, w in zip(tv, hw, strict=True)])
        c = np.linalg.lstsq(a, o_p, rcond=None)[0]
        got = [cal.floats[k][i, j] for k in ("coeffs.offset", "tc.tc1", "tc.tc2", "th.th1",
                                            "th.thx", "th.th2")]
        np.testing.assert_allclose(got, c, rtol=1e-7, atol=1e-6)
    # 9 points, 6 terms, an exact quadratic: the float fit leaves the rounding of the codes
    assert max(r["float_std"] for r in cal.summary["residual"]) < 0.5


def _half_up(x: int, k: int) -> int:
    return (x + (1 << (k - 1))) >> k if k else x


def test_golden_polynomial_is_exact_integer_arithmetic() -> None:
    cfg = load_pipeline(CFG)
    rng = np.random.default_rng(5)
    shape = (6, 7)

    def draw(name: str, signed: bool = True) -> np.ndarray:
        f = cfg.format(name)
        lo, hi = (-(1 << (f.bits - 1)), (1 << (f.bits - 1)) - 1) if signed else (0, (1 << f.bits) - 1)
        return rng.integers(lo, hi + 1, shape)

    gain = draw("gain", signed=False)
    offset = draw("offset")
    tc = {n: draw(n) for n in ("tc1", "tc2", "th1", "thx", "th2")}
    for reading, housing in ((7000, 9000), (7000, 4000), (100, 16383), (7485, 7485),
                             (9000, 7600)):
        tr = tc_reading(reading, 7485, cfg, housing, 7300)
        # tc_reading by hand: Ts = Hs = 11, clamps +-2047, floors
        u = max(-2047, min(2047, reading - 7485))
        w = max(-2047, min(2047, housing - 7300))
        assert (tr.u, tr.u2, tr.w, tr.uw, tr.w2) == (u, (u * u) // 2048, w, (u * w) // 2048,
                                                   (w * w) // 2048)
        g, o = tc_coeffs(gain, offset, tc, tr, cfg)
        assert np.array_equal(g, gain)
        # Fo = max(3, 3 + 11, 4 + 11, 3 + 11, 4 + 11, 4 + 11) = 15: the sum in Python ints
        for i in range(shape[0]):
            for j in range(shape[1]):
                acc = (int(offset[i, j]) << 12) + (int(tc["tc1"][i, j]) * u << 1) \
                    + int(tc["tc2"][i, j]) * ((u * u) // 2048) \
                    + (int(tc["th1"][i, j]) * w << 1) + int(tc["thx"][i, j]) * ((u * w) // 2048) \
                    + int(tc["th2"][i, j]) * ((w * w) // 2048)
                want = max(-(1 << 15), min((1 << 15) - 1, _half_up(acc, 12)))
                assert int(o[i, j]) == want, (reading, housing, i, j)


@pytest.fixture(scope="module")
def model_points() -> PointFrames:
    plan = CalibrationPlan(scene=(290.0, 330.0, 370.0), fpa=(288.0, 298.0, 308.0), frames=2,
                           housing_offset=(-5.0, 0.0, 5.0))
    return run_plan(plan, "default", {"fpa.active_rows": 12, "fpa.active_cols": 16}, seed=3)


def test_model_plan_over_fpa_and_housing(model_points: PointFrames) -> None:
    # Every (FPA, housing) point within about the model's nonlinearity, where tc_offset
    # (fitted at housing = FPA) leaves more than 20 codes 5 K away.
    th = calibrate_points(model_points, CFG)
    tc = calibrate_points(model_points, "tcoffset14")
    assert th.summary["reads_housing"] and th.summary["points"]["all_points"] == 9
    for key, rep in th.summary["coefficients"].items():
        assert rep["saturated"] == 0, key
    worst = {}
    for r in th.summary["residual"]:
        assert r["std"] < 2.0, r
        assert abs(r["std"] - r["float_std"]) < 0.2, r
    for r in tc.summary["residual"]:
        off = round(r["housing_K"] - r["fpa_K"])
        worst[off] = max(worst.get(off, 0.0), r["std"])
    assert worst[5] > 20 and worst[-5] > 20 and worst[0] < 2.0, worst


def test_a_plan_without_the_housing_is_refused() -> None:
    pts, _ = _exact_points()
    keep = [0, 3, 6]  # one housing reading per FPA point: nothing to fit w' on
    pts = PointFrames(codes=pts.codes[keep], scene_K=pts.scene_K, fpa_K=pts.fpa_K[keep],
                      reading=pts.reading[keep], adc_bits=14, reference=1, source="plan.toml",
                      housing_K=pts.housing_K[keep], housing_reading=pts.housing_reading[keep])
    with pytest.raises(PlanError, match=r"plan.toml: .*tc_housing.*housing_offset"):
        calibrate_points(pts, load_pipeline(CFG).replace(reading_range_bits=12,
                                                         housing_range_bits=12))


def test_a_plan_whose_housing_follows_the_fpa_is_refused() -> None:
    # Three housing readings, but each with its FPA's: w' and v cannot be told apart.
    pts, _ = _exact_points()
    keep = [0, 4, 8]  # (t0 - 1024, h0 - 1024), (t0, h0), (t0 + 1024, h0 + 1024)
    pts = PointFrames(codes=pts.codes[keep], scene_K=pts.scene_K, fpa_K=pts.fpa_K[keep],
                      reading=pts.reading[keep], adc_bits=14, reference=1, source="plan.toml",
                      housing_K=pts.housing_K[keep], housing_reading=pts.housing_reading[keep])
    with pytest.raises(PlanError, match=r"plan.toml: .*do not separate them.*housing_offset"):
        calibrate_points(pts, load_pipeline(CFG).replace(reading_range_bits=12,
                                                         housing_range_bits=12))


def test_the_command_line_refuses_a_plan_without_housing_offsets(
        tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    from irnuc.cli import main

    plan = tmp_path / "plan.toml"
    plan.write_text('[plan]\nscene = [290.0, 330.0, 370.0]\nfpa = [288.0, 298.0, 308.0]\n'
                    'frames = 2\n')
    out = tmp_path / "cal"
    assert main(["calibrate", "--plan", str(plan), "--pipeline", CFG, "--out", str(out),
                 "--set", "fpa.active_rows=8", "--set", "fpa.active_cols=8"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "housing_offset" in err and str(plan) in err, err
    assert not out.exists()


def test_calibrate_then_correct_through_the_command_line(tmp_path) -> None:
    # The housing reading of the frame file reaches the golden model: the corrected frames
    # of a housing 3 K off the FPA are those of method_top with the file's two readings,
    # and differ from those with the housing reading at the FPA's.
    from irnuc.cli import main
    from irnuc.nuc_fixed.memimage import read_calibration
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    plan = tmp_path / "plan.toml"
    plan.write_text('[plan]\nscene = [290.0, 330.0, 370.0]\nfpa = [288.0, 298.0, 308.0]\n'
                    'housing_offset = [-5.0, 0.0, 5.0]\nframes = 1\n')
    small = ["--set", "fpa.active_rows=8", "--set", "fpa.active_cols=8"]
    assert main(["calibrate", "--plan", str(plan), "--pipeline", CFG, "--out",
                 str(tmp_path / "cal"), "-q", *small]) == 0
    assert main(["frames", *small, "--set", "environment.T_cam=301", "--temps", "300,330",
                 "--out", str(tmp_path / "fr"), "-q"]) == 0
    assert main(["correct", "--frames", str(tmp_path / "fr"), "--coeffs", str(tmp_path / "cal"),
                 "--out", str(tmp_path / "cor"), "-q"]) == 0
    fr = np.load(tmp_path / "fr" / "frames.npz")
    got = np.load(tmp_path / "cor" / "corrected.npz")["corrected"]
    mc, _ = read_calibration(tmp_path / "cal")
    want = method_top(fr["codes"], mc, FrameInputs(reading=fr["fpa_reading"],
                                                   housing_reading=fr["housing_reading"])).y
    np.testing.assert_array_equal(got, want)
    assert int(fr["housing_reading"][0]) - int(fr["fpa_reading"][0]) == 100  # 1 K, 0.01 K/code
    at_fpa = method_top(fr["codes"], mc, FrameInputs(reading=fr["fpa_reading"],
                                                     housing_reading=fr["fpa_reading"])).y
    assert not np.array_equal(got, at_fpa)
