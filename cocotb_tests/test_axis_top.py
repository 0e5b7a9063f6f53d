"""Co-simulation of ``irnuc_axis_top`` with cocotbext-axi against the golden models (the
register model and the framing model, then the core's), on the named two-point
configurations (the functional coverage of that one run closes: every bin hit), and built
around method_dpc_top on a method configuration (``tb_axis_method``) and around
method_ffc_top on an FFC composition (``tb_axis_ffc``: a refresh through the registers)."""

from __future__ import annotations

import pytest

from irnuc import cosim
from irnuc.cocotb_tests import tb_axis, tb_axis_ffc, tb_axis_method, tb_axis_reset, tb_axis_table
from irnuc.cocotb_tests.runs import (
    case_params,
    coverage_json,
    module_metrics,
    results_root,
    run_case,
    run_module,
)
from irnuc.cocotb_tests.test_coverage import _assert_closed
from irnuc.cosim import coverage
from irnuc.nuc_fixed import load_pipeline

pytestmark = [pytest.mark.cosim, pytest.mark.slow]

#: minimal (short words, frequent saturation) and typical14 (the camera's widths).
CONFIGS = ("minimal", "typical14")
#: tc_offset: the FPA reading written through AXI4-Lite between frames and mid frame;
#: two_point + blind_drift: the blind sum (BLIND_SUM) likewise, method_drift_top the core;
#: table_interp: the same, each frame's weight computed from READING and TABLE_READING[k].
METHOD_CONFIGS = ("tcoffset14", "drift14", "table14", "tchousing14")
#: table_interp: TABLE_SEL and the frame start held while the weight is computed.
TABLE_CONFIGS = ("table14",)
#: base method + ffc (N = 8): FFC_CTRL, the four FFC streams; two_point and tc_offset hold
#: the shutter frames, quadratic passes them; tc_offset takes READING per frame.
FFC_CONFIGS = ("ffc14", "quadffc14", "tcffc14")


@pytest.mark.parametrize(("config", "case"), case_params(tb_axis, CONFIGS))
def test_irnuc_axis_top(config: str, case: str) -> None:
    run_case("irnuc_axis_top", load_pipeline(config), tb_axis, case)


@pytest.mark.parametrize(("config", "case"), case_params(tb_axis_method, METHOD_CONFIGS))
def test_irnuc_axis_top_method(config: str, case: str) -> None:
    run_case("irnuc_axis_top", load_pipeline(config), tb_axis_method, case)


@pytest.mark.parametrize(("config", "case"), case_params(tb_axis_table, TABLE_CONFIGS))
def test_irnuc_axis_top_table(config: str, case: str) -> None:
    run_case("irnuc_axis_top", load_pipeline(config), tb_axis_table, case)


@pytest.mark.parametrize(("config", "case"), case_params(tb_axis_ffc, FFC_CONFIGS))
def test_irnuc_axis_top_ffc(config: str, case: str) -> None:
    run_case("irnuc_axis_top", load_pipeline(config), tb_axis_ffc, case)


@pytest.mark.parametrize("config", FFC_CONFIGS)
def test_irnuc_axis_top_ffc_full_rate(config: str) -> None:
    """At valid = ready = 1 on every port the last two (open, back-to-back) frames of
    ffc_refresh_full_rate leave one pixel per clock: 2 H W pixels in 2 H W cycles (the
    run test_irnuc_axis_top_ffc makes, its recorded cycles; the wrapper's fork into
    method_ffc_top's pixel and coefficient inputs lost one cycle in four before)."""
    lines = [m for m in module_metrics("irnuc_axis_top", load_pipeline(config),
                                       tb_axis_ffc.__name__)
             if m.get("throughput") == "last_two_frames"]
    assert lines, "ffc_refresh_full_rate recorded no throughput"
    m = lines[-1]
    assert m["cycles"] == m["pixels"], (
        f"{m['pixels']} pixels took {m['cycles']} cycles; idle/stalled cycles by port "
        f"{m['stalls']}")


