"""``irnuc report`` end to end on the tiny configuration (the `minimal` pipeline on a tiny
frame): the recommendation is synthesized and co-simulated bit-exact, the cost model's
error is stated, the HTML shows the fronts and the co-simulation detail; and a report
killed at random points leaves its output folder old or new, whole, and no simulator,
Yosys or nextpnr process behind."""

from __future__ import annotations

import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from irnuc.cli import main
from irnuc.reports import report

pytestmark = pytest.mark.slow

TINY = Path(report.__file__).with_name("report_tiny.toml")


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("tiny") / "out"
    rc = main(["report", "-q", "--config", "tiny", "--out", str(out)])
    return rc, out


def test_recommendation_is_synthesized_and_cosimulated(tiny_run) -> None:
    rc, out = tiny_run
    assert rc == 0
    s = json.loads((out / "summary.json").read_text())
    report.validate_summary(s)
    sw = s["sections"]["sweep"]
    r = sw["recommended"]
    assert r["err_max_lsb"] <= sw["tolerance"]["max_error"]
    # The cheapest meeting the tolerance: nothing with fewer bits per pixel meets it.
    assert all(p["err_max_lsb"] > 1.0 for p in sw["points"] if p["bits_per_pixel"] < r["bits_per_pixel"])
    assert r["cosim"]["failed"] == 0 and r["cosim"]["mismatches"] == 0 and r["cosim"]["pixels"] > 0
    assert r["synth"]["fmax_mhz"] > 0 and r["synth"]["xc7"]["lut"] > 0
    assert r["pipeline"]["gain_frac_bits"] == r["gain_frac_bits"]
    # The suite's time: test_suite's coverage test shares this recommendation's coverage build.
    from tests.test_suite import TINY_RECOMMENDED

    widths = ("gain_int_bits", "gain_frac_bits", "offset_int_bits", "offset_frac_bits",
              "max_width", "max_height")
    assert {k: r["pipeline"][k] for k in widths} == {
        k: getattr(TINY_RECOMMENDED, k) for k in widths}, (
        "the tiny report recommends another configuration: update tests/test_suite.py "
        "TINY_RECOMMENDED so that its coverage test shares the report's build")
    # Every point carries its memory and datapath cost; a few were synthesized.
    assert all(p["hw"] and p["datapath_cost"] is not None for p in sw["points"])
    sources = {p["hw"]["source"] for p in sw["points"]}
    assert sources == {"synthesized", "model"}
    syn = sw["synth"]
    assert len(syn["fit_indices"]) == 3 and syn["model_error_all"]["xc7.lut"]["points"] >= 4
    assert r["index"] in [x["index"] for x in syn["synthesized"]]
    c = s["sections"]["cosim"]
    assert c["source"] == "irnuc.verif.run_suite" and not c["partial"]
    neg = [x for x in c["cases"] if x["negative_control"]]
    assert neg and neg[0]["detected"] > 0 and neg[0]["triage"][0].startswith("frame ")
    for x in c["cases"]:
        assert (out / x["log"]).is_file()  # paths inside the report folder, after the swap
    assert s["metrics"]["synth.recommended.fmax_mhz"]["value"] == r["synth"]["fmax_mhz"]
    # Coverage of the tests the report ran: bins of the recommended configuration, line and
    # toggle coverage of every design module, the merged file in the report folder.
    cov = c["coverage"]
    label = next(iter(cov["functional"]["configurations"]))
    f = cov["functional"]["configurations"][label]
    assert 0 < f["hit"] <= f["total"] and f["coverpoints"]["frame.size"]["hit"] > 0
    assert {"nuc_core", "dpc_core", "dpc_ctrl", "nuc_dpc_top"} <= set(cov["code"][label])
    on_disk = json.loads((out / c["coverage_file"]).read_text())
    assert on_disk["functional"]["configurations"][label]["hit"] == f["hit"]


