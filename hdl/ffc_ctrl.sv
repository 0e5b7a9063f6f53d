// The FFC sequencer (docs/datapath.md "ffc"; nuc_fixed.ffc.FfcState and the frame loop of
// nuc_fixed.method_top): the mode of each frame, decided from its shutter flag when the
// frame's first pixel is taken (take_i), and kept until the next.
//
//   shutter, count < N     acc_first (count = 0) or acc_add; the N-th is also the mean pass
//   shutter, count >= N    nothing (the run goes on; the correction stays)
//   open                   count = 0 (a run shorter than N leaves the correction as it was)
//   after a mean pass      refresh (whatever the frame's shutter flag)
//   shutter with hold      hold, once an open frame has been output since reset
//
// mode_o is combinational from shutter_i and the state (the join uses it for the frame's
// first pixel); the state moves on take_i. The count's comparisons are kept as flags of
// their own, set from the next count, so that mode_o is one LUT of shutter_i and flops (the
// join's decision and every input register's enable hang on it).
module ffc_ctrl
  import irnuc_stage_pkg::*;
#(
  parameter int unsigned FfcFrames = 8,
  parameter bit          Hold      = 1'b1,
  // Derived, do not override.
  localparam int unsigned CountBits = $clog2(FfcFrames + 1)
) (
  input  logic      clk_i,
  input  logic      rst_ni,
  input  logic      shutter_i,  // the shutter flag of the frame whose first pixel waits
  input  logic      take_i,     // that pixel is taken: the frame starts in mode_o
  output ffc_mode_t mode_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (FfcFrames >= 1 && FfcFrames <= (1 << 16) && (FfcFrames & (FfcFrames - 1)) == 0)
      else $fatal(1, "ffc_ctrl: FfcFrames = %0d is not a power of two in 1..65536", FfcFrames);
  end
`endif

  logic [CountBits-1:0] count_q;
  logic                 pending_q;  // a mean pass ended: the next frame refreshes
  logic                 open_q;     // an open frame was output since reset
  // What a shutter frame would do at the present count: count = 0, 0 < count < N,
  // count = N - 1.
  logic                 first_q, add_q, last_q;

  logic [CountBits-1:0] count_d;
  logic                 acc;

  assign acc     = shutter_i && (first_q || add_q);
  assign count_d = !shutter_i ? '0 : (acc ? count_q + CountBits'(1) : count_q);

  always_comb begin : p_mode
    mode_o           = '0;
    mode_o.acc_first = shutter_i && first_q;
    mode_o.acc_add   = shutter_i && add_q;
    mode_o.acc_rd    = mode_o.acc_add || pending_q;
    mode_o.mean      = shutter_i && last_q;
    mode_o.refresh   = pending_q;
    mode_o.hold      = Hold && shutter_i && open_q;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      count_q   <= '0;
      pending_q <= 1'b0;
      open_q    <= 1'b0;
      first_q   <= 1'b1;
      add_q     <= 1'b0;
      last_q    <= (FfcFrames == 1);
    end else if (take_i) begin
      count_q   <= count_d;
      pending_q <= mode_o.mean;
      open_q    <= open_q || !shutter_i;
      first_q   <= count_d == '0;
      add_q     <= count_d != '0 && count_d < CountBits'(FfcFrames);
      last_q    <= count_d == CountBits'(FfcFrames - 1);
    end
  end

endmodule
