// Temperature-compensated coefficients, docs/datapath.md "tc_poly" (nuc_fixed.tempcomp
// .tc_coeffs with tc_reading): the frame's offset (and gain) of every pixel as a polynomial
// in the FPA reading,
//   o = SAT_O( ROUND_(Fo-Of)( c0 << (Fo-Of) + (c1*u) << (Fo-T1f-Ts) [+ (c2*u2) << (Fo-T2f-Ts)] ) )
//   Fo = max(Of, T1f + Ts[, T2f + Ts]),  ROUND the pipeline's rounding,
// and with TcGain the gain likewise from g0, tg1, tg2 (Fg, saturated to 0 .. 2^GW - 1);
// without it the stored gain passes. u and u2 come from tc_reading (the reading and t_ref
// travel with the pixel: method_dpc_top holds the frame's values).
//
// With Housing (tc_housing) the offset has three more terms in the housing reading h
// (h_ref and the housing's clamp as the FPA's, tc_reading's w, uw, w2):
//   + (h1*w) << (Fo-H1f-Hs) + (hx*uw) << (Fo-Hxf-Ts) + (h2*w2) << (Fo-H2f-Hs),
//   Fo the largest fraction bits of all the terms.
//
// Coefficient words as in the memory image (fields from bit 0 up): tc = {tc2, tc1} (tc1 at
// bit 0; tc2 only with TcOrder 2), tg = {tg2, tg1} (with TcGain; else one unused bit),
// th = {th2, thx, th1} (with Housing; else one unused bit).
//
// Pipeline (one enable, en = "the output register can take an item", a flop; see nuc_core):
//   u_in        input register (irnuc_spill_register)
//   u_reading   tc_reading: t - t_ref, u, then u*u on a DSP (4 stages with Ts <= 17)
//   u_c1 ...    c1*u, c2*u2 (and tg1*u, tg2*u2) as DSP partial products, two stages
//   u_osum      the aligned terms of o (and u_gsum of g, padded to the same depth),
//               clog2(leaves) stages
//   round       both ROUND, registered
//   u_out       SAT into the output register (irnuc_spill_register)
// Latency 8 + clog2(reading parts) + clog2(leaves) (tcoffset14 and tcgain14: 10, tchousing14:
// 11); one pixel per clock. UserBits of side band (raw code, markers, bad flag) pass
// unchanged.
module tc_poly
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  parameter int unsigned GainIntBits      = 2,
  parameter int unsigned GainFracBits     = 14,
  parameter int unsigned OffsetIntBits    = 13,
  parameter int unsigned OffsetFracBits   = 3,
  parameter int unsigned Tc1IntBits       = 13,
  parameter int unsigned Tc1FracBits      = 3,
  parameter int unsigned Tc2IntBits       = 12,
  parameter int unsigned Tc2FracBits      = 4,
  parameter int unsigned Tg1IntBits       = 2,
  parameter int unsigned Tg1FracBits      = 14,
  parameter int unsigned Tg2IntBits       = 2,
  parameter int unsigned Tg2FracBits      = 14,
  parameter int unsigned Th1IntBits       = 15,
  parameter int unsigned Th1FracBits      = 3,
  parameter int unsigned ThxIntBits       = 14,
  parameter int unsigned ThxFracBits      = 4,
  parameter int unsigned Th2IntBits       = 12,
  parameter int unsigned Th2FracBits      = 4,
  parameter int unsigned TcOrder          = 2,
  parameter bit          TcGain           = 1'b0,
  parameter bit          Housing          = 1'b0,
  parameter int unsigned ReadingBits      = 14,
  parameter int unsigned ReadingRangeBits = 11,
  parameter int unsigned HousingBits      = 14,
  parameter int unsigned HousingRangeBits = 11,
  parameter int unsigned Rounding         = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned UserBits         = 1,
  // Derived, do not override.
  localparam int unsigned GainBits        = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits      = OffsetIntBits + OffsetFracBits,
  localparam int unsigned Tc1Bits         = Tc1IntBits + Tc1FracBits,
  localparam int unsigned Tc2Bits         = Tc2IntBits + Tc2FracBits,
  localparam int unsigned Tg1Bits         = Tg1IntBits + Tg1FracBits,
  localparam int unsigned Tg2Bits         = Tg2IntBits + Tg2FracBits,
  localparam int unsigned TcWordBits      = Tc1Bits + ((TcOrder == 2) ? Tc2Bits : 0),
  localparam int unsigned TgWordBits      = TcGain ? Tg1Bits + ((TcOrder == 2) ? Tg2Bits : 0)
                                                   : 1,
  localparam int unsigned Th1Bits         = Th1IntBits + Th1FracBits,
  localparam int unsigned ThxBits         = ThxIntBits + ThxFracBits,
  localparam int unsigned Th2Bits         = Th2IntBits + Th2FracBits,
  localparam int unsigned ThWordBits      = Housing ? Th1Bits + ThxBits + Th2Bits : 1
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  // Input stream: the frame's reading and t_ref, the pixel's stored coefficients, side band.
  input  logic                   s_valid_i,
  output logic                   s_ready_o,
  input  logic [ReadingBits-1:0] s_reading_i,
  input  logic [ReadingBits-1:0] s_t_ref_i,
  input  logic [HousingBits-1:0] s_housing_i,
  input  logic [HousingBits-1:0] s_h_ref_i,
  input  logic [GainBits-1:0]    s_gain_i,
  input  logic [OffsetBits-1:0]  s_offset_i,
  input  logic [TcWordBits-1:0]  s_tc_i,
  input  logic [TgWordBits-1:0]  s_tg_i,
  input  logic [ThWordBits-1:0]  s_th_i,
  input  logic [UserBits-1:0]    s_user_i,
  // Output stream: the pixel's gain and offset for this frame, the same side band.
  output logic                   m_valid_o,
  input  logic                   m_ready_i,
  output logic [GainBits-1:0]    m_gain_o,
  output logic [OffsetBits-1:0]  m_offset_o,
  output logic [UserBits-1:0]    m_user_o
);

  // ---- derived widths (docs/datapath.md "tc_poly", nuc_fixed.widths.method_widths) -------
  localparam bit          Order2  = (TcOrder == 2);
  localparam int unsigned Ts      = ReadingRangeBits;
  localparam int unsigned UBits   = Ts + 1;  // u, signed
  localparam int unsigned U2Bits  = Ts;      // u2, unsigned
  localparam int unsigned Hs      = HousingRangeBits;
  localparam int unsigned WBits   = Hs + 1;  // w, signed
  localparam int unsigned W2Bits  = Hs;      // w2, unsigned
  // Offset: Fo, the terms' widths at Fo fraction bits (as signed words), the sum.
  localparam int unsigned OFrac   = max2(max3(OffsetFracBits, Tc1FracBits + Ts,
                                              Order2 ? Tc2FracBits + Ts : 0),
                                         Housing ? max3(Th1FracBits + Hs, ThxFracBits + Ts,
                                                        Th2FracBits + Hs) : 0);
  localparam int unsigned O0Shift = OFrac - OffsetFracBits;
  localparam int unsigned O1Shift = OFrac - Tc1FracBits - Ts;
  localparam int unsigned O2Shift = Order2 ? OFrac - Tc2FracBits - Ts : 0;
  localparam int unsigned H1Shift = Housing ? OFrac - Th1FracBits - Hs : 0;
  localparam int unsigned HxShift = Housing ? OFrac - ThxFracBits - Ts : 0;
  localparam int unsigned H2Shift = Housing ? OFrac - Th2FracBits - Hs : 0;
  localparam int unsigned OTerms  = 2 + (Order2 ? 1 : 0) + (Housing ? 3 : 0);
  localparam int unsigned OSumBits = max2(max3(OffsetBits + O0Shift, Tc1Bits + UBits + O1Shift,
                                               Order2 ? Tc2Bits + U2Bits + O2Shift : 0),
                                          Housing ? max3(Th1Bits + WBits + H1Shift,
                                                         ThxBits + UBits + HxShift,
                                                         Th2Bits + W2Bits + H2Shift) : 0)
                                     + $clog2(OTerms);
  localparam int unsigned ORndBits = OSumBits + 1 - O0Shift;
  // Gain (TcGain): Fg likewise; g0 is unsigned (one more bit as a signed word).
  localparam int unsigned GFrac   = max3(GainFracBits, Tg1FracBits + Ts,
                                         Order2 ? Tg2FracBits + Ts : 0);
  localparam int unsigned G0Shift = GFrac - GainFracBits;
  localparam int unsigned G1Shift = GFrac - Tg1FracBits - Ts;
  localparam int unsigned G2Shift = Order2 ? GFrac - Tg2FracBits - Ts : 0;
  localparam int unsigned GSumBits = max3(GainBits + 1 + G0Shift, Tg1Bits + UBits + G1Shift,
                                          Order2 ? Tg2Bits + U2Bits + G2Shift : 0)
                                     + (Order2 ? 2 : 1);
  localparam int unsigned GRndBits = GSumBits + 1 - G0Shift;
  // Partial products and the leaves of the two sums (the gain's padded to the offset's
  // depth or the other way round, so both come out in the same cycle).
  localparam int unsigned P1      = smul_parts(Tc1Bits, 1'b1, UBits, 1'b1);
  localparam int unsigned P2      = Order2 ? smul_parts(Tc2Bits, 1'b1, U2Bits, 1'b0) : 0;
  localparam int unsigned PG1     = TcGain ? smul_parts(Tg1Bits, 1'b1, UBits, 1'b1) : 0;
  localparam int unsigned PG2     = (TcGain && Order2) ? smul_parts(Tg2Bits, 1'b1, U2Bits, 1'b0)
                                                       : 0;
  localparam int unsigned PH1     = Housing ? smul_parts(Th1Bits, 1'b1, WBits, 1'b1) : 0;
  localparam int unsigned PHx     = Housing ? smul_parts(ThxBits, 1'b1, UBits, 1'b1) : 0;
  localparam int unsigned PH2     = Housing ? smul_parts(Th2Bits, 1'b1, W2Bits, 1'b0) : 0;
  localparam int unsigned OLeaves = 1 + P1 + P2 + PH1 + PHx + PH2;
  localparam int unsigned GLeaves = 1 + PG1 + PG2;
  localparam int unsigned Leaves  = TcGain ? max2(OLeaves, GLeaves) : OLeaves;
  localparam int unsigned CoefBits = ThWordBits + TgWordBits + TcWordBits + OffsetBits
                                     + GainBits;
  // The input register holds the housing reading and h_ref only with Housing.
  localparam int unsigned HInBits = Housing ? 2 * HousingBits : 0;
  localparam int unsigned InBits  = UserBits + CoefBits + 2 * ReadingBits + HInBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (GainBits >= 1 && GainIntBits <= 16 && GainFracBits <= 32)
      else $fatal(1, "tc_poly: gain U%0d.%0d outside U0..16.0..32 (at least one bit)",
                  GainIntBits, GainFracBits);
    assert (OffsetIntBits >= 1 && OffsetIntBits <= 32 && OffsetFracBits <= 32)
      else $fatal(1, "tc_poly: offset S%0d.%0d outside S1..32.0..32", OffsetIntBits,
                  OffsetFracBits);
    assert (Tc1IntBits >= 1 && Tc2IntBits >= 1 && Tg1IntBits >= 1 && Tg2IntBits >= 1
            && Th1IntBits >= 1 && ThxIntBits >= 1 && Th2IntBits >= 1)
      else $fatal(1, "tc_poly: every tc/tg/th format is signed: at least one integer bit");
    assert (TcOrder == 1 || TcOrder == 2)
      else $fatal(1, "tc_poly: TcOrder = %0d outside 1..2", TcOrder);
    assert (Rounding <= 2)
      else $fatal(1, "tc_poly: Rounding = %0d outside 0..2", Rounding);
    assert (UserBits >= 1)
      else $fatal(1, "tc_poly: UserBits = %0d must be at least 1", UserBits);
    assert (OSumBits <= 62 && GSumBits <= 62)
      else $fatal(1, "tc_poly: sum widths %0d, %0d exceed 62", OSumBits, GSumBits);
  end
