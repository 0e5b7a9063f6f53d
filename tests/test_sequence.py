"""Drift sequences: the issue's example from the CLI and the API, profiles against their
formulas, bad input refused before any work, and the thermal models against each other."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from irnuc import model
from irnuc.cli import main
from irnuc.cli._files import load_frames
from irnuc.model.profiles import first_order_lag, parse_profile
from irnuc.model.sequence import load_sequence, sequence_from_dict, simulate_sequence
from irnuc.model.validate import ConfigError

#: The example of issue 18, verbatim.
ISSUE_EXAMPLE = """\
[sequence]
frame_rate = 30.0                 # Hz
duration = 60.0                   # s
[sequence.fpa]                    # substrate temperature, K
profile = "ramp"
start = 293.0
rate = 2.0                        # K/min
[sequence.housing]
profile = "constant"
value = 293.0
[sequence.scene]
profile = "constant"
value = 300.0
[sequence.shutter]
every = 10.0                      # s
frames = 4
"""

TINY = ["--set", "fpa.active_rows=8", "--set", "fpa.active_cols=10"]


def _tiny(**over):
    return model.load_preset("default", {"fpa.active_rows": 8, "fpa.active_cols": 10,
                                         "fpa.defects": {}, **over})


def _seq(**table):
    base = {"frame_rate": 30.0, "duration": 1.0, "fpa": 300.0, "housing": 300.0, "scene": 300.0}
    return sequence_from_dict({"sequence": {**base, **table}})


def _check_issue_fields(fields, n=1800):
    t = np.arange(n) / 30.0
    np.testing.assert_allclose(fields["time_s"], t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fields["fpa_K"], 293.0 + 2.0 * t / 60.0, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(fields["T_cam_K"], 293.0)
    np.testing.assert_array_equal(fields["scene_K"], 300.0)
    closed = np.flatnonzero(fields["shutter"])
    expected = [k * 300 + i for k in range(6) for i in range(4)]  # every 10 s, 4 frames
    np.testing.assert_array_equal(closed, expected)
    # the on-die sensor's default: 0.01 K per code from 223.15 K
    np.testing.assert_array_equal(fields["fpa_reading"],
                                  np.rint((fields["fpa_K"] - 223.15) / 0.01).astype(np.int64))


def test_issue_example_from_the_cli(tmp_path):
    toml = tmp_path / "drift.toml"
    toml.write_text(ISSUE_EXAMPLE)
    out = tmp_path / "f"
    assert main(["frames", "-q", "--sequence", str(toml), *TINY, "--out", str(out)]) == 0
    data = load_frames(str(out))
    assert data["codes"].shape == (1800, 8, 10) and data["frame_rate"] == 30.0
    _check_issue_fields(data)
    good = data["defect_kind"] == 0  # defective pixels (dead, stuck) do not drift
    codes = data["codes"].astype(float)[:, good].mean(axis=1)
    open_ = ~data["shutter"]
    # The offset drifts by many codes while the FPA warms by 2 K (housing and scene fixed).
    first, last = codes[open_][:20].mean(), codes[open_][-20:].mean()
    assert abs(last - first) > 200.0
    # Shutter frames: the array sees a uniform source at T_cam = 293 K instead of the
    # 300 K scene: colder, and the frame after a closing still remembers the shutter.
    assert (codes[data["shutter"]] < codes[4:300].min() - 100).all()
    assert codes[304] < codes[305] - 5
    # the reference ring follows the FPA drift of the image
    ring = data["blind_codes"].astype(float).mean(axis=1)
    assert (ring[-20:].mean() - ring[:20].mean()) / (last - first) == pytest.approx(1.0, abs=0.05)
    assert str(data["thermal"]) == "lagged"


def test_issue_example_from_the_api_gives_the_same_frames(tmp_path):
    toml = tmp_path / "drift.toml"
    toml.write_text(ISSUE_EXAMPLE)
    seq = load_sequence(toml)
    cfg = model.load_preset("default", {"fpa.active_rows": 8, "fpa.active_cols": 10})
    fr = simulate_sequence(cfg, seq, seed=0)
    _check_issue_fields(fr.fields)
    assert main(["frames", "-q", "--sequence", str(toml), *TINY, "--out",
                 str(tmp_path / "f")]) == 0
    data = load_frames(str(tmp_path / "f"))
    np.testing.assert_array_equal(fr.codes, data["codes"])
    np.testing.assert_array_equal(fr.blind_codes, data["blind_codes"])


# ---- profiles against their formulas ------------------------------------------------------

T = np.array([0.0, 5.0, 30.0, 59.0, 90.0])


@pytest.mark.parametrize(("table", "expected"), [
    ({"profile": "constant", "value": 301.5}, [301.5] * 5),
    ({"profile": "ramp", "start": 290.0, "rate": 6.0}, [290.0, 290.5, 293.0, 295.9, 299.0]),
    ({"profile": "ramp", "start": 290.0, "rate": 6.0, "delay": 10.0, "stop": 294.0},
     [290.0, 290.0, 292.0, 294.0, 294.0]),
    ({"profile": "ramp", "start": 300.0, "rate": -2.0, "stop": 299.0},
     [300.0, 300.0 - 1 / 6, 299.0, 299.0, 299.0]),
    ({"profile": "step", "before": 280.0, "after": 320.0, "at": 30.0},
     [280.0, 280.0, 320.0, 320.0, 320.0]),
    ({"profile": "sine", "mean": 300.0, "amplitude": 2.0, "period": 20.0, "phase": 90.0},
     [302.0, 300.0, 298.0, 300.0 + 2 * math.cos(2 * math.pi * 59 / 20), 298.0]),
])
def test_profiles_follow_their_formulas(table, expected):
    p = parse_profile(table, "sequence.x")
    np.testing.assert_allclose(p.values(T), expected, rtol=0, atol=1e-9)


def test_table_profile_interpolates_and_holds_its_ends(tmp_path):
    csv = tmp_path / "log.csv"
    csv.write_text("time_s,temperature_K\n# a housing log\n10, 290\n20, 300\n40,300.5\n")
    p = parse_profile({"profile": "table", "file": "log.csv"}, "sequence.housing", tmp_path)
    np.testing.assert_allclose(p.values(np.array([0.0, 10.0, 15.0, 30.0, 50.0])),
                               [290.0, 290.0, 295.0, 300.25, 300.5])


def test_fpa_lag_behind_a_ramping_housing_matches_the_closed_form():
    """tau y' = u - y with u = u0 + r t: y = u - r tau + (y0 - u0 + r tau) exp(-t/tau)."""
    t = np.linspace(0.0, 600.0, 1801)
    u0, r, tau, y0 = 295.0, 3.0 / 60.0, 120.0, 293.0
    y = first_order_lag(t, u0 + r * t, tau, y0)
    exact = u0 + r * t - r * tau + (y0 - u0 + r * tau) * np.exp(-t / tau)
    np.testing.assert_allclose(y, exact, rtol=0, atol=1e-10)
    seq = _seq(duration=600.0, frame_rate=3.0,
               housing={"profile": "ramp", "start": u0, "rate": 3.0},
               fpa={"profile": "lag", "time_constant": tau, "start": y0, "offset": 1.5})
    sched = seq.schedule()
    tt = sched.time_s
    exact = u0 + 1.5 + r * tt - r * tau + (y0 - u0 - 1.5 + r * tau) * np.exp(-tt / tau)
    np.testing.assert_allclose(sched.fpa_K, exact, rtol=0, atol=1e-10)


