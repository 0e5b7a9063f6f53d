"""``irnuc calibrate --plan`` and ``irnuc correct`` for every method, end to end, and the
one-line errors of their new flags."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from irnuc.cli import main
from irnuc.model.fpa_sensor import FpaSensor, frame_fields
from irnuc.nuc_fixed import load_pipeline, pipeline_names
from irnuc.nuc_fixed.memimage import read_method_image
from irnuc.nuc_fixed.method_top import FrameInputs, method_top

PLAN = """[plan]
scene = [290.0, 330.0, 370.0]     # K, blackbody temperatures
fpa = [288.0, 298.0, 308.0]       # K, FPA (substrate) temperatures
frames = 4                        # per point
"""
SMALL = ["--set", "fpa.active_rows=12", "--set", "fpa.active_cols=16", "--seed", "3"]
METHODS = [n for n in pipeline_names(method=None) if n not in ("wide16", "minimal")]


@pytest.fixture(scope="module")
def plan_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    p = tmp_path_factory.mktemp("plan") / "plan.toml"
    p.write_text(PLAN)
    return p


@pytest.fixture(scope="module")
def seq_frames(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A short sequence at FPA 303 K with the per-frame fields: scene frames, shutter
    frames (the shutter at 303 K), scene frames."""
    from irnuc import model

    rows = [(330.0, False)] * 2 + [(303.0, True)] * 9 + [(350.0, False)] * 2
    codes = []
    for scene, _ in rows:
        cfg = model.load_preset("default", overrides={
            "fpa.active_rows": 12, "fpa.active_cols": 16, "environment.T_substrate": 303.0,
            "environment.T_cam": 303.0})
        codes.append(model.simulate(cfg, [scene], seed=3).codes[0])
    n = len(rows)
    rng = np.random.default_rng(1)
    temps = np.array([r[0] for r in rows])
    fields = frame_fields(np.arange(n) / 30.0, np.full(n, 303.0), np.full(n, 303.0), temps,
                          np.array([r[1] for r in rows]), FpaSensor())
    p = tmp_path_factory.mktemp("seq") / "frames.npz"
    np.savez(p, codes=np.stack(codes), temps=temps, adc_bits=np.int64(14), **fields,
             blind_codes=rng.integers(4990, 5010, (n, 30)),
             blind_positions=np.zeros((30, 2), np.int32))
    return p


