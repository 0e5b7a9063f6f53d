"""``irnuc formal`` and ``irnuc.verif.formal``: the proofs of the test suite, the planted
faults that show each property can fail, the results (JUnit, VCD, cache) and the command
line.

The suite runs the quick proofs (a few seconds each: the spill register, a buffer, the
framer, the FFC sequencer, minimal's register file, by PDR) and one planted fault per
property module; the rest (every configuration's register file, irnuc_axis_top bounded per
configuration, every fault) runs with ``irnuc formal`` (docs/formal.md).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from irnuc.cosim import formal as fv
from irnuc.cosim.sources import HDL_DIR
from irnuc.verif import formal


def test_every_property_has_a_planted_fault() -> None:
    props = formal.properties()
    # The property modules and the reference of ffc_ctrl, each with its assertions.
    assert set(props) >= {"irnuc_fv_stream", "irnuc_fv_order", "irnuc_fv_video",
                          "irnuc_fv_axil", "fv_ffc_ctrl"}
    assert {"a_valid_held", "a_data_stable", "a_reset_idle"} <= set(props["irnuc_fv_stream"])
    assert {"a_r_stable", "a_b_request", "a_open"} <= set(props["irnuc_fv_axil"])
    assert formal.unplanted_properties() == []
    proofs = {p.id for p in formal.PROOFS}
    for f in formal.FAULTS:
        assert f.proof in proofs, f.id
        file, changes = f.change()
        text = (HDL_DIR / file).read_text()
        for find, _ in changes:
            assert text.count(find) == 1, f.id
    assert len({f.id for f in formal.FAULTS}) == len(formal.FAULTS)
    assert len({p.id for p in formal.PROOFS}) == len(formal.PROOFS)


def test_every_configuration_is_proved() -> None:
    from irnuc.nuc_fixed import pipeline_names

    names = set(pipeline_names(method=None))
    regs = {p.config for p in formal.PROOFS if p.harness == "fv_axil_regs"}
    top = {p.config: p for p in formal.PROOFS if p.harness == "fv_axis_top"}
    assert regs == names and set(top) == names
    assert all(p.engine == "bmc3" and p.depth == p.cover
               == formal.TOP_DEPTHS.get(name, formal.TOP_DEPTH) >= formal.TOP_DEPTH
               and p.exclude == formal.TOP_REGFILE_CHECKS for name, p in top.items())
    # the register file's checks left out of the top are proved on it, per configuration
    assert all(p.engine == "pdr" for p in formal.PROOFS if p.id.startswith("axil_regs_"))
    assert all(p.parameters()["MaxWidth"] == formal.PROOF_SIZE[0] for p in top.values())
    with pytest.raises(ValueError, match="--only nope: no such proof or planted fault"):
        formal.select(["nope"])


def test_harness_takes_every_register_file_parameter() -> None:
    """fv_axil_regs declares and passes on every parameter the register file takes on any
    configuration: a parameter the harness lacks is silently left at the design's default
    (tc_housing's HousingReadingRegBits / HRefRegBits were: H_REF absent from the proved
    register file while the map had it, found by axil_regmap_tchousing14's a_pending)."""
    from irnuc.cosim.sources import register_file_parameters
    from irnuc.nuc_fixed import load_pipeline

    text = (fv.FORMAL_DIR / "fv_axil_regs.sv").read_text()
    declared = set(re.findall(r"parameter\s+int\s+unsigned\s+(\w+)", text))
    passed = set(re.findall(r"\.(\w+)\(\1\)", text))
    for name in formal._configs():
        cfg = load_pipeline(name).replace(max_width=formal.PROOF_SIZE[0],
                                          max_height=formal.PROOF_SIZE[1])
        params = set(register_file_parameters(cfg))
        assert params <= declared, (name, sorted(params - declared))
        assert params <= passed, (name, sorted(params - passed))


def test_labels_of_an_smtbmc_log() -> None:
    log = ("##   0:00:00  Checking assertions in step 3..\n"
           "##   0:00:00  BMC failed!\n"
           "##   0:00:00  Assert failed in fv_x: u_out.gen_output.p_rules.a_valid_held\n"
           "##   0:00:00  Assert failed in fv_x: a.sv:3.1-3.9 (u_order.p_check.a_order)\n")
    assert fv._labels(log) == ["u_out.a_valid_held", "u_order.a_order"]
    assert formal._matches("u_order.a_order", ["u_order.a_order"])
    assert not formal._matches("u_order.a_order", ["u_out.a_order"])
    assert formal._matches("a_mean", ["a_mean"])


@pytest.mark.slow
def test_quick_campaign(tmp_path, monkeypatch) -> None:
    # The results in a cache of their own (the campaign really runs).
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    (tmp_path / "cache").mkdir()
    assert formal.cached_summary() is None
    proofs, faults = formal.select(quick=True)
    assert {p.id for p in proofs} >= {"spill_register", "axis_framer", "ffc_ctrl",
                                      "axil_regs_minimal"}
    # One planted fault per property module at least.
    assert {f.proof for f in faults} >= {"spill_register", "axis_framer", "ffc_ctrl",
                                         "axil_regs_minimal"}
    s = formal.run_campaign(proofs, faults, workers=0)
    for r in s["proofs"]:
        assert r["status"] == "proved" and r["engine"] == "pdr", r
        assert r["cover"]["status"] == "covered" and r["cover"]["total"] >= 2, r
        assert r["asserts"] >= 7 and r["ok"], r
    for r in s["faults"]:
        assert r["status"] == "failed" and r["detected"], r
        assert formal._matches(r["property"], r["failed"]), r
        vcd = Path(r["vcd"]).read_text()
        assert "$enddefinitions" in vcd and "rst_ni" in vcd, r["id"]
    assert s["ok"] and not s["complete"] and not s["missed"]
    # JUnit: every proof and fault a passing test case; a missed fault a failure.
    root = ET.fromstring(formal.junit(s))
    cases = root.findall(".//testcase")
    assert len(cases) == len(proofs) + len(faults)
    assert not root.findall(".//failure")
    bad = dict(s, faults=[dict(s["faults"][0], detected=False)])
    assert len(ET.fromstring(formal.junit(bad)).findall(".//failure")) == 1
    # The report reads the campaign from the cache (no run): a row per proof and fault of
    # the whole campaign, those never run on these sources "not run" and named, never
    # counted as holding.
    from irnuc.reports.report import render
    from irnuc.reports.report.phases.cosim import measured_formal

    m = measured_formal()
    assert m is not None and m["proved"] == len(proofs) and m["detected"] == len(faults)
    ran = {p.id for p in proofs} | {f.id for f in faults}
    assert set(m["missing"]) == {x.id for x in [*formal.PROOFS, *formal.FAULTS]} - ran
    assert not m["ok"] and not m["complete"] and not m["not_ok"] and not m["missed"]
    rows = render.formal_rows(m)
    assert [r[0] for r in rows["proofs"]] == [p.id for p in formal.PROOFS]
    for r in rows["proofs"]:
        assert (r[4], r[3]) == (("proved", "unbounded") if r[0] in ran else ("not run", "")), r
    for r in rows["faults"]:
        assert r[3] == ("detected" if r[0] in ran else "not run"), r
    # A second run comes from the cache.
    again = formal.run_campaign(proofs[:1], faults[:1], workers=0)
    assert all(r["cached"] for r in [*again["proofs"], *again["faults"]])
    # The command line (its own process): from the cache, formal.json, junit.xml and the
    # traces under --out; a bad id is one line and exit 2, before any work.
    irnuc = Path(sys.executable).with_name("irnuc")
    env = {**os.environ, "IRNUC_CACHE_DIR": str(tmp_path / "cache")}
    out = tmp_path / "out"
    proc = subprocess.run([str(irnuc), "formal", "--only", "spill_register", "--only",
                           "spill_skid_order", "--out", str(out), "-q"], env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    data = json.loads((out / "formal.json").read_text())
    assert data["proved"] == 1 and data["detected"] == 1
    assert (out / data["faults"][0]["vcd"]).is_file()
    assert ET.parse(out / "junit.xml").getroot().find(".//testsuite").get("tests") == "2"
    bad = subprocess.run([str(irnuc), "formal", "--only", "nope", "--out",
                          str(tmp_path / "o2")], env=env, capture_output=True, text=True)
    err = bad.stderr.strip().splitlines()
    assert bad.returncode == 2 and len(err) == 1 and "--only nope" in err[0], bad.stderr
    assert not (tmp_path / "o2").exists()


def test_bmc3_bounded_and_replayed(tmp_path) -> None:
    """A bounded proof by ABC's bmc3: the spill register passes 12 frames; with its output
    register reloading whatever the ready (planted fault spill_drops_stalled) it fails, and
    the replay by yosys-smtbmc names the assertion and writes the trace."""
    from irnuc.cosim.sources import hdl_sources

    proof = next(p for p in formal.PROOFS if p.id == "spill_register")
    fault = next(f for f in formal.FAULTS if f.id == "spill_drops_stalled")
    hdl = tmp_path / "hdl"
    shutil.copytree(HDL_DIR, hdl, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    for where, tag in ((HDL_DIR, "good"), (hdl, "bad")):
        if tag == "bad":
            f = hdl / fault.file
            f.write_text(f.read_text().replace(fault.find, fault.replace))
        srcs = fv.formal_sources(hdl_sources(proof.design, where), proof.harness,
                                 where / "formal")
        models = fv.write_models(srcs, proof.harness, proof.parameters(), tmp_path / tag)
        res = fv.check(models, "bmc3", 12, tmp_path / tag)
        if tag == "good":
            assert res.status == "passed" and res.engine == "bmc3", res
            assert Path(res.log).name == "bmc3.log", res  # ABC's, not yosys-smtbmc
            assert res.depth == 12 and res.wanted is None, res
            # A bound out of reach in a 1-s budget: a bounded pass to the frames finished,
            # the bound asked for beside it (irnuc_axis_top's proofs).
            far = fv.check(models, "bmc3", 10**7, tmp_path / "far", budget=1)
            assert far.status == "passed" and far.wanted == 10**7, far
            assert 12 < far.depth < 10**7 and "budget" in far.message, far
        else:
            assert res.status == "failed" and res.step is not None, res
            assert "u_out.a_valid_held" in res.failed, res
            assert res.vcd and "$enddefinitions" in Path(res.vcd).read_text()
            # replayed along ABC's own trace (its witness), not by a search
            assert (tmp_path / tag / "cex.yw").is_file() and Path(res.vcd).name == "witness.vcd"


def test_top_covers_by_bmc3(tmp_path) -> None:
    """irnuc_axis_top's cover model (minimal): ABC reaches every cover and names each by
    its label; the frame out takes W x H beats (its last pixel W * H - 1 cycles after its
    first at the earliest), the next frame starts a cycle after it. The top's own ports are
    no AIGER outputs (ABC took them for properties: a false failure at frame 0)."""
    from irnuc.cosim.sources import hdl_sources

    proof = next(p for p in formal.PROOFS if p.id == "axis_top_minimal")
    srcs = fv.formal_sources(hdl_sources(proof.design), proof.harness)
    models = fv.write_models(srcs, proof.formal_top, proof.parameters(), tmp_path,
                             covers=True)
    header = Path(models["aig"]).read_bytes().split(b"\n", 1)[0].split()
    labels = fv.aiger_labels(models["aig"])
    assert int(header[4]) == 0 and int(header[6]) == len(labels) == 5, header  # O, B
    res = fv.bmc3_covers(models["aig"], formal.TOP_DEPTH, tmp_path)
    assert res.status == "covered", res
    steps = {k.rsplit(".", 1)[-1]: v for k, v in res.covers.items()}
    w, h = formal.PROOF_SIZE
    assert steps["c_frame_out"] - steps["c_video_out"] == w * h - 1, steps
    assert steps["c_next_sof"] == steps["c_frame_out"] + 1, steps


@pytest.mark.parametrize("module", ["irnuc_fv_stream", "irnuc_fv_order", "irnuc_fv_video",
                                    "irnuc_fv_axil", "irnuc_fv_reset", "irnuc_fv_regs"])
def test_property_modules_lint_clean(module: str, tmp_path) -> None:
    """``verilator --lint-only -Wall -DFORMAL`` is clean for every property module (the
    register semantics with minimal's generated map package)."""
    from irnuc.cosim.verilator import verilator_executable
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.verif.formal_regmap import package

    files = [fv.FORMAL_DIR / f"{module}.sv"]
    if module == "irnuc_fv_regs":
        pkg = tmp_path / "irnuc_fv_map.sv"
        pkg.write_text(package(load_pipeline("minimal")))
        files.insert(0, pkg)
    proc = subprocess.run([str(verilator_executable()), "--lint-only", "-Wall", "-DFORMAL",
                           "--top-module", module, *map(str, files)],
                          capture_output=True, text=True)
    report = proc.stdout + proc.stderr
    assert proc.returncode == 0 and "%Warning" not in report and "%Error" not in report, report
