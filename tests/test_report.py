"""``irnuc report`` on a small configuration: the HTML is one self-contained file with the
figures, summary.json validates against the shipped schema, a planted regression and a
failing co-simulation test give a non-zero exit status, and sections appear only with data."""

from __future__ import annotations

import copy
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from irnuc.cli import main
from irnuc.reports import report

SMALL = Path(report.__file__).with_name("report_small.toml")

JUNIT_PASS = """<?xml version="1.0" encoding="utf-8"?>
<testsuites><testsuite name="pytest" tests="2" failures="0" errors="0" skipped="0">
<testcase classname="cocotb_tests.test_nuc_core" name="test_nuc_core[typical14-corner_codes]" time="1.5"/>
<testcase classname="cocotb_tests.test_dpc_core" name="test_dpc_core[typical14-borders]" time="2.0"/>
</testsuite></testsuites>
"""
JUNIT_FAIL = JUNIT_PASS.replace(
    'time="2.0"/>', 'time="2.0"><failure message="mismatch at frame 0, x 3, y 1">expected 5 got 6'
    '</failure></testcase>')


def _config(tmp_path: Path) -> Path:
    """The small configuration without the numerical-fidelity phase (that has its own tests)."""
    text = SMALL.read_text()
    assert "[precision]\nquick = true\n" in text
    path = tmp_path / "small_no_precision.toml"
    path.write_text(text.replace("[precision]\nquick = true\n", ""))
    assert "precision" not in report.load_report_config(str(path))
    return path


@pytest.fixture(scope="module")
def small_run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("report")
    junit = tmp / "cosim.xml"
    junit.write_text(JUNIT_PASS)
    cfg = _config(tmp)
    out = tmp / "out"
    rc = main(["report", "--config", str(cfg), "--out", str(out), "--junit", str(junit)])
    return rc, out, cfg, junit


def test_report_passes_and_writes_outputs(small_run) -> None:
    rc, out, _, _ = small_run
    assert rc == 0
    assert {p.name for p in out.iterdir() if not p.name.startswith(".")} == {
        "index.html", "summary.json", "junit.xml", "recommended.toml"}
    # The recommended widths as a pipeline configuration that loads.
    from irnuc.nuc_fixed import load_pipeline

    cfg = load_pipeline(str(out / "recommended.toml"))
    rec = json.loads((out / "summary.json").read_text())["sections"]["sweep"]["recommended"]
    assert (cfg.gain_frac_bits, cfg.offset_frac_bits) == (rec["gain_frac_bits"], rec["offset_frac_bits"])


def test_html_is_self_contained_with_figures(small_run) -> None:
    _, out, _, _ = small_run
    h = (out / "index.html").read_text()
    pngs = re.findall(r"src='data:image/png;base64,([A-Za-z0-9+/=]+)'", h)
    # calibration 1, sweep 2, paper 3 (Table 2, comparison, Table 1), run times 1
    assert len(pngs) == 7
    # One stylesheet, inlined; no f-string leftovers of an unrendered template.
    assert h.count("<style>") == 1 and "{{" not in h and "{%" not in h
    import base64

    assert all(base64.b64decode(p)[:8] == b"\x89PNG\r\n\x1a\n" for p in pngs)
    # Nothing is fetched from elsewhere: no external scripts, stylesheets or images.
    assert not re.search(r"(src|href)=['\"](https?:|//|file:)", h)
    for anchor in ("calibration", "sweep", "paper", "cosim", "provenance"):
        assert f"id='{anchor}'" in h
    assert "id='precision'" not in h and "id='baseline'" not in h


