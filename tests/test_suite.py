"""The co-simulation suite as a Python API (``irnuc.verif.run_suite``): results per test,
metrics from the scoreboard, JUnit, coverage, and a timeout that stops only its own test
and leaves no simulator running."""

from __future__ import annotations

import json
import os
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from irnuc import cosim
from irnuc.cocotb_tests import tb_top
from irnuc.cosim import coverage
from irnuc.nuc_fixed import load_pipeline
from irnuc.verif import SuiteCase, run_suite

pytestmark = [pytest.mark.cosim, pytest.mark.slow]

TB_TOP = tb_top.__name__

#: The configuration the tiny report (tests/test_report_e2e.py) recommends and co-simulates
#: with coverage: U0.8 gain, S4.1 offset on the minimal pipeline's 8-bit input and 6-bit
#: output, 16 x 12 frames. The coverage test below runs on it so that the two share one
#: coverage build (builds are cached by name, parameters and options); any configuration
#: would check the same. test_report_e2e checks that it is still the recommendation.
TINY_RECOMMENDED = load_pipeline("minimal").replace(
    name="recommended", gain_int_bits=0, gain_frac_bits=8, offset_int_bits=3, offset_frac_bits=0,
    max_width=16, max_height=12)


def _simulators(under: Path) -> list[int]:
    """PIDs of running Verilated cocotb models (their executable is the top's name) working
    in a folder under ``under`` (not those of other tests running in parallel)."""
    pids = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                exe = os.readlink(f"/proc/{d}/exe")
                cwd = os.readlink(f"/proc/{d}/cwd")
            except OSError:
                continue
            if exe.endswith("/nuc_dpc_top") and cwd.startswith(str(under)):
                pids.append(int(d))
    return pids


def test_suite_runs_each_test_and_keeps_metrics(tmp_path) -> None:
    case = SuiteCase("nuc_dpc_top", load_pipeline("minimal"), TB_TOP,
                     tests=("corner_codes", "checker_detects_mismatch"))
    res = run_suite([case], tmp_path)
    assert [o.test for o in res.outcomes] == ["corner_codes", "checker_detects_mismatch"]
    assert res.passed, [(o.test, o.status, o.message) for o in res.outcomes]
    corner = res.outcomes[0]
    assert corner.metrics and corner.metrics[0]["compared"] > 0
    assert corner.metrics[0]["errors"] == 0 and corner.log is not None
    # The deliberately wrong golden model was caught, and recorded with triage lines.
    wrong = [m for m in res.outcomes[1].metrics if m["errors"] > 0]
    assert wrong and wrong[0]["lines"][0].startswith("frame ")
    tot = res.totals()
    assert tot["tests"] == 2 and tot["passed"] == 2 and tot["pixels"] > 0
    junit = res.write_junit(tmp_path / "junit.xml")
    cases = ET.parse(junit).getroot().findall(".//testcase")
    assert {c.get("name") for c in cases} == {"corner_codes", "checker_detects_mismatch"}


def test_timeout_stops_only_that_test_and_its_simulator(tmp_path) -> None:
    cfg = load_pipeline("minimal")
    case = SuiteCase("nuc_dpc_top", cfg, TB_TOP, tests=("model_frames",))
    cosim.build("nuc_dpc_top", cfg)  # built outside the timer, as run_suite does
    # A limit far below what the test needs: it must end as "timeout", not hang.
    res = run_suite([case], tmp_path, timeout_base=0.3)
    assert [o.status for o in res.outcomes] == ["timeout"]
    assert "stopped" in res.outcomes[0].message
    assert not _simulators(tmp_path), "a simulator survived the timeout"


def test_run_suite_collects_coverage(tmp_path) -> None:
    # One test in the coverage build (the report's end-to-end test runs two more there).
    case = SuiteCase("nuc_dpc_top", TINY_RECOMMENDED, TB_TOP, tests=("frame_error_causes",))
    res = run_suite([case], tmp_path, coverage=True)
    assert res.passed, [(o.test, o.message) for o in res.outcomes]
    label = coverage.config_label(TINY_RECOMMENDED)
    f = res.coverage["functional"]["configurations"][label]
    pts = f["coverpoints"]
    assert pts["frame.error"]["hit"] == pts["frame.error"]["total"]
    assert pts["nuc.round.half_even"]["hit"] > 0
    assert 0 < f["hit"] < f["total"]  # one test does not reach every bin
    code = res.coverage["code"][label]
    assert {"nuc_core", "dpc_core", "dpc_ctrl", "nuc_dpc_top"} <= set(code)
    assert 0 < code["dpc_ctrl"]["line"]["percent"] <= 100
    assert 0 < code["nuc_core"]["toggle"]["percent"] <= 100
    on_disk = json.loads((tmp_path / "coverage.json").read_text())
    assert on_disk["functional"]["configurations"][label]["hit"] == f["hit"]
    # Without coverage=True there is none (a short test, in the plain build).
    plain = SuiteCase("nuc_dpc_top", load_pipeline("minimal"), TB_TOP, tests=("corner_codes",))
    res = run_suite([plain], tmp_path / "plain")
    assert res.passed and res.coverage is None and not (tmp_path / "plain" / "coverage.json").exists()
