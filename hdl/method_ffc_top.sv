// FFC composition top: one_point, two_point, quadratic or tc_offset with the shutter offset refresh,
// then the DPC (docs/datapath.md "ffc"; docs/rtl.md "Stages"; nuc_fixed.method_top for a
// method "<base>+ffc").
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
//   m_foff   the new FFC offset correction of every pixel, in the refresh frame (the frame
//            after the N-th shutter frame): written back to ffc_offset, read from the next
//            frame on (the refresh frame itself uses them already, as the golden model);
//   m_pix    corrected pixels with sof/eol, of every frame but a held one (ffc_output
//            hold: a shutter frame once an open frame was output; the display keeps the
//            last open frame).
// Per pixel: the base method's sum on the raw code (core_sum, F = max(.., Cf)) beside the
// same sum on the accumulator (core_sum, Xf = n, the refresh and mean passes); then
//   dc = OVF_C(ROUND_(F' - Cf)((T << (F' - Cf)) - (s_acc << (F' - F_acc))))   (ffc_refresh)
//   v  = ROUND_(F' - Cf)(s_acc << (F' - F_acc))                             (ffc_mean)
//   y  = OUT(ROUND_F(s + (c << (F - Cf)))),  c = dc in a refresh frame, else s_foff
// and the DPC. The mean frame's v over good pixels give the target T (ffc_mean, one
// division, before the refresh frame's first pixel is taken; ffc_target_o).
// One pixel per clock, no bubbles, but for the division: a refresh frame's first pixel
// waits for the target (NumBits + 3 cycles after the mean frame's last pixel).
module method_ffc_top
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
  import irnuc_stage_pkg::*;
