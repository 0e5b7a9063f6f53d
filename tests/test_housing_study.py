"""`irnuc study housing` (issue 36): the residual against the housing-FPA difference, its
command line, an independent (float, numpy) check of its residual, the physics it must
show, and the blind pixels' coupling to the housing."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from irnuc.cli import main

PNG = b"\x89PNG\r\n\x1a\n"
ROWS, COLS = 12, 16


@pytest.fixture(scope="module")
def housing_run(tmp_path_factory: pytest.TempPathFactory) -> dict:
    """The study's default path through the command line, on a tiny array."""
    out = tmp_path_factory.mktemp("housing") / "s"
    assert main(["study", "housing", "--quick", "--set", f"fpa.active_rows={ROWS}",
                 "--set", f"fpa.active_cols={COLS}", "--out", str(out), "-q"]) == 0
    assert (out / "housing.png").read_bytes().startswith(PNG)
    text = (out / "housing.txt").read_text()

    def strict(c: str) -> float:
        raise AssertionError(f"{c} in the study's JSON")

    data = json.loads((out / "housing.json").read_text(), parse_constant=strict)
    data["_text"] = text
    return data


def _row(r: dict, config: str, calibration: str, variant: str = "") -> dict:
    (row,) = [x for x in r["rows"] if (x["config"], x["calibration"], x["variant"])
              == (config, calibration, variant)]
    return row


def test_the_study_writes_every_method_both_calibrations(housing_run: dict) -> None:
    r = housing_run
    assert r["study"] == "housing" and r["sensor"]["rows"] == ROWS
    assert r["offset_K"] == [-5.0, -2.0, 0.0, 2.0, 5.0] and r["fpa_K"] == [298.0]
    keys = {(x["config"], x["calibration"], x["variant"]) for x in r["rows"]}
    for cfg in ("typical14", "drift14", "tcoffset14", "tcgain14", "table14"):
        assert {(cfg, "housing_at_fpa", ""), (cfg, "over_housing", "")} <= keys
    for cfg in ("ffc14", "tcffc14"):
        for cal in ("housing_at_fpa", "over_housing"):
            assert {(cfg, cal, "FFC at housing = FPA"), (cfg, cal, "FFC at this housing")} <= keys
    # every row and offset in the text table
    assert all(x["config"] in r["_text"] for x in r["rows"]) and "+5K" in r["_text"]


def test_no_method_but_tc_housing_reads_the_housing(housing_run: dict) -> None:
    # The registry fits at the reference offset: the plan over the housing gives the same
    # coefficients, codes for codes, but blind_drift's coupling, which it measures, and
    # tc_housing, fitted on every (FPA, housing) point and only over the housing.
    keys = {(x["config"], x["calibration"]) for x in housing_run["rows"]}
    assert ("tchousing14", "over_housing") in keys
    assert ("tchousing14", "housing_at_fpa") not in keys
    for x in housing_run["rows"]:
        if x["config"] == "tchousing14":
            assert x["same_coefficients"] is None
            continue
        assert x["same_coefficients"] == (x["config"] != "drift14" or
                                          x["calibration"] == "housing_at_fpa"), x["config"]
        if x["same_coefficients"] and x["calibration"] == "over_housing":
            twin = _row(housing_run, x["config"], "housing_at_fpa", x["variant"])
            assert x["worst_fpn_mK"] == twin["worst_fpn_mK"]


def test_tc_housing_follows_the_housing(housing_run: dict) -> None:
    # Calibrated over FPA x housing (-5/0/5 K), the housing-aware offset keeps the pattern
    # near its level at housing = FPA at every offset, where tc_offset's grows past 20 NETD.
    r = housing_run
    o = np.asarray(r["offset_K"])
    th = np.asarray(_row(r, "tchousing14", "over_housing")["worst_fpn_mK"])
    tc = np.asarray(_row(r, "tcoffset14", "over_housing")["worst_fpn_mK"])
    assert th.max() < r["netd_mK"], th
    assert (th[o != 0] < tc[o != 0] / 20).all(), (th, tc)


def test_the_residual_grows_with_the_housing_offset(housing_run: dict) -> None:
    r = housing_run
    o = np.asarray(r["offset_K"])
    for cfg in ("tcoffset14", "typical14", "tcgain14"):
        f = np.asarray(_row(r, cfg, "housing_at_fpa")["worst_fpn_mK"])
        # monotonic in |offset| on either side of 0, and 5 K away far above the NETD
        assert (np.diff(f[o >= 0]) > 0).all() and (np.diff(f[o <= 0]) < 0).all()
        assert f[o == 5.0][0] > 20 * r["netd_mK"] and f[o == 0.0][0] < r["netd_mK"]
    # an FFC at the state measured flattens whatever the housing; one at housing = FPA
    # does not survive the housing moving
    here = _row(r, "ffc14", "housing_at_fpa", "FFC at this housing")["worst_fpn_mK"]
    then = _row(r, "ffc14", "housing_at_fpa", "FFC at housing = FPA")["worst_fpn_mK"]
    assert max(here) < r["netd_mK"] and max(then) > 20 * r["netd_mK"]


