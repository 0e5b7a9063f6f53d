// The end of every top (docs/rtl.md "Architecture"): dpc_core on the NUC's stream, and the
// frame-size assertion at the top's input (frame_start_i: the top took a pixel with sof),
// written once for nuc_dpc_top, method_dpc_top, method_drift_top and method_ffc_top.
//   s_*  the NUC's output: pixel, bad flag, sof, eol (valid/ready)
//   m_*  the corrected pixels with sof/eol; frame_err_o sticky (see dpc_core)
module dpc_tail #(
  parameter int unsigned OutBits    = 14,
  parameter int unsigned MaxWidth   = 1024,
  parameter int unsigned MaxHeight  = 1024,
  // s_* is checked by dpc_core's input register (0: by the top, whose driver of s_* is a
  // checked register; the frame size is checked here either way).
  parameter bit          CheckIn    = 1'b1,
  // dpc_core's own input register (0: s_* comes straight from the caller's register).
  parameter bit          InReg      = 1'b1,
  // Derived, do not override.
  localparam int unsigned WidthBits  = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits = $clog2(MaxHeight + 1)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic [WidthBits-1:0]  frame_width_i,
  input  logic [HeightBits-1:0] frame_height_i,
  input  logic                  frame_start_i,  // the assertion's only input
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [OutBits-1:0]    s_pix_data_i,
  input  logic                  s_bad_i,
  input  logic                  s_sof_i,
  input  logic                  s_eol_i,
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic                  m_sof_o,
  output logic                  m_eol_o,
  output logic                  frame_err_o
);

  dpc_core #(
    .OutBits  (OutBits),
    .MaxWidth (MaxWidth),
    .MaxHeight(MaxHeight),
    .CheckIn  (CheckIn),
    .InReg    (InReg)
  ) u_dpc (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .frame_width_i (frame_width_i),
    .frame_height_i(frame_height_i),
    .s_valid_i     (s_valid_i),
    .s_ready_o     (s_ready_o),
    .s_pix_data_i  (s_pix_data_i),
    .s_bad_i       (s_bad_i),
    .s_sof_i       (s_sof_i),
    .s_eol_i       (s_eol_i),
    .m_valid_o     (m_valid_o),
    .m_ready_i     (m_ready_i),
    .m_pix_data_o  (m_pix_data_o),
    .m_sof_o       (m_sof_o),
    .m_eol_o       (m_eol_o),
    .frame_err_o   (frame_err_o)
  );

`ifdef IRNUC_ASSERT
  // The frame size at a frame start of the top's input (the protocol assertions of the
  // streams are in their registers: dpc_core's u_out and the top's input registers).
  irnuc_frame_assert #(
    .MaxWidth (MaxWidth),
    .MaxHeight(MaxHeight)
  ) u_assert_frame (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .start_i (frame_start_i),
    .width_i (frame_width_i),
    .height_i(frame_height_i)
  );
`else
  logic unused_start;
  assign unused_start = frame_start_i;
`endif

endmodule
