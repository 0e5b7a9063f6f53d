"""The correction-method studies on a small array: their JSON, their figures, and what
the physics says each must show."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from irnuc.cli import main
from irnuc.nuc_fixed import load_pipeline
from irnuc.reports.studies import camera_temperature, ffc_interval, method_bits, methods_range
from irnuc.reports.studies.drift_common import StudySensor, memory_bits
from irnuc.reports.studies.ffc_interval import longest_period

TINY = StudySensor(rows=12, cols=16)
PNG = b"\x89PNG\r\n\x1a\n"


def _jsonable(result: dict) -> dict:
    return json.loads(json.dumps(result))


def test_camera_temperature_blind_drift_follows_the_housing() -> None:
    r = camera_temperature.run(quick=True, sensor=TINY)
    assert _jsonable(r)["study"] == "camera_temperature"
    prof = r["profiles"]
    assert set(prof) == {"rising", "falling", "constant_low", "constant_mid", "constant_high"}
    assert prof["rising"]["T_cam_K"] == prof["falling"]["T_cam_K"][::-1]
    for name in ("rising", "falling", "constant_high"):
        two, drift = prof[name]["two_point"], prof[name]["two_point+blind_drift"]
        # The housing 20 K warm moves the image by tens of K of scene; the blind pixels
        # take out all but a few percent of it.
        assert two["worst_level_error_mK"] > 10_000
        assert drift["worst_level_error_mK"] < 0.05 * two["worst_level_error_mK"]
        assert drift["worst_fpn_mK"] < two["worst_fpn_mK"]
    # At the calibration's housing temperature both are the calibrated camera.
    low = prof["constant_low"]
    assert low["two_point"]["level_error_mK"] == pytest.approx(
        low["two_point+blind_drift"]["level_error_mK"], abs=5.0)
    assert 0.5 < r["drift_coupling"] < 1.2 and r["netd_mK"] > 0
    assert camera_temperature.figure(r).startswith(PNG)


def test_longest_period_interpolates() -> None:
    t = np.array([0.0, 1.0, 2.0, 4.0])
    assert longest_period(t, np.array([10.0, 15.0, 25.0, 40.0]), 20.0) == pytest.approx(1.5)
    assert longest_period(t, np.array([10.0, 11.0, 12.0, 13.0]), 20.0) is None
    assert longest_period(t, np.array([30.0, 31.0, 32.0, 33.0]), 20.0) == 0.0


def test_ffc_interval() -> None:
    r = ffc_interval.run(quick=True, sensor=TINY, max_change_K=3.0)
    curves = r["fpn_mK"]
    assert set(curves) == {"two_point+ffc", "tc_offset+ffc", "two_point (no FFC)"}
    two, tc = np.asarray(curves["two_point+ffc"]), np.asarray(curves["tc_offset+ffc"])
    # Right after the FFC both are flat to about the NETD; the FPA drift then undoes the
    # two-point correction, which tc_offset follows.
    assert two[0] < 2 * r["netd_mK"] and two[-1] > 5 * r["netd_mK"]
    assert (np.diff(two) > 0).all() and tc.max() < 2 * r["netd_mK"]
    assert (two <= np.asarray(curves["two_point (no FFC)"]) + 1e-9).all()
    slow, fast = r["ramps"]["0.5 K/min"], r["ramps"]["2 K/min"]
    assert slow["longest_period_min"]["two_point+ffc"] == pytest.approx(
        4 * fast["longest_period_min"]["two_point+ffc"])
    assert ffc_interval.figure(r).startswith(PNG)


def test_methods_range_and_memory() -> None:
    names = ("onepoint14", "typical14", "tcgain14", "table14", "drift14")
    r = methods_range.run(quick=True, sensor=TINY, names=names)
    m = r["methods"]
    # Temperature compensation wins over 20 K of FPA temperature.
    for temp in ("tcgain14", "table14"):
        for other in ("onepoint14", "typical14", "drift14"):
            assert m[temp]["worst_fpn_mK"] < 0.1 * m[other]["worst_fpn_mK"]
    # Memory, counted independently from the documented layouts (docs/datapath.md).
    assert (m["typical14"]["calibration_bits"], m["typical14"]["read_bits_per_frame"]) == (33, 33)
    assert m["onepoint14"]["calibration_bits"] == 12 + 4 + 1
    assert (m["table14"]["calibration_bits"], m["table14"]["read_bits_per_frame"]) == (99, 66)
    assert m["tcgain14"]["calibration_bits"] == 33 + (16 + 16) + (16 + 16)
    assert m["typical14"]["bandwidth_MB_per_s_vga60"] == pytest.approx(33 * 640 * 480 * 60 / 8e6)
    assert methods_range.figure(r).startswith(PNG)


def test_memory_bits_of_ffc() -> None:
    mb = memory_bits(load_pipeline("ffc14"))
    assert mb == {"calibration_bits": 33, "runtime_bits": 16 + 14 + 3,
                  "read_bits_per_frame": 33 + 16}


def test_method_bits_falls_to_the_float_floor() -> None:
    r = method_bits.run(quick=True, sensor=TINY, frac_bits=(3, 6, 12), names=("table14",))
    rows = r["methods"]["table14"]["rows"]
    mk = [row["worst_fpn_mK"] for row in rows]
    assert mk[0] > mk[1] > mk[2]
    assert mk[2] == pytest.approx(r["methods"]["table14"]["float_fpn_mK"], rel=0.3)
    assert all(row["valid"] for row in rows)
    assert method_bits.figure(r).startswith(PNG)


def test_residuals_in_mK_through_the_local_responsivity_and_the_level_error() -> None:
    """The one conversion (metrics.residuals_mK): synthetic corrected frames with a known
    local slope, pattern and level offset give them back; the temperature scale is linear
    in in-band radiance between the calibration scenes (scipy quad of Planck's law, an
    independent radiance)."""
    import math

    from scipy.integrate import quad

    from irnuc.reports.studies.metrics import TemperatureScale, residuals_mK, slope_scenes

    band = (8e-6, 14e-6)
    c1, c2 = 1.191042972e-16, 1.438776877e-2

    def L(T):  # W m^-2 sr^-1, Planck's law integrated over the band
        return quad(lambda lam: c1 / lam**5 / math.expm1(c2 / (lam * T)), *band,
                    epsabs=0, epsrel=1e-12)[0]

    sc = TemperatureScale([1000.0, 3000.0, 7000.0], [290.0, 330.0, 370.0], band)
    assert sc.level(330.0) == pytest.approx(3000.0, rel=1e-12)
    lev = 1000.0 + 2000.0 * (L(310.0) - L(290.0)) / (L(330.0) - L(290.0))
    assert sc.level(310.0) == pytest.approx(lev, rel=1e-9)
    assert sc.temperature(sc.level(351.3)) == pytest.approx(351.3, abs=1e-8)
    rng = np.random.default_rng(1)
    pattern = rng.normal(0.0, 2.0, (8, 10))
    good = np.ones((8, 10), bool)
    good[0, 0] = False
    scenes = [300.0, 360.0]
    slope = {300.0: 45.0, 360.0: 61.0}  # output codes per K, where each scene is
    frames = []
    for T in slope_scenes(scenes):
        s0 = min(scenes, key=lambda x: abs(x - T))
        frames.append(sc.level(s0) + 7.0 + slope[s0] * (T - s0) + pattern)
    res = residuals_mK(np.stack(frames), good, scenes, sc)
    for r, s0 in zip(res, scenes, strict=True):
        assert r["responsivity_codes_per_K"] == pytest.approx(slope[s0], rel=1e-9)
        assert r["fpn_mK"] == pytest.approx(1e3 * pattern[good].std() / slope[s0], rel=1e-9)
        assert r["level_lsb"] == pytest.approx(7.0 + pattern[good].mean(), rel=1e-9)
        read = sc.temperature(sc.level(s0) + 7.0 + pattern[good].mean())
        assert r["level_error_mK"] == pytest.approx(1e3 * (read - s0), rel=1e-9)


def test_study_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "s"
    assert main(["study", "ffc_interval", "--quick", "--set", "fpa.active_rows=12",
                 "--set", "fpa.active_cols=16", "--out", str(out), "-q"]) == 0
    data = json.loads((out / "ffc_interval.json").read_text())
    assert data["sensor"]["rows"] == 12 and data["study"] == "ffc_interval"
    assert (out / "ffc_interval.png").read_bytes().startswith(PNG)
    for args, match in ((["study", "ffc_intervl"], "did you mean 'ffc_interval'"),
                        (["study", "method_bits", "--set", "environment.T_cam=300"],
                         "--set environment.T_cam: the study sets it"),
                        (["study", "method_bits", "--set", "adc.bits=12"], "12-bit ADC"),
                        (["study", "method_bits", "--seed", "-2"], "--seed -2")):
        assert main([*args, "--out", str(tmp_path / "x")]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and match in err, err