def test_shutter_closings_every_period_and_at_given_times():
    seq = _seq(duration=2.0, frame_rate=10.0,
               shutter={"every": 0.5, "frames": 2, "start": 0.25, "at": [1.9]})
    closed = np.flatnonzero(seq.schedule().shutter)
    # closings at 0.25, 0.75, 1.25, 1.75 s (frames 3, 8, 13, 18) and at 1.9 s (frame 19)
    np.testing.assert_array_equal(closed, [3, 4, 8, 9, 13, 14, 18, 19])


# ---- bad input: one line naming the key, before any work ---------------------------------

BAD = [
    ({"duration": -1.0}, "sequence.duration = -1 s is outside the allowed range"),
    ({"frame_rate": 0}, "sequence.frame_rate = 0 Hz"),
    ({"duration": 60.0, "fpa": {"profile": "ramp", "start": 293.0, "rate": 300.0}},
     "sequence.fpa: the ramp profile reaches"),
    ({"housing": {"profile": "sine", "mean": 300.0, "amplitude": 250.0, "period": 2.0}},
     "sequence.housing: the sine profile reaches"),
    ({"shutter": {"every": 0.1, "frames": 4}},
     "sequence.shutter.frames = 4 (0.133333 s at 30 Hz) is longer than its period "
     "sequence.shutter.every = 0.1 s"),
    ({"shutter": {"frames": 4}}, "sequence.shutter: give every (s) or at"),
    ({"fpa": {"profile": "ramp", "start": 293.0, "rate": 2.0, "slope": 1.0}},
     "sequence.fpa.slope is not a known field of profile 'ramp'"),
    ({"housing": {"profile": "lag", "time_constant": 10.0}},
     "a lag follows a temperature that is not given"),
    ({"housing": {"profile": "lag", "time_constant": 10.0, "follows": "fpa"},
      "fpa": {"profile": "lag", "time_constant": 10.0}}, "follow each other"),
    ({"fpa": {"profile": "lag", "time_constant": 10.0, "follows": "fpa"}},
     "sequence.fpa.follows = 'fpa': a lag of the fpa follows one of housing, ambient"),
    ({"network": {"housing_tau": 900.0, "fpa_tau": 120.0}},
     "sequence.ambient is required with sequence.network"),
    ({"ambient": 298.0, "network": {"housing_tau": 900.0, "fpa_tau": 120.0, "fpa_taus": 1.0}},
     "sequence.network.fpa_taus is not a known field; did you mean 'fpa_tau'?"),
    ({"ambient": 298.0, "network": {"housing_tau": 900.0}}, "sequence.network.fpa_tau is required"),
    ({"ambient": 298.0, "network": {"housing_tau": -1.0, "fpa_tau": 1.0}},
     "sequence.network.housing_tau = -1 s is outside the allowed range"),
    ({"record_every": 10, "thermal": "lagged"}, "sequence.record_every = 10 needs the steady"),
    ({"housing_sensor": {"node": "lid"}}, "housing_sensor.node = 'lid'"),
    ({"housing_sensor": {"lag": 1.0}}, "sequence.housing_sensor.lag is not a known field; "
                                       "did you mean 'lag_s'?"),
    ({"scene": {"profile": "rampe", "start": 300.0, "rate": 1.0}}, "did you mean 'ramp'?"),
    ({"scene": {"profile": "step", "before": 300.0, "at": 1.0}},
     "sequence.scene.after is required by profile 'step'"),
    ({"framerate": 30.0}, "sequence.framerate is not a known field; did you mean 'frame_rate'?"),
    ({"shutter": {"every": 1.0, "frames": 1, "colour": 1}}, "sequence.shutter.colour is not"),
    ({"fpa_sensor": {"bits": 40}}, "fpa_sensor.bits = 40"),
    ({"fpa_sensor": {"lsb": 0.1}}, "sequence.fpa_sensor.lsb is not a known field"),
    ({"thermal": "fast"}, "sequence.thermal = 'fast'"),
    ({"transient": {"frame_period": 0.1}}, "sequence.transient.frame_period is not a known"),
]


