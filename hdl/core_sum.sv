// The aligned sum s of a base method's core for an input x of any width, signedness and
// fraction bits (docs/datapath.md "Core input", "Cores, per pixel"; nuc_fixed.cores with
// sum_only): the core of the compositions, on x' of drift_sub (signed, Xf = Df) and on the
// FFC accumulator (A + n bits, Xf = n) as well as on raw codes.
//
//   lin   s = x*g << (F - Gf - Xf) + o << (F - Of),                 F = max(Gf + Xf, Of, Fmin)
//   quad  s = lin + qs,  xq = (x*x) >> (2 Xf + Sq),  qs = q*xq at F fraction bits (floor),
//         QPf = Qf + 2A - Sq
//   pwl   d = (x << (D - Xf)) - (k << (D - Kf)),  g = g_lo if d <= 0 else g_hi,
//         s = d*g << (F - Gf - D) + L << (F - Lf),  D = max(Kf, Xf),  F = max(Gf + D, Lf, Fmin)
//
// A building block of an enclosing pipeline (like irnuc_mul_parts): every register moves
// with en_i, the valid flag and SideBits of side band travel along, only the valid flags
// reset. Stages (irnuc_stage_pkg::core_sum_latency):
//   lin   u_mul x*g (2, the DSP's registers), u_sum parts and offset (clog2(parts + 1))
//   quad  u_sq x*x (2), u_sq_sum (clog2(square parts)), u_qp q*xq beside u_gp x*g (2),
//         u_sum (clog2(parts + 1)); qs's floor is the K = QPf - F low bits of the sum,
//         formed at F + K fraction bits, dropped (every other term is a multiple of 2^-F)
//   pwl   diff d and the segment's gain (1), u_mul d*g (2), u_sum parts and level
// then Latency - that of delay (Latency = 0: none). MinFracBits raises F so that a term
// with more fraction bits (the FFC correction) can be added to the sum unchanged.
module core_sum
  import irnuc_method_pkg::*;
  import irnuc_stage_pkg::*;
