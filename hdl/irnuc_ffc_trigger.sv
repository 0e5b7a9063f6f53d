// The FFC request of the register file (issue 36; golden model nuc_fixed/ffc_policy.py,
// ffc_trigger; docs/integration.md "FFC requests"): at each frame start (start_i, the
// framer taking the pending settings)
//   * the frame is a reference when an FFC_CTRL.start applies to it (ffc_start_i before
//     this frame start and after the previous one: irnuc_axis_ffc's rule for the run's
//     first shutter frame) or it is the first frame after reset: since = 0 and the
//     reference reading = the frame's READING; else since + 1, saturating;
//   * due = (period != 0 && since >= period) || (threshold != 0 && |reading - ref| >= threshold);
//   * request_o pulses when due rises (once per crossing: an FFC, which makes due 0 again,
//     re-arms it).
// The compares run from flops over two cycles after the frame start (a subtractor, then
// the two comparators), the request a flop: nothing here is on a path of the stream.
module irnuc_ffc_trigger #(
  parameter int unsigned PeriodBits    = 24,
  parameter int unsigned ThresholdBits = 24,
  // Bits of the FPA reading (READING); 0: the build has none (the reading is 0).
  parameter int unsigned ReadingBits   = 14,
  // Derived, do not override.
  localparam int unsigned RdBits       = (ReadingBits > 0) ? ReadingBits : 1
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     start_i,      // a frame starts
  input  logic                     ffc_start_i,  // FFC_CTRL.start written (one cycle)
  input  logic [RdBits-1:0]        reading_i,    // the pending READING (the frame's at start_i)
  input  logic [PeriodBits-1:0]    period_i,     // FFC_PERIOD.frames
  input  logic [ThresholdBits-1:0] threshold_i,  // FFC_THRESHOLD.codes
  output logic [PeriodBits-1:0]    since_o,      // FFC_TRIGGER.since
  output logic [RdBits-1:0]        ref_o,        // FFC_REF.reading
  output logic                     period_o,     // FFC_TRIGGER.period
  output logic                     threshold_o,  // FFC_TRIGGER.threshold
  output logic                     request_o     // IRQ_STATUS.ffc_request (one cycle)
);

  logic                  arm_q;  // the next frame start is a reference
  logic [PeriodBits-1:0] since_q;
  logic [RdBits-1:0]     ref_q, rd_q, diff_q;
  logic                  s1_q, s2_q, per_q, per_hit_q, thr_hit_q, due_q, req_q;
  logic                  thr_hit;

  // Frame start: the counter, the reference and the frame's reading.
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_frame
    if (!rst_ni) begin
      arm_q   <= 1'b1;  // the first frame after reset is a reference
      since_q <= '0;
      ref_q   <= '0;
      rd_q    <= '0;
      s1_q    <= 1'b0;
    end else begin
      // As irnuc_axis_ffc's armed flag: a start in a frame start's cycle is the next one's.
      if (ffc_start_i) begin
        arm_q <= 1'b1;
      end else if (start_i) begin
        arm_q <= 1'b0;
      end
      if (start_i) begin
        rd_q <= reading_i;
        if (arm_q) begin
          since_q <= '0;
          ref_q   <= reading_i;
        end else if (!(&since_q)) begin
          since_q <= since_q + PeriodBits'(1);
        end
      end
      s1_q <= start_i;
    end
  end

  // Cycle 1: |reading - ref| and the period compare; cycle 2: the threshold compare, due
  // and the request (its rising edge).
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_compare
    if (!rst_ni) begin
      diff_q    <= '0;
      per_q     <= 1'b0;
      s2_q      <= 1'b0;
      per_hit_q <= 1'b0;
      thr_hit_q <= 1'b0;
      due_q     <= 1'b0;
      req_q     <= 1'b0;
    end else begin
      s2_q  <= s1_q;
      req_q <= 1'b0;
      if (s1_q) begin
        diff_q <= (rd_q >= ref_q) ? rd_q - ref_q : ref_q - rd_q;
        per_q  <= (period_i != '0) && (since_q >= period_i);
      end
      if (s2_q) begin
        per_hit_q <= per_q;
        thr_hit_q <= thr_hit;
        due_q     <= per_q || thr_hit;
        req_q     <= (per_q || thr_hit) && !due_q;
      end
    end
  end

  // The difference zero-extended to the threshold's width (a reading is at most 24 bits).
  if (ThresholdBits >= RdBits) begin : gen_cmp_wide
    assign thr_hit = (threshold_i != '0) && (ThresholdBits'(diff_q) >= threshold_i);
  end else begin : gen_cmp_narrow
    assign thr_hit = (threshold_i != '0) && (RdBits'(threshold_i) <= diff_q);
  end

  assign since_o     = since_q;
  assign ref_o       = (ReadingBits > 0) ? ref_q : '0;
  assign period_o    = per_hit_q;
  assign threshold_o = thr_hit_q;
  assign request_o   = req_q;

`ifdef IRNUC_ASSERT
  // The request is due's rising edge: due is 1 with it.
  logic armed_q;
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_request_due: assert (!req_q || due_q)
        else $error("irnuc_ffc_trigger: a request without due");
    end
  end
`endif

endmodule
