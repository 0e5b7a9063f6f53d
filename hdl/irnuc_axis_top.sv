// The NUC + DPC core with the interfaces a video system integrates (docs/integration.md):
//   s_axis_video  raw pixels, AXI4-Stream video (UG934): tuser[0] start of frame, tlast
//                 end of line; the code in tdata[AdcBits-1:0], the bits above ignored
//   s_axis_coef   coefficient words, one per pixel in raster order, as a DMA reads the
//                 memory image of irnuc calibrate: word in tdata[WordBits-1:0] (the image's
//                 bytes of one word, little-endian), tlast on each frame's last word; the
//                 word of the configured method (method_dpc_top's s_coef: its calibration
//                 memories concatenated, the first at bit 0)
//   m_axis_video  corrected pixels, AXI4-Stream video; the code in tdata[OutBits-1:0], the
//                 bits above 0
//   s_axis_foff, s_axis_acc, m_axis_acc, m_axis_foff
//                 (Ffc = 1) the FFC offsets and the accumulator in and their new values
//                 out (method_ffc_top's s_foff, s_acc, m_acc, m_foff): one word per pixel
//                 in raster order in the frames that carry them, the word in the low bits
//                 of tdata, tlast on each frame's last word (out; ignored in); with Ffc = 0
//                 the inputs are never ready and the outputs never valid (8-bit tdata)
//   s_axil        the register file (docs/registers.md), irq_o its interrupt
// One clock, one asynchronous active-low reset (release it synchronously: a reset
// synchronizer or the system's reset block). AXI port names follow the AXI specification
// (the prefix finds the interface in Vivado, LiteX and cocotbext-axi), the others the
// lowRISC style of the rest of the RTL.
//
//   s_axis_video -> u_vid_in --\
//                               u_framer (frames, markers, join, enables) -> u_core -> m_axis_video
//   s_axis_coef  -> u_coef_in --/        ^ pending settings, events v   (irnuc_axis_core)
//   s_axil <-> u_regs (register file, counters, interrupt)
//
// u_core (irnuc_axis_core) holds the core: method_ffc_top with Ffc = 1 (one_point,
// two_point, quadratic or tc_offset with the shutter offset refresh) inside irnuc_axis_ffc
// (the shutter flag of each frame from FFC_CTRL, the fork, the FFC streams),
// method_drift_top with Drift = 1 (one_point or two_point after the blind drift), else
// nuc_dpc_top for two_point (Method = 1) and method_dpc_top for one_point, piecewise,
// quadratic, tc_offset and table_interp, whose two input streams move in lockstep (one item
// of the framer is a pixel and its word). A method's per-frame word comes from its registers
// (GAIN, LEVEL, READING and T_REF; table_interp's weight from READING and TABLE_READING_k,
// irnuc_axis_table, TABLE_SEL; BLIND_SUM, BLIND_REF and DRIFT_GAIN with Drift), taken at a
// frame start like every shadowed register.
// Every output port is a flop.
module irnuc_axis_top
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  // irnuc-params: begin irnuc_axis_top (generated from nuc_fixed.methods; do not edit)
  // the base method (irnuc_pkg::method_e)
  parameter method_e                  Method                = MethodTwoPoint,
  parameter int unsigned              AdcBits               = 14,
  parameter int unsigned              GainIntBits           = 2,
  parameter int unsigned              GainFracBits          = 14,
  parameter int unsigned              OffsetIntBits         = 12,
  parameter int unsigned              OffsetFracBits        = 4,
  parameter int unsigned              OutBits               = 14,
  parameter int unsigned              Rounding              = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned              Overflow              = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned              MaxWidth              = 1024,
  parameter int unsigned              MaxHeight             = 1024,
  parameter int unsigned              KneeIntBits           = 14,
  parameter int unsigned              KneeFracBits          = 2,
  parameter int unsigned              LevelIntBits          = 14,
  parameter int unsigned              LevelFracBits         = 4,
  parameter int unsigned              QuadIntBits           = 10,
  parameter int unsigned              QuadFracBits          = 6,
  // bits the square of a raw code is truncated to
  parameter int unsigned              SquareBits            = 18,
  // bits of the FPA sensor's reading
  parameter int unsigned              ReadingBits           = 14,
  parameter int unsigned              Tc1IntBits            = 13,
  parameter int unsigned              Tc1FracBits           = 3,
  parameter int unsigned              Tc2IntBits            = 12,
  parameter int unsigned              Tc2FracBits           = 4,
  parameter int unsigned              Tg1IntBits            = 2,
  parameter int unsigned              Tg1FracBits           = 14,
  parameter int unsigned              Tg2IntBits            = 2,
  parameter int unsigned              Tg2FracBits           = 14,
  parameter int unsigned              TcOrder               = 2,  // order of the polynomials
  parameter bit                       TcGain                = 1'b0,  // the gain is a polynomial too
  parameter int unsigned              ReadingRangeBits      = 11,  // Ts: v = (t - t_ref) / 2^Ts
  parameter int unsigned              WeightIntBits         = 1,
  parameter int unsigned              WeightFracBits        = 15,
  parameter int unsigned              WeightRounding        = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned              Tables                = 3,  // K, the tables
  // bits of the housing sensor's reading
  parameter int unsigned              HousingBits           = 14,
  parameter int unsigned              Th1IntBits            = 15,
  parameter int unsigned              Th1FracBits           = 3,
  parameter int unsigned              ThxIntBits            = 14,
  parameter int unsigned              ThxFracBits           = 4,
  parameter int unsigned              Th2IntBits            = 12,
  parameter int unsigned              Th2FracBits           = 4,
  parameter int unsigned              HousingRangeBits      = 11,  // Hs: w' = (h - h_ref) / 2^Hs
  parameter int unsigned              DriftIntBits          = 14,
  parameter int unsigned              DriftFracBits         = 2,
  parameter int unsigned              DriftRounding         = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned              DriftOverflow         = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned              DriftGainIntBits      = 1,
  parameter int unsigned              DriftGainFracBits     = 24,
  // the most blind pixels a frame has
  parameter int unsigned              BlindMax              = 8192,
  // 1: the core is method_drift_top
  parameter bit                       Drift                 = 1'b0,
  parameter int unsigned              FfcIntBits            = 12,
  parameter int unsigned              FfcFracBits           = 4,
  parameter int unsigned              FfcRounding           = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned              FfcOverflow           = 0,  // irnuc_pkg::overflow_e
  // N, the shutter frames of a refresh (a power of two)
  parameter int unsigned              FfcFrames             = 8,
  // what the output shows during the shutter frames
  parameter bit                       FfcHold               = 1'b1,
  // 1: the core is method_ffc_top
  parameter bit                       Ffc                   = 1'b0,
  // Derived, do not override.
  localparam int unsigned              GainBits              = GainIntBits + GainFracBits,
  localparam int unsigned              OffsetBits            = OffsetIntBits + OffsetFracBits,
  localparam int unsigned              KneeBits              = KneeIntBits + KneeFracBits,
  localparam int unsigned              LevelBits             = LevelIntBits + LevelFracBits,
  localparam int unsigned              QuadBits              = QuadIntBits + QuadFracBits,
  localparam int unsigned              TcWordBits            = Tc1IntBits + Tc1FracBits
                                                               + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned              TgWordBits            = (TcGain != 0) ? Tg1IntBits
                                                               + Tg1FracBits
                                                               + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0) : 0,
  localparam int unsigned              ThWordBits            = Th1IntBits + Th1FracBits + ThxIntBits
                                                               + ThxFracBits + Th2IntBits
                                                               + Th2FracBits,
  localparam int unsigned              WeightBits            = WeightIntBits + WeightFracBits,
  localparam int unsigned              WordBits              = coef_stream_bits(Method, OffsetBits,
                                                                                GainBits, KneeBits,
                                                                                QuadBits,
                                                                                TcWordBits,
                                                                                TgWordBits,
                                                                                ThWordBits),
  localparam int unsigned              BaseFrameBits         = frame_word_bits(Method, GainBits,
                                                                               LevelBits,
                                                                               ReadingBits,
                                                                               WeightBits,
                                                                               HousingBits),
  localparam int unsigned              WidthBits             = $clog2(MaxWidth + 1),
  localparam int unsigned              HeightBits            = $clog2(MaxHeight + 1),
  localparam int unsigned              BlindBits             = blind_sum_bits(AdcBits, BlindMax),
  localparam int unsigned              DriftGainBits         = DriftGainIntBits + DriftGainFracBits,
  localparam int unsigned              ReadingRegBits        = (Method == MethodTcOffset || Method == MethodTableInterp || Method == MethodTcHousing) ? ReadingBits : 0,
  localparam int unsigned              HousingReadingRegBits = (Method == MethodTcHousing) ? HousingBits : 0,
  localparam int unsigned              GainRegBits           = (Method == MethodOnePoint) ? GainBits : 0,
  localparam int unsigned              LevelRegBits          = (Method == MethodPiecewise) ? LevelBits : 0,
  localparam int unsigned              TRefRegBits           = (Method == MethodTcOffset || Method == MethodTcHousing) ? ReadingBits : 0,
  localparam int unsigned              TableReadingBits      = (Method == MethodTableInterp) ? ReadingBits : 1,
  localparam int unsigned              TableReadings         = (Method == MethodTableInterp) ? Tables : 0,
  localparam int unsigned              HRefRegBits           = (Method == MethodTcHousing) ? HousingBits : 0,
  localparam int unsigned              BlindSumRegBits       = (Drift) ? BlindBits : 0,
  localparam int unsigned              BlindRefRegBits       = (Drift) ? BlindBits : 0,
  localparam int unsigned              DriftGainRegBits      = (Drift) ? DriftGainBits : 0,
  localparam int unsigned              FfcTargetRegBits      = (Ffc) ? OutBits + FfcFracBits : 0,
  localparam logic [WordBits-1:0]      NeutralWord           = WordBits'(neutral_stream_word(Method, GainIntBits, GainFracBits, OffsetBits, GainBits, KneeBits, QuadBits, TcWordBits, TgWordBits, ThWordBits)),
  localparam logic [WordBits-1:0]      BadMask               = WordBits'(stream_bad_mask(Method, OffsetBits, GainBits, KneeBits, QuadBits, TcWordBits, TgWordBits, ThWordBits)),
  localparam logic [BaseFrameBits-1:0] NeutralBaseFrame      = BaseFrameBits'(neutral_frame_word(Method, GainIntBits, GainFracBits, GainBits, LevelBits, ReadingBits, WeightBits, HousingBits)),
  // irnuc-params: end
  localparam int unsigned FrameBits     = (Drift != 0)
                                          ? frame_blind_drift_bits(BaseFrameBits, BlindBits,
                                                                   DriftGainBits)
                                          : BaseFrameBits,
  // AXI4-Stream data are whole bytes.
  localparam int unsigned VidInBits     = 8 * ((AdcBits + 7) / 8),
  localparam int unsigned VidOutBits    = 8 * ((OutBits + 7) / 8),
  localparam int unsigned CoefBits      = 8 * ((WordBits + 7) / 8),
  localparam int unsigned AddrBits      = RegAddrBits,
  // The FFC words (memories ffc_offset and ffc_acc) and their AXI4-Stream widths.
  localparam int unsigned FoffWordBits  = FfcIntBits + FfcFracBits,
  localparam int unsigned AccWordBits   = AdcBits + $clog2(FfcFrames),
  // Without the stage the ports stay, one byte wide (a top-level port is a pin in an
  // FPGA flow: the widest method words already use most of a package's pins).
  localparam int unsigned FoffBits      = (Ffc != 0) ? 8 * ((FoffWordBits + 7) / 8) : 8,
  localparam int unsigned AccBits       = (Ffc != 0) ? 8 * ((AccWordBits + 7) / 8) : 8,
  // The framer's frame word: the method's, and the shutter flag above it (Ffc).
  localparam int unsigned ItemFrameBits = FrameBits + ((Ffc != 0) ? 1 : 0)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Raw video in.
  input  logic [VidInBits-1:0]  s_axis_video_tdata,
  input  logic                  s_axis_video_tvalid,
  output logic                  s_axis_video_tready,
  input  logic                  s_axis_video_tlast,
  input  logic [0:0]            s_axis_video_tuser,
  // Coefficient words in.
  input  logic [CoefBits-1:0]   s_axis_coef_tdata,
  input  logic                  s_axis_coef_tvalid,
  output logic                  s_axis_coef_tready,
  input  logic                  s_axis_coef_tlast,
  // Corrected video out.
  output logic [VidOutBits-1:0] m_axis_video_tdata,
  output logic                  m_axis_video_tvalid,
  input  logic                  m_axis_video_tready,
  output logic                  m_axis_video_tlast,
  output logic [0:0]            m_axis_video_tuser,
  // FFC offsets in (every frame) and the accumulator in (the frames that add to it and
  // the refresh frame).
  input  logic [FoffBits-1:0]   s_axis_foff_tdata,
  input  logic                  s_axis_foff_tvalid,
  output logic                  s_axis_foff_tready,
  input  logic                  s_axis_foff_tlast,
  input  logic [AccBits-1:0]    s_axis_acc_tdata,
  input  logic                  s_axis_acc_tvalid,
  output logic                  s_axis_acc_tready,
  input  logic                  s_axis_acc_tlast,
  // The new accumulator (the shutter frames of a run, up to FfcFrames) and the new FFC
  // offsets (the refresh frame) out.
  output logic [AccBits-1:0]    m_axis_acc_tdata,
  output logic                  m_axis_acc_tvalid,
  input  logic                  m_axis_acc_tready,
  output logic                  m_axis_acc_tlast,
  output logic [FoffBits-1:0]   m_axis_foff_tdata,
  output logic                  m_axis_foff_tvalid,
  input  logic                  m_axis_foff_tready,
  output logic                  m_axis_foff_tlast,
  // Registers.
  input  logic [AddrBits-1:0]   s_axil_awaddr,
  input  logic [2:0]            s_axil_awprot,
  input  logic                  s_axil_awvalid,
  output logic                  s_axil_awready,
  input  logic [31:0]           s_axil_wdata,
  input  logic [3:0]            s_axil_wstrb,
  input  logic                  s_axil_wvalid,
  output logic                  s_axil_wready,
  output logic [1:0]            s_axil_bresp,
  output logic                  s_axil_bvalid,
  input  logic                  s_axil_bready,
  input  logic [AddrBits-1:0]   s_axil_araddr,
  input  logic [2:0]            s_axil_arprot,
  input  logic                  s_axil_arvalid,
  output logic                  s_axil_arready,
  output logic [31:0]           s_axil_rdata,
  output logic [1:0]            s_axil_rresp,
  output logic                  s_axil_rvalid,
  input  logic                  s_axil_rready,
  // Interrupt (level, active high): framing errors, frame done, FFC done, as enabled.
  output logic                  irq_o
);

  // The method's neutral frame word (NUC off; its neutral words are the header's).
  localparam logic [FrameBits-1:0] NeutralFrame = FrameBits'(NeutralBaseFrame);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (!Ffc || ffc_composes(Method))
      else $fatal(1, "irnuc_axis_top: Ffc = 1 composes the methods of ffc_composes, not %0d",
                  Method);
    assert (!Drift || (!Ffc && blind_drift_composes(Method)))
      else $fatal(1, "irnuc_axis_top: Drift = 1 composes the methods of blind_drift_composes, %s",
                  "without Ffc");
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax)
      else $fatal(1, "irnuc_axis_top: MaxWidth = %0d outside %0d..%0d", MaxWidth, MaxWidthMin,
                  MaxWidthMax);
    assert (MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "irnuc_axis_top: MaxHeight = %0d outside %0d..%0d", MaxHeight,
                  MaxHeightMin, MaxHeightMax);
  end
