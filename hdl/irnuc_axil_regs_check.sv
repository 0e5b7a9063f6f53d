// Checks of irnuc_axil_regs that synthesis does not see: its parameters at elaboration, and
// (with IRNUC_ASSERT) the contract of the generated register block's external requests
// that the hand-written registers rely on. The AXI4-Lite ports themselves are checked in
// the top (irnuc_axil_assert).
module irnuc_axil_regs_check
  import irnuc_pkg::*;
#(
  parameter int unsigned MaxWidth         = 1024,
  parameter int unsigned MaxHeight        = 1024,
  parameter int unsigned WidthBits        = 11,
  parameter int unsigned HeightBits       = 11,
  parameter int unsigned NumSlots         = 8,
  parameter int unsigned SlotBits [NumSlots] = '{default: 0},
  parameter int unsigned TableReadings    = 0,
  parameter int unsigned TableReadingBits = 16,
  parameter int unsigned NumExternal      = 1
) (
  input logic                   clk_i,
  input logic                   rst_ni,
  input logic [NumExternal-1:0] ext_req_i,   // every external register's request
  input logic                   ext_ack_i,   // any external register's rd_ack or wr_ack
  input logic                   size_req_i,  // FRAME_SIZE's write request, two cycles late
  input logic                   size_ack_i   // FRAME_SIZE's wr_ack
);

  initial begin : p_param_ranges
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax &&
            MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "irnuc_axil_regs: MaxWidth = %0d, MaxHeight = %0d outside %0d..%0d",
                  MaxWidth, MaxHeight, MaxWidthMin, MaxWidthMax);
    assert (WidthBits <= RegFrameSizeWidthBits && HeightBits <= RegFrameSizeHeightBits)
      else $fatal(1, "irnuc_axil_regs: the frame size does not fit FRAME_SIZE");
    for (int k = 0; k < NumSlots; k++) begin
      assert (SlotBits[k] <= 64)
        else $fatal(1, "irnuc_axil_regs: method register %0d of %0d bits > 64", k,
                    SlotBits[k]);
    end
    assert (TableReadings <= RegTableReadingCount && TableReadingBits >= 1 && TableReadingBits <= 32)
      else $fatal(1, "irnuc_axil_regs: %0d table readings of %0d bits", TableReadings,
                  TableReadingBits);
  end

`ifdef IRNUC_ASSERT
  // The register block hands one external request at a time, for one cycle, and waits for
  // its acknowledge before the next (external_pending): the hand-written registers answer
  // a read in its request's cycle and FRAME_SIZE's write three cycles after it.
  logic armed_q, size_req_q, ext_open_q;
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_track
    if (!rst_ni) begin
      size_req_q <= 1'b0;
      ext_open_q <= 1'b0;
    end else begin
      size_req_q <= size_req_i;
      ext_open_q <= (ext_open_q || |ext_req_i) && !ext_ack_i;
    end
  end
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_one_request: assert ($onehot0(ext_req_i))
        else $error("irnuc_axil_regs: two external requests in one cycle");
      a_request_waits: assert (!(|ext_req_i) || !ext_open_q)
        else $error("irnuc_axil_regs: an external request before the last one's acknowledge");
      a_size_ack: assert (size_ack_i == size_req_q)
        else $error("irnuc_axil_regs: FRAME_SIZE's write not acknowledged three cycles after it");
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, ext_req_i, ext_ack_i, size_req_i, size_ack_i};
`endif

endmodule
