"""Calibration over the housing too (issue 35): the plan's housing_offset (every
combination), frames grouped by (FPA, housing), the housing reading on its way to the
golden model, and the plan's keys checked before any work."""

from __future__ import annotations

import json

import numpy as np
import pytest

from irnuc.cli import main
from irnuc.nuc_fixed.fit import calibrate_points
from irnuc.nuc_fixed.plan import CalibrationPlan, PlanError, load_plan, points_from_frames, run_plan

ISSUE_PLAN = """\
[plan]
scene = [290.0, 370.0]
fpa = [290.0, 300.0, 310.0]
housing_offset = [-5.0, 0.0, 5.0]   # K, the housing relative to the FPA, every combination
frames = 4
"""
SMALL = {"fpa.active_rows": 12, "fpa.active_cols": 16}


def test_the_issue_plan_works_as_written(tmp_path, capsys):
    plan = tmp_path / "plan.toml"
    plan.write_text(ISSUE_PLAN)
    out = tmp_path / "cal"
    assert main(["calibrate", "--plan", str(plan), "--pipeline", "tcoffset14", "--set",
                 "fpa.active_rows=12", "--set", "fpa.active_cols=16", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "fitted on the 3 points with the housing at the reference offset" in text
    assert "x housing offset [-5.0, 0.0, 5.0] K x 4 frames" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["points"]["all_points"] == 9 and s["points"]["fpa_K"] == [290.0, 300.0, 310.0]
    assert s["points"]["housing_K"] == [290.0, 300.0, 310.0]
    assert s["points"]["housing_offset_K"] == [-5.0, 0.0, 5.0]
    res = {(r["fpa_K"], r["housing_K"], r["scene_K"]): r["std"] for r in s["residual"]}
    assert len(res) == 18  # 3 FPA x 3 housing x 2 scenes
    # the method assumes the housing at the FPA: there it corrects to a code or so, 5 K
    # away the housing's radiation leaves a fixed pattern of tens of codes
    at = [v for (f, c, _), v in res.items() if c == f]
    away = [v for (f, c, _), v in res.items() if c != f]
    assert max(at) < 2.0 and min(away) > 20 * max(at)


def test_points_are_every_combination_and_the_methods_fit_at_the_reference_offset():
    p = CalibrationPlan(scene=(290.0, 370.0), fpa=(290.0, 300.0), frames=2,
                        housing_offset=(-3.0, 2.0), reference_fpa=300.0)
    assert p.points() == [(290.0, 287.0), (290.0, 292.0), (300.0, 297.0), (300.0, 302.0)]
    assert p.reference_offset == 2.0 and p.points()[p.reference_point] == (300.0, 302.0)
    pts = run_plan(p, "default", SMALL, seed=2)
    assert pts.codes.shape[:3] == (4, 2, 2)
    np.testing.assert_array_equal(pts.housing_K, [287.0, 292.0, 297.0, 302.0])
    hs = p.housing_sensor
    np.testing.assert_array_equal(pts.housing_reading[1], hs.read(np.full(4, 292.0)).reshape(2, 2))
    sub = pts.fpa_points()
    np.testing.assert_array_equal(sub.housing_K, [292.0, 302.0])
    assert sub.reference == 1 and sub.codes.shape[0] == 2
    np.testing.assert_array_equal(sub.codes[0], pts.codes[1])
    # frames of every combination (as a drift sequence would give them) group back
    n = pts.codes.shape[0] * 2 * 2
    data = {"codes": pts.codes.reshape(n, *pts.codes.shape[-2:]),
            "scene_K": np.tile(np.repeat([290.0, 370.0], 2), 4),
            "fpa_K": np.repeat(pts.fpa_K, 4), "T_cam_K": np.repeat(pts.housing_K, 4),
            "fpa_reading": pts.reading.reshape(-1),
            "housing_reading": pts.housing_reading.reshape(-1), "adc_bits": 14}
    back = points_from_frames(data)
    np.testing.assert_array_equal(back.codes, pts.codes)
    np.testing.assert_array_equal(back.housing_K, pts.housing_K)
    assert back.fpa_points().codes.shape[0] == 2
    cal = calibrate_points(pts, "typical14")
    assert cal.summary["points"]["all_points"] == 4


@pytest.mark.parametrize(("text", "fragment"), [
    ("housing_offset = [0.0, 5.0]\ncam = [300.0, 310.0]\n",
     "plan.cam and plan.housing_offset both set the housing"),
    ("housing_offsets = [0.0]\n", "did you mean 'housing_offset'"),
    ("housing_offset = [5.0, 0.0]\n", "plan.housing_offset = [5.0, 0.0] must increase strictly"),
    ("housing_offset = [500.0]\n", "housing_offset"),
    ("[housing_sensor]\nnode = \"lid\"\n", "housing_sensor.node"),
])
def test_bad_plans_are_refused_naming_the_key(tmp_path, text, fragment):
    plan = tmp_path / "p.toml"
    body = "[plan]\nscene = [290.0, 370.0]\nfpa = [300.0, 310.0]\nframes = 2\n"
    plan.write_text(body + text)
    with pytest.raises(PlanError) as err:
        load_plan(plan)
    assert fragment in str(err.value) and "\n" not in str(err.value)


def test_correct_hands_the_housing_reading_to_the_golden_model(tmp_path, monkeypatch):
    frames = tmp_path / "f"
    assert main(["frames", "-q", "--set", "fpa.active_rows=12", "--set", "fpa.active_cols=16",
                 "--temps", "290,370", "--repeats", "2", "--set", "environment.T_cam=303",
                 "--out", str(frames)]) == 0
    cal = tmp_path / "c"
    assert main(["calibrate", "-q", "--frames", str(frames), "--pipeline", "typical14",
                 "--out", str(cal)]) == 0
    import importlib

    mt = importlib.import_module("irnuc.nuc_fixed.method_top")

    seen = {}
    real = mt.method_top

    def spy(raw, coeffs, inputs=None, **kw):
        seen["housing"] = None if inputs is None else inputs.housing_reading
        return real(raw, coeffs, inputs, **kw)

    monkeypatch.setattr(mt, "method_top", spy)
    assert main(["correct", "-q", "--frames", str(frames), "--coeffs", str(cal), "--out",
                 str(tmp_path / "o")]) == 0
    from irnuc.model.fpa_sensor import HousingSensor

    np.testing.assert_array_equal(seen["housing"], HousingSensor().read(np.full(4, 303.0)))
