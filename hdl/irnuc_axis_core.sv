// The core of irnuc_axis_top and the FFC side around it (docs/integration.md): the framer's
// items go to irnuc_axis_ffc (method_ffc_top and its streams) with Ffc = 1, to
// method_drift_top with Drift = 1 (each frame's blind sum from the frame word), else to
// nuc_dpc_top for two_point (Method = 1) or method_dpc_top for one_point, piecewise,
// quadratic, tc_offset and table_interp, whose two inputs move in lockstep (one item is a pixel and its
// word; the frame word rides on the pixel stream, read with sof). Without the ffc stage
// the FFC streams are tied off: inputs never ready, outputs never valid.
module irnuc_axis_core
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  // irnuc-params: begin irnuc_axis_core (generated from nuc_fixed.methods; do not edit)
  // the base method (irnuc_pkg::method_e)
  parameter method_e     Method            = MethodTwoPoint,
  parameter int unsigned AdcBits           = 14,
  parameter int unsigned GainIntBits       = 2,
  parameter int unsigned GainFracBits      = 14,
  parameter int unsigned OffsetIntBits     = 12,
  parameter int unsigned OffsetFracBits    = 4,
  parameter int unsigned OutBits           = 14,
  parameter int unsigned Rounding          = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow          = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned MaxWidth          = 1024,
  parameter int unsigned MaxHeight         = 1024,
  parameter int unsigned KneeIntBits       = 14,
  parameter int unsigned KneeFracBits      = 2,
  parameter int unsigned LevelIntBits      = 14,
  parameter int unsigned LevelFracBits     = 4,
  parameter int unsigned QuadIntBits       = 10,
  parameter int unsigned QuadFracBits      = 6,
  parameter int unsigned SquareBits        = 18,  // bits the square of a raw code is truncated to
  parameter int unsigned ReadingBits       = 14,  // bits of the FPA sensor's reading
  parameter int unsigned Tc1IntBits        = 13,
  parameter int unsigned Tc1FracBits       = 3,
  parameter int unsigned Tc2IntBits        = 12,
  parameter int unsigned Tc2FracBits       = 4,
  parameter int unsigned Tg1IntBits        = 2,
  parameter int unsigned Tg1FracBits       = 14,
  parameter int unsigned Tg2IntBits        = 2,
  parameter int unsigned Tg2FracBits       = 14,
  parameter int unsigned TcOrder           = 2,  // order of the polynomials
  parameter bit          TcGain            = 1'b0,  // the gain is a polynomial too
  parameter int unsigned ReadingRangeBits  = 11,  // Ts: v = (t - t_ref) / 2^Ts
  parameter int unsigned WeightIntBits     = 1,
  parameter int unsigned WeightFracBits    = 15,
  parameter int unsigned WeightRounding    = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned HousingBits       = 14,  // bits of the housing sensor's reading
  parameter int unsigned Th1IntBits        = 15,
  parameter int unsigned Th1FracBits       = 3,
  parameter int unsigned ThxIntBits        = 14,
  parameter int unsigned ThxFracBits       = 4,
  parameter int unsigned Th2IntBits        = 12,
  parameter int unsigned Th2FracBits       = 4,
  parameter int unsigned HousingRangeBits  = 11,  // Hs: w' = (h - h_ref) / 2^Hs
  parameter int unsigned DriftIntBits      = 14,
  parameter int unsigned DriftFracBits     = 2,
  parameter int unsigned DriftRounding     = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned DriftOverflow     = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned DriftGainIntBits  = 1,
  parameter int unsigned DriftGainFracBits = 24,
  parameter int unsigned BlindMax          = 8192,  // the most blind pixels a frame has
  parameter bit          Drift             = 1'b0,  // 1: the core is method_drift_top
  parameter int unsigned FfcIntBits        = 12,
  parameter int unsigned FfcFracBits       = 4,
  parameter int unsigned FfcRounding       = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned FfcOverflow       = 0,  // irnuc_pkg::overflow_e
  // N, the shutter frames of a refresh (a power of two)
  parameter int unsigned FfcFrames         = 8,
  // what the output shows during the shutter frames
  parameter bit          FfcHold           = 1'b1,
  parameter bit          Ffc               = 1'b0,  // 1: the core is method_ffc_top
  // Derived, do not override.
  localparam int unsigned GainBits          = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits        = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits          = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits         = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits          = QuadIntBits + QuadFracBits,
  localparam int unsigned TcWordBits        = Tc1IntBits + Tc1FracBits
                                              + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned TgWordBits        = (TcGain != 0) ? Tg1IntBits + Tg1FracBits
                                              + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0) : 0,
  localparam int unsigned ThWordBits        = Th1IntBits + Th1FracBits + ThxIntBits + ThxFracBits
                                              + Th2IntBits + Th2FracBits,
  localparam int unsigned WeightBits        = WeightIntBits + WeightFracBits,
  localparam int unsigned WordBits          = coef_stream_bits(Method, OffsetBits, GainBits,
                                                               KneeBits, QuadBits, TcWordBits,
                                                               TgWordBits, ThWordBits),
  localparam int unsigned BaseFrameBits     = frame_word_bits(Method, GainBits, LevelBits,
                                                              ReadingBits, WeightBits, HousingBits),
  localparam int unsigned WidthBits         = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits        = $clog2(MaxHeight + 1),
  // irnuc-params: end
  localparam int unsigned BlindBits     = blind_sum_bits(AdcBits, BlindMax),
  localparam int unsigned DriftGainBits = DriftGainIntBits + DriftGainFracBits,
  localparam int unsigned FrameBits     = (Drift != 0)
                                          ? frame_blind_drift_bits(BaseFrameBits, BlindBits,
                                                                   DriftGainBits)
                                          : BaseFrameBits,
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
  input  logic                            clk_i,
  input  logic                            rst_ni,
  // The frame size the framer's frames are taken with.
  input  logic [WidthBits-1:0]            act_w_i,
  input  logic [WidthBits-1:0]            act_wm1_i,
  input  logic [HeightBits-1:0]           act_h_i,
  input  logic [HeightBits-1:0]           act_hm1_i,
  // The method's pending frame word in, the framer's (with the shutter flag: Ffc) out.
  input  logic [FrameBits-1:0]            pend_frame_i,
  output logic [ItemFrameBits-1:0]        pend_item_frame_o,
  // Register file: a frame start, FFC_CTRL, FFC_STATUS.
  input  logic                            start_i,
  input  logic                            ffc_start_i,
  input  logic [RegFfcCtrlFramesBits-1:0] ffc_frames_i,
  output logic                            ffc_busy_o,
  output logic                            ffc_done_o,
  // The framer's items (a pixel and its word).
  input  logic                            item_valid_i,
  output logic                            item_ready_o,
  input  logic [AdcBits-1:0]              item_raw_i,
  input  logic [WordBits-1:0]             item_word_i,
  input  logic                            item_sof_i,
  input  logic                            item_eol_i,
  input  logic [ItemFrameBits-1:0]        item_frame_i,
  // Corrected pixels (the core's output register).
  output logic                            m_valid_o,
  input  logic                            m_ready_i,
  output logic [OutBits-1:0]              m_data_o,
  output logic                            m_sof_o,
  output logic                            m_eol_o,
  output logic [1:0]                      core_out_o,  // items that left the core (output, and one of a held frame)
  output logic                            wb_busy_o,   // FFC write-back words owed (a flop)
  output logic                            frame_err_o,
  // The FFC streams (irnuc_axis_top's ports).
  input  logic [FoffBits-1:0]             s_axis_foff_tdata,
  input  logic                            s_axis_foff_tvalid,
  output logic                            s_axis_foff_tready,
  input  logic                            s_axis_foff_tlast,
  input  logic [AccBits-1:0]              s_axis_acc_tdata,
  input  logic                            s_axis_acc_tvalid,
  output logic                            s_axis_acc_tready,
  input  logic                            s_axis_acc_tlast,
  output logic [AccBits-1:0]              m_axis_acc_tdata,
  output logic                            m_axis_acc_tvalid,
  input  logic                            m_axis_acc_tready,
  output logic                            m_axis_acc_tlast,
  output logic [FoffBits-1:0]             m_axis_foff_tdata,
  output logic                            m_axis_foff_tvalid,
  input  logic                            m_axis_foff_tready,
  output logic                            m_axis_foff_tlast
);

  logic core_pix_ready, core_coef_ready;
  logic core_pass;  // the item may go to the core (Drift: a frame start waits for its blind item)

  if (Ffc != 0) begin : gen_ffc
    irnuc_axis_ffc #(
      // irnuc-params: forward irnuc_axis_ffc (generated from nuc_fixed.methods; do not edit)
      .Method           (Method),
      .AdcBits          (AdcBits),
      .GainIntBits      (GainIntBits),
      .GainFracBits     (GainFracBits),
      .OffsetIntBits    (OffsetIntBits),
      .OffsetFracBits   (OffsetFracBits),
      .OutBits          (OutBits),
      .Rounding         (Rounding),
      .Overflow         (Overflow),
      .MaxWidth         (MaxWidth),
      .MaxHeight        (MaxHeight),
      .KneeIntBits      (KneeIntBits),
      .KneeFracBits     (KneeFracBits),
      .LevelIntBits     (LevelIntBits),
      .LevelFracBits    (LevelFracBits),
      .QuadIntBits      (QuadIntBits),
      .QuadFracBits     (QuadFracBits),
      .SquareBits       (SquareBits),
      .ReadingBits      (ReadingBits),
      .Tc1IntBits       (Tc1IntBits),
      .Tc1FracBits      (Tc1FracBits),
      .Tc2IntBits       (Tc2IntBits),
      .Tc2FracBits      (Tc2FracBits),
      .Tg1IntBits       (Tg1IntBits),
      .Tg1FracBits      (Tg1FracBits),
      .Tg2IntBits       (Tg2IntBits),
      .Tg2FracBits      (Tg2FracBits),
      .TcOrder          (TcOrder),
      .TcGain           (TcGain),
      .ReadingRangeBits (ReadingRangeBits),
      .FfcIntBits       (FfcIntBits),
      .FfcFracBits      (FfcFracBits),
      .FfcRounding      (FfcRounding),
      .FfcOverflow      (FfcOverflow),
      .FfcFrames        (FfcFrames),
      .FfcHold          (FfcHold)
      // irnuc-params: end
    ) u_ffc (
      .clk_i             (clk_i),
      .rst_ni            (rst_ni),
      .act_w_i           (act_w_i),
      .act_wm1_i         (act_wm1_i),
      .act_h_i           (act_h_i),
      .act_hm1_i         (act_hm1_i),
      .pend_frame_i      (pend_frame_i),
      .pend_item_frame_o (pend_item_frame_o),
      .start_i           (start_i),
      .ffc_start_i       (ffc_start_i),
      .ffc_frames_i      (ffc_frames_i),
      .ffc_busy_o        (ffc_busy_o),
      .ffc_done_o        (ffc_done_o),
      .item_valid_i      (item_valid_i),
      .item_ready_o      (item_ready_o),
      .item_raw_i        (item_raw_i),
      .item_word_i       (item_word_i),
      .item_sof_i        (item_sof_i),
      .item_eol_i        (item_eol_i),
      .item_frame_i      (item_frame_i),
      .m_valid_o         (m_valid_o),
      .m_ready_i         (m_ready_i),
      .m_data_o          (m_data_o),
      .m_sof_o           (m_sof_o),
      .m_eol_o           (m_eol_o),
      .core_out_o        (core_out_o),
      .wb_busy_o         (wb_busy_o),
      .frame_err_o       (frame_err_o),
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
    // Its two inputs are forked in u_ffc (not in lockstep).
    assign core_pix_ready  = 1'b1;
    assign core_coef_ready = 1'b1;
    logic unused_pass;
    assign unused_pass = core_pass;
  end else if (Drift != 0) begin : gen_drift
    // method_drift_top: each frame's blind sum (the frame word's BLIND_SUM) goes to its
    // s_blind as one item, flagged last, before the frame's first pixel: the framer's sof
    // item waits until the item is taken (blind_sent_q), and method_drift_top's join waits
    // for the frame's drift code (blind_drift: MW + 5 cycles, a bubble at each frame
    // start). blind_drift samples BLIND_REF and DRIFT_GAIN from the frame word when it
    // takes the item, a cycle after the handshake; one item at a time (blind_busy_q, until
    // the frame's first pixel leaves the core), so the framer's frame word is still that
    // frame's then even when frames are a pixel long.
    frame_blind_drift#(BaseFrameBits, BlindBits, DriftGainBits)::word_t fw;
    logic blind_sent_q, blind_busy_q, blind_valid, blind_ready, pass, core_valid;

    assign fw          = item_frame_i;
    assign blind_valid = item_valid_i && item_sof_i && !blind_sent_q && !blind_busy_q;
    assign pass        = !item_sof_i || blind_sent_q;
    assign core_valid  = item_valid_i && pass;
    assign core_pass   = pass;

    always_ff @(posedge clk_i or negedge rst_ni) begin : p_blind
      if (!rst_ni) begin
        blind_sent_q <= 1'b0;
        blind_busy_q <= 1'b0;
      end else begin
        if (blind_valid && blind_ready) begin
          blind_sent_q <= 1'b1;
        end else if (core_valid && item_ready_o && item_sof_i) begin
          blind_sent_q <= 1'b0;
        end
        if (blind_valid && blind_ready) begin
          blind_busy_q <= 1'b1;
        end else if (m_valid_o && m_ready_i && m_sof_o) begin
          blind_busy_q <= 1'b0;
        end
      end
    end

    method_drift_top #(

      // irnuc-params: forward method_drift_top (generated from nuc_fixed.methods; do not edit)
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
      .DriftIntBits      (DriftIntBits),
      .DriftFracBits     (DriftFracBits),
      .DriftRounding     (DriftRounding),
      .DriftOverflow     (DriftOverflow),
      .DriftGainIntBits  (DriftGainIntBits),
      .DriftGainFracBits (DriftGainFracBits),
      .BlindMax          (BlindMax)
      // irnuc-params: end
    ) u_core (
      .clk_i          (clk_i),
      .rst_ni         (rst_ni),
      .frame_width_i  (act_w_i),
      .frame_height_i (act_h_i),
      .s_pix_valid_i  (core_valid),
      .s_pix_ready_o  (core_pix_ready),
      .s_pix_data_i   (item_raw_i),
      .s_pix_sof_i    (item_sof_i),
      .s_pix_eol_i    (item_eol_i),
      .s_pix_frame_i  (fw.base),
      .s_coef_valid_i (core_valid),
      .s_coef_ready_o (core_coef_ready),
      .s_coef_data_i  (item_word_i),
      .s_blind_valid_i(blind_valid),
      .s_blind_ready_o(blind_ready),
      .s_blind_data_i (fw.blind_sum),
      .s_blind_last_i (1'b1),
      .blind_ref_i    (fw.blind_ref),
      .drift_gain_i   (fw.drift_gain),
      .m_pix_valid_o  (m_valid_o),
      .m_pix_ready_i  (m_ready_i),
      .m_pix_data_o   (m_data_o),
      .m_pix_sof_o    (m_sof_o),
      .m_pix_eol_o    (m_eol_o),
      .frame_err_o    (frame_err_o)
    );
  end else if (method_plain(Method)) begin : gen_plain
    nuc_dpc_top #(
      // irnuc-params: forward nuc_dpc_top (generated from nuc_fixed.methods; do not edit)
      .AdcBits        (AdcBits),
      .GainIntBits    (GainIntBits),
      .GainFracBits   (GainFracBits),
      .OffsetIntBits  (OffsetIntBits),
      .OffsetFracBits (OffsetFracBits),
      .OutBits        (OutBits),
      .Rounding       (Rounding),
      .Overflow       (Overflow),
      .MaxWidth       (MaxWidth),
      .MaxHeight      (MaxHeight)
      // irnuc-params: end
    ) u_core (
      .clk_i         (clk_i),
      .rst_ni        (rst_ni),
      .frame_width_i (act_w_i),
      .frame_height_i(act_h_i),
      .s_pix_valid_i (item_valid_i),
      .s_pix_ready_o (core_pix_ready),
      .s_pix_data_i  (item_raw_i),
      .s_pix_sof_i   (item_sof_i),
      .s_pix_eol_i   (item_eol_i),
      .s_coef_valid_i(item_valid_i),
      .s_coef_ready_o(core_coef_ready),
      .s_coef_data_i (item_word_i),
      .m_pix_valid_o (m_valid_o),
      .m_pix_ready_i (m_ready_i),
      .m_pix_data_o  (m_data_o),
      .m_pix_sof_o   (m_sof_o),
      .m_pix_eol_o   (m_eol_o),
      .frame_err_o   (frame_err_o)
    );
    logic unused_frame;
    assign unused_frame = ^item_frame_i;
  end else begin : gen_method
    method_dpc_top #(
      // irnuc-params: forward method_dpc_top (generated from nuc_fixed.methods; do not edit)
      .Method           (Method),
      .AdcBits          (AdcBits),
      .GainIntBits      (GainIntBits),
      .GainFracBits     (GainFracBits),
      .OffsetIntBits    (OffsetIntBits),
      .OffsetFracBits   (OffsetFracBits),
      .OutBits          (OutBits),
      .Rounding         (Rounding),
      .Overflow         (Overflow),
      .MaxWidth         (MaxWidth),
      .MaxHeight        (MaxHeight),
      .KneeIntBits      (KneeIntBits),
      .KneeFracBits     (KneeFracBits),
      .LevelIntBits     (LevelIntBits),
      .LevelFracBits    (LevelFracBits),
      .QuadIntBits      (QuadIntBits),
      .QuadFracBits     (QuadFracBits),
      .SquareBits       (SquareBits),
      .ReadingBits      (ReadingBits),
      .Tc1IntBits       (Tc1IntBits),
      .Tc1FracBits      (Tc1FracBits),
      .Tc2IntBits       (Tc2IntBits),
      .Tc2FracBits      (Tc2FracBits),
      .Tg1IntBits       (Tg1IntBits),
      .Tg1FracBits      (Tg1FracBits),
      .Tg2IntBits       (Tg2IntBits),
      .Tg2FracBits      (Tg2FracBits),
      .TcOrder          (TcOrder),
      .TcGain           (TcGain),
      .ReadingRangeBits (ReadingRangeBits),
      .WeightIntBits    (WeightIntBits),
      .WeightFracBits   (WeightFracBits),
      .WeightRounding   (WeightRounding),
      .HousingBits      (HousingBits),
      .Th1IntBits       (Th1IntBits),
      .Th1FracBits      (Th1FracBits),
      .ThxIntBits       (ThxIntBits),
      .ThxFracBits      (ThxFracBits),
      .Th2IntBits       (Th2IntBits),
      .Th2FracBits      (Th2FracBits),
      .HousingRangeBits (HousingRangeBits)
      // irnuc-params: end
    ) u_core (
      .clk_i         (clk_i),
      .rst_ni        (rst_ni),
      .frame_width_i (act_w_i),
      .frame_height_i(act_h_i),
      .s_pix_valid_i (item_valid_i),
      .s_pix_ready_o (core_pix_ready),
      .s_pix_data_i  (item_raw_i),
      .s_pix_sof_i   (item_sof_i),
      .s_pix_eol_i   (item_eol_i),
      .s_pix_frame_i (item_frame_i),
      .s_coef_valid_i(item_valid_i),
      .s_coef_ready_o(core_coef_ready),
      .s_coef_data_i (item_word_i),
      .m_pix_valid_o (m_valid_o),
      .m_pix_ready_i (m_ready_i),
      .m_pix_data_o  (m_data_o),
      .m_pix_sof_o   (m_sof_o),
      .m_pix_eol_o   (m_eol_o),
      .frame_err_o   (frame_err_o)
    );
  end
  if (Drift == 0) begin : gen_no_drift
    assign core_pass = 1'b1;
  end
  if (Ffc == 0) begin : gen_no_ffc
    assign pend_item_frame_o  = pend_frame_i;
    // (Drift: a frame's first item waits for its blind item, gen_drift.)
    assign item_ready_o       = core_pix_ready && core_coef_ready && core_pass;
    assign core_out_o         = {1'b0, m_valid_o && m_ready_i};
    assign wb_busy_o          = 1'b0;
    assign ffc_busy_o         = 1'b0;
    assign ffc_done_o         = 1'b0;
    assign s_axis_foff_tready = 1'b0;
    assign s_axis_acc_tready  = 1'b0;
    assign m_axis_acc_tvalid  = 1'b0;
    assign m_axis_acc_tdata   = '0;
    assign m_axis_acc_tlast   = 1'b0;
    assign m_axis_foff_tvalid = 1'b0;
    assign m_axis_foff_tdata  = '0;
    assign m_axis_foff_tlast  = 1'b0;
    logic unused_ffc;
    assign unused_ffc = ^{s_axis_foff_tdata, s_axis_foff_tvalid, s_axis_foff_tlast,
                          s_axis_acc_tdata, s_axis_acc_tvalid, s_axis_acc_tlast,
                          m_axis_acc_tready, m_axis_foff_tready, start_i, ffc_start_i,
                          ffc_frames_i, act_wm1_i, act_hm1_i};
  end

`ifdef IRNUC_ASSERT
  // The FFC streams (tied off with Ffc = 0: checked all the same).
  irnuc_axis_assert #(.DataBits(FoffBits), .UserBits(1)) u_assert_foff_in (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .tvalid_i(s_axis_foff_tvalid),
    .tready_i(s_axis_foff_tready),
    .tdata_i (s_axis_foff_tdata),
    .tlast_i (s_axis_foff_tlast),
    .tuser_i (1'b0)
  );
  irnuc_axis_assert #(.DataBits(AccBits), .UserBits(1)) u_assert_acc_in (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .tvalid_i(s_axis_acc_tvalid),
    .tready_i(s_axis_acc_tready),
    .tdata_i (s_axis_acc_tdata),
    .tlast_i (s_axis_acc_tlast),
    .tuser_i (1'b0)
  );
  irnuc_axis_assert #(.DataBits(AccBits), .UserBits(1)) u_assert_acc_out (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .tvalid_i(m_axis_acc_tvalid),
    .tready_i(m_axis_acc_tready),
    .tdata_i (m_axis_acc_tdata),
    .tlast_i (m_axis_acc_tlast),
    .tuser_i (1'b0)
  );
  irnuc_axis_assert #(.DataBits(FoffBits), .UserBits(1)) u_assert_foff_out (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .tvalid_i(m_axis_foff_tvalid),
    .tready_i(m_axis_foff_tready),
    .tdata_i (m_axis_foff_tdata),
    .tlast_i (m_axis_foff_tlast),
    .tuser_i (1'b0)
  );

  // The core's two inputs hold the same items, so their readies agree.
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_lockstep: assert (core_pix_ready == core_coef_ready)
        else $error("irnuc_axis_core: the core's pixel and coefficient readies differ");
    end
  end
`endif

endmodule