`endif

  // Pipeline enable: the output register has room (a flop of u_out).
  logic en;

  // ---- input register ----------------------------------------------------------------------
  logic                   in_valid;
  logic [ReadingBits-1:0] in_reading, in_t_ref;
  logic [HousingBits-1:0] in_housing, in_h_ref;
  logic [CoefBits-1:0]    in_coef;
  logic [UserBits-1:0]    in_user;

  logic [InBits-1:0] in_d, in_q;

  if (Housing) begin : gen_in_housing
    assign in_d = {s_user_i, s_th_i, s_tg_i, s_tc_i, s_offset_i, s_gain_i, s_h_ref_i,
                   s_housing_i, s_t_ref_i, s_reading_i};
    assign {in_user, in_coef, in_h_ref, in_housing, in_t_ref, in_reading} = in_q;
  end else begin : gen_in_fpa
    // No housing flops: tc_reading ignores its housing inputs without Housing.
    assign in_d = {s_user_i, s_th_i, s_tg_i, s_tc_i, s_offset_i, s_gain_i, s_t_ref_i,
                   s_reading_i};
    assign {in_user, in_coef, in_t_ref, in_reading} = in_q;
    assign in_housing = '0;
    assign in_h_ref   = '0;
    logic unused_housing_in;
    assign unused_housing_in = ^{s_h_ref_i, s_housing_i};
  end

  irnuc_spill_register #(.DataBits(InBits)) u_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_valid_i),
    .ready_o(s_ready_o),
    .data_i (in_d),
    .valid_o(in_valid),
    .ready_i(en),
    .data_o (in_q)
  );

  // ---- u and u2 --------------------------------------------------------------------------
  logic                  rd_valid;
  logic [UBits-1:0]      rd_u;
  logic [U2Bits-1:0]     rd_u2;
  logic [UserBits-1:0]   rd_user;
  logic [GainBits-1:0]   rd_g0;
  logic [OffsetBits-1:0] rd_c0;
  logic [TcWordBits-1:0] rd_tc;
  logic [TgWordBits-1:0] rd_tg;
  logic [ThWordBits-1:0] rd_th;
  logic [WBits-1:0]      rd_w;
  logic [UBits-1:0]      rd_uw;
  logic [W2Bits-1:0]     rd_w2;

  tc_reading #(
    .ReadingBits     (ReadingBits),
    .ReadingRangeBits(ReadingRangeBits),
    .Square          (Order2),
    .Housing         (Housing),
    .HousingBits     (HousingBits),
    .HousingRangeBits(HousingRangeBits),
    .SideBits        (UserBits + CoefBits)
  ) u_reading (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en),
    .valid_i  (in_valid),
    .reading_i(in_reading),
    .t_ref_i  (in_t_ref),
    .housing_i(in_housing),
    .h_ref_i  (in_h_ref),
    .side_i   ({in_user, in_coef}),
    .valid_o  (rd_valid),
    .u_o      (rd_u),
    .u2_o     (rd_u2),
    .w_o      (rd_w),
    .uw_o     (rd_uw),
    .w2_o     (rd_w2),
    .side_o   ({rd_user, rd_th, rd_tg, rd_tc, rd_c0, rd_g0})
  );

  // ---- the tc and tg words (irnuc_pkg::tc_word1/2, tg_word1/2) ----------------------------
  logic [Tc1Bits-1:0] rd_tc1;
  if (Order2) begin : gen_tc_word
    tc_word2#(Tc1Bits, Tc2Bits)::word_t w;
    assign w      = rd_tc;
    assign rd_tc1 = w.tc1;
  end else begin : gen_tc_word
    tc_word1#(Tc1Bits)::word_t w;
    assign w      = rd_tc;
    assign rd_tc1 = w.tc1;
  end

  // ---- offset terms: c1*u, c2*u2 -----------------------------------------------------------
  logic                            mul_valid;
  logic [UserBits-1:0]             mul_user;
  logic [GainBits-1:0]             mul_g0;
  logic [OffsetBits-1:0]           mul_c0;
  logic [Leaves-1:0][OSumBits-1:0] o_leaves;

  logic [P1-1:0][OSumBits-1:0] c1_parts;

  irnuc_mul_parts #(
    .ABits   (Tc1Bits),
    .BBits   (UBits),
    .ASigned (1'b1),
    .BSigned (1'b1),
    .PartBits(OSumBits),
    .SideBits(UserBits + GainBits + OffsetBits)
  ) u_c1 (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(rd_valid),
    .a_i    (rd_tc1),
    .b_i    (rd_u),
    .side_i ({rd_user, rd_g0, rd_c0}),
    .valid_o(mul_valid),
    .parts_o(c1_parts),
    .side_o ({mul_user, mul_g0, mul_c0})
  );

  assign o_leaves[0] = OSumBits'($signed(mul_c0)) << O0Shift;
  for (genvar k = 0; k < P1; k++) begin : gen_c1_leaf
    assign o_leaves[1 + k] = c1_parts[k] << O1Shift;
  end

  if (Order2) begin : gen_c2
    logic [P2-1:0][OSumBits-1:0] c2_parts;
    logic                        c2_valid, c2_side;
    irnuc_mul_parts #(
      .ABits   (Tc2Bits),
      .BBits   (U2Bits),
      .ASigned (1'b1),
      .BSigned (1'b0),
      .PartBits(OSumBits),
      .SideBits(1)
    ) u_c2 (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en),
      .valid_i(rd_valid),
      .a_i    (gen_tc_word.w.tc2),
      .b_i    (rd_u2),
      .side_i (1'b0),
      .valid_o(c2_valid),
      .parts_o(c2_parts),
      .side_o (c2_side)
    );
    for (genvar k = 0; k < P2; k++) begin : gen_c2_leaf
      assign o_leaves[1 + P1 + k] = c2_parts[k] << O2Shift;
    end
    // Same enable and valid as u_c1: c2_valid equals mul_valid.
    logic unused_c2;
    assign unused_c2 = c2_valid ^ c2_side;
  end else begin : gen_no_c2
    logic unused_u2;
    assign unused_u2 = ^rd_u2;
  end

  // ---- housing terms (tc_housing): h1*w, hx*uw, h2*w2 ------------------------------------
  if (Housing) begin : gen_th
    housing_word#(Th1Bits, ThxBits, Th2Bits)::word_t w;
    assign w = rd_th;
    logic [PH1-1:0][OSumBits-1:0] h1_parts;
    logic [PHx-1:0][OSumBits-1:0] hx_parts;
    logic [PH2-1:0][OSumBits-1:0] h2_parts;
    logic                         h1_valid, h1_side, hx_valid, hx_side, h2_valid, h2_side;
    irnuc_mul_parts #(
      .ABits   (Th1Bits),
      .BBits   (WBits),
      .ASigned (1'b1),
      .BSigned (1'b1),
      .PartBits(OSumBits),
      .SideBits(1)
    ) u_h1 (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en),
      .valid_i(rd_valid),
      .a_i    (w.th1),
      .b_i    (rd_w),
      .side_i (1'b0),
      .valid_o(h1_valid),
      .parts_o(h1_parts),
      .side_o (h1_side)
    );
    irnuc_mul_parts #(
      .ABits   (ThxBits),
      .BBits   (UBits),
      .ASigned (1'b1),
      .BSigned (1'b1),
      .PartBits(OSumBits),
      .SideBits(1)
    ) u_hx (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en),
      .valid_i(rd_valid),
      .a_i    (w.thx),
      .b_i    (rd_uw),
      .side_i (1'b0),
      .valid_o(hx_valid),
      .parts_o(hx_parts),
      .side_o (hx_side)
    );
    irnuc_mul_parts #(
      .ABits   (Th2Bits),
      .BBits   (W2Bits),
      .ASigned (1'b1),
      .BSigned (1'b0),
      .PartBits(OSumBits),
      .SideBits(1)
    ) u_h2 (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en),
      .valid_i(rd_valid),
      .a_i    (w.th2),
      .b_i    (rd_w2),
      .side_i (1'b0),
      .valid_o(h2_valid),
      .parts_o(h2_parts),
      .side_o (h2_side)
    );
    for (genvar k = 0; k < PH1; k++) begin : gen_h1_leaf
      assign o_leaves[1 + P1 + P2 + k] = h1_parts[k] << H1Shift;
    end
    for (genvar k = 0; k < PHx; k++) begin : gen_hx_leaf
      assign o_leaves[1 + P1 + P2 + PH1 + k] = hx_parts[k] << HxShift;
    end
    for (genvar k = 0; k < PH2; k++) begin : gen_h2_leaf
      assign o_leaves[1 + P1 + P2 + PH1 + PHx + k] = h2_parts[k] << H2Shift;
    end
    // Same enable and valid as u_c1.
    logic unused_th;
    assign unused_th = ^{h1_valid, h1_side, hx_valid, hx_side, h2_valid, h2_side};
  end else begin : gen_no_th
    logic unused_th;
    assign unused_th = ^{rd_th, rd_w, rd_uw, rd_w2};
  end

  for (genvar k = OLeaves; k < Leaves; k++) begin : gen_o_pad
    assign o_leaves[k] = '0;
  end

  // ---- offset sum ------------------------------------------------------------------------
  logic                  osum_valid;
  logic [OSumBits-1:0]   osum;
  logic [UserBits-1:0]   osum_user;
  logic [GainBits-1:0]   osum_g0;

  irnuc_add_tree #(
    .Leaves  (Leaves),
    .Width   (OSumBits),
    .SideBits(UserBits + GainBits)
  ) u_osum (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (mul_valid),
    .leaves_i(o_leaves),
    .side_i  ({mul_user, mul_g0}),
    .valid_o (osum_valid),
    .sum_o   (osum),
    .side_o  ({osum_user, osum_g0})
  );

  logic [ORndBits-1:0] ornd_d;

  irnuc_round #(
    .InBits  (OSumBits),
    .FracBits(O0Shift),
    .Rounding(Rounding)
  ) u_oround (
    .s_i(osum),
    .r_o(ornd_d)
  );

  // ---- gain: the polynomial (TcGain) or the stored gain -----------------------------------
  // gain_q: a rounded sum of GRndBits (TcGain) or the stored gain zero-extended to a signed
  // word (no TcGain); saturated to the gain's code range on the way out.
  localparam int unsigned GQBits = TcGain ? GRndBits : GainBits + 1;
  logic [GQBits-1:0] grnd_d;

  if (TcGain) begin : gen_tg
    logic [Leaves-1:0][GSumBits-1:0] g_leaves;
    logic [PG1-1:0][GSumBits-1:0]    g1_parts;
    logic                            g1_valid, g1_side;
    logic [Tg1Bits-1:0]              tg1;
    if (Order2) begin : gen_tg_word
      tg_word2#(Tg1Bits, Tg2Bits)::word_t w;
      assign w   = rd_tg;
      assign tg1 = w.tg1;
    end else begin : gen_tg_word
      tg_word1#(Tg1Bits)::word_t w;
      assign w   = rd_tg;
      assign tg1 = w.tg1;
    end
    irnuc_mul_parts #(
      .ABits   (Tg1Bits),
      .BBits   (UBits),
      .ASigned (1'b1),
      .BSigned (1'b1),
      .PartBits(GSumBits),
      .SideBits(1)
    ) u_g1 (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en),
      .valid_i(rd_valid),
      .a_i    (tg1),
      .b_i    (rd_u),
      .side_i (1'b0),
      .valid_o(g1_valid),
      .parts_o(g1_parts),
      .side_o (g1_side)
    );
    // g0 is unsigned: zero extension.
    assign g_leaves[0] = GSumBits'(mul_g0) << G0Shift;
    for (genvar k = 0; k < PG1; k++) begin : gen_g1_leaf
      assign g_leaves[1 + k] = g1_parts[k] << G1Shift;
    end
    if (Order2) begin : gen_g2
      logic [PG2-1:0][GSumBits-1:0] g2_parts;
      logic                         g2_valid, g2_side;
      irnuc_mul_parts #(
        .ABits   (Tg2Bits),
        .BBits   (U2Bits),
        .ASigned (1'b1),
        .BSigned (1'b0),
        .PartBits(GSumBits),
        .SideBits(1)
      ) u_g2 (
        .clk_i  (clk_i),
        .rst_ni (rst_ni),
        .en_i   (en),
        .valid_i(rd_valid),
        .a_i    (gen_tg_word.w.tg2),
        .b_i    (rd_u2),
        .side_i (1'b0),
        .valid_o(g2_valid),
        .parts_o(g2_parts),
        .side_o (g2_side)
      );
      for (genvar k = 0; k < PG2; k++) begin : gen_g2_leaf
        assign g_leaves[1 + PG1 + k] = g2_parts[k] << G2Shift;
      end
      logic unused_g2;
      assign unused_g2 = g2_valid ^ g2_side;
    end
    for (genvar k = GLeaves; k < Leaves; k++) begin : gen_g_pad
      assign g_leaves[k] = '0;
    end

    logic                gsum_valid, gsum_side;
    logic [GSumBits-1:0] gsum;
    irnuc_add_tree #(
      .Leaves  (Leaves),
      .Width   (GSumBits),
      .SideBits(1)
    ) u_gsum (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (en),
      .valid_i (mul_valid),
      .leaves_i(g_leaves),
      .side_i  (1'b0),
      .valid_o (gsum_valid),
      .sum_o   (gsum),
      .side_o  (gsum_side)
    );

    irnuc_round #(
      .InBits  (GSumBits),
      .FracBits(G0Shift),
      .Rounding(Rounding)
    ) u_ground (
      .s_i(gsum),
      .r_o(grnd_d)
    );

    // The stored gain went through the products' side band unused; the sum's valid equals
    // the offset sum's (same enable, same depth).
    logic unused_tg;
    assign unused_tg = ^{g1_valid, g1_side, gsum_valid, gsum_side, osum_g0};
  end else begin : gen_no_tg
    assign grnd_d = GQBits'(osum_g0);
    logic unused_tg;
    assign unused_tg = ^rd_tg;
  end

  // ---- round registers, SAT and the output register ----------------------------------------
  logic                rnd_valid_q;
  logic [ORndBits-1:0] ornd_q;
  logic [GQBits-1:0]   grnd_q;
  logic [UserBits-1:0] rnd_user_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_round_valid
    if (!rst_ni) begin
      rnd_valid_q <= 1'b0;
    end else if (en) begin
      rnd_valid_q <= osum_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_round
    if (en) begin
      ornd_q     <= ornd_d;
      grnd_q     <= grnd_d;
      rnd_user_q <= osum_user;
    end
  end

  logic [OffsetBits-1:0] offset_d;
  logic [GainBits-1:0]   gain_d;

  irnuc_clip #(
    .InBits   (ORndBits),
    .OutBits  (OffsetBits),
    .OutSigned(1'b1),
    .Overflow (0)
  ) u_oclip (
    .v_i(ornd_q),
    .y_o(offset_d)
  );

  irnuc_clip #(
    .InBits   (GQBits),
    .OutBits  (GainBits),
    .OutSigned(1'b0),
    .Overflow (0)
  ) u_gclip (
    .v_i(grnd_q),
    .y_o(gain_d)
  );

  irnuc_spill_register #(.DataBits(UserBits + GainBits + OffsetBits)) u_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(rnd_valid_q),
    .ready_o(en),
    .data_i ({rnd_user_q, gain_d, offset_d}),
    .valid_o(m_valid_o),
    .ready_i(m_ready_i),
    .data_o ({m_user_o, m_gain_o, m_offset_o})
  );

  // Protocol assertions of s_* and m_* (irnuc_stream_assert, `ifdef IRNUC_ASSERT): in u_in
  // and u_out, whose ports these are.

endmodule
