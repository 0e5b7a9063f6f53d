"""The sign-off verdict apart from the regression status (issue 37, item 3): the verdict of
hand-built Temperature sections (met; not met by the residual, by Fmax at the best placer
seed, by the co-simulation; not run), summary.json's ``signoff`` against the schema, the
sign-off's own JUnit testcase, and ``--baseline``'s comparison of the verdicts, an old
baseline without one included."""

from __future__ import annotations

import copy
import json
import xml.etree.ElementTree as ET

import jsonschema
import pytest

from irnuc.common.schema import SchemaError
from irnuc.reports.report.base import Report
from irnuc.reports.report.phases import temperature as tp
from irnuc.reports.report.render import status_line
from irnuc.reports.report.run import signoff_junit
from irnuc.reports.report.sections import TemperatureSection, Verdict
from irnuc.reports.report.summary import (
    SCHEMA_PATH,
    compare_signoff,
    load_baseline,
    make_summary,
    validate_summary,
)
from irnuc.reports.studies.hwcost import coefficient_memory

TOL = "0.5 x NETD = 15.6 mK (tolerance_netd)"


def _synth(best: float, worst: float, target: float = 150.0) -> dict:
    return {"top": "irnuc_axis_top", "fmax_mhz": best, "target_mhz": target,
            "xc7": {}, "ecp5": {}, "why": "",
            "seeds": {"runs": 4, "best_mhz": best, "best_seed": 3, "worst_mhz": worst,
                      "worst_seed": 1, "at_target": int(best >= target) + int(worst >= target)}}


def _cosim(mismatches: int = 0) -> dict:
    return {"frames": 20, "shape": [480, 640], "pixels_compared": 6144000,
            "mismatches": mismatches, "passed": mismatches == 0, "source": "x", "seconds": 1.0,
            "ffc_events": 2, "top": "irnuc_axis_top"}


def _section(worst: float = 12.0, synth: dict | None = None, cosim: dict | None = None) -> dict:
    """A Temperature section as the phase makes it: the tolerance 15.6 mK (0.5 x NETD)."""
    rec = {"key": "tcgain14_f14", "config": "tcgain14", "method": "tc_gain", "frac_bits": 14,
           "widths": {"gain": "18 bits"}, "ffc_period_min": None, "worst_fpn_mK": worst,
           "worst_fpn_lsb": worst / 10, "netd_mK": 31.2, "tolerance_mK": 15.6,
           "meets_tolerance": worst <= 15.6, "memory_bits": 40, "bandwidth_MBps": 90.0,
           "edges": [], "pipeline": {}, "memory": coefficient_memory(40, 480, 640),
           "synth": synth, "cosim": cosim}
    pt = {"index": 0, "key": "tcgain14_f14", "config": "tcgain14", "method": "tc_gain",
          "frac_bits": 14, "valid": True, "worst_fpn_mK": worst, "worst_fpn_lsb": worst / 10,
          "memory_bits": 40, "meets_tolerance": worst <= 15.6}
    return {"spec": {}, "points": [pt], "netd_mK": 31.2, "netd": {}, "tolerance_mK": 15.6,
            "tolerance": TOL, "noise_3d": {"components": {}}, "camera_temperature": {},
            "fronts": {"memory_bits": {}, "datapath_cost": None, "bandwidth_MBps": {}},
            "recommended": rec, "cost": None}


# ---- the verdict -------------------------------------------------------------------------------
def test_met_when_every_check_is_met() -> None:
    v = tp.signoff_verdict(_section(12.0, _synth(152.3, 141.0), _cosim()))
    assert v.verdict == "met" and v.recommendation == "tcgain14_f14"
    assert [(c.name, c.status) for c in v.checks] == [("residual", "met"), ("fmax", "met"),
                                                      ("cosim", "met")]
    assert v.reason == "tcgain14_f14: 12 mK <= tolerance 15.6 mK (0.5 x NETD)"


def test_not_met_by_the_residual() -> None:
    v = tp.signoff_verdict(_section(28.4, _synth(152.3, 152.3), _cosim()))
    assert v.verdict == "not met"
    assert v.reason.startswith("tcgain14_f14: 28.4 mK > tolerance 15.6 mK (0.5 x NETD)")
    assert "MHz" not in v.reason and "co-simulated" not in v.reason  # only what missed


