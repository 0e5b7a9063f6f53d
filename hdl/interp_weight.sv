// The two tables nearest the FPA reading and the weight between them, docs/datapath.md
// "interp_weight" (nuc_fixed.tempcomp.interp_weight), once per frame:
//   j    = the largest i <= K - 2 with r_i <= t (0 when t < r_0)
//   span = r_(j+1) - r_j,  num = CLAMP(t - r_j, 0, span)
//   w    = RDIV(num << Wf, span), the weight format's rounding (0 <= w <= 2^Wf)
// r_i are the table readings (registers, strictly increasing). The division is sequential
// (one quotient bit a cycle, restoring), for the blanking between frames: a start pulse
// takes the reading and the table readings (hold them until done), done_o rises
// Wf + 6 cycles later and holds j_o and weight_o until the next start. For Fmax in
// irnuc_axis_top (docs/rtl.md): the rounding's decision is registered before its increment,
// the division step's fits selects last, the order check has a flop of its own. error_o (with done)
// says the table readings do not increase strictly; j_o and weight_o are then meaningless.
// The DMA reads tables j and j + 1; method_dpc_top takes the weight with the frame.
module interp_weight #(
  parameter int unsigned ReadingBits    = 14,
  parameter int unsigned Tables         = 3,
  parameter int unsigned WeightFracBits = 15,
  parameter int unsigned WeightRounding = 1,  // irnuc_pkg::rounding_e
  // Derived, do not override.
  localparam int unsigned IndexBits     = (Tables > 2) ? $clog2(Tables - 1) : 1,
  localparam int unsigned WBits         = WeightFracBits + 1
) (
  input  logic                                clk_i,
  input  logic                                rst_ni,
  input  logic                                start_i,
  input  logic [ReadingBits-1:0]              reading_i,
  input  logic [Tables-1:0][ReadingBits-1:0]  table_readings_i,
  output logic                                busy_o,
  output logic                                done_o,
  output logic                                error_o,
  output logic [IndexBits-1:0]                j_o,
  output logic [WBits-1:0]                    weight_o
);

  localparam irnuc_pkg::rounding_e RoundMode = irnuc_pkg::rounding_e'(WeightRounding);
  localparam int unsigned CountBits = $clog2(WeightFracBits + 1) + 1;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (ReadingBits >= 1 && ReadingBits <= 24)
      else $fatal(1, "interp_weight: ReadingBits = %0d outside 1..24", ReadingBits);
    assert (Tables >= 2 && Tables <= 16)
      else $fatal(1, "interp_weight: Tables = %0d outside 2..16", Tables);
    assert (WeightFracBits <= 40)
      else $fatal(1, "interp_weight: WeightFracBits = %0d outside 0..40", WeightFracBits);
    assert (WeightRounding <= 2)
      else $fatal(1, "interp_weight: WeightRounding = %0d outside 0..2", WeightRounding);
  end