def test_temperature_section_in_summary_and_html(tiny_run) -> None:
    _, out = tiny_run
    s = json.loads((out / "summary.json").read_text())
    t = s["sections"]["temperature"]
    assert {p["config"] for p in t["points"]} == {"typical14", "ffc14"}
    assert len(t["points"]) == 4 and "temperature" in s["phases"]
    r = t["recommended"]
    # the choice follows the rule: cheapest meeting the tolerance, else the lowest residual
    meeting = [p for p in t["points"] if p["worst_fpn_mK"] <= t["tolerance_mK"]]
    if meeting:
        assert r["meets_tolerance"] and r["memory_bits"] == min(p["memory_bits"] for p in meeting)
    else:
        assert not r["meets_tolerance"]
        assert r["worst_fpn_mK"] == min(p["worst_fpn_mK"] for p in t["points"])
    assert t["tolerance_mK"] == 0.5 * t["netd_mK"]
    assert s["metrics"]["temperature.recommended.worst_fpn_mK"]["value"] == r["worst_fpn_mK"]
    h = (out / "index.html").read_text()
    for text in ("id='temperature'", "against time on each thermal scenario", "housing-FPA",
                 "3D noise", "Camera-temperature test", "Residual against fraction bits per method",
                 "fpa_ramp"):
        assert text in h, text
    # every point judged on the configuration's scenarios, worst over them (issue 37)
    assert list(t["scenarios"]) == ["fpa_ramp"]
    for p in t["points"]:
        assert set(p["scenarios"]) == {"fpa_ramp"} and p["worst_scenario"] == "fpa_ramp"
        assert p["worst_fpn_mK"] == p["scenarios"]["fpa_ramp"]["worst_fpn_mK"]
        assert (p["dead_time_pct"] > 0) == (p["config"] == "ffc14")
    if not r["meets_tolerance"]:
        assert r["breaks"] and r["breaks"][0].startswith("fpa_ramp (")
        assert "fpa_ramp (" in s["signoff"]["reason"]
    # The sign-off verdict apart from the regression status (issue 37): judged on the
    # residual against the tolerance (the tiny configuration neither synthesizes nor
    # co-simulates its recommendation: those checks did not run).
    so = s["signoff"]
    assert so["verdict"] == ("met" if r["meets_tolerance"] else "not met")
    assert t["verdict"] == so and so["recommendation"] == r["key"]
    assert [(c["name"], c["status"]) for c in so["checks"]][1:] == [("fmax", "not run"),
                                                                    ("cosim", "not run")]
    assert f"sign-off: {so['verdict']} (" in h and "Sign-off: <b>" in h
    import xml.etree.ElementTree as ET

    root = ET.parse(out / "junit.xml").getroot()
    cases = {(tc.get("classname"), tc.get("name")): tc for tc in root.iter("testcase")}
    sign = cases.pop(("signoff", "temperature"))
    assert (sign.find("failure") is not None) == (so["verdict"] == "not met")
    assert cases and all(cn != "signoff" for cn, _ in cases)  # the co-simulation's, kept


def test_html_shows_fronts_costs_and_cosim_detail(tiny_run) -> None:
    _, out = tiny_run
    h = (out / "index.html").read_text()
    for text in ("id='synth'", "Cost, broken down", "RAMB36E1", "Pareto fronts", "Triage lines",
                 "negative control", "Functional coverage", "Code coverage", "Mutation",
                 "recommended.toml"):
        assert text in h, text
    run_id = json.loads((out / "summary.json").read_text())["provenance"]["run_id"]
    assert f"content='{run_id}'" in h