def test_not_met_by_fmax_at_the_best_seed() -> None:
    v = tp.signoff_verdict(_section(12.0, _synth(148.0, 139.5), _cosim()))
    assert v.verdict == "not met"
    assert v.reason == "irnuc_axis_top 148.0 MHz at the best of 4 placer seeds (seed 3) < 150 MHz"
    # A target met at the best seed only is met (the seed spread is the report's note).
    assert tp.signoff_verdict(_section(12.0, _synth(150.0, 120.0), _cosim())).verdict == "met"
    # One placement (no seed sweep): its Fmax is the figure.
    one = {**_synth(149.9, 149.9), "seeds": None}
    assert tp.signoff_verdict(_section(12.0, one, None)).checks[1].status == "not met"


def test_not_met_by_the_cosimulation_and_every_miss_named() -> None:
    v = tp.signoff_verdict(_section(12.0, _synth(160.0, 155.0), _cosim(mismatches=3)))
    assert v.verdict == "not met"
    assert v.reason == "co-simulated through irnuc_axis_top: 3 mismatch(es) of 6144000 pixels"
    both = tp.signoff_verdict(_section(28.4, _synth(148.0, 140.0), _cosim(mismatches=3)))
    assert [c.status for c in both.checks] == ["not met"] * 3
    assert both.reason.count("; ") == 2


def test_not_run_and_checks_that_did_not_run() -> None:
    assert tp.signoff_verdict(None).verdict == "not run"
    # Synthesis and co-simulation switched off: met on the residual, the rest named.
    v = tp.signoff_verdict(_section(12.0))
    assert v.verdict == "met" and v.reason.endswith("(not checked: fmax, cosim)")
    # A composition without RTL: the co-simulation did not run, never a pass.
    nr = {**_cosim(), "passed": None, "mismatches": None, "not_run": "no RTL for table_interp"}
    c = tp.signoff_verdict(_section(12.0, None, nr)).checks[2]
    assert c.status == "not run" and "table_interp" in c.detail
    # No valid point: nothing recommended, not met.
    empty = {**_section(), "recommended": None}
    assert tp.signoff_verdict(empty).verdict == "not met"
    with pytest.raises(ValueError, match="verdict"):
        Verdict("maybe", "x")


# ---- summary.json ------------------------------------------------------------------------------
def _report(d: dict | None) -> Report:
    rep = Report(config={}, verbose=False)
    rep.metric("cosim.failed", 0, "lower")  # something that can fail: the regression passes
    if d is not None:
        rep.sections["temperature"] = TemperatureSection.of(d, verdict=tp.signoff_verdict(d))
    return rep


def test_summary_carries_the_verdict_apart_from_the_status() -> None:
    s = make_summary(_report(_section(28.4, _synth(152.0, 150.0), _cosim())), [], None, None)
    assert s["status"] == "pass"  # the regression status is what it was
    assert s["signoff"]["verdict"] == "not met" and "28.4 mK > tolerance" in s["signoff"]["reason"]
    assert s["sections"]["temperature"]["verdict"] == s["signoff"]
    assert validate_summary(s).startswith("valid")
    assert status_line(s).startswith("regression: pass · sign-off: not met (tcgain14_f14: 28.4 mK")
    schema = json.loads(SCHEMA_PATH.read_text())
    for key, value in (("verdict", "maybe"), ("reason", "")):
        bad = copy.deepcopy(s)
        bad["signoff"][key] = value
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(bad, schema)
    bad = copy.deepcopy(s)
    del bad["signoff"]
    with pytest.raises(jsonschema.ValidationError, match="signoff"):
        jsonschema.validate(bad, schema)
    none = make_summary(_report(None), [], None, None)
    assert none["signoff"]["verdict"] == "not run" and none["status"] == "pass"
    validate_summary(none)


# ---- junit.xml ---------------------------------------------------------------------------------
REGRESSION = """<testsuites><testsuite name="minimal" tests="1" failures="0" errors="0">
<testcase classname="minimal" name="test_top" time="1.000"/></testsuite></testsuites>
"""


def _shape(tc) -> tuple:
    return tc.tag, dict(tc.attrib), [(k.tag, dict(k.attrib), k.text) for k in tc]


def _cases(path) -> dict:
    root = ET.parse(path).getroot()
    return {(tc.get("classname"), tc.get("name")): tc for tc in root.iter("testcase")}