def _assert_axis_closed(config: str, tb, prefix: str) -> None:
    """Every bin of irnuc_axis_top's coverpoints on ``config`` is hit by the one run of
    ``tb`` (read again: no second simulation), and points named ``prefix...`` are among
    them."""
    cfg = load_pipeline(config)
    run_module("irnuc_axis_top", cfg, tb.__name__)
    summary = coverage.summarize(coverage.merge(
        [coverage_json("irnuc_axis_top", cfg, tb.__name__)]))
    label = coverage.config_label(cfg)
    points = summary["configurations"].get(label, {}).get("coverpoints", {})
    assert any(p.startswith(prefix) for p in points), f"no {prefix} point exported"
    _assert_closed(summary, label)


@pytest.mark.parametrize("config", CONFIGS)
def test_irnuc_axis_top_coverage(config: str) -> None:
    """Every bin of irnuc_axis_top's coverpoints (cosim.axis_coverage and the stream
    points) is hit by the one run of tb_axis (no second simulation)."""
    _assert_axis_closed(config, tb_axis, "axis.")


@pytest.mark.parametrize("config", TABLE_CONFIGS)
def test_irnuc_axis_top_table_coverage(config: str) -> None:
    """Every bin of table_interp's selection (cosim.axis_coverage's axis.table points: each
    j, the weight's classes, TABLE_SEL computing / valid / error, both held frame starts)
    and of the stream points is hit by the one run of tb_axis_table."""
    _assert_axis_closed(config, tb_axis_table, "axis.table.")


@pytest.mark.parametrize("config", FFC_CONFIGS)
def test_irnuc_axis_top_ffc_coverage(config: str) -> None:
    """Every bin of the FFC sequence through the registers (cosim.axis_coverage's
    axis.ffc points) and of the stream points is hit by the one run of tb_axis_ffc."""
    _assert_axis_closed(config, tb_axis_ffc, "axis.ffc.")


def test_irnuc_axis_top_drift_coverage() -> None:
    """Every bin of blind_drift through the registers (cosim.axis_coverage's axis.drift
    points: each sign of the drift code and its saturation, BLIND_SUM written between
    frames and mid frame, NUC off) and of the stream points is hit by the one run of
    tb_axis_method on drift14."""
    _assert_axis_closed("drift14", tb_axis_method, "axis.drift.")


def test_irnuc_axis_top_housing_coverage() -> None:
    """Every bin of the housing reading through the registers (cosim.axis_coverage's
    axis.housing point: HOUSING_READING written between frames and mid frame) and of the
    stream points is hit by the one run of tb_axis_method on tchousing14."""
    _assert_axis_closed("tchousing14", tb_axis_method, "axis.housing.")


def test_irnuc_axis_top_reset_idle_fires() -> None:
    """A valid held high across reset (a stale item the DUT would take at the first edge
    after it: the bench's idle_inputs left out) stops the simulation through
    irnuc_axis_assert's a_reset_idle on that port (tb_axis_reset, a simulation of its own;
    tb_axis.stale_inputs_idled is the legal start with the same junk)."""
    cfg = load_pipeline("minimal")
    case = "violation_valid_at_reset"
    xml = cosim.run(cosim.build("irnuc_axis_top", cfg), tb_axis_reset.__name__, testcase=case,
                    results_xml=results_root() / f"{cfg.name}-{cfg.digest()[:8]}-"
                    f"irnuc_axis_top-reset-{case}.xml")
    res = cosim.read_results(xml)[case]
    fired = cosim.assertion_failures(xml)
    assert not res.passed, "the valid held across reset passed"
    assert tb_axis_reset.NOT_FIRED not in res.message, f"the simulation went on\n{res.message}"
    assert any("u_assert_coef_in." in ln and ".a_reset_idle:" in ln for ln in fired), (
        f"expected a_reset_idle in u_assert_coef_in; the simulator log reports {fired}")
