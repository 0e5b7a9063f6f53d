// The frame's coefficients of a pixel (nuc_fixed.method_top.frame_coefficients):
// the configured method's front (hdl/method_<name>.sv, MethodSpec.rtl_module),
// every front behind these ports: the pixel's coefficient word and its frame's
// word in, the coefficients of the core of the method's kind and the pixel's bad
// flag out (m_user_o = {s_user_i, bad}). A front that computes per frame
// (tc_offset, table_interp) is a pipeline; the others pass through
// combinationally (s_ready_o = m_ready_i, no state).
//
// Generated from the method registry (nuc_fixed.methods.rtl.frame_coefficients,
// python -m irnuc.cosim.spec_files --write); do not edit.
module frame_coefficients
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  // the base method (irnuc_pkg::method_e)
  parameter method_e     Method           = MethodTwoPoint,
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
  parameter int unsigned Rounding         = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned ReadingBits      = 14,  // bits of the FPA sensor's reading
  parameter int unsigned Tc1IntBits       = 13,
  parameter int unsigned Tc1FracBits      = 3,
  parameter int unsigned Tc2IntBits       = 12,
  parameter int unsigned Tc2FracBits      = 4,
  parameter int unsigned Tg1IntBits       = 2,
  parameter int unsigned Tg1FracBits      = 14,
  parameter int unsigned Tg2IntBits       = 2,
  parameter int unsigned Tg2FracBits      = 14,
  parameter int unsigned TcOrder          = 2,  // order of the polynomials
  parameter bit          TcGain           = 1'b0,  // the gain is a polynomial too
  parameter int unsigned ReadingRangeBits = 11,  // Ts: v = (t - t_ref) / 2^Ts
  parameter int unsigned WeightIntBits    = 1,
  parameter int unsigned WeightFracBits   = 15,
  parameter int unsigned WeightRounding   = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned HousingBits      = 14,  // bits of the housing sensor's reading
  parameter int unsigned Th1IntBits       = 15,
  parameter int unsigned Th1FracBits      = 3,
  parameter int unsigned ThxIntBits       = 14,
  parameter int unsigned ThxFracBits      = 4,
  parameter int unsigned Th2IntBits       = 12,
  parameter int unsigned Th2FracBits      = 4,
  parameter int unsigned HousingRangeBits = 11,  // Hs: w' = (h - h_ref) / 2^Hs
  parameter int unsigned UserBits         = 1,  // side band passed with the pixel
  // Derived, do not override.
  localparam int unsigned GainBits         = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits       = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits         = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits        = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits         = QuadIntBits + QuadFracBits,
  localparam int unsigned TcWordBits       = Tc1IntBits + Tc1FracBits
                                             + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned TgWordBits       = (TcGain != 0) ? Tg1IntBits + Tg1FracBits
                                             + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0) : 0,
  localparam int unsigned ThWordBits       = Th1IntBits + Th1FracBits + ThxIntBits + ThxFracBits
                                             + Th2IntBits + Th2FracBits,
  localparam int unsigned WeightBits       = WeightIntBits + WeightFracBits,
  localparam int unsigned CoefBits         = coef_stream_bits(Method, OffsetBits, GainBits,
                                                              KneeBits, QuadBits, TcWordBits,
                                                              TgWordBits, ThWordBits),
  localparam int unsigned FrameBits        = frame_word_bits(Method, GainBits, LevelBits,
                                                             ReadingBits, WeightBits, HousingBits)
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

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (UserBits >= 1)
      else $fatal(1, "frame_coefficients: UserBits = %0d, at least 1", UserBits);
  end
