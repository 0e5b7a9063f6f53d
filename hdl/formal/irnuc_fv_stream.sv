// AXI4-Stream rules (ARM IHI0051, 2.2.1 "Handshake process", 2.7.1 "Reset") on one
// valid/ready port, for the proofs of `irnuc formal` (docs/formal.md). Immediate
// assertions on this cycle's values and registered copies of the previous cycle's (the open
// Yosys front end reads no concurrent SVA); compiled only with FORMAL.
//
// Assume = 1: the port is an input of the design under proof and the rules constrain its
// environment (assumptions m_*); Assume = 0: an output, and they are proof obligations:
//   a_valid_held   TVALID, once high, stays high until TREADY
//   a_data_stable  the payload (TDATA with TUSER, TLAST: data_i) is unchanged while
//                  TVALID && !TREADY
//   a_reset_idle   TVALID is low in reset and in the first cycle after it
module irnuc_fv_stream #(
  parameter int unsigned DataBits = 1,
  parameter bit          Assume   = 1'b0
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                valid_i,
  input logic                ready_i,
  input logic [DataBits-1:0] data_i
);

`ifdef FORMAL
  logic                stall_q, reset_q;
  logic [DataBits-1:0] data_q;

  always_ff @(posedge clk_i) begin : p_sample
    stall_q <= rst_ni && valid_i && !ready_i;
    data_q  <= data_i;
    reset_q <= !rst_ni;
  end

  if (Assume) begin : gen_input
    always_comb begin : p_rules
      if (!rst_ni) begin
        m_reset_idle: assume (!valid_i);
      end else if (stall_q) begin
        m_valid_held: assume (valid_i);
        m_data_stable: assume (data_i == data_q);
      end
    end
  end else begin : gen_output
    always_comb begin : p_rules
      if (!rst_ni || reset_q) begin
        a_reset_idle: assert (!valid_i);
      end else if (stall_q) begin
        a_valid_held: assert (valid_i);
        a_data_stable: assert (data_i == data_q);
      end
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, valid_i, ready_i, data_i};
`endif

endmodule