def test_coverage_and_mutation_condensed_and_rendered(monkeypatch) -> None:
    """The report condenses what irnuc.cosim measured (coverage of a suite run, the cached
    mutation campaign) and shows it: uncovered bins and missed lines by name, every mutant
    with its status and killing test, the equivalent ones with their arguments."""
    import types

    from irnuc.cosim import coverage as cov
    from irnuc.reports.report import render
    from irnuc.reports.report.phases import cosim as phase
    from irnuc.verif import mutate

    snap = {"version": 1, "configurations": {"minimal": {"config_digest": "d", "tops": ["t"],
            "coverpoints": {"dpc.n": {"kind": "point", "bins": {"0": 2, "8": 0},
                                      "removed": {"9": "at most 8 neighbours"}}}}}}
    dat = {("v_line", "dpc_ctrl", "dpc_ctrl.sv", "10", "", ""): 3,
           ("v_line", "dpc_ctrl", "dpc_ctrl.sv", "12", "", ""): 0,
           ("v_toggle", "dpc_ctrl", "dpc_ctrl.sv", "14", "", ""): 1}
    result = types.SimpleNamespace(coverage={"functional": cov.summarize(cov.merge_data([snap])),
                                             "code": {"minimal": cov.code_coverage(dat)}})
    c = phase.measured_coverage(result)
    f = c["functional"]["configurations"]["minimal"]
    assert (f["hit"], f["total"], f["uncovered"]) == (1, 2, ["dpc.n:8"])
    assert f["coverpoints"]["dpc.n"]["removed"] == {"9": "at most 8 neighbours"}
    m = c["code"]["minimal"]["dpc_ctrl"]
    assert m["line"]["percent"] == 50.0 and m["missed_lines"] == ["dpc_ctrl.sv:12"]
    assert phase.measured_coverage(types.SimpleNamespace(coverage=None)) is None

    results = [{"id": "a", "file": "x.sv", "what": "w", "config": "minimal",
                "status": "killed", "killed_by": "t1"},
               {"id": "b", "file": "x.sv", "what": "w", "config": "minimal",
                "status": "survived", "killed_by": None},
               {"id": "e", "file": "y.sv", "what": "w", "config": "minimal",
                "status": "equivalent", "killed_by": None, "equivalent": "same outputs"}]
    # The report reads each mutant's cached result on these sources: the ones without one
    # are named, not counted; none at all is "not measured".
    monkeypatch.setattr(mutate, "cached_results", lambda ms: (results, ["z"]))
    monkeypatch.setattr(mutate, "CATALOGUE", mutate.CATALOGUE[:4])
    mut = phase.measured_mutation()
    assert (mut["killed"], mut["survived"], mut["equivalent"], mut["score"]) == (1, 1, 1, 0.5)
    assert mut["survivors"] == ["b"] and mut["equivalents"] == {"e": "same outputs"}
    assert mut["missing"] == ["z"] and not mut["complete"] and mut["catalogue_size"] == 4
    monkeypatch.setattr(mutate, "cached_results", lambda ms: ([], [m.id for m in ms]))
    assert phase.measured_mutation() is None

    rows = render.coverage_rows(c)
    assert rows["fcov"][0][2:] == ["1 / 2", 50.0, "dpc.n:8"]
    assert rows["ccov"][0][:4] == ["minimal", "dpc_ctrl", "1 / 2", 50.0]
    assert any("at most 8 neighbours" in r[-1] for r in rows["fcov_points"])
    mrows = render.mutation_rows(mut)
    assert [r[4] for r in mrows["mutants"]] == ["killed", "survived", "equivalent"]
    assert mrows["mutants"][0][5] == "t1" and mrows["equivalents"] == [("e", "same outputs")]


# ---- SIGKILL at random points ---------------------------------------------------------------

KILL_CONFIG = TINY.read_text().replace(
    'tests = ["corner_codes", "checker_detects_mismatch"]', 'tests = ["corner_codes"]')