`endif

  if (Method == MethodOnePoint) begin : gen_one_point
    method_one_point #(
      .GainIntBits    (GainIntBits),
      .GainFracBits   (GainFracBits),
      .OffsetIntBits  (OffsetIntBits),
      .OffsetFracBits (OffsetFracBits),
      .KneeIntBits    (KneeIntBits),
      .KneeFracBits   (KneeFracBits),
      .LevelIntBits   (LevelIntBits),
      .LevelFracBits  (LevelFracBits),
      .QuadIntBits    (QuadIntBits),
      .QuadFracBits   (QuadFracBits),
      .UserBits       (UserBits)
    ) u_front (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_coef_i    (s_coef_i),
      .s_frame_i   (s_frame_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_gain_o    (m_gain_o),
      .m_gain_hi_o (m_gain_hi_o),
      .m_offset_o  (m_offset_o),
      .m_quad_o    (m_quad_o),
      .m_knee_o    (m_knee_o),
      .m_level_o   (m_level_o),
      .m_user_o    (m_user_o)
    );
  end else if (Method == MethodTwoPoint) begin : gen_two_point
    method_two_point #(
      .GainIntBits    (GainIntBits),
      .GainFracBits   (GainFracBits),
      .OffsetIntBits  (OffsetIntBits),
      .OffsetFracBits (OffsetFracBits),
      .KneeIntBits    (KneeIntBits),
      .KneeFracBits   (KneeFracBits),
      .LevelIntBits   (LevelIntBits),
      .LevelFracBits  (LevelFracBits),
      .QuadIntBits    (QuadIntBits),
      .QuadFracBits   (QuadFracBits),
      .UserBits       (UserBits)
    ) u_front (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_coef_i    (s_coef_i),
      .s_frame_i   (s_frame_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_gain_o    (m_gain_o),
      .m_gain_hi_o (m_gain_hi_o),
      .m_offset_o  (m_offset_o),
      .m_quad_o    (m_quad_o),
      .m_knee_o    (m_knee_o),
      .m_level_o   (m_level_o),
      .m_user_o    (m_user_o)
    );
  end else if (Method == MethodPiecewise) begin : gen_piecewise
    method_piecewise #(
      .GainIntBits    (GainIntBits),
      .GainFracBits   (GainFracBits),
      .OffsetIntBits  (OffsetIntBits),
      .OffsetFracBits (OffsetFracBits),
      .KneeIntBits    (KneeIntBits),
      .KneeFracBits   (KneeFracBits),
      .LevelIntBits   (LevelIntBits),
      .LevelFracBits  (LevelFracBits),
      .QuadIntBits    (QuadIntBits),
      .QuadFracBits   (QuadFracBits),
      .UserBits       (UserBits)
    ) u_front (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_coef_i    (s_coef_i),
      .s_frame_i   (s_frame_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_gain_o    (m_gain_o),
      .m_gain_hi_o (m_gain_hi_o),
      .m_offset_o  (m_offset_o),
      .m_quad_o    (m_quad_o),
      .m_knee_o    (m_knee_o),
      .m_level_o   (m_level_o),
      .m_user_o    (m_user_o)
    );
  end else if (Method == MethodQuadratic) begin : gen_quadratic
    method_quadratic #(
      .GainIntBits    (GainIntBits),
      .GainFracBits   (GainFracBits),
      .OffsetIntBits  (OffsetIntBits),
      .OffsetFracBits (OffsetFracBits),
      .KneeIntBits    (KneeIntBits),
      .KneeFracBits   (KneeFracBits),
      .LevelIntBits   (LevelIntBits),
      .LevelFracBits  (LevelFracBits),
      .QuadIntBits    (QuadIntBits),
      .QuadFracBits   (QuadFracBits),
      .UserBits       (UserBits)
    ) u_front (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_coef_i    (s_coef_i),
      .s_frame_i   (s_frame_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_gain_o    (m_gain_o),
      .m_gain_hi_o (m_gain_hi_o),
      .m_offset_o  (m_offset_o),
      .m_quad_o    (m_quad_o),
      .m_knee_o    (m_knee_o),
      .m_level_o   (m_level_o),
      .m_user_o    (m_user_o)
    );
  end else if (Method == MethodTcOffset) begin : gen_tc_offset
    method_tc_offset #(
      .GainIntBits      (GainIntBits),
      .GainFracBits     (GainFracBits),
      .OffsetIntBits    (OffsetIntBits),
      .OffsetFracBits   (OffsetFracBits),
      .KneeIntBits      (KneeIntBits),
      .KneeFracBits     (KneeFracBits),
      .LevelIntBits     (LevelIntBits),
      .LevelFracBits    (LevelFracBits),
      .QuadIntBits      (QuadIntBits),
      .QuadFracBits     (QuadFracBits),
      .Rounding         (Rounding),
      .ReadingBits      (ReadingBits),
      .Tc1IntBits       (Tc1IntBits),
      .Tc1FracBits      (Tc1FracBits),
      .Tc2IntBits       (Tc2IntBits),
      .Tc2FracBits      (Tc2FracBits),
      .Tg1IntBits       (Tg1IntBits),
      .Tg1FracBits      (Tg1FracBits),
      .Tg2IntBits       (Tg2IntBits),
      .Tg2FracBits      (Tg2FracBits),
      .TcOrder          (TcOrder),
      .TcGain           (TcGain),
      .ReadingRangeBits (ReadingRangeBits),
      .UserBits         (UserBits)
    ) u_front (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_coef_i    (s_coef_i),
      .s_frame_i   (s_frame_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_gain_o    (m_gain_o),
      .m_gain_hi_o (m_gain_hi_o),
      .m_offset_o  (m_offset_o),
      .m_quad_o    (m_quad_o),
      .m_knee_o    (m_knee_o),
      .m_level_o   (m_level_o),
      .m_user_o    (m_user_o)
    );
  end else if (Method == MethodTableInterp) begin : gen_table_interp
    method_table_interp #(
      .GainIntBits    (GainIntBits),
      .GainFracBits   (GainFracBits),
      .OffsetIntBits  (OffsetIntBits),
      .OffsetFracBits (OffsetFracBits),
      .KneeIntBits    (KneeIntBits),
      .KneeFracBits   (KneeFracBits),
      .LevelIntBits   (LevelIntBits),
      .LevelFracBits  (LevelFracBits),
      .QuadIntBits    (QuadIntBits),
      .QuadFracBits   (QuadFracBits),
      .WeightIntBits  (WeightIntBits),
      .WeightFracBits (WeightFracBits),
      .WeightRounding (WeightRounding),
      .UserBits       (UserBits)
    ) u_front (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_coef_i    (s_coef_i),
      .s_frame_i   (s_frame_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_gain_o    (m_gain_o),
      .m_gain_hi_o (m_gain_hi_o),
      .m_offset_o  (m_offset_o),
      .m_quad_o    (m_quad_o),
      .m_knee_o    (m_knee_o),
      .m_level_o   (m_level_o),
      .m_user_o    (m_user_o)
    );
  end else begin : gen_tc_housing
    method_tc_offset #(
      .GainIntBits      (GainIntBits),
      .GainFracBits     (GainFracBits),
      .OffsetIntBits    (OffsetIntBits),
      .OffsetFracBits   (OffsetFracBits),
      .KneeIntBits      (KneeIntBits),
      .KneeFracBits     (KneeFracBits),
      .LevelIntBits     (LevelIntBits),
      .LevelFracBits    (LevelFracBits),
      .QuadIntBits      (QuadIntBits),
      .QuadFracBits     (QuadFracBits),
      .Rounding         (Rounding),
      .ReadingBits      (ReadingBits),
      .HousingBits      (HousingBits),
      .Tc1IntBits       (Tc1IntBits),
      .Tc1FracBits      (Tc1FracBits),
      .Tc2IntBits       (Tc2IntBits),
      .Tc2FracBits      (Tc2FracBits),
      .Tg1IntBits       (Tg1IntBits),
      .Tg1FracBits      (Tg1FracBits),
      .Tg2IntBits       (Tg2IntBits),
      .Tg2FracBits      (Tg2FracBits),
      .Th1IntBits       (Th1IntBits),
      .Th1FracBits      (Th1FracBits),
      .ThxIntBits       (ThxIntBits),
      .ThxFracBits      (ThxFracBits),
      .Th2IntBits       (Th2IntBits),
      .Th2FracBits      (Th2FracBits),
      .TcOrder          (TcOrder),
      .TcGain           (TcGain),
      .ReadingRangeBits (ReadingRangeBits),
      .HousingRangeBits (HousingRangeBits),
      .Housing          (1'b1),
      .UserBits         (UserBits)
    ) u_front (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_coef_i    (s_coef_i),
      .s_frame_i   (s_frame_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_gain_o    (m_gain_o),
      .m_gain_hi_o (m_gain_hi_o),
      .m_offset_o  (m_offset_o),
      .m_quad_o    (m_quad_o),
      .m_knee_o    (m_knee_o),
      .m_level_o   (m_level_o),
      .m_user_o    (m_user_o)
    );
  end

endmodule
