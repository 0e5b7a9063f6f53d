// The front of tc_offset and tc_housing (docs/datapath.md "tc_offset", docs/methods.md
// "tc_housing"; nuc_fixed.methods.tc_offset, .tc_housing): the pixel's coefficient word and
// the frame's word to the frame's gain and offset of the pixel: tc_poly (tc_reading inside),
// a pipeline of its latency with its own input and output registers. m_user_o = {s_user_i,
// bad}. Coefficient words (bit 0 up) coeffs: gain, offset c0, bad at bit 0; tc: tc1[, tc2];
// with Housing th: th1, thx, th2; with TcGain tg: tg1[, tg2]:
//   tc_offset   {tg, tc, coef_word},      frame_tc_offset  {t_ref, reading}
//   tc_housing  {tg, th, tc, coef_word},  frame_tc_housing {h_ref, housing_reading, t_ref,
//                                                            reading}
// Housing (tc_housing's instance, the registry's rtl_front_flags) switches on tc_poly's and
// tc_reading's housing terms; without it the hardware is tc_offset's alone.
module method_tc_offset
  import irnuc_pkg::*;
#(
  // irnuc-params: begin method_tc_offset (generated from nuc_fixed.methods; do not edit)
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
  parameter int unsigned HousingBits      = 14,  // bits of the housing sensor's reading
  parameter int unsigned Th1IntBits       = 15,
  parameter int unsigned Th1FracBits      = 3,
  parameter int unsigned ThxIntBits       = 14,
  parameter int unsigned ThxFracBits      = 4,
  parameter int unsigned Th2IntBits       = 12,
  parameter int unsigned Th2FracBits      = 4,
  parameter int unsigned HousingRangeBits = 11,  // Hs: w' = (h - h_ref) / 2^Hs
  parameter bit          Housing          = 1'b0,  // 1: tc_housing
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
  localparam int unsigned CoefBits         = (Housing != 0) ? (coef_word_bits(GainBits, OffsetBits) + TcWordBits + ThWordBits + TgWordBits) : (coef_word_bits(GainBits, OffsetBits) + TcWordBits + TgWordBits),
  localparam int unsigned FrameBits        = (Housing != 0) ? (frame_tc_housing_bits(ReadingBits, HousingBits)) : (frame_tc_offset_bits(ReadingBits))
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

  localparam int unsigned TwoPointBits = coef_word_bits(GainBits, OffsetBits);
  // Where the tg word starts: after th with Housing.
  localparam int unsigned TgLsb        = TwoPointBits + TcWordBits + (Housing ? ThWordBits : 0);
  localparam int unsigned ThPortBits   = Housing ? ThWordBits : 1;

  coef_word#(GainBits, OffsetBits)::word_t     coeffs;
  logic [ReadingBits-1:0]                      reading, t_ref;
  logic [HousingBits-1:0]                      housing, h_ref;
  logic [ThPortBits-1:0]                       th;
  logic [((TcGain != 0) ? TgWordBits : 1)-1:0] tg;

  assign coeffs = s_coef_i[TwoPointBits-1:0];
  if (Housing) begin : gen_housing
    frame_tc_housing#(ReadingBits, HousingBits)::word_t fw;
    assign fw      = s_frame_i;
    assign reading = fw.reading;
    assign t_ref   = fw.t_ref;
    assign housing = fw.housing_reading;
    assign h_ref   = fw.h_ref;
    assign th      = s_coef_i[TwoPointBits + TcWordBits +: ThPortBits];
  end else begin : gen_fpa
    frame_tc_offset#(ReadingBits)::word_t fw;
    assign fw      = s_frame_i;
    assign reading = fw.reading;
    assign t_ref   = fw.t_ref;
    assign housing = '0;
    assign h_ref   = '0;
    assign th      = '0;
  end
  if (TcGain != 0) begin : gen_tg
    assign tg = s_coef_i[TgLsb +: TgWordBits];
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
    .Th1IntBits      (Th1IntBits),
    .Th1FracBits     (Th1FracBits),
    .ThxIntBits      (ThxIntBits),
    .ThxFracBits     (ThxFracBits),
    .Th2IntBits      (Th2IntBits),
    .Th2FracBits     (Th2FracBits),
    .TcOrder         (TcOrder),
    .TcGain          (TcGain),
    .Housing         (Housing),
    .ReadingBits     (ReadingBits),
    .ReadingRangeBits(ReadingRangeBits),
    .HousingBits     (HousingBits),
    .HousingRangeBits(HousingRangeBits),
    .Rounding        (Rounding),
    .UserBits        (UserBits + 1)
  ) u_coef (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .s_valid_i  (s_valid_i),
    .s_ready_o  (s_ready_o),
    .s_reading_i(reading),
    .s_t_ref_i  (t_ref),
    .s_housing_i(housing),
    .s_h_ref_i  (h_ref),
    .s_gain_i   (coeffs.gain),
    .s_offset_i (coeffs.offset),
    .s_tc_i     (s_coef_i[TwoPointBits +: TcWordBits]),
    .s_tg_i     (tg),
    .s_th_i     (th),
    .s_user_i   ({s_user_i, coeffs.bad}),
    .m_valid_o  (m_valid_o),
    .m_ready_i  (m_ready_i),
    .m_gain_o   (m_gain_o),
    .m_offset_o (m_offset_o),
    .m_user_o   (m_user_o)
  );

  assign m_gain_hi_o = '0;
  assign m_quad_o    = '0;
  assign m_knee_o    = '0;
  assign m_level_o   = '0;

endmodule
