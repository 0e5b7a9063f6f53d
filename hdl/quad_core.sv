// Quadratic NUC, docs/datapath.md "quad_core" (nuc_fixed.cores.quad_core):
//   y = OUT( ROUND_F( x*g << (F - Gf) + o << (F - Of) + qs ) ),  F = max(Gf, Of),
//   xq = (x*x) >> Sq (floor, Sq = max(0, 2A - SquareBits)),  qp = q*xq with
//   QPf = Qf + 2A - Sq fraction bits,  qs = qp at F fraction bits (floor when QPf > F).
//
// The floor of qs is exact without a shift of its own: with K = QPf - F > 0 every other
// term is an integer multiple of 2^-F, so floor((x*g, o at F + K bits) + qp, by K) equals
// their sum with qs; the sum is formed at F + K fraction bits and its K low bits dropped.
//
// Pipeline (one enable, en = "the output register can take an item", a flop; see nuc_core):
//   u_in     input register (irnuc_spill_register)
//   u_sq     x*x as DSP partial products (input and output registered), then their sum
//            (clog2(square parts) stages, none for A <= 17)
//   u_qp     q*xq and, beside it, u_gp x*g, DSP partial products (two stages each)
//   u_sum    the aligned parts and the aligned offset, clog2(parts + 1) stages
//   u_out    core_out: r = ROUND_F(s) of the sum without its K low bits (irnuc_round),
//            registered, then OUT(r) (irnuc_clip) into the output register (irnuc_axis_buffer)
// Latency 7 + clog2(square parts) + clog2(parts + 1) (quadratic14: 9); one pixel per clock.
module quad_core
  import irnuc_method_pkg::*;
#(
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned QuadIntBits    = 10,
  parameter int unsigned QuadFracBits   = 6,
  parameter int unsigned SquareBits     = 18,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow       = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned UserBits       = 1,
  // s_* is checked by u_in (0: by the caller, whose driver is a checked spill register).
  parameter bit          CheckIn        = 1'b1,
  // Derived, do not override.
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned QuadBits      = QuadIntBits + QuadFracBits
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Input stream: raw code, the pixel's gain, offset and quadratic term, side band.
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [AdcBits-1:0]    s_pix_data_i,
  input  logic [GainBits-1:0]   s_gain_i,
  input  logic [OffsetBits-1:0] s_offset_i,
  input  logic [QuadBits-1:0]   s_quad_i,
  input  logic [UserBits-1:0]   s_user_i,
  // Output stream: corrected code and the same side band.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic [UserBits-1:0]   m_user_o
);

  // ---- derived widths (docs/datapath.md "quad_core", nuc_fixed.widths.core_widths) -------
  localparam int unsigned FracBits = max2(GainFracBits, OffsetFracBits);
  localparam int unsigned SqShift  = (2 * AdcBits > SquareBits) ? 2 * AdcBits - SquareBits : 0;
  localparam int unsigned XsqBits  = 2 * AdcBits;
  localparam int unsigned XqBits   = XsqBits - SqShift;          // min(2A, SquareBits)
  localparam int unsigned QpFrac   = QuadFracBits + 2 * AdcBits - SqShift;
  localparam int unsigned ExtFrac  = (QpFrac > FracBits) ? QpFrac - FracBits : 0;  // K
  localparam int unsigned PBits    = AdcBits + GainBits;         // x*g, unsigned
  localparam int unsigned QpBits   = QuadBits + XqBits;          // q*xq, signed
  localparam int unsigned QsBits   = (QpFrac <= FracBits) ? QpBits + FracBits - QpFrac
                                                          : QpBits - ExtFrac;
  // s = ps + os + qs (the golden widths), then K more fraction bits inside.
  localparam int unsigned SumBits  = max3(PBits + FracBits - GainFracBits + 1,
                                          OffsetBits + FracBits - OffsetFracBits, QsBits) + 2;
  localparam int unsigned ExtBits  = SumBits + ExtFrac;
  localparam int unsigned SqParts  = smul_parts(AdcBits, 1'b0, AdcBits, 1'b0);
  localparam int unsigned GpParts  = smul_parts(AdcBits, 1'b0, GainBits, 1'b0);
  localparam int unsigned QpParts  = smul_parts(QuadBits, 1'b1, XqBits, 1'b0);
  localparam int unsigned Leaves   = GpParts + QpParts + 1;
  localparam int unsigned InBits   = UserBits + QuadBits + OffsetBits + GainBits + AdcBits;
  localparam int unsigned SqSide   = InBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (AdcBits >= 1 && AdcBits <= 24)
      else $fatal(1, "quad_core: AdcBits = %0d outside 1..24", AdcBits);
    assert (GainBits >= 1 && GainIntBits <= 16 && GainFracBits <= 32)
      else $fatal(1, "quad_core: gain U%0d.%0d outside U0..16.0..32 (at least one bit)",
                  GainIntBits, GainFracBits);
    assert (OffsetIntBits >= 1 && OffsetIntBits <= 32 && OffsetFracBits <= 32)
      else $fatal(1, "quad_core: offset S%0d.%0d outside S1..32.0..32", OffsetIntBits,
                  OffsetFracBits);
    assert (QuadIntBits >= 1 && QuadBits <= 40)
      else $fatal(1, "quad_core: quad S%0d.%0d outside S1..40 bits", QuadIntBits,
                  QuadFracBits);
    assert (SquareBits >= 1 && SquareBits <= 24)
      else $fatal(1, "quad_core: SquareBits = %0d outside 1..24", SquareBits);
    assert (OutBits >= 1 && OutBits <= 24)
      else $fatal(1, "quad_core: OutBits = %0d outside 1..24", OutBits);
    assert (Rounding <= 2 && Overflow <= 1)
      else $fatal(1, "quad_core: Rounding = %0d, Overflow = %0d outside 0..2, 0..1",
                  Rounding, Overflow);
    assert (UserBits >= 1)
      else $fatal(1, "quad_core: UserBits = %0d must be at least 1", UserBits);
    assert (SumBits <= 62 && ExtBits <= 64)
      else $fatal(1, "quad_core: sum width %0d (%0d with the floor bits) exceeds 62 (64)",
                  SumBits, ExtBits);
  end
