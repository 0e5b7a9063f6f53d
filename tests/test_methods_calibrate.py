"""Calibration of every method over temperature: fits against numpy.polyfit / lstsq, the
paper repository's formulas (re-derived here), the model plan, errors, memory images."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from irnuc.model.fpa_sensor import FpaSensor
from irnuc.nuc_fixed import MemImageError, load_pipeline, pipeline_names, read_memimage
from irnuc.nuc_fixed.fit import (
    FormatRangeError,
    calibrate_points,
    ls_line,
    piecewise_fit,
    quadratic_fit,
)
from irnuc.nuc_fixed.memimage import read_method_image, write_method_image
from irnuc.nuc_fixed.method_top import FrameInputs, method_top
from irnuc.nuc_fixed.plan import CalibrationPlan, PlanError, PointFrames, load_plan, run_plan

#: The configurations a plan at housing = FPA calibrates (tc_housing needs a plan over the
#: housing: tests/test_tc_housing.py).
METHOD_CONFIGS = [n for n in pipeline_names(method=None) if n not in ("wide16", "minimal")
                  and "housing" not in load_pipeline(n).base.readings]

PLAN_TEXT = """[plan]
scene = [290.0, 330.0, 370.0]     # K, blackbody temperatures
fpa = [288.0, 298.0, 308.0]       # K, FPA (substrate) temperatures
frames = 4                        # per point
"""


def synth_points(fpa=(288.0, 298.0, 308.0), scene=(290.0, 330.0, 370.0), m=2, shape=(6, 8),
                 seed=0, sensor: FpaSensor | None = None, blind_k: int = 20,
                 coupling: float = 1.7, noise: float = 0.0,
                 housing: tuple[float, ...] = ()) -> PointFrames:
    """A smooth synthetic array: offset, responsivity and curvature per pixel, all drifting
    with the FPA temperature. Blind pixels at 5000 codes; a housing temperature change of
    ``h`` K (the ``housing`` points, at the reference FPA point and the middle scene)
    moves them by 10 h codes and the image by ``coupling`` times that. Without ``noise``
    the frames of a point are equal (the fits see exact codes; the noise detection's floor
    keeps every pixel)."""
    rng = np.random.default_rng(seed)
    o = 3000 + rng.normal(0, 150, shape)
    g = 40 * (1 + rng.normal(0, 0.05, shape))
    c = rng.normal(0, 0.001, shape)
    drift = -35 + rng.normal(0, 2, shape)
    sensor = sensor or FpaSensor()

    def image(tf: float, ts: float, dh: float) -> np.ndarray:
        mean = (o + drift * (tf - 298) + g * (1 + 0.02 * (tf - 298)) * (ts - 300)
                + c * (ts - 300) ** 2 + coupling * 10 * dh)
        return np.rint(mean + noise * rng.normal(0, 1.0, (m, *shape)))

    codes = np.empty((len(fpa), len(scene), m, *shape), np.int64)
    blind = np.empty((len(fpa), len(scene), m, blind_k), np.int64)
    for p, tf in enumerate(fpa):
        for s, ts in enumerate(scene):
            codes[p, s] = image(tf, ts, 0.0)
            blind[p, s] = np.rint(5000 + rng.normal(0, 1, (m, blind_k)))
    reading = np.stack([np.broadcast_to(sensor.read(tf), (len(scene), m)) for tf in fpa])
    ref = int(np.argmin(np.abs(np.asarray(fpa) - np.mean(fpa))))
    pts = PointFrames(codes=codes, scene_K=np.asarray(scene), fpa_K=np.asarray(fpa),
                      reading=reading.astype(np.int64), adc_bits=14, reference=ref,
                      blind_codes=blind, source="synthetic")
    if housing:
        mid = scene[len(scene) // 2]
        pts.drift_codes = np.stack([image(fpa[ref], mid, h) for h in housing]).astype(np.int64)
        pts.drift_blind = np.stack([np.rint(5000 + 10 * h + rng.normal(0, 1, (m, blind_k)))
                                    for h in housing]).astype(np.int64)
        pts.drift_cam_K = 300.0 + np.asarray(housing)
    return pts


def _targets(pts: PointFrames) -> tuple[np.ndarray, np.ndarray]:
    means = pts.codes.mean(axis=2)
    return means, means[pts.reference].reshape(len(pts.scene_K), -1).mean(axis=1)


# ---- fits against numpy ---------------------------------------------------------------------

def test_two_point_is_the_polyfit_line() -> None:
    pts = synth_points(scene=(290.0, 320.0, 350.0, 380.0))
    cal = calibrate_points(pts, "typical14")
    assert cal.summary["bad_pixels"] == 0
    means, t = _targets(pts)
    x = means[pts.reference]
    for i, j in ((0, 0), (3, 5), (5, 7)):
        slope = np.polyfit(x[:, i, j], t, 1)[0]
        assert cal.floats["coeffs.gain"][i, j] == pytest.approx(slope, rel=1e-10)
        gq = int(cal.coeffs.fields["coeffs"]["gain"][i, j]) / 2**14
        assert cal.floats["coeffs.offset"][i, j] == pytest.approx(np.mean(t - gq * x[:, i, j]), abs=1e-9)


@pytest.mark.parametrize("scene", [(290.0, 330.0, 370.0), (290.0, 310.0, 340.0, 370.0)])
def test_quadratic_is_the_polyfit_parabola(scene) -> None:
    pts = synth_points(scene=scene)
    cal = calibrate_points(pts, "quadratic14")
    means, t = _targets(pts)
    x = means[pts.reference]
    for i, j in ((0, 0), (2, 3), (5, 7)):
        xi = x[:, i, j] / 2**14
        a, _, _ = np.polyfit(xi, t, 2)
        assert cal.floats["quad.quad"][i, j] == pytest.approx(a, rel=1e-7)
        qq = int(cal.coeffs.fields["quad"]["quad"][i, j]) / 64
        rest = t - qq * xi**2
        (g, _), *_ = np.linalg.lstsq(np.stack([x[:, i, j], np.ones(len(t))], 1), rest, rcond=None)
        assert cal.floats["coeffs.gain"][i, j] == pytest.approx(g, rel=1e-9)


def test_tc_offset_fits_are_least_squares() -> None:
    # Readings 1024 codes apart: u^2 / 2^Ts is exact, so the datapath's v2 is v^2 and
    # numpy.polyfit applies as it is.
    sensor = FpaSensor(lsb_K=10.0 / 1024)
    pts = synth_points(fpa=(288.0, 298.0, 308.0, 318.0), sensor=sensor)
    pts.reference = 1
    cfg = load_pipeline("tcoffset14").replace(reading_range_bits=12)
    cal = calibrate_points(pts, cfg)
    means, t = _targets(pts)
    readings = [int(pts.reading[p, 0, 0]) for p in range(4)]
    v = (np.asarray(readings) - readings[1]) / 2.0**12
    for i, j in ((0, 0), (4, 6)):
        # The common gain: the full least-squares system, one offset per FPA point.
        rows, rhs = [], []
        for p in range(4):
            for s in range(3):
                rows.append([means[p, s, i, j]] + [1.0 if q == p else 0.0 for q in range(4)])
                rhs.append(t[s])
        sol = np.linalg.lstsq(np.asarray(rows), np.asarray(rhs), rcond=None)[0]
        assert cal.floats["coeffs.gain"][i, j] == pytest.approx(sol[0], rel=1e-9)
        gq = int(cal.coeffs.fields["coeffs"]["gain"][i, j]) / 2**14
        o_p = np.mean(t) - gq * means[:, :, i, j].mean(axis=1)
        c2, c1, c0 = np.polyfit(v, o_p, 2)
        assert cal.floats["coeffs.offset"][i, j] == pytest.approx(c0, abs=1e-6)
        assert cal.floats["tc.tc1"][i, j] == pytest.approx(c1, rel=1e-7)
        assert cal.floats["tc.tc2"][i, j] == pytest.approx(c2, rel=1e-6, abs=1e-6)
    assert cal.coeffs.registers["t_ref"] == readings[1]


def test_table_interp_tables_are_per_point_lines() -> None:
    pts = synth_points()
    cal = calibrate_points(pts, "table14")
    means, t = _targets(pts)
    assert cal.coeffs.registers["table_readings"] == tuple(int(pts.reading[p, 0, 0]) for p in range(3))
    for p in range(3):
        slope, _ = np.polyfit(means[p, :, 2, 2], t, 1)
        assert cal.floats[f"table{p}.gain"][2, 2] == pytest.approx(slope, rel=1e-10)


def test_blind_drift_coupling_and_registers() -> None:
    pts = synth_points(coupling=1.7, blind_k=20, housing=(-5.0, 5.0, 10.0))
    cal = calibrate_points(pts, "drift14")
    means, _ = _targets(pts)
    xs = [means[1, 1].mean()] + [d.mean() for d in pts.drift_codes]
    bs = [pts.blind_codes[1, 1].mean()] + [d.mean() for d in pts.drift_blind]
    k = np.polyfit(bs, xs, 1)[0]
    assert cal.floats["drift_coupling"] == pytest.approx(k, rel=1e-9)
    assert k == pytest.approx(1.7, rel=0.01)  # the planted coupling
    assert cal.coeffs.registers["drift_gain"] == round(k / 20 * 2**24)
    assert cal.coeffs.registers["blind_ref"] == round(pts.blind_codes[1].sum(axis=-1).mean())
    # Without housing points the coupling is the paper repository's 1.
    assert calibrate_points(synth_points(), "drift14").coeffs.registers["drift_gain"] == round(2**24 / 20)
    # The housing 10 K warmer: drift compensation brings the frame back to its target;
    # two_point alone is 170 codes off.
    two = calibrate_points(pts, "typical14")
    x = pts.drift_codes[2]
    y_d = method_top(x, cal.coeffs, FrameInputs(blind_codes=pts.drift_blind[2])).y.astype(float)
    y_2 = method_top(x, two.coeffs, FrameInputs()).y.astype(float)
    err_d = abs(y_d.mean() - cal.targets[1])
    err_2 = abs(y_2.mean() - two.targets[1])
    assert err_d < 1.5 and 150 < err_2 < 190


# ---- the paper repository's formulas, re-derived ----------------------------------------------
# (edi-riga/applause-ir-modelling, ir_sim/nuc.py: 1-point b = V0 - f0; 2-point through
# (f0, V0), (f1, V1); 3-point linear: two such lines, switched at their intersection;
# 3-point quadratic: the parabola through the three points. Written here from those
# definitions: Lagrange interpolation for the parabola, line intersection for the knee.)

def _paper_points(n_scene: int):
    pts = synth_points(scene=(290.0, 330.0, 370.0)[:n_scene] if n_scene < 3 else (290.0, 330.0, 370.0))
    means, t = _targets(pts)
    return pts, means[pts.reference], t


def test_paper_one_and_two_point() -> None:
    pts, x, t = _paper_points(2)
    f0, f1 = x[0], x[-1]
    v0, v1 = t[0], t[-1]
    k = (v0 - v1) / (f0 - f1)
    b = (v1 * f0 - v0 * f1) / (f0 - f1)
    g, o = ls_line(x, t)
    assert np.allclose(g, k, rtol=1e-12) and np.allclose(o, b, rtol=1e-9, atol=1e-9)
    # One point per scene: b_s = V_s - f_s (unit gain, A = B); ours is their least-squares
    # combination, the mean over the scenes.
    cal = calibrate_points(pts, "onepoint14")
    assert cal.coeffs.registers["gain"] == 2**14
    assert np.allclose(cal.floats["coeffs.offset"], np.mean([v0 - f0, v1 - f1], axis=0), atol=1e-9)


def test_paper_piecewise_and_quadratic() -> None:
    _, x, t = _paper_points(3)
    f0, f1, f2 = x
    v0, v1, v2 = t
    k1, b1 = (v0 - v1) / (f0 - f1), (v1 * f0 - v0 * f1) / (f0 - f1)
    k2, b2 = (v1 - v2) / (f1 - f2), (v2 * f1 - v1 * f2) / (f1 - f2)
    x_int = (b2 - b1) / (k1 - k2)
    knee, level, g_lo, g_hi = piecewise_fit(x, t)
    assert np.allclose(knee, x_int, rtol=1e-9)  # the knee is where the paper's lines meet
    for xs in (f0 - 500, f0, (f0 + f1) / 2, f1, (f1 + f2) / 2, f2, f2 + 700):
        paper = np.where(xs <= x_int, k1 * xs + b1, k2 * xs + b2)
        ours = level + np.where(xs <= knee, g_lo, g_hi) * (xs - knee)
        assert np.allclose(ours, paper, rtol=1e-9, atol=1e-6)
    # The parabola through the three points, by Lagrange's form.
    den = [(f0 - f1) * (f0 - f2), (f1 - f0) * (f1 - f2), (f2 - f0) * (f2 - f1)]
    a = v0 / den[0] + v1 / den[1] + v2 / den[2]
    b = -(v0 * (f1 + f2) / den[0] + v1 * (f0 + f2) / den[1] + v2 * (f0 + f1) / den[2])
    c = v0 * f1 * f2 / den[0] + v1 * f0 * f2 / den[1] + v2 * f0 * f1 / den[2]
    q, g, o = quadratic_fit(x, t, 14)
    assert np.allclose(q / 2.0**28, a, rtol=1e-6)
    assert np.allclose(g, b, rtol=1e-6) and np.allclose(o, c, rtol=1e-6, atol=1e-4)


# ---- the plan on the model, every method -----------------------------------------------------

@pytest.fixture(scope="module")
def model_points() -> PointFrames:
    plan = CalibrationPlan(scene=(290.0, 330.0, 370.0), fpa=(288.0, 298.0, 308.0), frames=4)
    return run_plan(plan, "default", {"fpa.active_rows": 24, "fpa.active_cols": 32}, seed=3)


@pytest.mark.parametrize("name", METHOD_CONFIGS)
def test_plan_calibrates_every_method(model_points: PointFrames, name: str) -> None:
    cal = calibrate_points(model_points, name)
    s = cal.summary
    assert s["method"] == load_pipeline(name).method
    for key, rep in s["coefficients"].items():
        assert rep["saturated"] == 0, key
        assert rep["calibratable"]["int_bits_needed"] <= rep["int_bits"], key
    res = {(r["fpa_K"], r["scene_K"]): r for r in s["residual"]}
    temperature = "fpa" in cal.cfg.base.readings
    for (fpa, _), r in res.items():
        if cal.cfg.base_method == "one_point":
            continue  # a global gain leaves the gain spread: large everywhere
        if temperature or fpa == 298.0:
            assert r["std"] < 2.0, (fpa, r)  # codes, about the model's nonlinearity
        else:
            assert r["std"] > 20.0, (fpa, r)  # the drift a method without compensation leaves
        # The quantized method is the float fit within a fraction of a code.
        assert abs(r["std"] - r["float_std"]) < 0.2
    # Planted defects are found (the model's ground truth).
    truth = model_points.defect_kind > 0
    assert (cal.bad & truth).sum() >= 0.8 * truth.sum()


def test_plan_text_of_the_issue(tmp_path: Path) -> None:
    f = tmp_path / "plan.toml"
    f.write_text(PLAN_TEXT)
    plan = load_plan(f)
    assert plan.scene == (290.0, 330.0, 370.0) and plan.fpa == (288.0, 298.0, 308.0)
    assert plan.frames == 4 and plan.reference_index == 1 and plan.cam_K == plan.fpa


@pytest.mark.parametrize(("text", "match"), [
    (PLAN_TEXT.replace("scene =", "scenes ="),
     "plan.scenes is not a known field; did you mean 'scene'"),
    (PLAN_TEXT.replace("frames = 4", "frames = 0"), "plan.frames = 0"),
    (PLAN_TEXT.replace("[290.0, 330.0, 370.0]", "[330.0, 290.0]"),
     "plan.scene = [330.0, 290.0] must increase"),
    (PLAN_TEXT.replace("[290.0, 330.0, 370.0]", "[]"), "plan.scene has 0 item(s)"),
    (PLAN_TEXT + "cam = [300.0]\n", "plan.cam has 1 values but plan.fpa has 3"),
    (PLAN_TEXT + "reference_fpa = 300.0\n", "plan.reference_fpa = 300 K is not one of plan.fpa"),
    (PLAN_TEXT + "[fpa_sensor]\nlsb = 0.1\n", "fpa_sensor.lsb is not a known field"),
    ("[plans]\n", "plans is not a known field"),
    (PLAN_TEXT.replace("288.0, ", "'x', "), "plan.fpa[0] = 'x' must be a number"),
])
def test_bad_plans_are_named(tmp_path: Path, text: str, match: str) -> None:
    f = tmp_path / "p.toml"
    f.write_text(text)
    with pytest.raises(PlanError, match=re.escape(match)):
        load_plan(f)


def test_method_needs_are_errors() -> None:
    two_scenes = synth_points(scene=(290.0, 370.0))
    with pytest.raises(PlanError, match="needs at least 3 scene temperatures"):
        calibrate_points(two_scenes, "quadratic14")
    with pytest.raises(PlanError, match="tables = 3 needs 3 FPA temperatures; the plan has 2"):
        calibrate_points(synth_points(fpa=(288.0, 308.0)), "table14")
    with pytest.raises(PlanError, match="tc_order = 2 needs at least 3 FPA temperatures"):
        calibrate_points(synth_points(fpa=(288.0, 308.0)), "tcoffset14")
    far = synth_points(fpa=(270.0, 298.0, 330.0))
    with pytest.raises(FormatRangeError, match=r"reading_range_bits = 11 \(\+-2047\): widen"):
        calibrate_points(far, "tcoffset14")
    no_read = synth_points()
    no_read.reading[:] = -1
    with pytest.raises(PlanError, match="needs the FPA reading of every frame"):
        calibrate_points(no_read, "table14")
    no_blind = synth_points()
    no_blind.blind_codes = None
    with pytest.raises(PlanError, match="needs the blind pixel codes"):
        calibrate_points(no_blind, "drift14")
    narrow = load_pipeline("quadratic14").replace(
        formats={"quad": {"int_bits": 1, "frac_bits": 6}})
    with pytest.raises(FormatRangeError,
                       match=r"quad\.quad saturates on .* widen formats\.quad\.int_bits to"):
        calibrate_points(synth_points(shape=(12, 12)), narrow)


# ---- memory images, version 2 ------------------------------------------------------------------

@pytest.mark.parametrize("name", [n for n in METHOD_CONFIGS if n != "typical14"])
def test_method_image_round_trip(tmp_path: Path, name: str) -> None:
    pts = synth_points()
    if "drift" not in name and "tc" not in name and "table" not in name:
        pts.blind_codes = None
    cal = calibrate_points(pts, name)
    m = write_method_image(tmp_path, cal.coeffs)
    assert m["version"] == 2 and m["method"] == cal.cfg.method
    for source in ("bin", "hex"):
        back = read_method_image(tmp_path, name, source=source)
        assert back.cfg == cal.cfg and back.registers == cal.coeffs.registers
        for mem, fields in cal.coeffs.fields.items():
            for f, v in fields.items():
                assert np.array_equal(back.fields[mem][f], v), (mem, f)
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    for d in manifest["memories"].values():
        lines = (tmp_path / d["hex_file"]).read_text().splitlines()
        assert len(lines) == 6 * 8 and all(len(s) == -(-d["word_bits"] // 4) for s in lines)
    # The version-1 reader refuses a version-2 folder.
    with pytest.raises(MemImageError, match="version = 2"):
        read_memimage(tmp_path)


def test_method_image_corruption_is_named(tmp_path: Path) -> None:
    cal = calibrate_points(synth_points(), "table14")
    write_method_image(tmp_path, cal.coeffs)
    raw = bytearray((tmp_path / "table1.bin").read_bytes())
    raw[3] ^= 1
    (tmp_path / "table1.bin").write_bytes(bytes(raw))
    with pytest.raises(MemImageError, match=re.escape("table1.bin: SHA-256")):
        read_method_image(tmp_path)
    write_method_image(tmp_path, cal.coeffs)
    m = json.loads((tmp_path / "manifest.json").read_text())
    m["method_fields"]["tables"] = 2
    (tmp_path / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(MemImageError, match="do not match their recorded SHA-256"):
        read_method_image(tmp_path)
    write_method_image(tmp_path, cal.coeffs)
    with pytest.raises(MemImageError, match=re.escape("whose fields differ from pipeline 'tcgain14'")):
        read_method_image(tmp_path, "tcgain14")
