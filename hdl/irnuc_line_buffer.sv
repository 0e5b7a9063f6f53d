// Line buffer: a simple dual-port memory of Depth words, one write port and one read
// port with a registered (synchronous) read, written so that synthesis maps it to block
// RAM (xc7 RAMB18E1/RAMB36E1, ECP5 DP16KD) or, when small, to LUT RAM.
//
// A read returns the word at rd_addr_i in the cycle after rd_en_i; rd_data_o holds while
// rd_en_i is low. Reading the address written in the same cycle gives an undefined word
// (no_rw_check: no collision logic is built); the user bypasses that case.
module irnuc_line_buffer
  import irnuc_pkg::*;
#(
  parameter int unsigned Depth    = 1024,
  parameter int unsigned DataBits = 30,
  // Derived, do not override.
  localparam int unsigned AddrBits = (Depth > 1) ? $clog2(Depth) : 1
) (
  input  logic                clk_i,
  input  logic                wr_en_i,
  input  logic [AddrBits-1:0] wr_addr_i,
  input  logic [DataBits-1:0] wr_data_i,
  input  logic                rd_en_i,
  input  logic [AddrBits-1:0] rd_addr_i,
  output logic [DataBits-1:0] rd_data_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (Depth >= 1 && Depth <= FrameDimMax)
      else $fatal(1, "irnuc_line_buffer: Depth = %0d outside 1..%0d", Depth, FrameDimMax);
    assert (DataBits >= 1)
      else $fatal(1, "irnuc_line_buffer: DataBits = %0d must be at least 1", DataBits);
  end
`endif

  (* no_rw_check *)
  logic [DataBits-1:0] mem_q [Depth];
  logic [DataBits-1:0] rd_data_q;

  always_ff @(posedge clk_i) begin : p_ram
    if (wr_en_i) begin
      mem_q[wr_addr_i] <= wr_data_i;
    end
    if (rd_en_i) begin
      rd_data_q <= mem_q[rd_addr_i];
    end
  end

  assign rd_data_o = rd_data_q;

endmodule
