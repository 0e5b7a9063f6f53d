// AXI4-Lite register file of irnuc_axis_top: the map of nuc_fixed/registers.toml (offsets,
// fields and resets are the irnuc_pkg constants generated from it; docs/registers.md).
//
// Slave: the write address and data are each taken into a holding register (awready /
// wready = it is empty); when both are held and no response waits, the address is decoded
// into one-hot register selects (a cycle), the write done and its response raised (the next
// cycle) and held until bready. A read address is taken when no read is in progress, decoded
// (a cycle), read through an AND-OR of the selects (a cycle) and held until rready. Every
// output is a flop: the readies are flops of their own, the complements of the holding
// flags the logic reads (each holding register follows its input while empty: no input
// passes an enable). No input-to-output path. One write and one read at a time; reads have
// no side effects.
//
// Responses: OKAY, or SLVERR for an offset outside the map, a write to a register without
// a writable field and a frame size of 0 or above MaxWidth x MaxHeight (the register keeps
// its value). A register of a method or stage that is not built in (method register slot
// of width 0, FFC registers without HasFfc) reads 0 and ignores writes, answered OKAY.
//
// Shadowed registers (CTRL, FRAME_SIZE, the method registers): the framer takes them at a
// frame start (start_i); a write changes the pending value, STATUS.pending is 1 until then,
// and a new frame size raises size_dirty_o (the framer drains the core before using it).
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
  parameter int unsigned TableReadings     = 0,
  parameter int unsigned TableReadingBits  = 1,
  // Derived, do not override.
  localparam int unsigned AddrBits         = RegAddrBits,
  localparam int unsigned WidthBits        = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits       = $clog2(MaxHeight + 1),
  localparam int unsigned NumSlots         = 8,
  localparam int unsigned NumTable         = RegTableReadingCount
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
  // table_interp: READING or a TABLE_READING_k written now; what TABLE_SEL reads.
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

  localparam int unsigned SlotBits [NumSlots] = '{
    GainRegBits, LevelRegBits, ReadingRegBits, TRefRegBits, BlindSumRegBits, BlindRefRegBits,
    DriftGainRegBits, FfcTargetRegBits
  };
  localparam int unsigned SlotOffset [NumSlots] = '{
    RegGainLoOffset, RegLevelLoOffset, RegReadingLoOffset, RegTRefLoOffset,
    RegBlindSumLoOffset, RegBlindRefLoOffset, RegDriftGainLoOffset, RegFfcTargetLoOffset
  };
  localparam int unsigned NumErrors = 6;

  // ---- the map: one index per register word -----------------------------------------------
  localparam int unsigned IxId         = 0;
  localparam int unsigned IxVersion    = 1;
  localparam int unsigned IxConfig     = 2;
  localparam int unsigned IxFormat     = 3;
  localparam int unsigned IxFrameMax   = 4;
  localparam int unsigned IxCtrl       = 5;
  localparam int unsigned IxFrameSize  = 6;
  localparam int unsigned IxCommand    = 7;
  localparam int unsigned IxStatus     = 8;
  localparam int unsigned IxIrqEnable  = 9;
  localparam int unsigned IxIrqStatus  = 10;
  localparam int unsigned IxFramesIn   = 11;
  localparam int unsigned IxFramesOut  = 12;
  localparam int unsigned IxPixelsIn   = 13;
  localparam int unsigned IxPixelsOut  = 14;
  localparam int unsigned IxDropped    = 15;
  localparam int unsigned IxPadded     = 16;
  localparam int unsigned IxSofErrors  = 17;
  localparam int unsigned IxEolErrors  = 18;
  localparam int unsigned IxCoefErrors = 19;
  localparam int unsigned IxFfcCtrl    = 20;
  localparam int unsigned IxFfcStatus  = 21;
  localparam int unsigned IxTableSel   = 22;
  localparam int unsigned NumFixed     = 23;
  localparam int unsigned IxSlot       = NumFixed;              // slot k: LO, HI
  localparam int unsigned IxTable      = IxSlot + 2 * NumSlots;  // table reading k
  localparam int unsigned NumRegs      = IxTable + NumTable;

  localparam int unsigned FixedOffset [NumFixed] = '{
    RegIdOffset, RegVersionOffset, RegConfigOffset, RegFormatOffset, RegFrameMaxOffset,
    RegCtrlOffset, RegFrameSizeOffset, RegCommandOffset, RegStatusOffset, RegIrqEnableOffset,
    RegIrqStatusOffset, RegFramesInOffset, RegFramesOutOffset, RegPixelsInOffset,
    RegPixelsOutOffset, RegDroppedOffset, RegPaddedOffset, RegSofErrorsOffset,
    RegEolErrorsOffset, RegCoefErrorsOffset, RegFfcCtrlOffset, RegFfcStatusOffset,
    RegTableSelOffset
  };

  // The byte offset of register index `ix`.
  function automatic int unsigned reg_offset(input int unsigned ix);
    if (ix < NumFixed) begin
      return FixedOffset[ix];
    end
    if (ix < IxTable) begin
      return SlotOffset[(ix - IxSlot) / 2] + 32'd4 * ((ix - IxSlot) % 2);
    end
    return RegTableReadingOffset + (ix - IxTable) * RegTableReadingStride;
  endfunction

  // Registers a write to is answered SLVERR: no writable field (reserved ones are OKAY).
  function automatic logic [NumRegs-1:0] read_only();
    logic [NumRegs-1:0] ro;
    ro = '0;
    for (int unsigned ix = IxId; ix <= IxFrameMax; ix++) begin
      ro[ix] = 1'b1;
    end
    for (int unsigned ix = IxFramesIn; ix <= IxCoefErrors; ix++) begin
      ro[ix] = 1'b1;
    end
    ro[IxFfcStatus] = (HasFfc != 0);
    ro[IxTableSel]  = (TableReadings != 0);
    return ro;
  endfunction
  localparam logic [NumRegs-1:0] ReadOnly = read_only();

  // The register indices a word address hits (at most one).
  function automatic logic [NumRegs-1:0] decode(input logic [AddrBits-3:0] word);
    logic [NumRegs-1:0] hit;
    for (int unsigned ix = 0; ix < NumRegs; ix++) begin
      hit[ix] = (32'({word, 2'b00}) == reg_offset(ix));
    end
    return hit;
  endfunction

  // ---- write channel: hold address and data, decode (a cycle), write (a cycle) --------------
  logic                aw_held_q, w_held_q, dec_q, b_valid_q;
  logic                aw_held_d, w_held_d;
  logic                aw_ready_q, w_ready_q;  // the ports: !aw_held_q, !w_held_q as flops
  logic [AddrBits-1:0] aw_addr_q;
  logic [31:0]         w_data_q;
  logic [3:0]          w_strb_q;
  axi_resp_e           b_resp_q;
  logic                w_legal_q, h_legal_q;  // the decoded write's width / height is legal
  logic                size_hit_q;  // the decoded write hits FRAME_SIZE's size bits
  logic                table_hit_q;  // ... READING or a TABLE_READING_k (table_interp)
  logic                size_legal;            // both (the write cycle)
  logic                decode_now, wr;
  logic [NumRegs-1:0]  w_hit, wsel_q;
  logic [31:0]         wmask, wdata;  // the decoded write: byte lanes and their data

  assign decode_now = aw_held_q && w_held_q && !dec_q && !b_valid_q;
  assign wr         = dec_q;
  assign w_hit      = decode(aw_addr_q[AddrBits-1:2]);
  // A holding register fills on its valid while empty and empties with the write cycle (it
  // is full then: no transfer in the same cycle).
  assign aw_held_d  = !dec_q && (aw_held_q || s_axil_awvalid_i);
  assign w_held_d   = !dec_q && (w_held_q || s_axil_wvalid_i);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_write_channel
    if (!rst_ni) begin
      aw_held_q  <= 1'b0;
      w_held_q   <= 1'b0;
      aw_ready_q <= 1'b1;
      w_ready_q  <= 1'b1;
      dec_q      <= 1'b0;
      b_valid_q  <= 1'b0;
      b_resp_q   <= AxiOkay;
    end else begin
      aw_held_q  <= aw_held_d;
      w_held_q   <= w_held_d;
      aw_ready_q <= !aw_held_d;
      w_ready_q  <= !w_held_d;
      dec_q      <= decode_now;
      if (dec_q) begin
        b_valid_q <= 1'b1;
        // OKAY for a writable or reserved register, SLVERR for a read-only or unmapped
        // one and for an illegal frame size (from the decode cycle's registers).
        b_resp_q  <= (|(wsel_q & ~ReadOnly) && !(wsel_q[IxFrameSize] && !size_legal))
                     ? AxiOkay : AxiSlvErr;
      end else if (s_axil_bready_i) begin
        b_valid_q <= 1'b0;
      end
    end
  end

  // An empty holding register follows its input (the enable is a flop, not the handshake):
  // it keeps what it had in the cycle it filled.
  always_ff @(posedge clk_i) begin : p_write_payload
    if (!aw_held_q) begin
      aw_addr_q <= s_axil_awaddr_i;
    end
    if (!w_held_q) begin
      w_data_q <= s_axil_wdata_i;
      w_strb_q <= s_axil_wstrb_i;
    end
  end

  assign s_axil_awready_o = aw_ready_q;
  assign s_axil_wready_o  = w_ready_q;
  assign s_axil_bvalid_o  = b_valid_q;
  assign s_axil_bresp_o   = b_resp_q;

  // ---- CTRL and FRAME_SIZE (shadowed) ------------------------------------------------------
  localparam logic [31:0] CtrlMask = (32'd1 << RegCtrlNucEnLsb) | (32'd1 << RegCtrlDpcEnLsb)
                                     | (32'd1 << RegCtrlCoefSyncLsb);
  localparam logic [31:0] WidthField  = ((32'd1 << RegFrameSizeWidthBits) - 32'd1)
                                        << RegFrameSizeWidthLsb;
  localparam logic [31:0] HeightField = ((32'd1 << RegFrameSizeHeightBits) - 32'd1)
                                        << RegFrameSizeHeightLsb;
  localparam logic [31:0] SizeMask    = WidthField | HeightField;
  // The byte lanes of the two fields (each two lanes, checked below).
  localparam int unsigned WLane       = RegFrameSizeWidthLsb / 8;
  localparam int unsigned HLane       = RegFrameSizeHeightLsb / 8;

  logic                  nuc_en_q, dpc_en_q, coef_sync_q;
  logic [WidthBits-1:0]  width_q, width_m1_q, new_w_q;
  logic [HeightBits-1:0] height_q, height_m1_q, new_h_q;
  logic                  width_is1_q, height_is1_q, size_dirty_q, pending_q;
  logic [31:0]           ctrl_view, size_view, ctrl_new, size_new;
  logic [RegFrameSizeWidthBits-1:0]  new_w;  // the fields as written: compared at their
  logic [RegFrameSizeHeightBits-1:0] new_h;  // own width (short carry chains)
  logic                  w_legal, h_legal, wr_ctrl, wr_size, shadow_touch;

  assign ctrl_view  = (32'(nuc_en_q) << RegCtrlNucEnLsb) | (32'(dpc_en_q) << RegCtrlDpcEnLsb)
                      | (32'(coef_sync_q) << RegCtrlCoefSyncLsb);
  assign size_view  = (32'(width_q) << RegFrameSizeWidthLsb)
                      | (32'(height_q) << RegFrameSizeHeightLsb);
  // The frame size the held write would make, and whether it is legal (decode cycle).
  assign size_new   = (size_view & ~axil_byte_mask(w_strb_q))
                      | (w_data_q & axil_byte_mask(w_strb_q));
  assign new_w      = RegFrameSizeWidthBits'(size_new >> RegFrameSizeWidthLsb);
  assign new_h      = RegFrameSizeHeightBits'(size_new >> RegFrameSizeHeightLsb);
  // Legality: each field is two byte lanes, so the compares are made for the four lane
  // choices in parallel, from flops, and the strobes pick one after them (the strobes'
  // fanout no longer precedes the carry chains).
  logic [3:0] w_legal_c, h_legal_c;
  for (genvar c = 0; c < 4; c++) begin : gen_legal
    logic [31:0]                       lanes, size_c;
    logic [RegFrameSizeWidthBits-1:0]  w_c;
    logic [RegFrameSizeHeightBits-1:0] h_c;
    assign lanes = axil_byte_mask(4'((c << WLane) | (c << HLane)));
    assign size_c = (size_view & ~lanes) | (w_data_q & lanes);
    assign w_c = RegFrameSizeWidthBits'(size_c >> RegFrameSizeWidthLsb);
    assign h_c = RegFrameSizeHeightBits'(size_c >> RegFrameSizeHeightLsb);
    assign w_legal_c[c] = (w_c != '0) && (w_c <= RegFrameSizeWidthBits'(MaxWidth));
    assign h_legal_c[c] = (h_c != '0) && (h_c <= RegFrameSizeHeightBits'(MaxHeight));
  end
  assign w_legal    = w_legal_c[w_strb_q[WLane +: 2]];
  assign h_legal    = h_legal_c[w_strb_q[HLane +: 2]];
  logic unused_new;  // the fields' bits above the frame size (a legal size has none)
  assign unused_new = ^{new_w, new_h};

  // The decode cycle: the register hit, the byte lanes, the new frame size and whether its
  // width and its height are legal (two flops: the AND of the two compares is made in the
  // write cycle; the response is made from these in the next cycle).
  always_ff @(posedge clk_i) begin : p_decode
    if (decode_now) begin
      wsel_q       <= w_hit;
      wmask        <= axil_byte_mask(w_strb_q);
      wdata        <= w_data_q & axil_byte_mask(w_strb_q);
      w_legal_q    <= w_legal;
      h_legal_q    <= h_legal;
      new_w_q      <= WidthBits'(new_w);
      new_h_q      <= HeightBits'(new_h);
      size_hit_q   <= w_hit[IxFrameSize] && |(axil_byte_mask(w_strb_q) & SizeMask);
      table_hit_q  <= |w_hit[IxSlot + 4 +: 2] || |w_hit[IxTable +: NumTable];
    end
  end

  assign ctrl_new = (ctrl_view & ~wmask) | (wdata & CtrlMask);
  assign wr_ctrl  = wr && wsel_q[IxCtrl];
  assign size_legal = w_legal_q && h_legal_q;
  assign wr_size  = wr && wsel_q[IxFrameSize] && size_legal;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_settings
    if (!rst_ni) begin
      nuc_en_q     <= 1'(RegCtrlNucEnReset);
      dpc_en_q     <= 1'(RegCtrlDpcEnReset);
      coef_sync_q  <= 1'(RegCtrlCoefSyncReset);
      width_q      <= WidthBits'(MaxWidth);
      width_m1_q   <= WidthBits'(MaxWidth - 1);
      width_is1_q  <= (MaxWidth == 1);
      height_q     <= HeightBits'(MaxHeight);
      height_m1_q  <= HeightBits'(MaxHeight - 1);
      height_is1_q <= (MaxHeight == 1);
    end else begin
      if (wr_ctrl) begin
        nuc_en_q    <= ctrl_new[RegCtrlNucEnLsb];
        dpc_en_q    <= ctrl_new[RegCtrlDpcEnLsb];
        coef_sync_q <= ctrl_new[RegCtrlCoefSyncLsb];
      end
      if (wr_size) begin
        width_q      <= new_w_q;
        width_m1_q   <= new_w_q - WidthBits'(1);  // from the flop: no strobe merge before
        width_is1_q  <= (new_w_q == WidthBits'(1));
        height_q     <= new_h_q;
        height_m1_q  <= new_h_q - HeightBits'(1);
        height_is1_q <= (new_h_q == HeightBits'(1));
      end
    end
  end

  assign width_o      = width_q;
  assign height_o     = height_q;
  assign width_m1_o   = width_m1_q;
  assign height_m1_o  = height_m1_q;
  assign width_is1_o  = width_is1_q;
  assign height_is1_o = height_is1_q;
  assign nuc_en_o     = nuc_en_q;
  assign dpc_en_o     = dpc_en_q;
  assign coef_sync_o  = coef_sync_q;

  // ---- method registers (shadowed) ---------------------------------------------------------
  logic [NumSlots-1:0] slot_touch;
  logic [NumTable-1:0] table_touch;

  for (genvar k = 0; k < NumSlots; k++) begin : gen_slot
    if (SlotBits[k] > 0) begin : gen_on
      localparam int unsigned Bits   = SlotBits[k];
      localparam logic [31:0] LoMask = axil_value_mask(Bits, 0);
      localparam logic [31:0] HiMask = axil_value_mask(Bits, 1);
      logic [Bits-1:0] value_q;
      logic [63:0]     view;
      logic [31:0]     lo, hi;
      logic            wr_lo, wr_hi;

      assign view  = 64'(value_q);
      assign wr_lo = wr && wsel_q[IxSlot + 2 * k];
      assign wr_hi = wr && wsel_q[IxSlot + 2 * k + 1];
      assign lo    = wr_lo ? (view[31:0] & ~wmask) | (wdata & LoMask) : view[31:0];
      assign hi    = wr_hi ? (view[63:32] & ~wmask) | (wdata & HiMask) : view[63:32];
      assign slot_touch[k] = (wr_lo && |(wmask & LoMask)) || (wr_hi && |(wmask & HiMask));

      always_ff @(posedge clk_i or negedge rst_ni) begin : p_value
        if (!rst_ni) begin
          value_q <= '0;
        end else if (wr_lo || wr_hi) begin
          value_q <= Bits'({hi, lo});
        end
      end
      assign slot_o[k] = view;
    end else begin : gen_off
      assign slot_touch[k] = 1'b0;
      assign slot_o[k]     = '0;
    end
  end

  for (genvar k = 0; k < NumTable; k++) begin : gen_table
    if (k < TableReadings) begin : gen_on
      localparam logic [31:0] Mask = axil_value_mask(TableReadingBits, 0);
      logic [TableReadingBits-1:0] value_q;
      logic                        wr_k;

      assign wr_k           = wr && wsel_q[IxTable + k];
      assign table_touch[k] = wr_k && |(wmask & Mask);

      always_ff @(posedge clk_i or negedge rst_ni) begin : p_value
        if (!rst_ni) begin
          value_q <= '0;
        end else if (wr_k) begin
          value_q <= TableReadingBits'(((32'(value_q) & ~wmask) | (wdata & Mask)));
        end
      end
      assign table_o[k] = 32'(value_q);
    end else begin : gen_off
      assign table_touch[k] = 1'b0;
      assign table_o[k]     = '0;
    end
  end

  // A write that changes a shadowed register: pending until the next frame start (a write
  // in the start cycle stays pending: the framer took the value before it).
  assign shadow_touch = (wr_ctrl && |(wmask & CtrlMask)) || (wr_size && |(wmask & SizeMask))
                        || |slot_touch || |table_touch;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_pending
    if (!rst_ni) begin
      pending_q    <= 1'b0;
      size_dirty_q <= 1'b0;
    end else begin
      pending_q    <= shadow_touch || (pending_q && !start_i);
      size_dirty_q <= size_write_o || (size_dirty_q && !start_i);
    end
  end

  assign size_dirty_o = size_dirty_q;
  // From flops in one LUT (the framer's start decision reads both): the register and its
  // byte lanes decoded a cycle early (size_hit_q, table_hit_q), legality, the write cycle.
  assign size_write_o  = wr && size_hit_q && size_legal;
  assign table_write_o = wr && table_hit_q && (TableReadings != 0);

  // ---- STATUS, IRQ ---------------------------------------------------------------------------
  logic [NumErrors-1:0] err_q, err_ev;
  logic [2:0]           irq_en_q, irq_st_q, irq_ev;
  logic                 irq_q;
  logic [31:0]          err_clear, irq_clear;

  assign err_ev    = {coef_late_i, coef_early_i, eol_late_i, eol_early_i, sof_late_i,
                      sof_early_i};
  assign irq_ev    = {ffc_done_i && (HasFfc != 0), frame_out_i, |err_ev};
  assign err_clear = (wr && wsel_q[IxStatus]) ? wdata : '0;
  assign irq_clear = (wr && wsel_q[IxIrqStatus]) ? wdata : '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_status
    if (!rst_ni) begin
      err_q    <= '0;
      irq_en_q <= '0;
      irq_st_q <= '0;
      irq_q    <= 1'b0;
    end else begin
      err_q    <= err_ev | (err_q & ~NumErrors'(err_clear >> RegStatusSofEarlyLsb));
      irq_st_q <= irq_ev | (irq_st_q & ~3'(irq_clear >> RegIrqStatusErrorLsb));
      irq_q    <= |(irq_st_q & irq_en_q);
      if (wr && wsel_q[IxIrqEnable]) begin
        irq_en_q <= 3'((((32'(irq_en_q) << RegIrqEnableErrorLsb) & ~wmask) | wdata)
                       >> RegIrqEnableErrorLsb);
      end
    end
  end

  assign irq_o = irq_q;

  // ---- counters --------------------------------------------------------------------------------
  // Traffic (32 bits, the registers FRAMES_IN .. PADDED in that order) and error causes (16
  // bits, in the order of err_ev: SOF early/late, EOL early/late, COEF early/late); all wrap.
  localparam int unsigned NumTraffic = 6;
  logic                              clear;
  logic [NumTraffic-1:0]             traffic_ev;
  logic [NumTraffic-1:0][31:0]       traffic_q;
  logic [NumErrors-1:0][15:0]        errors_q;

  assign clear      = wr && wsel_q[IxCommand] && wdata[RegCommandClearCountersLsb];
  assign traffic_ev = {pad_i, drop_i, pix_out_i, beat_i, frame_out_i, frame_start_i};

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_counters
    if (!rst_ni) begin
      traffic_q <= '0;
      errors_q  <= '0;
    end else if (clear) begin
      traffic_q <= '0;
      errors_q  <= '0;
    end else begin
      // The event enables the count (+1 from flops), not a carry-in: a stream handshake
      // (pix_out_i is the video output's) then reaches one enable, not a 32-bit carry chain.
      for (int unsigned k = 0; k < NumTraffic; k++) begin
        if (traffic_ev[k]) begin
          traffic_q[k] <= traffic_q[k] + 32'd1;
        end
      end
      for (int unsigned k = 0; k < NumErrors; k++) begin
        if (err_ev[k]) begin
          errors_q[k] <= errors_q[k] + 16'd1;
        end
      end
    end
  end

  // ---- FFC --------------------------------------------------------------------------------------
  logic [RegFfcCtrlFramesBits-1:0] ffc_frames_q;
  logic                            ffc_start_q, ffc_done_q;

  if (HasFfc != 0) begin : gen_ffc
    always_ff @(posedge clk_i or negedge rst_ni) begin : p_ffc
      if (!rst_ni) begin
        ffc_frames_q <= RegFfcCtrlFramesBits'(FfcFrames);
        ffc_start_q  <= 1'b0;
        ffc_done_q   <= 1'b0;
      end else begin
        ffc_start_q <= wr && wsel_q[IxFfcCtrl] && wdata[RegFfcCtrlStartLsb];
        if (wr && wsel_q[IxFfcCtrl]) begin
          ffc_frames_q <= RegFfcCtrlFramesBits'(
            (((32'(ffc_frames_q) << RegFfcCtrlFramesLsb) & ~wmask) | wdata)
            >> RegFfcCtrlFramesLsb);
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

  assign ffc_start_o  = ffc_start_q;
  assign ffc_frames_o = ffc_frames_q;

  // ---- read channel: hold the address, decode (a cycle), read (a cycle) -------------------------
  logic                     ar_held_q, rdec_q, r_valid_q;
  logic                     ar_busy_d, ar_busy_q, ar_ready_q;  // busy: held, decoded or answered
  logic                     r_valid_d;
  logic [AddrBits-1:0]      ar_addr_q;
  logic [NumRegs-1:0]       rsel_q;
  logic [31:0]              r_data_q, rd_data;
  axi_resp_e                r_resp_q;
  logic [NumRegs-1:0][31:0] rvals;

  // A read address is taken when none is held, decoded or answered (busy); arready is a flop
  // of its own, the complement of ar_busy_q, which the logic reads.
  assign r_valid_d = rdec_q || (r_valid_q && !s_axil_rready_i);
  assign ar_busy_d = (s_axil_arvalid_i && !ar_busy_q) || ar_held_q || r_valid_d;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_read_channel
    if (!rst_ni) begin
      ar_held_q  <= 1'b0;
      ar_busy_q  <= 1'b0;
      ar_ready_q <= 1'b1;
      rdec_q     <= 1'b0;
      r_valid_q  <= 1'b0;
      r_resp_q   <= AxiOkay;
    end else begin
      ar_held_q  <= s_axil_arvalid_i && !ar_busy_q;
      ar_busy_q  <= ar_busy_d;
      ar_ready_q <= !ar_busy_d;
      rdec_q     <= ar_held_q;
      r_valid_q  <= r_valid_d;
      if (rdec_q) begin
        r_resp_q <= (|rsel_q) ? AxiOkay : AxiSlvErr;
      end
    end
  end

  // The address register follows the input while no read is in progress (see the write).
  always_ff @(posedge clk_i) begin : p_read_payload
    if (!ar_busy_q) begin
      ar_addr_q <= s_axil_araddr_i;
    end
    if (ar_held_q) begin
      rsel_q <= decode(ar_addr_q[AddrBits-1:2]);
    end
    if (rdec_q) begin
      r_data_q <= rd_data;
    end
  end

  assign s_axil_arready_o = ar_ready_q;
  assign s_axil_rvalid_o  = r_valid_q;
  assign s_axil_rdata_o   = r_data_q;
  assign s_axil_rresp_o   = r_resp_q;

  // What each register reads.
  always_comb begin : p_read_values
    rvals = '0;
    rvals[IxId]      = 32'(RegMapId) << RegIdValueLsb;
    rvals[IxVersion] = (32'(RegMapMinor) << RegVersionMinorLsb)
                       | (32'(RegMapMajor) << RegVersionMajorLsb)
                       | (32'(CoefLayoutVersion) << RegVersionCoefLayoutLsb);
    rvals[IxConfig]  = (32'(AdcBits) << RegConfigAdcBitsLsb)
                       | (32'(OutBits) << RegConfigOutBitsLsb)
                       | (32'(CoefWordBits) << RegConfigWordBitsLsb)
                       | (32'(MethodCode) << RegConfigMethodLsb)
                       | (32'(HasBlindDrift) << RegConfigBlindDriftLsb)
                       | (32'(HasFfc) << RegConfigFfcLsb)
                       | (32'(Rounding) << RegConfigRoundingLsb)
                       | (32'(Overflow) << RegConfigOverflowLsb);
    rvals[IxFormat]  = (32'(GainIntBits) << RegFormatGainIntBitsLsb)
                       | (32'(GainFracBits) << RegFormatGainFracBitsLsb)
                       | (32'(OffsetIntBits) << RegFormatOffsetIntBitsLsb)
                       | (32'(OffsetFracBits) << RegFormatOffsetFracBitsLsb);
    rvals[IxFrameMax] = (32'(MaxWidth) << RegFrameMaxWidthLsb)
                        | (32'(MaxHeight) << RegFrameMaxHeightLsb);
    rvals[IxCtrl]      = ctrl_view;
    rvals[IxFrameSize] = size_view;
    rvals[IxStatus]    = (32'(err_q) << RegStatusSofEarlyLsb)
                         | (32'(core_err_i) << RegStatusCoreErrLsb)
                         | (32'(in_frame_i) << RegStatusInFrameLsb)
                         | (32'(pending_q) << RegStatusPendingLsb);
    rvals[IxIrqEnable]  = 32'(irq_en_q) << RegIrqEnableErrorLsb;
    rvals[IxIrqStatus]  = 32'(irq_st_q) << RegIrqStatusErrorLsb;
    rvals[IxFramesIn]   = traffic_q[0];
    rvals[IxFramesOut]  = traffic_q[1];
    rvals[IxPixelsIn]   = traffic_q[2];
    rvals[IxPixelsOut]  = traffic_q[3];
    rvals[IxDropped]    = traffic_q[4];
    rvals[IxPadded]     = traffic_q[5];
    rvals[IxSofErrors]  = (32'(errors_q[0]) << RegSofErrorsEarlyLsb)
                          | (32'(errors_q[1]) << RegSofErrorsLateLsb);
    rvals[IxEolErrors]  = (32'(errors_q[2]) << RegEolErrorsEarlyLsb)
                          | (32'(errors_q[3]) << RegEolErrorsLateLsb);
    rvals[IxCoefErrors] = (32'(errors_q[4]) << RegCoefErrorsEarlyLsb)
                          | (32'(errors_q[5]) << RegCoefErrorsLateLsb);
    rvals[IxFfcCtrl]    = 32'(ffc_frames_q) << RegFfcCtrlFramesLsb;
    rvals[IxFfcStatus]  = (32'(ffc_busy_i && HasFfc != 0) << RegFfcStatusBusyLsb)
                          | (32'(ffc_done_q) << RegFfcStatusDoneLsb);
    rvals[IxTableSel]   = (TableReadings != 0) ? table_sel_i : '0;
    for (int unsigned k = 0; k < NumSlots; k++) begin
      rvals[IxSlot + 2 * k]     = slot_o[k][31:0];
      rvals[IxSlot + 2 * k + 1] = slot_o[k][63:32];
    end
    for (int unsigned k = 0; k < NumTable; k++) begin
      rvals[IxTable + k] = table_o[k];
    end
  end

  // The selected register's value: an AND-OR of one-hot selects (no address decode here).
  always_comb begin : p_read_mux
    rd_data = '0;
    for (int unsigned ix = 0; ix < NumRegs; ix++) begin
      rd_data |= rvals[ix] & {32{rsel_q[ix]}};
    end
  end

  // Address bits 1:0 select a byte of the word (not used: whole words are read).
  logic unused_addr;
  assign unused_addr = ^{aw_addr_q[1:0], ar_addr_q[1:0]};

`ifndef SYNTHESIS
  // The parameters' ranges and (IRNUC_ASSERT) the ready flops: irnuc_axil_regs_check.
  irnuc_axil_regs_check #(
    .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .WidthBits(WidthBits), .HeightBits(HeightBits),
    .NumSlots(NumSlots), .SlotBits(SlotBits), .TableReadings(TableReadings),
    .TableReadingBits(TableReadingBits)
  ) u_check (
    .clk_i, .rst_ni, .aw_ready_i(aw_ready_q), .aw_held_i(aw_held_q), .w_ready_i(w_ready_q),
    .w_held_i(w_held_q), .ar_ready_i(ar_ready_q), .ar_busy_i(ar_busy_q),
    .ar_held_i(ar_held_q), .rdec_i(rdec_q), .r_valid_i(r_valid_q), .wr_i(wr),
    .size_hit_i(size_hit_q), .size_hit_ref_i(wsel_q[IxFrameSize] && |(wmask & SizeMask))
  );
`endif

endmodule