def test_summary_validates_against_schema(small_run) -> None:
    jsonschema = pytest.importorskip("jsonschema")
    _, out, _, _ = small_run
    summary = json.loads((out / "summary.json").read_text())
    schema = json.loads(report.SCHEMA_PATH.read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    jsonschema.validate(summary, schema)
    assert summary["schema_validation"].startswith("valid")
    # The schema can fail: a broken summary is rejected.
    bad = copy.deepcopy(summary)
    bad["metrics"]["calibration.precision"]["better"] = "sideways"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(bad, schema)


def test_summary_contents(small_run) -> None:
    _, out, _, _ = small_run
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "pass"
    assert set(s["sections"]) == {"calibration", "sweep", "paper", "cosim"}
    assert set(s["phases"]) == {"frames", "calibration", "sweep", "paper", "cosim"}
    rec = s["sections"]["sweep"]["recommended"]
    assert rec["bits_per_pixel"] == s["sections"]["sweep"]["smallest"]["bits_per_pixel"]
    assert rec["cosim"] is None and rec["synth"] is None  # --junit ingested, no [synth]
    assert rec["memory"]["bits_per_frame"] == rec["bits_per_pixel"] * 32 * 48
    prov = s["provenance"]
    assert prov["seeds"] == {"sensor": 1, "sweep": 2, "paper": 3}
    assert re.fullmatch(r"[0-9a-f]{16}", prov["config_hash"])
    for k in ("python", "numpy", "numba", "cocotb", "verilator"):
        assert k in prov["versions"]
    c = s["sections"]["cosim"]
    assert (c["tests"], c["passed"], c["failed"]) == (2, 2, 0)
    d = s["sections"]["calibration"]["detection"]
    assert d["precision"] > 0.9 and d["recall"] > 0.9
    assert s["metrics"]["calibration.precision"]["value"] == d["precision"]
    assert s["sections"]["sweep"]["smallest"]["found"]
    assert len(s["sections"]["paper"]["variants"]) >= 2


def test_labels_and_widths_come_from_the_types(small_run) -> None:
    """Every label and width the report shows is the one the typed point gives
    (SweepPoint.record: FixedFormat's text, the configuration's widths), and the report's
    code re-derives none from integer fields."""
    from irnuc.nuc_fixed import gain_format, offset_format
    from irnuc.reports.studies.sweep import SweepPoint

    _, out, _, _ = small_run
    s = json.loads((out / "summary.json").read_text())
    fields = SweepPoint.__dataclass_fields__
    h = (out / "index.html").read_text()
    for p in s["sections"]["sweep"]["points"]:
        pt = SweepPoint(**{k: p[k] for k in fields})
        cfg = pt.config(*s["sections"]["sweep"]["frame"])
        g, o = gain_format(cfg), offset_format(cfg)
        assert (p["label"], p["gain_format"], p["offset_format"]) == (f"{g} / {o}", str(g), str(o))
        assert (p["gain_bits"], p["offset_bits"], p["bits_per_pixel"]) == (
            cfg.gain_bits, cfg.offset_bits, cfg.word_bits)
        assert f"sweep.point.{p['key']}.err_max_lsb" in s["metrics"]
        assert f"<td class='l'>{p['label']}</td>" in h
    rec = s["sections"]["sweep"]["recommended"]
    assert f"gain {rec['gain_format']}, offset" in h
    # No label or width built from the integer fields anywhere in the report's code.
    code = [*Path(report.__file__).parent.rglob("*.py"),
            *Path(report.__file__).parent.rglob("*.j2")]
    pattern = re.compile(r"[US]\{[^}]*int_bits|int_bits\W+\s*\+|\.gain_int_bits \}\}")
    hits = [f"{f.name}: {m.group(0)}" for f in code for m in pattern.finditer(f.read_text())]
    assert not hits, hits


def test_planted_regression_is_caught(small_run, tmp_path, capsys) -> None:
    _, out, cfg, junit = small_run
    base = json.loads((out / "summary.json").read_text())
    # Plant: the baseline claims a better sweep error and a higher recall than this code gives.
    base["metrics"]["sweep.best_err_max_lsb"]["value"] *= 0.5
    base["metrics"]["calibration.recall"]["value"] = 1.0 + 1e-3
    bpath = tmp_path / "baseline.json"
    bpath.write_text(json.dumps(base))
    out2 = tmp_path / "out2"
    rc = main(["report", "--config", str(cfg), "--out", str(out2), "--junit", str(junit),
               "--baseline", str(bpath)])
    assert rc == 1
    s = json.loads((out2 / "summary.json").read_text())
    regressed = {e["metric"] for e in s["baseline"]["regressions"]}
    # Exactly the planted ones: the run is deterministic, every other metric matches.
    assert regressed == {"sweep.best_err_max_lsb", "calibration.recall"}
    assert s["status"] == "fail" and s["baseline"]["compared"] > 20
    assert "id='baseline'" in (out2 / "index.html").read_text()
    assert "regressed" in capsys.readouterr().err


def test_failing_cosim_fails_the_report_and_sections_follow_data(tmp_path) -> None:
    junit = tmp_path / "fail.xml"
    junit.write_text(JUNIT_FAIL)
    cfg = tmp_path / "only_cosim.toml"
    cfg.write_text('name = "only-cosim"\n')
    out = tmp_path / "o"
    rc = main(["report", "--config", str(cfg), "--out", str(out), "--junit", str(junit)])
    assert rc == 1
    s = json.loads((out / "summary.json").read_text())
    assert set(s["sections"]) == {"cosim"} and set(s["phases"]) == {"cosim"}
    assert s["sections"]["cosim"]["failed"] == 1
    h = (out / "index.html").read_text()
    assert "id='cosim'" in h and "id='sweep'" not in h and "id='calibration'" not in h
    assert "mismatch at frame 0, x 3, y 1" in h


def test_no_cosim_leaving_nothing_to_run_is_an_error(tmp_path, capsys) -> None:
    # Only [cosim], skipped: the report would check nothing, so it is no PASS (issue 19).
    cfg = tmp_path / "empty.toml"
    cfg.write_text('name = "empty"\n[cosim]\npipelines = ["minimal"]\ntests = ["corner_codes"]\n')
    out = tmp_path / "o"
    assert main(["report", "--config", str(cfg), "--out", str(out), "--no-cosim"]) == 2
    assert "no phase to run" in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize(("better", "base", "now", "regress"), [
    ("lower", 1.0, 1.1, True), ("lower", 1.0, 0.9, False), ("lower", 1.0, 1.0 + 1e-9, False),
    ("higher", 0.9, 0.8, True), ("higher", 0.9, 0.95, False),
    ("equal", 5, 6, True), ("equal", 5, 5, False),
    ("info", 1.0, 100.0, False),
    ("lower", 3, None, True), ("lower", None, 3, False),
])
def test_compare_baseline_direction_aware(better, base, now, regress) -> None:
    rep = report.Report(config={})
    rep.metric("m", now, better)
    cmp = report.compare_baseline(rep.metrics, {"m": {"value": base, "better": better}})
    assert bool(cmp["regressions"]) == regress


def test_missing_and_new_metrics_are_listed_not_skipped() -> None:
    rep = report.Report(config={})
    rep.metric("sweep.best_err_max_lsb", 0.5, "lower")
    cmp = report.compare_baseline(rep.metrics, {"cosim.failed": {"value": 0, "better": "lower"},
                                                "time.sweep": {"value": 1.0, "better": "info"}})
    assert cmp["regressions"] == [] and cmp["missing"] == ["cosim.failed"]
    assert cmp["new"] == ["sweep.best_err_max_lsb"]


@pytest.mark.parametrize(("text", "match"), [
    ('[sweep]\npreset = "default"\nseed = -1\n', "sweep.seed = -1"),
    ('[cosim]\npipelines = ["minimal"]\ntests = [3]\n', "cosim.tests[0]"),
    ('[cosim]\npipelines = ["minimal"]\ntests = ["corner_code"]\n', "did you mean 'corner_codes'"),
    ('[cosim]\npipelines = ["recommended"]\ntests = ["corner_codes"]\n', "no [sweep]"),
    ('[cosim]\npipeline = ["minimal"]\ntests = ["corner_codes"]\n', "did you mean 'pipelines'"),
    ('[precison]\nquick = true\n', "did you mean 'precision'"),
    ('[quick]\n"sweep.rows" = 3\n', "sweep is not a table"),
    ('[paper]\npreset = "paper"\nseed = 1\nrows = 8\ncols = 8\nfrac_bits = [3, 4]\n'
     'reference_nu = [0.1]\ngrid_temps = [300.0]\n', "paper.reference_nu has 1 values"),
])
def test_bad_config_is_a_clear_error(tmp_path, capsys, text, match) -> None:
    cfg = tmp_path / "bad.toml"
    cfg.write_text(text)
    assert main(["report", "--config", str(cfg), "--out", str(tmp_path / "o")]) == 2
    assert match in capsys.readouterr().err


def test_bad_junit_and_unknown_config(tmp_path, capsys) -> None:
    bad = tmp_path / "bad.xml"
    bad.write_text("<html/>")
    cfg = tmp_path / "e.toml"
    cfg.write_text('name = "e"\n')
    assert main(["report", "--config", str(cfg), "--junit", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "expected <testsuites>" in capsys.readouterr().err
    assert main(["report", "--config", "nonesuch", "--out", str(tmp_path / "o")]) == 2
    assert "neither an embedded configuration" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_quick_overrides_apply() -> None:
    full = report.load_report_config("default")
    quick = report.load_report_config("default", quick=True)
    assert quick["sweep"]["rows"] < full["sweep"]["rows"] and quick["quick"] is True


def test_report_imports_no_dev_only_package() -> None:
    code = ("import sys, irnuc.reports.report, irnuc.reports.studies.sweep, irnuc.cli; "
            "bad = [m for m in ('distributed', 'dask', 'pytest', 'hypothesis') "
            "if m in sys.modules]; print(bad); sys.exit(1 if bad else 0)")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr


def test_background_work_runs_niced_with_its_pool_workers() -> None:
    """Work started beside the phases runs at a lower priority: its thread, the processes
    it starts and the workers of the pools it opens (so a phase keeps its core); the
    report's own thread keeps its priority."""
    import os
    import subprocess
    import sys
    import threading

    from irnuc.common.executor import open_executor
    from irnuc.reports.report.base import Report

    def nice_of(pid: int) -> int:
        return os.getpriority(os.PRIO_PROCESS, pid)

    main_nice = nice_of(threading.get_native_id())
    seen = {}

    def job() -> None:
        seen["thread"] = nice_of(threading.get_native_id())
        seen["child"] = int(subprocess.run(
            [sys.executable, "-c", "import os; print(os.nice(0))"], capture_output=True,
            text=True, check=True).stdout)
        with open_executor(1) as h:
            seen["worker"] = h.executor.submit(os.nice, 0).result()

    rep = Report(config={}, verbose=False)
    rep.start_background("job", job)
    rep.close_background()
    assert "error" not in rep.background["job"], rep.background["job"]
    want = min(19, main_nice + 10)
    assert seen == {"thread": want, "child": want, "worker": min(19, want)}
    assert nice_of(threading.get_native_id()) == main_nice
    with open_executor(1) as h:  # a pool opened by the report's thread: not niced
        assert h.executor.submit(os.nice, 0).result() == os.nice(0)
