// Proof harness of the AXI4-Lite register file irnuc_axil_regs (`irnuc formal`,
// docs/formal.md): the AXI4-Lite slave rules of irnuc_fv_axil on its s_axil port (the
// master's assumed) and the register semantics of irnuc_fv_regs (responses, reset values,
// strobes, W1C against a simultaneous event, counters, STATUS.pending and the frame start),
// with every other input free (the framer's events and levels, the FFC unit, TABLE_SEL),
// one transaction at a time (a_one_transaction), and its own checks (with IRNUC_ASSERT:
// irnuc_axil_regs_check's contract of the generated block's external requests, the CPU
// interface's readies). The parameters are the
// register file's for one configuration (irnuc.cosim.sources.register_file_parameters), the
// map package irnuc_fv_map that configuration's (irnuc.verif.formal_regmap).
module fv_axil_regs
  import irnuc_pkg::*;
#(
  parameter int unsigned AdcBits           = 14,
  parameter int unsigned GainIntBits       = 2,
  parameter int unsigned GainFracBits      = 14,
  parameter int unsigned OffsetIntBits     = 12,
  parameter int unsigned OffsetFracBits    = 4,
  parameter int unsigned OutBits           = 14,
  parameter int unsigned Rounding          = 1,
  parameter int unsigned Overflow          = 0,
  parameter int unsigned MaxWidth          = 1024,
  parameter int unsigned MaxHeight         = 1024,
  // The configured method (CONFIG) and what it builds in.
  parameter int unsigned MethodCode        = 1,
  parameter int unsigned HasBlindDrift     = 0,
  parameter int unsigned HasFfc            = 0,
  parameter int unsigned FfcFrames         = 1,
  parameter int unsigned CoefLayoutVersion = 1,
  // Bits of one s_axis_coef word (the method's coefficient word; default two_point's).
  parameter int unsigned CoefWordBits      = coef_word_bits(GainIntBits + GainFracBits,
                                                            OffsetIntBits + OffsetFracBits),
  // Widths of the method registers (PipelineConfig.registers), 0 = not in this method.
  parameter int unsigned GainRegBits       = 0,
  parameter int unsigned LevelRegBits      = 0,
  parameter int unsigned ReadingRegBits    = 0,
  parameter int unsigned TRefRegBits       = 0,
  parameter int unsigned BlindSumRegBits   = 0,
  parameter int unsigned BlindRefRegBits   = 0,
  parameter int unsigned DriftGainRegBits  = 0,
  parameter int unsigned FfcTargetRegBits  = 0,
  parameter int unsigned HousingReadingRegBits = 0,
  parameter int unsigned HRefRegBits       = 0,
  parameter int unsigned TableReadings     = 0,
  parameter int unsigned TableReadingBits  = 1,
  localparam int unsigned AddrBits   = RegAddrBits,
  localparam int unsigned WidthBits  = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits = $clog2(MaxHeight + 1)
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic [AddrBits-1:0]   s_axil_awaddr_i,
  input logic                  s_axil_awvalid_i,
  input logic [31:0]           s_axil_wdata_i,
  input logic [3:0]            s_axil_wstrb_i,
  input logic                  s_axil_wvalid_i,
  input logic                  s_axil_bready_i,
  input logic [AddrBits-1:0]   s_axil_araddr_i,
  input logic                  s_axil_arvalid_i,
  input logic                  s_axil_rready_i,
  input logic [31:0]           table_sel_i,
  input logic                  start_i,
  input logic                  frame_start_i,
  input logic                  beat_i,
  input logic                  drop_i,
  input logic                  pad_i,
  input logic                  pix_out_i,
  input logic                  frame_out_i,
  input logic                  sof_early_i,
  input logic                  sof_late_i,
  input logic                  eol_early_i,
  input logic                  eol_late_i,
  input logic                  coef_early_i,
  input logic                  coef_late_i,
  input logic                  in_frame_i,
  input logic                  core_err_i,
  input logic                  ffc_busy_i,
  input logic                  ffc_done_i,
  input logic [AddrBits-3:0]   pick_i  // the register irnuc_fv_regs follows (constant)
);

  logic                   s_axil_awready_o, s_axil_wready_o, s_axil_bvalid_o, s_axil_arready_o;
  logic                   s_axil_rvalid_o;
  logic [1:0]             s_axil_bresp_o, s_axil_rresp_o;
  logic [31:0]            s_axil_rdata_o;

  irnuc_axil_regs #(
    .AdcBits(AdcBits), .GainIntBits(GainIntBits), .GainFracBits(GainFracBits),
    .OffsetIntBits(OffsetIntBits), .OffsetFracBits(OffsetFracBits), .OutBits(OutBits),
    .Rounding(Rounding), .Overflow(Overflow), .MaxWidth(MaxWidth), .MaxHeight(MaxHeight),
    .MethodCode(MethodCode), .HasBlindDrift(HasBlindDrift), .HasFfc(HasFfc),
    .FfcFrames(FfcFrames), .CoefLayoutVersion(CoefLayoutVersion), .CoefWordBits(CoefWordBits),
    .GainRegBits(GainRegBits), .LevelRegBits(LevelRegBits), .ReadingRegBits(ReadingRegBits),
    .TRefRegBits(TRefRegBits), .BlindSumRegBits(BlindSumRegBits),
    .BlindRefRegBits(BlindRefRegBits), .DriftGainRegBits(DriftGainRegBits),
    .FfcTargetRegBits(FfcTargetRegBits), .HousingReadingRegBits(HousingReadingRegBits),
    .HRefRegBits(HRefRegBits), .TableReadings(TableReadings),
    .TableReadingBits(TableReadingBits)
  ) u_dut (
    .*,
    .width_o(), .height_o(), .width_m1_o(), .height_m1_o(), .width_is1_o(), .height_is1_o(),
    .size_dirty_o(), .size_write_o(), .nuc_en_o(), .dpc_en_o(), .coef_sync_o(), .slot_o(),
    .table_o(), .table_write_o(), .ffc_start_o(), .ffc_frames_o(), .irq_o()
  );

  irnuc_fv_reset u_reset (.clk_i, .rst_ni);
  irnuc_fv_axil #(.AddrBits(AddrBits), .MaxOpen(2)) u_axil (
    .clk_i, .rst_ni,
    .awaddr_i(s_axil_awaddr_i), .awprot_i(3'b000), .awvalid_i(s_axil_awvalid_i),
    .awready_i(s_axil_awready_o), .wdata_i(s_axil_wdata_i), .wstrb_i(s_axil_wstrb_i),
    .wvalid_i(s_axil_wvalid_i), .wready_i(s_axil_wready_o), .bresp_i(s_axil_bresp_o),
    .bvalid_i(s_axil_bvalid_o), .bready_i(s_axil_bready_i), .araddr_i(s_axil_araddr_i),
    .arprot_i(3'b000), .arvalid_i(s_axil_arvalid_i), .arready_i(s_axil_arready_o),
    .rdata_i(s_axil_rdata_o), .rresp_i(s_axil_rresp_o), .rvalid_i(s_axil_rvalid_o),
    .rready_i(s_axil_rready_i));

  irnuc_fv_regs #(.AddrBits(AddrBits), .Depth(2)) u_regs (
    .clk_i, .rst_ni,
    .awaddr_i(s_axil_awaddr_i), .awvalid_i(s_axil_awvalid_i), .awready_i(s_axil_awready_o),
    .wdata_i(s_axil_wdata_i), .wstrb_i(s_axil_wstrb_i), .wvalid_i(s_axil_wvalid_i),
    .wready_i(s_axil_wready_o), .bresp_i(s_axil_bresp_o), .bvalid_i(s_axil_bvalid_o),
    .bready_i(s_axil_bready_i), .araddr_i(s_axil_araddr_i), .arvalid_i(s_axil_arvalid_i),
    .arready_i(s_axil_arready_o), .rdata_i(s_axil_rdata_o), .rresp_i(s_axil_rresp_o),
    .rvalid_i(s_axil_rvalid_o), .rready_i(s_axil_rready_i),
    // irnuc_fv_map's event order (irnuc.verif.formal_regmap.EVENTS).
    .ev_i({ffc_done_i, coef_late_i, coef_early_i, eol_late_i, eol_early_i, sof_late_i,
           sof_early_i, pad_i, drop_i, pix_out_i, beat_i, frame_out_i, frame_start_i}),
    .start_i, .pick_i);

`ifdef FORMAL
  logic [AddrBits-3:0] pick_q;
  logic                init_q = 1'b1;
  always_ff @(posedge clk_i) begin : p_pick
    pick_q <= pick_i;
    init_q <= 1'b0;
  end
  always_comb begin : p_env
    if (!init_q) begin
      m_pick_constant: assume (pick_i == pick_q);
    end
  end
  // One AXI4-Lite transaction at a time (docs/regmap.md): never a write and a read
  // response at once (a request waits while the other channel's is in progress).
  always_comb begin : p_one
    if (rst_ni) begin
      a_one_transaction: assert (!(s_axil_bvalid_o && s_axil_rvalid_o));
    end
  end
  always_comb begin : p_cover
    if (rst_ni) begin
      c_read_wait: cover (s_axil_rvalid_o && !s_axil_rready_i && u_axil.aw_open_q != '0);
      c_two_writes: cover (u_axil.aw_open_q == 2'd2);
      c_picked_read: cover (s_axil_rvalid_o && u_regs.ar_q[0] == pick_i && pick_i == 10'd12
                            && s_axil_rdata_o[0]);
    end
  end
`endif

endmodule
