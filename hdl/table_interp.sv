// Table interpolation, docs/datapath.md "table_interp" (nuc_fixed.tempcomp.interp_coeffs):
// the frame's gain and offset of every pixel between its words in tables j and j + 1,
//   g = g_j + ROUND_Wf(w * (g_(j+1) - g_j)),  o likewise,
// w the frame's weight (U 1.Wf, 0 <= w <= 2^Wf), ROUND the weight format's rounding. The
// result lies between the two tables' codes, so it needs no saturation.
//
// Pipeline (one enable, en = "the output register can take an item", a flop; see nuc_core):
//   u_in     input register (irnuc_spill_register)
//   diff     dg = g1 - g0, do = o1 - o0, registered
//   u_gp     w*dg and u_op w*do as DSP partial products, two stages each, then their sums
//            (u_gsum, u_osum: clog2(parts) stages, none with 17-bit weights)
//   round    ROUND_Wf(w*dg), ROUND_Wf(w*do) (irnuc_round), registered
//   u_out    g0 + ROUND_Wf(w*dg), o0 + ROUND_Wf(w*do) into the output register
// Latency 6 + clog2(parts) (table14: 6); one pixel per clock. The weight comes with every
// pixel (method_dpc_top holds the frame's value); UserBits of side band pass unchanged.
module table_interp
  import irnuc_method_pkg::*;
#(
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 13,
  parameter int unsigned OffsetFracBits = 3,
  parameter int unsigned WeightFracBits = 15,
  parameter int unsigned WeightRounding = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned UserBits       = 1,
  // Derived, do not override.
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned WBits         = WeightFracBits + 1  // 0 .. 2^Wf
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Input stream: the pixel's words of tables j and j + 1, the frame's weight, side band.
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [GainBits-1:0]   s_gain0_i,
  input  logic [OffsetBits-1:0] s_offset0_i,
  input  logic [GainBits-1:0]   s_gain1_i,
  input  logic [OffsetBits-1:0] s_offset1_i,
  input  logic [WBits-1:0]      s_weight_i,
  input  logic [UserBits-1:0]   s_user_i,
  // Output stream: the interpolated gain and offset, the same side band.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [GainBits-1:0]   m_gain_o,
  output logic [OffsetBits-1:0] m_offset_o,
  output logic [UserBits-1:0]   m_user_o
);

  // ---- derived widths (docs/datapath.md "table_interp", nuc_fixed.widths.method_widths) --
  localparam int unsigned DgBits  = GainBits + 1;        // g1 - g0, signed
  localparam int unsigned DoBits  = OffsetBits + 1;      // o1 - o0, signed
  localparam int unsigned PgBits  = DgBits + WBits;      // w*dg, signed
  localparam int unsigned PoBits  = DoBits + WBits;      // w*do, signed
  localparam int unsigned RgBits  = PgBits + 1 - WeightFracBits;
  localparam int unsigned RoBits  = PoBits + 1 - WeightFracBits;
  localparam int unsigned GParts  = smul_parts(DgBits, 1'b1, WBits, 1'b0);
  localparam int unsigned OParts  = smul_parts(DoBits, 1'b1, WBits, 1'b0);
  localparam int unsigned Leaves  = max2(GParts, OParts);
  localparam int unsigned InBits  = UserBits + WBits + 2 * (GainBits + OffsetBits);
  localparam int unsigned Side    = UserBits + GainBits + OffsetBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (GainBits >= 1 && GainIntBits <= 16 && GainFracBits <= 32)
      else $fatal(1, "table_interp: gain U%0d.%0d outside U0..16.0..32 (at least one bit)",
                  GainIntBits, GainFracBits);
    assert (OffsetIntBits >= 1 && OffsetIntBits <= 32 && OffsetFracBits <= 32)
      else $fatal(1, "table_interp: offset S%0d.%0d outside S1..32.0..32", OffsetIntBits,
                  OffsetFracBits);
    assert (WeightFracBits <= 40)
      else $fatal(1, "table_interp: WeightFracBits = %0d outside 0..40", WeightFracBits);
    assert (WeightRounding <= 2)
      else $fatal(1, "table_interp: WeightRounding = %0d outside 0..2", WeightRounding);
    assert (UserBits >= 1)
      else $fatal(1, "table_interp: UserBits = %0d must be at least 1", UserBits);
    assert (PgBits + 1 <= 64 && PoBits + 1 <= 64)
      else $fatal(1, "table_interp: product widths %0d, %0d exceed 63", PgBits, PoBits);
  end