#(
  parameter int unsigned Kind           = 0,  // irnuc_stage_pkg::core_kind_e
  parameter int unsigned XBits          = 14,
  parameter bit          XSigned        = 1'b0,
  parameter int unsigned XFracBits      = 0,
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned QuadIntBits    = 10,
  parameter int unsigned QuadFracBits   = 6,
  parameter int unsigned SquareBits     = 18,
  parameter int unsigned KneeIntBits    = 14,
  parameter int unsigned KneeFracBits   = 2,
  parameter int unsigned LevelIntBits   = 14,
  parameter int unsigned LevelFracBits  = 4,
  parameter int unsigned MinFracBits    = 0,
  parameter int unsigned Latency        = 0,
  parameter int unsigned SideBits       = 1,
  // Derived, do not override.
  localparam core_kind_e  KindSel       = core_kind_e'(Kind),
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned QuadBits      = QuadIntBits + QuadFracBits,
  localparam int unsigned KneeBits      = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits     = LevelIntBits + LevelFracBits,
  localparam int unsigned FracBits      = core_frac(KindSel, XFracBits, GainFracBits,
                                                    OffsetFracBits, KneeFracBits,
                                                    LevelFracBits, MinFracBits),
  localparam int unsigned SumBits       = core_sum_bits(KindSel, XBits, XSigned, XFracBits,
                                                        AdcBits, GainBits, GainFracBits,
                                                        OffsetBits, OffsetFracBits, QuadBits,
                                                        QuadFracBits, SquareBits, KneeBits,
                                                        KneeFracBits, LevelBits,
                                                        LevelFracBits, MinFracBits),
  localparam int unsigned Natural       = core_sum_latency(KindSel, XBits, XSigned,
                                                           XFracBits, AdcBits, GainBits,
                                                           QuadBits, SquareBits, KneeBits,
                                                           KneeFracBits),
  localparam int unsigned Stages        = (Latency == 0) ? Natural : Latency
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  en_i,
  input  logic                  valid_i,
  input  logic [XBits-1:0]      x_i,
  input  logic [GainBits-1:0]   gain_i,     // g (pwl: g_lo)
  input  logic [GainBits-1:0]   gain_hi_i,  // pwl: g_hi
  input  logic [OffsetBits-1:0] offset_i,   // lin, quad
  input  logic [QuadBits-1:0]   quad_i,     // quad
  input  logic [KneeBits-1:0]   knee_i,     // pwl
  input  logic [LevelBits-1:0]  level_i,    // pwl
  input  logic [SideBits-1:0]   side_i,
  output logic                  valid_o,
  output logic [SumBits-1:0]    sum_o,      // s, signed, FracBits fraction bits
  output logic [SideBits-1:0]   side_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (Kind <= 32'(CorePwl))
      else $fatal(1, "core_sum: Kind = %0d outside 0..2", Kind);
    assert (XBits >= 1 && XBits <= 40 && XFracBits < XBits + 1)
      else $fatal(1, "core_sum: XBits = %0d, XFracBits = %0d out of range", XBits, XFracBits);
    assert (KindSel == CoreLin || !XSigned)
      else $fatal(1, "core_sum: only the linear core takes a signed input");
    assert (KindSel != CoreQuad || XBits == AdcBits + XFracBits)
      else $fatal(1, "core_sum: the quadratic core needs XBits = AdcBits + XFracBits");
    assert (GainBits >= 1 && OffsetIntBits >= 1 && SideBits >= 1)
      else $fatal(1, "core_sum: empty gain or offset format, or no side band");
    assert (SumBits <= 62)
      else $fatal(1, "core_sum: sum width %0d exceeds 62", SumBits);
    assert (Stages >= Natural)
      else $fatal(1, "core_sum: Latency = %0d below the core's %0d stages", Latency, Natural);
  end
`endif

  logic                sum_valid;
  logic [SumBits-1:0]  sum_s;
  logic [SideBits-1:0] sum_side;

  if (KindSel == CoreLin) begin : gen_lin
    localparam int unsigned Parts = smul_parts(XBits, XSigned, GainBits, 1'b0);
    localparam int unsigned PShift = FracBits - GainFracBits - XFracBits;

    logic                            mul_valid;
    logic [Parts-1:0][SumBits-1:0]   prod_parts;
    logic [OffsetBits-1:0]           mul_offset;
    logic [SideBits-1:0]             mul_side;

    irnuc_mul_parts #(
      .ABits   (XBits),
      .BBits   (GainBits),
      .ASigned (XSigned),
      .BSigned (1'b0),
      .PartBits(SumBits),
      .SideBits(SideBits + OffsetBits)
    ) u_mul (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en_i),
      .valid_i(valid_i),
      .a_i    (x_i),
      .b_i    (gain_i),
      .side_i ({side_i, offset_i}),
      .valid_o(mul_valid),
      .parts_o(prod_parts),
      .side_o ({mul_side, mul_offset})
    );

    logic [Parts:0][SumBits-1:0] leaves;
    for (genvar k = 0; k < Parts; k++) begin : gen_leaf
      assign leaves[k] = prod_parts[k] << PShift;
    end
    assign leaves[Parts] = SumBits'($signed(mul_offset)) << (FracBits - OffsetFracBits);

    irnuc_add_tree #(
      .Leaves  (Parts + 1),
      .Width   (SumBits),
      .SideBits(SideBits)
    ) u_sum (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (en_i),
      .valid_i (mul_valid),
      .leaves_i(leaves),
      .side_i  (mul_side),
      .valid_o (sum_valid),
      .sum_o   (sum_s),
      .side_o  (sum_side)
    );

    logic unused_lin;
    assign unused_lin = ^{gain_hi_i, quad_i, knee_i, level_i};
  end else if (KindSel == CoreQuad) begin : gen_quad
    localparam int unsigned SqShift = 2 * XFracBits + square_shift(AdcBits, SquareBits);
    localparam int unsigned XsqBits = 2 * XBits;
    localparam int unsigned XqBits  = XsqBits - SqShift;
    localparam int unsigned QpFrac  = quad_qp_frac(AdcBits, QuadFracBits, SquareBits);
    localparam int unsigned ExtFrac = (QpFrac > FracBits) ? QpFrac - FracBits : 0;  // K
    localparam int unsigned ExtBits = SumBits + ExtFrac;
    localparam int unsigned SqParts = smul_parts(XBits, 1'b0, XBits, 1'b0);
    localparam int unsigned GpParts = smul_parts(XBits, 1'b0, GainBits, 1'b0);
    localparam int unsigned QpParts = smul_parts(QuadBits, 1'b1, XqBits, 1'b0);
    localparam int unsigned Leaves  = GpParts + QpParts + 1;
    localparam int unsigned Side1   = SideBits + QuadBits + OffsetBits + GainBits + XBits;

`ifndef SYNTHESIS
    initial begin : p_ext_range
      assert (ExtBits <= 64)
        else $fatal(1, "core_sum: quadratic sum with its floor bits %0d exceeds 64", ExtBits);
    end
`endif

    // ---- xsq = x*x, xq = xsq >> (2 Xf + Sq) ------------------------------------------------
    logic                            sqp_valid;
    logic [SqParts-1:0][XsqBits-1:0] sq_parts;
    logic [Side1-1:0]                sqp_side;

    irnuc_mul_parts #(
      .ABits   (XBits),
      .BBits   (XBits),
      .SideBits(Side1)
    ) u_sq (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en_i),
      .valid_i(valid_i),
      .a_i    (x_i),
      .b_i    (x_i),
      .side_i ({side_i, quad_i, offset_i, gain_i, x_i}),
      .valid_o(sqp_valid),
      .parts_o(sq_parts),
      .side_o (sqp_side)
    );

    logic                  sq_valid;
    logic [XsqBits-1:0]    sq_xsq;
    logic [XBits-1:0]      sq_x;
    logic [GainBits-1:0]   sq_gain;
    logic [OffsetBits-1:0] sq_offset;
    logic [QuadBits-1:0]   sq_quad;
    logic [SideBits-1:0]   sq_side;

    irnuc_add_tree #(
      .Leaves  (SqParts),
      .Width   (XsqBits),
      .SideBits(Side1)
    ) u_sq_sum (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (en_i),
      .valid_i (sqp_valid),
      .leaves_i(sq_parts),
      .side_i  (sqp_side),
      .valid_o (sq_valid),
      .sum_o   (sq_xsq),
      .side_o  ({sq_side, sq_quad, sq_offset, sq_gain, sq_x})
    );

    logic [XqBits-1:0] sq_xq;
    assign sq_xq = sq_xsq[XsqBits-1:SqShift];
    if (SqShift > 0) begin : gen_sq_low
      logic unused_sq_low;
      assign unused_sq_low = ^sq_xsq[SqShift-1:0];
    end

    // ---- q*xq (signed) beside x*g ----------------------------------------------------------
    logic                            qp_valid, gp_valid, qp_side;
    logic [QpParts-1:0][ExtBits-1:0] qp_parts;
    logic [GpParts-1:0][ExtBits-1:0] gp_parts;
    logic [OffsetBits-1:0]           mul_offset;
    logic [SideBits-1:0]             mul_side;

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
      .en_i   (en_i),
      .valid_i(sq_valid),
      .a_i    (sq_quad),
      .b_i    (sq_xq),
      .side_i (1'b0),
      .valid_o(qp_valid),
      .parts_o(qp_parts),
      .side_o (qp_side)
    );

    irnuc_mul_parts #(
      .ABits   (XBits),
      .BBits   (GainBits),
      .PartBits(ExtBits),
      .SideBits(SideBits + OffsetBits)
    ) u_gp (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en_i),
      .valid_i(sq_valid),
      .a_i    (sq_x),
      .b_i    (sq_gain),
      .side_i ({sq_side, sq_offset}),
      .valid_o(gp_valid),
      .parts_o(gp_parts),
      .side_o ({mul_side, mul_offset})
    );

    // Both multipliers move with en_i from the same valid flag.
    logic unused_qp;
    assign unused_qp = qp_valid ^ qp_side;

    // ---- the sum at F + K fraction bits -----------------------------------------------------
    logic [Leaves-1:0][ExtBits-1:0] leaves;
    for (genvar k = 0; k < GpParts; k++) begin : gen_gp_leaf
      assign leaves[k] = gp_parts[k] << (FracBits - GainFracBits - XFracBits + ExtFrac);
    end
    for (genvar k = 0; k < QpParts; k++) begin : gen_qp_leaf
      assign leaves[GpParts + k] = qp_parts[k] << (FracBits + ExtFrac - QpFrac);
    end
    assign leaves[Leaves-1] = ExtBits'($signed(mul_offset))
                              << (FracBits - OffsetFracBits + ExtFrac);

    logic [ExtBits-1:0] sum_ext;

    irnuc_add_tree #(
      .Leaves  (Leaves),
      .Width   (ExtBits),
      .SideBits(SideBits)
    ) u_sum (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (en_i),
      .valid_i (gp_valid),
      .leaves_i(leaves),
      .side_i  (mul_side),
      .valid_o (sum_valid),
      .sum_o   (sum_ext),
      .side_o  (sum_side)
    );

    // s = floor(sum / 2^K): the K low bits are dropped.
    assign sum_s = sum_ext[ExtBits-1:ExtFrac];
    if (ExtFrac > 0) begin : gen_ext_low
      logic unused_ext;
      assign unused_ext = ^sum_ext[ExtFrac-1:0];
    end

    logic unused_quad;
    assign unused_quad = ^{gain_hi_i, knee_i, level_i};
  end else begin : gen_pwl
    localparam int unsigned DBits    = pwl_d_frac(KneeFracBits, XFracBits);
    localparam int unsigned DiffBits = pwl_diff_bits(XBits, XSigned, XFracBits, KneeBits,
                                                     KneeFracBits);
    localparam int unsigned Parts    = smul_parts(DiffBits, 1'b1, GainBits, 1'b0);

    // ---- d and the segment's gain ----------------------------------------------------------
    logic [DiffBits-1:0] xa, ka;
    assign xa = DiffBits'(x_i) << (DBits - XFracBits);
    assign ka = DiffBits'(knee_i) << (DBits - KneeFracBits);

    logic                 diff_valid_q;
    logic [DiffBits-1:0]  diff_q;
    logic [GainBits-1:0]  diff_gain_q;
    logic [LevelBits-1:0] diff_level_q;
    logic [SideBits-1:0]  diff_side_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin : p_diff_valid
      if (!rst_ni) begin
        diff_valid_q <= 1'b0;
      end else if (en_i) begin
        diff_valid_q <= valid_i;
      end
    end

    always_ff @(posedge clk_i) begin : p_diff
      if (en_i) begin
        diff_q       <= xa - ka;
        // d <= 0 exactly when xa <= ka (both non-negative).
        diff_gain_q  <= (xa <= ka) ? gain_i : gain_hi_i;
        diff_level_q <= level_i;
        diff_side_q  <= side_i;
      end
    end

    // ---- d*g and the sum with the level ----------------------------------------------------
    logic                          mul_valid;
    logic [Parts-1:0][SumBits-1:0] prod_parts;
    logic [LevelBits-1:0]          mul_level;
    logic [SideBits-1:0]           mul_side;

    irnuc_mul_parts #(
      .ABits   (DiffBits),
      .BBits   (GainBits),
      .ASigned (1'b1),
      .BSigned (1'b0),
      .PartBits(SumBits),
      .SideBits(SideBits + LevelBits)
    ) u_mul (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en_i),
      .valid_i(diff_valid_q),
      .a_i    (diff_q),
      .b_i    (diff_gain_q),
      .side_i ({diff_side_q, diff_level_q}),
      .valid_o(mul_valid),
      .parts_o(prod_parts),
      .side_o ({mul_side, mul_level})
    );

    logic [Parts:0][SumBits-1:0] leaves;
    for (genvar k = 0; k < Parts; k++) begin : gen_leaf
      assign leaves[k] = prod_parts[k] << (FracBits - GainFracBits - DBits);
    end
    // The level is unsigned: zero extension.
    assign leaves[Parts] = SumBits'(mul_level) << (FracBits - LevelFracBits);

    irnuc_add_tree #(
      .Leaves  (Parts + 1),
      .Width   (SumBits),
      .SideBits(SideBits)
    ) u_sum (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (en_i),
      .valid_i (mul_valid),
      .leaves_i(leaves),
      .side_i  (mul_side),
      .valid_o (sum_valid),
      .sum_o   (sum_s),
      .side_o  (sum_side)
    );

    logic unused_pwl;
    assign unused_pwl = ^{offset_i, quad_i};
  end

  // ---- padding to Latency ----------------------------------------------------------------
  if (Stages == Natural) begin : gen_no_pad
    assign valid_o = sum_valid;
    assign sum_o   = sum_s;
    assign side_o  = sum_side;
  end else begin : gen_pad
    localparam int unsigned Pad = Stages - Natural;
    logic [Pad-1:0]                       pad_valid_q;
    logic [Pad-1:0][SumBits+SideBits-1:0] pad_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin : p_pad_valid
      if (!rst_ni) begin
        pad_valid_q <= '0;
      end else if (en_i) begin
        pad_valid_q[0] <= sum_valid;
        for (int unsigned i = 1; i < Pad; i++) pad_valid_q[i] <= pad_valid_q[i-1];
      end
    end

    always_ff @(posedge clk_i) begin : p_pad
      if (en_i) begin
        pad_q[0] <= {sum_side, sum_s};
        for (int unsigned i = 1; i < Pad; i++) pad_q[i] <= pad_q[i-1];
      end
    end

    assign valid_o           = pad_valid_q[Pad-1];
    assign {side_o, sum_o}   = pad_q[Pad-1];
  end

endmodule
