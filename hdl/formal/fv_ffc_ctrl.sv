// Proof harness of ffc_ctrl, the FFC sequencer (`irnuc formal`, docs/formal.md): the mode
// of every frame equals that of a reference written from the rules of docs/datapath.md
// "ffc" (and nuc_fixed.ffc.FfcState): with r the shutter frames taken in a row before this
// one (counted up to N = FfcFrames),
//   acc_first  shutter and r = 0          acc_add  shutter and 0 < r < N
//   mean       shutter and r = N - 1      refresh  the frame before was a mean pass
//   acc_rd     acc_add or refresh         hold     Hold, shutter, an open frame since reset
// for any sequence of shutter flags and frame starts (shutter_i and take_i free).
module fv_ffc_ctrl
  import irnuc_stage_pkg::*;
#(
  parameter int unsigned FfcFrames = 4,
  parameter bit          Hold      = 1'b1,
  localparam int unsigned CountBits = $clog2(FfcFrames + 1)
) (
  input logic clk_i,
  input logic rst_ni,
  input logic shutter_i,
  input logic take_i
);

  ffc_mode_t mode;

  ffc_ctrl #(.FfcFrames(FfcFrames), .Hold(Hold)) u_dut (
    .clk_i, .rst_ni, .shutter_i, .take_i, .mode_o(mode));

  irnuc_fv_reset u_reset (.clk_i, .rst_ni);

`ifdef FORMAL
  // The reference: shutter frames in a row, a mean pass just taken, an open frame seen.
  logic [CountBits-1:0] run_q;
  logic                 mean_q, open_q;
  ffc_mode_t            want;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_reference
    if (!rst_ni) begin
      run_q  <= '0;
      mean_q <= 1'b0;
      open_q <= 1'b0;
    end else if (take_i) begin
      run_q  <= !shutter_i ? '0 : (32'(run_q) < FfcFrames ? run_q + CountBits'(1) : run_q);
      mean_q <= shutter_i && 32'(run_q) == FfcFrames - 1;
      open_q <= open_q || !shutter_i;
    end
  end

  always_comb begin : p_want
    want           = '0;
    want.acc_first = shutter_i && run_q == '0;
    want.acc_add   = shutter_i && run_q != '0 && 32'(run_q) < FfcFrames;
    want.mean      = shutter_i && 32'(run_q) == FfcFrames - 1;
    want.refresh   = mean_q;
    want.acc_rd    = want.acc_add || mean_q;
    want.hold      = Hold && shutter_i && open_q;
  end

  always_comb begin : p_check
    if (rst_ni) begin
      a_acc_first: assert (mode.acc_first == want.acc_first);
      a_acc_add: assert (mode.acc_add == want.acc_add);
      a_mean: assert (mode.mean == want.mean);
      a_refresh: assert (mode.refresh == want.refresh);
      a_acc_rd: assert (mode.acc_rd == want.acc_rd);
      a_hold: assert (mode.hold == want.hold);
    end
  end

  // Reachable: a second full run (a refresh after an open frame after a refresh).
  logic refreshed_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_runs
    if (!rst_ni) begin
      refreshed_q <= 1'b0;
    end else if (take_i && mode.refresh) begin
      refreshed_q <= 1'b1;
    end
  end
  always_comb begin : p_cover
    if (rst_ni) begin
      c_second_refresh: cover (refreshed_q && open_q && mode.refresh && shutter_i);
    end
  end
  if (Hold) begin : gen_hold
    always_comb begin : p_cover_hold
      if (rst_ni) begin
        c_hold: cover (mode.hold && (mode.acc_add || FfcFrames == 1));
      end
    end
  end
`endif

endmodule
