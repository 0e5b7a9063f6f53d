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


def _numeric_leaves(d, path=()):
    """Every number of a parsed TOML document, by its path (lists by index)."""
    if isinstance(d, dict):
        return [p for k, v in d.items() for p in _numeric_leaves(v, (*path, k))]
    if isinstance(d, list):
        return [p for i, v in enumerate(d) for p in _numeric_leaves(v, (*path, i))]
    return [path] if isinstance(d, int | float) and not isinstance(d, bool) else []


def _dotted(path) -> str:
    out = ""
    for k in path:
        out += f"[{k}]" if isinstance(k, int) else (f".{k}" if out else k)
    return out


FULL = {"sequence": {
    "frame_rate": 30.0, "duration": 2.0, "steady_tolerance": 0.01, "chunk_frames": 8,
    "fpa": {"profile": "ramp", "start": 300.0, "rate": 1.0, "delay": 0.1, "stop": 301.0},
    "housing": {"profile": "sine", "mean": 300.0, "amplitude": 0.5, "period": 1.0,
                "phase": 0.1},
    "scene": {"profile": "step", "before": 300.0, "after": 310.0, "at": 1.0},
    "shutter": {"frames": 2, "every": 1.0, "start": 0.2, "at": [0.5],
                "temperature": {"profile": "constant", "value": 300.0}},
    "fpa_sensor": {"bits": 14, "lsb_K": 0.01, "zero_K": 223.15, "offset_K": 0.1,
                   "noise_K": 0.01},
}}


def _refuses_every_number(doc, error, load) -> int:
    """Load ``doc`` as it is, then with each of its numbers made a boolean and a string (its
    own value's text): each refused with ``error`` naming the dotted key. The numbers'
    count."""
    import copy

    load(doc)  # valid as it is
    leaves = _numeric_leaves(doc)
    for path in leaves:
        for bad in (True, "30"):
            d = copy.deepcopy(doc)
            node = d
            for k in path[:-1]:
                node = node[k]
            node[path[-1]] = bad if bad is True else str(node[path[-1]])
            with pytest.raises(error) as exc:
                load(d)
            assert _dotted(path) in str(exc.value), (path, str(exc.value))
    return len(leaves)


def _plan_loader(tmp_path):
    """load_plan of a document written as a TOML file."""
    import json

    from irnuc.nuc_fixed.plan import load_plan

    def load(doc):
        lines = []
        for table, fields in doc.items():
            lines.append(f"[{table}]")
            lines += [f"{k} = {json.dumps(v)}" for k, v in fields.items()]
        p = tmp_path / "p.toml"
        p.write_text("\n".join(lines) + "\n")
        return load_plan(str(p))

    return load


def test_every_number_of_a_sequence_refuses_booleans_and_strings() -> None:
    """`frame_rate = true` was taken as 1 Hz and `"30"` as 30: every number field of a
    sequence (and of its profiles, shutter and FPA sensor) refuses a boolean and a string,
    naming its dotted key."""
    from irnuc.model.sequence import sequence_from_dict
    from irnuc.model.validate import ConfigError

    assert _refuses_every_number(FULL, ConfigError, sequence_from_dict) == 25


def test_every_number_of_a_plan_refuses_booleans_and_strings(tmp_path) -> None:
    from irnuc.nuc_fixed.plan import PlanError

    plan = {"plan": {"scene": [290.0, 330.0], "fpa": [288.0, 298.0], "frames": 2,
                     "cam": [290.0, 300.0], "reference_fpa": 288.0, "drift_cam": [295.0]},
            "fpa_sensor": {"bits": 14, "lsb_K": 0.01, "zero_K": 223.15, "offset_K": 0.0,
                           "noise_K": 0.0}}
    assert _refuses_every_number(plan, PlanError, _plan_loader(tmp_path)) == 14


WORLD = {"sequence": {
    "frame_rate": 30.0, "duration": 2.0, "record_every": 2,
    "ambient": {"profile": "ramp", "start": 290.0, "rate": 1.0},
    "network": {"start": 290.0, "housing_tau": 900.0, "fpa_tau": 120.0, "lens_tau": 600.0,
                "shutter_tau": 300.0, "housing_self_heating": 3.0, "fpa_self_heating": 6.0},
    "scene": {"profile": "constant", "value": 300.0},
    "fpa_sensor": {"lag_s": 2.0},
    "housing_sensor": {"bits": 14, "lsb_K": 0.01, "zero_K": 223.15, "offset_K": 0.1,
                       "noise_K": 0.01, "lag_s": 5.0, "node": "lens"},
}}


def test_every_number_of_the_thermal_world_refuses_booleans_and_strings(tmp_path) -> None:
    """The same for issue 35's keys: the ambient, the network, the housing sensor, the
    sensors' lags, record_every, and a plan's housing offsets and housing sensor."""
    from irnuc.model.sequence import sequence_from_dict
    from irnuc.model.validate import ConfigError
    from irnuc.nuc_fixed.plan import PlanError

    assert _refuses_every_number(WORLD, ConfigError, sequence_from_dict) == 20
    doc = {"plan": {"scene": [290.0, 330.0], "fpa": [288.0, 298.0], "frames": 2,
                    "housing_offset": [-5.0, 0.0, 5.0]},
           "housing_sensor": {"bits": 14, "lsb_K": 0.01, "zero_K": 223.15, "offset_K": 0.0,
                              "noise_K": 0.0, "lag_s": 0.0, "node": "housing"}}
    assert _refuses_every_number(doc, PlanError, _plan_loader(tmp_path)) == 14
