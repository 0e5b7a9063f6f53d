"""The outcome table (``outcomes.py``): one test per row."""

from __future__ import annotations

import errno
import hashlib
import json
import os
import resource
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from robustness.harness import run_cli
from robustness.outcomes import OUTCOMES


def _files(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def test_outcome_synth_cache_carries_the_asked_name(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    from irnuc.cosim import synth
    from irnuc.nuc_fixed import load_pipeline

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    # The tools replaced by fakes: the cache and the naming are under test, not Yosys.
    counts = {"xc7": {k: 1 for k in synth.XC7_KEYS}, "ecp5": {k: 2 for k in synth.ECP5_KEYS}}
    monkeypatch.setattr(synth, "synth_xc7", lambda *a, **k: {
        **counts["xc7"], "cells": {}, "seconds": 0.0})
    monkeypatch.setattr(synth, "synth_ecp5", lambda *a, **k: (tmp_path / "net.json", {
        **counts["ecp5"], "cells": {}, "seconds": 0.0}))
    monkeypatch.setattr(synth, "place_route_ecp5", lambda *a, **k: {
        "fmax_mhz": 123.0, "utilization": {}, "critical_path": [], "seconds": 0.0,
        "timing_weight": k.get("timing_weight", 7), "timing_ripup": False,
        "out_of_context": k.get("out_of_context")})
    monkeypatch.setattr(synth, "tool_versions", lambda: {})
    first = synth.synth_config(load_pipeline("typical14"))
    assert first["cached"] is False and first["config"]["name"] == "typical14"
    assert first["placer_timing_weight"] == 7  # what place-and-route reports, recorded as is
    assert first["router_timing_ripup"] is False
    assert first["out_of_context"] is False  # asked for on pins, by default
    alias = tmp_path / "alias.toml"
    alias.write_text(load_pipeline("typical14").to_toml().replace("[typical14]", "[alias]"))
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    assert run_cli(["synth", "-q", "--workers", "0", "--pipeline", str(alias), "--pipeline",
                    "minimal", "--out", "syn"]) == 0
    index = json.loads((work / "syn" / "synth.json").read_text())
    assert [c["name"] for c in index["configurations"]] == ["alias", "minimal"]
    got = json.loads((work / "syn" / "alias" / "synth.json").read_text())
    assert got["cached"] is True and got["config"]["name"] == "alias"
    assert got["config_digest"] == load_pipeline(str(alias)).digest()
    assert got["source_digest"] == first["source_digest"]  # the same design, from the cache
    assert _files(work) == {"syn", "syn/.irnuc-output", "syn/synth.json", "syn/alias",
                            "syn/alias/synth.json", "syn/minimal", "syn/minimal/synth.json"}


_MAIN = "import sys; from irnuc.cli import main; sys.exit(main(sys.argv[1:]))"


def _frames(path: Path, seed: int = 1) -> Path:
    from irnuc.nuc_fixed.synthetic import synth_frames

    s = synth_frames(shape=(24, 32), temps=(300.0, 400.0), repeats=3, defect_fraction=0.03,
                     seed=seed)
    np.savez(path, codes=s.codes, temps=s.temps, adc_bits=np.int64(s.adc_bits))
    return path


def _digest(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def _irnuc(args: list[str], cwd: Path, **kw) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
    return subprocess.run([sys.executable, "-c", _MAIN, *args], cwd=cwd, env=env, text=True,
                          stderr=subprocess.PIPE, timeout=120, **kw)


def _one_error_line(err: str) -> str:
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and "Traceback" not in err and "Exception ignored" not in err, err
    return lines[0]


def test_outcome_write_file_too_large(tmp_path: Path) -> None:
    from irnuc.cli import main

    out = tmp_path / "cal"
    assert main(["calibrate", "-q", "--frames", str(_frames(tmp_path / "a.npz")), "--out",
                 str(out)]) == 0
    before = _digest(out)
    limit = 8000  # below coeffs.npz (~20 kB), above every other file of the run

    def limited() -> None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # write() then fails with EFBIG
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    r = _irnuc(["calibrate", "-q", "--frames", str(_frames(tmp_path / "b.npz", 2)), "--out",
                str(out)], tmp_path, stdout=subprocess.DEVNULL, preexec_fn=limited)
    line = _one_error_line(r.stderr)
    assert r.returncode == 2, line
    assert line.startswith(f"irnuc calibrate: error: --out {out}: ") and "File too large" in line
    assert "previous content is left whole" in line
    assert _digest(out) == before
    assert not list(tmp_path.glob(".cal.tmp-*"))


def test_outcome_write_disk_full(tmp_path: Path) -> None:
    from irnuc.common.io import WriteError, output_folder, write_atomic, write_text_atomic

    def full(fh) -> None:
        fh.write(b"half")
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    f = write_text_atomic(tmp_path / "a.txt", "old")
    with pytest.raises(WriteError, match=rf"^{f}: cannot be written \(No space left on device\); "
                       "the previous file is left whole$"):
        write_atomic(f, full)
    assert f.read_text() == "old" and sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]
    out = tmp_path / "out"
    with output_folder(out, kind="test") as tmp:
        (tmp / "x").write_text("old")
    with pytest.raises(WriteError, match=rf"^--out {out}: x.npz: cannot be written \(No space "
                       r"left on device\); its previous content is left whole$"):
        with output_folder(out, kind="test") as tmp:
            write_atomic(tmp / "x.npz", full)
    assert (out / "x").read_text() == "old"
    assert not list(tmp_path.glob(".out.tmp-*"))


def test_outcome_stdout_closed(tmp_path: Path) -> None:
    r, w = os.pipe()
    os.close(r)  # the reader is gone before the first line
    try:
        p = _irnuc(["calibrate", "--frames", str(_frames(tmp_path / "a.npz")), "--out",
                    str(tmp_path / "cal")], tmp_path, stdout=w)
    finally:
        os.close(w)
    line = _one_error_line(p.stderr)
    assert p.returncode == 2
    assert line.startswith("irnuc calibrate: error: stdout: cannot be written (the reader closed it)")


def test_outcome_stdout_closed_at_start(tmp_path: Path) -> None:
    def close_stdout() -> None:
        os.close(1)

    frames = str(_frames(tmp_path / "a.npz"))
    p = _irnuc(["calibrate", "--frames", frames, "--out", str(tmp_path / "cal")], tmp_path,
               preexec_fn=close_stdout)
    line = _one_error_line(p.stderr)
    assert p.returncode == 2, line
    assert line.startswith("irnuc calibrate: error: stdout: cannot be written (it is closed)")
    assert not (tmp_path / "cal").exists() and not list(tmp_path.glob(".cal*"))
    q = _irnuc(["calibrate", "-q", "--frames", frames, "--out", str(tmp_path / "cal")], tmp_path,
               preexec_fn=close_stdout)
    assert q.returncode == 0 and q.stderr == "", q.stderr
    from irnuc.nuc_fixed.memimage import read_memimage

    read_memimage(tmp_path / "cal", "typical14")  # whole


def test_outcome_ffc_without_a_good_pixel(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                          ) -> None:
    from irnuc.cli import main
    from irnuc.cocotb_tests.method_stim import random_coefficients
    from irnuc.model.fpa_sensor import FpaSensor, frame_fields
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.memimage import write_method_image
    from irnuc.nuc_fixed.method_top import MethodCoefficients

    cfg = load_pipeline("ffc14")
    rng = np.random.default_rng(3)
    c = random_coefficients(cfg, 4, 5, rng)
    fields = {m: {**v, "bad": np.ones((4, 5), bool)} for m, v in c.fields.items()}
    write_method_image(tmp_path / "cal", MethodCoefficients(cfg, fields, c.registers),
                       fpa_sensor=FpaSensor())
    n = cfg.ffc_frames
    shut = np.r_[np.zeros(1, bool), np.ones(n, bool), np.zeros(2, bool)]
    codes = rng.integers(4000, 6000, (shut.size, 4, 5)).astype(np.uint16)
    t = np.full(shut.size, 300.0)
    ff = frame_fields(np.arange(shut.size) / 30.0, t, t, t, shut, FpaSensor())
    np.savez(tmp_path / "f.npz", codes=codes, temps=t, adc_bits=np.int64(14), **ff,
             **FpaSensor().arrays())
    assert main(["correct", "-q", "--frames", str(tmp_path / "f.npz"), "--coeffs",
                 str(tmp_path / "cal"), "--out", str(tmp_path / "corr")]) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "1 FFC refresh(es) kept the previous offsets" in err[0], err
    with np.load(tmp_path / "corr" / "corrected.npz") as z:
        assert z["ffc_kept"].tolist() == z["ffc_refreshes"].tolist() == [n]
        assert not z["ffc_offset"].any()  # the offsets before: none yet


def test_outcome_stdout_full(tmp_path: Path) -> None:
    if not Path("/dev/full").exists():
        pytest.skip("no /dev/full here")
    with open("/dev/full", "w") as full:
        p = _irnuc(["calibrate", "--frames", str(_frames(tmp_path / "a.npz")), "--out",
                    str(tmp_path / "cal")], tmp_path, stdout=full)
    line = _one_error_line(p.stderr)
    assert p.returncode == 2
    assert line.startswith("irnuc calibrate: error: stdout: cannot be written (No space left")
    from irnuc.nuc_fixed.memimage import read_memimage

    read_memimage(tmp_path / "cal", "typical14")  # whole: every file checks against the manifest


def test_outcome_frames_some_solves_fail(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from irnuc.cli import main

    out = tmp_path / "f"
    # A positive TCR near runaway with a 5 % parameter spread: some pixels have no
    # equilibrium below the runaway temperature, the others do (the pulse train's periodic
    # state runs away a little above the single pulse's bias: 3.1e-5 A fails about a fifth).
    assert main(["frames", "-q", "--set", "fpa.active_rows=4", "--set", "fpa.active_cols=4",
                 "--set", "bolometer.tcr=0.02", "--set", "bolometer.bias_current=3.1e-5",
                 "--set", "fpa.tolerance={R_ref = 0.05, g = 0.05, C = 0.05}",
                 "--out", str(out)]) == 0
    err = capsys.readouterr().err
    with np.load(out / "frames.npz") as z:
        assert {"codes", "temps", "defect_kind", "defect_pattern", "adc_bits", "seed",
                "config_json", "diagnostics_json"} <= set(z.files)
        assert "status" not in z.files  # no status written
        d = json.loads(str(z["diagnostics_json"]))["solver_failures"]
    n = d["runaway"]
    assert 0 < n < 100 and not d["no_convergence"] and not d["invalid"]
    # The failures of the whole array (4 x 4 active pixels and their blind surround).
    assert err.splitlines() == [f"irnuc frames: warning: {n} of 100 pixel solves failed "
                                "(runaway); those pixels read the high rail"], err


def test_outcome_report_checks_nothing() -> None:
    from irnuc.reports.report.base import Report
    from irnuc.reports.report.summary import make_summary

    rep = Report(config={"name": "x"}, verbose=False)
    rep.metric("calibration.bad_pixels", 3, "lower")
    base = {"metrics": {"other.metric": {"value": 1.0, "better": "lower"}}}
    s = make_summary(rep, [], base, "base.json")
    assert s["baseline"]["compared"] == 0 and s["baseline"]["new"] == ["calibration.bad_pixels"]
    assert s["status"] == "fail"
    assert any("nothing was checked against it" in r for r in s["status_reasons"])
    # The same run against a baseline holding its metric: compared, and a pass.
    same = {"metrics": {"calibration.bad_pixels": {"value": 3, "better": "lower"}}}
    assert make_summary(rep, [], same, "base.json")["status"] == "pass"
    info = Report(config={"name": "x"}, verbose=False)
    info.metric("cosim.tests", 4, "info")
    s = make_summary(info, [], None, None)
    assert s["status"] == "fail" and s["status_reasons"] == [
        "the report measured nothing that can pass or fail"]


def test_every_outcome_is_tested() -> None:
    tests = {n.removeprefix("test_outcome_") for n in globals() if n.startswith("test_outcome_")}
    assert tests == set(OUTCOMES)