`endif

  // ---- input registers -------------------------------------------------------------------
  logic               vid_valid, vid_ready, vid_sof, vid_eol;
  logic [AdcBits-1:0] vid_data;
  logic               coef_valid, coef_ready, coef_last;
  logic [WordBits-1:0] coef_data;

  // Each input behind irnuc_axis_buffer: the framer's take decisions move only its
  // pointers and flags, not the enables of its data registers (docs/rtl.md); the markers
  // the framer decides on (tuser, tlast) come from the buffers' head registers.
  irnuc_axis_buffer #(.DataBits(AdcBits + 2), .HeadBits(2)) u_vid_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_axis_video_tvalid),
    .ready_o(s_axis_video_tready),
    .data_i ({s_axis_video_tuser[0], s_axis_video_tlast, s_axis_video_tdata[AdcBits-1:0]}),
    .valid_o(vid_valid),
    .ready_i(vid_ready),
    .data_o ({vid_sof, vid_eol, vid_data})
  );

  irnuc_axis_buffer #(.DataBits(WordBits + 1), .HeadBits(1)) u_coef_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_axis_coef_tvalid),
    .ready_o(s_axis_coef_tready),
    .data_i ({s_axis_coef_tlast, s_axis_coef_tdata[WordBits-1:0]}),
    .valid_o(coef_valid),
    .ready_i(coef_ready),
    .data_o ({coef_last, coef_data})
  );

  // ---- register file -----------------------------------------------------------------------
  logic [WidthBits-1:0]  pend_w, pend_wm1, act_w, act_wm1;
  logic [HeightBits-1:0] pend_h, pend_hm1, act_h, act_hm1;
  logic                  pend_w_is1, pend_h_is1, size_dirty, size_write, pend_nuc, pend_dpc;
  logic                  pend_sync;
  logic [RegSlotCount-1:0][63:0] slots;
  logic [RegTableReadingCount-1:0][31:0] table_readings;
  logic                  table_write, frame_hold;  // table_interp: irnuc_axis_table
  logic [31:0]           table_sel;
  logic                  start, frame_start, beat, drop, pad, in_frame;
  logic                  sof_early, sof_late, eol_early, eol_late, coef_early, coef_late;
  logic                  pix_out, frame_out, core_err;
  logic [1:0]            core_out;  // items that left the core (output, and one of a held frame)
  logic                  wb_busy;   // FFC write-back words owed: the drain waits for them
  logic                  ffc_start, ffc_busy, ffc_done;
  logic [RegFfcCtrlFramesBits-1:0] ffc_frames;

  irnuc_axil_regs #(
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .OutBits       (OutBits),
    .Rounding      (Rounding),
    .Overflow      (Overflow),
    .MaxWidth      (MaxWidth),
    .MaxHeight     (MaxHeight),
    .MethodCode    (32'(Method)),
    // The memory image version of irnuc calibrate: 1 the plain two_point, 2 the other
    // methods (nuc_fixed.memimage; VERSION is checked against it by tb_axis).
    .CoefLayoutVersion((method_plain(Method) && !Ffc && !Drift) ? 1 : 2),
    .CoefWordBits  (WordBits),
    // The method's register slots (the header's, from the registry's RegisterSlot).
    .GainRegBits     (GainRegBits),
    .LevelRegBits    (LevelRegBits),
    .ReadingRegBits  (ReadingRegBits),
    .TRefRegBits     (TRefRegBits),
    .BlindSumRegBits (BlindSumRegBits),
    .BlindRefRegBits (BlindRefRegBits),
    .DriftGainRegBits(DriftGainRegBits),
    .HasBlindDrift   (32'(Drift)),
    .HasFfc          (32'(Ffc)),
    .FfcFrames       (FfcFrames),
    .FfcTargetRegBits(FfcTargetRegBits),
    .HousingReadingRegBits(HousingReadingRegBits),
    .HRefRegBits     (HRefRegBits),
    .TableReadings   (TableReadings),
    .TableReadingBits(TableReadingBits)
  ) u_regs (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .s_axil_awaddr_i (s_axil_awaddr),
    .s_axil_awvalid_i(s_axil_awvalid),
    .s_axil_awready_o(s_axil_awready),
    .s_axil_wdata_i  (s_axil_wdata),
    .s_axil_wstrb_i  (s_axil_wstrb),
    .s_axil_wvalid_i (s_axil_wvalid),
    .s_axil_wready_o (s_axil_wready),
    .s_axil_bresp_o  (s_axil_bresp),
    .s_axil_bvalid_o (s_axil_bvalid),
    .s_axil_bready_i (s_axil_bready),
    .s_axil_araddr_i (s_axil_araddr),
    .s_axil_arvalid_i(s_axil_arvalid),
    .s_axil_arready_o(s_axil_arready),
    .s_axil_rdata_o  (s_axil_rdata),
    .s_axil_rresp_o  (s_axil_rresp),
    .s_axil_rvalid_o (s_axil_rvalid),
    .s_axil_rready_i (s_axil_rready),
    .width_o         (pend_w),
    .height_o        (pend_h),
    .width_m1_o      (pend_wm1),
    .height_m1_o     (pend_hm1),
    .width_is1_o     (pend_w_is1),
    .height_is1_o    (pend_h_is1),
    .size_dirty_o    (size_dirty),
    .size_write_o    (size_write),
    .nuc_en_o        (pend_nuc),
    .dpc_en_o        (pend_dpc),
    .coef_sync_o     (pend_sync),
    .slot_o          (slots),
    .table_o         (table_readings),
    .table_write_o   (table_write),
    .table_sel_i     (table_sel),
    .start_i         (start),
    .frame_start_i   (frame_start),
    .beat_i          (beat),
    .drop_i          (drop),
    .pad_i           (pad),
    .pix_out_i       (pix_out),
    .frame_out_i     (frame_out),
    .sof_early_i     (sof_early),
    .sof_late_i      (sof_late),
    .eol_early_i     (eol_early),
    .eol_late_i      (eol_late),
    .coef_early_i    (coef_early),
    .coef_late_i     (coef_late),
    .in_frame_i      (in_frame),
    .core_err_i      (core_err),
    .ffc_start_o     (ffc_start),
    .ffc_frames_o    (ffc_frames),
    .ffc_busy_i      (ffc_busy),
    .ffc_done_i      (ffc_done),
    .irq_o           (irq_o)
  );

  // ---- the frame word: the method's registers (slots of irnuc_axil_regs) --------------------
  // one_point GAIN, piecewise LEVEL, tc_offset {T_REF, READING} (frame_tc_offset),
  // table_interp the weight of READING between TABLE_READING_j and _j+1 (irnuc_axis_table,
  // which holds the frame start while it computes it); none for two_point and quadratic;
  // with Drift {DRIFT_GAIN, BLIND_REF, BLIND_SUM} above it (frame_blind_drift). The framer
  // takes it at a frame start.
  logic [BaseFrameBits-1:0] base_frame;
  logic [FrameBits-1:0]     pend_frame;

  // table_interp's weight: irnuc_axis_table computes it from READING and TABLE_READING_k
  // (and holds the frame start while it does), TABLE_SEL.
  logic [WeightFracBits:0] frame_weight;

  if (Method == MethodTableInterp) begin : gen_table
    irnuc_axis_table #(
      // irnuc-params: forward irnuc_axis_table (generated from nuc_fixed.methods; do not edit)
      .ReadingBits    (ReadingBits),
      .Tables         (Tables),
      .WeightFracBits (WeightFracBits),
      .WeightRounding (WeightRounding)
      // irnuc-params: end
    ) u_table (
      .clk_i           (clk_i),
      .rst_ni          (rst_ni),
      .write_i         (table_write),
      .reading_i       (slots[2][ReadingBits-1:0]),
      .table_readings_i(table_readings),
      .hold_o          (frame_hold),
      .start_i         (start),
      .weight_o        (frame_weight),
      .table_sel_o     (table_sel)
    );
  end else begin : gen_no_table
    assign frame_weight = '0;
    assign frame_hold   = 1'b0;
    assign table_sel    = '0;
    logic unused_table_write;
    assign unused_table_write = ^{table_write, frame_weight};
  end

  // irnuc-params: frame (generated from nuc_fixed.methods; do not edit)
  if (Method == MethodOnePoint) begin : gen_frame_one_point
    assign base_frame = BaseFrameBits'(slots[0][GainBits-1:0]);
  end else if (Method == MethodPiecewise) begin : gen_frame_piecewise
    assign base_frame = BaseFrameBits'(slots[1][LevelBits-1:0]);
  end else if (Method == MethodTcOffset) begin : gen_frame_tc_offset
    frame_tc_offset#(ReadingBits)::word_t part0;
    assign part0.reading = slots[2][ReadingBits-1:0];
    assign part0.t_ref = slots[3][ReadingBits-1:0];
    assign base_frame = BaseFrameBits'(part0);
  end else if (Method == MethodTableInterp) begin : gen_frame_table_interp
    assign base_frame = BaseFrameBits'(frame_weight);
  end else if (Method == MethodTcHousing) begin : gen_frame_tc_housing
    frame_tc_housing#(ReadingBits, HousingBits)::word_t part0;
    assign part0.reading = slots[2][ReadingBits-1:0];
    assign part0.t_ref = slots[3][ReadingBits-1:0];
    assign part0.housing_reading = slots[8][HousingBits-1:0];
    assign part0.h_ref = slots[9][HousingBits-1:0];
    assign base_frame = BaseFrameBits'(part0);
  end else begin : gen_frame_none
    assign base_frame = '0;
  end
  // irnuc-params: end

  if (Drift != 0) begin : gen_frame_drift
    frame_blind_drift#(BaseFrameBits, BlindBits, DriftGainBits)::word_t fw;
    assign fw.base       = base_frame;
    assign fw.blind_sum  = slots[4][BlindBits-1:0];
    assign fw.blind_ref  = slots[5][BlindBits-1:0];
    assign fw.drift_gain = slots[6][DriftGainBits-1:0];
    assign pend_frame    = fw;
  end else begin : gen_frame_base
    assign pend_frame = base_frame;
  end

  // The framer's frame word: the method's, the shutter flag above it with Ffc (FFC_CTRL,
  // irnuc_axis_ffc); NUC off sends the neutral frame word, flag 0.
  logic [ItemFrameBits-1:0] pend_item_frame;
  localparam logic [ItemFrameBits-1:0] NeutralItemFrame = ItemFrameBits'(NeutralFrame);

  // ---- framer ---------------------------------------------------------------------------------
  logic                     item_valid, item_ready, item_sof, item_eol;
  logic [AdcBits-1:0]       item_raw;
  logic [WordBits-1:0]      item_word;
  logic [ItemFrameBits-1:0] item_frame;

  irnuc_axis_framer #(
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .MaxWidth      (MaxWidth),
    .MaxHeight     (MaxHeight),
    .FrameBits     (ItemFrameBits),
    .WordBits      (WordBits),
    .NeutralWord   (NeutralWord),
    .BadMask       (BadMask),
    .NeutralFrame  (NeutralItemFrame)
  ) u_framer (
    .clk_i            (clk_i),
    .rst_ni           (rst_ni),
    .vid_valid_i      (vid_valid),
    .vid_ready_o      (vid_ready),
    .vid_data_i       (vid_data),
    .vid_sof_i        (vid_sof),
    .vid_eol_i        (vid_eol),
    .coef_valid_i     (coef_valid),
    .coef_ready_o     (coef_ready),
    .coef_data_i      (coef_data),
    .coef_last_i      (coef_last),
    .coef_in_valid_i  (s_axis_coef_tvalid),
    .coef_in_ready_i  (s_axis_coef_tready),
    .vid_in_valid_i   (s_axis_video_tvalid),
    .vid_in_ready_i   (s_axis_video_tready),
    .vid_in_sof_i     (s_axis_video_tuser[0]),
    .pend_width_i     (pend_w),
    .pend_height_i    (pend_h),
    .pend_width_m1_i  (pend_wm1),
    .pend_height_m1_i (pend_hm1),
    .pend_width_is1_i (pend_w_is1),
    .pend_height_is1_i(pend_h_is1),
    .size_dirty_i     (size_dirty),
    .size_write_i     (size_write),
    .pend_nuc_en_i    (pend_nuc),
    .pend_dpc_en_i    (pend_dpc),
    .pend_coef_sync_i (pend_sync),
    .pend_frame_i     (pend_item_frame),
    .hold_i           (frame_hold),
    .act_width_o      (act_w),
    .act_width_m1_o   (act_wm1),
    .act_height_o     (act_h),
    .act_height_m1_o  (act_hm1),
    .m_valid_o        (item_valid),
    .m_ready_i        (item_ready),
    .m_raw_o          (item_raw),
    .m_word_o         (item_word),
    .m_sof_o          (item_sof),
    .m_eol_o          (item_eol),
    .m_frame_o        (item_frame),
    .core_out_i       (core_out),
    .wb_busy_i        (wb_busy),
    .start_o          (start),
    .frame_start_o    (frame_start),
    .beat_o           (beat),
    .drop_o           (drop),
    .pad_o            (pad),
    .sof_early_o      (sof_early),
    .sof_late_o       (sof_late),
    .eol_early_o      (eol_early),
    .eol_late_o       (eol_late),
    .coef_early_o     (coef_early),
    .coef_late_o      (coef_late),
    .in_frame_o       (in_frame)
  );

  // ---- the core (irnuc_axis_core: the core of the method, the FFC side with Ffc) ------------
  logic               core_valid, core_sof, core_eol;
  logic [OutBits-1:0] core_data;

  irnuc_axis_core #(

    // irnuc-params: forward irnuc_axis_core (generated from nuc_fixed.methods; do not edit)
    .Method            (Method),
    .AdcBits           (AdcBits),
    .GainIntBits       (GainIntBits),
    .GainFracBits      (GainFracBits),
    .OffsetIntBits     (OffsetIntBits),
    .OffsetFracBits    (OffsetFracBits),
    .OutBits           (OutBits),
    .Rounding          (Rounding),
    .Overflow          (Overflow),
    .MaxWidth          (MaxWidth),
    .MaxHeight         (MaxHeight),
    .KneeIntBits       (KneeIntBits),
    .KneeFracBits      (KneeFracBits),
    .LevelIntBits      (LevelIntBits),
    .LevelFracBits     (LevelFracBits),
    .QuadIntBits       (QuadIntBits),
    .QuadFracBits      (QuadFracBits),
    .SquareBits        (SquareBits),
    .ReadingBits       (ReadingBits),
    .Tc1IntBits        (Tc1IntBits),
    .Tc1FracBits       (Tc1FracBits),
    .Tc2IntBits        (Tc2IntBits),
    .Tc2FracBits       (Tc2FracBits),
    .Tg1IntBits        (Tg1IntBits),
    .Tg1FracBits       (Tg1FracBits),
    .Tg2IntBits        (Tg2IntBits),
    .Tg2FracBits       (Tg2FracBits),
    .TcOrder           (TcOrder),
    .TcGain            (TcGain),
    .ReadingRangeBits  (ReadingRangeBits),
    .WeightIntBits     (WeightIntBits),
    .WeightFracBits    (WeightFracBits),
    .WeightRounding    (WeightRounding),
    .HousingBits       (HousingBits),
    .Th1IntBits        (Th1IntBits),
    .Th1FracBits       (Th1FracBits),
    .ThxIntBits        (ThxIntBits),
    .ThxFracBits       (ThxFracBits),
    .Th2IntBits        (Th2IntBits),
    .Th2FracBits       (Th2FracBits),
    .HousingRangeBits  (HousingRangeBits),
    .DriftIntBits      (DriftIntBits),
    .DriftFracBits     (DriftFracBits),
    .DriftRounding     (DriftRounding),
    .DriftOverflow     (DriftOverflow),
    .DriftGainIntBits  (DriftGainIntBits),
    .DriftGainFracBits (DriftGainFracBits),
    .BlindMax          (BlindMax),
    .Drift             (Drift),
    .FfcIntBits        (FfcIntBits),
    .FfcFracBits       (FfcFracBits),
    .FfcRounding       (FfcRounding),
    .FfcOverflow       (FfcOverflow),
    .FfcFrames         (FfcFrames),
    .FfcHold           (FfcHold),
    .Ffc               (Ffc)
    // irnuc-params: end
  ) u_core (
    .clk_i             (clk_i),
    .rst_ni            (rst_ni),
    .act_w_i           (act_w),
    .act_wm1_i         (act_wm1),
    .act_h_i           (act_h),
    .act_hm1_i         (act_hm1),
    .pend_frame_i      (pend_frame),
    .pend_item_frame_o (pend_item_frame),
    .start_i           (start),
    .ffc_start_i       (ffc_start),
    .ffc_frames_i      (ffc_frames),
    .ffc_busy_o        (ffc_busy),
    .ffc_done_o        (ffc_done),
    .item_valid_i      (item_valid),
    .item_ready_o      (item_ready),
    .item_raw_i        (item_raw),
    .item_word_i       (item_word),
    .item_sof_i        (item_sof),
    .item_eol_i        (item_eol),
    .item_frame_i      (item_frame),
    .m_valid_o         (core_valid),
    .m_ready_i         (m_axis_video_tready),
    .m_data_o          (core_data),
    .m_sof_o           (core_sof),
    .m_eol_o           (core_eol),
    .core_out_o        (core_out),
    .wb_busy_o         (wb_busy),
    .frame_err_o       (core_err),
    .s_axis_foff_tdata (s_axis_foff_tdata),
    .s_axis_foff_tvalid(s_axis_foff_tvalid),
    .s_axis_foff_tready(s_axis_foff_tready),
    .s_axis_foff_tlast (s_axis_foff_tlast),
    .s_axis_acc_tdata  (s_axis_acc_tdata),
    .s_axis_acc_tvalid (s_axis_acc_tvalid),
    .s_axis_acc_tready (s_axis_acc_tready),
    .s_axis_acc_tlast  (s_axis_acc_tlast),
    .m_axis_acc_tdata  (m_axis_acc_tdata),
    .m_axis_acc_tvalid (m_axis_acc_tvalid),
    .m_axis_acc_tready (m_axis_acc_tready),
    .m_axis_acc_tlast  (m_axis_acc_tlast),
    .m_axis_foff_tdata (m_axis_foff_tdata),
    .m_axis_foff_tvalid(m_axis_foff_tvalid),
    .m_axis_foff_tready(m_axis_foff_tready),
    .m_axis_foff_tlast (m_axis_foff_tlast)
  );

  assign m_axis_video_tvalid = core_valid;
  assign m_axis_video_tdata  = VidOutBits'(core_data);
  assign m_axis_video_tlast  = core_eol;
  assign m_axis_video_tuser  = core_sof;

  // ---- output frames: the last line's end ---------------------------------------------------
  logic [HeightBits-1:0] out_row_q;
  logic                  frame_out_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_out_frames
    if (!rst_ni) begin
      out_row_q   <= '0;
      frame_out_q <= 1'b0;
    end else begin
      frame_out_q <= core_valid && m_axis_video_tready && core_eol && (out_row_q == act_hm1);
      if (core_valid && m_axis_video_tready && core_eol) begin
        out_row_q <= (out_row_q == act_hm1) ? '0 : out_row_q + HeightBits'(1);
      end
    end
  end

  assign pix_out   = core_valid && m_axis_video_tready;
  assign frame_out = frame_out_q;

  // Not used: AxPROT, the tdata bits above the code, the method registers the method does
  // not read (docs/integration.md).
  logic unused_inputs;
  assign unused_inputs = ^{s_axil_awprot, s_axil_arprot, slots, table_readings};
  if (VidInBits > AdcBits) begin : gen_vid_pad
    logic unused_vid;
    assign unused_vid = ^s_axis_video_tdata[VidInBits-1:AdcBits];
  end
  if (CoefBits > WordBits) begin : gen_coef_pad
    logic unused_coef;
    assign unused_coef = ^s_axis_coef_tdata[CoefBits-1:WordBits];
  end

`ifdef IRNUC_ASSERT
  // Every AXI port is checked; the input buffers check their output sides.
  irnuc_axis_assert #(.DataBits(VidInBits), .UserBits(1)) u_assert_vid_in (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .tvalid_i(s_axis_video_tvalid),
    .tready_i(s_axis_video_tready),
    .tdata_i (s_axis_video_tdata),
    .tlast_i (s_axis_video_tlast),
    .tuser_i (s_axis_video_tuser)
  );
  irnuc_axis_assert #(.DataBits(CoefBits), .UserBits(1)) u_assert_coef_in (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .tvalid_i(s_axis_coef_tvalid),
    .tready_i(s_axis_coef_tready),
    .tdata_i (s_axis_coef_tdata),
    .tlast_i (s_axis_coef_tlast),
    .tuser_i (1'b0)
  );
  irnuc_axis_assert #(.DataBits(VidOutBits), .UserBits(1)) u_assert_vid_out (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .tvalid_i(m_axis_video_tvalid),
    .tready_i(m_axis_video_tready),
    .tdata_i (m_axis_video_tdata),
    .tlast_i (m_axis_video_tlast),
    .tuser_i (m_axis_video_tuser)
  );
  irnuc_axil_assert #(.AddrBits(AddrBits)) u_assert_axil (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .awaddr_i (s_axil_awaddr),
    .awprot_i (s_axil_awprot),
    .awvalid_i(s_axil_awvalid),
    .awready_i(s_axil_awready),
    .wdata_i  (s_axil_wdata),
    .wstrb_i  (s_axil_wstrb),
    .wvalid_i (s_axil_wvalid),
    .wready_i (s_axil_wready),
    .bresp_i  (s_axil_bresp),
    .bvalid_i (s_axil_bvalid),
    .bready_i (s_axil_bready),
    .araddr_i (s_axil_araddr),
    .arprot_i (s_axil_arprot),
    .arvalid_i(s_axil_arvalid),
    .arready_i(s_axil_arready),
    .rdata_i  (s_axil_rdata),
    .rresp_i  (s_axil_rresp),
    .rvalid_i (s_axil_rvalid),
    .rready_i (s_axil_rready)
  );
`endif

endmodule
