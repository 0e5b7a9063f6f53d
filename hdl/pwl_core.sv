// Piecewise-linear NUC, docs/datapath.md "pwl_core" (nuc_fixed.cores.pwl_core): two linear
// segments meet at the pixel's knee k, where the output is the level L:
//   d = (x << D) - k,  g = g_lo if d <= 0 else g_hi,
//   y = OUT( ROUND_F( d*g << (F - Gf - D) + L << (F - Lf) ) ),  D = Kf, F = max(Gf + D, Lf)
// (raw codes in: Xf = 0, so D = max(Kf, Xf) = Kf).
//
// Pipeline (every register moves with one enable, en = "the output register can take an
// item", a flop; see nuc_core):
//   u_in    input register (irnuc_spill_register)
//   diff    d = xa - ka and the segment's gain (xa <= ka picks g_lo), registered
//   u_mul   d * g as DSP partial products, input and output registered (irnuc_mul_parts)
//   u_sum   the aligned parts and the aligned level, clog2(parts + 1) stages
//   u_out   core_out: r = ROUND_F(s) (irnuc_round), registered, then OUT(r) (irnuc_clip)
//           into the output register (irnuc_axis_buffer)
// Latency 6 + clog2(parts + 1) cycles (piecewise14: 7); one pixel per clock. The level
// comes with every pixel (method_dpc_top holds the frame's value); UserBits of side band
// pass unchanged.
module pwl_core
  import irnuc_method_pkg::*;
#(
  parameter int unsigned AdcBits       = 14,
  parameter int unsigned GainIntBits   = 2,
  parameter int unsigned GainFracBits  = 14,
  parameter int unsigned KneeIntBits   = 14,
  parameter int unsigned KneeFracBits  = 2,
  parameter int unsigned LevelIntBits  = 14,
  parameter int unsigned LevelFracBits = 4,
  parameter int unsigned OutBits       = 14,
  parameter int unsigned Rounding      = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow      = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned UserBits      = 1,
  // s_* is checked by u_in (0: by the caller, whose driver is a checked spill register).
  parameter bit          CheckIn       = 1'b1,
  // Derived, do not override.
  localparam int unsigned GainBits     = GainIntBits + GainFracBits,
  localparam int unsigned KneeBits     = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits    = LevelIntBits + LevelFracBits
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // Input stream: raw code, the pixel's two gains and knee, the level, side band.
  input  logic                 s_valid_i,
  output logic                 s_ready_o,
  input  logic [AdcBits-1:0]   s_pix_data_i,
  input  logic [GainBits-1:0]  s_gain_lo_i,
  input  logic [GainBits-1:0]  s_gain_hi_i,
  input  logic [KneeBits-1:0]  s_knee_i,
  input  logic [LevelBits-1:0] s_level_i,
  input  logic [UserBits-1:0]  s_user_i,
  // Output stream: corrected code and the same side band.
  output logic                 m_valid_o,
  input  logic                 m_ready_i,
  output logic [OutBits-1:0]   m_pix_data_o,
  output logic [UserBits-1:0]  m_user_o
);

  // ---- derived widths (docs/datapath.md "pwl_core", nuc_fixed.widths.core_widths) --------
  localparam int unsigned DBits    = KneeFracBits;  // D = max(Kf, Xf), Xf = 0
  localparam int unsigned FracBits = max2(GainFracBits + DBits, LevelFracBits);
  localparam int unsigned XaBits   = AdcBits + DBits;
  localparam int unsigned DiffBits = max2(XaBits + 1, KneeBits + 1) + 1;  // signed
  localparam int unsigned ProdBits = DiffBits + GainBits;                 // signed
  localparam int unsigned PShift   = FracBits - GainFracBits - DBits;
  localparam int unsigned LShift   = FracBits - LevelFracBits;
  localparam int unsigned SumBits  = max2(ProdBits + PShift, LevelBits + 1 + LShift) + 1;
  localparam int unsigned Parts    = smul_parts(DiffBits, 1'b1, GainBits, 1'b0);
  localparam int unsigned InBits   = UserBits + LevelBits + KneeBits + 2 * GainBits + AdcBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (AdcBits >= 1 && AdcBits <= 24)
      else $fatal(1, "pwl_core: AdcBits = %0d outside 1..24", AdcBits);
    assert (GainBits >= 1 && GainIntBits <= 16 && GainFracBits <= 32)
      else $fatal(1, "pwl_core: gain U%0d.%0d outside U0..16.0..32 (at least one bit)",
                  GainIntBits, GainFracBits);
    assert (KneeIntBits >= AdcBits && KneeBits <= 40)
      else $fatal(1, "pwl_core: knee U%0d.%0d: at least AdcBits = %0d integer bits",
                  KneeIntBits, KneeFracBits, AdcBits);
    assert (LevelBits >= 1 && LevelBits <= 40)
      else $fatal(1, "pwl_core: level U%0d.%0d outside 1..40 bits", LevelIntBits,
                  LevelFracBits);
    assert (OutBits >= 1 && OutBits <= 24)
      else $fatal(1, "pwl_core: OutBits = %0d outside 1..24", OutBits);
    assert (Rounding <= 2 && Overflow <= 1)
      else $fatal(1, "pwl_core: Rounding = %0d, Overflow = %0d outside 0..2, 0..1",
                  Rounding, Overflow);
    assert (UserBits >= 1)
      else $fatal(1, "pwl_core: UserBits = %0d must be at least 1", UserBits);
    assert (SumBits <= 62)
      else $fatal(1, "pwl_core: sum width %0d exceeds 62", SumBits);
  end
