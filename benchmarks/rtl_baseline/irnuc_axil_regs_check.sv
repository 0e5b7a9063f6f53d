// Checks of irnuc_axil_regs that synthesis does not see: its parameters at elaboration, and
// (with IRNUC_ASSERT) its ready flops, each the complement of the state it stands for. The
// AXI4-Lite ports themselves are checked in the top (irnuc_axil_assert).
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
  parameter int unsigned TableReadingBits = 16
) (
  input logic clk_i,
  input logic rst_ni,
  input logic aw_ready_i,  // the register file's flops
  input logic aw_held_i,
  input logic w_ready_i,
  input logic w_held_i,
  input logic ar_ready_i,
  input logic ar_busy_i,
  input logic ar_held_i,
  input logic rdec_i,
  input logic r_valid_i,
  input logic wr_i,          // the write cycle
  input logic size_hit_i,    // size_hit_q, decoded a cycle early
  input logic size_hit_ref_i // the write's hit of FRAME_SIZE's size bits, from wsel_q, wmask
);

  initial begin : p_param_ranges
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax &&
            MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "irnuc_axil_regs: MaxWidth = %0d, MaxHeight = %0d outside %0d..%0d",
                  MaxWidth, MaxHeight, MaxWidthMin, MaxWidthMax);
    assert (WidthBits <= RegFrameSizeWidthBits && HeightBits <= RegFrameSizeHeightBits)
      else $fatal(1, "irnuc_axil_regs: the frame size does not fit FRAME_SIZE");
    assert (RegFrameSizeWidthLsb % 8 == 0 && RegFrameSizeWidthBits == 16
            && RegFrameSizeHeightLsb % 8 == 0 && RegFrameSizeHeightBits == 16)
      else $fatal(1, "irnuc_axil_regs: FRAME_SIZE's fields are not two byte lanes each");
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
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_aw_ready: assert (aw_ready_i == !aw_held_i)
        else $error("irnuc_axil_regs: awready is not 'no write address held'");
      a_w_ready: assert (w_ready_i == !w_held_i)
        else $error("irnuc_axil_regs: wready is not 'no write data held'");
      a_ar_busy: assert (ar_busy_i == (ar_held_i || rdec_i || r_valid_i))
        else $error("irnuc_axil_regs: the read channel's busy flag lost its read");
      a_ar_ready: assert (ar_ready_i == !ar_busy_i)
        else $error("irnuc_axil_regs: arready is not 'no read in progress'");
      a_size_hit: assert (!wr_i || size_hit_i == size_hit_ref_i)
        else $error("irnuc_axil_regs: size_hit_q is not the write's hit of FRAME_SIZE's size");
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, aw_ready_i, aw_held_i, w_ready_i, w_held_i,
                          ar_ready_i, ar_busy_i, ar_held_i, rdec_i, r_valid_i, wr_i,
                          size_hit_i, size_hit_ref_i};
`endif

endmodule
