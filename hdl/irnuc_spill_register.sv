// Registered stream boundary: a two-entry elastic buffer that cuts every combinational
// path between its two sides (in the manner of a spill or skid register).
//
//   valid_o, data_o  come straight from the main register;
//   ready_o          is "the skid register is empty", a flop as well.
//
// An item is taken when valid_i && ready_o and goes to the main register if that is empty
// or leaves in the same cycle, else it is parked in the skid register; the main register
// refills from the skid register first, so the order is kept. One item per clock with no
// bubble at valid = 1 / ready = 1; one cycle of latency. Only the valid flags reset; the
// data registers are qualified by them.
//
// Simulation (`ifdef IRNUC_ASSERT): a protocol checker on each side; CheckIn = 0 leaves
// the input side's out where that stream is already checked, as the output of another
// spill register (each boundary is then checked once; no logic either way).
module irnuc_spill_register #(
  parameter int unsigned DataBits = 1,
  parameter bit          CheckIn  = 1'b1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  // Input side.
  input  logic                valid_i,
  output logic                ready_o,
  input  logic [DataBits-1:0] data_i,
  // Output side.
  output logic                valid_o,
  input  logic                ready_i,
  output logic [DataBits-1:0] data_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (DataBits >= 1)
      else $fatal(1, "irnuc_spill_register: DataBits = %0d must be at least 1", DataBits);
  end
`endif

  logic                main_valid_q, skid_valid_q;
  logic [DataBits-1:0] main_data_q, skid_data_q;
  logic                main_load;

  // The main register takes a new item when it is empty or its item leaves now.
  assign main_load = ~main_valid_q | ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_valid
    if (!rst_ni) begin
      main_valid_q <= 1'b0;
      skid_valid_q <= 1'b0;
    end else if (main_load) begin
      // From the skid register if it holds an item (then no input is taken), else the input.
      main_valid_q <= skid_valid_q | valid_i;
      skid_valid_q <= 1'b0;
    end else if (valid_i && !skid_valid_q) begin
      skid_valid_q <= 1'b1;
    end
  end

  always_ff @(posedge clk_i) begin : p_data
    if (main_load) begin
      main_data_q <= skid_valid_q ? skid_data_q : data_i;
    end
    // While the skid register is empty it follows the input; it keeps what it got in the
    // cycle it became full.
    if (!skid_valid_q) begin
      skid_data_q <= data_i;
    end
  end

  assign ready_o = ~skid_valid_q;
  assign valid_o = main_valid_q;
  assign data_o  = main_data_q;

`ifdef IRNUC_ASSERT
  if (CheckIn) begin : gen_assert_in
    irnuc_stream_assert #(.DataBits(DataBits)) u_assert_in (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .valid_i(valid_i),
      .ready_i(ready_o),
      .data_i (data_i)
    );
  end
  irnuc_stream_assert #(.DataBits(DataBits)) u_assert_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(valid_o),
    .ready_i(ready_i),
    .data_i (data_o)
  );
`endif

endmodule