`endif

  // Pipeline enable: the output register has room (a flop of u_out).
  logic en;

  // ---- input register ----------------------------------------------------------------------
  logic                  in_valid;
  logic [AdcBits-1:0]    in_pix;
  logic [GainBits-1:0]   in_gain;
  logic [OffsetBits-1:0] in_offset;
  logic [QuadBits-1:0]   in_quad;
  logic [UserBits-1:0]   in_user;

  irnuc_spill_register #(.DataBits(InBits), .CheckIn(CheckIn)) u_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_valid_i),
    .ready_o(s_ready_o),
    .data_i ({s_user_i, s_quad_i, s_offset_i, s_gain_i, s_pix_data_i}),
    .valid_o(in_valid),
    .ready_i(en),
    .data_o ({in_user, in_quad, in_offset, in_gain, in_pix})
  );

  // ---- square: xsq = x*x, xq = xsq >> Sq ----------------------------------------------------
  logic                             sqp_valid;
  logic [SqParts-1:0][XsqBits-1:0]  sq_parts;
  logic [SqSide-1:0]                sqp_side;

  irnuc_mul_parts #(
    .ABits   (AdcBits),
    .BBits   (AdcBits),
    .SideBits(SqSide)
  ) u_sq (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(in_valid),
    .a_i    (in_pix),
    .b_i    (in_pix),
    .side_i ({in_user, in_quad, in_offset, in_gain, in_pix}),
    .valid_o(sqp_valid),
    .parts_o(sq_parts),
    .side_o (sqp_side)
  );

  logic                  sq_valid;
  logic [XsqBits-1:0]    sq_xsq;
  logic [AdcBits-1:0]    sq_pix;
  logic [GainBits-1:0]   sq_gain;
  logic [OffsetBits-1:0] sq_offset;
  logic [QuadBits-1:0]   sq_quad;
  logic [UserBits-1:0]   sq_user;

  irnuc_add_tree #(
    .Leaves  (SqParts),
    .Width   (XsqBits),
    .SideBits(SqSide)
  ) u_sq_sum (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (sqp_valid),
    .leaves_i(sq_parts),
    .side_i  (sqp_side),
    .valid_o (sq_valid),
    .sum_o   (sq_xsq),
    .side_o  ({sq_user, sq_quad, sq_offset, sq_gain, sq_pix})
  );

  logic [XqBits-1:0] sq_xq;
  assign sq_xq = sq_xsq[XsqBits-1:SqShift];
  if (SqShift > 0) begin : gen_sq_low_unused
    logic unused_sq_low;
    assign unused_sq_low = ^sq_xsq[SqShift-1:0];
  end

  // ---- products: q*xq (signed) and x*g, side by side ---------------------------------------
  logic                            qp_valid, gp_valid;
  logic [QpParts-1:0][ExtBits-1:0] qp_parts;
  logic [GpParts-1:0][ExtBits-1:0] gp_parts;
  logic [OffsetBits-1:0]           mul_offset;
  logic [UserBits-1:0]             mul_user;
  logic                            qp_side_unused;

  irnuc_mul_parts #(
    .ABits   (QuadBits),
    .BBits   (XqBits),
    .ASigned (1'b1),
    .BSigned (1'b0),
    .PartBits(ExtBits),
    .SideBits(1)
  ) u_qp (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(sq_valid),
    .a_i    (sq_quad),
    .b_i    (sq_xq),
    .side_i (1'b0),
    .valid_o(qp_valid),
    .parts_o(qp_parts),
    .side_o (qp_side_unused)
  );

  irnuc_mul_parts #(
    .ABits   (AdcBits),
    .BBits   (GainBits),
    .PartBits(ExtBits),
    .SideBits(UserBits + OffsetBits)
  ) u_gp (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(sq_valid),
    .a_i    (sq_pix),
    .b_i    (sq_gain),
    .side_i ({sq_user, sq_offset}),
    .valid_o(gp_valid),
    .parts_o(gp_parts),
    .side_o ({mul_user, mul_offset})
  );

  // Both multipliers move with en from the same valid: qp_valid equals gp_valid.
  logic unused_qp;
  assign unused_qp = qp_valid ^ qp_side_unused;

  // ---- sum at F + K fraction bits, ExtBits signed --------------------------------------------
  logic [Leaves-1:0][ExtBits-1:0] leaves;

  for (genvar k = 0; k < GpParts; k++) begin : gen_gp_leaf
    // x*g is unsigned: its parts are zero-extended.
    assign leaves[k] = gp_parts[k] << (FracBits - GainFracBits + ExtFrac);
  end
  for (genvar k = 0; k < QpParts; k++) begin : gen_qp_leaf
    // At F + K fraction bits qp needs a left shift only when QPf < F.
    assign leaves[GpParts + k] = qp_parts[k] << (FracBits + ExtFrac - QpFrac);
  end
  // o is two's complement: sign extension.
  assign leaves[Leaves-1] = ExtBits'($signed(mul_offset)) << (FracBits - OffsetFracBits
                                                               + ExtFrac);

  logic                sum_valid;
  logic [ExtBits-1:0]  sum_ext;
  logic [UserBits-1:0] sum_user;

  irnuc_add_tree #(
    .Leaves  (Leaves),
    .Width   (ExtBits),
    .SideBits(UserBits)
  ) u_sum (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (gp_valid),
    .leaves_i(leaves),
    .side_i  (mul_user),
    .valid_o (sum_valid),
    .sum_o   (sum_ext),
    .side_o  (sum_user)
  );

  // s = floor(sum / 2^K): the K low bits are dropped.
  logic [SumBits-1:0] sum_s;
  assign sum_s = sum_ext[ExtBits-1:ExtFrac];
  if (ExtFrac > 0) begin : gen_ext_unused
    logic unused_ext;
    assign unused_ext = ^sum_ext[ExtFrac-1:0];
  end

  // ---- round, OUT and the output register (core_out; en is its output register's ready) --
  core_out #(
    .SumBits (SumBits),
    .FracBits(FracBits),
    .OutBits (OutBits),
    .Rounding(Rounding),
    .Overflow(Overflow),
    .UserBits(UserBits)
  ) u_out (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_o     (en),
    .valid_i  (sum_valid),
    .sum_i    (sum_s),
    .user_i   (sum_user),
    .m_valid_o(m_valid_o),
    .m_ready_i(m_ready_i),
    .m_data_o (m_pix_data_o),
    .m_user_o (m_user_o)
  );

  // Protocol assertions of s_* and m_* (irnuc_stream_assert, `ifdef IRNUC_ASSERT): in u_in
  // (unless CheckIn = 0) and core_out's output register, whose ports these are.

endmodule