def test_the_residual_against_a_float_two_point_by_hand(housing_run: dict) -> None:
    """typical14 at FPA 298 K, housing 0 and +5 K from it: a per-pixel numpy.polyfit line
    over the plan's scenes at the reference point (the housing at the FPA), applied in
    float to the model's frames, gives the study's fixed pattern in mK."""
    from irnuc import model
    from irnuc.nuc_fixed import load_pipeline

    cfg = load_pipeline("typical14")
    good = np.ones((ROWS, COLS), bool)
    for i, j in housing_run["bad_pixels"]:
        good[i, j] = False

    def frames(fpa: float, cam: float, scenes: list[float]) -> np.ndarray:
        c = model.load_preset("default", {"fpa.active_rows": ROWS, "fpa.active_cols": COLS,
                                          "environment.T_substrate": fpa,
                                          "environment.T_cam": cam})
        return model.simulate(c, scenes, seed=3, outputs=["codes"]).codes.astype(np.float64)

    cal = frames(298.0, 298.0, [290.0, 330.0, 370.0])
    t = cal[:, good].mean(axis=1) * 2.0 ** (cfg.out_bits - cfg.adc_bits)
    gain = np.zeros((ROWS, COLS))
    off = np.zeros((ROWS, COLS))
    for i, j in np.argwhere(good):
        gain[i, j], off[i, j] = np.polyfit(cal[:, i, j], t, 1)
    row = _row(housing_run, "typical14", "housing_at_fpa")
    for dh in (0.0, 5.0):
        k = housing_run["offset_K"].index(dh)
        y = gain * frames(298.0, 298.0 + dh, [330.0, 329.5, 330.5]) + off
        resp = y[2][good].mean() - y[1][good].mean()
        hand = 1e3 * y[0][good].std() / resp
        study = row["per_offset"][k]["per_fpa"][0]["fpn_mK"][0]
        # the study's is the 14-bit method (coefficients and output rounded): a few % at
        # offset 0 (about a code of pattern), nothing at 5 K (2 K of pattern)
        assert study == pytest.approx(hand, rel=0.1 if dh == 0.0 else 1e-3), dh


def test_blind_pixels_couple_globally_not_per_pixel(housing_run: dict) -> None:
    b = housing_run["blind_pixels"]
    # the ring views the whole housing, an image pixel the part its optics leave
    # (docs/model.md): 1/(1 - tau sin^2(theta) <cos^4>) = 1.24 on the default preset
    assert b["housing"]["blind_to_active"] == pytest.approx(1.24, abs=0.02)
    # blind_drift's own fit (the mean image against the mean ring over drift_cam) is the
    # slope ratio measured here per pixel, a second derivation
    assert b["drift14_fitted_coupling"]["over_housing"] == pytest.approx(
        b["global_coupling"], rel=0.01)
    assert b["drift14_fitted_coupling"]["housing_at_fpa"] == 1.0
    res = b["residual"][0]
    far = b["offset_K"].index(5.0)
    # one global k leaves the pattern of the coupling's spread, k = 1 a level error, a
    # per-pixel coupling neither
    assert res["global_mK"][far] > 5 * housing_run["netd_mK"]
    assert abs(res["k1_level_mK"][far]) > 1000
    assert res["per_pixel_mK"][far] < housing_run["netd_mK"]
    assert abs(res["per_pixel_level_mK"][far]) < housing_run["netd_mK"]
    assert b["per_pixel_coupling"]["radial_fraction"] > 0.5
    # the study's drift14 rows show the same: k fitted, the level; k = 1, the pattern
    d1 = _row(housing_run, "drift14", "housing_at_fpa")
    d2 = _row(housing_run, "drift14", "over_housing")
    assert d2["worst_level_error_mK"][-1] < 0.05 * d1["worst_level_error_mK"][-1]
    assert d1["worst_fpn_mK"][-1] < 0.2 * d2["worst_fpn_mK"][-1]


@pytest.mark.parametrize(("args", "fragment"), [
    (["study", "housin"], "did you mean 'housing'"),
    (["study", "housing", "--set", "environment.T_cam=305"],
     "--set environment.T_cam: the study sets it"),
    (["study", "housing", "--set", "adc.bits=12"], "12-bit ADC"),
    (["study", "housing", "--sensor", "nosuch"], "--sensor 'nosuch'"),
    (["study", "housing", "--set", "fpa.active_rowz=4"], "fpa.active_rowz"),
])
def test_bad_input_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                               args: list[str], fragment: str) -> None:
    assert main([*args, "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and fragment in err, err
    assert not (tmp_path / "x" / "housing.json").exists()


def test_a_bad_sensor_file_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "sensor.toml"
    bad.write_text("[fpa]\nactive_rows = -3\n")
    assert main(["study", "housing", "--sensor", str(bad), "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "active_rows" in err and str(bad) in err, err


def test_undefined_values_are_null_in_the_json() -> None:
    # a responsivity <= 0 (a ring that ignores the housing, a dead image) gives inf mK
    from irnuc.reports.studies.housing import _json_safe

    assert _json_safe({"a": [1.0, float("inf")], "b": (float("nan"), 2), "c": "x"}) == {
        "a": [1.0, None], "b": [None, 2], "c": "x"}


def test_the_api_refuses_a_grid_without_the_reference() -> None:
    from irnuc.reports.studies import housing

    with pytest.raises(ValueError, match="must include 0 K"):
        housing.run(quick=True, offsets=(-5.0, 5.0))
