// Frame-size checker (simulation only, no logic): when a frame's first pixel is taken
// (start_i: valid && ready && sof), the run-time size must lie in 1..MaxWidth x
// 1..MaxHeight. Instantiated under `ifdef IRNUC_ASSERT next to the stream checkers;
// frame_err_o flags the same condition in hardware.
module irnuc_frame_assert
  import irnuc_pkg::*;
#(
  parameter int unsigned MaxWidth   = 1024,
  parameter int unsigned MaxHeight  = 1024,
  // Derived, do not override.
  localparam int unsigned WidthBits  = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits = $clog2(MaxHeight + 1)
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic                  start_i,
  input logic [WidthBits-1:0]  width_i,
  input logic [HeightBits-1:0] height_i
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax &&
            MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "irnuc_frame_assert: MaxWidth = %0d, MaxHeight = %0d outside %0d..%0d",
                  MaxWidth, MaxHeight, MaxWidthMin, MaxWidthMax);
  end

  // Off in reset, on from the first edge after it (rst_ni stays a pure asynchronous reset).
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));

  // Immediate assertion at the edge: the same check as start_i |-> legal size, at a
  // fraction of the concurrent form's simulation cost.
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q && start_i) begin
      a_frame_size: assert (width_i >= WidthBits'(1) && 32'(width_i) <= MaxWidth &&
                            height_i >= HeightBits'(1) && 32'(height_i) <= MaxHeight)
        else $error("irnuc_frame_assert: frame size %0d x %0d outside 1..%0d x 1..%0d",
                    width_i, height_i, MaxWidth, MaxHeight);
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, start_i, width_i, height_i};
`endif

endmodule
