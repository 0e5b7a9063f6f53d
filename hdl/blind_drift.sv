// blind_drift, once per frame (docs/datapath.md "blind_drift"; nuc_fixed.drift.blind_drift):
//   bsum  = sum of the frame's blind codes                      SB = A + bit_length(blind_max)
//   bd    = bsum - blind_ref                                    SB + 1, signed
//   dp    = bd * m   (m = drift_gain, S Mi.Mf)                  SB + 1 + MW, signed
//   delta = OVF_drift(ROUND_(Mf - Df)(dp))                      DW, signed (drift format)
//
// The blind (reference) rows come before the active rows of their frame: s_blind carries
// the frame's blind codes, the last one flagged (s_blind_last_i). Each item may also be a
// partial sum (a register holding the whole frame's sum, one item with last), as long as
// the frame's sum fits SB bits (asserted). With the last item the registers blind_ref_i
// and drift_gain_i are sampled and the one wide multiply runs sequentially, one bit of m a
// cycle (MSB first, the sign bit's weight negative), then the rounding and the overflow;
// delta leaves on m_drift, one item per frame, which the top takes with the frame's first
// active pixel. The next frame's codes are summed meanwhile; its last item waits until
// the multiplier is free. Latency from the last item taken to delta valid: MW + 5 cycles.
//
//   u_in    input register (irnuc_spill_register): registered s_blind_ready_o
//   sum     bsum, restarted after a last item
//   load    the frame's sum registered (state BdLoad), then bd and -bd beside it
//   mul     p = 2 p + (m_i ? +-bd : 0), MW cycles (state BdMul)
//   round   r = ROUND_(Mf - Df)(p) (irnuc_round), registered (state BdRound)
//   u_out   OVF (irnuc_clip) into the output register (irnuc_spill_register, two entries)
module blind_drift #(
  parameter int unsigned AdcBits           = 14,
  parameter int unsigned BlindMax          = 8192,
  parameter int unsigned DriftIntBits      = 14,
  parameter int unsigned DriftFracBits     = 2,
  parameter int unsigned DriftRounding     = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned DriftOverflow     = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned DriftGainIntBits  = 1,
  parameter int unsigned DriftGainFracBits = 24,
  // Derived, do not override.
  localparam int unsigned SumBits          = irnuc_pkg::blind_sum_bits(AdcBits, BlindMax),
  localparam int unsigned DriftBits        = DriftIntBits + DriftFracBits,
  localparam int unsigned GainBits         = DriftGainIntBits + DriftGainFracBits
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // The frame's blind codes (or partial sums), the last one flagged.
  input  logic                 s_blind_valid_i,
  output logic                 s_blind_ready_o,
  input  logic [SumBits-1:0]   s_blind_data_i,
  input  logic                 s_blind_last_i,
  // Calibration registers, sampled with each frame's last item.
  input  logic [SumBits-1:0]   blind_ref_i,
  input  logic [GainBits-1:0]  drift_gain_i,
  // One drift code per frame.
  output logic                 m_drift_valid_o,
  input  logic                 m_drift_ready_i,
  output logic [DriftBits-1:0] m_drift_data_o,
  // A multiply or rounding is under way.
  output logic                 busy_o
);

  localparam int unsigned BdBits    = SumBits + 1;
  localparam int unsigned ProdBits  = BdBits + GainBits;
  localparam int unsigned Shift     = DriftGainFracBits - DriftFracBits;  // Mf - Df
  localparam int unsigned RndBits   = ProdBits + 1 - Shift;
  localparam int unsigned CountBits = $clog2(GainBits + 1);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (AdcBits >= 1 && AdcBits <= 32 && BlindMax >= 1 && BlindMax <= (1 << 20))
      else $fatal(1, "blind_drift: AdcBits = %0d, BlindMax = %0d out of range", AdcBits,
                  BlindMax);
    assert (DriftGainFracBits >= DriftFracBits)
      else $fatal(1, "blind_drift: drift_gain has %0d fraction bits, fewer than drift's %0d",
                  DriftGainFracBits, DriftFracBits);
    assert (DriftIntBits >= 1 && DriftGainIntBits >= 1 && GainBits >= 2)
      else $fatal(1, "blind_drift: a signed format needs its sign bit");
    assert (ProdBits <= 63 && Shift < ProdBits)
      else $fatal(1, "blind_drift: the product needs %0d bits (at most 63)", ProdBits);
    assert (DriftRounding <= 2 && DriftOverflow <= 1)
      else $fatal(1, "blind_drift: DriftRounding = %0d, DriftOverflow = %0d out of range",
                  DriftRounding, DriftOverflow);
  end