#(
  parameter int unsigned Method         = 1,  // irnuc_pkg::method_e: 0, 1, 3 or 4
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow       = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned MaxWidth       = 1024,
  parameter int unsigned MaxHeight      = 1024,
  parameter int unsigned QuadIntBits    = 10,
  parameter int unsigned QuadFracBits   = 6,
  parameter int unsigned SquareBits     = 18,
  parameter int unsigned Tc1IntBits     = 13,
  parameter int unsigned Tc1FracBits    = 3,
  parameter int unsigned Tc2IntBits     = 12,
  parameter int unsigned Tc2FracBits    = 4,
  parameter int unsigned Tg1IntBits     = 2,
  parameter int unsigned Tg1FracBits    = 14,
  parameter int unsigned Tg2IntBits     = 2,
  parameter int unsigned Tg2FracBits    = 14,
  parameter int unsigned TcOrder        = 2,
  parameter int unsigned TcGain         = 0,
  parameter int unsigned ReadingBits    = 14,
  parameter int unsigned ReadingRangeBits = 11,
  parameter int unsigned FfcFrames      = 8,
  parameter int unsigned FfcHold        = 1,  // ffc_output: 1 hold, 0 pass
  parameter int unsigned FfcIntBits     = 12,
  parameter int unsigned FfcFracBits    = 4,
  parameter int unsigned FfcRounding    = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned FfcOverflow    = 0,  // irnuc_pkg::overflow_e
  // Derived, do not override.
  localparam method_e     MethodSel     = method_e'(Method),
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned QuadBits      = QuadIntBits + QuadFracBits,
  localparam int unsigned TcWordBits    = Tc1IntBits + Tc1FracBits
                                          + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned TgWordBits    = (TcGain != 0) ? Tg1IntBits + Tg1FracBits
                                          + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0)
                                                        : 0,
  localparam int unsigned CoefBits      = coef_stream_bits(MethodSel, GainBits, OffsetBits,
                                                           1, QuadBits, TcWordBits,
                                                           TgWordBits),
  localparam int unsigned FrameBits     = frame_word_bits(MethodSel, GainBits, 1, ReadingBits,
                                                          1),
  localparam int unsigned NShift        = $clog2(FfcFrames),
  localparam int unsigned AccBits       = AdcBits + NShift,
  localparam int unsigned CBits         = FfcIntBits + FfcFracBits,
  localparam int unsigned TBits         = OutBits + FfcFracBits,
  localparam int unsigned WidthBits     = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits    = $clog2(MaxHeight + 1)
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
  // The last FFC target (register ffc_target, U B.Cf) and whether one was taken.
  output logic                  ffc_target_valid_o,
  output logic [TBits-1:0]      ffc_target_o,
  // Sticky framing error (see dpc_core).
  output logic                  frame_err_o
);

  localparam core_kind_e  Kind      = core_kind(MethodSel);
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
  localparam int unsigned DiffBits  = max2(TBits + 1 + RShift, SxBits) + 1;
  localparam int unsigned VBits     = SxBits + 1 - RShift;
  localparam int unsigned NBits     = $clog2(MaxWidth * MaxHeight + 1);
  // s + (c << (F - Cf)).
  localparam int unsigned TotBits   = max2(SumBits, CBits + FracBits - FfcFracBits) + 1;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MethodSel == MethodOnePoint || MethodSel == MethodTwoPoint
            || MethodSel == MethodQuadratic || MethodSel == MethodTcOffset)
      else $fatal(1, "method_ffc_top: Method = %0d; the RTL composes ffc with one_point (0), two_point (1), quadratic (3) and tc_offset (4)",
                  Method);
    assert (MaxWidth >= 1 && MaxWidth <= 65535 && MaxHeight >= 1 && MaxHeight <= 65535)
      else $fatal(1, "method_ffc_top: MaxWidth = %0d, MaxHeight = %0d outside 1..65535",
                  MaxWidth, MaxHeight);
    assert (FfcHold <= 1 && FfcRounding <= 2 && FfcOverflow <= 1 && FfcIntBits >= 1)
      else $fatal(1, "method_ffc_top: FfcHold, FfcRounding, FfcOverflow or FfcIntBits out of range");
    assert (TotBits <= 62 && DiffBits <= 64)
      else $fatal(1, "method_ffc_top: sums of %0d and %0d bits exceed the limits", TotBits,
                  DiffBits);
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

  irnuc_axis_buffer #(.DataBits(FrameBits + $bits(ffc_mode_t) + AdcBits + 3)) u_px (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(pix_valid),
    .ready_o(pix_ready),
    .data_i ({frame_e, mode_e, tgt_e, pix_sof, pix_eol, pix_data}),
    .valid_o(px_valid),
    .ready_i(join_take),
    .data_o ({px_frame, px_mode, px_tgt, px_sof, px_eol, px_data})
  );

  // The division starts when a refresh frame's first pixel waits and every pixel of the
  // mean frame has been summed (none in flight between the join and ffc_mean).
  // At most Latency + 4 pixels sit between the join and ffc_mean, and tc_poly's (below 32).
  localparam int unsigned FlightBits = $clog2(Latency + 40);

  logic                  mean_valid, target_valid, div_busy, started_q, start;
  logic [FlightBits-1:0] flight_q;
  // flight_q == 0 as a flop of its own (start drives ffc_mean's wide enables), set from
  // flight_q's compares and the count's steps, not from the next count (the join's take
  // would then pass the adder and a compare).
  logic                  flight_zero_q, flight_one, flight_in, flight_out;
  logic [TBits-1:0]      target;
  logic signed [VBits-1:0] mean_v;
  logic                  mean_good;

  assign start      = px_valid && px_tgt && !started_q && flight_zero_q;
  assign flight_in  = join_take && px_mode.mean;
  assign flight_out = mean_valid;
  assign flight_one = flight_q == FlightBits'(1);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_flight
    if (!rst_ni) begin
      flight_q      <= '0;
      flight_zero_q <= 1'b1;
      started_q     <= 1'b0;
    end else begin
      flight_q      <= flight_q + FlightBits'(flight_in) - FlightBits'(flight_out);
      flight_zero_q <= (flight_zero_q && flight_in == flight_out)
                       || (flight_one && flight_out && !flight_in);
      if (start) begin
        started_q <= 1'b1;
      end else if (join_take && px_sof) begin
        started_q <= 1'b0;
      end
    end
  end

  ffc_mean #(
    .VBits(VBits),
    .NBits(NBits),
    .TBits(TBits)
  ) u_mean (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .valid_i       (mean_valid),
    .good_i        (mean_good),
    .v_i           (mean_v),
    .start_i       (start),
    .busy_o        (div_busy),
    .target_valid_o(target_valid),
    .target_o      (target)
  );

  logic unused_div_busy;
  assign unused_div_busy = div_busy;
  assign ffc_target_valid_o = target_valid;
  assign ffc_target_o       = target;

  // ---- join: a pixel, its words and (in the frames that read it) its accumulator ----------
  logic need_acc, need_target, join_ready;

  assign need_acc    = px_mode.acc_rd;
  assign need_target = px_tgt;
  assign join_valid  = px_valid && coef_valid && foff_valid && (!need_acc || acc_valid)
                       && (!need_target || (started_q && target_valid));
  assign join_take   = join_valid && join_ready;
  assign coef_ready  = join_take;
  assign foff_ready  = join_take;
  assign acc_ready   = join_take && need_acc;

  logic [FrameBits-1:0] frame;

  assign frame = px_frame;

  // ---- the front: the frame's coefficients of the pixel ----------------------------------------
  // The pixel's side band: {x, the accumulator read, the correction read, acc_first, mean,
  // refresh, write, hold, sof, eol, bad}. The new accumulator (x or acc + x) is summed
  // behind the front (tc_poly's output register for tc_offset), not on the input
  // registers' read multiplexers.
  localparam int unsigned Pass = AdcBits + AccBits + CBits + 8;

  logic [Pass-1:0]       join_pass, f_pass;
  logic                  f_valid;
  logic [GainBits-1:0]   f_gain;
  logic [OffsetBits-1:0] f_offset;
  logic [QuadBits-1:0]   f_quad;
  logic                  bad;

  assign join_pass = {px_data, acc_in, foff_in, px_mode.acc_first, px_mode.mean,
                      px_mode.refresh, px_mode.acc_first || px_mode.acc_add, px_mode.hold,
                      px_sof, px_eol, bad};

  if (MethodSel == MethodTcOffset) begin : gen_tc_offset
    // coeffs: gain, offset (c0), bad | tc: tc1[, tc2] | tg: tg1[, tg2]; frame: reading,
    // t_ref. tc_poly gives the frame's gain and offset of the pixel (a stream stage).
    localparam int unsigned TwoPointBits = coef_word_bits(GainBits, OffsetBits);
    coef_word#(GainBits, OffsetBits)::word_t     coeffs;
    frame_tc_offset#(ReadingBits)::word_t        fw;
    logic [((TcGain != 0) ? TgWordBits : 1)-1:0] tg;
    assign coeffs = coef[TwoPointBits-1:0];
    assign fw     = frame;
    assign bad    = coeffs.bad;
    assign f_quad = '0;
    if (TcGain != 0) begin : gen_tg
      assign tg = coef[TwoPointBits + TcWordBits +: TgWordBits];
    end else begin : gen_no_tg
      assign tg = 1'b0;
    end

    tc_poly #(
      .GainIntBits     (GainIntBits),
      .GainFracBits    (GainFracBits),
      .OffsetIntBits   (OffsetIntBits),
      .OffsetFracBits  (OffsetFracBits),
      .Tc1IntBits      (Tc1IntBits),
      .Tc1FracBits     (Tc1FracBits),
      .Tc2IntBits      (Tc2IntBits),
      .Tc2FracBits     (Tc2FracBits),
      .Tg1IntBits      (Tg1IntBits),
      .Tg1FracBits     (Tg1FracBits),
      .Tg2IntBits      (Tg2IntBits),
      .Tg2FracBits     (Tg2FracBits),
      .TcOrder         (TcOrder),
      .TcGain          (TcGain != 0),
      .ReadingBits     (ReadingBits),
      .ReadingRangeBits(ReadingRangeBits),
      .Rounding        (Rounding),
      .UserBits        (Pass)
    ) u_coef (
      .clk_i      (clk_i),
      .rst_ni     (rst_ni),
      .s_valid_i  (join_valid),
      .s_ready_o  (join_ready),
      .s_reading_i(fw.reading),
      .s_t_ref_i  (fw.t_ref),
      .s_gain_i   (coeffs.gain),
      .s_offset_i (coeffs.offset),
      .s_tc_i     (coef[TwoPointBits +: TcWordBits]),
      .s_tg_i     (tg),
      .s_user_i   (join_pass),
      .m_valid_o  (f_valid),
      .m_ready_i  (en),
      .m_gain_o   (f_gain),
      .m_offset_o (f_offset),
      .m_user_o   (f_pass)
    );
  end else begin : gen_direct
    // The pixel's words go straight to stage 1.
    assign f_valid    = join_valid;
    assign join_ready = en;
    assign f_pass     = join_pass;
    if (MethodSel == MethodOnePoint) begin : gen_one_point
      // coeffs: offset, bad; the gain is the frame's register.
      coef_one_point#(OffsetBits)::word_t w;
      assign w        = coef;
      assign f_gain   = frame[GainBits-1:0];
      assign f_offset = w.offset;
      assign bad      = w.bad;
      assign f_quad   = '0;
    end else if (MethodSel == MethodQuadratic) begin : gen_quadratic
      // coeffs: gain, offset, bad | quad: quad.
      typedef struct packed {
        quad_word#(QuadBits)::word_t             quad;
        coef_word#(GainBits, OffsetBits)::word_t coeffs;
      } stream_t;
      stream_t w;
      assign w        = coef;
      assign f_gain   = w.coeffs.gain;
      assign f_offset = w.coeffs.offset;
      assign bad      = w.coeffs.bad;
      assign f_quad   = w.quad.quad;
      logic unused_frame;
      assign unused_frame = ^frame;
    end else begin : gen_two_point
      // coeffs: gain, offset, bad.
      coef_word#(GainBits, OffsetBits)::word_t w;
      assign w        = coef;
      assign f_gain   = w.gain;
      assign f_offset = w.offset;
      assign bad      = w.bad;
      assign f_quad   = '0;
      logic unused_frame;
      assign unused_frame = ^frame;
    end
  end

  // ---- stage 1: the new accumulator, acc_new = x (a run's first frame) or acc + x ----------
  localparam int unsigned Side = 6 + AccBits + CBits;  // {mean, refresh, write, hold, acc, foff, sof, eol}

  logic [AdcBits-1:0] f_x;
  logic [AccBits-1:0] f_acc, acc_new;
  logic [CBits-1:0]   f_foff;
  logic [6:0]         f_flags;  // {mean, refresh, write, hold, sof, eol, bad}
  logic               f_acc_first;

  assign {f_x, f_acc, f_foff, f_acc_first, f_flags} = f_pass;
  assign acc_new = f_acc_first ? AccBits'(f_x) : f_acc + AccBits'(f_x);

  logic                  s1_valid_q;
  logic [AdcBits-1:0]    s1_x_q;
  logic [AccBits-1:0]    s1_acc_q, s1_acc_new_q;
  logic [GainBits-1:0]   s1_gain_q;
  logic [OffsetBits-1:0] s1_offset_q;
  logic [QuadBits-1:0]   s1_quad_q;
  logic [CBits-1:0]      s1_foff_q;
  logic                  s1_mean_q, s1_refresh_q, s1_write_q, s1_hold_q, s1_sof_q, s1_eol_q;
  logic                  s1_bad_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_s1_valid
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
    end else if (en) begin
      s1_valid_q <= f_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_s1
    if (en) begin
      s1_x_q       <= f_x;
      // The accumulator core sums the read accumulator in the refresh pass, else acc_new.
      s1_acc_q     <= f_flags[5] ? f_acc : acc_new;
      s1_acc_new_q <= acc_new;
      s1_foff_q    <= f_foff;
      {s1_mean_q, s1_refresh_q, s1_write_q, s1_hold_q, s1_sof_q, s1_eol_q, s1_bad_q} <= f_flags;
      s1_gain_q   <= f_gain;
      s1_offset_q <= f_offset;
      s1_quad_q   <= f_quad;
    end
  end
  // ---- the two sums --------------------------------------------------------------------------
  logic               sum_valid, asum_valid;
  logic [SumBits-1:0] sum_s;
  logic [ASumBits-1:0] asum_s;
  logic [Side:0]      sum_side;  // {Side, bad}
  logic               asum_side;

  core_sum #(
    .Kind          (32'(Kind)),
    .XBits         (AdcBits),
    .XSigned       (1'b0),
    .XFracBits     (0),
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .QuadIntBits   (QuadIntBits),
    .QuadFracBits  (QuadFracBits),
    .SquareBits    (SquareBits),
    .MinFracBits   (FfcFracBits),
    .Latency       (Latency),
    .SideBits      (Side + 1)
  ) u_core (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en),
    .valid_i  (s1_valid_q),
    .x_i      (s1_x_q),
    .gain_i   (s1_gain_q),
    .gain_hi_i('0),
    .offset_i (s1_offset_q),
    .quad_i   (s1_quad_q),
    .knee_i   ('0),
    .level_i  ('0),
    .side_i   ({s1_mean_q, s1_refresh_q, s1_write_q, s1_hold_q, s1_acc_new_q, s1_foff_q,
                s1_sof_q, s1_eol_q, s1_bad_q}),
    .valid_o  (sum_valid),
    .sum_o    (sum_s),
    .side_o   (sum_side)
  );

  core_sum #(
    .Kind          (32'(Kind)),
    .XBits         (AccBits),
    .XSigned       (1'b0),
    .XFracBits     (NShift),
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .QuadIntBits   (QuadIntBits),
    .QuadFracBits  (QuadFracBits),
    .SquareBits    (SquareBits),
    .MinFracBits   (0),
    .Latency       (Latency),
    .SideBits      (1)
  ) u_acc_core (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .en_i     (en),
    .valid_i  (s1_valid_q),
    .x_i      (s1_acc_q),
    .gain_i   (s1_gain_q),
    .gain_hi_i('0),
    .offset_i (s1_offset_q),
    .quad_i   (s1_quad_q),
    .knee_i   ('0),
    .level_i  ('0),
    .side_i   (1'b0),
    .valid_o  (asum_valid),
    .sum_o    (asum_s),
    .side_o   (asum_side)
  );

  logic unused_asum;
  assign unused_asum = ^{asum_valid, asum_side};

  // ---- stage D: sa aligned and the refresh's difference ---------------------------------------
  logic [SxBits-1:0]   sx;
  logic [DiffBits-1:0] diff;

  assign sx   = SxBits'($signed(asum_s)) << (RFrac - AFracBits);
  assign diff = (DiffBits'(target) << RShift) - DiffBits'($signed(sx));

  logic                d_valid_q;
  logic [SxBits-1:0]   d_sx_q;
  logic [DiffBits-1:0] d_diff_q;
  logic [SumBits-1:0]  d_sum_q;
  logic [Side:0]       d_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_d_valid
    if (!rst_ni) begin
      d_valid_q <= 1'b0;
    end else if (en) begin
      d_valid_q <= sum_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_d
    if (en) begin
      d_sx_q   <= sx;
      d_diff_q <= diff;
      d_sum_q  <= sum_s;
      d_side_q <= sum_side;
    end
  end

  // ---- stage R: ffc_refresh's ROUND, the mean's v --------------------------------------------
  logic [VBits-1:0]         v_d;
  logic [DiffBits-RShift:0] dr_d;

  irnuc_round #(
    .InBits  (SxBits),
    .FracBits(RShift),
    .Rounding(FfcRounding)
  ) u_round_v (
    .s_i(d_sx_q),
    .r_o(v_d)
  );

  irnuc_round #(
    .InBits  (DiffBits),
    .FracBits(RShift),
    .Rounding(FfcRounding)
  ) u_round_dc (
    .s_i(d_diff_q),
    .r_o(dr_d)
  );

  logic                     r_valid_q;
  logic [SumBits-1:0]       r_sum_q;
  logic [DiffBits-RShift:0] r_dr_q;
  logic [VBits-1:0]         r_v_q;
  logic [Side:0]            r_side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_r_valid
    if (!rst_ni) begin
      r_valid_q <= 1'b0;
    end else if (en) begin
      r_valid_q <= d_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin : p_r
    if (en) begin
      r_sum_q  <= d_sum_q;
      r_dr_q   <= dr_d;
      r_v_q    <= v_d;
      r_side_q <= d_side_q;
    end
  end

  assign mean_valid = en && r_valid_q && r_side_q[Side];
  assign mean_good  = !r_side_q[0];
  assign mean_v     = $signed(r_v_q);

  // ---- stage C: ffc_refresh's OVF, the correction of the pixel ----------------------------
  logic [CBits-1:0] dc_d;

  irnuc_clip #(
    .InBits   (DiffBits + 1 - RShift),
    .OutBits  (CBits),
    .OutSigned(1'b1),
    .Overflow (FfcOverflow)
  ) u_clip_dc (
    .v_i(r_dr_q),
    .y_o(dc_d)
  );

  logic                  c_valid_q;
  logic [SumBits-1:0]    c_sum_q;
  logic [CBits-1:0]      c_c_q, c_dc_q;
  logic [AccBits-1:0]    c_acc_q;
  logic                  c_refresh_q, c_write_q, c_hold_q, c_sof_q, c_eol_q, c_bad_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_c_valid
    if (!rst_ni) begin
      c_valid_q <= 1'b0;
    end else if (en) begin
      c_valid_q <= r_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin : p_c
    if (en) begin
      c_sum_q     <= r_sum_q;
      c_c_q       <= r_side_q[Side-1] ? dc_d : r_side_q[3 +: CBits];
      c_dc_q      <= dc_d;
      c_acc_q     <= r_side_q[3 + CBits +: AccBits];
      c_refresh_q <= r_side_q[Side-1];
      c_write_q   <= r_side_q[Side-2];
      c_hold_q    <= r_side_q[Side-3];
      c_sof_q     <= r_side_q[2];
      c_eol_q     <= r_side_q[1];
      c_bad_q     <= r_side_q[0];
    end
  end

  // ---- stage T: the FFC term added ---------------------------------------------------------
  logic                t_valid_q;
  logic [TotBits-1:0]  t_sum_q;
  localparam int unsigned User = 6 + AccBits + CBits;  // {hold, write, acc, refresh, dc, sof, eol, bad}
  logic [User-1:0]     t_user_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_t_valid
    if (!rst_ni) begin
      t_valid_q <= 1'b0;
    end else if (en) begin
      t_valid_q <= c_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin : p_t
    if (en) begin
      t_sum_q  <= TotBits'($signed(c_sum_q))
                  + (TotBits'($signed(c_c_q)) << (FracBits - FfcFracBits));
      t_user_q <= {c_hold_q, c_write_q, c_acc_q, c_refresh_q, c_dc_q, c_sof_q, c_eol_q,
                   c_bad_q};
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
  logic [CBits-1:0]   o_dc;

  assign {o_hold, o_write, o_acc, o_refresh, o_dc, o_sof, o_eol, o_bad} = out_user;

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
    .data_i (o_dc),
    .valid_o(m_foff_valid_o),
    .ready_i(m_foff_ready_i),
    .data_o (m_foff_data_o)
  );

  // ---- DPC ---------------------------------------------------------------------------------
  dpc_core #(
    .OutBits  (OutBits),
    .MaxWidth (MaxWidth),
    .MaxHeight(MaxHeight)
  ) u_dpc (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .frame_width_i (frame_width_i),
    .frame_height_i(frame_height_i),
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
  // s_acc (their irnuc_axis_buffer checks its output side only): here. Also the frame size
  // at a frame start, and no mean pixel lost by the in-flight count.
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
  irnuc_frame_assert #(
    .MaxWidth (MaxWidth),
    .MaxHeight(MaxHeight)
  ) u_assert_frame (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .start_i (s_pix_valid_i && s_pix_ready_o && s_pix_sof_i),
    .width_i (frame_width_i),
    .height_i(frame_height_i)
  );

  logic armed_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_armed
    if (!rst_ni) begin
      armed_q <= 1'b0;
    end else begin
      armed_q <= 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_flight_range: assert (!(flight_q == '0 && mean_valid))
        else $error("method_ffc_top: a mean pixel summed that was never counted in");
      a_flight_zero: assert (flight_zero_q == (flight_q == '0))
        else $error("method_ffc_top: the in-flight count's zero flag disagrees with it");
      a_flight_room: assert (!(flight_q == '1 && join_take && px_mode.mean && !mean_valid))
        else $error("method_ffc_top: more mean pixels in flight than the count holds");
    end
  end
`endif

endmodule
