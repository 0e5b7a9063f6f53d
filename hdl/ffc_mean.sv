// The FFC target of a mean pass (docs/datapath.md "ffc"; nuc_fixed.ffc.ffc_mean_target):
//   T = CLAMP(RDIV_half_up(sum over good pixels of v, n_good), 0, 2^TBits - 1)
// with v = ROUND_(F' - Cf)(s_acc << (F' - F)) per pixel (formed by the enclosing top).
//
// The mean frame's pixels are summed as they pass (valid_i, good_i). When a refresh frame's
// first pixel waits (request_i) and none of the mean frame's pixels is in flight any more
// (counted in by enter_i as they enter the enclosing pipeline, out by valid_i), one
// restoring division starts, one quotient bit a cycle (NumBits cycles, then the clamp into
// a register):
// q = floor((2 sum + n) / 2n) is the half-up quotient of sum / n for sum >= 0; a negative
// sum gives T = 0 (its rounded quotient is at most 0). n_good = 0 (no good pixel in the
// mean frame) gives no target: empty_o is 1 and target_o 0 (the division by 2n = 0 runs
// but its quotient is not used), and the refresh keeps the previous offsets (keep_i of
// ffc_refresh; nuc_fixed.ffc.ffc_mean_target returns None). The target and empty_o are then
// held (target_valid_o) until the next division is done; the sums restart with the
// division. ready_o: the waiting frame's division has started and its target is valid
// (until the cycle after a frame's first pixel is taken, frame_taken_i).
module ffc_mean #(
  parameter int unsigned VBits     = 20,  // v, signed
  parameter int unsigned NBits     = 21,  // n_good, unsigned (clog2 of the largest frame + 1)
  parameter int unsigned TBits     = 18,  // the target, unsigned (B + Cf)
  parameter int unsigned MaxFlight = 63,  // the most mean pixels between enter_i and valid_i
  // Derived, do not override.
  localparam int unsigned SumBits    = VBits + NBits,  // signed
  localparam int unsigned NumBits    = SumBits + 1,
  localparam int unsigned DenBits    = NBits + 1,
  localparam int unsigned FlightBits = $clog2(MaxFlight + 1)
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    enter_i,        // a mean pixel enters the pipeline
  input  logic                    valid_i,        // a mean pixel's v
  input  logic                    good_i,
  input  logic signed [VBits-1:0] v_i,
  input  logic                    request_i,      // a refresh frame's first pixel waits
  input  logic                    frame_taken_i,  // a frame's first pixel is taken
  output logic                    ready_o,        // the waiting frame's target is valid
  output logic                    target_valid_o,
  output logic [TBits-1:0]        target_o,
  output logic                    empty_o         // no good pixel: no target
);

  localparam int unsigned CountBits = $clog2(NumBits + 1);
  // A quotient of NumBits bits can exceed TBits bits (then TBits < NumBits fits the count).
  localparam bit          CanOver   = NumBits > TBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (VBits >= 2 && NBits >= 1 && TBits >= 1 && NumBits <= 96 && MaxFlight >= 1)
      else $fatal(1, "ffc_mean: VBits = %0d, NBits = %0d, TBits = %0d, MaxFlight = %0d out of range",
                  VBits, NBits, TBits, MaxFlight);
  end
`endif

  // ---- the start: no mean pixel in flight, once per waiting frame -------------------------
  logic                  start, started_q;
  logic [FlightBits-1:0] flight_q;
  // The count adds enter_i a cycle late (enter_q: the enclosing join's take reaches one
  // flop, not the count's adder), so the pixels in flight are flight_q + enter_q. "None
  // counted" (flight_q = 0) is a flop of its own, stepped from enter_q and valid_i, and start
  // also asks !enter_q: the join's take reaches no other flop here (start drives the
  // division's wide enables). A frame's first pixel taken clears started_q a cycle late
  // (taken_q: ready_o holds a cycle longer, when no other refresh frame can wait).
  logic                  flight_zero_q, flight_one, enter_q, taken_q;

  assign start      = request_i && !started_q && flight_zero_q && !enter_q;
  assign flight_one = flight_q == FlightBits'(1);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_flight
    if (!rst_ni) begin
      enter_q       <= 1'b0;
      taken_q       <= 1'b0;
      flight_q      <= '0;
      flight_zero_q <= 1'b1;
      started_q     <= 1'b0;
    end else begin
      enter_q       <= enter_i;
      taken_q       <= frame_taken_i;
      flight_q      <= flight_q + FlightBits'(enter_q) - FlightBits'(valid_i);
      flight_zero_q <= (flight_zero_q && enter_q == valid_i)
                       || (flight_one && valid_i && !enter_q);
      if (start) begin
        started_q <= 1'b1;
      end else if (taken_q) begin
        started_q <= 1'b0;
      end
    end
  end

  logic signed [SumBits-1:0] sum_q;
  logic        [NBits-1:0]   n_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_sum
    if (!rst_ni) begin
      sum_q <= '0;
      n_q   <= '0;
    end else if (start) begin
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
  logic                 none_q;  // n = 0: no target (empty_o once done)
  logic                 empty_q;
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
    end else if (start) begin
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
    if (start) begin
      // 2 sum + n (sum >= 0 here, or zero_q makes it moot) and 2n.
      num_q   <= (NumBits'(sum_q) << 1) + NumBits'(n_q);
      den_q   <= {n_q, 1'b0};
      rem_q   <= '0;
      count_q <= CountBits'(NumBits);
      zero_q  <= sum_q < 0 || n_q == '0;
      none_q  <= n_q == '0;
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
      empty_q  <= none_q;
    end
  end

  assign target_o       = target_q;
  assign empty_o        = empty_q;
  assign target_valid_o = valid_q;
  assign ready_o        = started_q && valid_q;

`ifdef IRNUC_ASSERT
  // The in-flight count neither underflows nor overflows, and its zero flag agrees with it.
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_flight_range: assert (!(flight_q == '0 && !enter_q && valid_i))
        else $error("ffc_mean: a mean pixel summed that was never counted in");
      a_flight_zero: assert (flight_zero_q == (flight_q == '0))
        else $error("ffc_mean: the in-flight count's zero flag disagrees with it");
      a_flight_room: assert (!(flight_q == '1 && enter_q && !valid_i))
        else $error("ffc_mean: more mean pixels in flight than the count holds");
    end
  end
`endif

endmodule
