// Two-point non-uniformity correction, docs/datapath.md section "NUC":
//   y = OUT( ROUND_F( x*g*2^(F-Gf) + o*2^(F-Of) ) ),  F = max(Gf, Of)
//
// Three pipeline stages with a valid/ready handshake on both sides; a stage takes a new
// item when it is empty or its content moves on in the same cycle, so the core runs one
// pixel per clock when the output is not back-pressured. UserBits of sideband (markers,
// bad flag) travel with each pixel unchanged.
//   stage 1: p = x*g (unsigned, A+GW bits), offset code registered
//   stage 2: s = (p << (F-Gf)) + (o << (F-Of)), r = ROUND_F(s)
//   stage 3: y = OUT(r)
module nuc_core #(
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,  // 0 truncate, 1 half_up, 2 half_even
  parameter int unsigned Overflow       = 0,  // 0 saturate, 1 wrap
  parameter int unsigned UserBits       = 1,
  // Derived, do not override.
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Input stream: raw code, coefficients and sideband of one pixel.
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [AdcBits-1:0]    s_pix_data_i,
  input  logic [GainBits-1:0]   s_gain_i,
  input  logic [OffsetBits-1:0] s_offset_i,
  input  logic [UserBits-1:0]   s_user_i,
  // Output stream: corrected code and the same sideband.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic [UserBits-1:0]   m_user_o
);

  // ---- derived widths (docs/datapath.md, table "Step by step") ----------------------
  localparam int unsigned FracBits =
      (GainFracBits > OffsetFracBits) ? GainFracBits : OffsetFracBits;
  localparam int unsigned ProdBits = AdcBits + GainBits;
  localparam int unsigned SumBitsA = AdcBits + GainIntBits + FracBits + 1;
  localparam int unsigned SumBitsB = OffsetIntBits + FracBits;
  localparam int unsigned SumBits  = ((SumBitsA > SumBitsB) ? SumBitsA : SumBitsB) + 1;
  // The rounding add is done in SumBits+1 bits; r keeps the integer part of that.
  localparam int unsigned AddBits  = SumBits + 1;
  localparam int unsigned RndBits  = AddBits - FracBits;

