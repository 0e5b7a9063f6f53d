// FFC composition top: a base method (those of ffc_composes: one_point, two_point, quadratic,
// tc_offset) with the shutter offset refresh, then the DPC (docs/datapath.md "ffc";
// docs/rtl.md "Stages"; nuc_fixed.method_top for a method "<base>+ffc").
//
// Streams (valid/ready), each input behind its own input register and each output behind
// its own output register (irnuc_spill_register):
//   s_pix    raw pixels with sof/eol, the frame word s_pix_frame_i (read at sof, as
//            method_dpc_top: one_point's gain register, tc_offset's reading and t_ref) and the frame's shutter flag
//            s_pix_shutter_i (read at sof);
//   s_coef   one coefficient word per pixel, as method_dpc_top;
//   s_foff   the FFC offset correction of every pixel (memory ffc_offset: S Ci.Cf), every
//            frame; a refresh frame ignores it and uses its new words;
//   s_acc    the accumulator (memory ffc_acc: U (A + n).0) of every pixel, in the frames
//            that add to it (the 2nd..N-th shutter frame of a run) and in the refresh frame;
//   m_acc    the new accumulator of every pixel, in the 1st..N-th shutter frame of a run;
//   m_foff   the FFC offset correction of every pixel in the refresh frame (the frame
//            after the N-th shutter frame): the new one, or the one read when the mean
//            frame had no good pixel (no target: ffc_kept_o); written back to ffc_offset,
//            read from the next frame on (the refresh frame itself uses them already, as
//            the golden model);
//   m_pix    corrected pixels with sof/eol, of every frame but a held one (ffc_output
//            hold: a shutter frame once an open frame was output; the display keeps the
//            last open frame).
// Per pixel: the base method's sum on the raw code (core_sum, F = max(.., Cf)) beside the
// same sum on the accumulator (core_sum, Xf = n, the refresh and mean passes); then
//   dc = OVF_C(ROUND_(F' - Cf)((T << (F' - Cf)) - (s_acc << (F' - F_acc))))   (ffc_refresh)
//   v  = ROUND_(F' - Cf)(s_acc << (F' - F_acc))                             (ffc_mean)
//   y  = OUT(ROUND_F(s + (c << (F - Cf)))),  c = dc in a refresh frame, else s_foff
// and the DPC. The mean frame's v over good pixels give the target T (ffc_mean, one
// division, before the refresh frame's first pixel is taken; ffc_target_o); a mean frame
// without a good pixel gives none (ffc_kept_o): its refresh frame keeps c = s_foff.
// One pixel per clock, no bubbles, but for the division: a refresh frame's first pixel
// waits for the target (NumBits + 3 cycles after the mean frame's last pixel).
module method_ffc_top
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
  import irnuc_stage_pkg::*;
