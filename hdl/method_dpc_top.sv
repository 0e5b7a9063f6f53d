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
// The method is one module of each kind (nuc_fixed.method_top): its front (frame_coefficients:
// hdl/method_<name>.sv, the pixel's coefficients of the frame; tc_offset's tc_poly and
// table_interp's table_interp are pipelines, the others pass through) and the core of its
// kind (method_core: nuc_core, quad_core or pwl_core), then the DPC tail (dpc_tail). One pixel
// per clock, no bubbles. Latency: 1 + the front + the core + dpc_core (docs/rtl.md).
module method_dpc_top
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
#(
  // irnuc-params: begin method_dpc_top (generated from nuc_fixed.methods; do not edit)
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
  parameter int unsigned WeightIntBits    = 1,
  parameter int unsigned WeightFracBits   = 15,
  parameter int unsigned WeightRounding   = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned HousingBits      = 14,  // bits of the housing sensor's reading
  parameter int unsigned Th1IntBits       = 15,
  parameter int unsigned Th1FracBits      = 3,
  parameter int unsigned ThxIntBits       = 14,
  parameter int unsigned ThxFracBits      = 4,
  parameter int unsigned Th2IntBits       = 12,
  parameter int unsigned Th2FracBits      = 4,
  parameter int unsigned HousingRangeBits = 11,  // Hs: w' = (h - h_ref) / 2^Hs
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
  localparam int unsigned ThWordBits       = Th1IntBits + Th1FracBits + ThxIntBits + ThxFracBits
                                             + Th2IntBits + Th2FracBits,
  localparam int unsigned WeightBits       = WeightIntBits + WeightFracBits,
  localparam int unsigned CoefBits         = coef_stream_bits(Method, OffsetBits, GainBits,
                                                              KneeBits, QuadBits, TcWordBits,
                                                              TgWordBits, ThWordBits),
  localparam int unsigned FrameBits        = frame_word_bits(Method, GainBits, LevelBits,
                                                             ReadingBits, WeightBits, HousingBits),
  localparam int unsigned WidthBits        = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits       = $clog2(MaxHeight + 1)
  // irnuc-params: end
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

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax)
      else $fatal(1, "method_dpc_top: MaxWidth = %0d outside %0d..%0d", MaxWidth, MaxWidthMin,
                  MaxWidthMax);
    assert (MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "method_dpc_top: MaxHeight = %0d outside %0d..%0d", MaxHeight,
                  MaxHeightMin, MaxHeightMax);
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

  // ---- the method's front: the pixel's coefficients of the frame -----------------------
  // The raw code and the markers travel as side band: {raw, sof, eol}, then the bad flag.
  localparam int unsigned PassBits = AdcBits + 2;

  logic                  cf_valid, cf_ready;
  logic [GainBits-1:0]   cf_gain, cf_gain_hi;
  logic [OffsetBits-1:0] cf_offset;
  logic [QuadBits-1:0]   cf_quad;
  logic [KneeBits-1:0]   cf_knee;
  logic [LevelBits-1:0]  cf_level;
  logic [PassBits:0]     cf_user;  // {raw, sof, eol, bad}

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
    .HousingRangeBits (HousingRangeBits),
    // irnuc-params: end
    .UserBits(PassBits)
  ) u_front (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .s_valid_i  (join_valid),
    .s_ready_o  (core_ready),
    .s_coef_i   (coef),
    .s_frame_i  (frame),
    .s_user_i   ({pix_data, pix_sof, pix_eol}),
    .m_valid_o  (cf_valid),
    .m_ready_i  (cf_ready),
    .m_gain_o   (cf_gain),
    .m_gain_hi_o(cf_gain_hi),
    .m_offset_o (cf_offset),
    .m_quad_o   (cf_quad),
    .m_knee_o   (cf_knee),
    .m_level_o  (cf_level),
    .m_user_o   (cf_user)
  );

  // ---- the core of the method's kind ----------------------------------------------------
  logic               nuc_valid, nuc_ready;
  logic [OutBits-1:0] nuc_data;
  logic [2:0]         nuc_user;  // {sof, eol, bad}

  method_core #(
    .Kind(core_kind(Method)),
    // irnuc-params: forward method_core (generated from nuc_fixed.methods; do not edit)
    .AdcBits        (AdcBits),
    .GainIntBits    (GainIntBits),
    .GainFracBits   (GainFracBits),
    .OffsetIntBits  (OffsetIntBits),
    .OffsetFracBits (OffsetFracBits),
    .OutBits        (OutBits),
    .Rounding       (Rounding),
    .Overflow       (Overflow),
    .KneeIntBits    (KneeIntBits),
    .KneeFracBits   (KneeFracBits),
    .LevelIntBits   (LevelIntBits),
    .LevelFracBits  (LevelFracBits),
    .QuadIntBits    (QuadIntBits),
    .QuadFracBits   (QuadFracBits),
    .SquareBits     (SquareBits),
    // irnuc-params: end
    .UserBits(3),
    // A registered front's output register checks the core's input stream.
    .CheckIn(!front_registered(Method))
  ) u_nuc (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .s_valid_i   (cf_valid),
    .s_ready_o   (cf_ready),
    .s_pix_data_i(cf_user[PassBits:3]),
    .s_gain_i    (cf_gain),
    .s_gain_hi_i (cf_gain_hi),
    .s_offset_i  (cf_offset),
    .s_quad_i    (cf_quad),
    .s_knee_i    (cf_knee),
    .s_level_i   (cf_level),
    .s_user_i    (cf_user[2:0]),
    .m_valid_o   (nuc_valid),
    .m_ready_i   (nuc_ready),
    .m_pix_data_o(nuc_data),
    .m_user_o    (nuc_user)
  );

  // ---- DPC ---------------------------------------------------------------------------
  dpc_tail #(
    // Its s_* is the NUC core's output register (checked there), which is also dpc_core's
    // input register: no second register back to back (one cycle less latency).
    .CheckIn   (1'b0),
    .InReg     (1'b0),
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

endmodule
