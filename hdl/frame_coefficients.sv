// The frame's coefficients of a pixel for the stage tops' base methods (nuc_fixed.method_top
// .frame_coefficients): the pixel's coefficient word (s_coef of method_dpc_top) and its
// frame's word (read at sof by the enclosing top) to the gain, offset and quadratic term the
// core uses, and the pixel's bad flag.
//
//   one_point   coeffs: offset, bad; the gain is the frame's register (the frame word)
//   two_point   coeffs: gain, offset, bad
//   quadratic   coeffs: gain, offset, bad | quad: quad
//   tc_offset   coeffs: gain, offset (c0), bad | tc: tc1[, tc2] | tg: tg1[, tg2]; frame:
//               reading, t_ref; tc_poly gives the frame's gain and offset (a stream stage
//               of tc_poly's latency, with its own input and output registers)
//
// one_point, two_point and quadratic are combinational (s_ready_o = m_ready_i, no state);
// tc_offset is tc_poly's pipeline. UserBits of side band travel with the pixel; m_user_o is
// {s_user_i, bad}. The quadratic term is 0 for the other methods.
module frame_coefficients
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  parameter int unsigned Method           = 1,  // irnuc_pkg::method_e: 0, 1, 3 or 4
  parameter int unsigned GainIntBits      = 2,
  parameter int unsigned GainFracBits     = 14,
  parameter int unsigned OffsetIntBits    = 12,
  parameter int unsigned OffsetFracBits   = 4,
  parameter int unsigned QuadIntBits      = 10,
  parameter int unsigned QuadFracBits     = 6,
  parameter int unsigned Tc1IntBits       = 13,
  parameter int unsigned Tc1FracBits      = 3,
  parameter int unsigned Tc2IntBits       = 12,
  parameter int unsigned Tc2FracBits      = 4,
  parameter int unsigned Tg1IntBits       = 2,
  parameter int unsigned Tg1FracBits      = 14,
  parameter int unsigned Tg2IntBits       = 2,
  parameter int unsigned Tg2FracBits      = 14,
  parameter int unsigned TcOrder          = 2,
  parameter int unsigned TcGain           = 0,
  parameter int unsigned ReadingBits      = 14,
  parameter int unsigned ReadingRangeBits = 11,
  parameter int unsigned Rounding         = 1,  // irnuc_pkg::rounding_e (tc_poly's ROUND)
  parameter int unsigned UserBits         = 1,
  // Derived, do not override.
  localparam method_e     MethodSel  = method_e'(Method),
  localparam int unsigned GainBits   = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits = OffsetIntBits + OffsetFracBits,
  localparam int unsigned QuadBits   = QuadIntBits + QuadFracBits,
  localparam int unsigned TcWordBits = Tc1IntBits + Tc1FracBits
                                       + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned TgWordBits = (TcGain != 0) ? Tg1IntBits + Tg1FracBits
                                       + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0)
                                                     : 0,
  localparam int unsigned CoefBits   = coef_stream_bits(MethodSel, GainBits, OffsetBits, 1,
                                                        QuadBits, TcWordBits, TgWordBits),
  localparam int unsigned FrameBits  = frame_word_bits(MethodSel, GainBits, 1, ReadingBits, 1)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [CoefBits-1:0]   s_coef_i,
  input  logic [FrameBits-1:0]  s_frame_i,
  input  logic [UserBits-1:0]   s_user_i,
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [GainBits-1:0]   m_gain_o,
  output logic [OffsetBits-1:0] m_offset_o,
  output logic [QuadBits-1:0]   m_quad_o,
  output logic [UserBits:0]     m_user_o  // {s_user_i, bad}
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MethodSel == MethodOnePoint || MethodSel == MethodTwoPoint
            || MethodSel == MethodQuadratic || MethodSel == MethodTcOffset)
      else $fatal(1, "frame_coefficients: Method = %0d; one_point (0), two_point (1), quadratic (3) or tc_offset (4)",
                  Method);
    assert (UserBits >= 1 && TcOrder >= 1 && TcOrder <= 2 && TcGain <= 1)
      else $fatal(1, "frame_coefficients: UserBits = %0d, TcOrder = %0d, TcGain = %0d out of range",
                  UserBits, TcOrder, TcGain);
  end
