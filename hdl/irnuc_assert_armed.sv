// The arming flop of the simulation checks: armed_o is low in reset and rises at the first
// clock edge after it, so a check guarded by it starts from the second edge (the flops it
// reads have left their reset values by then). Instantiated only in `ifdef IRNUC_ASSERT /
// `ifndef SYNTHESIS blocks.
module irnuc_assert_armed (
  input  logic clk_i,
  input  logic rst_ni,
  output logic armed_o
);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_armed
    if (!rst_ni) begin
      armed_o <= 1'b0;
    end else begin
      armed_o <= 1'b1;
    end
  end

endmodule
