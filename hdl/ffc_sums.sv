// The two sums of method_ffc_top (docs/datapath.md "ffc"; nuc_fixed.method_top for a method
// "<base>+ffc"): the base method's sum on the pixel's raw code x (core_sum, Xf = 0, F raised
// to at least the FFC's Cf, MinFracBits) beside the same sum on the accumulator (core_sum,
// A + n bits, Xf = n), both on the frame's gain, offset and quadratic term of the pixel.
//
// The new accumulator acc_new = x (first_i: a run's first shutter frame) or acc + x travels
// beside the pixel's sum (acc_new_o, for m_acc); the accumulator core sums the accumulator
// read (refresh_i: the refresh and mean passes) or acc_new. Where (AddBehind):
//   1  stage 1 registers the core's two addends masked as the pass needs them,
//      (first_i && !refresh_i ? 0 : acc) and (refresh_i ? 0 : x), and one adder behind it
//      drives the core's multipliers; acc_new is formed behind stage 1 too. For inputs
//      straight from the enclosing top's input buffers, whose read pointers fan out over
//      the whole word: the masks share a LUT with the read multiplexer.
//   0  acc_new and the core's x are formed into stage 1 (inputs from flops of few loads,
//      e.g. tc_poly's output register).
// Every register moves with en_i (the enclosing pipeline's enable); only the valid flags
// reset. Latency: 1 + Latency (both cores padded to Latency, irnuc_stage_pkg).
module ffc_sums
  import irnuc_method_pkg::*;
  import irnuc_stage_pkg::*;
#(
  parameter int unsigned Kind           = 0,  // irnuc_stage_pkg::core_kind_e
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned NShift         = 3,  // n = log2 of the FFC frames
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned QuadIntBits    = 10,
  parameter int unsigned QuadFracBits   = 6,
  parameter int unsigned SquareBits     = 18,
  parameter int unsigned FfcFracBits    = 4,   // Cf: the pixel's sum has F >= Cf
  parameter int unsigned Latency        = 0,   // of each core (the larger of both; 0: own)
  parameter int unsigned SideBits       = 1,
  parameter bit          AddBehind      = 1'b1,  // the accumulator's adder behind stage 1
  // Derived, do not override.
  localparam core_kind_e  KindSel       = core_kind_e'(Kind),
  localparam int unsigned AccBits       = AdcBits + NShift,
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned QuadBits      = QuadIntBits + QuadFracBits,
  localparam int unsigned SumBits       = core_sum_bits(KindSel, AdcBits, 1'b0, 0, AdcBits,
                                                        GainBits, GainFracBits, OffsetBits,
                                                        OffsetFracBits, QuadBits,
                                                        QuadFracBits, SquareBits, 1, 0, 1,
                                                        0, FfcFracBits),
  localparam int unsigned ASumBits      = core_sum_bits(KindSel, AccBits, 1'b0, NShift,
                                                        AdcBits, GainBits, GainFracBits,
                                                        OffsetBits, OffsetFracBits, QuadBits,
                                                        QuadFracBits, SquareBits, 1, 0, 1,
                                                        0, 0)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  en_i,
  input  logic                  valid_i,
  input  logic [AdcBits-1:0]    x_i,        // the raw code
  input  logic [AccBits-1:0]    acc_i,      // the accumulator read (s_acc)
  input  logic                  first_i,    // a run's first shutter frame: acc_new = x
  input  logic                  refresh_i,  // the accumulator core sums acc_i, not acc_new
  input  logic [GainBits-1:0]   gain_i,
  input  logic [OffsetBits-1:0] offset_i,
  input  logic [QuadBits-1:0]   quad_i,
  input  logic [SideBits-1:0]   side_i,
  output logic                  valid_o,
  output logic [SumBits-1:0]    sum_o,      // s on x, signed
  output logic [ASumBits-1:0]   asum_o,     // s on the accumulator, signed
  output logic [AccBits-1:0]    acc_new_o,  // acc_new of the same pixel
  output logic [SideBits-1:0]   side_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (SideBits >= 1 && NShift <= 16)
      else $fatal(1, "ffc_sums: SideBits = %0d, NShift = %0d out of range", SideBits,
                  NShift);
  end
