"""Functional coverage (cocotb-coverage) and code coverage (Verilator) of the co-simulation.

* every named configuration (and every mode variant of ``nuc_core``) reaches 100 % of its
  bins over the testbenches run for it; an unreachable bin is removed with its reason;
* the merge, the summary and the ``coverage.dat`` reader on small hand-made data (so the
  100 % check can fail: an unhit bin is reported by name).

``run_suite(coverage=True)`` is tested in ``tests/test_suite.py``.
"""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_dpc, tb_nuc, tb_top
from irnuc.cocotb_tests.runs import coverage_json, run_module
from irnuc.cocotb_tests.test_nuc_core import _VARIANTS, _config
from irnuc.cosim import coverage
from irnuc.nuc_fixed import load_pipeline, pipeline_names

TB = {"nuc_dpc_top": tb_top.__name__, "dpc_core": tb_dpc.__name__, "nuc_core": tb_nuc.__name__}


def _labels() -> list[str]:
    return list(_VARIANTS)


@pytest.mark.cosim
@pytest.mark.slow
@pytest.mark.parametrize("variant", _labels())
def test_functional_coverage_complete(variant: str) -> None:
    """Every bin of the configuration's coverpoints is hit by the testbenches run for it
    (named configurations: tb_top, tb_dpc, tb_nuc; mode variants: tb_nuc)."""
    cfg = _config(variant)
    tops = ["nuc_core"] if variant not in pipeline_names() else list(TB)
    files = []
    for top in tops:
        run_module(top, cfg, TB[top])
        files.append(coverage_json(top, cfg, TB[top]))
    summary = coverage.summarize(coverage.merge(files))
    label = coverage.config_label(cfg)
    assert label in summary["configurations"], f"no coverage exported for {label}"
    c = summary["configurations"][label]
    assert c["total"] > 0
    assert c["hit"] == c["total"], f"{label}: {c['hit']}/{c['total']}; uncovered {c['uncovered']}"
    for p in c["coverpoints"].values():
        for b, reason in p["removed"].items():
            assert reason and b not in p["bins"], (b, reason)


def _snap(bins: dict[str, int], removed: dict[str, str] | None = None) -> dict:
    return {"version": 1, "configurations": {"x": {"config_digest": "d", "tops": ["t"],
            "coverpoints": {"p": {"kind": "point", "bins": bins, "removed": removed or {}}}}}}


def test_merge_and_summary_report_uncovered_bins() -> None:
    merged = coverage.merge_data([_snap({"a": 1, "b": 0}), _snap({"a": 2, "b": 0, "c": 1})])
    s = coverage.summarize(merged)["configurations"]["x"]
    assert s["coverpoints"]["p"]["bins"] == {"a": 3, "b": 0, "c": 1}
    assert (s["hit"], s["total"], s["uncovered"]) == (2, 3, ["p:b"])
    full = coverage.summarize(coverage.merge_data([merged, _snap({"b": 5})]))
    assert full["percent"] == 100.0 and full["configurations"]["x"]["uncovered"] == []


def test_model_removes_unreachable_cross_bins_with_reasons() -> None:
    cfg = load_pipeline("minimal")
    m = coverage.CoverageModel("nuc_dpc_top", cfg, prefix="unit")
    snap = m.snapshot()["configurations"]["minimal"]["coverpoints"]
    cross = snap["dpc.n_x_position"]
    assert "(4, 'corner')" in cross["removed"] and "(4, 'corner')" not in cross["bins"]
    assert "(3, 'corner')" in cross["bins"] and "(8, 'interior')" in cross["bins"]
    assert "at most 3" in cross["removed"]["(4, 'corner')"]
    assert set(snap["frame.error"]["bins"]) == set(coverage.FRAME_ERRORS)
    assert set(snap["reset.stage"]["bins"]) >= {"top_input", "nuc_round", "dpc_window", "flush"}


def test_code_coverage_from_a_coverage_dat(tmp_path) -> None:
    def point(page: str, line: int, count: int, h: str) -> str:
        kv = {"f": "hdl/nuc_core.sv", "l": str(line), "n": "3", "page": page, "o": "c",
              "h": h}
        return "C '" + "".join(f"\x01{k}\x02{v}" for k, v in kv.items()) + f"' {count}"

    dat = tmp_path / "coverage.dat"
    dat.write_text("# SystemC::Coverage-3\n" + "\n".join([
        point("v_line/nuc_core__pi1", 10, 4, "top.a"), point("v_line/nuc_core__pi1", 10, 0,
                                                             "top.b"),
        point("v_line/nuc_core", 12, 0, "top.a"), point("v_toggle/nuc_core", 14, 1, "top.a"),
        point("v_toggle/nuc_core", 15, 0, "top.a")]) + "\n")
    cc = coverage.code_coverage(coverage.read_coverage_dat(dat))
    assert cc["nuc_core"]["line"] == {"hit": 1, "total": 2, "percent": 50.0}
    assert cc["nuc_core"]["toggle"]["percent"] == 50.0
    assert cc["nuc_core"]["missed_lines"] == ["nuc_core.sv:12"]