def _ours(token: str, roots: list[str]) -> list[str]:
    """Processes started by the killed report: its token in their environment, or its
    folders in their command line or working directory."""
    found = []
    for d in os.listdir("/proc"):
        if not d.isdigit() or int(d) == os.getpid():
            continue
        try:
            env = Path(f"/proc/{d}/environ").read_bytes()
            cmd = Path(f"/proc/{d}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
            cwd = os.readlink(f"/proc/{d}/cwd")
            state = Path(f"/proc/{d}/stat").read_text().split(") ")[1][0]
        except OSError:
            continue
        if state == "Z":
            continue
        if token.encode() in env or any(r in cmd or cwd.startswith(r) for r in roots):
            found.append(f"{d}: {cmd[:200]}")
    return found


def _whole(out: Path) -> str | None:
    """The run id of a whole report folder (summary.json and index.html of one run)."""
    if not out.exists():
        return None
    s = json.loads((out / "summary.json").read_text())
    h = (out / "index.html").read_text()
    m = re.search(r"name='irnuc-run-id' content='([0-9a-f]{32})'", h)
    assert m and m.group(1) == s["provenance"]["run_id"], "summary.json and index.html of two runs"
    return m.group(1)


def _share_warm_cache(private: Path) -> None:
    """Point the kill test's cache at this session's for the slow parts (syntheses,
    Verilator builds): what the cold trial left there is dropped."""
    from irnuc.common.cache import cache_dir

    for part in ("synth", "sim_build"):
        shutil.rmtree(private / part, ignore_errors=True)
        (private / part).symlink_to(cache_dir(part), target_is_directory=True)


#: What the cold trial waits for before its kill: a synthesis child of the report (Yosys in
#: pyosys, nextpnr), so that the kill lands while the report has children to leave behind.
SYNTH_CHILDREN = ("pyosys", "nextpnr")


def _wait_for_child(token: str, roots: list[str], words: tuple[str, ...], limit: float,
                    proc: subprocess.Popen) -> str | None:
    """The first process of the report whose command line holds one of ``words``, waited
    for up to ``limit`` seconds (None: none appeared, or the report ended first)."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline and proc.poll() is None:
        for found in _ours(token, roots):
            try:  # the whole command line (_ours shortens it)
                cmd = Path(f"/proc/{found.split(':', 1)[0]}/cmdline").read_bytes()
            except OSError:
                continue
            if any(w.encode() in cmd for w in words):
                return found
        time.sleep(0.1)
    return None


def test_sigkill_leaves_old_or_new_report_and_no_child(tiny_run, tmp_path) -> None:
    cfg = tmp_path / "kill.toml"
    cfg.write_text(KILL_CONFIG)
    out = tmp_path / "out"
    token = uuid.uuid4().hex
    env = {**os.environ, "IRNUC_CACHE_DIR": str(tmp_path / "cache"), "IRNUC_KILL_TEST": token}
    cmd = [str(Path(sys.executable).with_name("irnuc")), "report", "-q", "--config", str(cfg),
           "--out", str(out)]
    rng = random.Random(20261122)
    seen: set[str] = set()
    # Trial 0: cold (its own empty cache), killed a moment after its first synthesis child
    # appeared (Yosys or nextpnr running). Then the old folder is a whole report (the
    # tiny report's, copied), the cache that of this test session (warmed by the tiny
    # report), and the warm runs are killed anywhere from the sweep's workers to the
    # co-simulation, at delays from the test's seed.
    plan = [("cold", rng.uniform(0.2, 1.5))] + [("kill", rng.uniform(0.5, 8.0)) for _ in range(2)]
    for trial, (what, delay) in enumerate(plan):
        if trial == 1:
            _share_warm_cache(tmp_path / "cache")
            shutil.copytree(tiny_run[1], out, symlinks=True)
            seen.add(_whole(out))
        before = _whole(out)
        t0 = time.monotonic()
        proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                start_new_session=True)
        if what == "cold":
            child = _wait_for_child(token, [str(tmp_path)], SYNTH_CHILDREN, 120.0, proc)
            assert child is not None, "the cold report ended or ran 120 s without a synthesis child"
        try:
            proc.wait(timeout=delay)
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGKILL)
            proc.wait()
        after = _whole(out)
        # Old, or new and whole (_whole checks that summary.json and index.html are of
        # one run): a kill can land after the swap, before the process exits.
        assert after == before or after is not None, \
            f"after a kill at {time.monotonic() - t0:.1f} s the folder is gone"
        deadline = time.monotonic() + 15.0
        while (left := _ours(token, [str(tmp_path)])) and time.monotonic() < deadline:
            time.sleep(0.25)
        assert not left, f"survived the killed report: {left}"
    # The next run ends with a new whole folder and removes what killed runs left beside it.
    assert subprocess.run(cmd, env=env, capture_output=True, timeout=600).returncode == 0
    final = _whole(out)
    assert final is not None and final not in seen and not list(tmp_path.glob(".out.tmp-*"))
