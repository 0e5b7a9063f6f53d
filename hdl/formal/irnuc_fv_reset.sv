// The start of every proof of `irnuc formal` (docs/formal.md): the first cycle is in reset
// (rst_ni low); after it rst_ni is free, so a reset may come at any cycle. FORMAL only.
module irnuc_fv_reset (
  input logic clk_i,
  input logic rst_ni
);

`ifdef FORMAL
  // The initial state: an initial value (formal only; no reset can give it).
  /* verilator lint_off PROCASSINIT */
  logic init_q = 1'b1;
  /* verilator lint_on PROCASSINIT */

  always_ff @(posedge clk_i) begin : p_init
    init_q <= 1'b0;
  end

  always_comb begin : p_start
    if (init_q) begin
      m_start_in_reset: assume (!rst_ni);
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni};
`endif

endmodule
