"""Every flip-flop that should reset does: ``irnuc.cosim.resets`` on the Yosys netlist
(pyosys, slang front end) against the documented allow-list."""

from __future__ import annotations

import pytest

from irnuc.cosim import configspace, resets

_SV = """
module m (
  input  logic       clk_i,
  input  logic       rst_ni,
  input  logic       d_i,
  input  logic [1:0] a_i,
  output logic       q_o,
  output logic       c_o,
  output logic       r_o
);
  logic valid_q, ctrl_q, data_q;
  logic mem_q [4];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_q <= 1'b0;
    else         valid_q <= d_i;
  end
  always_ff @(posedge clk_i) begin
    ctrl_q <= ~ctrl_q ^ d_i;
    data_q <= d_i;
    mem_q[a_i] <= d_i;
  end
  assign q_o = valid_q & data_q;
  assign c_o = ctrl_q;
  assign r_o = mem_q[a_i];
endmodule
"""


def test_registers_are_classified_by_their_reset(tmp_path) -> None:
    sv = tmp_path / "m.sv"
    sv.write_text(_SV)
    regs = resets.registers(resets.netlist([sv], "m", {}, tmp_path / "y"), "m")
    assert regs["reset"] == {"valid_q"}
    assert regs["no_reset"] == {"ctrl_q", "data_q", "mem_q"}


def test_allow_list_reports_unexpected_and_stale(monkeypatch, tmp_path) -> None:
    sv = tmp_path / "m.sv"
    sv.write_text(_SV)
    monkeypatch.setattr(resets, "hdl_sources", lambda top: [sv])
    monkeypatch.setattr(resets, "top_parameters", lambda top, cfg: {})
    cfg = configspace.named()[0]
    allowed = {"data_q": "data", "mem_*": "memory", "gone_q": "removed from the RTL"}
    rep = resets.check("m", cfg, tmp_path / "w", allowed)
    assert rep.unexpected == ("ctrl_q",) and rep.stale == ("gone_q",) and not rep.passed
    text = resets.format_report(rep, allowed)
    assert "ctrl_q: UNEXPECTED" in text and "gone_q: STALE" in text
    ok = resets.check("m", cfg, tmp_path / "w2", {"*_q": "all data"})
    assert ok.passed, resets.format_report(ok, {"*_q": "all data"})


@pytest.mark.slow
def test_nuc_dpc_top_flops_without_reset_are_allowed(tmp_path) -> None:
    """Over every configuration that runs in CI: the registers without reset are exactly
    the allow-list's data-path registers; the control registers reset."""
    cfgs = configspace.named() + list(configspace.ci_sample())
    rep = resets.check("nuc_dpc_top", cfgs, tmp_path)
    assert rep.passed, resets.format_report(rep)
    for reg in ("u_tail.u_dpc.u_ctrl.state_q", "u_tail.u_dpc.u_ctrl.geo_w_q", "u_tail.u_dpc.u_ctrl.row_q",
                "u_nuc.rnd_valid_q", "u_pix_in.main_valid_q", "u_tail.u_dpc.u_ctrl.err_q"):
        assert reg in rep.with_reset, reg