def _refused(expected_fragment, **table):
    with pytest.raises(ConfigError) as err:
        _seq(**table)
    msg = str(err.value)
    assert expected_fragment in msg, msg
    assert "\n" not in msg


@pytest.mark.parametrize(("table", "fragment"), BAD)
def test_bad_sequences_are_refused_naming_the_key(table, fragment):
    _refused(fragment, **table)


def test_a_steep_ramp_is_accepted_while_it_stays_in_range():
    seq = _seq(fpa={"profile": "ramp", "start": 293.0, "rate": 300.0})  # 298 K after 1 s
    assert seq.schedule().fpa_K.max() < 298.0


@pytest.mark.parametrize(("csv", "fragment"), [
    ("0,300\n5,301\n4,302\n", "time is not increasing at line 3 (4 s after 5 s); the table "
                              "must be monotonic in time"),
    ("0,300\n0,301\n", "time is not increasing at line 2"),
    ("0,300\n", "needs at least two rows"),
    ("0,300\n1,warm\n", "line 2 ('1,warm') is not two numbers"),
    ("0,300\n1,nan\n", "line 2 holds a non-finite number"),
])
def test_bad_table_csv_is_refused_naming_the_line(tmp_path, csv, fragment):
    (tmp_path / "t.csv").write_text(csv)
    with pytest.raises(ConfigError, match=r"sequence\.scene\.file") as err:
        parse_profile({"profile": "table", "file": "t.csv"}, "sequence.scene", tmp_path)
    assert fragment in str(err.value)


