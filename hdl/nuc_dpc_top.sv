// NUC + DPC pipeline top: joins the raw-pixel stream and the coefficient-word stream (one
// word per pixel, raster order, as a DMA reads the memory image), corrects the
// non-uniformity (nuc_core) and replaces defective pixels (dpc_core).
//
// Coefficient word (docs/datapath.md, memory image version 1), WW = GW + OW + 1 bits:
//   [GW-1:0] gain (unsigned), [GW+OW-1:GW] offset (two's complement), [GW+OW] bad flag;
//   the type irnuc_pkg::coef_word #(GW, OW)::word_t.
//
// Streams use valid/ready; a transfer happens on a rising edge with both high. Each input
// stream has its own input register (irnuc_spill_register), so its ready is a flop and
// does not depend on the other stream's valid; behind them a pixel and its word are
// joined and enter nuc_core together. Latency: 1 + nuc_core + dpc_core (docs/rtl.md).
module nuc_dpc_top
  import irnuc_pkg::*;
#(
  // irnuc-params: begin nuc_dpc_top (generated from nuc_fixed.methods; do not edit)
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
  // Derived, do not override.
  localparam int unsigned GainBits         = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits       = OffsetIntBits + OffsetFracBits,
  localparam int unsigned WidthBits        = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits       = $clog2(MaxHeight + 1),
  // irnuc-params: end
  localparam int unsigned WordBits         = coef_word_bits(GainBits, OffsetBits)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Run-time frame size, 1..MaxWidth x 1..MaxHeight.
  input  logic [WidthBits-1:0]  frame_width_i,
  input  logic [HeightBits-1:0] frame_height_i,
  // Raw pixels in.
  input  logic                  s_pix_valid_i,
  output logic                  s_pix_ready_o,
  input  logic [AdcBits-1:0]    s_pix_data_i,
  input  logic                  s_pix_sof_i,
  input  logic                  s_pix_eol_i,
  // Coefficient words in.
  input  logic                  s_coef_valid_i,
  output logic                  s_coef_ready_o,
  input  logic [WordBits-1:0]   s_coef_data_i,
  // Corrected pixels out.
  output logic                  m_pix_valid_o,
  input  logic                  m_pix_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic                  m_pix_sof_o,
  output logic                  m_pix_eol_o,
  // Sticky framing error (see dpc_core).
  output logic                  frame_err_o
);

  typedef coef_word#(GainBits, OffsetBits)::word_t coef_word_t;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax)
      else $fatal(1, "nuc_dpc_top: MaxWidth = %0d outside %0d..%0d", MaxWidth, MaxWidthMin,
                  MaxWidthMax);
    assert (MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "nuc_dpc_top: MaxHeight = %0d outside %0d..%0d", MaxHeight, MaxHeightMin,
                  MaxHeightMax);
    assert ($bits(coef_word_t) == WordBits)
      else $fatal(1, "nuc_dpc_top: coefficient word type of %0d bits, expected %0d",
                  $bits(coef_word_t), WordBits);
  end
`endif

  // ---- input registers -----------------------------------------------------------------
  logic               pix_valid, pix_ready, pix_sof, pix_eol;
  logic [AdcBits-1:0] pix_data;
  logic               coef_valid, coef_ready;
  coef_word_t         coef;

  irnuc_spill_register #(.DataBits(AdcBits + 2)) u_pix_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_pix_valid_i),
    .ready_o(s_pix_ready_o),
    .data_i ({s_pix_sof_i, s_pix_eol_i, s_pix_data_i}),
    .valid_o(pix_valid),
    .ready_i(pix_ready),
    .data_o ({pix_sof, pix_eol, pix_data})
  );

  irnuc_spill_register #(.DataBits(WordBits)) u_coef_in (
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
  logic nuc_in_ready, join_valid;

  assign join_valid = pix_valid && coef_valid;
  assign pix_ready  = nuc_in_ready && coef_valid;
  assign coef_ready = nuc_in_ready && pix_valid;

  // ---- NUC ---------------------------------------------------------------------------
  logic               nuc_valid, nuc_ready;
  logic [OutBits-1:0] nuc_data;
  logic [2:0]         nuc_user;  // {sof, eol, bad}

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
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .s_valid_i    (join_valid),
    .s_ready_o    (nuc_in_ready),
    .s_pix_data_i (pix_data),
    .s_gain_i     (coef.gain),
    .s_offset_i   (coef.offset),
    .s_user_i     ({pix_sof, pix_eol, coef.bad}),
    .m_valid_o    (nuc_valid),
    .m_ready_i    (nuc_ready),
    .m_pix_data_o (nuc_data),
    .m_user_o     (nuc_user)
  );

  // ---- DPC ---------------------------------------------------------------------------
  dpc_tail #(
    .CheckIn   (1'b0),  // its s_* is nuc_core's output register, checked there
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

  // Protocol assertions of s_pix_*, s_coef_* and m_pix_*: in u_pix_in, u_coef_in and
  // u_tail.u_dpc.u_out (irnuc_spill_register), whose ports these are; the frame size at a
  // frame start: in u_tail.

endmodule