`endif

  typedef enum logic [2:0] {
    IwIdle   = 3'd0,  // holding the last result
    IwSelect = 3'd1,  // j and the order check from the latched reading
    IwSpan   = 3'd2,  // span and t - r_j
    IwClamp  = 3'd3,  // the clamped numerator: the quotient's top bit and the remainder
    IwDivide = 3'd4,  // one quotient bit a cycle
    IwRound  = 3'd5,  // the rounding decision from the remainder
    IwInc    = 3'd6   // the rounding increment
  } iw_state_e;

  iw_state_e              state_q;
  logic [ReadingBits-1:0] t_q;
  logic [IndexBits-1:0]   j_q;
  logic                   err_q, done_q, inc_q;
  logic                   order_q;  // order_bad, registered every cycle (err_q takes it)
  logic [ReadingBits-1:0] span_q;
  logic [ReadingBits:0]   above_q;  // t - r_j, signed
  logic [ReadingBits:0]   rem_q;    // remainder, below span (one bit more after a shift)
  logic [WBits-1:0]       quot_q;
  logic [CountBits-1:0]   count_q;

  // ---- j and the order check --------------------------------------------------------------
  // With strictly increasing readings, j is the number of r_1 .. r_(K-2) at or below t.
  logic [IndexBits-1:0] j_d;
  logic                 order_bad;

  always_comb begin : p_select
    j_d = '0;
    for (int i = 1; i <= int'(Tables) - 2; i++) begin
      if (table_readings_i[i] <= t_q) begin
        j_d = IndexBits'(i);
      end
    end
    order_bad = 1'b0;
    for (int i = 0; i + 1 < int'(Tables); i++) begin
      if (table_readings_i[i + 1] <= table_readings_i[i]) begin
        order_bad = 1'b1;
      end
    end
  end

  // ---- span and numerator -------------------------------------------------------------------
  logic [ReadingBits-1:0] r_lo, r_hi;
  logic [ReadingBits:0]   above;  // t - r_j, signed
  assign r_lo  = table_readings_i[j_q];
  assign r_hi  = table_readings_i[32'(j_q) + 1];
  assign above = {1'b0, t_q} - {1'b0, r_lo};

  // ---- restoring division step: rem <= 2 rem (- span) ---------------------------------------
  // fits is the difference's sign (one carry chain gives both), and it selects last, right
  // before the registers: the other selects are made beside the chain (p_divide).
  logic [ReadingBits+1:0] twice;
  logic [ReadingBits+2:0] diff;  // 2 rem - span, signed
  logic                   fits;
  assign twice = {rem_q, 1'b0};
  assign diff  = {1'b0, twice} - {3'b000, span_q};
  assign fits  = !diff[ReadingBits+2];

  // ---- rounding from the remainder: compare 2 rem with span --------------------------------
  logic [ReadingBits+1:0] twice_rem;
  logic                   inc;
  assign twice_rem = {rem_q, 1'b0};

  always_comb begin : p_inc
    unique case (RoundMode)
      irnuc_pkg::RoundHalfUp:   inc = twice_rem >= {2'b00, span_q};
      irnuc_pkg::RoundHalfEven: inc = (twice_rem > {2'b00, span_q}) ||
                                      (twice_rem == {2'b00, span_q} && quot_q[0]);
      default:                  inc = 1'b0;
    endcase
  end

  // ---- remainder and quotient: their next values with and without `fits` ----------------
  // Outside IwDivide both are the same (fits then selects nothing).
  logic [ReadingBits:0] rem_fit, rem_keep;
  logic [WBits-1:0]     quot_fit, quot_keep;

  always_comb begin : p_divide
    rem_keep  = rem_q;
    quot_keep = quot_q;
    unique case (state_q)
      IwClamp: begin
        // num = CLAMP(t - r_j, 0, span); the quotient's top bit (weight 2^Wf) is
        // num >= span, i.e. num = span, after which the remainder is 0.
        if (above_q[ReadingBits]) begin
          rem_keep  = '0;
          quot_keep = '0;
        end else if (above_q[ReadingBits-1:0] >= span_q) begin
          rem_keep  = '0;
          quot_keep = WBits'(1) << WeightFracBits;
        end else begin
          rem_keep  = {1'b0, above_q[ReadingBits-1:0]};
          quot_keep = '0;
        end
      end
      // rem < span after every step: ReadingBits + 1 bits hold it and its double.
      IwDivide: rem_keep = (ReadingBits + 1)'(twice);
      IwInc:    quot_keep = quot_q + WBits'(inc_q);
      default: ;
    endcase
    rem_fit  = rem_keep;
    quot_fit = quot_keep;
    if (state_q == IwDivide) begin
      rem_fit  = (ReadingBits + 1)'(diff);
      quot_fit = quot_q | (WBits'(1'b1) << (count_q - CountBits'(1)));
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_fsm
    if (!rst_ni) begin
      state_q <= IwIdle;
      done_q  <= 1'b0;
      err_q   <= 1'b0;
      order_q <= 1'b0;
      t_q     <= '0;
      j_q     <= '0;
      span_q  <= '0;
      above_q <= '0;
      rem_q   <= '0;
      quot_q  <= '0;
      count_q <= '0;
      inc_q   <= 1'b0;
    end else begin
      // The order check's compares and OR reach a flop of their own; err_q takes it a cycle
      // later (IwSpan: the readings are held since the start).
      order_q <= order_bad;
      rem_q   <= fits ? rem_fit : rem_keep;
      quot_q  <= fits ? quot_fit : quot_keep;
      unique case (state_q)
        IwIdle: begin
          if (start_i) begin
            t_q     <= reading_i;
            done_q  <= 1'b0;
            state_q <= IwSelect;
          end
        end
        IwSelect: begin
          j_q     <= j_d;
          state_q <= IwSpan;
        end
        IwSpan: begin
          err_q   <= order_q;
          span_q  <= r_hi - r_lo;
          above_q <= above;
          state_q <= IwClamp;
        end
        IwClamp: begin
          // num = CLAMP(t - r_j, 0, span); the quotient's top bit (weight 2^Wf) is
          // num >= span, i.e. num = span, after which the remainder is 0.
          count_q <= CountBits'(WeightFracBits);
          state_q <= (WeightFracBits == 0) ? IwRound : IwDivide;
        end
        IwDivide: begin
          count_q <= count_q - CountBits'(1);
          if (count_q == CountBits'(1)) begin
            state_q <= IwRound;
          end
        end
        IwRound: begin
          inc_q   <= inc;
          state_q <= IwInc;
        end
        default: begin  // IwInc
          done_q  <= 1'b1;
          state_q <= IwIdle;
        end
      endcase
    end
  end

  assign busy_o   = (state_q != IwIdle);
  assign done_o   = done_q;
  assign error_o  = err_q;
  assign j_o      = j_q;
  assign weight_o = quot_q;

endmodule
