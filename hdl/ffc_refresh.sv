// The FFC's offset refresh and the mean's v on the accumulator's sum (docs/datapath.md
// "ffc"; nuc_fixed.ffc.ffc_refresh, and the v of nuc_fixed.ffc.ffc_mean_target):
//   dc = OVF_C(ROUND_(F' - Cf)((T << (F' - Cf)) - (sa << (F' - F))))
//   v  = ROUND_(F' - Cf)(sa << (F' - F)),   F' = max(F, Cf)
// with sa the base method's sum on the accumulator (F = SumFracBits fraction bits), T the
// target (U B.Cf) and C the ffc format (S FfcIntBits.FfcFracBits, its rounding and
// overflow).
//
// Three register stages, moving on en_i (the enclosing pipeline's enable):
//   D  sa aligned to F' and the difference;
//   R  both rounded: v_o, with v_valid_o and the side band of the same pixel (v_side_o),
//      for the mean pass;
//   C  dc clipped, and the pixel's correction c_o = refresh_i && !keep_i ? dc : c_i (the
//      new word in a refresh frame, the word read in any other, and in a refresh frame
//      without a target: keep_i, no good pixel in its mean frame).
// SideBits of side band travel beside the three stages (latency 3 from valid_i to
// valid_o). Only the valid flags reset; the data registers are read only when valid.
module ffc_refresh
  import irnuc_method_pkg::max2;
#(
  parameter int unsigned SumBits     = 24,  // sa, signed
  parameter int unsigned SumFracBits = 3,   // F of sa
  parameter int unsigned OutBits     = 14,  // B: the target is U B.Cf
  parameter int unsigned FfcIntBits  = 12,
  parameter int unsigned FfcFracBits = 4,
  parameter int unsigned FfcRounding = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned FfcOverflow = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned SideBits    = 1,
  // Derived, do not override.
  localparam int unsigned TBits    = OutBits + FfcFracBits,
  localparam int unsigned CBits    = FfcIntBits + FfcFracBits,
  localparam int unsigned RFrac    = max2(SumFracBits, FfcFracBits),  // F'
  localparam int unsigned RShift   = RFrac - FfcFracBits,
  localparam int unsigned SxBits   = SumBits + RFrac - SumFracBits,
  localparam int unsigned DiffBits = max2(TBits + 1 + RShift, SxBits) + 1,
  localparam int unsigned VBits    = SxBits + 1 - RShift
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    en_i,
  input  logic                    valid_i,
  input  logic [SumBits-1:0]      sum_i,      // sa
  input  logic [TBits-1:0]        target_i,   // T, steady while a refresh frame passes
  input  logic                    refresh_i,  // a refresh frame: c_o = dc
  input  logic                    keep_i,     // ... but no target: c_o = c_i (steady as target_i)
  input  logic [CBits-1:0]        c_i,        // the pixel's correction otherwise
  input  logic [SideBits-1:0]     side_i,
  // Stage R: the pixel's v.
  output logic                    v_valid_o,
  output logic signed [VBits-1:0] v_o,
  output logic [SideBits-1:0]     v_side_o,
  // Stage C: the pixel's correction (written back in a refresh frame).
  output logic                    valid_o,
  output logic                    refresh_o,
  output logic [CBits-1:0]        c_o,
  output logic [SideBits-1:0]     side_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (SumBits >= 2 && SumFracBits < SumBits && OutBits >= 1 && SideBits >= 1)
      else $fatal(1, "ffc_refresh: SumBits = %0d, SumFracBits = %0d, OutBits = %0d, SideBits = %0d out of range",
                  SumBits, SumFracBits, OutBits, SideBits);
    assert (FfcIntBits >= 1 && FfcRounding <= 2 && FfcOverflow <= 1)
      else $fatal(1, "ffc_refresh: FfcIntBits, FfcRounding or FfcOverflow out of range");
    assert (DiffBits <= 64)
      else $fatal(1, "ffc_refresh: the difference of %0d bits exceeds 64", DiffBits);
  end
`endif

  // ---- stage D: sa aligned and the difference -------------------------------------------
  logic [SxBits-1:0]   sx;
  logic [DiffBits-1:0] diff;

  assign sx   = SxBits'($signed(sum_i)) << (RFrac - SumFracBits);
  assign diff = (DiffBits'(target_i) << RShift) - DiffBits'($signed(sx));

  logic                d_valid_q, d_refresh_q;
  logic [SxBits-1:0]   d_sx_q;
  logic [DiffBits-1:0] d_diff_q;
  logic [CBits-1:0]    d_c_q;
  logic [SideBits-1:0] d_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_d_valid
    if (!rst_ni) begin
      d_valid_q <= 1'b0;
    end else if (en_i) begin
      d_valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin : p_d
    if (en_i) begin
      d_sx_q      <= sx;
      d_diff_q    <= diff;
      d_refresh_q <= refresh_i;
      d_c_q       <= c_i;
      d_side_q    <= side_i;
    end
  end

  // ---- stage R: ROUND of both -------------------------------------------------------------
  logic [VBits-1:0]         v_d;
  logic [DiffBits-RShift:0] dr_d;

  irnuc_round #(
    .InBits  (SxBits),
    .FracBits(RShift),
    .Rounding(FfcRounding)
  ) u_round_v (
    .s_i(d_sx_q),
    .r_o(v_d)
  );

  irnuc_round #(
    .InBits  (DiffBits),
    .FracBits(RShift),
    .Rounding(FfcRounding)
  ) u_round_dc (
    .s_i(d_diff_q),
    .r_o(dr_d)
  );

  logic                     r_valid_q, r_refresh_q;
  logic [DiffBits-RShift:0] r_dr_q;
  logic [VBits-1:0]         r_v_q;
  logic [CBits-1:0]         r_c_q;
  logic [SideBits-1:0]      r_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_r_valid
    if (!rst_ni) begin
      r_valid_q <= 1'b0;
    end else if (en_i) begin
      r_valid_q <= d_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin : p_r
    if (en_i) begin
      r_dr_q      <= dr_d;
      r_v_q       <= v_d;
      r_refresh_q <= d_refresh_q;
      r_c_q       <= d_c_q;
      r_side_q    <= d_side_q;
    end
  end

  assign v_valid_o = r_valid_q;
  assign v_o       = $signed(r_v_q);
  assign v_side_o  = r_side_q;

  // ---- stage C: OVF, and the pixel's correction -------------------------------------------
  logic [CBits-1:0] dc_d;

  irnuc_clip #(
    .InBits   (DiffBits + 1 - RShift),
    .OutBits  (CBits),
    .OutSigned(1'b1),
    .Overflow (FfcOverflow)
  ) u_clip_dc (
    .v_i(r_dr_q),
    .y_o(dc_d)
  );

  logic                c_valid_q, c_refresh_q;
  logic [CBits-1:0]    c_c_q;
  logic [SideBits-1:0] c_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_c_valid
    if (!rst_ni) begin
      c_valid_q <= 1'b0;
    end else if (en_i) begin
      c_valid_q <= r_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin : p_c
    if (en_i) begin
      c_c_q       <= (r_refresh_q && !keep_i) ? dc_d : r_c_q;
      c_refresh_q <= r_refresh_q;
      c_side_q    <= r_side_q;
    end
  end

  assign valid_o   = c_valid_q;
  assign refresh_o = c_refresh_q;
  assign c_o       = c_c_q;
  assign side_o    = c_side_q;

endmodule