def test_cli_refuses_a_bad_sequence_before_any_work(tmp_path, capsys):
    toml = tmp_path / "bad.toml"
    toml.write_text(ISSUE_EXAMPLE.replace("rate = 2.0", "rate = 400.0"))
    out = tmp_path / "f"
    assert main(["frames", "--sequence", str(toml), *TINY, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "--sequence" in err and "sequence.fpa: the ramp profile reaches" in err
    assert "[100, 500] K" in err
    assert not (out / "frames.npz").exists()
    for extra, fragment in ((["--temps", "300"], "--temps and --sequence"),
                            (["--repeats", "2"], "--repeats and --sequence")):
        toml.write_text(ISSUE_EXAMPLE)
        assert main(["frames", "--sequence", str(toml), *extra, "--out", str(out)]) == 2
        assert fragment in capsys.readouterr().err
    assert main(["frames", "--sequence", str(tmp_path / "none.toml"), "--out", str(out)]) == 2
    assert "no such file" in capsys.readouterr().err


# ---- equivalences ----------------------------------------------------------------------------

def test_a_constant_sequence_is_bit_for_bit_the_plain_frames():
    cfg = _tiny(**{"noise.enabled": True})
    seq = _seq(scene={"profile": "step", "before": 300.0, "after": 320.0, "at": 0.5})
    fr = simulate_sequence(cfg, seq, seed=3)
    assert fr.thermal == "lagged"  # a scene step: memory kept; force steady for the plain
    seq = _seq(scene={"profile": "step", "before": 300.0, "after": 320.0, "at": 0.5},
               thermal="steady")
    fr = simulate_sequence(cfg, seq, seed=3)
    plain = model.simulate(cfg, fr.fields["scene_K"], seed=3)
    np.testing.assert_array_equal(fr.codes, plain.codes)
    np.testing.assert_array_equal(fr.blind_codes, plain.blind_codes)
    assert "env_frames" not in fr.counts and fr.counts["housing"] == 1  # static environment


@pytest.mark.parametrize("thermal", ["steady", "lagged", "transient"])
def test_chunking_never_changes_the_bits(thermal):
    cfg = _tiny(**{"noise.enabled": True, "noise.flicker_sigma": 1e-4})
    table = {"duration": 0.4, "thermal": thermal, "fpa_sensor": {"noise_K": 0.02},
             "fpa": {"profile": "ramp", "start": 299.0, "rate": 120.0},
             "housing": {"profile": "sine", "mean": 300.0, "amplitude": 0.5, "period": 0.3},
             "scene": {"profile": "step", "before": 300.0, "after": 330.0, "at": 0.2},
             "shutter": {"at": [0.1], "frames": 2}}
    a = simulate_sequence(cfg, _seq(**table, chunk_frames=12), seed=8)
    b = simulate_sequence(cfg, _seq(**table, chunk_frames=5), seed=8)
    np.testing.assert_array_equal(a.codes, b.codes)
    np.testing.assert_array_equal(a.blind_codes, b.blind_codes)
    np.testing.assert_array_equal(a.fields["fpa_reading"], b.fields["fpa_reading"])
    assert b.counts["env_frames"] == 3 and b.counts["bolometer"] == 3


#: A sensor whose steady pulse model is exact (a small bias: little self-heating), with a
#: high integrator gain so that the scene still moves many codes.
LOW_BIAS = {"bolometer.bias_current": 5e-7, "readout.gain": 1000.0}
STEPS = {"fpa": {"profile": "ramp", "start": 299.0, "rate": 60.0},
         "housing": {"profile": "sine", "mean": 300.0, "amplitude": 1.0, "period": 0.5},
         "scene": {"profile": "step", "before": 300.0, "after": 340.0, "at": 0.5},
         "shutter": {"at": [0.2], "frames": 3, "temperature": 310.0}}


def _codes(cfg, thermal):
    fr = simulate_sequence(cfg, _seq(**STEPS, thermal=thermal), seed=1)
    return fr.codes.astype(np.int64), fr


def test_lagged_memory_matches_the_time_domain_model():
    """tau = 15 ms at 30 Hz: a frame remembers exp(-33/15) = 11 % of the one before. The
    time-domain model (state carried across frames) and the lagged model agree to the code;
    the steady model misses the memory by hundreds of codes after each step."""
    cfg = _tiny(**LOW_BIAS, **{"bolometer.C": 1.5e-10})
    lagged, _ = _codes(cfg, "lagged")
    transient, _ = _codes(cfg, "transient")
    steady, _ = _codes(cfg, "steady")
    assert np.abs(lagged - transient).max() <= 1
    assert np.abs(steady - transient).max() > 200
    auto = simulate_sequence(cfg, _seq(**STEPS), seed=1)
    assert auto.thermal == "lagged" and "0.11" in auto.thermal_reason


def test_where_the_time_constant_is_far_below_the_frame_period_steady_is_used_and_equal():
    """tau = 0.1 ms at 30 Hz: nothing is remembered (exp(-333)) and the pixel lags the
    1 K/s substrate ramp by tau r = 0.1 mK; ``auto`` says so and uses the steady model,
    which gives the time-domain and the lagged models' codes to the code."""
    cfg = _tiny(**LOW_BIAS, **{"bolometer.C": 1e-12})
    auto = simulate_sequence(cfg, _seq(**STEPS), seed=1)
    assert auto.thermal == "steady" and "steady model gives the same frames" in auto.thermal_reason
    steady, _ = _codes(cfg, "steady")
    lagged, _ = _codes(cfg, "lagged")
    transient, _ = _codes(cfg, "transient")
    np.testing.assert_array_equal(auto.codes, steady)
    assert np.abs(lagged - steady).max() <= 1
    assert np.abs(steady - transient).max() <= 1


def test_shutter_frames_see_a_uniform_source():
    """No spread and the shutter at the housing = substrate temperature: a closed frame is
    uniform (the net power on every pixel is zero) while the open frames show the gradient
    scene; a hotter shutter raises the closed frames."""
    cfg = _tiny(**{"fpa.tolerance": {"R_ref": 0.0, "g": 0.0, "C": 0.0}})
    seq = _seq(shutter={"at": [0.3], "frames": 2})
    fr = simulate_sequence(cfg, seq, "gradient", seed=1, scene_params={"span": 40.0})
    closed = fr.fields["shutter"]
    assert fr.codes[closed].std(axis=(1, 2)).max() == 0.0
    assert fr.codes[~closed].std(axis=(1, 2)).min() > 100.0
    hot = simulate_sequence(cfg, _seq(shutter={"at": [0.3], "frames": 2, "temperature": 320.0}),
                            seed=1)
    assert hot.codes[closed].mean() > fr.codes[closed].mean() + 500


def test_a_sequence_file_toml_reads_relative_tables(tmp_path):
    (tmp_path / "housing.csv").write_text("0,300\n1,301\n")
    toml = Path(tmp_path / "s.toml")
    toml.write_text('[sequence]\nframe_rate = 10.0\nduration = 1.0\nfpa = 300.0\n'
                    'scene = 300.0\n[sequence.housing]\nprofile = "table"\n'
                    'file = "housing.csv"\n')
    seq = load_sequence(toml)
    np.testing.assert_allclose(seq.schedule().T_cam_K, 300.0 + np.arange(10) / 10.0)
    toml.write_text(toml.read_text() + "[extra]\nx = 1\n")
    with pytest.raises(ConfigError, match=r"s.toml: .*extra is not a known section"):
        load_sequence(toml)
