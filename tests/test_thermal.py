"""The camera's thermal world: the network driven by the ambient (against solve_ivp and
the closed form of the warm-up), the shipped scenarios, the housing sensor, a lens away
from the housing, and the per-frame fields of frame files (issue 35)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from irnuc import model
from irnuc.cli import main
from irnuc.cli._files import load_frames
from irnuc.model.fpa_sensor import FRAME_FIELDS, HousingSensor
from irnuc.model.sequence import (
    load_sequence,
    scenario_names,
    sequence_from_dict,
    simulate_sequence,
)
from irnuc.model.thermal import ThermalNetwork

ISSUE_TOML = """\
[sequence]
frame_rate = 30.0
duration = 1200.0
[sequence.ambient]
profile = "constant"
value = 298.0
[sequence.network]          # the housing follows the ambient, the FPA follows the housing
start = 298.0               # K, every node at power-on
housing_tau = 900.0         # s
fpa_tau = 120.0             # s
housing_self_heating = 3.0  # K above the ambient once settled
fpa_self_heating = 6.0      # K above the housing once settled
[sequence.scene]
profile = "constant"
value = 300.0
"""
SMALL = ["--set", "fpa.active_rows=6", "--set", "fpa.active_cols=8"]


def test_network_against_solve_ivp():
    """Housing, FPA, lens and shutter nodes for an ambient that ramps, holds and steps
    (linear between the frames): the exact discretization against solve_ivp (DOP853,
    rtol 1e-11) of the same linear system with the ambient interpolated linearly."""
    from scipy.integrate import solve_ivp

    net = ThermalNetwork(housing_tau=300.0, fpa_tau=40.0, start=290.0, housing_self_heating=2.5,
                         fpa_self_heating=4.0, lens_tau=150.0, shutter_tau=60.0)
    t = np.arange(0.0, 1200.0, 4.0)
    amb = np.interp(t, [0, 300, 600, 604, 1200], [280.0, 310.0, 310.0, 295.0, 300.0])
    got = net.solve(t, amb)

    def f(tt, x):
        a = np.interp(tt, t, amb)
        h, fp, ln, sh = x
        return [(a + 2.5 - h) / 300.0, (h + 4.0 - fp) / 40.0, (h - ln) / 150.0, (h - sh) / 60.0]

    ref = solve_ivp(f, (0.0, t[-1]), [290.0] * 4, method="DOP853", t_eval=t, rtol=1e-11,
                    atol=1e-9, max_step=2.0)
    for i, k in enumerate(("housing", "fpa", "lens", "shutter")):
        np.testing.assert_allclose(got[k], ref.y[i], atol=1e-6, err_msg=k)
    # an explicit housing replaces the housing node; lens and shutter follow it
    h = 300.0 + 0.01 * t
    got2 = net.solve(t, amb, housing=h)
    np.testing.assert_array_equal(got2["housing"], h)
    # the lens behind the housing's ramp: h - r tau + (l0 - h0 + r tau) exp(-t / tau)
    lens = h - 1.5 + (290.0 - 300.0 + 1.5) * np.exp(-t / 150.0)
    np.testing.assert_allclose(got2["lens"], lens, atol=1e-9)


def _warmup(t, a=298.0, H=3.0, F=6.0, th=900.0, tf=120.0):
    """The closed form of the issue's warm-up (every node at a at t = 0)."""
    h = a + H * (1 - np.exp(-t / th))
    f = (a + H + F - F * np.exp(-t / tf)
         - H * (th * np.exp(-t / th) - tf * np.exp(-t / tf)) / (th - tf))
    return h, f


def test_the_issue_example_works_as_written_and_stores_every_node(tmp_path):
    toml = tmp_path / "warmup.toml"
    toml.write_text(ISSUE_TOML)
    out = tmp_path / "f"
    assert main(["frames", "-q", "--sequence", str(toml), *SMALL, "--out", str(out)]) == 0
    d = load_frames(str(out))
    n = 36000
    assert d["codes"].shape[0] == n and d["frame_rate"] == 30.0
    t = np.arange(n) / 30.0
    h, f = _warmup(t)
    np.testing.assert_allclose(d["T_cam_K"], h, atol=1e-9)
    np.testing.assert_allclose(d["fpa_K"], f, atol=1e-9)
    np.testing.assert_array_equal(d["ambient_K"], np.full(n, 298.0))
    np.testing.assert_array_equal(d["lens_K"], d["T_cam_K"])  # no lens_tau: at the housing
    hs = d["housing_sensor"]
    assert isinstance(hs, HousingSensor) and hs == HousingSensor()
    np.testing.assert_array_equal(d["housing_reading"], np.rint((h - hs.zero_K) / hs.lsb_K))
    assert not d["housing_synthesized"] and not d["fields_synthesized"]
    # the camera's self-heating shows in the raw codes: the FPA warms 8.1 K over the run
    assert abs(float(d["codes"][-1].mean()) - float(d["codes"][0].mean())) > 100


