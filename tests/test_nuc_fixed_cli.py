"""``irnuc calibrate`` and ``irnuc correct`` end to end on synthetic frames."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from irnuc.cli import main
from irnuc.nuc_fixed import load_pipeline, nuc_dpc_top, read_memimage, unpack_words
from irnuc.nuc_fixed.synthetic import synth_frames


@pytest.fixture
def frames_npz(tmp_path: Path) -> Path:
    s = synth_frames(shape=(12, 16), temps=(300.0, 350.0, 400.0), repeats=4,
                     defect_fraction=0.05, seed=4)
    p = tmp_path / "frames.npz"
    np.savez(p, codes=s.codes, temps=s.temps, defect_kind=s.defect_kind,
             adc_bits=np.int64(s.adc_bits), config_json=np.str_("{}"))
    return p


def test_calibrate_then_correct(tmp_path: Path, frames_npz: Path,
                                capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "cal"
    assert main(["calibrate", "--frames", str(frames_npz), "--pipeline", "typical14",
                 "--out", str(out)]) == 0
    assert "bad pixels" in capsys.readouterr().out
    for name in ("coeffs.npz", "badpix.csv", "coeffs.hex", "coeffs.bin", "manifest.json",
                 "summary.json", "summary.txt"):
        assert (out / name).is_file(), name
    summary = json.loads((out / "summary.json").read_text())
    assert (summary["t_low"], summary["t_high"]) == (300.0, 400.0)
    with np.load(out / "coeffs.npz") as z:
        bad, reasons = z["bad"], z["reasons"]
        words_npz = z["words"]
    words, cfg = read_memimage(out, "typical14", source="hex")
    assert np.array_equal(words, words_npz)
    assert np.array_equal(unpack_words(words, cfg)[2], bad)
    csv = (out / "badpix.csv").read_text().splitlines()
    assert len(csv) == 1 + int(bad.sum())
    r, c, code, _ = csv[1].split(",")
    assert reasons[int(r), int(c)] == int(code) != 0

    corr = tmp_path / "corr"
    assert main(["correct", "--frames", str(frames_npz), "--coeffs", str(out),
                 "--out", str(corr)]) == 0
    with np.load(frames_npz) as f, np.load(corr / "corrected.npz") as z:
        want = nuc_dpc_top(f["codes"], words, cfg)
        assert np.array_equal(z["corrected"], want)
        assert np.array_equal(z["temps"], f["temps"])
        # The flat field is flat after correction at the calibration temperatures.
        hot = z["corrected"][f["temps"] == 400.0].astype(float).mean(axis=0)
        assert hot.std() < 2.0


def test_calibrate_options(tmp_path: Path, frames_npz: Path) -> None:
    out = tmp_path / "cal2"
    assert main(["calibrate", "--frames", str(frames_npz), "--pipeline", "typical14",
                 "--out", str(out), "--t-low", "350", "--targets", "4000,6000",
                 "--set", "noisy_factor=5", "--coeff-rounding", "truncate"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["targets"] == [4000.0, 6000.0] and s["t_low"] == 350.0
    assert s["thresholds"]["noisy_factor"] == 5 and s["rounding"] == "truncate"


@pytest.mark.parametrize(
    ("extra", "match"),
    [
        (["--pipeline", "minimal"], "adc_bits = 14 but pipeline 'minimal'"),
        (["--pipeline", "typical14", "--t-low", "310"], "--t-low 310 K matches no frame"),
        (["--pipeline", "typical14", "--t-low", "400", "--t-high", "300"], "must be below"),
        (["--pipeline", "nope"], "pipeline 'nope' is neither a named configuration"),
        (["--pipeline", "typical14", "--set", "low_response"], "must look like KEY=VALUE"),
        (["--pipeline", "typical14", "--set", "low_respons=0.3"], "did you mean 'low_response'"),
    ],
)
def test_calibrate_errors(tmp_path: Path, frames_npz: Path, extra: list[str], match: str,
                          capsys: pytest.CaptureFixture[str]) -> None:
    rc = main(["calibrate", "--frames", str(frames_npz), "--out", str(tmp_path / "x"), *extra])
    assert rc == 2
    assert match in capsys.readouterr().err


def test_correct_errors(tmp_path: Path, frames_npz: Path,
                        capsys: pytest.CaptureFixture[str]) -> None:
    rc = main(["correct", "--frames", str(frames_npz), "--coeffs", str(tmp_path / "none"),
               "--out", str(tmp_path / "o")])
    assert rc == 2 and "not a folder" in capsys.readouterr().err
    (tmp_path / "empty").mkdir()
    rc = main(["correct", "--frames", str(frames_npz), "--coeffs", str(tmp_path / "empty"),
               "--out", str(tmp_path / "o")])
    assert rc == 2 and "no manifest.json" in capsys.readouterr().err
    out = tmp_path / "cal"
    assert main(["calibrate", "--frames", str(frames_npz), "--pipeline", "typical14",
                 "--out", str(out)]) == 0
    data = bytearray((out / "coeffs.bin").read_bytes())
    data[0] ^= 0xFF
    (out / "coeffs.bin").write_bytes(bytes(data))
    rc = main(["correct", "--frames", str(frames_npz), "--coeffs", str(out),
               "--out", str(tmp_path / "o")])
    assert rc == 2 and "SHA-256" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()
    assert load_pipeline("typical14")  # the configuration file is untouched
