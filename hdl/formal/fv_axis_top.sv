// Proof harness of irnuc_axis_top (`irnuc formal`, docs/formal.md), bounded: the property
// modules are bound into the top (its ports are the free environment), for any
// configuration's parameters.
//   s_axis_video, s_axis_coef, s_axis_foff, s_axis_acc  AXI4-Stream rules assumed
//   m_axis_video, m_axis_acc, m_axis_foff                AXI4-Stream rules proved
//   m_axis_video                                         video framing: a start of frame on
//                                                        each frame's first pixel only, an end
//                                                        of line on the last pixel of every
//                                                        line, frames of the size the framer
//                                                        took for them (act_w x act_h)
//   s_axil                                               AXI4-Lite rules (master assumed)
// and the design's own checks (IRNUC_ASSERT).
module fv_axis_top_props #(
  parameter int unsigned VidInBits  = 8,
  parameter int unsigned VidOutBits = 8,
  parameter int unsigned CoefBits   = 8,
  parameter int unsigned FoffBits   = 8,
  parameter int unsigned AccBits    = 8,
  parameter int unsigned AddrBits   = 12,
  parameter int unsigned WidthBits  = 11,
  parameter int unsigned HeightBits = 11
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic [VidInBits-1:0]  s_axis_video_tdata,
  input logic                  s_axis_video_tvalid,
  input logic                  s_axis_video_tready,
  input logic                  s_axis_video_tlast,
  input logic [0:0]            s_axis_video_tuser,
  input logic [CoefBits-1:0]   s_axis_coef_tdata,
  input logic                  s_axis_coef_tvalid,
  input logic                  s_axis_coef_tready,
  input logic                  s_axis_coef_tlast,
  input logic [VidOutBits-1:0] m_axis_video_tdata,
  input logic                  m_axis_video_tvalid,
  input logic                  m_axis_video_tready,
  input logic                  m_axis_video_tlast,
  input logic [0:0]            m_axis_video_tuser,
  input logic [FoffBits-1:0]   s_axis_foff_tdata,
  input logic                  s_axis_foff_tvalid,
  input logic                  s_axis_foff_tready,
  input logic                  s_axis_foff_tlast,
  input logic [AccBits-1:0]    s_axis_acc_tdata,
  input logic                  s_axis_acc_tvalid,
  input logic                  s_axis_acc_tready,
  input logic                  s_axis_acc_tlast,
  input logic [AccBits-1:0]    m_axis_acc_tdata,
  input logic                  m_axis_acc_tvalid,
  input logic                  m_axis_acc_tready,
  input logic                  m_axis_acc_tlast,
  input logic [FoffBits-1:0]   m_axis_foff_tdata,
  input logic                  m_axis_foff_tvalid,
  input logic                  m_axis_foff_tready,
  input logic                  m_axis_foff_tlast,
  input logic [AddrBits-1:0]   s_axil_awaddr,
  input logic [2:0]            s_axil_awprot,
  input logic                  s_axil_awvalid,
  input logic                  s_axil_awready,
  input logic [31:0]           s_axil_wdata,
  input logic [3:0]            s_axil_wstrb,
  input logic                  s_axil_wvalid,
  input logic                  s_axil_wready,
  input logic [1:0]            s_axil_bresp,
  input logic                  s_axil_bvalid,
  input logic                  s_axil_bready,
  input logic [AddrBits-1:0]   s_axil_araddr,
  input logic [2:0]            s_axil_arprot,
  input logic                  s_axil_arvalid,
  input logic                  s_axil_arready,
  input logic [31:0]           s_axil_rdata,
  input logic [1:0]            s_axil_rresp,
  input logic                  s_axil_rvalid,
  input logic                  s_axil_rready,
  input logic [WidthBits-1:0]  act_w,
  input logic [HeightBits-1:0] act_h
);

  irnuc_fv_reset u_reset (.clk_i, .rst_ni);
  irnuc_fv_stream #(.DataBits(VidInBits + 2), .Assume(1'b1)) u_video_in (
    .clk_i, .rst_ni, .valid_i(s_axis_video_tvalid), .ready_i(s_axis_video_tready),
    .data_i({s_axis_video_tdata, s_axis_video_tlast, s_axis_video_tuser}));
  irnuc_fv_stream #(.DataBits(CoefBits + 1), .Assume(1'b1)) u_coef_in (
    .clk_i, .rst_ni, .valid_i(s_axis_coef_tvalid), .ready_i(s_axis_coef_tready),
    .data_i({s_axis_coef_tdata, s_axis_coef_tlast}));
  irnuc_fv_stream #(.DataBits(FoffBits + 1), .Assume(1'b1)) u_foff_in (
    .clk_i, .rst_ni, .valid_i(s_axis_foff_tvalid), .ready_i(s_axis_foff_tready),
    .data_i({s_axis_foff_tdata, s_axis_foff_tlast}));
  irnuc_fv_stream #(.DataBits(AccBits + 1), .Assume(1'b1)) u_acc_in (
    .clk_i, .rst_ni, .valid_i(s_axis_acc_tvalid), .ready_i(s_axis_acc_tready),
    .data_i({s_axis_acc_tdata, s_axis_acc_tlast}));
  irnuc_fv_stream #(.DataBits(VidOutBits + 2), .Assume(1'b0)) u_video_out (
    .clk_i, .rst_ni, .valid_i(m_axis_video_tvalid), .ready_i(m_axis_video_tready),
    .data_i({m_axis_video_tdata, m_axis_video_tlast, m_axis_video_tuser}));
  irnuc_fv_stream #(.DataBits(AccBits + 1), .Assume(1'b0)) u_acc_out (
    .clk_i, .rst_ni, .valid_i(m_axis_acc_tvalid), .ready_i(m_axis_acc_tready),
    .data_i({m_axis_acc_tdata, m_axis_acc_tlast}));
  irnuc_fv_stream #(.DataBits(FoffBits + 1), .Assume(1'b0)) u_foff_out (
    .clk_i, .rst_ni, .valid_i(m_axis_foff_tvalid), .ready_i(m_axis_foff_tready),
    .data_i({m_axis_foff_tdata, m_axis_foff_tlast}));
  irnuc_fv_video #(.WidthBits(WidthBits), .HeightBits(HeightBits)) u_video (
    .clk_i, .rst_ni, .valid_i(m_axis_video_tvalid), .ready_i(m_axis_video_tready),
    .sof_i(m_axis_video_tuser[0]), .eol_i(m_axis_video_tlast), .width_i(act_w),
    .height_i(act_h));
  irnuc_fv_axil #(.AddrBits(AddrBits), .MaxOpen(2)) u_axil (
    .clk_i, .rst_ni,
    .awaddr_i(s_axil_awaddr), .awprot_i(s_axil_awprot), .awvalid_i(s_axil_awvalid),
    .awready_i(s_axil_awready), .wdata_i(s_axil_wdata), .wstrb_i(s_axil_wstrb),
    .wvalid_i(s_axil_wvalid), .wready_i(s_axil_wready), .bresp_i(s_axil_bresp),
    .bvalid_i(s_axil_bvalid), .bready_i(s_axil_bready), .araddr_i(s_axil_araddr),
    .arprot_i(s_axil_arprot), .arvalid_i(s_axil_arvalid), .arready_i(s_axil_arready),
    .rdata_i(s_axil_rdata), .rresp_i(s_axil_rresp), .rvalid_i(s_axil_rvalid),
    .rready_i(s_axil_rready));