#(
  // irnuc-params: begin method_ffc_top (generated from nuc_fixed.methods; do not edit)
  // the base method (irnuc_pkg::method_e)
  parameter method_e     Method           = MethodTwoPoint,
  parameter int unsigned AdcBits          = 14,
  parameter int unsigned GainIntBits      = 2,
  parameter int unsigned GainFracBits     = 14,
  parameter int unsigned OffsetIntBits    = 12,
  parameter int unsigned OffsetFracBits   = 4,
  parameter int unsigned OutBits          = 14,
  parameter int unsigned Rounding         = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow         = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned MaxWidth         = 1024,
  parameter int unsigned MaxHeight        = 1024,
  parameter int unsigned KneeIntBits      = 14,
  parameter int unsigned KneeFracBits     = 2,
  parameter int unsigned LevelIntBits     = 14,
  parameter int unsigned LevelFracBits    = 4,
  parameter int unsigned QuadIntBits      = 10,
  parameter int unsigned QuadFracBits     = 6,
  parameter int unsigned SquareBits       = 18,  // bits the square of a raw code is truncated to
  parameter int unsigned ReadingBits      = 14,  // bits of the FPA sensor's reading
  parameter int unsigned Tc1IntBits       = 13,
  parameter int unsigned Tc1FracBits      = 3,
  parameter int unsigned Tc2IntBits       = 12,
  parameter int unsigned Tc2FracBits      = 4,
  parameter int unsigned Tg1IntBits       = 2,
  parameter int unsigned Tg1FracBits      = 14,
  parameter int unsigned Tg2IntBits       = 2,
  parameter int unsigned Tg2FracBits      = 14,
  parameter int unsigned TcOrder          = 2,  // order of the polynomials
  parameter bit          TcGain           = 1'b0,  // the gain is a polynomial too
  parameter int unsigned ReadingRangeBits = 11,  // Ts: v = (t - t_ref) / 2^Ts
  parameter int unsigned FfcIntBits       = 12,
  parameter int unsigned FfcFracBits      = 4,
  parameter int unsigned FfcRounding      = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned FfcOverflow      = 0,  // irnuc_pkg::overflow_e
  // N, the shutter frames of a refresh (a power of two)
  parameter int unsigned FfcFrames        = 8,
  // what the output shows during the shutter frames
  parameter bit          FfcHold          = 1'b1,
  // Derived, do not override.
  localparam int unsigned GainBits         = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits       = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits         = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits        = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits         = QuadIntBits + QuadFracBits,
  localparam int unsigned TcWordBits       = Tc1IntBits + Tc1FracBits
                                             + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned TgWordBits       = (TcGain != 0) ? Tg1IntBits + Tg1FracBits
                                             + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0) : 0,
  localparam int unsigned CoefBits         = coef_stream_bits(Method, OffsetBits, GainBits,
                                                              KneeBits, QuadBits, TcWordBits,
                                                              TgWordBits, 32'd1),
  localparam int unsigned FrameBits        = frame_word_bits(Method, GainBits, LevelBits,
                                                             ReadingBits, 32'd1, 32'd1),
  localparam int unsigned WidthBits        = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits       = $clog2(MaxHeight + 1),
  // irnuc-params: end
  localparam int unsigned NShift           = $clog2(FfcFrames),
  localparam int unsigned AccBits          = AdcBits + NShift,
  localparam int unsigned CBits            = FfcIntBits + FfcFracBits,
  localparam int unsigned TBits            = OutBits + FfcFracBits
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic [WidthBits-1:0]  frame_width_i,
  input  logic [HeightBits-1:0] frame_height_i,
  // Raw pixels in, with the frame word and the shutter flag (read at sof).
  input  logic                  s_pix_valid_i,
  output logic                  s_pix_ready_o,
  input  logic [AdcBits-1:0]    s_pix_data_i,
  input  logic                  s_pix_sof_i,
  input  logic                  s_pix_eol_i,
  input  logic [FrameBits-1:0]  s_pix_frame_i,
  input  logic                  s_pix_shutter_i,
  // Coefficient words in.
  input  logic                  s_coef_valid_i,
  output logic                  s_coef_ready_o,
  input  logic [CoefBits-1:0]   s_coef_data_i,
  // FFC offset corrections in (every frame).
  input  logic                  s_foff_valid_i,
  output logic                  s_foff_ready_o,
  input  logic [CBits-1:0]      s_foff_data_i,
  // Accumulator in (frames that add to it, the refresh frame).
  input  logic                  s_acc_valid_i,
  output logic                  s_acc_ready_o,
  input  logic [AccBits-1:0]    s_acc_data_i,
  // Accumulator out (the shutter frames of a run, up to N).
  output logic                  m_acc_valid_o,
  input  logic                  m_acc_ready_i,
  output logic [AccBits-1:0]    m_acc_data_o,
  // New FFC offset corrections out (the refresh frame).
  output logic                  m_foff_valid_o,
  input  logic                  m_foff_ready_i,
  output logic [CBits-1:0]      m_foff_data_o,
  // Corrected pixels out (every frame but a held one).
  output logic                  m_pix_valid_o,
  input  logic                  m_pix_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic                  m_pix_sof_o,
  output logic                  m_pix_eol_o,
  // The last FFC target (register ffc_target, U B.Cf) and whether one was taken; kept: its
  // mean frame had no good pixel, so there is no target (0) and the refresh kept the
  // offsets (valid with ffc_target_valid_o).
  output logic                  ffc_target_valid_o,
  output logic [TBits-1:0]      ffc_target_o,
  output logic                  ffc_kept_o,
  // Sticky framing error (see dpc_core).
  output logic                  frame_err_o
);

  localparam core_kind_e  Kind      = core_kind(Method);
  // The pixel's sum (raw x, the FFC term's Cf) and the accumulator's (Xf = n).
  localparam int unsigned FracBits  = core_frac(Kind, 0, GainFracBits, OffsetFracBits, 0, 0,
                                                FfcFracBits);
  localparam int unsigned SumBits   = core_sum_bits(Kind, AdcBits, 1'b0, 0, AdcBits, GainBits,
                                                    GainFracBits, OffsetBits, OffsetFracBits,
                                                    QuadBits, QuadFracBits, SquareBits, 1, 0,
                                                    1, 0, FfcFracBits);
  localparam int unsigned AFracBits = core_frac(Kind, NShift, GainFracBits, OffsetFracBits, 0,
                                                0, 0);
  localparam int unsigned ASumBits  = core_sum_bits(Kind, AccBits, 1'b0, NShift, AdcBits,
                                                    GainBits, GainFracBits, OffsetBits,
                                                    OffsetFracBits, QuadBits, QuadFracBits,
                                                    SquareBits, 1, 0, 1, 0, 0);
  localparam int unsigned Latency   = max2(
      core_sum_latency(Kind, AdcBits, 1'b0, 0, AdcBits, GainBits, QuadBits, SquareBits, 1, 0),
      core_sum_latency(Kind, AccBits, 1'b0, NShift, AdcBits, GainBits, QuadBits, SquareBits,
                       1, 0));
  // ffc_refresh and the mean's v: F' = max(F_acc, Cf).
  localparam int unsigned RFrac     = max2(AFracBits, FfcFracBits);
  localparam int unsigned RShift    = RFrac - FfcFracBits;
  localparam int unsigned SxBits    = ASumBits + RFrac - AFracBits;
  localparam int unsigned VBits     = SxBits + 1 - RShift;
  localparam int unsigned NBits     = $clog2(MaxWidth * MaxHeight + 1);
  // s + (c << (F - Cf)).
  localparam int unsigned TotBits   = max2(SumBits, CBits + FracBits - FfcFracBits) + 1;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (ffc_composes(Method))
      else $fatal(1, "method_ffc_top: Method = %0d; the RTL composes ffc with %s", Method,
                  "the methods of irnuc_method_pkg::ffc_composes");
    assert (MaxWidth >= 1 && MaxWidth <= 65535 && MaxHeight >= 1 && MaxHeight <= 65535)
      else $fatal(1, "method_ffc_top: MaxWidth = %0d, MaxHeight = %0d outside 1..65535",
                  MaxWidth, MaxHeight);
    assert (FfcRounding <= 2 && FfcOverflow <= 1 && FfcIntBits >= 1)
      else $fatal(1, "method_ffc_top: FfcRounding, FfcOverflow or FfcIntBits out of range");
    assert (TotBits <= 62)
      else $fatal(1, "method_ffc_top: the sum of %0d bits exceeds the limit", TotBits);
  end
`endif

  // ---- input registers ----------------------------------------------------------------------
  logic                 pix_valid, pix_ready, pix_sof, pix_eol, pix_shutter;
  logic [AdcBits-1:0]   pix_data;
  logic [FrameBits-1:0] pix_frame;
  logic                 coef_valid, coef_ready;
  logic [CoefBits-1:0]  coef;
  logic                 foff_valid, foff_ready;
  logic [CBits-1:0]     foff_in;
  logic                 acc_valid, acc_ready;
  logic [AccBits-1:0]   acc_in;

  irnuc_spill_register #(.DataBits(FrameBits + AdcBits + 3)) u_pix_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_pix_valid_i),
    .ready_o(s_pix_ready_o),
    .data_i ({s_pix_shutter_i, s_pix_frame_i, s_pix_sof_i, s_pix_eol_i, s_pix_data_i}),
    .valid_o(pix_valid),
    .ready_i(pix_ready),
    .data_o ({pix_shutter, pix_frame, pix_sof, pix_eol, pix_data})
  );

  irnuc_axis_buffer #(.DataBits(CoefBits)) u_coef_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_coef_valid_i),
    .ready_o(s_coef_ready_o),
    .data_i (s_coef_data_i),
    .valid_o(coef_valid),
    .ready_i(coef_ready),
    .data_o (coef)
  );

  irnuc_axis_buffer #(.DataBits(CBits)) u_foff_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_foff_valid_i),
    .ready_o(s_foff_ready_o),
    .data_i (s_foff_data_i),
    .valid_o(foff_valid),
    .ready_i(foff_ready),
    .data_o (foff_in)
  );

  irnuc_axis_buffer #(.DataBits(AccBits)) u_acc_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_acc_valid_i),
    .ready_o(s_acc_ready_o),
    .data_i (s_acc_data_i),
    .valid_o(acc_valid),
    .ready_i(acc_ready),
    .data_o (acc_in)
  );

  // ---- the pixel stage: the frame's mode and word decided as the pixel enters ----------------
  // A second spill register after the pixel's input register. As a pixel enters it, it takes
  // its frame's mode and word (a frame's first pixel from ffc_ctrl and s_pix_frame_i, which
  // are then kept in mode_q / frame_q for the frame's other pixels) and whether it reads
  // s_acc and waits for the target. The join below then waits on flops only (the valid
  // flags, the pixel's mode and its wait, the target), and the pixel's input register moves on this register's
  // ready (a flop), not on the join.
  logic      en, join_valid, join_take;
  ffc_mode_t ctrl_mode, mode_q, mode_e;
  logic [FrameBits-1:0] frame_q, frame_e;
  logic      tgt_e, px_enter;

  assign px_enter = pix_valid && pix_ready;
  assign mode_e   = pix_sof ? ctrl_mode : mode_q;
  assign frame_e  = pix_sof ? pix_frame : frame_q;
  assign tgt_e    = pix_sof && ctrl_mode.refresh;

  ffc_ctrl #(
    .FfcFrames(FfcFrames),
    .Hold     (FfcHold != 0)
  ) u_ctrl (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .shutter_i(pix_shutter),
    .take_i   (px_enter && pix_sof),
    .mode_o   (ctrl_mode)
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_frame
    if (!rst_ni) begin
      frame_q <= '0;
      mode_q  <= '0;
    end else if (px_enter && pix_sof) begin
      frame_q <= pix_frame;
      mode_q  <= ctrl_mode;
    end
  end

  logic                 px_valid, px_sof, px_eol, px_tgt;
  logic [AdcBits-1:0]   px_data;
  ffc_mode_t            px_mode;
  logic [FrameBits-1:0] px_frame;

  // The mode and the wait on top, from the buffer's head register: the join decides on
  // them (need_acc, need_target), so they come from flops, not through the read pointer's
  // multiplexer (tcffc14's join was 4-5 LUTs deep from the buffers' flags).
  irnuc_axis_buffer #(
    .DataBits(FrameBits + $bits(ffc_mode_t) + AdcBits + 3),
    .HeadBits($bits(ffc_mode_t) + 1)
  ) u_px (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(pix_valid),
    .ready_o(pix_ready),
    .data_i ({mode_e, tgt_e, frame_e, pix_sof, pix_eol, pix_data}),
    .valid_o(px_valid),
    .ready_i(join_take),
    .data_o ({px_mode, px_tgt, px_frame, px_sof, px_eol, px_data})
  );

  // ---- ffc_mean: the target; the division starts when a refresh frame's first pixel waits
  // and every pixel of the mean frame has been summed (none in flight between the join and
  // ffc_mean). At most Latency + 4 pixels sit between the join and ffc_mean, and tc_poly's
  // (below 32).
  logic                    mean_valid, mean_good, target_valid, target_ready, target_empty;
  logic [TBits-1:0]        target;
  logic signed [VBits-1:0] mean_v;

  ffc_mean #(
    .VBits    (VBits),
    .NBits    (NBits),
    .TBits    (TBits),
    .MaxFlight(Latency + 39)
  ) u_mean (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .enter_i       (join_take && px_mode.mean),
    .valid_i       (mean_valid),
    .good_i        (mean_good),
    .v_i           (mean_v),
    .request_i     (px_valid && px_tgt),
    .frame_taken_i (join_take && px_sof),
    .ready_o       (target_ready),
    .target_valid_o(target_valid),
    .target_o      (target),
    .empty_o       (target_empty)
  );

  assign ffc_target_valid_o = target_valid;
  assign ffc_target_o       = target;
  assign ffc_kept_o         = target_empty;

  // ---- join: a pixel, its words and (in the frames that read it) its accumulator ----------
  logic need_acc, need_target, join_ready;

  assign need_acc    = px_mode.acc_rd;
  assign need_target = px_tgt;
  assign join_valid  = px_valid && coef_valid && foff_valid && (!need_acc || acc_valid)
                       && (!need_target || target_ready);
  assign join_take   = join_valid && join_ready;
  assign coef_ready  = join_take;
  assign foff_ready  = join_take;
  assign acc_ready   = join_take && need_acc;

  // ---- the front: the frame's coefficients of the pixel (tc_poly for tc_offset) ------------
  // The pixel's side band: {x, the accumulator read, the correction read, acc_first, mean,
  // refresh, write, hold, sof, eol} and the pixel's bad flag from its word.
  localparam int unsigned Pass = AdcBits + AccBits + CBits + 7;

  logic [Pass-1:0]       join_pass;
  logic [Pass:0]         f_pass;
  logic                  f_valid;
  logic [GainBits-1:0]   f_gain, f_gain_hi;
  logic [OffsetBits-1:0] f_offset;
  logic [QuadBits-1:0]   f_quad;
  logic [KneeBits-1:0]   f_knee;
  logic [LevelBits-1:0]  f_level;

  assign join_pass = {px_data, acc_in, foff_in, px_mode.acc_first, px_mode.mean,
                      px_mode.refresh, px_mode.acc_first || px_mode.acc_add, px_mode.hold,
                      px_sof, px_eol};

  frame_coefficients #(
    // irnuc-params: forward frame_coefficients (generated from nuc_fixed.methods; do not edit)
    .Method           (Method),
    .GainIntBits      (GainIntBits),
    .GainFracBits     (GainFracBits),
    .OffsetIntBits    (OffsetIntBits),
    .OffsetFracBits   (OffsetFracBits),
    .KneeIntBits      (KneeIntBits),
    .KneeFracBits     (KneeFracBits),
    .LevelIntBits     (LevelIntBits),
    .LevelFracBits    (LevelFracBits),
    .QuadIntBits      (QuadIntBits),
    .QuadFracBits     (QuadFracBits),
    .Rounding         (Rounding),
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
    // irnuc-params: end
    .UserBits(Pass)
  ) u_front (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .s_valid_i  (join_valid),
    .s_ready_o  (join_ready),
    .s_coef_i   (coef),
    .s_frame_i  (px_frame),
    .s_user_i   (join_pass),
    .m_valid_o  (f_valid),
    .m_ready_i  (en),
    .m_gain_o   (f_gain),
    .m_gain_hi_o(f_gain_hi),
    .m_offset_o (f_offset),
    .m_quad_o   (f_quad),
    .m_knee_o   (f_knee),
    .m_level_o  (f_level),
    .m_user_o   (f_pass)
  );
  // The sums of the kinds ffc composes with take gain, offset and quad (ffc_sums).
  logic unused_front;
  assign unused_front = ^{f_gain_hi, f_knee, f_level};

  // ---- stage 1 and the two sums: the pixel's (s) and the accumulator's (sa) ----------------
  // Beside the sums: {mean, refresh, write, hold, the correction read, sof, eol, bad}.
  localparam int unsigned Side = 7 + CBits;

  logic [AdcBits-1:0]  f_x;
  logic [AccBits-1:0]  f_acc, sum_acc_new;
  logic [Side-1:0]     f_side, sum_side;
  logic                f_acc_first, sum_valid;
  logic [SumBits-1:0]  sum_s;
  logic [ASumBits-1:0] asum_s;

  assign {f_x, f_acc, f_side[3 +: CBits], f_acc_first, f_side[Side-1 -: 4], f_side[2:0]}
         = f_pass;

  ffc_sums #(
    .Kind          (32'(Kind)),
    .AdcBits       (AdcBits),
    .NShift        (NShift),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .QuadIntBits   (QuadIntBits),
    .QuadFracBits  (QuadFracBits),
    .SquareBits    (SquareBits),
    .FfcFracBits   (FfcFracBits),
    .Latency       (Latency),
    .SideBits      (Side),
    .AddBehind     (!front_registered(Method))
  ) u_sums (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en),
    .valid_i  (f_valid),
    .x_i      (f_x),
    .acc_i    (f_acc),
    .first_i  (f_acc_first),
    .refresh_i(f_side[Side-2]),
    .gain_i   (f_gain),
    .offset_i (f_offset),
    .quad_i   (f_quad),
    .side_i   (f_side),
    .valid_o  (sum_valid),
    .sum_o    (sum_s),
    .asum_o   (asum_s),
    .acc_new_o(sum_acc_new),
    .side_o   (sum_side)
  );

  // ---- ffc_refresh: dc and the mean's v on sa; the pixel's correction c (written back) ------
  // Beside: {s, mean, write, hold, acc_new, sof, eol, bad}.
  localparam int unsigned RSide = SumBits + AccBits + 6;

  logic                 v_valid, c_valid, c_refresh;
  logic [RSide-1:0]     v_side, c_side;
  logic [CBits-1:0]     c_c;
  logic [SumBits-1:0]   c_sum;
  logic [AccBits-1:0]   c_acc;
  logic                 c_write, c_hold, c_sof, c_eol, c_bad, c_mean;

  ffc_refresh #(
    .SumBits    (ASumBits),
    .SumFracBits(AFracBits),
    .OutBits    (OutBits),
    .FfcIntBits (FfcIntBits),
    .FfcFracBits(FfcFracBits),
    .FfcRounding(FfcRounding),
    .FfcOverflow(FfcOverflow),
    .SideBits   (RSide)
  ) u_refresh (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en),
    .valid_i  (sum_valid),
    .sum_i    (asum_s),
    .target_i (target),
    .refresh_i(sum_side[Side-2]),
    .keep_i   (target_empty),
    .c_i      (sum_side[3 +: CBits]),
    .side_i   ({sum_s, sum_side[Side-1], sum_side[Side-3 -: 2], sum_acc_new, sum_side[2:0]}),
    .v_valid_o(v_valid),
    .v_o      (mean_v),
    .v_side_o (v_side),
    .valid_o  (c_valid),
    .refresh_o(c_refresh),
    .c_o      (c_c),
    .side_o   (c_side)
  );

  assign mean_valid = en && v_valid && v_side[AccBits + 5];
  assign mean_good  = !v_side[0];
  assign {c_sum, c_mean, c_write, c_hold, c_acc, c_sof, c_eol, c_bad} = c_side;

  logic unused_side;
  assign unused_side = ^{v_side[RSide-1:AccBits + 6], v_side[AccBits + 4:1], c_mean};

  // ---- stage T: the FFC term added ---------------------------------------------------------
  logic                t_valid_q;
  logic [TotBits-1:0]  t_sum_q;
  localparam int unsigned User = 6 + AccBits + CBits;  // {hold, write, acc, refresh, c, sof, eol, bad}
  logic [User-1:0]     t_user_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_t_valid
    if (!rst_ni) begin
      t_valid_q <= 1'b0;
    end else if (en) begin
      t_valid_q <= c_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_t
    if (en) begin
      t_sum_q  <= TotBits'($signed(c_sum))
                  + (TotBits'($signed(c_c)) << (FracBits - FfcFracBits));
      t_user_q <= {c_hold, c_write, c_acc, c_refresh, c_c, c_sof, c_eol, c_bad};
    end
  end

  // ---- ROUND and OUT, then the fork: DPC, m_acc, m_foff ----------------------------------------
  logic               out_valid, out_ready;
  logic [OutBits-1:0] out_data;
  logic [User-1:0]    out_user;

  core_out #(
    .SumBits (TotBits),
    .FracBits(FracBits),
    .OutBits (OutBits),
    .Rounding(Rounding),
    .Overflow(Overflow),
    .UserBits(User)
  ) u_out (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_o     (en),
    .valid_i  (t_valid_q),
    .sum_i    (t_sum_q),
    .user_i   (t_user_q),
    .m_valid_o(out_valid),
    .m_ready_i(out_ready),
    .m_data_o (out_data),
    .m_user_o (out_user)
  );

  logic               o_hold, o_write, o_refresh, o_sof, o_eol, o_bad;
  logic [AccBits-1:0] o_acc;
  logic [CBits-1:0]   o_c;

  assign {o_hold, o_write, o_acc, o_refresh, o_c, o_sof, o_eol, o_bad} = out_user;

  // A stream fork: the item leaves once every destination it goes to has taken it.
  logic [2:0] need, dest_valid, dest_ready, sent_q;

  assign need       = {o_refresh, o_write, !o_hold};  // {foff, acc, pix}
  assign dest_valid = {3{out_valid}} & need & ~sent_q;
  assign out_ready  = &(~need | sent_q | dest_ready);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_fork
    if (!rst_ni) begin
      sent_q <= '0;
    end else if (out_valid && out_ready) begin
      sent_q <= '0;
    end else begin
      sent_q <= sent_q | (dest_valid & dest_ready);
    end
  end

  irnuc_spill_register #(.DataBits(AccBits)) u_acc_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(dest_valid[1]),
    .ready_o(dest_ready[1]),
    .data_i (o_acc),
    .valid_o(m_acc_valid_o),
    .ready_i(m_acc_ready_i),
    .data_o (m_acc_data_o)
  );

  irnuc_spill_register #(.DataBits(CBits)) u_foff_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(dest_valid[2]),
    .ready_o(dest_ready[2]),
    .data_i (o_c),
    .valid_o(m_foff_valid_o),
    .ready_i(m_foff_ready_i),
    .data_o (m_foff_data_o)
  );

  // ---- DPC ---------------------------------------------------------------------------------
  dpc_tail #(
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
    .s_valid_i     (dest_valid[0]),
    .s_ready_o     (dest_ready[0]),
    .s_pix_data_i  (out_data),
    .s_bad_i       (o_bad),
    .s_sof_i       (o_sof),
    .s_eol_i       (o_eol),
    .m_valid_o     (m_pix_valid_o),
    .m_ready_i     (m_pix_ready_i),
    .m_pix_data_o  (m_pix_data_o),
    .m_sof_o       (m_pix_sof_o),
    .m_eol_o       (m_pix_eol_o),
    .frame_err_o   (frame_err_o)
  );

`ifdef IRNUC_ASSERT
  // Protocol assertions of every stream port: in the input and output registers
  // (irnuc_spill_register) and u_dpc.u_out, whose ports these are, but s_coef, s_foff and
  // s_acc (their irnuc_axis_buffer checks its output side only): here (the frame size at a
  // frame start: in u_tail).
  irnuc_stream_assert #(.DataBits(CoefBits)) u_assert_coef (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_coef_valid_i),
    .ready_i(s_coef_ready_o),
    .data_i (s_coef_data_i)
  );
  irnuc_stream_assert #(.DataBits(CBits)) u_assert_foff (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_foff_valid_i),
    .ready_i(s_foff_ready_o),
    .data_i (s_foff_data_i)
  );
  irnuc_stream_assert #(.DataBits(AccBits)) u_assert_acc (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_acc_valid_i),
    .ready_i(s_acc_ready_o),
    .data_i (s_acc_data_i)
  );
`endif

endmodule