@pytest.mark.parametrize("name", METHODS)
def test_plan_then_correct_every_method(tmp_path: Path, plan_file: Path, seq_frames: Path,
                                        name: str, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "cal"
    if "housing" in load_pipeline(name).base.readings:
        # A method that reads the housing is fitted over FPA x housing (3 housing offsets).
        plan_file = tmp_path / "plan_housing.toml"
        plan_file.write_text(PLAN.replace("[plan]\n", "[plan]\nhousing_offset = [-5.0, 0.0, 5.0]\n"))
    args = ["calibrate", "--plan", str(plan_file), "--pipeline", name, *SMALL, "--out", str(out)]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "needed range" in text and "bad pixels" in text
    manifest = json.loads((out / "manifest.json").read_text())
    summary = json.loads((out / "summary.json").read_text())
    assert summary["plan"] == str(plan_file) and summary["seed"] == 3
    for f in manifest["files"]:
        assert (out / f).is_file()
    mc = read_method_image(out)
    assert mc.cfg.name == name
    if mc.cfg.base_method == "table_interp":  # the DMA's pair images (irnuc_axis_top)
        pairs = sorted(f for f in manifest["files"] if f.startswith("table_pair"))
        assert pairs == [f"table_pair{j}.bin" for j in range(mc.cfg.tables - 1)]
        for j, f in enumerate(pairs):
            data = (out / f).read_bytes()
            h, w = mc.shape
            nb = -(-2 * mc.cfg.memories["table0"].word_bits // 8)
            assert len(data) == h * w * nb
            words = [int.from_bytes(data[k:k + nb], "little") for k in range(0, len(data), nb)]
            lo, hi = (mc.words()[f"table{i}"].ravel().tolist() for i in (j, j + 1))
            bits = mc.cfg.memories["table0"].word_bits
            assert words == [a | b << bits for a, b in zip(lo, hi, strict=True)]
    corr = tmp_path / "corr"
    assert main(["correct", "--frames", str(seq_frames), "--coeffs", str(out), "--out",
                 str(corr)]) == 0
    with np.load(seq_frames) as f, np.load(corr / "corrected.npz") as z:
        want = method_top(f["codes"], mc, FrameInputs(
            reading=f["fpa_reading"], blind_codes=f["blind_codes"], shutter=f["shutter"],
            housing_reading=f["housing_reading"] if "housing" in mc.cfg.base.readings else None))
        assert np.array_equal(z["corrected"], want.y)
        assert str(z["method"]) == mc.cfg.method
        if mc.cfg.has("ffc"):
            assert z["ffc_refreshes"].tolist() == [2 + 8 - 1]


def test_plan_is_reproducible_and_seeded(tmp_path: Path, plan_file: Path) -> None:
    outs = []
    for i, seed in enumerate(("3", "3", "4")):
        o = tmp_path / f"c{i}"
        assert main(["calibrate", "--plan", str(plan_file), "--pipeline", "table14",
                     *SMALL[:-1], seed, "--out", str(o), "-q"]) == 0
        outs.append((o / "table1.bin").read_bytes())
    assert outs[0] == outs[1] != outs[2]


@pytest.mark.parametrize(("extra", "match"), [
    (["--plan", "nope.toml"], "--plan nope.toml: no such file"),
    (["--pipeline", "quadratic15"], "--pipeline quadratic15"),
    (["--set", "environment.T_substrate=300"], "--set environment.T_substrate: the plan sets it"),
    (["--set", "fpa.activ_rows=3"], "fpa.activ_rows is not a known field"),
    (["--set", "low_respons=0.3"], "low_respons"),
    (["--seed", "-1"], "--seed -1 is outside"),
    (["--max-saturated", "2"], "--max-saturated 2.0: must lie in 0..1"),
    (["--t-low", "290"], "--t-low: not with --plan"),
    (["--sensor", "nope"], "--sensor 'nope' is neither a preset"),
    (["--set", "adc.bits=12"], "a 12-bit ADC but pipeline 'quadratic14' has adc_bits = 14"),
])
def test_calibrate_plan_errors(tmp_path: Path, plan_file: Path, extra: list[str], match: str,
                               capsys: pytest.CaptureFixture[str]) -> None:
    args = ["calibrate", "--plan", str(plan_file), "--pipeline", "quadratic14", "--out",
            str(tmp_path / "o")]
    if extra[0] in ("--plan", "--pipeline"):
        args[args.index(extra[0]) + 1] = extra[1]
    else:
        args += extra
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and match in err, err
    assert not (tmp_path / "o").exists()


def test_frames_flags_errors(tmp_path: Path, seq_frames: Path, plan_file: Path,
                             capsys: pytest.CaptureFixture[str]) -> None:
    cases = [
        (["calibrate", "--frames", str(seq_frames), "--seed", "4"], "--seed: only with --plan"),
        (["calibrate", "--frames", str(seq_frames), "--set", "fpa.active_rows=3"],
         "--set fpa.active_rows: a sensor field is set only with --plan"),
        (["calibrate", "--pipeline", "table14"], "one of the arguments --frames --plan is required"),
    ]
    for args, match in cases:
        try:
            rc = main([*args, "--out", str(tmp_path / "o")])
        except SystemExit as exc:  # a usage error: argparse exits, with one line
            rc = exc.code
        assert rc == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and match in err, err


def test_correct_without_the_fields_a_method_needs(tmp_path: Path, plan_file: Path,
                                                   seq_frames: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    cal = tmp_path / "cal"
    assert main(["calibrate", "--plan", str(plan_file), "--pipeline", "tcffc14", *SMALL,
                 "--out", str(cal), "-q"]) == 0
    # A frame file of an older irnuc: no per-frame fields (the reader makes them up from
    # its configuration, but a made-up reading is no reading).
    p = tmp_path / "old.npz"
    with np.load(seq_frames) as f:
        np.savez(p, **{k: f[k] for k in ("codes", "temps", "adc_bits")})
    assert main(["correct", "--frames", str(p), "--coeffs", str(cal), "--out",
                 str(tmp_path / "c")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "method 'tc_offset+ffc' needs the per-frame field fpa_reading" in err
    assert main(["correct", "--frames", str(seq_frames), "--coeffs", str(cal), "--out",
                 str(tmp_path / "c"), "--ffc-target", "99999"]) == 2
    assert "--ffc-target 99999: must lie in 0..16383" in capsys.readouterr().err
    # A target given: the shutter image is flattened to it.
    assert main(["correct", "--frames", str(seq_frames), "--coeffs", str(cal), "--out",
                 str(tmp_path / "c"), "--ffc-target", "6000", "-q"]) == 0
    with np.load(tmp_path / "c" / "corrected.npz") as z, np.load(seq_frames) as f:
        assert z["held"].tolist() == f["shutter"].tolist()
        good = z["ffc_offset"] != 0
        assert good.any()


def test_correct_refuses_another_housing_sensor(tmp_path: Path, plan_file: Path,
                                                seq_frames: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    """tc_housing's coefficients hold for the housing sensor of the calibration: frames of
    a sensor on another node (or with another LSB) get a one-line error, not a correction
    with the wrong housing terms; the FPA-only methods do not look at it."""
    plan = tmp_path / "plan_housing.toml"
    plan.write_text(PLAN.replace("[plan]\n", "[plan]\nhousing_offset = [-5.0, 0.0, 5.0]\n"))
    cal = tmp_path / "cal"
    assert main(["calibrate", "--plan", str(plan), "--pipeline", "tchousing14", *SMALL,
                 "--out", str(cal), "-q"]) == 0
    assert json.loads((cal / "manifest.json").read_text())["housing_sensor"]["node"] == "housing"
    with np.load(seq_frames) as f:
        data = dict(f)
    for key, value, what in (("housing_sensor_node", np.array("lens"), "node = 'lens'"),
                             ("housing_sensor_lsb_K", np.float64(0.02), "lsb_K = 0.02")):
        p = tmp_path / f"{key}.npz"
        np.savez(p, **{**data, key: value})
        assert main(["correct", "--frames", str(p), "--coeffs", str(cal), "--out",
                     str(tmp_path / key)]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1, err
        assert f"the frames' housing sensor ({what})" in err
        assert not (tmp_path / key).exists()
    assert main(["correct", "--frames", str(seq_frames), "--coeffs", str(cal), "--out",
                 str(tmp_path / "ok"), "-q"]) == 0


def test_unknown_method_in_a_pipeline_file(tmp_path: Path, plan_file: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    from irnuc.nuc_fixed import load_pipeline

    text = load_pipeline("typical14").to_toml().replace("[typical14]", "[mine]\nmethod = \"three_point\"")
    f = tmp_path / "mine.toml"
    f.write_text(text)
    assert main(["calibrate", "--plan", str(plan_file), "--pipeline", str(f), *SMALL, "--out",
                 str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "'three_point' is not a base method" in err, err
    assert err.startswith(f"irnuc calibrate: error: --pipeline {f}")
