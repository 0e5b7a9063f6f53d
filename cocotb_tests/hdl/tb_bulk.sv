// Bulk co-simulation testbench (no cocotb): stimulus from $readmemh files, results to a
// file, comparison in numpy (benchmarks/bench_cosim.py). Not synthesizable.
//
// Plusargs: +pix=<file> (one line per pixel: {sof, eol, raw code} in hex)
//           +coef=<file> (coefficient words, the $readmemh memory image format)
//           +out=<file> (written: one line per output pixel, {sof, eol, data} in hex)
//           +n=<pixels> +w=<width> +h=<height>
//           +idle=<percent> +stall=<percent> (optional random input gaps / backpressure)
module tb_bulk #(
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,
  parameter int unsigned Overflow       = 0,
  parameter int unsigned MaxWidth       = 1024,
  parameter int unsigned MaxHeight      = 1024,
  parameter int unsigned Depth          = 1 << 20
);
  localparam int unsigned WordBits   = GainIntBits + GainFracBits + OffsetIntBits
                                       + OffsetFracBits + 1;
  localparam int unsigned WidthBits  = $clog2(MaxWidth + 1);
  localparam int unsigned HeightBits = $clog2(MaxHeight + 1);

  logic clk = 1'b0;
  logic rst_n = 1'b0;
  always #5 clk = ~clk;

  logic [AdcBits+1:0]  pix_mem  [Depth];
  logic [WordBits-1:0] coef_mem [Depth];

  logic                  pix_valid, pix_ready, coef_valid, coef_ready;
  logic                  out_valid, out_ready, out_sof, out_eol, err;
  logic [OutBits-1:0]    out_data;
  logic [WidthBits-1:0]  width;
  logic [HeightBits-1:0] height;
  int unsigned n, pi, ci, oi, idle, stall, fd;
  string pix_file, coef_file, out_file;

  nuc_dpc_top #(
    .AdcBits(AdcBits), .GainIntBits(GainIntBits), .GainFracBits(GainFracBits),
    .OffsetIntBits(OffsetIntBits), .OffsetFracBits(OffsetFracBits), .OutBits(OutBits),
    .Rounding(Rounding), .Overflow(Overflow), .MaxWidth(MaxWidth), .MaxHeight(MaxHeight)
  ) u_dut (
    .clk_i(clk), .rst_ni(rst_n), .frame_width_i(width), .frame_height_i(height),
    .s_pix_valid_i(pix_valid), .s_pix_ready_o(pix_ready),
    .s_pix_data_i(pix_mem[pi][AdcBits-1:0]), .s_pix_sof_i(pix_mem[pi][AdcBits+1]),
    .s_pix_eol_i(pix_mem[pi][AdcBits]),
    .s_coef_valid_i(coef_valid), .s_coef_ready_o(coef_ready), .s_coef_data_i(coef_mem[ci]),
    .m_pix_valid_o(out_valid), .m_pix_ready_i(out_ready), .m_pix_data_o(out_data),
    .m_pix_sof_o(out_sof), .m_pix_eol_o(out_eol), .frame_err_o(err)
  );

  initial begin
    int unsigned w, h;
    if (!$value$plusargs("pix=%s", pix_file) || !$value$plusargs("coef=%s", coef_file) ||
        !$value$plusargs("out=%s", out_file) || !$value$plusargs("n=%d", n) ||
        !$value$plusargs("w=%d", w) || !$value$plusargs("h=%d", h)) begin
      $fatal(1, "tb_bulk: need +pix= +coef= +out= +n= +w= +h=");
    end
    if (n > Depth) $fatal(1, "tb_bulk: n = %0d exceeds Depth = %0d", n, Depth);
    if (!$value$plusargs("idle=%d", idle)) idle = 0;
    if (!$value$plusargs("stall=%d", stall)) stall = 0;
    width = WidthBits'(w);
    height = HeightBits'(h);
    $readmemh(pix_file, pix_mem, 0, n - 1);
    $readmemh(coef_file, coef_mem, 0, n - 1);
    fd = $fopen(out_file, "w");
    pi = 0; ci = 0; oi = 0;
    pix_valid = 1'b0; coef_valid = 1'b0; out_ready = 1'b0;
    repeat (3) @(posedge clk);
    #1 rst_n = 1'b1;
  end

  // Transfers are decided by the values present at the edge; the next values are
  // scheduled with non-blocking assignments, so the DUT samples the old ones.
  always @(posedge clk) begin
    int unsigned pn, cn;
    if (rst_n) begin
      pn = pi + ((pix_valid && pix_ready) ? 1 : 0);
      cn = ci + ((coef_valid && coef_ready) ? 1 : 0);
      pi <= pn;
      ci <= cn;
      if (out_valid && out_ready) begin
        $fwrite(fd, "%h\n", {out_sof, out_eol, out_data});
        oi = oi + 1;
        if (oi == n) begin
          $fclose(fd);
          if (err) $display("tb_bulk: frame_err_o set");
          $finish;
        end
      end
      pix_valid <= (pn < n) && (idle == 0 || ($urandom % 100) >= idle);
      coef_valid <= (cn < n) && (idle == 0 || ($urandom % 100) >= idle);
      out_ready <= stall == 0 || ($urandom % 100) >= stall;
    end
  end
endmodule
