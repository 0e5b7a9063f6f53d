// NUC + DPC pipeline top: joins the raw-pixel stream and the coefficient-word stream (one
// word per pixel, raster order, as a DMA reads the memory image), corrects the
// non-uniformity (nuc_core) and replaces defective pixels (dpc_core).
//
// Coefficient word (docs/datapath.md, memory image version 1), WW = GW + OW + 1 bits:
//   [GW-1:0] gain (unsigned), [GW+OW-1:GW] offset (two's complement), [GW+OW] bad flag.
//
// Streams use valid/ready; a transfer happens on a rising edge with both high. The two
// input streams are joined: a pixel and a word are taken together, in the same cycle.
module nuc_dpc_top #(
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,  // 0 truncate, 1 half_up, 2 half_even
  parameter int unsigned Overflow       = 0,  // 0 saturate, 1 wrap
  parameter int unsigned MaxWidth       = 1024,
  parameter int unsigned MaxHeight      = 1024,
  // Derived, do not override.
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned WordBits      = GainBits + OffsetBits + 1,
  localparam int unsigned WidthBits     = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits    = $clog2(MaxHeight + 1)
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

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MaxWidth >= 1 && MaxWidth <= 65535)
      else $fatal(1, "nuc_dpc_top: MaxWidth = %0d outside 1..65535", MaxWidth);
    assert (MaxHeight >= 1 && MaxHeight <= 65535)
      else $fatal(1, "nuc_dpc_top: MaxHeight = %0d outside 1..65535", MaxHeight);
  end
`endif

  // ---- join: a pixel and its word move together -------------------------------------
  logic                  nuc_in_ready, join_valid;
  logic [GainBits-1:0]   gain;
  logic [OffsetBits-1:0] offset;
  logic                  bad;

  assign join_valid     = s_pix_valid_i && s_coef_valid_i;
  assign s_pix_ready_o  = nuc_in_ready && s_coef_valid_i;
  assign s_coef_ready_o = nuc_in_ready && s_pix_valid_i;
  assign gain           = s_coef_data_i[GainBits-1:0];
  assign offset         = s_coef_data_i[GainBits +: OffsetBits];
  assign bad            = s_coef_data_i[GainBits + OffsetBits];

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
    .s_pix_data_i (s_pix_data_i),
    .s_gain_i     (gain),
    .s_offset_i   (offset),
    .s_user_i     ({s_pix_sof_i, s_pix_eol_i, bad}),
    .m_valid_o    (nuc_valid),
    .m_ready_i    (nuc_ready),
    .m_pix_data_o (nuc_data),
    .m_user_o     (nuc_user)
  );

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

endmodule
