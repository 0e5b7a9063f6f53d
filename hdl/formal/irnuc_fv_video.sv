// Video framing over a valid/ready stream with start-of-frame and end-of-line markers
// (Xilinx UG934 "AXI4-Stream Video": TUSER[0] on a frame's first beat only, TLAST on the
// last beat of every line), counted against the frame size, for `irnuc formal`
// (docs/formal.md); FORMAL only. The size of a frame is width_i x height_i at its first
// beat (the size the design took at that frame's start), kept to its last beat.
//   a_sof        sof on a frame's first beat, never elsewhere (a frame is exactly W x H beats:
//                the beat after its last is the next frame's first)
//   a_eol        eol on the W-th beat of every line, never elsewhere
//   a_size       a frame's size is at least 1 x 1
module irnuc_fv_video #(
  parameter int unsigned WidthBits  = 11,
  parameter int unsigned HeightBits = 11
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic                  valid_i,
  input logic                  ready_i,
  input logic                  sof_i,
  input logic                  eol_i,
  input logic [WidthBits-1:0]  width_i,
  input logic [HeightBits-1:0] height_i
);

`ifdef FORMAL
  logic                  in_q, beat, first, line_end, frame_end;
  logic [WidthBits-1:0]  x_q, w_q, w;
  logic [HeightBits-1:0] y_q, h_q, h;

  assign beat      = valid_i && ready_i;
  assign first     = !in_q;
  assign w         = first ? width_i : w_q;
  assign h         = first ? height_i : h_q;
  assign line_end  = (first ? '0 : x_q) == w - WidthBits'(1);
  assign frame_end = line_end && (first ? '0 : y_q) == h - HeightBits'(1);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_position
    if (!rst_ni) begin
      in_q <= 1'b0;
      x_q  <= '0;
      y_q  <= '0;
    end else if (beat) begin
      in_q <= !frame_end;
      x_q  <= line_end ? '0 : (first ? WidthBits'(1) : x_q + WidthBits'(1));
      y_q  <= first ? HeightBits'(line_end) : y_q + HeightBits'(line_end);
    end
  end

  always_ff @(posedge clk_i) begin : p_size
    if (beat && first) begin
      w_q <= width_i;
      h_q <= height_i;
    end
  end

  always_comb begin : p_check
    if (rst_ni) begin
      if (beat) begin
        a_sof: assert (sof_i == first);
        a_eol: assert (eol_i == line_end);
        if (first) begin
          a_size: assert (width_i != '0 && height_i != '0);
        end
      end
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, valid_i, ready_i, sof_i, eol_i, width_i, height_i};
`endif

endmodule
