// Two-point non-uniformity correction, docs/datapath.md section "NUC":
//   y = OUT( ROUND_F( x*g*2^(F-Gf) + o*2^(F-Of) ) ),  F = max(Gf, Of)
//
// Pipeline (every register moves with one enable, en = "the output register can take an
// item", itself a flop, so no path runs from m_ready_i to s_ready_o):
//   u_in       input register (irnuc_spill_register): registered s_ready_o and DSP inputs
//   u_mul      p = x*g as DSP-sized partial products, registered (irnuc_mul_parts)
//   u_sum      s = sum of the aligned partial products and the aligned offset, one level
//              of additions per stage (irnuc_add_tree, clog2(parts + 1) stages)
//   round      r = ROUND_F(s) = (s >>> F) + inc, inc from the fraction bits, registered
//   u_out      OUT(r) (saturate or wrap) into the output register (irnuc_spill_register)
// Latency: 4 + clog2(parts + 1) cycles, parts = ceil(A/17) * ceil(GW/17) (typical14 and
// minimal: 5, wide16: 6); one pixel per clock. UserBits of side band (markers, bad flag)
// travel with each pixel unchanged.
module nuc_core
  import irnuc_pkg::*;
#(
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow       = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned UserBits       = 1,
  // s_* is checked by u_in (0: by the caller, whose driver is a checked spill register).
  parameter bit          CheckIn        = 1'b1,
  // Derived, do not override.
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Input stream: raw code, coefficients and side band of one pixel.
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [AdcBits-1:0]    s_pix_data_i,
  input  logic [GainBits-1:0]   s_gain_i,
  input  logic [OffsetBits-1:0] s_offset_i,
  input  logic [UserBits-1:0]   s_user_i,
  // Output stream: corrected code and the same side band.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic [UserBits-1:0]   m_user_o
);

  // ---- derived widths (docs/datapath.md, table "Step by step") ----------------------
  localparam rounding_e RoundMode    = rounding_e'(Rounding);
  localparam overflow_e OverflowMode = overflow_e'(Overflow);
  localparam int unsigned FracBits =
      (GainFracBits > OffsetFracBits) ? GainFracBits : OffsetFracBits;
  localparam int unsigned ProdBits = AdcBits + GainBits;
  localparam int unsigned SumBitsA = AdcBits + GainIntBits + FracBits + 1;
  localparam int unsigned SumBitsB = OffsetIntBits + FracBits;
  localparam int unsigned SumBits  = ((SumBitsA > SumBitsB) ? SumBitsA : SumBitsB) + 1;
  // r = ROUND_F(s) needs one bit more than the integer part of s (docs/datapath.md).
  localparam int unsigned RndBits  = SumBits + 1 - FracBits;
  localparam int unsigned Parts    = mul_parts(AdcBits, GainBits);
  localparam int unsigned InBits   = UserBits + OffsetBits + GainBits + AdcBits;

