// Proof harness of irnuc_axis_framer (`irnuc formal`, docs/formal.md).
//
// Environment: the video and coefficient beats keep the AXI4-Stream rules (assumed; the
// beats themselves, markers included, are free: the framer must cope with any video); the
// video beats and the coefficient words pass the top's input buffers (irnuc_axis_buffer
// with its head bits, as u_vid_in and u_coef_in of irnuc_axis_top: the framer's registered
// decision reads each buffer's fill and the video buffer's head a cycle ahead from their
// input sides); the pending settings are free but for the frame size, which changes as the register file
// changes it (a write pulses size_write_i, the new size is taken at the next edge and
// size_dirty_i stays up from the next cycle to a frame start); hold_i and wb_busy_i are free;
// the core is a spill register draining into a free ready (it reports each item leaving).
// Obligations: the AXI4-Stream rules on the items to the core; video framing there (a start
// of frame on each frame's first item only, an end of line on the last item of every line,
// frames of exactly the size the framer reports for them, act_width_o x act_height_o); the
// framer's own checks (IRNUC_ASSERT: the in-flight count, the line size, the one-hot states).
module fv_axis_framer
  import irnuc_pkg::*;
#(
  parameter int unsigned AdcBits        = 2,
  parameter int unsigned GainIntBits    = 1,
  parameter int unsigned GainFracBits   = 1,
  parameter int unsigned OffsetIntBits  = 1,
  parameter int unsigned OffsetFracBits = 0,
  parameter int unsigned MaxWidth       = 3,
  parameter int unsigned MaxHeight      = 2,
  localparam int unsigned WordBits      = coef_word_bits(GainIntBits + GainFracBits,
                                                         OffsetIntBits + OffsetFracBits),
  localparam int unsigned WidthBits     = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits    = $clog2(MaxHeight + 1),
  localparam int unsigned ItemBits      = 1 + 2 + AdcBits + WordBits
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic                  vid_valid_i,
  input logic [AdcBits-1:0]    vid_data_i,
  input logic                  vid_sof_i,
  input logic                  vid_eol_i,
  input logic                  coef_valid_i,
  input logic [WordBits-1:0]   coef_data_i,
  input logic                  coef_last_i,
  input logic                  size_write_i,
  input logic [WidthBits-1:0]  new_width_i,
  input logic [HeightBits-1:0] new_height_i,
  input logic                  nuc_en_i,
  input logic                  dpc_en_i,
  input logic                  coef_sync_i,
  input logic                  frame_i,
  input logic                  hold_i,
  input logic                  wb_busy_i,
  input logic                  sink_ready_i
);

  // ---- the register file's frame size --------------------------------------------------
  logic [WidthBits-1:0]  width_q;
  logic [HeightBits-1:0] height_q;
  logic                  size_dirty_q, start;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_size
    if (!rst_ni) begin
      width_q      <= WidthBits'(MaxWidth);
      height_q     <= HeightBits'(MaxHeight);
      size_dirty_q <= 1'b0;
    end else begin
      if (size_write_i) begin
        width_q  <= new_width_i;
        height_q <= new_height_i;
      end
      size_dirty_q <= size_write_i || (size_dirty_q && !start);
    end
  end

  // ---- the coefficient input buffer (irnuc_axis_top's u_coef_in) --------------------------
  logic                  coef_in_ready, coef_valid, coef_last, coef_ready;
  logic [WordBits-1:0]   coef_data;

  irnuc_axis_buffer #(.DataBits(WordBits + 1), .HeadBits(1)) u_coef_in (
    .clk_i, .rst_ni, .valid_i(coef_valid_i), .ready_o(coef_in_ready),
    .data_i({coef_last_i, coef_data_i}), .valid_o(coef_valid), .ready_i(coef_ready),
    .data_o({coef_last, coef_data}));

  // ---- the video input buffer (irnuc_axis_top's u_vid_in) --------------------------------
  logic                  vid_in_ready, vid_valid, vid_sof, vid_eol, vid_ready;
  logic [AdcBits-1:0]    vid_data;

  irnuc_axis_buffer #(.DataBits(AdcBits + 2), .HeadBits(2)) u_vid_in (
    .clk_i, .rst_ni, .valid_i(vid_valid_i), .ready_o(vid_in_ready),
    .data_i({vid_sof_i, vid_eol_i, vid_data_i}), .valid_o(vid_valid), .ready_i(vid_ready),
    .data_o({vid_sof, vid_eol, vid_data}));

  // ---- the framer ------------------------------------------------------------------------
  logic                  m_valid, m_ready, m_sof, m_eol, m_frame;
  logic [AdcBits-1:0]    m_raw;
  logic [WordBits-1:0]   m_word;
  logic [WidthBits-1:0]  act_w, act_wm1;
  logic [HeightBits-1:0] act_h, act_hm1;
  logic [1:0]            core_out;

  irnuc_axis_framer #(
    .AdcBits(AdcBits), .GainIntBits(GainIntBits), .GainFracBits(GainFracBits),
    .OffsetIntBits(OffsetIntBits), .OffsetFracBits(OffsetFracBits),
    .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .FrameBits(1)
  ) u_dut (
    .clk_i, .rst_ni,
    .vid_valid_i(vid_valid), .vid_ready_o(vid_ready), .vid_data_i(vid_data),
    .vid_sof_i(vid_sof), .vid_eol_i(vid_eol),
    .coef_valid_i(coef_valid), .coef_ready_o(coef_ready), .coef_data_i(coef_data),
    .coef_last_i(coef_last), .coef_in_valid_i(coef_valid_i), .coef_in_ready_i(coef_in_ready),
    .vid_in_valid_i(vid_valid_i), .vid_in_ready_i(vid_in_ready), .vid_in_sof_i(vid_sof_i),
    .pend_width_i(width_q), .pend_height_i(height_q),
    .pend_width_m1_i(width_q - WidthBits'(1)), .pend_height_m1_i(height_q - HeightBits'(1)),
    .pend_width_is1_i(width_q == WidthBits'(1)), .pend_height_is1_i(height_q == HeightBits'(1)),
    .size_dirty_i(size_dirty_q), .size_write_i,
    .pend_nuc_en_i(nuc_en_i), .pend_dpc_en_i(dpc_en_i), .pend_coef_sync_i(coef_sync_i),
    .pend_frame_i(frame_i), .hold_i,
    .act_width_o(act_w), .act_width_m1_o(act_wm1), .act_height_o(act_h),
    .act_height_m1_o(act_hm1),
    .m_valid_o(m_valid), .m_ready_i(m_ready), .m_raw_o(m_raw), .m_word_o(m_word),
    .m_sof_o(m_sof), .m_eol_o(m_eol), .m_frame_o(m_frame),
    .core_out_i(core_out), .wb_busy_i, .start_o(start),
    .frame_start_o(), .beat_o(), .drop_o(), .pad_o(), .sof_early_o(), .sof_late_o(),
    .eol_early_o(), .eol_late_o(), .coef_early_o(), .coef_late_o(), .in_frame_o()
  );

  // ---- the core: a spill register into a free ready -------------------------------------
  logic core_valid;
  irnuc_spill_register #(.DataBits(ItemBits)) u_core (
    .clk_i, .rst_ni, .valid_i(m_valid), .ready_o(m_ready),
    .data_i({m_frame, m_sof, m_eol, m_raw, m_word}), .valid_o(core_valid),
    .ready_i(sink_ready_i), .data_o());
  assign core_out = {1'b0, core_valid && sink_ready_i};

  // ---- environment and properties -------------------------------------------------------
  irnuc_fv_reset u_reset (.clk_i, .rst_ni);
  irnuc_fv_stream #(.DataBits(AdcBits + 2), .Assume(1'b1)) u_vid (
    .clk_i, .rst_ni, .valid_i(vid_valid_i), .ready_i(vid_in_ready),
    .data_i({vid_data_i, vid_sof_i, vid_eol_i}));
  irnuc_fv_stream #(.DataBits(WordBits + 1), .Assume(1'b1)) u_coef (
    .clk_i, .rst_ni, .valid_i(coef_valid_i), .ready_i(coef_in_ready),
    .data_i({coef_data_i, coef_last_i}));
  irnuc_fv_stream #(.DataBits(ItemBits), .Assume(1'b0)) u_items (
    .clk_i, .rst_ni, .valid_i(m_valid), .ready_i(m_ready),
    .data_i({m_frame, m_sof, m_eol, m_raw, m_word}));
  irnuc_fv_video #(.WidthBits(WidthBits), .HeightBits(HeightBits)) u_video (
    .clk_i, .rst_ni, .valid_i(m_valid), .ready_i(m_ready), .sof_i(m_sof), .eol_i(m_eol),
    .width_i(act_w), .height_i(act_h));

`ifdef FORMAL
  always_comb begin : p_env
    if (size_write_i) begin  // the register file answers an illegal size SLVERR
      m_size_legal: assume (new_width_i != '0 && 32'(new_width_i) <= MaxWidth
                            && new_height_i != '0 && 32'(new_height_i) <= MaxHeight);
    end
  end
  always_comb begin : p_cover
    if (rst_ni) begin
      c_frame_end: cover (m_valid && m_ready && m_eol && u_video.frame_end && act_w != act_h);
      c_resized: cover (m_valid && m_ready && m_sof && 32'(act_w) != MaxWidth);
    end
  end
`endif

endmodule
