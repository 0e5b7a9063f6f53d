"""Bad input to ``irnuc frames --sequence`` and ``irnuc noise``: one line naming the flag,
the file or the dotted field, exit status 2, no output written."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.cli import main

GOOD = ('[sequence]\nframe_rate = 30.0\nduration = 0.5\nfpa = 300.0\nhousing = 300.0\n'
        'scene = 300.0\n')
SMALL = ["--set", "fpa.active_rows=6", "--set", "fpa.active_cols=8"]

CASES = [
    ("a folder", lambda t: str(t), "is a folder, not a TOML file"),
    ("not TOML", lambda t: _write(t, "[sequence\nframe_rate = 30"), "not valid TOML"),
    ("no sequence keys", lambda t: _write(t, "[sequence]\n"), "sequence.frame_rate is required"),
    ("unknown section", lambda t: _write(t, GOOD + "[camera]\nx = 1\n"),
     "camera is not a known section"),
    ("scene below 0 K", lambda t: _write(t, GOOD.replace("scene = 300.0", "scene = -3.0")),
     "sequence.scene.value = -3 K"),
    ("fpa as text", lambda t: _write(t, GOOD.replace("fpa = 300.0", 'fpa = "warm"')),
     "sequence.fpa = 'warm' must be a table"),
    ("negative shutter frames", lambda t: _write(
        t, GOOD + "[sequence.shutter]\nevery = 1.0\nframes = -2\n"),
     "sequence.shutter.frames = -2"),
    ("table file missing", lambda t: _write(
        t, GOOD.replace("scene = 300.0", '[sequence.scene]\nprofile = "table"\n'
                                         'file = "nope.csv"')),
     "sequence.scene.file = 'nope.csv': no such file"),
    ("thermal transient with an unknown setting", lambda t: _write(
        t, GOOD + "[sequence.transient]\nsteps = 4\nintegrater = 'rk4'\n"),
     "sequence.transient.integrater is not a known field; did you mean 'integrator'?"),
]


def _write(folder, text):
    p = folder / "s.toml"
    p.write_text(text)
    return str(p)


@pytest.mark.parametrize(("name", "make", "fragment"), CASES, ids=[c[0] for c in CASES])
def test_bad_sequence_files(tmp_path, capsys, name, make, fragment):
    out = tmp_path / "out"
    assert main(["frames", "--sequence", make(tmp_path), *SMALL, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert fragment in err, err
    assert len(err.splitlines()) == 1 and "Traceback" not in err and "--sequence" in err
    assert not (out / "frames.npz").exists()


def test_noise_needs_a_responsivity_for_foreign_frames(tmp_path, capsys):
    p = tmp_path / "f.npz"
    rng = np.random.default_rng(0)
    np.savez(p, codes=rng.integers(1000, 1010, (8, 4, 5)).astype(np.uint16),
             temps=np.full(8, 300.0), adc_bits=np.int64(14))
    assert main(["noise", "--frames", str(p), "--out", str(tmp_path / "n")]) == 2
    assert "no responsivity to turn codes into kelvin" in capsys.readouterr().err
    assert main(["noise", "--frames", str(tmp_path / "none.npz"), "--out",
                 str(tmp_path / "n")]) == 2
    assert "no such file" in capsys.readouterr().err
    assert main(["noise", "--frames", str(p), "--seed", "-4", "--out",
                 str(tmp_path / "n")]) == 2
    assert "--seed -4" in capsys.readouterr().err
    assert not (tmp_path / "n" / "noise.json").exists()


def test_lagged_memory_needs_the_equilibrium_variant(tmp_path, capsys):
    toml = _write(tmp_path, GOOD.replace("scene = 300.0", 'scene = 300.0\nthermal = "lagged"'))
    assert main(["frames", "--sequence", toml, *SMALL, "--set", "bolometer.variant=paper",
                 "--out", str(tmp_path / "o")]) == 2
    assert "sequence.thermal = 'lagged' needs bolometer.variant" in capsys.readouterr().err
