"""The suite's scheduling over pytest-xdist workers (the root ``conftest.py``,
docs/testing.md): the groups that keep shared work in one worker."""

from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _conftest():
    spec = importlib.util.spec_from_file_location("irnuc_root_conftest", ROOT / "conftest.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_groups_of_node_ids() -> None:
    group_of = _conftest().group_of
    # co-simulation tests: by the configuration among their parameters, wherever it is
    assert group_of("cocotb_tests/test_nuc_dpc_top.py::test_nuc_dpc_top[minimal-corner_codes]") \
        == "cosim-minimal"
    assert group_of("cocotb_tests/test_nuc_dpc_top.py::test_stream_pattern[wide16-none-bursty]") \
        == "cosim-wide16"
    assert group_of("cocotb_tests/test_protocol.py::test_registered_boundary"
                    "[nuc_core-typical14-clean_stall]") == "cosim-typical14"
    assert group_of("cocotb_tests/test_nuc_core.py::test_nuc_core"
                    "[typical14+half_even+wrap-corner_codes]") == "cosim-typical14+half_even+wrap"
    # the methods' and stages' configurations too: one run of their testbench per worker
    assert group_of("cocotb_tests/test_method_dpc_top.py::test_method_dpc_top"
                    "[tcoffset14-stream_patterns]") == "cosim-tcoffset14"
    assert group_of("cocotb_tests/test_coverage.py::test_ffc_coverage_complete[ffc14]") \
        == group_of("cocotb_tests/test_method_ffc_top.py::test_method_ffc_top[ffc14-refresh_edges]") \
        == "cosim-ffc14"
    # no configuration: alone; tests/: by file
    alone = "cocotb_tests/test_protocol.py::test_assertion_fires[dpc_core-violation_valid_dropped]"
    assert group_of(alone) == alone
    assert group_of("cocotb_tests/test_coverage.py::test_merge_and_summary_report_uncovered_bins") \
        == "cocotb_tests/test_coverage.py::test_merge_and_summary_report_uncovered_bins"
    assert group_of("tests/test_report_e2e.py::test_html_shows_fronts_costs_and_cosim_detail") \
        == group_of("tests/test_report_e2e.py::test_sigkill_leaves_old_or_new_report_and_no_child") \
        == "file-tests/test_report_e2e.py"
