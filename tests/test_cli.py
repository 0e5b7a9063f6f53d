"""The irnuc command line: frames written atomically, errors as one line with exit status 2."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from irnuc.cli import main

SMALL = ["--set", "fpa.active_rows=10", "--set", "fpa.active_cols=12"]


def test_frames_npz_contents(tmp_path, capsys):
    folder = tmp_path / "sub" / "f"
    assert main(["frames", *SMALL, "--temps", "300,350,400", "--seed", "4", "--params",
                 "--out", str(folder)]) == 0
    out = folder / "frames.npz"
    with np.load(out) as z:
        assert z["codes"].shape == (3, 10, 12) and z["codes"].dtype == np.uint16
        np.testing.assert_array_equal(z["temps"], [300.0, 350.0, 400.0])
        assert z["defect_kind"].shape == (10, 12) and int(z["adc_bits"]) == 14
        meta = json.loads(str(z["config_json"]))
        assert meta["seed"] == 4 and meta["config"]["fpa"]["active_rows"] == 10
        assert z["param_R_ref"].shape == (10 + 6, 12 + 6)
    # The result and the marker that lets a later run replace this folder as a whole.
    assert sorted(p.name for p in folder.iterdir()) == [".irnuc-output", "frames.npz"]
    # Nothing but the result beside it: no temporary folder, no lock file left behind.
    assert sorted(p.name for p in folder.parent.iterdir()) == ["f"]
    assert "wrote" in capsys.readouterr().out
    assert main(["frames", "-q", *SMALL, "--out", str(folder)]) == 0
    assert capsys.readouterr().out == ""


def test_same_seed_same_file_contents(tmp_path):
    for name in ("a", "b"):
        assert main(["frames", *SMALL, "--temps", "310", "--seed", "9", "--out",
                     str(tmp_path / name)]) == 0
    with np.load(tmp_path / "a" / "frames.npz") as a, np.load(tmp_path / "b" / "frames.npz") as b:
        np.testing.assert_array_equal(a["codes"], b["codes"])


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["--temps", "0,300"], "temps = 0 K"),
        (["--temps", "warm"], "--temps"),
        (["--set", "bolometer.t_int=0"], "bolometer.t_int = 0 s"),
        (["--set", "fpa.tolerance={R_ref=-0.5}"], "fpa.tolerance.R_ref = -0.5"),
        (["--sensor", "nope"], "--sensor 'nope' is neither a preset"),
        (["--sensor", "/nonexistent.toml"], "/nonexistent.toml: no such file"),
        (["--set", "fpa.activ_rows=3"], "did you mean 'active_rows'"),
    ],
)
def test_errors_are_one_line_with_status_2(tmp_path, capsys, args, fragment):
    out = tmp_path / "x"
    assert main(["frames", *SMALL, *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err
    assert not out.exists()


def test_progress_bar_on_long_batches(tmp_path, capsys):
    assert main(["frames", *SMALL, "--set", "run.chunk_frames=2", "--temps",
                 "300,301,302,303,304", "--out", str(tmp_path / "p")]) == 0
    assert "frames [" in capsys.readouterr().err


def test_progress_bar_redraws_on_a_terminal_and_logs_quarters_otherwise():
    import io

    from irnuc.common.progress import ProgressBar

    class Tty(io.StringIO):
        def isatty(self):
            return True

    tty, log = Tty(), io.StringIO()
    for stream in (tty, log):
        bar = ProgressBar("x", stream)
        for k in range(1, 101):
            bar(k, 100)
    # A tqdm bar on the terminal: redrawn in place, ending at 100/100.
    assert tty.getvalue().count("\r") >= 100 and "100/100" in tty.getvalue()
    assert tty.getvalue().endswith("\n") and tty.getvalue().count("\n") == 1
    assert log.getvalue().count("\n") == 5 and "\r" not in log.getvalue()


def test_version_and_verbosity_flags(capsys):
    from irnuc import __version__

    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and capsys.readouterr().out.strip() == f"irnuc {__version__}"


def test_out_that_is_a_file_is_refused_before_work(tmp_path, capsys):
    target = tmp_path / "file"
    target.write_text("keep")
    assert main(["frames", *SMALL, "--out", str(target)]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "not a folder" in err and "Traceback" not in err
    assert target.read_text() == "keep"


def test_synth_help_names_every_method_the_axi_top_wraps(capsys):
    # `irnuc synth --help` once listed five of the methods irnuc_axis_top wraps: its words
    # must be the method registry's (every base method, each stage's rtl_bases), and every
    # named configuration that tops_for builds in irnuc_axis_top must be named in it.
    from irnuc.cli import synth as synth_cli
    from irnuc.cosim.synth import tops_for
    from irnuc.nuc_fixed import load_pipeline, methods, pipeline_names

    assert synth_cli.AXIS_WRAPS == tuple(methods.BASES)
    assert synth_cli.AXIS_STAGES == {s.name: s.rtl_bases for s in methods.STAGES.values()}
    with pytest.raises(SystemExit):
        main(["synth", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    wrapped = text.split("irnuc_axis_top (", 1)[1].split("); default", 1)[0]
    for name in pipeline_names(method=None):
        cfg = load_pipeline(name)
        if "irnuc_axis_top" not in tops_for(cfg):
            continue
        assert cfg.base_method in wrapped, name
        for stage in cfg.stages:
            assert re.search(rf"{stage} with [a-z_, ]*{cfg.base_method}", wrapped), name
