// Protocol checker of one AXI4-Stream port (simulation only, no logic): irnuc_axis_top
// puts one on each of s_axis_video, s_axis_coef and m_axis_video under `ifdef IRNUC_ASSERT.
// Immediate assertions at the rising edge on the values of this and the previous edge,
// armed from the first edge after reset (as irnuc_stream_assert):
//   a_known          tvalid and tready are never X/Z
//   a_payload_known  tdata, tlast and tuser are not X/Z while tvalid
//   a_valid_held     tvalid, once high, stays high until tready (AXI4-Stream rule)
//   a_payload_stable tdata, tlast and tuser do not change while tvalid && !tready
//   a_reset_idle     tvalid is low in reset and at the first edge after it (AXI: a master
//                    raises VALID only after that edge; a stale item left by a stopped
//                    driver would be taken there)
module irnuc_axis_assert #(
  parameter int unsigned DataBits = 8,
  parameter int unsigned UserBits = 1
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                tvalid_i,
  input logic                tready_i,
  input logic [DataBits-1:0] tdata_i,
  input logic                tlast_i,
  input logic [UserBits-1:0] tuser_i
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (DataBits >= 1 && UserBits >= 1)
      else $fatal(1, "irnuc_axis_assert: DataBits = %0d, UserBits = %0d must be >= 1",
                  DataBits, UserBits);
  end

  logic                         armed_q, stall_q;
  logic [DataBits+UserBits:0]   payload, payload_q;

  assign payload = {tdata_i, tlast_i, tuser_i};

  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));

  always_ff @(posedge clk_i) begin : p_sample
    stall_q   <= tvalid_i && !tready_i;
    payload_q <= payload;
  end

  always_ff @(posedge clk_i) begin : p_check
`ifndef FORMAL  // the formal harness assumes the stream rules from its own first cycle
    // Until armed: the edges in reset and the first after it (rst_ni itself is not
    // sampled here: it stays a pure asynchronous reset).
    if (!armed_q) begin
      a_reset_idle: assert (!tvalid_i)
        else $error("irnuc_axis_assert: tvalid high in reset or at the first edge after it");
    end
`endif
    if (armed_q) begin
`ifndef FORMAL  // two-valued in the formal model (irnuc formal)
      a_known: assert (!$isunknown(tvalid_i) && !$isunknown(tready_i))
        else $error("irnuc_axis_assert: tvalid or tready is X/Z");
      if (tvalid_i) begin
        a_payload_known: assert (!$isunknown(payload))
          else $error("irnuc_axis_assert: tdata, tlast or tuser is X/Z while tvalid");
      end
`endif
      if (stall_q) begin
        a_valid_held: assert (tvalid_i)
          else $error("irnuc_axis_assert: tvalid dropped before tready");
        a_payload_stable: assert (payload == payload_q)
          else $error("irnuc_axis_assert: tdata, tlast or tuser changed while stalled");
      end
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, tvalid_i, tready_i, tdata_i, tlast_i, tuser_i};
`endif

endmodule
