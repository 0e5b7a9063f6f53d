// Smoke testbench of irnuc_axis_top for the FuseSoC core's sim target (hdl/irnuc.core,
// built with --binary --timing): reset, then the register file over AXI4-Lite: ID and
// VERSION, FRAME_MAX against the parameters, a frame size written and read back, the
// SLVERR answers (an illegal frame size, which leaves the register as it was; a write to a
// read-only register; an offset outside the map). The bit-exact co-simulation of every
// port is irnuc's cocotb suite (cocotb_tests/test_axis_top.py). Not part of the design.
module irnuc_axis_top_tb;
  import irnuc_pkg::*;

  localparam int unsigned MaxWidth  = 1024;  // irnuc_axis_top's defaults
  localparam int unsigned MaxHeight = 1024;

  logic                   clk, rst_n;
  logic [RegAddrBits-1:0] awaddr, araddr;
  logic                   awvalid, wvalid, bready, arvalid, rvalid, rready;
  logic                   awready, wready, bvalid, arready;
  logic [31:0]            wdata, rdata;
  logic [3:0]             wstrb;
  logic [1:0]             bresp, rresp;
  int unsigned            errors;
  // The streams are idle; their outputs are not looked at.
  logic [15:0]            video_out;
  logic [7:0]             acc_out, foff_out;
  logic                   vid_ready, coef_ready, foff_ready, acc_ready, video_valid, video_last;
  logic                   video_user, acc_valid, acc_last, foff_valid, foff_last, irq;

  initial clk = 1'b0;
  always #5 clk = !clk;

  irnuc_axis_top u_dut (
    .clk_i(clk), .rst_ni(rst_n),
    .s_axis_video_tdata('0), .s_axis_video_tvalid(1'b0), .s_axis_video_tready(vid_ready),
    .s_axis_video_tlast(1'b0), .s_axis_video_tuser(1'b0),
    .s_axis_coef_tdata('0), .s_axis_coef_tvalid(1'b0), .s_axis_coef_tready(coef_ready),
    .s_axis_coef_tlast(1'b0),
    .m_axis_video_tdata(video_out), .m_axis_video_tvalid(video_valid),
    .m_axis_video_tready(1'b1), .m_axis_video_tlast(video_last),
    .m_axis_video_tuser(video_user),
    .s_axis_foff_tdata('0), .s_axis_foff_tvalid(1'b0), .s_axis_foff_tready(foff_ready),
    .s_axis_foff_tlast(1'b0),
    .s_axis_acc_tdata('0), .s_axis_acc_tvalid(1'b0), .s_axis_acc_tready(acc_ready),
    .s_axis_acc_tlast(1'b0),
    .m_axis_acc_tdata(acc_out), .m_axis_acc_tvalid(acc_valid), .m_axis_acc_tready(1'b1),
    .m_axis_acc_tlast(acc_last),
    .m_axis_foff_tdata(foff_out), .m_axis_foff_tvalid(foff_valid),
    .m_axis_foff_tready(1'b1), .m_axis_foff_tlast(foff_last),
    .s_axil_awaddr(awaddr), .s_axil_awprot(3'b000), .s_axil_awvalid(awvalid),
    .s_axil_awready(awready), .s_axil_wdata(wdata), .s_axil_wstrb(wstrb),
    .s_axil_wvalid(wvalid), .s_axil_wready(wready), .s_axil_bresp(bresp),
    .s_axil_bvalid(bvalid), .s_axil_bready(bready),
    .s_axil_araddr(araddr), .s_axil_arprot(3'b000), .s_axil_arvalid(arvalid),
    .s_axil_arready(arready), .s_axil_rdata(rdata), .s_axil_rresp(rresp),
    .s_axil_rvalid(rvalid), .s_axil_rready(rready),
    .irq_o(irq)
  );
  logic unused_outputs;
  assign unused_outputs = ^{video_out, acc_out, foff_out, vid_ready, coef_ready, foff_ready,
                            acc_ready, video_valid, video_last, video_user, acc_valid, acc_last,
                            foff_valid, foff_last, irq};

  // The master drives on the falling edge (blocking: no race with the rising edge the
  // slave samples on) and sees the slave's handshakes on the rising edge.
  task automatic axil_write(input logic [RegAddrBits-1:0] addr, input logic [31:0] data,
                            output logic [1:0] resp);
    logic aw_done, w_done;
    @(negedge clk);
    awaddr = addr; awvalid = 1'b1; wdata = data; wstrb = 4'hf; wvalid = 1'b1; bready = 1'b1;
    aw_done = 1'b0;
    w_done = 1'b0;
    while (!(aw_done && w_done)) begin
      @(posedge clk);
      aw_done = aw_done || awready;
      w_done  = w_done || wready;
      @(negedge clk);
      if (aw_done) awvalid = 1'b0;
      if (w_done) wvalid = 1'b0;
    end
    while (!bvalid) @(negedge clk);
    resp = bresp;
    @(posedge clk);
    @(negedge clk);
    bready = 1'b0;
  endtask

  task automatic axil_read(input logic [RegAddrBits-1:0] addr, output logic [31:0] data,
                           output logic [1:0] resp);
    @(negedge clk);
    araddr = addr; arvalid = 1'b1; rready = 1'b1;
    do @(posedge clk); while (!arready);
    @(negedge clk);
    arvalid = 1'b0;
    while (!rvalid) @(negedge clk);
    data = rdata;
    resp = rresp;
    @(posedge clk);
    @(negedge clk);
    rready = 1'b0;
  endtask

  task automatic expect_read(input int unsigned addr, input logic [31:0] want,
                             input logic [1:0] want_resp, input string what);
    logic [31:0] data;
    logic [1:0]  resp;
    axil_read(RegAddrBits'(addr), data, resp);
    if (data !== want || resp !== want_resp) begin
      $display("FAIL %s: read 0x%03x = 0x%08x (%0d), expected 0x%08x (%0d)", what, addr, data,
               resp, want, want_resp);
      errors++;
    end
  endtask

  task automatic expect_write(input int unsigned addr, input logic [31:0] data,
                              input logic [1:0] want_resp, input string what);
    logic [1:0] resp;
    axil_write(RegAddrBits'(addr), data, resp);
    if (resp !== want_resp) begin
      $display("FAIL %s: write 0x%08x at 0x%03x answered %0d, expected %0d", what, data, addr,
               resp, want_resp);
      errors++;
    end
  endtask

  localparam logic [31:0] Size = (32'd4 << RegFrameSizeHeightLsb) | (32'd6 << RegFrameSizeWidthLsb);

  initial begin
    errors = 0;
    rst_n = 1'b0;
    awaddr = '0; araddr = '0; wdata = '0; wstrb = '0;
    awvalid = 1'b0; wvalid = 1'b0; bready = 1'b0; arvalid = 1'b0; rready = 1'b0;
    repeat (5) @(negedge clk);
    rst_n = 1'b1;
    expect_read(RegIdOffset, RegMapId, AxiOkay, "ID");
    expect_read(RegFrameMaxOffset, (32'(MaxHeight) << RegFrameMaxHeightLsb)
                | (32'(MaxWidth) << RegFrameMaxWidthLsb), AxiOkay, "FRAME_MAX");
    expect_write(RegFrameSizeOffset, Size, AxiOkay, "FRAME_SIZE");
    expect_read(RegFrameSizeOffset, Size, AxiOkay, "FRAME_SIZE read back");
    expect_write(RegFrameSizeOffset, 32'd0, AxiSlvErr, "FRAME_SIZE of 0");
    expect_read(RegFrameSizeOffset, Size, AxiOkay, "FRAME_SIZE kept");
    expect_write(RegIdOffset, 32'd0, AxiSlvErr, "a write to ID");
    expect_read(RegFrameMaxOffset + 4, 32'd0, AxiSlvErr, "an offset outside the map");
    if (errors != 0) $fatal(1, "irnuc_axis_top_tb: %0d checks failed", errors);
    $display("irnuc_axis_top_tb: PASS");
    $finish;
  end

  initial begin
    #100000;
    $fatal(1, "irnuc_axis_top_tb: timeout");
  end
endmodule
