// The FFC target of a mean pass (docs/datapath.md "ffc"; nuc_fixed.ffc.ffc_mean_target):
//   T = CLAMP(RDIV_half_up(sum over good pixels of v, n_good), 0, 2^TBits - 1)
// with v = ROUND_(F' - Cf)(s_acc << (F' - F)) per pixel (formed by the enclosing top).
//
// The mean frame's pixels are summed as they pass (valid_i, good_i); start_i (the frame
// has passed) starts one restoring division, one quotient bit a cycle (NumBits cycles, then the clamp into a register):
// q = floor((2 sum + n) / 2n) is the half-up quotient of sum / n for sum >= 0; a negative
// sum gives T = 0 (its rounded quotient is at most 0), as does n_good = 0 (the golden
// model refuses it). The target is then held on target_o (target_valid_o) until the next
// start; the sums restart with the division.
module ffc_mean #(
  parameter int unsigned VBits   = 20,  // v, signed
  parameter int unsigned NBits   = 21,  // n_good, unsigned (clog2 of the largest frame + 1)
  parameter int unsigned TBits   = 18,  // the target, unsigned (B + Cf)
  // Derived, do not override.
  localparam int unsigned SumBits = VBits + NBits,  // signed
  localparam int unsigned NumBits = SumBits + 1,
  localparam int unsigned DenBits = NBits + 1
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    valid_i,
  input  logic                    good_i,
  input  logic signed [VBits-1:0] v_i,
  input  logic                    start_i,
  output logic                    busy_o,
  output logic                    target_valid_o,
  output logic [TBits-1:0]        target_o
);

  localparam int unsigned CountBits = $clog2(NumBits + 1);
  // A quotient of NumBits bits can exceed TBits bits (then TBits < NumBits fits the count).
  localparam bit          CanOver   = NumBits > TBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (VBits >= 2 && NBits >= 1 && TBits >= 1 && NumBits <= 96)
      else $fatal(1, "ffc_mean: VBits = %0d, NBits = %0d, TBits = %0d out of range", VBits,
                  NBits, TBits);
  end
`endif

  logic signed [SumBits-1:0] sum_q;
  logic        [NBits-1:0]   n_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_sum
    if (!rst_ni) begin
      sum_q <= '0;
      n_q   <= '0;
    end else if (start_i) begin
      sum_q <= '0;
      n_q   <= '0;
    end else if (valid_i && good_i) begin
      sum_q <= sum_q + SumBits'(v_i);
      n_q   <= n_q + NBits'(1);
    end
  end

  // ---- the division, MSB first ----------------------------------------------------------
  logic [NumBits-1:0]   num_q;  // shifted left: the next bit at the top; quotient from below
  logic [DenBits-1:0]   den_q;
  logic [DenBits-1:0]   rem_q;
  logic [CountBits-1:0] count_q;
  logic                 zero_q;  // sum < 0 or n = 0: T = 0
  logic                 busy_q, valid_q, done_q;
  logic                 over_q;  // a quotient bit at or above TBits is set
  logic [TBits-1:0]     target_q;
  logic [DenBits:0]     rem_shift;
  logic [DenBits+1:0]   rem_diff;
  logic                 fits;

  // One subtraction gives both the comparison (its borrow) and the new remainder.
  assign rem_shift = {rem_q, num_q[NumBits-1]};
  assign rem_diff  = {1'b0, rem_shift} - {2'b0, den_q};
  assign fits      = !rem_diff[DenBits+1];

  // busy: the division; done: one cycle more, the clamp into target_q; then valid.
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_ctrl
    if (!rst_ni) begin
      busy_q  <= 1'b0;
      done_q  <= 1'b0;
      valid_q <= 1'b0;
    end else if (start_i) begin
      busy_q  <= 1'b1;
      done_q  <= 1'b0;
      valid_q <= 1'b0;
    end else if (busy_q && count_q == CountBits'(1)) begin
      busy_q  <= 1'b0;
      done_q  <= 1'b1;
    end else if (done_q) begin
      done_q  <= 1'b0;
      valid_q <= 1'b1;
    end
  end

  always_ff @(posedge clk_i) begin : p_div
    if (start_i) begin
      // 2 sum + n (sum >= 0 here, or zero_q makes it moot) and 2n.
      num_q   <= (NumBits'(sum_q) << 1) + NumBits'(n_q);
      den_q   <= {n_q, 1'b0};
      rem_q   <= '0;
      count_q <= CountBits'(NumBits);
      zero_q  <= sum_q < 0 || n_q == '0;
      over_q  <= 1'b0;
    end else if (busy_q) begin
      rem_q   <= fits ? rem_diff[DenBits-1:0] : rem_shift[DenBits-1:0];
      num_q   <= {num_q[NumBits-2:0], fits};
      count_q <= count_q - CountBits'(1);
      // This quotient bit ends at bit count_q - 1 of num_q.
      over_q  <= over_q || (CanOver && fits && count_q > CountBits'(TBits));
    end
  end

  localparam logic [TBits-1:0] TMax = '1;

  // num_q holds the quotient when the division is done: clamped into the target register.
  // Above TMax = 2^TBits - 1 means a quotient bit at or above TBits set: over_q, gathered
  // as the bits are made (no wide OR of num_q's top bits before the clamp).
  always_ff @(posedge clk_i) begin : p_target
    if (done_q) begin
      target_q <= zero_q ? '0 : over_q ? TMax : num_q[TBits-1:0];
    end
  end

  assign target_o       = target_q;
  assign target_valid_o = valid_q;
  assign busy_o         = busy_q || done_q;

endmodule