def test_shipped_scenarios_load_by_name_and_run(tmp_path, capsys):
    assert scenario_names() == ["ambient_ramp", "fpa_ramp", "indoor_to_outdoor",
                                "power_on_warmup"]
    from irnuc.cli.frames import SCENARIOS

    assert tuple(scenario_names()) == SCENARIOS
    ramp = load_sequence("ambient_ramp").schedule()
    assert ramp.ambient_K[0] == pytest.approx(263.15) and ramp.ambient_K[-1] > 322.0
    assert np.all(np.diff(ramp.T_cam_K) > 0) and not np.array_equal(ramp.lens_K, ramp.T_cam_K)
    step = load_sequence("indoor_to_outdoor").schedule()
    assert step.T_cam_K[-1] < step.T_cam_K[0] - 15  # carried out into the cold
    fpa = load_sequence("fpa_ramp").schedule()
    assert fpa.T_cam_K[-1] > fpa.T_cam_K[0]  # the housing follows the FPA's ramp
    out = tmp_path / "w"
    assert main(["frames", "-q", "--sequence", "power_on_warmup", *SMALL, "--out",
                 str(out)]) == 0
    d = load_frames(str(out))
    assert d["codes"].shape[0] == 1200 and d["frame_rate"] == 1.0
    assert d["housing_sensor"].lag_s == 5.0
    # a name is never a path; an unknown name is one line with the nearest
    for bad in ("power_on_warmpu", "../power_on_warmup"):
        rc = main(["frames", "--sequence", bad, "--out", str(tmp_path / "x")])
        err = capsys.readouterr().err
        assert rc == 2 and "Traceback" not in err
    assert "did you mean 'power_on_warmup'" in err or "no such file" in err


def test_housing_sensor_lag_noise_and_clamped_readings_are_told():
    """A sensor on the lens with a 10 s lag behind a 1 K/min ramp reads tau r = 0.167 K
    low once settled (closed form); noise is seeded per frame; readings outside its range
    are clamped and counted in one warning."""
    seq = sequence_from_dict({"sequence": {
        "frame_rate": 2.0, "duration": 120.0, "fpa": 300.0, "scene": 300.0,
        "housing": {"profile": "ramp", "start": 300.0, "rate": 1.0},
        "housing_sensor": {"lag_s": 10.0, "lsb_K": 0.001, "zero_K": 250.0, "bits": 16}}})
    sched = seq.schedule()
    f = sched.fields(seq.fpa_sensor, 1, seq.housing_sensor)
    read = seq.housing_sensor.temperature(f["housing_reading"])
    assert read[-1] == pytest.approx(sched.T_cam_K[-1] - 10.0 / 60.0, abs=2e-3)
    noisy = HousingSensor(noise_K=0.05, lsb_K=0.001, zero_K=250.0, bits=16)
    a = noisy.read(np.full(2000, 300.0), seed=3)
    assert noisy.temperature(a).std() == pytest.approx(0.05, rel=0.1)
    np.testing.assert_array_equal(a[1000:], noisy.read(np.full(1000, 300.0), seed=3,
                                                       first_frame=1000))
    narrow = HousingSensor(bits=8, lsb_K=0.1, zero_K=290.0)  # 290 .. 315.5 K
    with pytest.warns(RuntimeWarning, match=r"housing: 3 of 5 reading\(s\) clamped"):
        narrow.read(np.array([280.0, 300.0, 320.0, 330.0, 301.0]), warn="housing")


