"""Noise metrics: 3D noise recovered from a synthetic cube, responsivity against the
model's own finite difference, NETD measured on a sequence against the closed form, and
``irnuc noise``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from irnuc import model
from irnuc.cli import main
from irnuc.model import noise_metrics as nm
from irnuc.model.sequence import sequence_from_dict, simulate_sequence

SIGMAS = {"tvh": 1.5, "tv": 0.4, "th": 0.6, "t": 2.0, "vh": 5.0, "v": 3.0, "h": 1.0}


def test_3d_noise_recovers_known_components_of_a_synthetic_cube():
    cube = nm.synthetic_cube((60, 48, 64), SIGMAS, seed=5)
    n3 = nm.noise_3d(cube, chunk=7)
    for name, sigma in SIGMAS.items():
        var, se = n3.variance[name], n3.variance_se[name]
        # The estimate is unbiased with the stated standard error: 4 of them at most.
        assert abs(var - sigma**2) <= 4.0 * se, (name, var, sigma**2, se)
        # and the error is small enough to mean something (the v, h, t components have
        # only 47..63 draws, so their relative error is ~20 %)
        assert se < 0.35 * sigma**2, name
    assert n3.mean == pytest.approx(1000.0, abs=6.0)


def test_3d_noise_standard_errors_match_the_spread_over_seeds():
    """The stated standard error of each variance is the spread of the estimates over
    independent cubes (within the sampling error of 40 repeats)."""
    est = {k: [] for k in SIGMAS}
    ses = {k: [] for k in SIGMAS}
    for seed in range(40):
        n3 = nm.noise_3d(nm.synthetic_cube((12, 10, 14), SIGMAS, seed=seed))
        for k in SIGMAS:
            est[k].append(n3.variance[k])
            ses[k].append(n3.variance_se[k])
    for k, sigma in SIGMAS.items():
        spread = float(np.std(est[k], ddof=1))
        assert float(np.mean(est[k])) == pytest.approx(sigma**2, abs=3 * spread / math.sqrt(40))
        assert float(np.mean(ses[k])) == pytest.approx(spread, rel=0.45), k


def test_the_naive_directional_averages_are_biased_where_the_anova_is_not():
    """Frame-to-frame noise 0 under large random noise: the frame means still scatter by
    sigma_tvh / sqrt(V H); the plain estimate reports that, the ANOVA removes it."""
    cube = nm.synthetic_cube((200, 8, 8), {"tvh": 8.0}, seed=2)
    n3 = nm.noise_3d(cube)
    assert n3.naive["t"] == pytest.approx(8.0 / 8.0, rel=0.15)  # sigma_tvh / sqrt(64)
    assert abs(n3.variance["t"]) <= 4 * n3.variance_se["t"]
    assert n3.sigma["t"] < 0.5 * n3.naive["t"]


def test_band_radiance_derivative_matches_the_radiance_series():
    for T in (250.0, 300.0, 400.0):
        h = 1e-3
        fd = (model.band_radiance([T + h])[0] - model.band_radiance([T - h])[0]) / (2 * h)
        assert nm.band_radiance_derivative(T, (8e-6, 14e-6)) == pytest.approx(fd, rel=1e-8)


def _cfg(**over):
    return model.load_preset("default", {"fpa.active_rows": 24, "fpa.active_cols": 32,
                                         "fpa.defects": {}, **over})


def test_closed_form_responsivity_is_the_model_s_derivative():
    """Per pixel, against the central difference of the model's own integrator voltage
    (no ADC rounding, no noise): a second derivation of the same chain."""
    for over in ({}, {"environment.T_substrate": 296.0, "environment.T_cam": 303.0},
                 {"bolometer.variant": "paper"}):
        cfg = _cfg(**over)
        rsp = nm.responsivity(cfg, 310.0, seed=2)
        h = 0.01
        v = model.simulate(cfg, [310.0 - h, 310.0 + h], seed=2, outputs=["voltage"])
        a = cfg["adc"]
        per_volt = 2 ** a["bits"] / (a["v_high"] - a["v_low"])
        fd = (v.outputs["voltage"][1] - v.outputs["voltage"][0]) / (2 * h) * per_volt
        np.testing.assert_allclose(rsp.codes_per_K, fd, rtol=1e-6)


def _noisy_sequence(scene, **over):
    cfg = _cfg(**{"noise.enabled": True, **over})
    seq = sequence_from_dict({"sequence": {"frame_rate": 30.0, "duration": 8.0, "fpa": 300.0,
                                           "housing": 300.0, "scene": scene}})
    return cfg, simulate_sequence(cfg, seq, seed=4)


def test_netd_measured_on_a_sequence_agrees_with_the_closed_form():
    """A scene swinging +-1 K around 300 K: noise and responsivity both measured on the
    frames (every source on: Johnson, 1/f, thermal fluctuation, the skimming references',
    readout) agree with the closed form within three standard errors of the measurement
    (about 0.2 %); the closed form's own +- is the pixels' spread, tens of times wider."""
    cfg, fr = _noisy_sequence({"profile": "sine", "mean": 300.0, "amplitude": 1.0,
                               "period": 2.0})
    f = fr.fields
    fit = nm.fit_frames(fr.codes, f["scene_K"], f["fpa_K"], f["T_cam_K"], time_s=f["time_s"])
    good = fr.defect_kind == 0
    measured = nm.measured_netd(fit, good)
    closed = nm.netd(cfg, 300.0, seed=4)
    assert measured.uncertainty_K < 0.003 * measured.netd_K
    assert abs(measured.netd_K - closed.netd_K) <= 3 * measured.uncertainty_K
    assert closed.uncertainty_K > 10 * measured.uncertainty_K
    assert 0.015 < closed.netd_K < 0.050  # an uncooled VOx camera at F/1: tens of mK
    assert closed.conditions["f_number"] == 1.0 and closed.conditions["frame_rate"] == 30.0
    # and it is not the agreement of two zeros: every source moves both sides alike
    for off in ({"noise.johnson": False}, {"noise.thermal_fluctuation": False}):
        cfg2, fr2 = _noisy_sequence({"profile": "sine", "mean": 300.0, "amplitude": 1.0,
                                     "period": 2.0}, **off)
        f2 = fr2.fields
        m2 = nm.measured_netd(nm.fit_frames(fr2.codes, f2["scene_K"], f2["fpa_K"],
                                            f2["T_cam_K"], time_s=f2["time_s"]), good)
        c2 = nm.netd(cfg2, 300.0, seed=4)
        assert c2.netd_K < 0.95 * closed.netd_K, off
        assert abs(m2.netd_K - c2.netd_K) <= 3 * m2.uncertainty_K, off


def test_a_constant_scene_measures_noise_with_the_closed_form_responsivity():
    cfg, fr = _noisy_sequence(300.0)
    f = fr.fields
    fit = nm.fit_frames(fr.codes, f["scene_K"], f["fpa_K"], f["T_cam_K"], time_s=f["time_s"])
    assert fit.responsivity is None and fit.regressors == ["1"]
    closed = nm.netd(cfg, 300.0, seed=4)
    m = nm.measured_netd(fit, fr.defect_kind == 0, closed.responsivity_codes_per_K)
    assert m.noise_codes == pytest.approx(closed.noise_codes, rel=0.01)
    with pytest.raises(model.ConfigError, match="responsivity cannot be measured"):
        nm.measured_netd(fit, fr.defect_kind == 0)


def test_without_temporal_noise_the_closed_form_says_it_is_the_adc_s():
    c = nm.netd(_cfg(), 300.0)
    lsb_codes = 1.0 / math.sqrt(12.0)
    assert c.noise_codes == pytest.approx(lsb_codes, rel=1e-12) and "rounding" in c.notes


def test_noise_command_prints_and_writes_the_figures(tmp_path, capsys):
    toml = tmp_path / "s.toml"
    toml.write_text('[sequence]\nframe_rate = 30.0\nduration = 4.0\nfpa = 300.0\n'
                    'housing = 300.0\n[sequence.scene]\nprofile = "sine"\nmean = 300.0\n'
                    'amplitude = 1.0\nperiod = 2.0\n[sequence.shutter]\nevery = 2.0\nframes = 2\n')
    frames = tmp_path / "f"
    assert main(["frames", "-q", "--sequence", str(toml), "--set", "fpa.active_rows=16",
                 "--set", "fpa.active_cols=20", "--set", "noise.enabled=true", "--out",
                 str(frames)]) == 0
    out = tmp_path / "n"
    assert main(["noise", "--frames", str(frames), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "NETD measured" in text and "NETD closed form" in text and "sigma_tvh" in text
    res = json.loads((out / "noise.json").read_text())
    assert set(res["noise_3d"]["codes"]) == set(nm.COMPONENTS)
    assert res["agreement"]["judged"] and res["agreement"]["within_3_sigma"]
    assert res["frames_used"] == 120 - 4 - 2 * res["settle_frames"]
    assert (out / "noise.png").stat().st_size > 10_000
    assert len(res["responsivity_per_frame_codes_per_K"]["closed_form"]) == res["frames_used"]


@pytest.mark.parametrize(("extra", "fragment"), [
    (["--range", "5"], "--range '5': expected START:STOP"),
    (["--range", "0:2"], "--range '0:2': 2 frame(s)"),
    (["--settle", "-1"], "--settle -1"),
])
def test_noise_command_bad_flags(tmp_path, capsys, extra, fragment):
    frames = tmp_path / "f"
    assert main(["frames", "-q", "--set", "fpa.active_rows=6", "--set", "fpa.active_cols=8",
                 "--temps", "300,301,302,303", "--out", str(frames)]) == 0
    assert main(["noise", "--frames", str(frames), *extra, "--out", str(tmp_path / "n")]) == 2
    err = capsys.readouterr().err
    assert fragment in err and len(err.strip().splitlines()) == 1


def test_noise_free_frames_are_compared_but_not_judged(tmp_path, capsys):
    """Without temporal noise the closed form is the ADC's LSB/sqrt(12) and the frames'
    rounding is deterministic: the difference is printed, no verdict (neither a pass nor
    an OUTSIDE)."""
    toml = tmp_path / "s.toml"
    toml.write_text('[sequence]\nframe_rate = 30.0\nduration = 2.0\nhousing = 300.0\n'
                    '[sequence.fpa]\nprofile = "ramp"\nstart = 300.0\nrate = 2.0\n'
                    '[sequence.scene]\nprofile = "constant"\nvalue = 300.0\n')
    frames, out = tmp_path / "f", tmp_path / "n"
    assert main(["frames", "-q", "--sequence", str(toml), "--set", "fpa.active_rows=16",
                 "--set", "fpa.active_cols=20", "--set", "noise.enabled=false", "--out",
                 str(frames)]) == 0
    assert main(["noise", "--frames", str(frames), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "not judged" in text and "OUTSIDE" not in text
    res = json.loads((out / "noise.json").read_text())
    assert res["agreement"]["judged"] is False and res["agreement"]["within_3_sigma"] is None
