// Correction-method pipeline top: the NUC of one base method (parameter Method), then the
// DPC, unchanged (docs/datapath.md "Correction methods", docs/rtl.md "Methods").
//
// Streams (valid/ready; a transfer on a rising edge with both high), each behind its own
// input register (irnuc_spill_register), joined behind them as in nuc_dpc_top:
//   s_pix   raw pixels with sof/eol and the frame word s_pix_frame_i, which is read with
//           the first pixel of every frame (sof) and holds for all of its pixels: the
//           per-frame inputs and registers of the method (irnuc_method_pkg::frame_word_bits:
//           one_point gain, piecewise level, tc_offset {t_ref, reading}, table_interp
//           weight; none for two_point and quadratic);
//   s_coef  one coefficient word per pixel, raster order: the method's calibration memories
//           concatenated (irnuc_method_pkg::coef_stream_bits; table_interp: tables j and
//           j + 1 of the frame);
//   m_pix   corrected pixels with sof/eol.
//
// Per method (one module per golden-model function, nuc_fixed.method_top):
//   one_point     nuc_core, the frame's gain register and the pixel's offset
//   two_point     nuc_core
//   piecewise     pwl_core, the frame's level
//   quadratic     quad_core
//   tc_offset     tc_poly (tc_reading inside) -> nuc_core
//   table_interp  table_interp -> nuc_core (DPC replaces a pixel flagged bad in table j or
//                 in table j + 1, the two the frame interpolates between)
// then dpc_core. One pixel per clock, no bubbles. Latency: 1 + the method's cores +
// dpc_core (docs/rtl.md).
module method_dpc_top
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  parameter int unsigned Method           = 1,  // irnuc_method_pkg::method_e
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
  // Formats and parameters of the methods (docs/datapath.md "Formats"); a method reads
  // only its own.
  parameter int unsigned KneeIntBits      = 14,
  parameter int unsigned KneeFracBits     = 2,
  parameter int unsigned LevelIntBits     = 14,
  parameter int unsigned LevelFracBits    = 4,
  parameter int unsigned QuadIntBits      = 10,
  parameter int unsigned QuadFracBits     = 6,
  parameter int unsigned SquareBits       = 18,
  parameter int unsigned Tc1IntBits       = 13,
  parameter int unsigned Tc1FracBits      = 3,
  parameter int unsigned Tc2IntBits       = 12,
  parameter int unsigned Tc2FracBits      = 4,
  parameter int unsigned Tg1IntBits       = 2,
  parameter int unsigned Tg1FracBits      = 14,
  parameter int unsigned Tg2IntBits       = 2,
  parameter int unsigned Tg2FracBits      = 14,
  parameter int unsigned TcOrder          = 2,
  parameter int unsigned TcGain           = 0,
  parameter int unsigned ReadingBits      = 14,
  parameter int unsigned ReadingRangeBits = 11,
  parameter int unsigned WeightIntBits    = 1,
  parameter int unsigned WeightFracBits   = 15,
  parameter int unsigned WeightRounding   = 1,  // irnuc_pkg::rounding_e
  // Derived, do not override.
  localparam method_e     MethodSel       = method_e'(Method),
  localparam int unsigned GainBits        = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits      = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits        = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits       = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits        = QuadIntBits + QuadFracBits,
  localparam int unsigned TcWordBits      = Tc1IntBits + Tc1FracBits
                                            + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned TgWordBits      = (TcGain != 0) ? Tg1IntBits + Tg1FracBits
                                            + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0)
                                                          : 0,
  localparam int unsigned WeightBits      = WeightIntBits + WeightFracBits,
  localparam int unsigned CoefBits        = coef_stream_bits(MethodSel, GainBits, OffsetBits,
                                                             KneeBits, QuadBits, TcWordBits,
                                                             TgWordBits),
  localparam int unsigned FrameBits       = frame_word_bits(MethodSel, GainBits, LevelBits,
                                                            ReadingBits, WeightBits),
  localparam int unsigned WidthBits       = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits      = $clog2(MaxHeight + 1)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Run-time frame size, 1..MaxWidth x 1..MaxHeight.
  input  logic [WidthBits-1:0]  frame_width_i,
  input  logic [HeightBits-1:0] frame_height_i,
  // Raw pixels in, with the frame word (read at sof).
  input  logic                  s_pix_valid_i,
  output logic                  s_pix_ready_o,
  input  logic [AdcBits-1:0]    s_pix_data_i,
  input  logic                  s_pix_sof_i,
  input  logic                  s_pix_eol_i,
  input  logic [FrameBits-1:0]  s_pix_frame_i,
  // Coefficient words in.
  input  logic                  s_coef_valid_i,
  output logic                  s_coef_ready_o,
  input  logic [CoefBits-1:0]   s_coef_data_i,
  // Corrected pixels out.
  output logic                  m_pix_valid_o,
  input  logic                  m_pix_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic                  m_pix_sof_o,
  output logic                  m_pix_eol_o,
  // Sticky framing error (see dpc_core).
  output logic                  frame_err_o
);

  // The memory words (irnuc_pkg, generated from the spec): the two-point word, and where
  // the next memory starts in a coefficient word that begins with it.
  typedef coef_word#(GainBits, OffsetBits)::word_t coef_word_t;
  localparam int unsigned TwoPointBits = coef_word_bits(GainBits, OffsetBits);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (Method <= 32'(MethodTableInterp))
      else $fatal(1, "method_dpc_top: Method = %0d outside 0..%0d", Method,
                  32'(MethodTableInterp));
    assert (MaxWidth >= 1 && MaxWidth <= 65535)
      else $fatal(1, "method_dpc_top: MaxWidth = %0d outside 1..65535", MaxWidth);
    assert (MaxHeight >= 1 && MaxHeight <= 65535)
      else $fatal(1, "method_dpc_top: MaxHeight = %0d outside 1..65535", MaxHeight);
    assert (TcGain <= 1)
      else $fatal(1, "method_dpc_top: TcGain = %0d outside 0..1", TcGain);
    assert (MethodSel != MethodTableInterp || WeightIntBits >= 1)
      else $fatal(1, "method_dpc_top: the weight format needs an integer bit (w = 1)");
  end
`endif

  // ---- input registers -----------------------------------------------------------------
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

  // ---- join: a pixel and its word move together -------------------------------------
  logic core_ready, join_valid, join_take;

  assign join_valid = pix_valid && coef_valid;
  assign pix_ready  = core_ready && coef_valid;
  assign coef_ready = core_ready && pix_valid;
  assign join_take  = join_valid && core_ready;

  // ---- the frame word: the first pixel's, held for the rest of the frame --------------
  logic [FrameBits-1:0] frame_q, frame;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_frame
    if (!rst_ni) begin
      frame_q <= '0;
    end else if (join_take && pix_sof) begin
      frame_q <= pix_frame;
    end
  end

  assign frame = pix_sof ? pix_frame : frame_q;

  // ---- the method's NUC -------------------------------------------------------------
  logic               nuc_valid, nuc_ready;
  logic [OutBits-1:0] nuc_data;
  logic [2:0]         nuc_user;  // {sof, eol, bad}

  // A core that forms gain and offset per frame (tc_poly, table_interp) hands them to a
  // nuc_core with the raw code and the markers as side band.
  localparam int unsigned PassBits = AdcBits + 3;  // {raw, sof, eol, bad}

  if (MethodSel == MethodOnePoint || MethodSel == MethodTwoPoint) begin : gen_linear
    logic [GainBits-1:0]   gain;
    logic [OffsetBits-1:0] offset;
    logic                  bad;
    if (MethodSel == MethodOnePoint) begin : gen_one_point
      // coeffs: offset, bad; the gain is the frame's register.
      coef_one_point#(OffsetBits)::word_t w;
      assign w      = coef;
      assign gain   = frame[GainBits-1:0];
      assign offset = w.offset;
      assign bad    = w.bad;
    end else begin : gen_two_point
      // coeffs: gain, offset, bad.
      coef_word_t w;
      assign w      = coef;
      assign gain   = w.gain;
      assign offset = w.offset;
      assign bad    = w.bad;
      logic unused_frame;
      assign unused_frame = ^frame;
    end

    nuc_core #(
      .AdcBits       (AdcBits),
      .GainIntBits   (GainIntBits),
      .GainFracBits  (GainFracBits),
      .OffsetIntBits (OffsetIntBits),
      .OffsetFracBits(OffsetFracBits),
      .OutBits       (OutBits),
      .Rounding      (Rounding),
      .Overflow      (Overflow),
      .UserBits      (3)
    ) u_nuc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (join_valid),
      .s_ready_o   (core_ready),
      .s_pix_data_i(pix_data),
      .s_gain_i    (gain),
      .s_offset_i  (offset),
      .s_user_i    ({pix_sof, pix_eol, bad}),
      .m_valid_o   (nuc_valid),
      .m_ready_i   (nuc_ready),
      .m_pix_data_o(nuc_data),
      .m_user_o    (nuc_user)
    );
  end else if (MethodSel == MethodPiecewise) begin : gen_piecewise
    // coeffs: gain_lo, gain_hi, knee, bad; the level is the frame's register.
    coef_piecewise#(GainBits, KneeBits)::word_t w;
    assign w = coef;

    pwl_core #(
      .AdcBits      (AdcBits),
      .GainIntBits  (GainIntBits),
      .GainFracBits (GainFracBits),
      .KneeIntBits  (KneeIntBits),
      .KneeFracBits (KneeFracBits),
      .LevelIntBits (LevelIntBits),
      .LevelFracBits(LevelFracBits),
      .OutBits      (OutBits),
      .Rounding     (Rounding),
      .Overflow     (Overflow),
      .UserBits     (3)
    ) u_nuc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (join_valid),
      .s_ready_o   (core_ready),
      .s_pix_data_i(pix_data),
      .s_gain_lo_i (w.gain_lo),
      .s_gain_hi_i (w.gain_hi),
      .s_knee_i    (w.knee),
      .s_level_i   (frame[LevelBits-1:0]),
      .s_user_i    ({pix_sof, pix_eol, w.bad}),
      .m_valid_o   (nuc_valid),
      .m_ready_i   (nuc_ready),
      .m_pix_data_o(nuc_data),
      .m_user_o    (nuc_user)
    );
  end else if (MethodSel == MethodQuadratic) begin : gen_quadratic
    // coeffs: gain, offset, bad | quad: quad.
    typedef struct packed {
      quad_word#(QuadBits)::word_t quad;
      coef_word_t                  coeffs;
    } stream_t;
    stream_t w;
    assign w = coef;

    quad_core #(
      .AdcBits       (AdcBits),
      .GainIntBits   (GainIntBits),
      .GainFracBits  (GainFracBits),
      .OffsetIntBits (OffsetIntBits),
      .OffsetFracBits(OffsetFracBits),
      .QuadIntBits   (QuadIntBits),
      .QuadFracBits  (QuadFracBits),
      .SquareBits    (SquareBits),
      .OutBits       (OutBits),
      .Rounding      (Rounding),
      .Overflow      (Overflow),
      .UserBits      (3)
    ) u_nuc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (join_valid),
      .s_ready_o   (core_ready),
      .s_pix_data_i(pix_data),
      .s_gain_i    (w.coeffs.gain),
      .s_offset_i  (w.coeffs.offset),
      .s_quad_i    (w.quad.quad),
      .s_user_i    ({pix_sof, pix_eol, w.coeffs.bad}),
      .m_valid_o   (nuc_valid),
      .m_ready_i   (nuc_ready),
      .m_pix_data_o(nuc_data),
      .m_user_o    (nuc_user)
    );
    logic unused_frame;
    assign unused_frame = ^frame;
  end else begin : gen_per_frame
    // tc_offset and table_interp: the frame's gain and offset of the pixel, then nuc_core.
    logic                  cf_valid, cf_ready;
    logic [GainBits-1:0]   cf_gain;
    logic [OffsetBits-1:0] cf_offset;
    logic [PassBits-1:0]   cf_user;

    if (MethodSel == MethodTcOffset) begin : gen_tc_offset
      // coeffs: gain, offset (c0), bad | tc: tc1[, tc2] | tg: tg1[, tg2] (the tc and tg
      // words go to tc_poly whole); frame: reading, t_ref.
      coef_word_t                                coeffs;
      frame_tc_offset#(ReadingBits)::word_t      fw;
      logic [((TcGain != 0) ? TgWordBits : 1)-1:0] tg;
      assign coeffs = coef[TwoPointBits-1:0];
      assign fw     = frame;
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
        .UserBits        (PassBits)
      ) u_coef (
        .clk_i      (clk_i),
        .rst_ni     (rst_ni),
        .s_valid_i  (join_valid),
        .s_ready_o  (core_ready),
        .s_reading_i(fw.reading),
        .s_t_ref_i  (fw.t_ref),
        .s_gain_i   (coeffs.gain),
        .s_offset_i (coeffs.offset),
        .s_tc_i     (coef[TwoPointBits +: TcWordBits]),
        .s_tg_i     (tg),
        .s_user_i   ({pix_data, pix_sof, pix_eol, coeffs.bad}),
        .m_valid_o  (cf_valid),
        .m_ready_i  (cf_ready),
        .m_gain_o   (cf_gain),
        .m_offset_o (cf_offset),
        .m_user_o   (cf_user)
      );
    end else begin : gen_table_interp
      // table j: gain, offset, bad | table j + 1: gain, offset, bad; the weight is the
      // frame's (at most 2^Wf: the bits above Wf are 0, asserted below).
      typedef struct packed {
        coef_word_t upper;  // table j + 1
        coef_word_t lower;  // table j
      } stream_t;
      stream_t w;
      assign w = coef;

      table_interp #(
        .GainIntBits   (GainIntBits),
        .GainFracBits  (GainFracBits),
        .OffsetIntBits (OffsetIntBits),
        .OffsetFracBits(OffsetFracBits),
        .WeightFracBits(WeightFracBits),
        .WeightRounding(WeightRounding),
        .UserBits      (PassBits)
      ) u_coef (
        .clk_i      (clk_i),
        .rst_ni     (rst_ni),
        .s_valid_i  (join_valid),
        .s_ready_o  (core_ready),
        .s_gain0_i  (w.lower.gain),
        .s_offset0_i(w.lower.offset),
        .s_gain1_i  (w.upper.gain),
        .s_offset1_i(w.upper.offset),
        .s_weight_i (frame[WeightFracBits:0]),
        .s_user_i   ({pix_data, pix_sof, pix_eol, w.lower.bad | w.upper.bad}),
        .m_valid_o  (cf_valid),
        .m_ready_i  (cf_ready),
        .m_gain_o   (cf_gain),
        .m_offset_o (cf_offset),
        .m_user_o   (cf_user)
      );
      // The weight's bits above Wf are 0 (asserted below).
      if (WeightBits > WeightFracBits + 1) begin : gen_weight_high
        logic unused_weight;
        assign unused_weight = ^frame[WeightBits-1:WeightFracBits+1];
      end
`ifdef IRNUC_ASSERT
      // table_interp's contract (docs/datapath.md), at the join:
      //   a_weight_range  the frame's weight is at most 2^Wf.
      logic armed_q;  // from the second edge after reset
      irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
      always_ff @(posedge clk_i) begin : p_check
        if (armed_q && join_take) begin
          a_weight_range: assert (64'(frame) <= (64'd1 << WeightFracBits))
            else $error("method_dpc_top: weight %0d above 2^%0d", frame, WeightFracBits);
        end
      end
`endif
    end

    nuc_core #(
      .AdcBits       (AdcBits),
      .GainIntBits   (GainIntBits),
      .GainFracBits  (GainFracBits),
      .OffsetIntBits (OffsetIntBits),
      .OffsetFracBits(OffsetFracBits),
      .OutBits       (OutBits),
      .Rounding      (Rounding),
      .Overflow      (Overflow),
      .UserBits      (3)
    ) u_nuc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (cf_valid),
      .s_ready_o   (cf_ready),
      .s_pix_data_i(cf_user[PassBits-1:3]),
      .s_gain_i    (cf_gain),
      .s_offset_i  (cf_offset),
      .s_user_i    (cf_user[2:0]),
      .m_valid_o   (nuc_valid),
      .m_ready_i   (nuc_ready),
      .m_pix_data_o(nuc_data),
      .m_user_o    (nuc_user)
    );
  end

  // ---- DPC ---------------------------------------------------------------------------
  dpc_core #(
    .OutBits  (OutBits),
    .MaxWidth (MaxWidth),
    .MaxHeight(MaxHeight)
  ) u_dpc (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .frame_width_i (frame_width_i),
    .frame_height_i(frame_height_i),
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

`ifdef IRNUC_ASSERT
  // Protocol assertions of s_pix_*, s_coef_* and m_pix_*: in u_pix_in, u_coef_in and
  // u_dpc.u_out (irnuc_spill_register), whose ports these are; the frame size at a frame
  // start:
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
`endif

endmodule
