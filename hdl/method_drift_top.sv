// Blind-drift composition top: a linear base method (those of blind_drift_composes:
// one_point, two_point) with blind_drift, then the DPC (docs/datapath.md "blind_drift",
// "drift_sub"; docs/rtl.md "Stages"; nuc_fixed.method_top for a method
// "one_point+blind_drift" / "two_point+blind_drift").
//
// Streams (valid/ready), each behind its own input register (irnuc_spill_register):
//   s_pix    raw pixels with sof/eol and the frame word s_pix_frame_i (read at sof:
//            one_point's gain register; two_point: none, one unused bit), as method_dpc_top;
//   s_coef   one coefficient word per pixel (one_point: offset, bad; two_point: gain,
//            offset, bad), as method_dpc_top;
//   s_blind  the frame's blind codes (or partial sums), the last one flagged: they come
//            before the frame's active pixels (the blind rows precede the active rows);
//   m_pix    corrected pixels with sof/eol.
// blind_drift turns each frame's blind sum into its drift code delta (one sequential
// multiply); the frame's first active pixel waits for it and latches it for the frame.
// Per pixel: the method's front (frame_coefficients: the pixel's gain and offset of the
// frame), drift_sub x' = (x << Df) - delta, the linear core on the signed x' (Xf = Df,
// core_sum), ROUND_F and OUT (core_out), the DPC tail (dpc_tail). One pixel per clock, no bubbles, as
// long as each frame's blind items are taken before its first pixel arrives.
// Latency: 2 + core_sum + 2 + dpc_core (drift14: W + 17).
module method_drift_top
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
  import irnuc_stage_pkg::*;
#(
  // irnuc-params: begin method_drift_top (generated from nuc_fixed.methods; do not edit)
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
  parameter int unsigned DriftIntBits      = 14,
  parameter int unsigned DriftFracBits     = 2,
  parameter int unsigned DriftRounding     = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned DriftOverflow     = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned DriftGainIntBits  = 1,
  parameter int unsigned DriftGainFracBits = 24,
  parameter int unsigned BlindMax          = 8192,  // the most blind pixels a frame has
  // Derived, do not override.
  localparam int unsigned GainBits          = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits        = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits          = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits         = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits          = QuadIntBits + QuadFracBits,
  localparam int unsigned CoefBits          = coef_stream_bits(Method, OffsetBits, GainBits,
                                                               KneeBits, QuadBits, 32'd1, 32'd1,
                                                               32'd1),
  localparam int unsigned FrameBits         = frame_word_bits(Method, GainBits, LevelBits, 32'd1,
                                                              32'd1, 32'd1),
  localparam int unsigned WidthBits         = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits        = $clog2(MaxHeight + 1),
  // irnuc-params: end
  localparam int unsigned BlindBits        = blind_sum_bits(AdcBits, BlindMax),
  localparam int unsigned DriftBits        = DriftIntBits + DriftFracBits,
  localparam int unsigned DriftGainBits    = DriftGainIntBits + DriftGainFracBits
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic [WidthBits-1:0]     frame_width_i,
  input  logic [HeightBits-1:0]    frame_height_i,
  // Raw pixels in, with the frame word (read at sof).
  input  logic                     s_pix_valid_i,
  output logic                     s_pix_ready_o,
  input  logic [AdcBits-1:0]       s_pix_data_i,
  input  logic                     s_pix_sof_i,
  input  logic                     s_pix_eol_i,
  input  logic [FrameBits-1:0]     s_pix_frame_i,
  // Coefficient words in.
  input  logic                     s_coef_valid_i,
  output logic                     s_coef_ready_o,
  input  logic [CoefBits-1:0]      s_coef_data_i,
  // Blind codes in, before their frame.
  input  logic                     s_blind_valid_i,
  output logic                     s_blind_ready_o,
  input  logic [BlindBits-1:0]     s_blind_data_i,
  input  logic                     s_blind_last_i,
  // Calibration registers of blind_drift.
  input  logic [BlindBits-1:0]     blind_ref_i,
  input  logic [DriftGainBits-1:0] drift_gain_i,
  // Corrected pixels out.
  output logic                     m_pix_valid_o,
  input  logic                     m_pix_ready_i,
  output logic [OutBits-1:0]       m_pix_data_o,
  output logic                     m_pix_sof_o,
  output logic                     m_pix_eol_o,
  // Sticky framing error (see dpc_core).
  output logic                     frame_err_o
);

  localparam int unsigned XBits    = ((AdcBits + DriftFracBits + 1 > DriftBits)
                                      ? AdcBits + DriftFracBits + 1 : DriftBits) + 1;
  localparam int unsigned FracBits = core_frac(CoreLin, DriftFracBits, GainFracBits,
                                               OffsetFracBits, 0, 0, 0);
  localparam int unsigned SumBits  = core_sum_bits(CoreLin, XBits, 1'b1, DriftFracBits,
                                                   AdcBits, GainBits, GainFracBits,
                                                   OffsetBits, OffsetFracBits, 1, 0, 1, 1,
                                                   0, 1, 0, 0);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (blind_drift_composes(Method))
      else $fatal(1, "method_drift_top: Method = %0d; blind_drift composes with %s", Method,
                  "the methods of irnuc_method_pkg::blind_drift_composes");
    assert (MaxWidth >= 1 && MaxWidth <= 65535 && MaxHeight >= 1 && MaxHeight <= 65535)
      else $fatal(1, "method_drift_top: MaxWidth = %0d, MaxHeight = %0d outside 1..65535",
                  MaxWidth, MaxHeight);
  end
