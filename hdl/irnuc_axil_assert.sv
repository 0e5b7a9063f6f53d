// Protocol checker of an AXI4-Lite slave port (simulation only, no logic): irnuc_axis_top
// puts one on s_axil under `ifdef IRNUC_ASSERT. Immediate assertions at the rising edge,
// armed from the first edge after reset; for each channel c of aw, w, b, ar, r:
//   a_<c>_known      valid and ready are never X/Z
//   a_<c>_held       valid, once high, stays high until ready
//   a_<c>_stable     the payload does not change while valid && !ready
//   a_<c>_payload    the payload is not X/Z while valid
// and for the responses:
//   a_b_request      a write response only for a write whose address and data were both
//                    taken and not yet answered (one response per request)
//   a_r_request      a read response only for a read address taken and not yet answered
//   a_bresp_legal    BRESP is not EXOKAY (no exclusive access in AXI4-Lite)
//   a_rresp_legal    RRESP is not EXOKAY
module irnuc_axil_assert
  import irnuc_pkg::*;
#(
  parameter int unsigned AddrBits = 12
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic [AddrBits-1:0] awaddr_i,
  input logic [2:0]          awprot_i,
  input logic                awvalid_i,
  input logic                awready_i,
  input logic [31:0]         wdata_i,
  input logic [3:0]          wstrb_i,
  input logic                wvalid_i,
  input logic                wready_i,
  input logic [1:0]          bresp_i,
  input logic                bvalid_i,
  input logic                bready_i,
  input logic [AddrBits-1:0] araddr_i,
  input logic [2:0]          arprot_i,
  input logic                arvalid_i,
  input logic                arready_i,
  input logic [31:0]         rdata_i,
  input logic [1:0]          rresp_i,
  input logic                rvalid_i,
  input logic                rready_i
);

`ifndef SYNTHESIS
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));

  // Payloads, stalls of the previous edge and their payloads.
  logic [AddrBits+2:0] aw, aw_q, ar, ar_q;
  logic [35:0]         w, w_q;
  logic [1:0]          b, b_q;
  logic [33:0]         r, r_q;
  logic                aw_stall_q, w_stall_q, b_stall_q, ar_stall_q, r_stall_q;

  assign aw = {awaddr_i, awprot_i};
  assign ar = {araddr_i, arprot_i};
  assign w  = {wdata_i, wstrb_i};
  assign b  = bresp_i;
  assign r  = {rdata_i, rresp_i};

  always_ff @(posedge clk_i) begin : p_sample
    aw_stall_q <= awvalid_i && !awready_i;
    w_stall_q  <= wvalid_i && !wready_i;
    b_stall_q  <= bvalid_i && !bready_i;
    ar_stall_q <= arvalid_i && !arready_i;
    r_stall_q  <= rvalid_i && !rready_i;
    aw_q       <= aw;
    w_q        <= w;
    b_q        <= b;
    ar_q       <= ar;
    r_q        <= r;
  end

  // Requests not yet answered: addresses and data taken, responses given.
  logic [7:0] aw_open_q, w_open_q, ar_open_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_open
    if (!rst_ni) begin
      aw_open_q <= '0;
      w_open_q  <= '0;
      ar_open_q <= '0;
    end else begin
      aw_open_q <= aw_open_q + 8'(awvalid_i && awready_i) - 8'(bvalid_i && bready_i);
      w_open_q  <= w_open_q + 8'(wvalid_i && wready_i) - 8'(bvalid_i && bready_i);
      ar_open_q <= ar_open_q + 8'(arvalid_i && arready_i) - 8'(rvalid_i && rready_i);
    end
  end

`ifndef FORMAL  // two-valued in the formal model (irnuc formal): no X/Z to check
  always_ff @(posedge clk_i) begin : p_known
    if (armed_q) begin
      a_aw_known: assert (!$isunknown({awvalid_i, awready_i}))
        else $error("irnuc_axil_assert: awvalid or awready is X/Z");
      a_w_known: assert (!$isunknown({wvalid_i, wready_i}))
        else $error("irnuc_axil_assert: wvalid or wready is X/Z");
      a_b_known: assert (!$isunknown({bvalid_i, bready_i}))
        else $error("irnuc_axil_assert: bvalid or bready is X/Z");
      a_ar_known: assert (!$isunknown({arvalid_i, arready_i}))
        else $error("irnuc_axil_assert: arvalid or arready is X/Z");
      a_r_known: assert (!$isunknown({rvalid_i, rready_i}))
        else $error("irnuc_axil_assert: rvalid or rready is X/Z");
      if (awvalid_i) begin
        a_aw_payload: assert (!$isunknown(aw))
          else $error("irnuc_axil_assert: awaddr or awprot is X/Z while awvalid");
      end
      if (wvalid_i) begin
        a_w_payload: assert (!$isunknown(w))
          else $error("irnuc_axil_assert: wdata or wstrb is X/Z while wvalid");
      end
      if (bvalid_i) begin
        a_b_payload: assert (!$isunknown(b))
          else $error("irnuc_axil_assert: bresp is X/Z while bvalid");
      end
      if (arvalid_i) begin
        a_ar_payload: assert (!$isunknown(ar))
          else $error("irnuc_axil_assert: araddr or arprot is X/Z while arvalid");
      end
      if (rvalid_i) begin
        a_r_payload: assert (!$isunknown(r))
          else $error("irnuc_axil_assert: rdata or rresp is X/Z while rvalid");
      end
    end
  end