`ifdef FORMAL
  // A frame has left whole (the next start of frame is then a frame after a finished one).
  logic frame_done_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_frame_done
    if (!rst_ni) begin
      frame_done_q <= 1'b0;
    end else if (m_axis_video_tvalid && m_axis_video_tready && u_video.frame_end) begin
      frame_done_q <= 1'b1;
    end
  end

  // Reachable within the bound: a whole frame out and the next one's first pixel. With
  // IRNUC_FV_COVER_BMC (irnuc formal's cover model for ABC) each cover is an assertion that
  // fails where it is reached: bmc3 finds the step of every cover in one run.
`ifdef IRNUC_FV_COVER_BMC
  `define IRNUC_FV_COVER(label, cond) label: assert (!(cond));
`else
  `define IRNUC_FV_COVER(label, cond) label: cover (cond);
`endif
  always_comb begin : p_cover
    if (rst_ni) begin
      `IRNUC_FV_COVER(c_video_in, s_axis_video_tvalid && s_axis_video_tready
                                  && s_axis_video_tuser[0])
      `IRNUC_FV_COVER(c_coef_in, s_axis_coef_tvalid && s_axis_coef_tready)
      `IRNUC_FV_COVER(c_video_out, m_axis_video_tvalid && m_axis_video_tready)
      `IRNUC_FV_COVER(c_frame_out, m_axis_video_tvalid && m_axis_video_tready
                                   && u_video.frame_end)
      `IRNUC_FV_COVER(c_next_sof, m_axis_video_tvalid && m_axis_video_tready
                                  && m_axis_video_tuser[0] && frame_done_q)
    end
  end
`undef IRNUC_FV_COVER
`endif

endmodule

bind irnuc_axis_top fv_axis_top_props #(
  .VidInBits(VidInBits), .VidOutBits(VidOutBits), .CoefBits(CoefBits), .FoffBits(FoffBits),
  .AccBits(AccBits), .AddrBits(AddrBits), .WidthBits(WidthBits), .HeightBits(HeightBits)
) u_fv (.*);
