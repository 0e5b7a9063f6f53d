// AXI4-Lite register file of irnuc_axis_top: the map of nuc_fixed/registers.rdl
// (docs/registers.md).
//
// u_regblock (irnuc_axil_regblock, generated from the map by peakrdl-regblock) is the
// AXI4-Lite slave, the address decode, the registers it can store (CTRL, COMMAND, STATUS's
// sticky bits, IRQ_ENABLE, IRQ_STATUS, the counters) and the read-back; its responses
// (SLVERR outside the map, for a write to a read-only and a read of a write-only register)
// depend on the address and the access only. This module connects its hardware interface
// (hwif_in / hwif_out, docs/registers.md "Hardware interface"):
//   * the build's constants (VERSION.coef_layout, CONFIG, FORMAT, FRAME_MAX: fields the
//     map resets to a parameter of the map, driven from this module's parameter of that
//     name), the events and levels (STATUS, IRQ_STATUS, the counters' increments, FFC_STATUS,
//     TABLE_SEL); irq_o is a flop of the block's interrupt;
//   * the settings it stores (CTRL; STATUS.pending from its software-modified strobes);
// and implements the registers the map marks `external`, each answered a cycle after the
// block's (registered) request:
//   * FRAME_SIZE: a size of 0 or above FRAME_MAX is refused with SLVERR (hwif_wr_err: an
//     answer that depends on the value written) and the register keeps its value; the
//     size, the size minus one and the size-is-one flags are flops for the framer; a new
//     size raises size_dirty_o (the framer drains the core before using it);
//   * FFC_CTRL: its reset (FfcFrames) and presence (HasFfc) are the build's;
//   * FFC_PERIOD, FFC_THRESHOLD: present on FFC builds only; with FFC_TRIGGER and FFC_REF
//     they are irnuc_ffc_trigger's (the FFC request, IRQ_STATUS.ffc_request);
//   * the method registers (the 64-bit slots GAIN .. FFC_TARGET, TABLE_READING[k]): their
//     widths and presence are the build's (no flop for a bit the build has not; bits from
//     the width on read 0).
// Shadowed registers (CTRL, FRAME_SIZE, the method registers): the framer takes them at a
// frame start (start_i); a write changes the pending value, STATUS.pending is 1 until then.
module irnuc_axil_regs
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
  // Derived, do not override.
  localparam int unsigned AddrBits         = RegAddrBits,
  localparam int unsigned WidthBits        = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits       = $clog2(MaxHeight + 1),
  localparam int unsigned NumTable         = RegTableReadingCount,
  localparam int unsigned NumSlots         = RegSlotCount
) (
  input  logic                             clk_i,
  input  logic                             rst_ni,
  // AXI4-Lite slave (AxPROT is not used).
  input  logic [AddrBits-1:0]              s_axil_awaddr_i,
  input  logic                             s_axil_awvalid_i,
  output logic                             s_axil_awready_o,
  input  logic [31:0]                      s_axil_wdata_i,
  input  logic [3:0]                       s_axil_wstrb_i,
  input  logic                             s_axil_wvalid_i,
  output logic                             s_axil_wready_o,
  output logic [1:0]                       s_axil_bresp_o,
  output logic                             s_axil_bvalid_o,
  input  logic                             s_axil_bready_i,
  input  logic [AddrBits-1:0]              s_axil_araddr_i,
  input  logic                             s_axil_arvalid_i,
  output logic                             s_axil_arready_o,
  output logic [31:0]                      s_axil_rdata_o,
  output logic [1:0]                       s_axil_rresp_o,
  output logic                             s_axil_rvalid_o,
  input  logic                             s_axil_rready_i,
  // Pending settings (CTRL, FRAME_SIZE; *_m1 = value - 1, *_is1 = value is 1).
  output logic [WidthBits-1:0]             width_o,
  output logic [HeightBits-1:0]            height_o,
  output logic [WidthBits-1:0]             width_m1_o,
  output logic [HeightBits-1:0]            height_m1_o,
  output logic                             width_is1_o,
  output logic                             height_is1_o,
  output logic                             size_dirty_o,
  output logic                             size_write_o,  // size_dirty_o is set next cycle
  output logic                             nuc_en_o,
  output logic                             dpc_en_o,
  output logic                             coef_sync_o,
  // Pending method registers: the 64-bit slots (GAIN, LEVEL, READING, T_REF, BLIND_SUM,
  // BLIND_REF, DRIFT_GAIN, FFC_TARGET) and the table readings.
  output logic [NumSlots-1:0][63:0]        slot_o,
  output logic [NumTable-1:0][31:0]        table_o,
  // table_interp: READING or a TABLE_READING[k] written now; what TABLE_SEL reads.
  output logic                             table_write_o,
  input  logic [31:0]                      table_sel_i,
  // A frame starts (the framer takes the pending settings).
  input  logic                             start_i,
  // Events (one cycle each) and levels for STATUS, the counters and IRQ_STATUS.
  input  logic                             frame_start_i,
  input  logic                             beat_i,
  input  logic                             drop_i,
  input  logic                             pad_i,
  input  logic                             pix_out_i,
  input  logic                             frame_out_i,
  input  logic                             sof_early_i,
  input  logic                             sof_late_i,
  input  logic                             eol_early_i,
  input  logic                             eol_late_i,
  input  logic                             coef_early_i,
  input  logic                             coef_late_i,
  input  logic                             in_frame_i,
  input  logic                             core_err_i,
  // The FFC unit (HasFfc).
  output logic                             ffc_start_o,
  output logic [RegFfcCtrlFramesBits-1:0]  ffc_frames_o,
  input  logic                             ffc_busy_i,
  input  logic                             ffc_done_i,
  // Interrupt: OR of IRQ_STATUS and IRQ_ENABLE (a flop).
  output logic                             irq_o
);

  // The block's package is not imported: it also holds the map's parameters (CONFIG's
  // defaults), which this module's parameters of the same names replace.
  irnuc_axil_regblock_pkg::irnuc_regs__in_t  hwif_in;
  irnuc_axil_regblock_pkg::irnuc_regs__out_t hwif_out;
  logic             wr_err;  // an external write refused (FRAME_SIZE), with its wr_ack

  irnuc_axil_regblock u_regblock (
    .clk           (clk_i),
    .arst_n        (rst_ni),
    .s_axil_awready(s_axil_awready_o),
    .s_axil_awvalid(s_axil_awvalid_i),
    .s_axil_awaddr (s_axil_awaddr_i),
    .s_axil_awprot (3'b000),
    .s_axil_wready (s_axil_wready_o),
    .s_axil_wvalid (s_axil_wvalid_i),
    .s_axil_wdata  (s_axil_wdata_i),
    .s_axil_wstrb  (s_axil_wstrb_i),
    .s_axil_bready (s_axil_bready_i),
    .s_axil_bvalid (s_axil_bvalid_o),
    .s_axil_bresp  (s_axil_bresp_o),
    .s_axil_arready(s_axil_arready_o),
    .s_axil_arvalid(s_axil_arvalid_i),
    .s_axil_araddr (s_axil_araddr_i),
    .s_axil_arprot (3'b000),
    .s_axil_rready (s_axil_rready_i),
    .s_axil_rvalid (s_axil_rvalid_o),
    .s_axil_rdata  (s_axil_rdata_o),
    .s_axil_rresp  (s_axil_rresp_o),
    .hwif_wr_err   (wr_err),
    .hwif_in       (hwif_in),
    .hwif_out      (hwif_out)
  );

  // ---- the build's constants (fields reset to a parameter of the map) ----------------------
  assign hwif_in.VERSION.coef_layout.next    = RegVersionCoefLayoutBits'(CoefLayoutVersion);
  assign hwif_in.CONFIG.adc_bits.next        = RegConfigAdcBitsBits'(AdcBits);
  assign hwif_in.CONFIG.out_bits.next        = RegConfigOutBitsBits'(OutBits);
  assign hwif_in.CONFIG.word_bits.next       = RegConfigWordBitsBits'(CoefWordBits);
  assign hwif_in.CONFIG.method.next          = RegConfigMethodBits'(MethodCode);
  assign hwif_in.CONFIG.blind_drift.next     = (HasBlindDrift != 0);
  assign hwif_in.CONFIG.ffc.next             = (HasFfc != 0);
  assign hwif_in.CONFIG.rounding.next        = RegConfigRoundingBits'(Rounding);
  assign hwif_in.CONFIG.overflow.next        = (Overflow != 0);
  assign hwif_in.FORMAT.gain_int_bits.next   = RegFormatGainIntBitsBits'(GainIntBits);
  assign hwif_in.FORMAT.gain_frac_bits.next  = RegFormatGainFracBitsBits'(GainFracBits);
  assign hwif_in.FORMAT.offset_int_bits.next = RegFormatOffsetIntBitsBits'(OffsetIntBits);
  assign hwif_in.FORMAT.offset_frac_bits.next = RegFormatOffsetFracBitsBits'(OffsetFracBits);
  assign hwif_in.FRAME_MAX.width.next        = RegFrameMaxWidthBits'(MaxWidth);
  assign hwif_in.FRAME_MAX.height.next       = RegFrameMaxHeightBits'(MaxHeight);

  // ---- CTRL (shadowed; stored by the block) -------------------------------------------------
  logic ctrl_touch;  // a write changed a CTRL field (its byte lanes enabled)

  assign nuc_en_o    = hwif_out.CTRL.nuc_en.value;
  assign dpc_en_o    = hwif_out.CTRL.dpc_en.value;
  assign coef_sync_o = hwif_out.CTRL.coef_sync.value;
  assign ctrl_touch  = hwif_out.CTRL.nuc_en.swmod || hwif_out.CTRL.dpc_en.swmod
                       || hwif_out.CTRL.coef_sync.swmod;

  // ---- FRAME_SIZE (external, shadowed) ------------------------------------------------------
  // A write is answered three cycles after the block's request, each step from flops: the
  // request is registered (cycle 1), the size it would make (the written byte lanes over
  // the register) registered (cycle 2), its width's and its height's legality registered
  // (cycle 3), then wr_ack with wr_err and the register written.
  localparam int unsigned FieldW = RegFrameSizeWidthBits;
  localparam int unsigned FieldH = RegFrameSizeHeightBits;

  logic [WidthBits-1:0]  width_q, width_m1_q;
  logic [HeightBits-1:0] height_q, height_m1_q;
  logic                  width_is1_q, height_is1_q, size_dirty_q;
  logic                  size_req_q;        // cycle 1: the write request and its bus
  logic [FieldW-1:0]     size_wd_q, size_bw_q;
  logic [FieldH-1:0]     size_hd_q, size_bh_q;
  logic                  size_new_q;        // cycle 2: the size it would make
  logic [FieldW-1:0]     new_w_q;  // the fields as written, compared at their own width
  logic [FieldH-1:0]     new_h_q;
  logic                  size_wr_q, w_legal_q, h_legal_q;  // cycle 3
  // Cycle 3 too: a legal write that changes the size, one flop for the framer's start
  // decision (it reaches the framer's next-state logic, across the die).
  logic                  size_write_q;
  logic [WidthBits-1:0]  set_w_q;
  logic [HeightBits-1:0] set_h_q;
  logic                  size_legal, w_legal_d, h_legal_d;

  assign w_legal_d = (new_w_q != '0) && (new_w_q <= FieldW'(MaxWidth));
  assign h_legal_d = (new_h_q != '0) && (new_h_q <= FieldH'(MaxHeight));

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_size_steps
    if (!rst_ni) begin
      size_req_q   <= 1'b0;
      size_new_q   <= 1'b0;
      size_wr_q    <= 1'b0;
      w_legal_q    <= 1'b0;
      h_legal_q    <= 1'b0;
      size_write_q <= 1'b0;
    end else begin
      size_req_q   <= hwif_out.FRAME_SIZE.req && hwif_out.FRAME_SIZE.req_is_wr;
      size_new_q   <= size_req_q;
      size_wr_q    <= size_new_q;
      w_legal_q    <= w_legal_d;
      h_legal_q    <= h_legal_d;
      size_write_q <= size_new_q && w_legal_d && h_legal_d && |{size_bw_q, size_bh_q};
    end
  end

  always_ff @(posedge clk_i) begin : p_size_bus
    if (hwif_out.FRAME_SIZE.req) begin
      size_wd_q <= hwif_out.FRAME_SIZE.wr_data.width;
      size_bw_q <= hwif_out.FRAME_SIZE.wr_biten.width;
      size_hd_q <= hwif_out.FRAME_SIZE.wr_data.height;
      size_bh_q <= hwif_out.FRAME_SIZE.wr_biten.height;
    end
    if (size_req_q) begin
      new_w_q <= (FieldW'(width_q) & ~size_bw_q) | (size_wd_q & size_bw_q);
      new_h_q <= (FieldH'(height_q) & ~size_bh_q) | (size_hd_q & size_bh_q);
    end
    if (size_new_q) begin
      set_w_q <= WidthBits'(new_w_q);
      set_h_q <= HeightBits'(new_h_q);
    end
  end

  assign size_legal = w_legal_q && h_legal_q;
  // A flop (size_wr_q && size_legal and a byte lane of a field written): the framer's start
  // decision reads it.
  assign size_write_o = size_write_q;
  assign wr_err       = size_wr_q && !size_legal;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_size
    if (!rst_ni) begin
      width_q      <= WidthBits'(MaxWidth);
      width_m1_q   <= WidthBits'(MaxWidth - 1);
      width_is1_q  <= (MaxWidth == 1);
      height_q     <= HeightBits'(MaxHeight);
      height_m1_q  <= HeightBits'(MaxHeight - 1);
      height_is1_q <= (MaxHeight == 1);
    end else if (size_wr_q && size_legal) begin
      width_q      <= set_w_q;
      width_m1_q   <= set_w_q - WidthBits'(1);  // from the flop: no strobe merge before
      width_is1_q  <= (set_w_q == WidthBits'(1));
      height_q     <= set_h_q;
      height_m1_q  <= set_h_q - HeightBits'(1);
      height_is1_q <= (set_h_q == HeightBits'(1));
    end
  end

  assign hwif_in.FRAME_SIZE.rd_ack       = hwif_out.FRAME_SIZE.req
                                           && !hwif_out.FRAME_SIZE.req_is_wr;
  assign hwif_in.FRAME_SIZE.wr_ack       = size_wr_q;
  assign hwif_in.FRAME_SIZE.rd_data.width  = FieldW'(width_q);
  assign hwif_in.FRAME_SIZE.rd_data.height = FieldH'(height_q);

  assign width_o      = width_q;
  assign height_o     = height_q;
  assign width_m1_o   = width_m1_q;
  assign height_m1_o  = height_m1_q;
  assign width_is1_o  = width_is1_q;
  assign height_is1_o = height_is1_q;

  // ---- the method registers (external, shadowed) --------------------------------------------
  // irnuc-regmap: begin (generated from nuc_fixed/registers.rdl; do not edit)
  // The method registers' 64-bit slots (the map's register files of LO and HI; 
  // NumSlots = irnuc_pkg::RegSlotCount), their widths (this module's parameters,
  // 0 = not in this build) and their indices.
  localparam int unsigned SlotBits [NumSlots] = '{
    GainRegBits,
    LevelRegBits,
    ReadingRegBits,
    TRefRegBits,
    BlindSumRegBits,
    BlindRefRegBits,
    DriftGainRegBits,
    FfcTargetRegBits,
    HousingReadingRegBits,
    HRefRegBits
  };
  /* verilator lint_off UNUSEDPARAM */  // the indices the module does not name
  localparam int unsigned SlotGain = 0;
  localparam int unsigned SlotLevel = 1;
  localparam int unsigned SlotReading = 2;
  localparam int unsigned SlotTRef = 3;
  localparam int unsigned SlotBlindSum = 4;
  localparam int unsigned SlotBlindRef = 5;
  localparam int unsigned SlotDriftGain = 6;
  localparam int unsigned SlotFfcTarget = 7;
  localparam int unsigned SlotHousingReading = 8;
  localparam int unsigned SlotHRef = 9;
  /* verilator lint_on UNUSEDPARAM */
  logic [NumSlots-1:0][1:0]       slot_req, slot_req_is_wr, slot_rd_ack, slot_wr_ack;
  logic [NumSlots-1:0][1:0][31:0] slot_wr_data, slot_wr_biten, slot_rd_data;
  assign slot_req[0][0]       = hwif_out.GAIN.LO.req;
  assign slot_req_is_wr[0][0] = hwif_out.GAIN.LO.req_is_wr;
  assign slot_wr_data[0][0]   = hwif_out.GAIN.LO.wr_data.value;
  assign slot_wr_biten[0][0]  = hwif_out.GAIN.LO.wr_biten.value;
  assign hwif_in.GAIN.LO.rd_ack       = slot_rd_ack[0][0];
  assign hwif_in.GAIN.LO.rd_data.value = slot_rd_data[0][0];
  assign hwif_in.GAIN.LO.wr_ack       = slot_wr_ack[0][0];
  assign slot_req[0][1]       = hwif_out.GAIN.HI.req;
  assign slot_req_is_wr[0][1] = hwif_out.GAIN.HI.req_is_wr;
  assign slot_wr_data[0][1]   = hwif_out.GAIN.HI.wr_data.value;
  assign slot_wr_biten[0][1]  = hwif_out.GAIN.HI.wr_biten.value;
  assign hwif_in.GAIN.HI.rd_ack       = slot_rd_ack[0][1];
  assign hwif_in.GAIN.HI.rd_data.value = slot_rd_data[0][1];
  assign hwif_in.GAIN.HI.wr_ack       = slot_wr_ack[0][1];
  assign slot_req[1][0]       = hwif_out.LEVEL.LO.req;
  assign slot_req_is_wr[1][0] = hwif_out.LEVEL.LO.req_is_wr;
  assign slot_wr_data[1][0]   = hwif_out.LEVEL.LO.wr_data.value;
  assign slot_wr_biten[1][0]  = hwif_out.LEVEL.LO.wr_biten.value;
  assign hwif_in.LEVEL.LO.rd_ack       = slot_rd_ack[1][0];
  assign hwif_in.LEVEL.LO.rd_data.value = slot_rd_data[1][0];
  assign hwif_in.LEVEL.LO.wr_ack       = slot_wr_ack[1][0];
  assign slot_req[1][1]       = hwif_out.LEVEL.HI.req;
  assign slot_req_is_wr[1][1] = hwif_out.LEVEL.HI.req_is_wr;
  assign slot_wr_data[1][1]   = hwif_out.LEVEL.HI.wr_data.value;
  assign slot_wr_biten[1][1]  = hwif_out.LEVEL.HI.wr_biten.value;
  assign hwif_in.LEVEL.HI.rd_ack       = slot_rd_ack[1][1];
  assign hwif_in.LEVEL.HI.rd_data.value = slot_rd_data[1][1];
  assign hwif_in.LEVEL.HI.wr_ack       = slot_wr_ack[1][1];
  assign slot_req[2][0]       = hwif_out.READING.LO.req;
  assign slot_req_is_wr[2][0] = hwif_out.READING.LO.req_is_wr;
  assign slot_wr_data[2][0]   = hwif_out.READING.LO.wr_data.value;
  assign slot_wr_biten[2][0]  = hwif_out.READING.LO.wr_biten.value;
  assign hwif_in.READING.LO.rd_ack       = slot_rd_ack[2][0];
  assign hwif_in.READING.LO.rd_data.value = slot_rd_data[2][0];
  assign hwif_in.READING.LO.wr_ack       = slot_wr_ack[2][0];
  assign slot_req[2][1]       = hwif_out.READING.HI.req;
  assign slot_req_is_wr[2][1] = hwif_out.READING.HI.req_is_wr;
  assign slot_wr_data[2][1]   = hwif_out.READING.HI.wr_data.value;
  assign slot_wr_biten[2][1]  = hwif_out.READING.HI.wr_biten.value;
  assign hwif_in.READING.HI.rd_ack       = slot_rd_ack[2][1];
  assign hwif_in.READING.HI.rd_data.value = slot_rd_data[2][1];
  assign hwif_in.READING.HI.wr_ack       = slot_wr_ack[2][1];
  assign slot_req[3][0]       = hwif_out.T_REF.LO.req;
  assign slot_req_is_wr[3][0] = hwif_out.T_REF.LO.req_is_wr;
  assign slot_wr_data[3][0]   = hwif_out.T_REF.LO.wr_data.value;
  assign slot_wr_biten[3][0]  = hwif_out.T_REF.LO.wr_biten.value;
  assign hwif_in.T_REF.LO.rd_ack       = slot_rd_ack[3][0];
  assign hwif_in.T_REF.LO.rd_data.value = slot_rd_data[3][0];
  assign hwif_in.T_REF.LO.wr_ack       = slot_wr_ack[3][0];
  assign slot_req[3][1]       = hwif_out.T_REF.HI.req;
  assign slot_req_is_wr[3][1] = hwif_out.T_REF.HI.req_is_wr;
  assign slot_wr_data[3][1]   = hwif_out.T_REF.HI.wr_data.value;
  assign slot_wr_biten[3][1]  = hwif_out.T_REF.HI.wr_biten.value;
  assign hwif_in.T_REF.HI.rd_ack       = slot_rd_ack[3][1];
  assign hwif_in.T_REF.HI.rd_data.value = slot_rd_data[3][1];
  assign hwif_in.T_REF.HI.wr_ack       = slot_wr_ack[3][1];
  assign slot_req[4][0]       = hwif_out.BLIND_SUM.LO.req;
  assign slot_req_is_wr[4][0] = hwif_out.BLIND_SUM.LO.req_is_wr;
  assign slot_wr_data[4][0]   = hwif_out.BLIND_SUM.LO.wr_data.value;
  assign slot_wr_biten[4][0]  = hwif_out.BLIND_SUM.LO.wr_biten.value;
  assign hwif_in.BLIND_SUM.LO.rd_ack       = slot_rd_ack[4][0];
  assign hwif_in.BLIND_SUM.LO.rd_data.value = slot_rd_data[4][0];
  assign hwif_in.BLIND_SUM.LO.wr_ack       = slot_wr_ack[4][0];
  assign slot_req[4][1]       = hwif_out.BLIND_SUM.HI.req;
  assign slot_req_is_wr[4][1] = hwif_out.BLIND_SUM.HI.req_is_wr;
  assign slot_wr_data[4][1]   = hwif_out.BLIND_SUM.HI.wr_data.value;
  assign slot_wr_biten[4][1]  = hwif_out.BLIND_SUM.HI.wr_biten.value;
  assign hwif_in.BLIND_SUM.HI.rd_ack       = slot_rd_ack[4][1];
  assign hwif_in.BLIND_SUM.HI.rd_data.value = slot_rd_data[4][1];
  assign hwif_in.BLIND_SUM.HI.wr_ack       = slot_wr_ack[4][1];
  assign slot_req[5][0]       = hwif_out.BLIND_REF.LO.req;
  assign slot_req_is_wr[5][0] = hwif_out.BLIND_REF.LO.req_is_wr;
  assign slot_wr_data[5][0]   = hwif_out.BLIND_REF.LO.wr_data.value;
  assign slot_wr_biten[5][0]  = hwif_out.BLIND_REF.LO.wr_biten.value;
  assign hwif_in.BLIND_REF.LO.rd_ack       = slot_rd_ack[5][0];
  assign hwif_in.BLIND_REF.LO.rd_data.value = slot_rd_data[5][0];
  assign hwif_in.BLIND_REF.LO.wr_ack       = slot_wr_ack[5][0];
  assign slot_req[5][1]       = hwif_out.BLIND_REF.HI.req;
  assign slot_req_is_wr[5][1] = hwif_out.BLIND_REF.HI.req_is_wr;
  assign slot_wr_data[5][1]   = hwif_out.BLIND_REF.HI.wr_data.value;
  assign slot_wr_biten[5][1]  = hwif_out.BLIND_REF.HI.wr_biten.value;
  assign hwif_in.BLIND_REF.HI.rd_ack       = slot_rd_ack[5][1];
  assign hwif_in.BLIND_REF.HI.rd_data.value = slot_rd_data[5][1];
  assign hwif_in.BLIND_REF.HI.wr_ack       = slot_wr_ack[5][1];
  assign slot_req[6][0]       = hwif_out.DRIFT_GAIN.LO.req;
  assign slot_req_is_wr[6][0] = hwif_out.DRIFT_GAIN.LO.req_is_wr;
  assign slot_wr_data[6][0]   = hwif_out.DRIFT_GAIN.LO.wr_data.value;
  assign slot_wr_biten[6][0]  = hwif_out.DRIFT_GAIN.LO.wr_biten.value;
  assign hwif_in.DRIFT_GAIN.LO.rd_ack       = slot_rd_ack[6][0];
  assign hwif_in.DRIFT_GAIN.LO.rd_data.value = slot_rd_data[6][0];
  assign hwif_in.DRIFT_GAIN.LO.wr_ack       = slot_wr_ack[6][0];
  assign slot_req[6][1]       = hwif_out.DRIFT_GAIN.HI.req;
  assign slot_req_is_wr[6][1] = hwif_out.DRIFT_GAIN.HI.req_is_wr;
  assign slot_wr_data[6][1]   = hwif_out.DRIFT_GAIN.HI.wr_data.value;
  assign slot_wr_biten[6][1]  = hwif_out.DRIFT_GAIN.HI.wr_biten.value;
  assign hwif_in.DRIFT_GAIN.HI.rd_ack       = slot_rd_ack[6][1];
  assign hwif_in.DRIFT_GAIN.HI.rd_data.value = slot_rd_data[6][1];
  assign hwif_in.DRIFT_GAIN.HI.wr_ack       = slot_wr_ack[6][1];
  assign slot_req[7][0]       = hwif_out.FFC_TARGET.LO.req;
  assign slot_req_is_wr[7][0] = hwif_out.FFC_TARGET.LO.req_is_wr;
  assign slot_wr_data[7][0]   = hwif_out.FFC_TARGET.LO.wr_data.value;
  assign slot_wr_biten[7][0]  = hwif_out.FFC_TARGET.LO.wr_biten.value;
  assign hwif_in.FFC_TARGET.LO.rd_ack       = slot_rd_ack[7][0];
  assign hwif_in.FFC_TARGET.LO.rd_data.value = slot_rd_data[7][0];
  assign hwif_in.FFC_TARGET.LO.wr_ack       = slot_wr_ack[7][0];
  assign slot_req[7][1]       = hwif_out.FFC_TARGET.HI.req;
  assign slot_req_is_wr[7][1] = hwif_out.FFC_TARGET.HI.req_is_wr;
  assign slot_wr_data[7][1]   = hwif_out.FFC_TARGET.HI.wr_data.value;
  assign slot_wr_biten[7][1]  = hwif_out.FFC_TARGET.HI.wr_biten.value;
  assign hwif_in.FFC_TARGET.HI.rd_ack       = slot_rd_ack[7][1];
  assign hwif_in.FFC_TARGET.HI.rd_data.value = slot_rd_data[7][1];
  assign hwif_in.FFC_TARGET.HI.wr_ack       = slot_wr_ack[7][1];
  assign slot_req[8][0]       = hwif_out.HOUSING_READING.LO.req;
  assign slot_req_is_wr[8][0] = hwif_out.HOUSING_READING.LO.req_is_wr;
  assign slot_wr_data[8][0]   = hwif_out.HOUSING_READING.LO.wr_data.value;
  assign slot_wr_biten[8][0]  = hwif_out.HOUSING_READING.LO.wr_biten.value;
  assign hwif_in.HOUSING_READING.LO.rd_ack       = slot_rd_ack[8][0];
  assign hwif_in.HOUSING_READING.LO.rd_data.value = slot_rd_data[8][0];
  assign hwif_in.HOUSING_READING.LO.wr_ack       = slot_wr_ack[8][0];
  assign slot_req[8][1]       = hwif_out.HOUSING_READING.HI.req;
  assign slot_req_is_wr[8][1] = hwif_out.HOUSING_READING.HI.req_is_wr;
  assign slot_wr_data[8][1]   = hwif_out.HOUSING_READING.HI.wr_data.value;
  assign slot_wr_biten[8][1]  = hwif_out.HOUSING_READING.HI.wr_biten.value;
  assign hwif_in.HOUSING_READING.HI.rd_ack       = slot_rd_ack[8][1];
  assign hwif_in.HOUSING_READING.HI.rd_data.value = slot_rd_data[8][1];
  assign hwif_in.HOUSING_READING.HI.wr_ack       = slot_wr_ack[8][1];
  assign slot_req[9][0]       = hwif_out.H_REF.LO.req;
  assign slot_req_is_wr[9][0] = hwif_out.H_REF.LO.req_is_wr;
  assign slot_wr_data[9][0]   = hwif_out.H_REF.LO.wr_data.value;
  assign slot_wr_biten[9][0]  = hwif_out.H_REF.LO.wr_biten.value;
  assign hwif_in.H_REF.LO.rd_ack       = slot_rd_ack[9][0];
  assign hwif_in.H_REF.LO.rd_data.value = slot_rd_data[9][0];
  assign hwif_in.H_REF.LO.wr_ack       = slot_wr_ack[9][0];
  assign slot_req[9][1]       = hwif_out.H_REF.HI.req;
  assign slot_req_is_wr[9][1] = hwif_out.H_REF.HI.req_is_wr;
  assign slot_wr_data[9][1]   = hwif_out.H_REF.HI.wr_data.value;
  assign slot_wr_biten[9][1]  = hwif_out.H_REF.HI.wr_biten.value;
  assign hwif_in.H_REF.HI.rd_ack       = slot_rd_ack[9][1];
  assign hwif_in.H_REF.HI.rd_data.value = slot_rd_data[9][1];
  assign hwif_in.H_REF.HI.wr_ack       = slot_wr_ack[9][1];
  // irnuc-regmap: end

  logic [NumSlots-1:0] slot_touch;
  logic [NumTable-1:0] table_touch, table_wr;

  for (genvar k = 0; k < NumSlots; k++) begin : gen_slot
    logic [1:0] wr;  // a write to the slot's LO, HI word in this cycle
    for (genvar w = 0; w < 2; w++) begin : gen_word
      assign wr[w]              = slot_req[k][w] && slot_req_is_wr[k][w];
      assign slot_rd_ack[k][w]  = slot_req[k][w] && !slot_req_is_wr[k][w];
      assign slot_wr_ack[k][w]  = wr[w];
    end
    if (SlotBits[k] > 0) begin : gen_on
      localparam int unsigned Bits = SlotBits[k];
      localparam logic [63:0] Mask = (Bits >= 64) ? '1 : ((64'd1 << Bits) - 64'd1);
      localparam int unsigned LoBits = (Bits > 32) ? 32 : Bits;
      logic [63:0]     view, data, wbits;
      logic [Bits-1:0] next;

      assign data  = {slot_wr_data[k][1], slot_wr_data[k][0]};
      assign wbits = {slot_wr_biten[k][1], slot_wr_biten[k][0]};
      // A word's written bits within the width come from the request's flops: the touch is
      // one gate behind the word's write strobe.
      assign slot_touch[k] = (wr[0] && |(wbits[31:0] & Mask[31:0]))
                             || (wr[1] && |(wbits[63:32] & Mask[63:32]));
      // Each word's bits load on that word's write alone (LO and HI are two addresses, never
      // written together): the address decode reaches the enables only, not the data
      // multiplexers, and each strobe drives one word's enables.
      assign next  = Bits'((view & ~wbits) | (data & wbits));

      logic [LoBits-1:0] lo_q;
      always_ff @(posedge clk_i or negedge rst_ni) begin : p_value_lo
        if (!rst_ni) begin
          lo_q <= '0;
        end else if (wr[0]) begin
          lo_q <= next[LoBits-1:0];
        end
      end
      if (Bits > 32) begin : gen_hi
        logic [Bits-33:0] hi_q;
        always_ff @(posedge clk_i or negedge rst_ni) begin : p_value_hi
          if (!rst_ni) begin
            hi_q <= '0;
          end else if (wr[1]) begin
            hi_q <= next[Bits-1:32];
          end
        end
        assign view = 64'({hi_q, lo_q});
      end else begin : gen_lo_only
        assign view = 64'(lo_q);
      end
      assign slot_o[k]          = view;
      assign slot_rd_data[k][0] = view[31:0];
      assign slot_rd_data[k][1] = view[63:32];
    end else begin : gen_off
      assign slot_touch[k]      = 1'b0;
      assign slot_o[k]          = '0;
      assign slot_rd_data[k]    = '0;
      logic unused_slot;
      assign unused_slot = ^{slot_wr_data[k], slot_wr_biten[k]};
    end
  end

  for (genvar k = 0; k < NumTable; k++) begin : gen_table
    assign table_wr[k] = hwif_out.TABLE_READING[k].req && hwif_out.TABLE_READING[k].req_is_wr;
    assign hwif_in.TABLE_READING[k].rd_ack = hwif_out.TABLE_READING[k].req
                                             && !hwif_out.TABLE_READING[k].req_is_wr;
    assign hwif_in.TABLE_READING[k].wr_ack = table_wr[k];
    if (k < TableReadings) begin : gen_on
      localparam logic [31:0] Mask = axil_value_mask(TableReadingBits, 0);
      logic [TableReadingBits-1:0] value_q;
      logic [31:0]                 biten;

      assign biten          = hwif_out.TABLE_READING[k].wr_biten.value & {32{table_wr[k]}};
      assign table_touch[k] = |(biten & Mask);

      always_ff @(posedge clk_i or negedge rst_ni) begin : p_value
        if (!rst_ni) begin
          value_q <= '0;
        end else if (table_wr[k]) begin
          value_q <= TableReadingBits'((32'(value_q) & ~biten)
                                       | (hwif_out.TABLE_READING[k].wr_data.value & biten));
        end
      end
      assign table_o[k] = 32'(value_q);
    end else begin : gen_off
      assign table_touch[k] = 1'b0;
      assign table_o[k]     = '0;
      logic unused_table;
      assign unused_table = ^{hwif_out.TABLE_READING[k].wr_data.value,
                              hwif_out.TABLE_READING[k].wr_biten.value};
    end
    assign hwif_in.TABLE_READING[k].rd_data.value = table_o[k];
  end

  // READING or a TABLE_READING[k] written in this cycle (any byte lanes): irnuc_axis_table
  // computes the weight again.
  assign table_write_o = (TableReadings != 0)
                         && (|(slot_req[SlotReading] & slot_req_is_wr[SlotReading])
                             || |table_wr);

  // ---- STATUS.pending and the size change ---------------------------------------------------
  // A write that changes a shadowed register: pending until the next frame start (a write
  // in the start cycle stays pending: the framer took the value before it).
  // The writes' touches (CTRL, each method-register slot, each table reading) are flops of
  // their own, so the block's address decode ends one LUT behind its write strobes; STATUS
  // reads `pending` = pending_q || a touch of the last cycle, which is 1 in the same cycles as
  // a single flop fed by the touches directly would be (docs/regmap.md):
  //   pending(t+1) = touch(t) || size_write(t) || (pending(t) && !start(t)).
  localparam int unsigned NumTouch = 1 + NumSlots + NumTable;
  logic [NumTouch-1:0] touch_q;
  logic                pending_q, pending;

  assign pending = pending_q || |touch_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_pending
    if (!rst_ni) begin
      touch_q      <= '0;
      pending_q    <= 1'b0;
      size_dirty_q <= 1'b0;
    end else begin
      touch_q      <= {ctrl_touch, slot_touch, table_touch};
      pending_q    <= size_write_o || (pending && !start_i);
      size_dirty_q <= size_write_o || (size_dirty_q && !start_i);
    end
  end

  assign size_dirty_o = size_dirty_q;

  // ---- STATUS, IRQ_STATUS, the counters ---------------------------------------------------
  assign hwif_in.STATUS.sof_early.hwset  = sof_early_i;
  assign hwif_in.STATUS.sof_late.hwset   = sof_late_i;
  assign hwif_in.STATUS.eol_early.hwset  = eol_early_i;
  assign hwif_in.STATUS.eol_late.hwset   = eol_late_i;
  assign hwif_in.STATUS.coef_early.hwset = coef_early_i;
  assign hwif_in.STATUS.coef_late.hwset  = coef_late_i;
  assign hwif_in.STATUS.core_err.next    = core_err_i;
  assign hwif_in.STATUS.in_frame.next    = in_frame_i;
  assign hwif_in.STATUS.pending.next     = pending;

  assign hwif_in.IRQ_STATUS.error.next      = sof_early_i || sof_late_i || eol_early_i
                                              || eol_late_i || coef_early_i || coef_late_i;
  assign hwif_in.IRQ_STATUS.frame_done.next = frame_out_i;
  assign hwif_in.IRQ_STATUS.ffc_done.next   = ffc_done_i && (HasFfc != 0);

  // The counters' synchronous reset (the map's signal counters_clear): COMMAND's pulse, and
  // the cycle after rst_ni (init_q, 1 from reset): a clear mapped to the flops' set/reset
  // input, no logic before their adders.
  logic init_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_init
    if (!rst_ni) begin
      init_q <= 1'b1;
    end else begin
      init_q <= 1'b0;
    end
  end
  assign hwif_in.counters_clear = init_q || hwif_out.COMMAND.clear_counters.value;
  assign hwif_in.FRAMES_IN.count.incr   = frame_start_i;
  assign hwif_in.FRAMES_OUT.count.incr  = frame_out_i;
  assign hwif_in.PIXELS_IN.count.incr   = beat_i;
  assign hwif_in.PIXELS_OUT.count.incr  = pix_out_i;
  assign hwif_in.DROPPED.count.incr     = drop_i;
  assign hwif_in.PADDED.count.incr      = pad_i;
  assign hwif_in.SOF_ERRORS.early.incr  = sof_early_i;
  assign hwif_in.SOF_ERRORS.late.incr   = sof_late_i;
  assign hwif_in.EOL_ERRORS.early.incr  = eol_early_i;
  assign hwif_in.EOL_ERRORS.late.incr   = eol_late_i;
  assign hwif_in.COEF_ERRORS.early.incr = coef_early_i;
  assign hwif_in.COEF_ERRORS.late.incr  = coef_late_i;

  logic irq_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_irq
    if (!rst_ni) begin
      irq_q <= 1'b0;
    end else begin
      irq_q <= hwif_out.IRQ_STATUS.intr;
    end
  end
  assign irq_o = irq_q;

  // ---- FFC_CTRL (external), FFC_STATUS ------------------------------------------------------
  logic [RegFfcCtrlFramesBits-1:0] ffc_frames_q;
  logic                            ffc_start_q, ffc_done_q, ffc_wr;

  assign ffc_wr = hwif_out.FFC_CTRL.req && hwif_out.FFC_CTRL.req_is_wr;
  assign hwif_in.FFC_CTRL.rd_ack = hwif_out.FFC_CTRL.req && !hwif_out.FFC_CTRL.req_is_wr;
  assign hwif_in.FFC_CTRL.wr_ack = ffc_wr;

  if (HasFfc != 0) begin : gen_ffc
    always_ff @(posedge clk_i or negedge rst_ni) begin : p_ffc
      if (!rst_ni) begin
        ffc_frames_q <= RegFfcCtrlFramesBits'(FfcFrames);
        ffc_start_q  <= 1'b0;
        ffc_done_q   <= 1'b0;
      end else begin
        ffc_start_q <= ffc_wr && hwif_out.FFC_CTRL.wr_data.start
                       && hwif_out.FFC_CTRL.wr_biten.start;
        if (ffc_wr) begin
          ffc_frames_q <= (ffc_frames_q & ~hwif_out.FFC_CTRL.wr_biten.frames)
                          | (hwif_out.FFC_CTRL.wr_data.frames & hwif_out.FFC_CTRL.wr_biten.frames);
        end
        if (ffc_done_i) begin
          ffc_done_q <= 1'b1;
        end else if (ffc_start_q) begin
          ffc_done_q <= 1'b0;
        end
      end
    end
  end else begin : gen_no_ffc
    assign ffc_frames_q = '0;
    assign ffc_start_q  = 1'b0;
    assign ffc_done_q   = 1'b0;
  end

  assign hwif_in.FFC_CTRL.rd_data = 32'(ffc_frames_q) << RegFfcCtrlFramesLsb;

  // ---- the FFC request: FFC_PERIOD, FFC_THRESHOLD (external), FFC_TRIGGER, FFC_REF ---------
  // irnuc_ffc_trigger compares, at each frame start, the frames since the last FFC with
  // FFC_PERIOD and |READING - the reading at the last FFC| with FFC_THRESHOLD; a request
  // is IRQ_STATUS.ffc_request. On a build without the FFC the registers are reserved (no
  // flops, read 0) and the cause never rises.
  localparam int unsigned PeriodBits = RegFfcPeriodFramesBits;
  localparam int unsigned ThrBits    = RegFfcThresholdCodesBits;
  localparam int unsigned TrigRdBits = (ReadingRegBits > 0) ? ReadingRegBits : 1;
  logic [PeriodBits-1:0] period_q, trig_since;
  logic [ThrBits-1:0]    thr_q;
  logic [TrigRdBits-1:0] trig_ref;
  logic                  period_wr, thr_wr, trig_period, trig_thr, trig_request;

  assign period_wr = hwif_out.FFC_PERIOD.req && hwif_out.FFC_PERIOD.req_is_wr;
  assign thr_wr    = hwif_out.FFC_THRESHOLD.req && hwif_out.FFC_THRESHOLD.req_is_wr;
  assign hwif_in.FFC_PERIOD.rd_ack    = hwif_out.FFC_PERIOD.req
                                        && !hwif_out.FFC_PERIOD.req_is_wr;
  assign hwif_in.FFC_PERIOD.wr_ack    = period_wr;
  assign hwif_in.FFC_THRESHOLD.rd_ack = hwif_out.FFC_THRESHOLD.req
                                        && !hwif_out.FFC_THRESHOLD.req_is_wr;
  assign hwif_in.FFC_THRESHOLD.wr_ack = thr_wr;

  if (HasFfc != 0) begin : gen_ffc_trigger
    always_ff @(posedge clk_i or negedge rst_ni) begin : p_trigger_regs
      if (!rst_ni) begin
        period_q <= PeriodBits'(RegFfcPeriodFramesReset);
        thr_q    <= ThrBits'(RegFfcThresholdCodesReset);
      end else begin
        if (period_wr) begin
          period_q <= (period_q & ~hwif_out.FFC_PERIOD.wr_biten.frames)
                      | (hwif_out.FFC_PERIOD.wr_data.frames & hwif_out.FFC_PERIOD.wr_biten.frames);
        end
        if (thr_wr) begin
          thr_q <= (thr_q & ~hwif_out.FFC_THRESHOLD.wr_biten.codes)
                   | (hwif_out.FFC_THRESHOLD.wr_data.codes & hwif_out.FFC_THRESHOLD.wr_biten.codes);
        end
      end
    end

    irnuc_ffc_trigger #(
      .PeriodBits   (PeriodBits),
      .ThresholdBits(ThrBits),
      .ReadingBits  (ReadingRegBits)
    ) u_ffc_trigger (
      .clk_i,
      .rst_ni,
      .start_i,
      .ffc_start_i(ffc_start_q),
      .reading_i  (TrigRdBits'(slot_o[SlotReading])),
      .period_i   (period_q),
      .threshold_i(thr_q),
      .since_o    (trig_since),
      .ref_o      (trig_ref),
      .period_o   (trig_period),
      .threshold_o(trig_thr),
      .request_o  (trig_request)
    );
  end else begin : gen_no_ffc_trigger
    assign period_q     = '0;
    assign thr_q        = '0;
    assign trig_since   = '0;
    assign trig_ref     = '0;
    assign trig_period  = 1'b0;
    assign trig_thr     = 1'b0;
    assign trig_request = 1'b0;
  end

  assign hwif_in.FFC_PERIOD.rd_data.frames    = period_q;
  assign hwif_in.FFC_PERIOD.rd_data._reserved_31_24 = '0;
  assign hwif_in.FFC_THRESHOLD.rd_data.codes  = thr_q;
  assign hwif_in.FFC_THRESHOLD.rd_data._reserved_31_24 = '0;
  assign hwif_in.FFC_TRIGGER.since.next       = trig_since;
  assign hwif_in.FFC_TRIGGER.period.next      = trig_period;
  assign hwif_in.FFC_TRIGGER.threshold.next   = trig_thr;
  assign hwif_in.FFC_REF.reading.next         = RegFfcRefReadingBits'(trig_ref);
  assign hwif_in.IRQ_STATUS.ffc_request.next  = trig_request;
  assign hwif_in.FFC_STATUS.busy.next = ffc_busy_i && (HasFfc != 0);
  assign hwif_in.FFC_STATUS.done.next = ffc_done_q;
  assign ffc_start_o  = ffc_start_q;
  assign ffc_frames_o = ffc_frames_q;

  // ---- TABLE_SEL ------------------------------------------------------------------------------
  logic [31:0] table_sel;
  assign table_sel = (TableReadings != 0) ? table_sel_i : '0;
  assign hwif_in.TABLE_SEL.weight.next = table_sel[RegTableSelWeightLsb +: RegTableSelWeightBits];
  assign hwif_in.TABLE_SEL.j.next      = table_sel[RegTableSelJLsb +: RegTableSelJBits];
  assign hwif_in.TABLE_SEL.valid.next  = table_sel[RegTableSelValidLsb];
  assign hwif_in.TABLE_SEL.error.next  = table_sel[RegTableSelErrorLsb];

  // Not used: the FFC_CTRL word's bits outside its fields; table_sel's bits outside TABLE_SEL.
  logic unused_bits;
  assign unused_bits = ^{hwif_out.FFC_CTRL.wr_data, hwif_out.FFC_CTRL.wr_biten, table_sel,
                         hwif_out.FFC_PERIOD.wr_data._reserved_31_24,
                         hwif_out.FFC_PERIOD.wr_biten._reserved_31_24,
                         hwif_out.FFC_THRESHOLD.wr_data._reserved_31_24,
                         hwif_out.FFC_THRESHOLD.wr_biten._reserved_31_24};

`ifndef SYNTHESIS
  // The parameters' ranges and (IRNUC_ASSERT) the external requests: irnuc_axil_regs_check.
  logic [NumTable-1:0] table_req, table_ack;
  for (genvar k = 0; k < NumTable; k++) begin : gen_table_check
    assign table_req[k] = hwif_out.TABLE_READING[k].req;
    assign table_ack[k] = hwif_in.TABLE_READING[k].rd_ack || hwif_in.TABLE_READING[k].wr_ack;
  end
  irnuc_axil_regs_check #(
    .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .WidthBits(WidthBits), .HeightBits(HeightBits),
    .NumSlots(NumSlots), .SlotBits(SlotBits), .TableReadings(TableReadings),
    .TableReadingBits(TableReadingBits), .NumExternal(4 + 2 * NumSlots + NumTable)
  ) u_check (
    .clk_i,
    .rst_ni,
    .ext_req_i ({hwif_out.FRAME_SIZE.req, hwif_out.FFC_CTRL.req, hwif_out.FFC_PERIOD.req,
                 hwif_out.FFC_THRESHOLD.req, slot_req, table_req}),
    .ext_ack_i (hwif_in.FRAME_SIZE.rd_ack || hwif_in.FRAME_SIZE.wr_ack
                || hwif_in.FFC_CTRL.rd_ack || hwif_in.FFC_CTRL.wr_ack
                || hwif_in.FFC_PERIOD.rd_ack || hwif_in.FFC_PERIOD.wr_ack
                || hwif_in.FFC_THRESHOLD.rd_ack || hwif_in.FFC_THRESHOLD.wr_ack
                || |slot_rd_ack || |slot_wr_ack || |table_ack),
    .size_req_i(size_new_q),
    .size_ack_i(hwif_in.FRAME_SIZE.wr_ack)
  );
`endif

endmodule
