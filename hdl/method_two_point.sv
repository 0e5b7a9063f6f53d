// two_point's front (docs/datapath.md "Coefficient word", nuc_fixed.methods.two_point): the
// pixel's coef_word {bad, offset, gain} to the linear core's gain and offset; no frame word.
// Combinational: s_ready_o = m_ready_i, no state; m_user_o = {s_user_i, bad}.
module method_two_point
  import irnuc_pkg::*;
#(
  // irnuc-params: begin method_two_point (generated from nuc_fixed.methods; do not edit)
  parameter int unsigned GainIntBits      = 2,
  parameter int unsigned GainFracBits     = 14,
  parameter int unsigned OffsetIntBits    = 12,
  parameter int unsigned OffsetFracBits   = 4,
  parameter int unsigned KneeIntBits      = 14,
  parameter int unsigned KneeFracBits     = 2,
  parameter int unsigned LevelIntBits     = 14,
  parameter int unsigned LevelFracBits    = 4,
  parameter int unsigned QuadIntBits      = 10,
  parameter int unsigned QuadFracBits     = 6,
  parameter int unsigned UserBits         = 1,  // side band passed with the pixel
  // Derived, do not override.
  localparam int unsigned GainBits         = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits       = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits         = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits        = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits         = QuadIntBits + QuadFracBits,
  localparam int unsigned CoefBits         = coef_word_bits(GainBits, OffsetBits),
  localparam int unsigned FrameBits        = 32'd1
  // irnuc-params: end
) (
  // irnuc-params: ports (generated from nuc_fixed.methods; do not edit)
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // The pixel's coefficient word and its frame's word (read at sof by the top), side band.
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [CoefBits-1:0]   s_coef_i,
  input  logic [FrameBits-1:0]  s_frame_i,
  input  logic [UserBits-1:0]   s_user_i,
  // The coefficients of the core of the method's kind (core_sum's ports: lin gain, offset;
  // quad also quad; pwl gain (g_lo), gain_hi, knee, level; the others 0) and {user, bad}.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [GainBits-1:0]   m_gain_o,
  output logic [GainBits-1:0]   m_gain_hi_o,
  output logic [OffsetBits-1:0] m_offset_o,
  output logic [QuadBits-1:0]   m_quad_o,
  output logic [KneeBits-1:0]   m_knee_o,
  output logic [LevelBits-1:0]  m_level_o,
  output logic [UserBits:0]     m_user_o
  // irnuc-params: end
);

  coef_word#(GainBits, OffsetBits)::word_t w;

  assign w           = s_coef_i;
  assign m_valid_o   = s_valid_i;
  assign s_ready_o   = m_ready_i;
  assign m_gain_o    = w.gain;
  assign m_gain_hi_o = '0;
  assign m_offset_o  = w.offset;
  assign m_quad_o    = '0;
  assign m_knee_o    = '0;
  assign m_level_o   = '0;
  assign m_user_o    = {s_user_i, w.bad};

  logic unused;
  assign unused = ^{clk_i, rst_ni, s_frame_i};

endmodule
