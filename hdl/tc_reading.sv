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
//
// With Housing (tc_housing; nuc_fixed.tempcomp.tc_reading with the housing reading) the
// housing reading h and its centre h_ref make the second variable in the same stages:
//   w  = CLAMP(h - h_ref, -(2^Hs - 1), 2^Hs - 1)   (Hs + 1 bits, signed: w' = w / 2^Hs)
//   uw = (u * w) >> Hs                              (Ts + 1 bits, signed: v·w' at Ts bits)
//   w2 = (w * w) >> Hs                              (Hs bits, unsigned: w'^2 at Hs bits)
// (>> is floor); the three products' sums are padded to one depth, so u, u2, w, uw and w2
// come out together. Without Housing w, uw and w2 are 0 and the hardware is the one above.
module tc_reading
  import irnuc_method_pkg::*;
#(
  parameter int unsigned ReadingBits      = 14,
  parameter int unsigned ReadingRangeBits = 11,
  parameter bit          Square           = 1'b1,
  parameter bit          Housing          = 1'b0,
  parameter int unsigned HousingBits      = 14,
  parameter int unsigned HousingRangeBits = 11,
  parameter int unsigned SideBits         = 1,
  // Derived, do not override.
  localparam int unsigned UBits           = ReadingRangeBits + 1,
  localparam int unsigned U2Bits          = ReadingRangeBits,
  localparam int unsigned WBits           = HousingRangeBits + 1,
  localparam int unsigned W2Bits          = HousingRangeBits
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   en_i,
  input  logic                   valid_i,
  input  logic [ReadingBits-1:0] reading_i,
  input  logic [ReadingBits-1:0] t_ref_i,
  input  logic [HousingBits-1:0] housing_i,
  input  logic [HousingBits-1:0] h_ref_i,
  input  logic [SideBits-1:0]    side_i,
  output logic                   valid_o,
  output logic [UBits-1:0]       u_o,
  output logic [U2Bits-1:0]      u2_o,
  output logic [WBits-1:0]       w_o,
  output logic [UBits-1:0]       uw_o,
  output logic [W2Bits-1:0]      w2_o,
  output logic [SideBits-1:0]    side_o
);

  // t - t_ref and the limits in one signed width that holds both.
  localparam int unsigned CmpBits = max2(ReadingBits + 1, UBits) + 1;
  localparam int unsigned SqBits  = 2 * UBits;
  localparam int unsigned SqParts = smul_parts(UBits, 1'b1, UBits, 1'b1);
  // With Housing: the products u*w and w*w, and one depth for the three sums.
  localparam int unsigned UwBits  = UBits + WBits;
  localparam int unsigned WwBits  = 2 * WBits;
  localparam int unsigned UwParts = smul_parts(UBits, 1'b1, WBits, 1'b1);
  localparam int unsigned WwParts = smul_parts(WBits, 1'b1, WBits, 1'b1);
  localparam int unsigned Leaves  = Housing ? max3(SqParts, UwParts, WwParts) : SqParts;
  localparam bit          Mul     = Square || Housing;
  localparam int unsigned HCmpBits = max2(HousingBits + 1, WBits) + 1;
  // What travels beside the square: the side band, u (and w with Housing).
  localparam int unsigned CarryBits = SideBits + UBits + (Housing ? WBits : 0);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (ReadingBits >= 1 && ReadingBits <= 24)
      else $fatal(1, "tc_reading: ReadingBits = %0d outside 1..24", ReadingBits);
    assert (ReadingRangeBits >= 1 && ReadingRangeBits <= 20)
      else $fatal(1, "tc_reading: ReadingRangeBits = %0d outside 1..20", ReadingRangeBits);
    assert (SideBits >= 1)
      else $fatal(1, "tc_reading: SideBits = %0d must be at least 1", SideBits);
    assert (HousingBits >= 1 && HousingBits <= 24)
      else $fatal(1, "tc_reading: HousingBits = %0d outside 1..24", HousingBits);
    assert (HousingRangeBits >= 1 && HousingRangeBits <= 20)
      else $fatal(1, "tc_reading: HousingRangeBits = %0d outside 1..20", HousingRangeBits);
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

  // ---- the housing: w = CLAMP(h - h_ref, -hlim, hlim), hlim = 2^Hs - 1, beside u -------------
  logic [WBits-1:0] w_q;
  if (Housing) begin : gen_hclamp
    localparam logic signed [HCmpBits-1:0] HLim =
        HCmpBits'((64'd1 << HousingRangeBits) - 64'd1);
    logic signed [HCmpBits-1:0] hdiff_q;
    always_ff @(posedge clk_i) begin : p_hdiff
      if (en_i) begin
        hdiff_q <= $signed(HCmpBits'(housing_i)) - $signed(HCmpBits'(h_ref_i));
      end
    end
    always_ff @(posedge clk_i) begin : p_hclamp
      if (en_i) begin
        if (hdiff_q > HLim) begin
          w_q <= WBits'(HLim);
        end else if (hdiff_q < -HLim) begin
          w_q <= WBits'(-HLim);
        end else begin
          w_q <= WBits'(hdiff_q);
        end
      end
    end
  end else begin : gen_no_hclamp
    assign w_q = '0;
    logic unused_housing;
    assign unused_housing = ^{housing_i, h_ref_i, w_q};
  end

  // ---- square: u2 = (u*u) >> Ts --------------------------------------------------------------
  if (Mul) begin : gen_square
    logic                             sqp_valid;
    logic [CarryBits-1:0]             sqp_carry;
    logic [SqParts-1:0][SqBits-1:0]   sq_parts;
    logic [Leaves-1:0][SqBits-1:0]    sq_leaves;
    logic [SqBits-1:0]                sq_sum;
    logic [CarryBits-1:0]             carry_d, carry_o;

    if (Housing) begin : gen_carry_w
      assign carry_d = {clamp_side_q, u_q, w_q};
    end else begin : gen_carry_u
      assign carry_d = {clamp_side_q, u_q};
    end

    irnuc_mul_parts #(
      .ABits   (UBits),
      .BBits   (UBits),
      .ASigned (1'b1),
      .BSigned (1'b1),
      .SideBits(CarryBits)
    ) u_sq (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en_i),
      .valid_i(clamp_valid_q),
      .a_i    (u_q),
      .b_i    (u_q),
      .side_i (carry_d),
      .valid_o(sqp_valid),
      .parts_o(sq_parts),
      .side_o (sqp_carry)
    );

    for (genvar k = 0; k < Leaves; k++) begin : gen_sq_leaf
      if (k < SqParts) begin : gen_part
        assign sq_leaves[k] = sq_parts[k];
      end else begin : gen_pad
        assign sq_leaves[k] = '0;
      end
    end

    irnuc_add_tree #(
      .Leaves  (Leaves),
      .Width   (SqBits),
      .SideBits(CarryBits)
    ) u_sq_sum (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (en_i),
      .valid_i (sqp_valid),
      .leaves_i(sq_leaves),
      .side_i  (sqp_carry),
      .valid_o (valid_o),
      .sum_o   (sq_sum),
      .side_o  (carry_o)
    );

    // u*u < 2^(2 Ts): bits [2 Ts - 1 : Ts] are u2; the two top bits are 0, the low Ts bits
    // are dropped (floor). Without Square (tc_order 1 with Housing) u2 is 0.
    assign u2_o = Square ? sq_sum[2*ReadingRangeBits-1:ReadingRangeBits] : '0;
    logic unused_sq;
    assign unused_sq = ^{sq_sum[SqBits-1:2*ReadingRangeBits], sq_sum[ReadingRangeBits-1:0]};

    if (Housing) begin : gen_housing
      // u*w and w*w: the same two product stages and the same depth of sum as u*u.
      logic [UwParts-1:0][UwBits-1:0] uw_parts;
      logic [Leaves-1:0][UwBits-1:0]  uw_leaves;
      logic [UwBits-1:0]              uw_sum;
      logic [WwParts-1:0][WwBits-1:0] ww_parts;
      logic [Leaves-1:0][WwBits-1:0]  ww_leaves;
      logic [WwBits-1:0]              ww_sum;
      logic                           uwp_valid, uwp_side, wwp_valid, wwp_side;
      logic                           uws_valid, uws_side, wws_valid, wws_side;

      irnuc_mul_parts #(
        .ABits   (UBits),
        .BBits   (WBits),
        .ASigned (1'b1),
        .BSigned (1'b1),
        .SideBits(1)
      ) u_uw (
        .clk_i  (clk_i),
        .rst_ni (rst_ni),
        .en_i   (en_i),
        .valid_i(clamp_valid_q),
        .a_i    (u_q),
        .b_i    (w_q),
        .side_i (1'b0),
        .valid_o(uwp_valid),
        .parts_o(uw_parts),
        .side_o (uwp_side)
      );

      irnuc_mul_parts #(
        .ABits   (WBits),
        .BBits   (WBits),
        .ASigned (1'b1),
        .BSigned (1'b1),
        .SideBits(1)
      ) u_ww (
        .clk_i  (clk_i),
        .rst_ni (rst_ni),
        .en_i   (en_i),
        .valid_i(clamp_valid_q),
        .a_i    (w_q),
        .b_i    (w_q),
        .side_i (1'b0),
        .valid_o(wwp_valid),
        .parts_o(ww_parts),
        .side_o (wwp_side)
      );

      for (genvar k = 0; k < Leaves; k++) begin : gen_h_leaf
        if (k < UwParts) begin : gen_uw_part
          assign uw_leaves[k] = uw_parts[k];
        end else begin : gen_uw_pad
          assign uw_leaves[k] = '0;
        end
        if (k < WwParts) begin : gen_ww_part
          assign ww_leaves[k] = ww_parts[k];
        end else begin : gen_ww_pad
          assign ww_leaves[k] = '0;
        end
      end

      irnuc_add_tree #(
        .Leaves  (Leaves),
        .Width   (UwBits),
        .SideBits(1)
      ) u_uw_sum (
        .clk_i   (clk_i),
        .rst_ni  (rst_ni),
        .en_i    (en_i),
        .valid_i (uwp_valid),
        .leaves_i(uw_leaves),
        .side_i  (uwp_side),
        .valid_o (uws_valid),
        .sum_o   (uw_sum),
        .side_o  (uws_side)
      );

      irnuc_add_tree #(
        .Leaves  (Leaves),
        .Width   (WwBits),
        .SideBits(1)
      ) u_ww_sum (
        .clk_i   (clk_i),
        .rst_ni  (rst_ni),
        .en_i    (en_i),
        .valid_i (wwp_valid),
        .leaves_i(ww_leaves),
        .side_i  (wwp_side),
        .valid_o (wws_valid),
        .sum_o   (ww_sum),
        .side_o  (wws_side)
      );

      // |u*w| < 2^(Ts + Hs): bits [Ts + Hs : Hs] are uw (arithmetic shift, floor);
      // w*w < 2^(2 Hs): bits [2 Hs - 1 : Hs] are w2.
      assign uw_o = uw_sum[ReadingRangeBits+HousingRangeBits:HousingRangeBits];
      assign w2_o = ww_sum[2*HousingRangeBits-1:HousingRangeBits];
      assign {side_o, u_o, w_o} = carry_o;
      // Same enable and valid as the square's.
      logic unused_h;
      assign unused_h = ^{uws_valid, uws_side, wws_valid, wws_side,
                          uw_sum[UwBits-1:ReadingRangeBits+HousingRangeBits+1],
                          uw_sum[HousingRangeBits-1:0],
                          ww_sum[WwBits-1:2*HousingRangeBits], ww_sum[HousingRangeBits-1:0]};
    end else begin : gen_no_housing
      assign {side_o, u_o} = carry_o;
      assign w_o  = '0;
      assign uw_o = '0;
      assign w2_o = '0;
    end
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
    assign w_o  = '0;
    assign uw_o = '0;
    assign w2_o = '0;
  end

endmodule
