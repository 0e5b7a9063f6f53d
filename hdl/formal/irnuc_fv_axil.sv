// AXI4-Lite slave rules (ARM IHI0022, A3.2 "Basic read and write transactions", A3.3
// "Relationships between the channels", B1 "AXI4-Lite") on an s_axil port, for the proofs
// of `irnuc formal` (docs/formal.md); FORMAL only. Written against the interface, not a
// register file: any slave behind the port is held to them.
//
// The master (the environment) is assumed to keep the rules of its channels:
//   m_*_held / m_*_stable  AWVALID, WVALID, ARVALID stay high and their payload (AxPROT
//                          with the address) unchanged
//                          until the READY; m_reset_idle: no VALID in reset
// The slave must:
//   a_b_held, a_b_stable   BVALID stays high and BRESP unchanged until BREADY
//   a_r_held, a_r_stable   RVALID stays high, RDATA and RRESP unchanged, until RREADY
//   a_reset_idle           no BVALID, RVALID in reset and in the first cycle after it
//   a_b_request            a write response only for a write whose address and data were
//                          both taken and not yet answered (one B per AW + W pair)
//   a_r_request            a read response only for a read address taken and not answered
//   a_resp_legal           BRESP, RRESP never EXOKAY (no exclusive access on AXI4-Lite)
//   a_open                 (bound) at most MaxOpen addresses (and data) taken and not answered
module irnuc_fv_axil #(
  parameter int unsigned AddrBits = 12,
  parameter int unsigned MaxOpen  = 2
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic [AddrBits-1:0] awaddr_i,
  input logic [2:0]          awprot_i,
  input logic                awvalid_i,
  input logic                awready_i,
  input logic [31:0]         wdata_i,
  input logic [3:0]          wstrb_i,
  input logic                wvalid_i,
  input logic                wready_i,
  input logic [1:0]          bresp_i,
  input logic                bvalid_i,
  input logic                bready_i,
  input logic [AddrBits-1:0] araddr_i,
  input logic [2:0]          arprot_i,
  input logic                arvalid_i,
  input logic                arready_i,
  input logic [31:0]         rdata_i,
  input logic [1:0]          rresp_i,
  input logic                rvalid_i,
  input logic                rready_i
);

`ifdef FORMAL
  localparam int unsigned OpenBits = $clog2(MaxOpen + 2);
  localparam logic [1:0]  ExOkay   = 2'b01;

  logic                aw_stall_q, w_stall_q, ar_stall_q, b_stall_q, r_stall_q, reset_q;
  logic [AddrBits+2:0] aw_q, ar_q;
  logic [35:0]         w_q;
  logic [1:0]          bresp_q;
  logic [33:0]         r_q;
  logic                aw_fire, w_fire, b_fire, ar_fire, r_fire;
  logic [OpenBits-1:0] aw_open_q, w_open_q, ar_open_q;

  assign aw_fire = awvalid_i && awready_i;
  assign w_fire  = wvalid_i && wready_i;
  assign b_fire  = bvalid_i && bready_i;
  assign ar_fire = arvalid_i && arready_i;
  assign r_fire  = rvalid_i && rready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_stall
    if (!rst_ni) begin
      aw_stall_q <= 1'b0;
      w_stall_q  <= 1'b0;
      ar_stall_q <= 1'b0;
      b_stall_q  <= 1'b0;
      r_stall_q  <= 1'b0;
      reset_q    <= 1'b1;
    end else begin
      aw_stall_q <= awvalid_i && !awready_i;
      w_stall_q  <= wvalid_i && !wready_i;
      ar_stall_q <= arvalid_i && !arready_i;
      b_stall_q  <= bvalid_i && !bready_i;
      r_stall_q  <= rvalid_i && !rready_i;
      reset_q    <= 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin : p_sample
    aw_q       <= {awaddr_i, awprot_i};
    ar_q       <= {araddr_i, arprot_i};
    w_q        <= {wdata_i, wstrb_i};
    bresp_q    <= bresp_i;
    r_q        <= {rdata_i, rresp_i};
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_open
    if (!rst_ni) begin
      aw_open_q <= '0;
      w_open_q  <= '0;
      ar_open_q <= '0;
    end else begin
      aw_open_q <= aw_open_q + OpenBits'(aw_fire) - OpenBits'(b_fire);
      w_open_q  <= w_open_q + OpenBits'(w_fire) - OpenBits'(b_fire);
      ar_open_q <= ar_open_q + OpenBits'(ar_fire) - OpenBits'(r_fire);
    end
  end

  always_comb begin : p_master
    if (!rst_ni) begin
      m_reset_idle: assume (!awvalid_i && !wvalid_i && !arvalid_i);
    end else begin
      if (aw_stall_q) begin
        m_aw_held: assume (awvalid_i);
        m_aw_stable: assume ({awaddr_i, awprot_i} == aw_q);
      end
      if (w_stall_q) begin
        m_w_held: assume (wvalid_i);
        m_w_stable: assume ({wdata_i, wstrb_i} == w_q);
      end
      if (ar_stall_q) begin
        m_ar_held: assume (arvalid_i);
        m_ar_stable: assume ({araddr_i, arprot_i} == ar_q);
      end
    end
  end

  always_comb begin : p_slave
    if (!rst_ni || reset_q) begin
      a_reset_idle: assert (!bvalid_i && !rvalid_i);
    end else begin
      if (b_stall_q) begin
        a_b_held: assert (bvalid_i);
        a_b_stable: assert (bresp_i == bresp_q);
      end
      if (r_stall_q) begin
        a_r_held: assert (rvalid_i);
        a_r_stable: assert ({rdata_i, rresp_i} == r_q);
      end
      if (bvalid_i) begin
        a_b_request: assert (aw_open_q != '0 && w_open_q != '0);
        a_bresp_legal: assert (bresp_i != ExOkay);
      end
      if (rvalid_i) begin
        a_r_request: assert (ar_open_q != '0);
        a_rresp_legal: assert (rresp_i != ExOkay);
      end
      a_open: assert (32'(aw_open_q) <= MaxOpen && 32'(w_open_q) <= MaxOpen
                      && 32'(ar_open_q) <= MaxOpen);
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, awaddr_i, awprot_i, awvalid_i, awready_i, wdata_i, wstrb_i,
                          wvalid_i, wready_i, bresp_i, bvalid_i, bready_i, araddr_i, arprot_i,
                          arvalid_i, arready_i, rdata_i, rresp_i, rvalid_i, rready_i};
`endif

endmodule