`ifndef SYNTHESIS
  // Legal ranges (nuc_fixed/config.py checks the same before any build).
  initial begin : p_param_ranges
    assert (AdcBits >= 1 && AdcBits <= 24)
      else $fatal(1, "nuc_core: AdcBits = %0d outside 1..24", AdcBits);
    assert (GainIntBits <= 16)
      else $fatal(1, "nuc_core: GainIntBits = %0d outside 0..16", GainIntBits);
    assert (GainFracBits <= 32)
      else $fatal(1, "nuc_core: GainFracBits = %0d outside 0..32", GainFracBits);
    assert (GainBits >= 1)
      else $fatal(1, "nuc_core: GainIntBits + GainFracBits must be at least 1");
    assert (OffsetIntBits >= 1 && OffsetIntBits <= 32)
      else $fatal(1, "nuc_core: OffsetIntBits = %0d outside 1..32", OffsetIntBits);
    assert (OffsetFracBits <= 32)
      else $fatal(1, "nuc_core: OffsetFracBits = %0d outside 0..32", OffsetFracBits);
    assert (OutBits >= 1 && OutBits <= 24)
      else $fatal(1, "nuc_core: OutBits = %0d outside 1..24", OutBits);
    assert (Rounding <= 2)
      else $fatal(1, "nuc_core: Rounding = %0d outside 0..2", Rounding);
    assert (Overflow <= 1)
      else $fatal(1, "nuc_core: Overflow = %0d outside 0..1", Overflow);
    assert (UserBits >= 1)
      else $fatal(1, "nuc_core: UserBits = %0d must be at least 1", UserBits);
    assert (SumBits <= 62)
      else $fatal(1, "nuc_core: sum width %0d exceeds 62", SumBits);
  end
`endif

  // ---- handshake: a stage loads when it is empty or drains in the same cycle ----------
  logic [2:0] valid_q;
  logic [2:0] load;
  logic       ready1, ready2, ready3;

  assign ready3    = ~valid_q[2] | m_ready_i;
  assign ready2    = ~valid_q[1] | ready3;
  assign ready1    = ~valid_q[0] | ready2;
  assign s_ready_o = ready1;
  assign load[0]   = ready1;
  assign load[1]   = ready2;
  assign load[2]   = ready3;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_valid
    if (!rst_ni) begin
      valid_q <= '0;
    end else begin
      if (load[0]) valid_q[0] <= s_valid_i;
      if (load[1]) valid_q[1] <= valid_q[0];
      if (load[2]) valid_q[2] <= valid_q[1];
    end
  end

  // ---- stage 1: product ------------------------------------------------------------
  logic [ProdBits-1:0]   prod_q;
  logic [OffsetBits-1:0] offs_q;
  logic [UserBits-1:0]   user1_q, user2_q, user3_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_stage1
    if (!rst_ni) begin
      prod_q  <= '0;
      offs_q  <= '0;
      user1_q <= '0;
    end else if (load[0] && s_valid_i) begin
      prod_q  <= ProdBits'(s_pix_data_i) * ProdBits'(s_gain_i);
      offs_q  <= s_offset_i;
      user1_q <= s_user_i;
    end
  end

  // ---- stage 2: align, add, round ----------------------------------------------------
  logic signed [AddBits-1:0] prod_al, offs_al, sum_s, sum_rnd;
  logic signed [AddBits-1:0] rnd_const;
  logic signed [RndBits-1:0] rnd_d, rnd_q;

  // Both terms are brought to F fraction bits in AddBits (> SumBits) signed bits.
  assign prod_al = $signed({{(AddBits - ProdBits){1'b0}}, prod_q}) <<< (FracBits - GainFracBits);
  assign offs_al = $signed({{(AddBits - OffsetBits){offs_q[OffsetBits-1]}}, offs_q})
                   <<< (FracBits - OffsetFracBits);
  assign sum_s   = prod_al + offs_al;

  if (FracBits == 0 || Rounding == 0) begin : gen_rnd_none
    // truncate = floor; F = 0 makes every mode the identity.
    assign rnd_const = '0;
  end else if (Rounding == 1) begin : gen_rnd_half_up
    assign rnd_const = AddBits'(1) <<< (FracBits - 1);
  end else begin : gen_rnd_half_even
    // 2^(F-1) - 1 + lsb of the integer part: ties go to the even integer.
    assign rnd_const = (AddBits'(1) <<< (FracBits - 1)) - AddBits'(1)
                       + AddBits'(sum_s[FracBits]);
  end

  assign sum_rnd = sum_s + rnd_const;
  // Keeping bits [AddBits-1:F] is the arithmetic (floor) shift by F.
  assign rnd_d   = sum_rnd[AddBits-1:FracBits];

  if (FracBits > 0) begin : gen_frac_unused
    logic unused_frac;
    assign unused_frac = ^sum_rnd[FracBits-1:0];
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_stage2
    if (!rst_ni) begin
      rnd_q   <= '0;
      user2_q <= '0;
    end else if (load[1] && valid_q[0]) begin
      rnd_q   <= rnd_d;
      user2_q <= user1_q;
    end
  end

  // ---- stage 3: OUT (saturate or wrap to B bits) ------------------------------------
  logic [OutBits-1:0] out_d, out_q;

  if (Overflow == 0) begin : gen_saturate
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

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_stage3
    if (!rst_ni) begin
      out_q   <= '0;
      user3_q <= '0;
    end else if (load[2] && valid_q[1]) begin
      out_q   <= out_d;
      user3_q <= user2_q;
    end
  end

  assign m_valid_o    = valid_q[2];
  assign m_pix_data_o = out_q;
  assign m_user_o     = user3_q;

endmodule