`endif

  // ---- input registers ----------------------------------------------------------------------
  logic                 pix_valid, pix_ready, pix_sof, pix_eol;
  logic [AdcBits-1:0]   pix_data;
  logic [FrameBits-1:0] pix_frame;
  logic                 coef_valid, coef_ready;
  logic [CoefBits-1:0]  coef;

  irnuc_spill_register #(.DataBits(FrameBits + AdcBits + 2)) u_pix_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_pix_valid_i),
    .ready_o(s_pix_ready_o),
    .data_i ({s_pix_frame_i, s_pix_sof_i, s_pix_eol_i, s_pix_data_i}),
    .valid_o(pix_valid),
    .ready_i(pix_ready),
    .data_o ({pix_frame, pix_sof, pix_eol, pix_data})
  );

  irnuc_spill_register #(.DataBits(CoefBits)) u_coef_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_coef_valid_i),
    .ready_o(s_coef_ready_o),
    .data_i (s_coef_data_i),
    .valid_o(coef_valid),
    .ready_i(coef_ready),
    .data_o (coef)
  );

  // ---- the frame's drift code ----------------------------------------------------------------
  logic                 drift_valid, drift_ready, drift_busy;
  logic [DriftBits-1:0] drift;

  blind_drift #(
    .AdcBits          (AdcBits),
    .BlindMax         (BlindMax),
    .DriftIntBits     (DriftIntBits),
    .DriftFracBits    (DriftFracBits),
    .DriftRounding    (DriftRounding),
    .DriftOverflow    (DriftOverflow),
    .DriftGainIntBits (DriftGainIntBits),
    .DriftGainFracBits(DriftGainFracBits)
  ) u_drift (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .s_blind_valid_i(s_blind_valid_i),
    .s_blind_ready_o(s_blind_ready_o),
    .s_blind_data_i (s_blind_data_i),
    .s_blind_last_i (s_blind_last_i),
    .blind_ref_i    (blind_ref_i),
    .drift_gain_i   (drift_gain_i),
    .m_drift_valid_o(drift_valid),
    .m_drift_ready_i(drift_ready),
    .m_drift_data_o (drift),
    .busy_o         (drift_busy)
  );

  logic unused_drift_busy;
  assign unused_drift_busy = drift_busy;

  // ---- join: a pixel, its word and (at sof) its frame's drift code move together ----------
  logic en, need, join_valid, join_ready, join_take;

  assign need        = !pix_sof || drift_valid;
  assign join_valid  = pix_valid && coef_valid && need;
  assign join_take   = join_valid && join_ready;
  assign pix_ready   = join_ready && coef_valid && need;
  assign coef_ready  = join_ready && pix_valid && need;
  assign drift_ready = join_ready && pix_valid && coef_valid && pix_sof;

  // The frame word and the drift code: the first pixel's, held for the rest of the frame.
  logic [FrameBits-1:0] frame_q, frame;
  logic [DriftBits-1:0] delta_q, delta;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_frame
    if (!rst_ni) begin
      frame_q <= '0;
      delta_q <= '0;
    end else if (join_take && pix_sof) begin
      frame_q <= pix_frame;
      delta_q <= drift;
    end
  end

  assign frame = pix_sof ? pix_frame : frame_q;
  assign delta = pix_sof ? drift : delta_q;

  // ---- the method's front: the pixel's gain and offset of the frame ------------------------
  // The raw code, the frame's drift code and the markers travel as side band.
  localparam int unsigned PassBits = AdcBits + DriftBits + 2;  // {raw, delta, sof, eol}

  logic                  f_valid;
  logic [GainBits-1:0]   gain, f_gain_hi;
  logic [OffsetBits-1:0] offset;
  logic [QuadBits-1:0]   f_quad;
  logic [KneeBits-1:0]   f_knee;
  logic [LevelBits-1:0]  f_level;
  logic [AdcBits-1:0]    f_x;
  logic [DriftBits-1:0]  f_delta;
  logic                  f_sof, f_eol, bad;

  frame_coefficients #(
    // irnuc-params: forward frame_coefficients (generated from nuc_fixed.methods; do not edit)
    .Method         (Method),
    .GainIntBits    (GainIntBits),
    .GainFracBits   (GainFracBits),
    .OffsetIntBits  (OffsetIntBits),
    .OffsetFracBits (OffsetFracBits),
    .KneeIntBits    (KneeIntBits),
    .KneeFracBits   (KneeFracBits),
    .LevelIntBits   (LevelIntBits),
    .LevelFracBits  (LevelFracBits),
    .QuadIntBits    (QuadIntBits),
    .QuadFracBits   (QuadFracBits),
    .Rounding       (Rounding),
    // irnuc-params: end
    .UserBits(PassBits)
  ) u_front (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .s_valid_i  (join_valid),
    .s_ready_o  (join_ready),
    .s_coef_i   (coef),
    .s_frame_i  (frame),
    .s_user_i   ({pix_data, delta, pix_sof, pix_eol}),
    .m_valid_o  (f_valid),
    .m_ready_i  (en),
    .m_gain_o   (gain),
    .m_gain_hi_o(f_gain_hi),
    .m_offset_o (offset),
    .m_quad_o   (f_quad),
    .m_knee_o   (f_knee),
    .m_level_o  (f_level),
    .m_user_o   ({f_x, f_delta, f_sof, f_eol, bad})
  );
  // blind_drift composes with the linear kind: gain and offset.
  logic unused_front;
  assign unused_front = ^{f_gain_hi, f_quad, f_knee, f_level};

  // ---- drift_sub, the linear core on x', ROUND and OUT ----------------------------------------
  localparam int unsigned Side = GainBits + OffsetBits + 3;  // {gain, offset, sof, eol, bad}

  logic                  sub_valid;
  logic [XBits-1:0]      sub_x;
  logic [Side-1:0]       sub_side;

  drift_sub #(
    .AdcBits      (AdcBits),
    .DriftIntBits (DriftIntBits),
    .DriftFracBits(DriftFracBits),
    .SideBits     (Side)
  ) u_sub (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(f_valid),
    .x_i    (f_x),
    .delta_i(f_delta),
    .side_i ({gain, offset, f_sof, f_eol, bad}),
    .valid_o(sub_valid),
    .x_o    (sub_x),
    .side_o (sub_side)
  );

  logic               sum_valid;
  logic [SumBits-1:0] sum_s;
  logic [2:0]         sum_user;

  core_sum #(
    .Kind          (32'(CoreLin)),
    .XBits         (XBits),
    .XSigned       (1'b1),
    .XFracBits     (DriftFracBits),
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .SideBits      (3)
  ) u_core (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en),
    .valid_i  (sub_valid),
    .x_i      (sub_x),
    .gain_i   (sub_side[Side-1 -: GainBits]),
    .gain_hi_i('0),
    .offset_i (sub_side[3 +: OffsetBits]),
    .quad_i   ('0),
    .knee_i   ('0),
    .level_i  ('0),
    .side_i   (sub_side[2:0]),
    .valid_o  (sum_valid),
    .sum_o    (sum_s),
    .side_o   (sum_user)
  );

  logic               nuc_valid, nuc_ready;
  logic [OutBits-1:0] nuc_data;
  logic [2:0]         nuc_user;  // {sof, eol, bad}

  core_out #(
    .SumBits (SumBits),
    .FracBits(FracBits),
    .OutBits (OutBits),
    .Rounding(Rounding),
    .Overflow(Overflow),
    .UserBits(3)
  ) u_out (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_o     (en),
    .valid_i  (sum_valid),
    .sum_i    (sum_s),
    .user_i   (sum_user),
    .m_valid_o(nuc_valid),
    .m_ready_i(nuc_ready),
    .m_data_o (nuc_data),
    .m_user_o (nuc_user)
  );

  // ---- DPC ---------------------------------------------------------------------------------
  dpc_tail #(
    .CheckIn   (1'b0),  // its s_* is core_out's output register, checked there
    // irnuc-params: forward dpc_tail (generated from nuc_fixed.methods; do not edit)
    .OutBits   (OutBits),
    .MaxWidth  (MaxWidth),
    .MaxHeight (MaxHeight)
    // irnuc-params: end
  ) u_tail (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .frame_width_i (frame_width_i),
    .frame_height_i(frame_height_i),
    .frame_start_i (s_pix_valid_i && s_pix_ready_o && s_pix_sof_i),
    .s_valid_i     (nuc_valid),
    .s_ready_o     (nuc_ready),
    .s_pix_data_i  (nuc_data),
    .s_bad_i       (nuc_user[0]),
    .s_sof_i       (nuc_user[2]),
    .s_eol_i       (nuc_user[1]),
    .m_valid_o     (m_pix_valid_o),
    .m_ready_i     (m_pix_ready_i),
    .m_pix_data_o  (m_pix_data_o),
    .m_sof_o       (m_pix_sof_o),
    .m_eol_o       (m_pix_eol_o),
    .frame_err_o   (frame_err_o)
  );

  // Protocol assertions of s_pix_*, s_coef_*, s_blind_* and m_pix_*: in u_pix_in, u_coef_in,
  // u_drift.u_in and u_tail.u_dpc.u_out (irnuc_spill_register), whose ports these are; the
  // frame size at a frame start: in u_tail.

endmodule