@pytest.mark.parametrize("verdict,child", [("met", None), ("not met", "failure"),
                                           ("not run", "skipped")])
def test_the_signoff_testcase_beside_the_regression(tmp_path, verdict, child) -> None:
    path = tmp_path / "junit.xml"
    path.write_text(REGRESSION)
    before = _shape(_cases(path)[("minimal", "test_top")])
    signoff_junit(path, {"verdict": verdict, "reason": "tcgain14_f14: 28.4 mK > tolerance"}, True)
    cases = _cases(path)
    assert set(cases) == {("minimal", "test_top"), ("signoff", "temperature")}
    assert _shape(cases[("minimal", "test_top")]) == before  # unchanged
    tc = cases[("signoff", "temperature")]
    kids = [k.tag for k in tc if k.tag in ("failure", "skipped", "error")]
    assert kids == ([child] if child else [])
    if child == "failure":
        assert "28.4 mK > tolerance" in tc.find("failure").get("message")
    suite = ET.parse(path).getroot().find("testsuite[@name='signoff']")
    assert suite.get("failures") == str(int(verdict == "not met"))


def test_signoff_junit_without_a_regression_file_and_an_ingested_testsuite(tmp_path) -> None:
    path = tmp_path / "junit.xml"
    signoff_junit(path, {"verdict": "not run", "reason": "x"}, False)
    assert not path.exists()  # no co-simulation, no sign-off: no file
    signoff_junit(path, {"verdict": "not met", "reason": "x"}, True)
    assert list(_cases(path)) == [("signoff", "temperature")]
    # An ingested --junit whose root is one <testsuite>: kept, wrapped.
    path.write_text('<testsuite name="pytest" tests="1"><testcase classname="a" name="b"/></testsuite>')
    signoff_junit(path, {"verdict": "met", "reason": "x"}, True)
    root = ET.parse(path).getroot()
    assert root.tag == "testsuites" and [s.get("name") for s in root] == ["pytest", "signoff"]


# ---- --baseline --------------------------------------------------------------------------------
def test_compare_signoff_verdicts() -> None:
    met = {"verdict": "met", "reason": "ok"}
    miss = {"verdict": "not met", "reason": "28.4 mK > tolerance"}
    r = compare_signoff(miss, met)
    assert r["change"] == "regressed" and r["regressed"] and "28.4 mK" in r["text"]
    assert compare_signoff(met, miss)["change"] == "improved"
    assert compare_signoff(miss, miss)["change"] == "unchanged"
    assert compare_signoff(met, {"verdict": "not run", "reason": "x"})["change"] == "changed"
    old = compare_signoff(met, None)
    assert old["text"] == "no sign-off in the baseline" and not old["regressed"]


def _baseline(tmp_path, signoff: dict | None):
    s = {"schema_version": 2, "tool": "irnuc report", "metrics": {"cosim.failed": {
        "value": 0, "better": "lower"}}, "provenance": {"config_name": None, "config_hash": "h"}}
    if signoff is not None:
        s["signoff"] = signoff
    path = tmp_path / "base.json"
    path.write_text(json.dumps(s))
    return path


def test_baseline_sign_off_regression_is_shown_apart(tmp_path) -> None:
    rep = _report(_section(28.4, _synth(152.0, 150.0), _cosim()))
    path = _baseline(tmp_path, {"verdict": "met", "reason": "12 mK <= tolerance"})
    s = make_summary(rep, [], load_baseline(path), str(path))
    assert s["baseline"]["regressions"] == [] and s["status"] == "pass"
    assert s["baseline"]["signoff"]["regressed"]
    assert s["baseline"]["signoff"]["baseline_reason"] == "12 mK <= tolerance"
    validate_summary(s)


def test_old_baseline_without_signoff_is_accepted(tmp_path) -> None:
    rep = _report(_section(12.0))
    path = _baseline(tmp_path, None)
    s = make_summary(rep, [], load_baseline(path), str(path))
    assert s["baseline"]["signoff"]["text"] == "no sign-off in the baseline"
    assert s["baseline"]["signoff"]["change"] == "no baseline sign-off"
    validate_summary(s)
    bad = _baseline(tmp_path, {"verdict": "sideways", "reason": "x"})
    with pytest.raises(SchemaError, match=r"signoff\.verdict"):
        load_baseline(bad)