`endif

  if (MethodSel == MethodTcOffset) begin : gen_tc_offset
    localparam int unsigned TwoPointBits = coef_word_bits(GainBits, OffsetBits);
    coef_word#(GainBits, OffsetBits)::word_t     coeffs;
    frame_tc_offset#(ReadingBits)::word_t        fw;
    logic [((TcGain != 0) ? TgWordBits : 1)-1:0] tg;
    assign coeffs   = s_coef_i[TwoPointBits-1:0];
    assign fw       = s_frame_i;
    assign m_quad_o = '0;
    if (TcGain != 0) begin : gen_tg
      assign tg = s_coef_i[TwoPointBits + TcWordBits +: TgWordBits];
    end else begin : gen_no_tg
      assign tg = 1'b0;
    end

    tc_poly #(
      .GainIntBits     (GainIntBits),
      .GainFracBits    (GainFracBits),
      .OffsetIntBits   (OffsetIntBits),
      .OffsetFracBits  (OffsetFracBits),
      .Tc1IntBits      (Tc1IntBits),
      .Tc1FracBits     (Tc1FracBits),
      .Tc2IntBits      (Tc2IntBits),
      .Tc2FracBits     (Tc2FracBits),
      .Tg1IntBits      (Tg1IntBits),
      .Tg1FracBits     (Tg1FracBits),
      .Tg2IntBits      (Tg2IntBits),
      .Tg2FracBits     (Tg2FracBits),
      .TcOrder         (TcOrder),
      .TcGain          (TcGain != 0),
      .ReadingBits     (ReadingBits),
      .ReadingRangeBits(ReadingRangeBits),
      .Rounding        (Rounding),
      .UserBits        (UserBits + 1)
    ) u_coef (
      .clk_i      (clk_i),
      .rst_ni     (rst_ni),
      .s_valid_i  (s_valid_i),
      .s_ready_o  (s_ready_o),
      .s_reading_i(fw.reading),
      .s_t_ref_i  (fw.t_ref),
      .s_gain_i   (coeffs.gain),
      .s_offset_i (coeffs.offset),
      .s_tc_i     (s_coef_i[TwoPointBits +: TcWordBits]),
      .s_tg_i     (tg),
      .s_user_i   ({s_user_i, coeffs.bad}),
      .m_valid_o  (m_valid_o),
      .m_ready_i  (m_ready_i),
      .m_gain_o   (m_gain_o),
      .m_offset_o (m_offset_o),
      .m_user_o   (m_user_o)
    );
  end else begin : gen_direct
    // The words pass straight through.
    logic bad;
    assign m_valid_o = s_valid_i;
    assign s_ready_o = m_ready_i;
    assign m_user_o  = {s_user_i, bad};
    logic unused_clk;
    assign unused_clk = ^{clk_i, rst_ni};
    if (MethodSel == MethodOnePoint) begin : gen_one_point
      coef_one_point#(OffsetBits)::word_t w;
      assign w          = s_coef_i;
      assign m_gain_o   = s_frame_i[GainBits-1:0];
      assign m_offset_o = w.offset;
      assign bad        = w.bad;
      assign m_quad_o   = '0;
    end else if (MethodSel == MethodQuadratic) begin : gen_quadratic
      typedef struct packed {
        quad_word#(QuadBits)::word_t             quad;
        coef_word#(GainBits, OffsetBits)::word_t coeffs;
      } stream_t;
      stream_t w;
      assign w          = s_coef_i;
      assign m_gain_o   = w.coeffs.gain;
      assign m_offset_o = w.coeffs.offset;
      assign bad        = w.coeffs.bad;
      assign m_quad_o   = w.quad.quad;
      logic unused_frame;
      assign unused_frame = ^s_frame_i;
    end else begin : gen_two_point
      coef_word#(GainBits, OffsetBits)::word_t w;
      assign w          = s_coef_i;
      assign m_gain_o   = w.gain;
      assign m_offset_o = w.offset;
      assign bad        = w.bad;
      assign m_quad_o   = '0;
      logic unused_frame;
      assign unused_frame = ^s_frame_i;
    end
  end

endmodule