`endif

  // ---- stage 1: the pixel's words, and the accumulator the core sums -----------------------
  logic                  s1_valid_q;
  logic [AdcBits-1:0]    s1_x_q;
  logic [GainBits-1:0]   s1_gain_q;
  logic [OffsetBits-1:0] s1_offset_q;
  logic [QuadBits-1:0]   s1_quad_q;
  logic [SideBits-1:0]   s1_side_q;
  logic [AccBits-1:0]    acc_new, acc_x;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_s1_valid
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
    end else if (en_i) begin
      s1_valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin : p_s1
    if (en_i) begin
      s1_x_q      <= x_i;
      s1_gain_q   <= gain_i;
      s1_offset_q <= offset_i;
      s1_quad_q   <= quad_i;
      s1_side_q   <= side_i;
    end
  end

  if (AddBehind) begin : gen_behind
    logic               s1_first_q;
    logic [AdcBits-1:0] s1_xa_q;
    logic [AccBits-1:0] s1_acc_q, s1_acca_q;

    always_ff @(posedge clk_i) begin : p_s1_add
      if (en_i) begin
        s1_acc_q   <= acc_i;
        s1_first_q <= first_i;
        s1_xa_q    <= refresh_i ? '0 : x_i;
        s1_acca_q  <= (first_i && !refresh_i) ? '0 : acc_i;
      end
    end

    assign acc_new = s1_first_q ? AccBits'(s1_x_q) : s1_acc_q + AccBits'(s1_x_q);
    assign acc_x   = s1_acca_q + AccBits'(s1_xa_q);
  end else begin : gen_ahead
    logic [AccBits-1:0] acc_new_d, s1_acc_new_q, s1_acc_x_q;

    assign acc_new_d = first_i ? AccBits'(x_i) : acc_i + AccBits'(x_i);

    always_ff @(posedge clk_i) begin : p_s1_add
      if (en_i) begin
        s1_acc_x_q   <= refresh_i ? acc_i : acc_new_d;
        s1_acc_new_q <= acc_new_d;
      end
    end

    assign acc_new = s1_acc_new_q;
    assign acc_x   = s1_acc_x_q;
  end

  // ---- the two sums --------------------------------------------------------------------------
  logic                asum_valid, asum_side;

  core_sum #(
    .Kind          (Kind),
    .XBits         (AdcBits),
    .XSigned       (1'b0),
    .XFracBits     (0),
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .QuadIntBits   (QuadIntBits),
    .QuadFracBits  (QuadFracBits),
    .SquareBits    (SquareBits),
    .MinFracBits   (FfcFracBits),
    .Latency       (Latency),
    .SideBits      (SideBits + AccBits)
  ) u_core (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en_i),
    .valid_i  (s1_valid_q),
    .x_i      (s1_x_q),
    .gain_i   (s1_gain_q),
    .gain_hi_i('0),
    .offset_i (s1_offset_q),
    .quad_i   (s1_quad_q),
    .knee_i   ('0),
    .level_i  ('0),
    .side_i   ({s1_side_q, acc_new}),
    .valid_o  (valid_o),
    .sum_o    (sum_o),
    .side_o   ({side_o, acc_new_o})
  );

  core_sum #(
    .Kind          (Kind),
    .XBits         (AccBits),
    .XSigned       (1'b0),
    .XFracBits     (NShift),
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .QuadIntBits   (QuadIntBits),
    .QuadFracBits  (QuadFracBits),
    .SquareBits    (SquareBits),
    .MinFracBits   (0),
    .Latency       (Latency),
    .SideBits      (1)
  ) u_acc_core (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en_i),
    .valid_i  (s1_valid_q),
    .x_i      (acc_x),
    .gain_i   (s1_gain_q),
    .gain_hi_i('0),
    .offset_i (s1_offset_q),
    .quad_i   (s1_quad_q),
    .knee_i   ('0),
    .level_i  ('0),
    .side_i   (1'b0),
    .valid_o  (asum_valid),
    .sum_o    (asum_o),
    .side_o   (asum_side)
  );

  logic unused_asum;
  assign unused_asum = ^{asum_valid, asum_side};

endmodule
