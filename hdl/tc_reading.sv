// The FPA reading as the polynomial variable, docs/datapath.md "tc_reading"
// (nuc_fixed.tempcomp.tc_reading):
//   u  = CLAMP(t - t_ref, -(2^Ts - 1), 2^Ts - 1)   (Ts + 1 bits, signed: v = u / 2^Ts)
//   u2 = (u * u) >> Ts                              (Ts bits, unsigned: v^2 at Ts bits)
// A pipeline section inside tc_poly (no stream ports of its own): every register moves
// with en_i, the valid flag and SideBits of side band travel along, only valid flags reset.
//   diff     t - t_ref, registered
//   clamp    u, registered
//   u_sq     u*u as DSP partial products, input and output registered, then their sum
//            (clog2(parts) stages: none for Ts <= 17)
// Latency 4 + clog2(parts). With Square = 0 (tc_order 1) u2 is not formed: the same
// latency (for Ts <= 17), no multiplier.
module tc_reading
  import irnuc_method_pkg::*;
#(
  parameter int unsigned ReadingBits      = 14,
  parameter int unsigned ReadingRangeBits = 11,
  parameter bit          Square           = 1'b1,
  parameter int unsigned SideBits         = 1,
  // Derived, do not override.
  localparam int unsigned UBits           = ReadingRangeBits + 1,
  localparam int unsigned U2Bits          = ReadingRangeBits
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   en_i,
  input  logic                   valid_i,
  input  logic [ReadingBits-1:0] reading_i,
  input  logic [ReadingBits-1:0] t_ref_i,
  input  logic [SideBits-1:0]    side_i,
  output logic                   valid_o,
  output logic [UBits-1:0]       u_o,
  output logic [U2Bits-1:0]      u2_o,
  output logic [SideBits-1:0]    side_o
);

  // t - t_ref and the limits in one signed width that holds both.
  localparam int unsigned CmpBits = max2(ReadingBits + 1, UBits) + 1;
  localparam int unsigned SqBits  = 2 * UBits;
  localparam int unsigned SqParts = smul_parts(UBits, 1'b1, UBits, 1'b1);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (ReadingBits >= 1 && ReadingBits <= 24)
      else $fatal(1, "tc_reading: ReadingBits = %0d outside 1..24", ReadingBits);
    assert (ReadingRangeBits >= 1 && ReadingRangeBits <= 20)
      else $fatal(1, "tc_reading: ReadingRangeBits = %0d outside 1..20", ReadingRangeBits);
    assert (SideBits >= 1)
      else $fatal(1, "tc_reading: SideBits = %0d must be at least 1", SideBits);
  end
`endif

  // ---- difference, then clamp: u = CLAMP(t - t_ref, -lim, lim), lim = 2^Ts - 1 ----------
  localparam logic signed [CmpBits-1:0] Lim = CmpBits'((64'd1 << ReadingRangeBits) - 64'd1);

  logic                      diff_valid_q;
  logic signed [CmpBits-1:0] diff_q;
  logic [SideBits-1:0]       diff_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_diff_valid
    if (!rst_ni) begin
      diff_valid_q <= 1'b0;
    end else if (en_i) begin
      diff_valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin : p_diff
    if (en_i) begin
      diff_q      <= $signed(CmpBits'(reading_i)) - $signed(CmpBits'(t_ref_i));
      diff_side_q <= side_i;
    end
  end

  logic                clamp_valid_q;
  logic [UBits-1:0]    u_q;
  logic [SideBits-1:0] clamp_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_clamp_valid
    if (!rst_ni) begin
      clamp_valid_q <= 1'b0;
    end else if (en_i) begin
      clamp_valid_q <= diff_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin : p_clamp
    if (en_i) begin
      if (diff_q > Lim) begin
        u_q <= UBits'(Lim);
      end else if (diff_q < -Lim) begin
        u_q <= UBits'(-Lim);
      end else begin
        u_q <= UBits'(diff_q);
      end
      clamp_side_q <= diff_side_q;
    end
  end

  // ---- square: u2 = (u*u) >> Ts --------------------------------------------------------------
  if (Square) begin : gen_square
    logic                           sqp_valid;
    logic [UBits-1:0]               sqp_u;
    logic [SideBits-1:0]            sqp_side;
    logic [SqParts-1:0][SqBits-1:0] sq_parts;
    logic [SqBits-1:0]              sq_sum;

    irnuc_mul_parts #(
      .ABits   (UBits),
      .BBits   (UBits),
      .ASigned (1'b1),
      .BSigned (1'b1),
      .SideBits(SideBits + UBits)
    ) u_sq (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en_i),
      .valid_i(clamp_valid_q),
      .a_i    (u_q),
      .b_i    (u_q),
      .side_i ({clamp_side_q, u_q}),
      .valid_o(sqp_valid),
      .parts_o(sq_parts),
      .side_o ({sqp_side, sqp_u})
    );

    irnuc_add_tree #(
      .Leaves  (SqParts),
      .Width   (SqBits),
      .SideBits(SideBits + UBits)
    ) u_sq_sum (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (en_i),
      .valid_i (sqp_valid),
      .leaves_i(sq_parts),
      .side_i  ({sqp_side, sqp_u}),
      .valid_o (valid_o),
      .sum_o   (sq_sum),
      .side_o  ({side_o, u_o})
    );

    // u*u < 2^(2 Ts): bits [2 Ts - 1 : Ts] are u2; the two top bits are 0, the low Ts bits
    // are dropped (floor).
    assign u2_o = sq_sum[2*ReadingRangeBits-1:ReadingRangeBits];
    logic unused_sq;
    assign unused_sq = ^{sq_sum[SqBits-1:2*ReadingRangeBits], sq_sum[ReadingRangeBits-1:0]};
  end else begin : gen_no_square
    // The multiplier's two stages without a multiplier: the same latency.
    logic [1:0]                        valid_q;
    logic [1:0][SideBits+UBits-1:0]    side_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin : p_valid
      if (!rst_ni) begin
        valid_q <= '0;
      end else if (en_i) begin
        valid_q <= {valid_q[0], clamp_valid_q};
      end
    end
    always_ff @(posedge clk_i) begin : p_side
      if (en_i) begin
        side_q[0] <= {clamp_side_q, u_q};
        side_q[1] <= side_q[0];
      end
    end
    assign valid_o = valid_q[1];
    assign {side_o, u_o} = side_q[1];
    assign u2_o = '0;
  end

endmodule
