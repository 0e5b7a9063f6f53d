// Proof harness of irnuc_axis_buffer (`irnuc formal`, docs/formal.md), with and without
// head bits: the AXI4-Stream rules on both sides (assumed on the input, proved on the
// output), every item once, unchanged and in order, at most two inside; the buffer's own
// checks (a_head, a_rd_copy) with IRNUC_ASSERT.
module fv_axis_buffer #(
  parameter int unsigned DataBits = 5,
  parameter int unsigned HeadBits = 2
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                valid_i,
  input logic [DataBits-1:0] data_i,
  input logic                ready_i,
  input logic                pick_i
);

  logic                ready_o, valid_o;
  logic [DataBits-1:0] data_o;

  irnuc_axis_buffer #(.DataBits(DataBits), .HeadBits(HeadBits)) u_dut (.*);

  irnuc_fv_reset u_reset (.clk_i, .rst_ni);
  irnuc_fv_stream #(.DataBits(DataBits), .Assume(1'b1)) u_in (
    .clk_i, .rst_ni, .valid_i, .ready_i(ready_o), .data_i);
  irnuc_fv_stream #(.DataBits(DataBits), .Assume(1'b0)) u_out (
    .clk_i, .rst_ni, .valid_i(valid_o), .ready_i, .data_i(data_o));
  irnuc_fv_order #(.DataBits(DataBits), .Depth(2)) u_order (
    .clk_i, .rst_ni, .pick_i, .in_valid_i(valid_i), .in_ready_i(ready_o), .in_data_i(data_i),
    .out_valid_i(valid_o), .out_ready_i(ready_i), .out_data_i(data_o));

`ifdef FORMAL
  always_comb begin : p_cover
    if (rst_ni) begin
      c_full: cover (valid_o && !ready_o);
      c_through: cover (valid_i && ready_o && valid_o && ready_i);
    end
  end
`endif

endmodule