`ifndef SYNTHESIS
  // Legal ranges (nuc_fixed/config.py checks the same before any build).
  initial begin : p_param_ranges
    assert (AdcBits >= AdcBitsMin && AdcBits <= AdcBitsMax)
      else $fatal(1, "nuc_core: AdcBits = %0d outside %0d..%0d", AdcBits, AdcBitsMin,
                  AdcBitsMax);
    // (the Min of GainIntBits, GainFracBits and OffsetFracBits is 0: nothing to check)
    assert (GainIntBits <= GainIntBitsMax)
      else $fatal(1, "nuc_core: GainIntBits = %0d outside 0..%0d", GainIntBits,
                  GainIntBitsMax);
    assert (GainFracBits <= GainFracBitsMax)
      else $fatal(1, "nuc_core: GainFracBits = %0d outside 0..%0d", GainFracBits,
                  GainFracBitsMax);
    assert (GainBits >= 1)
      else $fatal(1, "nuc_core: GainIntBits + GainFracBits must be at least 1");
    assert (OffsetIntBits >= OffsetIntBitsMin && OffsetIntBits <= OffsetIntBitsMax)
      else $fatal(1, "nuc_core: OffsetIntBits = %0d outside %0d..%0d", OffsetIntBits,
                  OffsetIntBitsMin, OffsetIntBitsMax);
    assert (OffsetFracBits <= OffsetFracBitsMax)
      else $fatal(1, "nuc_core: OffsetFracBits = %0d outside 0..%0d", OffsetFracBits,
                  OffsetFracBitsMax);
    assert (OutBits >= OutBitsMin && OutBits <= OutBitsMax)
      else $fatal(1, "nuc_core: OutBits = %0d outside %0d..%0d", OutBits, OutBitsMin,
                  OutBitsMax);
    assert (Rounding < RoundingCount)
      else $fatal(1, "nuc_core: Rounding = %0d outside 0..%0d", Rounding, RoundingCount - 1);
    assert (Overflow < OverflowCount)
      else $fatal(1, "nuc_core: Overflow = %0d outside 0..%0d", Overflow, OverflowCount - 1);
    assert (UserBits >= 1)
      else $fatal(1, "nuc_core: UserBits = %0d must be at least 1", UserBits);
    assert (SumBits <= SumBitsMax)
      else $fatal(1, "nuc_core: sum width %0d exceeds %0d", SumBits, SumBitsMax);
  end
`endif

  // Pipeline enable: the output register has room (a flop of u_out).
  logic en;

  // ---- input register ----------------------------------------------------------------
  logic                  in_valid;
  logic [AdcBits-1:0]    in_pix;
  logic [GainBits-1:0]   in_gain;
  logic [OffsetBits-1:0] in_offset;
  logic [UserBits-1:0]   in_user;

  irnuc_spill_register #(.DataBits(InBits), .CheckIn(CheckIn)) u_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_valid_i),
    .ready_o(s_ready_o),
    .data_i ({s_user_i, s_offset_i, s_gain_i, s_pix_data_i}),
    .valid_o(in_valid),
    .ready_i(en),
    .data_o ({in_user, in_offset, in_gain, in_pix})
  );

  // ---- product: registered partial products ------------------------------------------
  logic                               mul_valid;
  logic [Parts-1:0][ProdBits-1:0]     prod_parts;
  logic [OffsetBits-1:0]              mul_offset;
  logic [UserBits-1:0]                mul_user;

  irnuc_mul_parts #(
    .ABits   (AdcBits),
    .BBits   (GainBits),
    .SideBits(UserBits + OffsetBits)
  ) u_mul (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(in_valid),
    .a_i    (in_pix),
    .b_i    (in_gain),
    .side_i ({in_user, in_offset}),
    .valid_o(mul_valid),
    .parts_o(prod_parts),
    .side_o ({mul_user, mul_offset})
  );

  // ---- sum: s = p << (F-Gf) + o << (F-Of), SumBits signed ------------------------------
  logic [Parts:0][SumBits-1:0] leaves;

  for (genvar k = 0; k < Parts; k++) begin : gen_leaf
    // p is unsigned: zero extension.
    assign leaves[k] = SumBits'(prod_parts[k]) << (FracBits - GainFracBits);
  end
  // o is two's complement: sign extension.
  assign leaves[Parts] = SumBits'($signed(mul_offset)) << (FracBits - OffsetFracBits);

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

  // ---- round: r = (s >>> F) + inc ---------------------------------------------------------
  // Adding the rounding constant of docs/datapath.md carries into the integer part exactly
  // when: half_up f >= 1/2 (bit F-1); half_even f > 1/2, or f = 1/2 and the integer part
  // is odd; truncate never.
  logic inc;

  if (FracBits == 0 || RoundMode == RoundTruncate) begin : gen_inc_none
    assign inc = 1'b0;
    if (FracBits > 0) begin : gen_frac_unused
      logic unused_frac;
      assign unused_frac = ^sum_s[FracBits-1:0];
    end
  end else if (RoundMode == RoundHalfUp) begin : gen_inc_half_up
    assign inc = sum_s[FracBits-1];
    if (FracBits > 1) begin : gen_frac_unused
      logic unused_frac;
      assign unused_frac = ^sum_s[FracBits-2:0];
    end
  end else begin : gen_inc_half_even
    logic sticky;  // fraction bits below the half
    if (FracBits > 1) begin : gen_sticky
      assign sticky = |sum_s[FracBits-2:0];
    end else begin : gen_no_sticky
      assign sticky = 1'b0;
    end
    assign inc = sum_s[FracBits-1] & (sticky | sum_s[FracBits]);
  end

  logic                       rnd_valid_q;
  logic signed [RndBits-1:0]  rnd_q;
  logic [UserBits-1:0]        rnd_user_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_round_valid
    if (!rst_ni) begin
      rnd_valid_q <= 1'b0;
    end else if (en) begin
      rnd_valid_q <= sum_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_round
    if (en) begin
      // Keeping bits [SumBits-1:F] is the arithmetic (floor) shift by F.
      rnd_q      <= RndBits'($signed(sum_s[SumBits-1:FracBits])) + RndBits'(inc);
      rnd_user_q <= sum_user;
    end
  end

  // ---- OUT (saturate or wrap to B bits) into the output register -------------------------
  logic [OutBits-1:0] out_d;

  if (OverflowMode == OverflowSaturate) begin : gen_saturate
    logic too_big;
    if (RndBits - 1 > OutBits) begin : gen_hi_check
      // r is positive and has a set bit at or above 2^B.
      assign too_big = |rnd_q[RndBits-2:OutBits];
    end else begin : gen_no_hi_check
      // r has no more than B magnitude bits: it cannot exceed 2^B - 1.
      assign too_big = 1'b0;
    end
    always_comb begin : p_saturate
      if (rnd_q[RndBits-1]) begin
        out_d = '0;
      end else if (too_big) begin
        out_d = '1;
      end else begin
        out_d = OutBits'(rnd_q[RndBits-2:0]);
      end
    end
  end else begin : gen_wrap
    if (RndBits >= OutBits) begin : gen_low_bits
      assign out_d = rnd_q[OutBits-1:0];
      if (RndBits > OutBits) begin : gen_hi_unused
        logic unused_hi;
        assign unused_hi = ^rnd_q[RndBits-1:OutBits];
      end
    end else begin : gen_sign_ext
      // r mod 2^B of a narrower two's complement number is its sign extension.
      assign out_d = OutBits'(rnd_q);
    end
  end

  irnuc_spill_register #(.DataBits(UserBits + OutBits)) u_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(rnd_valid_q),
    .ready_o(en),
    .data_i ({rnd_user_q, out_d}),
    .valid_o(m_valid_o),
    .ready_i(m_ready_i),
    .data_o ({m_user_o, m_pix_data_o})
  );

  // Protocol assertions of s_* and m_* (irnuc_stream_assert, `ifdef IRNUC_ASSERT): in u_in
  // (unless CheckIn = 0) and u_out, whose ports these are.

endmodule