`endif

  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      if (bvalid_i) begin
        a_bresp_legal: assert (axi_resp_e'(bresp_i) != AxiExOkay)
          else $error("irnuc_axil_assert: BRESP = EXOKAY on AXI4-Lite");
        a_b_request: assert (aw_open_q != '0 && w_open_q != '0)
          else $error("irnuc_axil_assert: a write response without an open write");
      end
      if (rvalid_i) begin
        a_rresp_legal: assert (axi_resp_e'(rresp_i) != AxiExOkay)
          else $error("irnuc_axil_assert: RRESP = EXOKAY on AXI4-Lite");
        a_r_request: assert (ar_open_q != '0)
          else $error("irnuc_axil_assert: a read response without an open read");
      end
      if (aw_stall_q) begin
        a_aw_held: assert (awvalid_i) else $error("irnuc_axil_assert: awvalid dropped");
        a_aw_stable: assert (aw == aw_q) else $error("irnuc_axil_assert: AW changed, stalled");
      end
      if (w_stall_q) begin
        a_w_held: assert (wvalid_i) else $error("irnuc_axil_assert: wvalid dropped");
        a_w_stable: assert (w == w_q) else $error("irnuc_axil_assert: W changed, stalled");
      end
      if (b_stall_q) begin
        a_b_held: assert (bvalid_i) else $error("irnuc_axil_assert: bvalid dropped");
        a_b_stable: assert (b == b_q) else $error("irnuc_axil_assert: B changed, stalled");
      end
      if (ar_stall_q) begin
        a_ar_held: assert (arvalid_i) else $error("irnuc_axil_assert: arvalid dropped");
        a_ar_stable: assert (ar == ar_q) else $error("irnuc_axil_assert: AR changed, stalled");
      end
      if (r_stall_q) begin
        a_r_held: assert (rvalid_i) else $error("irnuc_axil_assert: rvalid dropped");
        a_r_stable: assert (r == r_q) else $error("irnuc_axil_assert: R changed, stalled");
      end
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, awaddr_i, awprot_i, awvalid_i, awready_i, wdata_i,
                          wstrb_i, wvalid_i, wready_i, bresp_i, bvalid_i, bready_i, araddr_i,
                          arprot_i, arvalid_i, arready_i, rdata_i, rresp_i, rvalid_i,
                          rready_i};
`endif

endmodule
