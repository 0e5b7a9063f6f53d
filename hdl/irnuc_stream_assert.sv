// Protocol checker of one valid/ready stream (simulation only, no logic).
//
// irnuc_spill_register instantiates one on each of its two sides under `ifdef IRNUC_ASSERT
// (the co-simulation builds define it, synthesis does not); every stream port of
// nuc_core, dpc_core and nuc_dpc_top is a port of such a register, so every one is
// checked, and so is every internal register boundary, once: a register whose input is
// another register's output leaves its input checker out (CheckIn = 0). Immediate assertions in a clocked
// block on the values sampled at the rising edge and the previous edge (stall_q, data_q:
// the same properties as the concurrent form at less than half its simulation cost),
// checked from the second edge after reset (armed_q):
//   a_known       valid and ready are never X/Z
//   a_valid_held  valid, once high, stays high until a transfer (AXI-Stream rule)
//   a_data_stable data (with its markers) does not change while valid && !ready
// A failure prints "Assertion failed in <instance>.<label>: irnuc_stream_assert ..." and
// stops the simulation (Verilator --assert: $error, then $stop at the error limit).
module irnuc_stream_assert #(
  parameter int unsigned DataBits = 1
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                valid_i,
  input logic                ready_i,
  input logic [DataBits-1:0] data_i
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (DataBits >= 1)
      else $fatal(1, "irnuc_stream_assert: DataBits = %0d must be at least 1", DataBits);
  end

  // Off in reset, on from the first edge after it (rst_ni stays a pure asynchronous reset).
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));

  // The sampled values of the previous edge: a stall (valid && !ready) and its data.
  logic                stall_q;
  logic [DataBits-1:0] data_q;

  always_ff @(posedge clk_i) begin : p_sample
    stall_q <= valid_i && !ready_i;
    if (valid_i && !ready_i) data_q <= data_i;  // read only after a stall
  end

  // Checked at every edge from the second one after reset (the first one samples). The
  // two stall properties hold vacuously without a stall, so they sit under `if (stall_q)`:
  // the same properties, but at full rate the simulator skips them (Verilator calls its
  // assertion-enable query once per executed assertion: a quarter of the bulk run time).
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
`ifndef FORMAL  // two-valued in the formal model (irnuc formal)
      a_known: assert (!$isunknown(valid_i) && !$isunknown(ready_i))
        else $error("irnuc_stream_assert: valid or ready is X/Z");
`endif
      if (stall_q) begin
        a_valid_held: assert (valid_i)
          else $error("irnuc_stream_assert: valid dropped before ready");
        a_data_stable: assert (data_i == data_q)
          else $error("irnuc_stream_assert: data changed while valid and not ready");
      end
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, valid_i, ready_i, data_i};
`endif

endmodule