`endif

  // Pipeline enable: the output register has room (a flop of u_out).
  logic en;

  // ---- input register ----------------------------------------------------------------------
  logic                 in_valid;
  logic [AdcBits-1:0]   in_pix;
  logic [GainBits-1:0]  in_gain_lo, in_gain_hi;
  logic [KneeBits-1:0]  in_knee;
  logic [LevelBits-1:0] in_level;
  logic [UserBits-1:0]  in_user;

  irnuc_spill_register #(.DataBits(InBits), .CheckIn(CheckIn)) u_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_valid_i),
    .ready_o(s_ready_o),
    .data_i ({s_user_i, s_level_i, s_knee_i, s_gain_hi_i, s_gain_lo_i, s_pix_data_i}),
    .valid_o(in_valid),
    .ready_i(en),
    .data_o ({in_user, in_level, in_knee, in_gain_hi, in_gain_lo, in_pix})
  );

  // ---- diff: d = (x << D) - k and the segment's gain -------------------------------------
  logic [DiffBits-1:0] xa, ka;
  assign xa = DiffBits'(in_pix) << DBits;
  assign ka = DiffBits'(in_knee);

  logic                 diff_valid_q;
  logic [DiffBits-1:0]  diff_q;
  logic [GainBits-1:0]  diff_gain_q;
  logic [LevelBits-1:0] diff_level_q;
  logic [UserBits-1:0]  diff_user_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_diff_valid
    if (!rst_ni) begin
      diff_valid_q <= 1'b0;
    end else if (en) begin
      diff_valid_q <= in_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_diff
    if (en) begin
      diff_q       <= xa - ka;
      // d <= 0 exactly when xa <= ka (both non-negative).
      diff_gain_q  <= (xa <= ka) ? in_gain_lo : in_gain_hi;
      diff_level_q <= in_level;
      diff_user_q  <= in_user;
    end
  end

  // ---- product: d * g, signed -------------------------------------------------------------
  logic                           mul_valid;
  logic [Parts-1:0][SumBits-1:0]  prod_parts;
  logic [LevelBits-1:0]           mul_level;
  logic [UserBits-1:0]            mul_user;

  irnuc_mul_parts #(
    .ABits   (DiffBits),
    .BBits   (GainBits),
    .ASigned (1'b1),
    .BSigned (1'b0),
    .PartBits(SumBits),
    .SideBits(UserBits + LevelBits)
  ) u_mul (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(diff_valid_q),
    .a_i    (diff_q),
    .b_i    (diff_gain_q),
    .side_i ({diff_user_q, diff_level_q}),
    .valid_o(mul_valid),
    .parts_o(prod_parts),
    .side_o ({mul_user, mul_level})
  );

  // ---- sum: s = d*g << (F - Gf - D) + L << (F - Lf), SumBits signed ----------------------
  logic [Parts:0][SumBits-1:0] leaves;

  for (genvar k = 0; k < Parts; k++) begin : gen_leaf
    assign leaves[k] = prod_parts[k] << PShift;
  end
  assign leaves[Parts] = SumBits'(mul_level) << LShift;  // unsigned: zero extension

  logic                sum_valid;
  logic [SumBits-1:0]  sum_s;
  logic [UserBits-1:0] sum_user;

  irnuc_add_tree #(
    .Leaves  (Parts + 1),
    .Width   (SumBits),
    .SideBits(UserBits)
  ) u_sum (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (mul_valid),
    .leaves_i(leaves),
    .side_i  (mul_user),
    .valid_o (sum_valid),
    .sum_o   (sum_s),
    .side_o  (sum_user)
  );

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
