// offset_only's front (tests/demo_method/offset_only.py): the pixel's word
// coef_offset_only {bad, offset} to the linear core's offset, the gain 1.0. Combinational:
// s_ready_o = m_ready_i, no state; m_user_o = {s_user_i, bad}.
module method_offset_only
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  // irnuc-params: begin method_offset_only
  // irnuc-params: end
) (
  // irnuc-params: ports
  // irnuc-params: end
);

  coef_offset_only#(OffsetBits)::word_t w;

  assign w           = s_coef_i;
  assign m_valid_o   = s_valid_i;
  assign s_ready_o   = m_ready_i;
  assign m_gain_o    = GainBits'(unity_gain(GainIntBits, GainFracBits));
  assign m_gain_hi_o = '0;
  assign m_offset_o  = w.offset;
  assign m_quad_o    = '0;
  assign m_knee_o    = '0;
  assign m_level_o   = '0;
  assign m_user_o    = {s_user_i, w.bad};

  logic unused;
  assign unused = ^{clk_i, rst_ni, s_frame_i};

endmodule