def test_a_lens_away_from_the_housing_changes_what_each_pixel_absorbs():
    """A lens 10 K warmer than the housing adds eps A pi (1 - tau) sin^2(theta) cos^4 (the
    lens's emission over the optical cone) times L(T_lens) - L(T_cam) to every image pixel
    and nothing to the shielded ones (the optics' closed forms and the band radiance,
    independent of the pipeline's stages)."""
    cfg = model.load_preset("default", {"fpa.active_rows": 6, "fpa.active_cols": 8,
                                        "fpa.defects": {}})
    base = {"frame_rate": 30.0, "duration": 2 / 30, "fpa": 300.0, "housing": 300.0,
            "scene": 300.0, "thermal": "steady"}
    same = simulate_sequence(cfg, sequence_from_dict({"sequence": base}), outputs=["power"])
    warm = {**base, "ambient": 300.0, "housing": 300.0,
            "network": {"housing_tau": 1.0, "fpa_tau": 1.0, "lens_tau": 1e-9, "start": 300.0}}
    # a lens node at the housing (300 K) but its own: identical power
    lens = simulate_sequence(cfg, sequence_from_dict({"sequence": warm}), outputs=["power"])
    np.testing.assert_array_equal(lens.outputs["power"], same.outputs["power"])
    from irnuc.model.stages import stage_lens_view  # noqa: F401  (the stage under test)

    seq = sequence_from_dict({"sequence": {**base, "ambient": 300.0}})
    from irnuc.model.sequence import prepare

    run = prepare(cfg, seq)
    env = {**run.schedule.env(), "T_lens": np.full(2, 310.0)}
    q = run.pipe.run(run.schedule.scene_K, ["Q", "cos4"], env=env)
    o, f = cfg["optics"], cfg["fpa"]
    sin2 = (1.0 / (2.0 * o["f_number"])) ** 2
    dL = float(model.band_radiance([310.0])[0] - model.band_radiance([300.0])[0])
    expect = f["absorptance"] * f["pitch"] ** 2 * f["fill_factor"] * math.pi * \
        (1 - o["transmission"]) * sin2 * q["cos4"] * dL
    act = run.pipe.layout.active_slice
    dQ = q["Q"][0] - same.outputs["power"][0]
    np.testing.assert_allclose(dQ[act], expect[act], rtol=1e-9)
    blind = run.pipe.layout.kind_map() != 0  # the rings: shielded in the default preset
    assert np.abs(dQ[blind]).max() == 0.0


def test_plain_frames_and_format_2_files_carry_the_housing_fields(tmp_path):
    out = tmp_path / "p"
    assert main(["frames", "-q", *SMALL, "--temps", "300,310", "--set",
                 "environment.T_cam=305", "--out", str(out)]) == 0
    d = load_frames(str(out))
    for k in FRAME_FIELDS:
        assert d[k].shape == (2,), k
    np.testing.assert_array_equal(d["ambient_K"], [305.0, 305.0])
    np.testing.assert_array_equal(d["housing_reading"],
                                  d["housing_sensor"].read(np.array([305.0, 305.0])))
    assert not d["housing_synthesized"]
    # a file of format 2 (no ambient, lens, shutter temperature, no housing reading)
    arrays = dict(np.load(out / "frames.npz"))
    for k in ("ambient_K", "lens_K", "shutter_K", "housing_reading"):
        arrays.pop(k)
    for k in [k for k in arrays if k.startswith("housing_sensor_")]:
        arrays.pop(k)
    arrays["format_version"] = np.int64(2)
    old = tmp_path / "old.npz"
    np.savez(old, **arrays)
    d2 = load_frames(str(old))
    assert d2["housing_synthesized"]
    np.testing.assert_array_equal(d2["lens_K"], [305.0, 305.0])


def test_the_fpa_sensor_s_clamp_is_a_warning_with_the_count(tmp_path, capsys):
    seq = {"sequence": {"frame_rate": 30.0, "duration": 0.2, "fpa": 300.0, "housing": 300.0,
                        "scene": 300.0, "fpa_sensor": {"bits": 8, "zero_K": 223.15}}}
    with pytest.warns(RuntimeWarning, match=r"the FPA temperature sensor: 6 of 6 reading"):
        sequence_from_dict(seq).schedule().fields(sequence_from_dict(seq).fpa_sensor, 0)
    toml = tmp_path / "s.toml"
    toml.write_text('[sequence]\nframe_rate = 30.0\nduration = 0.2\nfpa = 300.0\n'
                    'housing = 300.0\nscene = 300.0\n[sequence.fpa_sensor]\nbits = 8\n')
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert main(["frames", "-q", "--sequence", str(toml), *SMALL, "--out",
                     str(tmp_path / "f")]) == 0
    err = capsys.readouterr().err
    assert "warning: the FPA temperature sensor: 6 of 6 reading(s) clamped" in err
