"""No combinational path from any input port to any output port, checked on the netlist.

``cosim.synth.comb_paths`` elaborates a module with Yosys (pyosys: slang front end,
``proc``, ``flatten``, memories mapped to flip-flops) and selects the fan-in cone of every
output port, stopping at flip-flops, latches and memories; no input port may be in it.
Checked for ``nuc_core``, ``dpc_core`` and ``nuc_dpc_top`` with the widths and modes of
every named configuration, and for the AXI wrapper ``irnuc_axis_top`` on ``minimal`` (line
buffers shortened to 32 entries: the combinational structure does not depend on their
depth, and mapping 2048 words to flip-flops is slow).
The negative control runs the same rule on the baseline RTL (``benchmarks/rtl_baseline``),
whose ready paths are known to be combinational: the cones must find them.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from irnuc import cosim
from irnuc.cosim import synth
from irnuc.nuc_fixed import load_pipeline, pipeline_names

pytestmark = pytest.mark.slow

BASELINE_DIR = Path(__file__).resolve().parents[1] / "benchmarks" / "rtl_baseline"
TOPS = ("nuc_core", "dpc_core", "nuc_dpc_top")
#: Depth of the line buffers in this check.
_SHORT = 32


def _params(top: str, config: str) -> dict[str, int]:
    params = cosim.top_parameters(top, load_pipeline(config))
    for key in ("MaxWidth", "MaxHeight"):
        if key in params:
            params[key] = min(params[key], _SHORT)
    return params


@pytest.mark.parametrize("config", pipeline_names())
@pytest.mark.parametrize("top", TOPS)
def test_no_combinational_input_to_output_path(top: str, config: str, tmp_path) -> None:
    paths = synth.comb_paths(cosim.hdl_sources(top), top, _params(top, config), tmp_path)
    assert "m_valid_o" in paths or "m_pix_valid_o" in paths, sorted(paths)
    found = {out: ins for out, ins in paths.items() if ins}
    assert not found, f"{top} ({config}): combinational input -> output paths {found}"


@pytest.mark.parametrize("config", ["minimal", "table14"])
def test_axis_top_has_no_combinational_input_to_output_path(config: str, tmp_path) -> None:
    """The AXI wrapper (irnuc_axis_top, docs/integration.md): every AXI4-Stream tready,
    every AXI4-Lite ready/valid/response and irq_o comes from flip-flops (on minimal: the
    wrapper's structure does not depend on the widths; on table14 with irnuc_axis_table,
    whose hold reaches the framer's start decision)."""
    top = "irnuc_axis_top"
    paths = synth.comb_paths(cosim.hdl_sources(top), top, _params(top, config), tmp_path)
    assert {"s_axis_video_tready", "s_axis_coef_tready", "m_axis_video_tvalid",
            "s_axil_awready", "s_axil_wready", "s_axil_bvalid", "s_axil_arready",
            "s_axil_rvalid", "irq_o"} <= set(paths), sorted(paths)
    found = {out: ins for out, ins in paths.items() if ins}
    assert not found, f"{top}: combinational input -> output paths {found}"


#: Paths the baseline RTL is known to have (docs/cosim.md of that version): the top's join,
#: nuc_core's ready chain, dpc_core's ready at a frame boundary.
_BASELINE_PATHS = {
    "nuc_core": {"s_ready_o": {"m_ready_i"}},
    "dpc_core": {"s_ready_o": {"m_ready_i", "s_valid_i", "frame_width_i"}},
    "nuc_dpc_top": {"s_pix_ready_o": {"s_coef_valid_i", "m_pix_ready_i"},
                    "s_coef_ready_o": {"s_pix_valid_i", "m_pix_ready_i"}},
}


@pytest.mark.parametrize("top", TOPS)
def test_negative_control_baseline_has_paths(top: str, tmp_path) -> None:
    """The rule does not stop early: it finds the baseline's combinational ready paths."""
    files = {"nuc_core": ["nuc_core.sv"], "dpc_core": ["dpc_core.sv"],
             "nuc_dpc_top": ["nuc_core.sv", "dpc_core.sv", "nuc_dpc_top.sv"]}[top]
    paths = synth.comb_paths([BASELINE_DIR / f for f in files], top,
                             _params(top, "minimal"), tmp_path)
    for out, ins in _BASELINE_PATHS[top].items():
        missing = ins - set(paths.get(out, []))
        assert not missing, f"baseline {top}: {out} should depend on {missing}; found {paths}"
    # ... and registered outputs stay clean: data out of a flop.
    data_out = "m_pix_data_o"
    assert paths.get(data_out, []) == [], paths