`endif

  // ---- input register and the sum ------------------------------------------------------
  logic               in_valid, in_ready, in_last;
  logic [SumBits-1:0] in_data;

  irnuc_spill_register #(.DataBits(SumBits + 1)) u_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_blind_valid_i),
    .ready_o(s_blind_ready_o),
    .data_i ({s_blind_last_i, s_blind_data_i}),
    .valid_o(in_valid),
    .ready_i(in_ready),
    .data_o ({in_last, in_data})
  );

  typedef enum logic [2:0] {
    BdIdle  = 3'd0,  // summing; a last item starts the multiply
    BdLoad  = 3'd1,  // bd, -bd and m are loaded from the registered sum
    BdMul   = 3'd2,  // one bit of m a cycle
    BdRound = 3'd3,  // the rounded product is registered
    BdPush  = 3'd4   // delta waits for room in the output register
  } bd_state_e;

  bd_state_e            state_q;
  logic [SumBits-1:0]   bsum_q;
  logic [SumBits:0]     bsum_next;  // one bit more: the carry is the overflow
  logic                 take;

  // A last item is taken only when the multiplier is free.
  assign in_ready  = !in_last || state_q == BdIdle;
  assign take      = in_valid && in_ready;
  assign bsum_next = {1'b0, bsum_q} + {1'b0, in_data};

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_sum
    if (!rst_ni) begin
      bsum_q <= '0;
    end else if (take) begin
      // A frame's last item closes its sum; the next item starts the next frame's.
      bsum_q <= in_last ? '0 : bsum_next[SumBits-1:0];
    end
  end

  // ---- the multiply, MSB first ------------------------------------------------------------
  logic signed [BdBits-1:0]   bd_q;
  logic signed [ProdBits-1:0] bd_neg_q;  // -bd, for the sign bit (one adder per cycle)
  logic        [GainBits-1:0] m_q;     // shifted left: bit GainBits-1 is the next bit
  logic        [CountBits-1:0] count_q; // bits left after the current one
  logic signed [ProdBits-1:0] p_q;
  logic                       first_q;  // the current bit is m's sign bit
  logic        [RndBits-1:0]  rnd_d, rnd_q;
  logic                       out_ready;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      state_q <= BdIdle;
    end else begin
      unique case (state_q)
        BdIdle:  if (take && in_last) state_q <= BdLoad;
        BdLoad:  state_q <= BdMul;
        BdMul:   if (count_q == '0) state_q <= BdRound;
        BdRound: state_q <= BdPush;
        BdPush:  if (out_ready) state_q <= BdIdle;
        default: state_q <= BdIdle;
      endcase
    end
  end

  logic signed [ProdBits-1:0] addend;
  always_comb begin : p_addend
    if (!m_q[GainBits-1]) begin
      addend = '0;
    end else if (first_q) begin
      addend = bd_neg_q;  // the sign bit weighs -2^(MW-1)
    end else begin
      addend = ProdBits'(bd_q);
    end
  end

  // The frame's sum and the registers, sampled with its last item (the multiply starts
  // from flops: a clock enable of the wide registers driven by a flop, not by the input).
  logic [SumBits-1:0]  bsum_last_q;
  logic [SumBits-1:0]  ref_q;
  logic [GainBits-1:0] gain_q;

  always_ff @(posedge clk_i) begin : p_last
    if (state_q == BdIdle && take && in_last) begin
      bsum_last_q <= bsum_next[SumBits-1:0];
      ref_q       <= blind_ref_i;
      gain_q      <= drift_gain_i;
    end
  end

  always_ff @(posedge clk_i) begin : p_mul
    if (state_q == BdLoad) begin
      bd_q    <= $signed({1'b0, bsum_last_q}) - $signed({1'b0, ref_q});
      m_q     <= gain_q;
      count_q <= CountBits'(GainBits - 1);
      bd_neg_q <= ProdBits'($signed({1'b0, ref_q}) - $signed({1'b0, bsum_last_q}));
      p_q     <= '0;
      first_q <= 1'b1;
    end else if (state_q == BdMul) begin
      p_q     <= (p_q <<< 1) + addend;
      m_q     <= m_q << 1;
      count_q <= count_q - CountBits'(1);
      first_q <= 1'b0;
    end
    if (state_q == BdRound) begin
      rnd_q <= rnd_d;
    end
  end

  irnuc_round #(
    .InBits  (ProdBits),
    .FracBits(Shift),
    .Rounding(DriftRounding)
  ) u_round (
    .s_i(p_q),
    .r_o(rnd_d)
  );

  // ---- OVF into the output register --------------------------------------------------------
  logic [DriftBits-1:0] delta_d;

  irnuc_clip #(
    .InBits   (RndBits),
    .OutBits  (DriftBits),
    .OutSigned(1'b1),
    .Overflow (DriftOverflow)
  ) u_clip (
    .v_i(rnd_q),
    .y_o(delta_d)
  );

  irnuc_spill_register #(.DataBits(DriftBits)) u_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(state_q == BdPush),
    .ready_o(out_ready),
    .data_i (delta_d),
    .valid_o(m_drift_valid_o),
    .ready_i(m_drift_ready_i),
    .data_o (m_drift_data_o)
  );

  assign busy_o = state_q != BdIdle;

`ifdef IRNUC_ASSERT
  // a_blind_sum_range: a frame's blind items sum to less than 2^SB (the golden model's
  // K <= blind_max codes of A bits).
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q && take) begin
      a_blind_sum_range: assert (!bsum_next[SumBits])
        else $error("blind_drift: the frame's blind sum exceeds %0d bits", SumBits);
    end
  end
`endif

endmodule
