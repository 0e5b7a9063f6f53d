"""``irnuc traffic`` (``irnuc.verif.traffic``): which testbench carries the random register
traffic on each configuration, and the command line's refusals (the traffic itself runs in
cocotb_tests/test_axis_top.py on the suite's configurations)."""

from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

import pytest

from irnuc.cosim import cocotb_test_names
from irnuc.nuc_fixed import load_pipeline, pipeline_names
from irnuc.verif import traffic


def test_every_configuration_has_its_traffic_test() -> None:
    cfgs = traffic.configurations(None)
    assert [c.name for c in cfgs] == list(pipeline_names(method=None))
    kinds = set()
    for cfg in cfgs:
        case = traffic.traffic_case(cfg)
        assert case.top == "irnuc_axis_top"
        names = cocotb_test_names(importlib.import_module(case.module))
        assert case.tests is not None and set(case.tests) <= set(names), (cfg.name, case)
        kinds.add(case.module.rsplit(".", 1)[-1])
    assert kinds == {"tb_axis", "tb_axis_method", "tb_axis_ffc"}
    assert traffic.traffic_case(load_pipeline("ffc14")).tests == ("ffc_second_run",)
    with pytest.raises(ValueError, match="--configs typcal14: no such configuration; did you"):
        traffic.configurations("minimal,typcal14")


def test_command_line_refuses_a_bad_configuration(tmp_path) -> None:
    irnuc = Path(sys.executable).with_name("irnuc")
    out = tmp_path / "out"
    proc = subprocess.run([str(irnuc), "traffic", "--configs", "nope", "--out", str(out)],
                          capture_output=True, text=True)
    err = proc.stderr.strip().splitlines()
    assert proc.returncode == 2 and len(err) == 1 and "--configs nope" in err[0]
    assert not out.exists()


def test_command_line_runs_the_traffic_and_closes_its_bins(tmp_path) -> None:
    """``irnuc traffic --configs minimal`` as documented (coverage on): the register traffic
    passes through irnuc_axis_top, junit.xml names the test, and every bin of the traffic's
    own coverpoints is hit on minimal (the expected bins written here, not read from the
    coverage model)."""
    import json
    import xml.etree.ElementTree as ET

    irnuc = Path(sys.executable).with_name("irnuc")
    out = tmp_path / "out"
    proc = subprocess.run([str(irnuc), "traffic", "--configs", "minimal", "--out", str(out)],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    cases = list(ET.parse(out / "junit.xml").iter("testcase"))
    assert [c.get("name") for c in cases] == ["register_traffic"]
    assert not any(c.find("failure") is not None or c.find("error") is not None
                   for c in cases)
    pts = json.loads((out / "coverage.json").read_text())[
        "functional"]["configurations"]["minimal"]["coverpoints"]
    want = {
        "axil.traffic.address": {"write", "read", "ro_write", "wo_read", "reserved_write",
                                 "reserved_ro_write", "reserved_read", "unmapped_write",
                                 "unmapped_read"},
        "axil.traffic.strobe": {"full", "partial", "noncontiguous", "none"},
        "axil.traffic.ready_held": {"bready", "rready"},
        "axil.traffic.streaming": {"read", "write", "w1c_clear"},
        "axil.traffic.overlap": {"write_and_read"},
        "axil.traffic.reset_size": {"frame"},
        "axil.traffic.size_strobe": {"ignored_lane0", "ignored_lane1", "ignored_lane2",
                                     "ignored_lane3", "refused"},
    }
    for point, bins in want.items():
        hit = {b for b, n in pts[point]["bins"].items() if n > 0}
        assert hit == bins, (point, hit)