`endif

  // Pipeline enable: the output register has room (a flop of u_out).
  logic en;

  // ---- input register ----------------------------------------------------------------------
  logic                  in_valid;
  logic [GainBits-1:0]   in_gain0, in_gain1;
  logic [OffsetBits-1:0] in_offset0, in_offset1;
  logic [WBits-1:0]      in_weight;
  logic [UserBits-1:0]   in_user;

  irnuc_spill_register #(.DataBits(InBits)) u_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_valid_i),
    .ready_o(s_ready_o),
    .data_i ({s_user_i, s_weight_i, s_offset1_i, s_gain1_i, s_offset0_i, s_gain0_i}),
    .valid_o(in_valid),
    .ready_i(en),
    .data_o ({in_user, in_weight, in_offset1, in_gain1, in_offset0, in_gain0})
  );

  // ---- differences -------------------------------------------------------------------------
  logic                  diff_valid_q;
  logic [DgBits-1:0]     dg_q;
  logic [DoBits-1:0]     do_q;
  logic [WBits-1:0]      diff_weight_q;
  logic [Side-1:0]       diff_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_diff_valid
    if (!rst_ni) begin
      diff_valid_q <= 1'b0;
    end else if (en) begin
      diff_valid_q <= in_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_diff
    if (en) begin
      dg_q          <= DgBits'(in_gain1) - DgBits'(in_gain0);
      do_q          <= DoBits'($signed(in_offset1)) - DoBits'($signed(in_offset0));
      diff_weight_q <= in_weight;
      diff_side_q   <= {in_user, in_offset0, in_gain0};
    end
  end

  // ---- products w*dg, w*do and their sums ---------------------------------------------------
  logic [Leaves-1:0][PgBits-1:0] g_leaves;
  logic [Leaves-1:0][PoBits-1:0] o_leaves;
  logic                          gp_valid, op_valid, op_side;
  logic [Side-1:0]               gp_side;

  irnuc_mul_parts #(
    .ABits   (DgBits),
    .BBits   (WBits),
    .ASigned (1'b1),
    .BSigned (1'b0),
    .SideBits(Side)
  ) u_gp (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(diff_valid_q),
    .a_i    (dg_q),
    .b_i    (diff_weight_q),
    .side_i (diff_side_q),
    .valid_o(gp_valid),
    .parts_o(g_leaves[GParts-1:0]),
    .side_o (gp_side)
  );

  irnuc_mul_parts #(
    .ABits   (DoBits),
    .BBits   (WBits),
    .ASigned (1'b1),
    .BSigned (1'b0),
    .SideBits(1)
  ) u_op (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(diff_valid_q),
    .a_i    (do_q),
    .b_i    (diff_weight_q),
    .side_i (1'b0),
    .valid_o(op_valid),
    .parts_o(o_leaves[OParts-1:0]),
    .side_o (op_side)
  );

  // The narrower product's sum is padded to the other's depth.
  for (genvar k = GParts; k < Leaves; k++) begin : gen_g_pad
    assign g_leaves[k] = '0;
  end
  for (genvar k = OParts; k < Leaves; k++) begin : gen_o_pad
    assign o_leaves[k] = '0;
  end

  logic                gsum_valid, osum_valid, osum_side;
  logic [PgBits-1:0]   gsum;
  logic [PoBits-1:0]   osum;
  logic [Side-1:0]     sum_side;

  irnuc_add_tree #(
    .Leaves  (Leaves),
    .Width   (PgBits),
    .SideBits(Side)
  ) u_gsum (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (gp_valid),
    .leaves_i(g_leaves),
    .side_i  (gp_side),
    .valid_o (gsum_valid),
    .sum_o   (gsum),
    .side_o  (sum_side)
  );

  irnuc_add_tree #(
    .Leaves  (Leaves),
    .Width   (PoBits),
    .SideBits(1)
  ) u_osum (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (op_valid),
    .leaves_i(o_leaves),
    .side_i  (op_side),
    .valid_o (osum_valid),
    .sum_o   (osum),
    .side_o  (osum_side)
  );

  // Same enable and depth: the offset path's valid equals the gain path's.
  logic unused_op;
  assign unused_op = osum_valid ^ osum_side;

  // ---- ROUND_Wf, then g0 + ROUND_Wf(w*dg), o0 + ROUND_Wf(w*do) into the output register --
  logic [RgBits-1:0]     rg;
  logic [RoBits-1:0]     ro;
  logic [UserBits-1:0]   sum_user;
  logic [GainBits-1:0]   sum_gain0;
  logic [OffsetBits-1:0] sum_offset0;

  assign {sum_user, sum_offset0, sum_gain0} = sum_side;

  irnuc_round #(
    .InBits  (PgBits),
    .FracBits(WeightFracBits),
    .Rounding(WeightRounding)
  ) u_ground (
    .s_i(gsum),
    .r_o(rg)
  );

  irnuc_round #(
    .InBits  (PoBits),
    .FracBits(WeightFracBits),
    .Rounding(WeightRounding)
  ) u_oround (
    .s_i(osum),
    .r_o(ro)
  );

  // The results lie between the two tables' codes, so only the low GainBits / OffsetBits
  // of the rounded products are needed (the sums modulo 2^GW, 2^OW are the codes).
  logic                  rnd_valid_q;
  logic [GainBits-1:0]   rg_q, rnd_gain0_q;
  logic [OffsetBits-1:0] ro_q, rnd_offset0_q;
  logic [UserBits-1:0]   rnd_user_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_round_valid
    if (!rst_ni) begin
      rnd_valid_q <= 1'b0;
    end else if (en) begin
      rnd_valid_q <= gsum_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_round
    if (en) begin
      rg_q          <= GainBits'(rg);
      ro_q          <= OffsetBits'(ro);
      rnd_gain0_q   <= sum_gain0;
      rnd_offset0_q <= sum_offset0;
      rnd_user_q    <= sum_user;
    end
  end

  if (RgBits > GainBits) begin : gen_rg_unused
    logic unused_rg;
    assign unused_rg = ^rg[RgBits-1:GainBits];
  end
  if (RoBits > OffsetBits) begin : gen_ro_unused
    logic unused_ro;
    assign unused_ro = ^ro[RoBits-1:OffsetBits];
  end

  logic [GainBits-1:0]   gain_d;
  logic [OffsetBits-1:0] offset_d;
  assign gain_d   = rnd_gain0_q + rg_q;
  assign offset_d = rnd_offset0_q + ro_q;

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
