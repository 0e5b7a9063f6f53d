// Defective-pixel correction, docs/datapath.md section "DPC".
//
// A bad pixel is replaced by floor((2S + n) / (2n)) = floor((S + floor(n/2)) / n), the
// half-up rounded mean of its n in-frame good neighbours (sum S); with n = 0 it passes.
// Neighbours outside the frame are masked, never padded.
//
// Structure: a line buffer of MaxWidth words {row-2, row-1} (value and bad flag of the two
// rows above the incoming item, one memory, one read and one write port, read data
// registered twice: the block RAM's read and output registers) and a 3x3 window. dpc_ctrl decides which item (pixel or phantom) enters the window and
// where the window centres (one row and one column behind the newest item); see there for
// the frame/flush FSM and the back-to-back frame rule.
//
// Pipeline (every register moves with one enable, en = "the output register can take an
// item", a flop: no path runs from m_ready_i, s_valid_i or the frame size to s_ready_o):
//   u_in     input register (irnuc_spill_register); with InReg = 0 none: the caller's
//            driver of s_* is a register output (the NUC core's output register in
//            method_dpc_top), which then is the input register (one cycle less latency)
//   window   the item enters: line buffer word read two items ahead, written one item late
//   mask     the masked in-frame good neighbours and their good flags, registered
//   u_sum    the 8 masked values summed, 3 stages (irnuc_add_tree), beside them the count
//            n (stage 1), floor(n/2) and R[n] (stage 2); then M = S + floor(n/2) (stage 4),
//            n != 0 and R[n] along
//   u_mul    M * R[n] as DSP-sized partial products, the DSPs' input and output registers
//            (irnuc_mul_parts, two stages)
//   u_prod   their sum, clog2(parts) stages; mean = (M * R[n]) >> K
//   u_out    output register (irnuc_spill_register)
// Latency after the window: 10 + clog2(parts) cycles from a pixel at s_* to the output it
// completes (parts = ceil((B+3)/17) * ceil((B+7)/17): minimal 10, typical14 11, wide16 12);
// the output of pixel (r, c) is completed by input (r+1, c+1), see docs/rtl.md.
module dpc_core
  import irnuc_pkg::*;
#(
  parameter int unsigned OutBits    = 14,
  parameter int unsigned MaxWidth   = 1024,
  parameter int unsigned MaxHeight  = 1024,
  // s_* and the frame size at its frame starts are checked here (0: by the caller, whose
  // driver of s_* is a checked spill register and which checks the frame size).
  parameter bit          CheckIn    = 1'b1,
  // s_* enters through an input register of its own (0: s_* comes straight from a
  // register of the caller, an irnuc_spill_register's output whose ready input may then
  // depend combinationally on this core's control flops; no path from s_valid_i or
  // m_ready_i reaches s_ready_o either way).
  parameter bit          InReg      = 1'b1,
  // Derived, do not override.
  localparam int unsigned WidthBits  = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits = $clog2(MaxHeight + 1)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Run-time frame size, 1..MaxWidth and 1..MaxHeight; hold stable during a frame.
  input  logic [WidthBits-1:0]  frame_width_i,
  input  logic [HeightBits-1:0] frame_height_i,
  // Input stream: NUC output, bad flag and frame markers (checked, see frame_err_o).
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [OutBits-1:0]    s_pix_data_i,
  input  logic                  s_bad_i,
  input  logic                  s_sof_i,
  input  logic                  s_eol_i,
  // Output stream: corrected pixel with start-of-frame and end-of-line markers.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic                  m_sof_o,
  output logic                  m_eol_o,
  // Sticky until reset: an input marker disagreed with the position counted from the
  // frame size, or the frame size was outside its legal range at a frame start.
  output logic                  frame_err_o
);

  localparam int unsigned AddrBits = (MaxWidth > 1) ? $clog2(MaxWidth) : 1;
  localparam int unsigned EntBits  = OutBits + 1;  // {bad, value}
  // Neighbour sum and the rounded numerator M = S + floor(n/2) < 2^(B+3).
  localparam int unsigned NumBits  = OutBits + 3;
  localparam int unsigned RecShift = dpc_recip_shift(OutBits);
  localparam int unsigned RecBits  = RecShift + 1;
  localparam int unsigned MulBits  = NumBits + RecBits;
  localparam int unsigned Parts    = mul_parts(NumBits, RecBits);
  localparam int unsigned InBits   = OutBits + 3;
  // Side band after the window: {sof, eol, n != 0, centre bad, centre value}.
  localparam int unsigned CtrBits  = OutBits + 4;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (OutBits >= OutBitsMin && OutBits <= OutBitsMax)
      else $fatal(1, "dpc_core: OutBits = %0d outside %0d..%0d", OutBits, OutBitsMin,
                  OutBitsMax);
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax)
      else $fatal(1, "dpc_core: MaxWidth = %0d outside %0d..%0d", MaxWidth, MaxWidthMin,
                  MaxWidthMax);
    assert (MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "dpc_core: MaxHeight = %0d outside %0d..%0d", MaxHeight, MaxHeightMin,
                  MaxHeightMax);
  end
`endif

  // Pipeline enable: the output register has room (a flop of u_out).
  logic en;

  // ---- input register ------------------------------------------------------------------
  logic               in_valid, in_ready, in_bad, in_sof, in_eol;
  logic [OutBits-1:0] in_pix;

  if (InReg) begin : gen_in_reg
    irnuc_spill_register #(.DataBits(InBits), .CheckIn(CheckIn)) u_in (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .valid_i(s_valid_i),
      .ready_o(s_ready_o),
      .data_i ({s_eol_i, s_sof_i, s_bad_i, s_pix_data_i}),
      .valid_o(in_valid),
      .ready_i(in_ready),
      .data_o ({in_eol, in_sof, in_bad, in_pix})
    );
  end else begin : gen_in_direct
    assign in_valid  = s_valid_i;
    assign s_ready_o = in_ready;
    assign {in_eol, in_sof, in_bad, in_pix} = {s_eol_i, s_sof_i, s_bad_i, s_pix_data_i};
  end

  // ---- control ---------------------------------------------------------------------------
  logic                take, phantom, lb_w1, lb_w2, lb_w3;
  logic [AddrBits-1:0] lb_rd_addr, lb_wr_addr;
  logic                win_valid, win_top, win_bottom, win_left, win_right, win_sof, win_eol;

  dpc_ctrl #(
    .MaxWidth (MaxWidth),
    .MaxHeight(MaxHeight)
  ) u_ctrl (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .frame_width_i (frame_width_i),
    .frame_height_i(frame_height_i),
    .en_i          (en),
    .pix_valid_i   (in_valid),
    .pix_sof_i     (in_sof),
    .pix_eol_i     (in_eol),
    .pix_ready_o   (in_ready),
    .take_o        (take),
    .phantom_o     (phantom),
    .lb_rd_addr_o  (lb_rd_addr),
    .lb_wr_addr_o  (lb_wr_addr),
    .lb_w1_o       (lb_w1),
    .lb_w2_o       (lb_w2),
    .lb_w3_o       (lb_w3),
    .win_valid_o   (win_valid),
    .win_top_o     (win_top),
    .win_bottom_o  (win_bottom),
    .win_left_o    (win_left),
    .win_right_o   (win_right),
    .win_sof_o     (win_sof),
    .win_eol_o     (win_eol),
    .frame_err_o   (frame_err_o)
  );

  // ---- line buffer and window -------------------------------------------------------------
  // win_q[row][col]: row 0 top, col 0 left (oldest column); column 2 is the newest item.
  logic [EntBits-1:0]   win_q [3][3];
  logic [EntBits-1:0]   col_top, col_mid, col_new;
  logic [2*EntBits-1:0] lb_next;

  // Phantom rows lie outside the frame; their content is masked, zero keeps it tidy.
  assign col_new = phantom ? '0 : {in_bad, in_pix};

  // Word of a column: {row two above, row just above} the item entering at that column.
  // It is read two items ahead and leaves the line buffer's output register (the block
  // RAM's own: its output goes straight into a register) one item later, as lb_next; it is
  // written one item late ({mid, new} of the item, from the window).
  irnuc_line_buffer #(
    .Depth   (MaxWidth),
    .DataBits(2 * EntBits)
  ) u_lb (
    .clk_i    (clk_i),
    .wr_en_i  (take),
    .wr_addr_i(lb_wr_addr),
    .wr_data_i({win_q[1][2], win_q[2][2]}),
    .rd_en_i  (take),
    .rd_addr_i(lb_rd_addr),
    .rd_data_o(lb_next)
  );

  // With W <= 3 the word comes from the item W before, which was written in the same cycle
  // as the read or later: take it from the window, which holds the last three items.
  always_comb begin : p_column
    if (lb_w1) begin
      {col_top, col_mid} = {win_q[1][2], win_q[2][2]};
    end else if (lb_w2) begin
      {col_top, col_mid} = {win_q[1][1], win_q[2][1]};
    end else if (lb_w3) begin
      {col_top, col_mid} = {win_q[1][0], win_q[2][0]};
    end else begin
      {col_top, col_mid} = lb_next;
    end
  end

  always_ff @(posedge clk_i) begin : p_window
    if (take) begin
      for (int r = 0; r < 3; r++) begin
        win_q[r][0] <= win_q[r][1];
        win_q[r][1] <= win_q[r][2];
      end
      win_q[0][2] <= col_top;
      win_q[1][2] <= col_mid;
      win_q[2][2] <= col_new;
    end
  end

  // ---- neighbours: in-frame good ones, their count n and sum S --------------------------
  // The mask stage registers the 8 masked values and the 8 good flags; the count n, floor(n/2)
  // and R[n] are taken from the registered flags beside the sum's first levels (a popcount
  // and a table of the count would otherwise sit between the window and one register).
  logic [NumBits-1:0]      nb_leaves [8];  // the 8 masked neighbours (unpacked)
  logic                    nb_good [8];    // their good flags (unpacked: a packed byte
                                           // costs the simulator a read-modify-write per bit)

  always_comb begin : p_neighbours
    logic in_frame;
    int unsigned k;
    k = 0;
    for (int r = 0; r < 3; r++) begin
      for (int c = 0; c < 3; c++) begin
        if (!(r == 1 && c == 1)) begin
          in_frame = !((r == 0 && win_top) || (r == 2 && win_bottom) ||
                       (c == 0 && win_left) || (c == 2 && win_right));
          nb_good[k]   = in_frame && !win_q[r][c][OutBits];
          nb_leaves[k] = nb_good[k] ? NumBits'(win_q[r][c][OutBits-1:0]) : '0;
          k++;
        end
      end
    end
  end

  logic                    mask_valid_q;
  logic [NumBits-1:0]      mask_leaves_q [8];
  logic                    mask_good_q [8];
  logic [CtrBits-2:0]      mask_ctr_q;  // {sof, eol, centre bad, centre value}

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_mask_valid
    if (!rst_ni) begin
      mask_valid_q <= 1'b0;
    end else if (en) begin
      mask_valid_q <= win_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_mask
    if (en) begin
      mask_leaves_q <= nb_leaves;
      mask_good_q   <= nb_good;
      mask_ctr_q    <= {win_sof, win_eol, win_q[1][1]};
    end
  end

  // The count n (beside the sum's level 1), then floor(n/2), n != 0 and R[n] (level 2),
  // held through level 3: the adder tree of the 8 values has 3 levels, floor(n/2) is added
  // in a fourth stage.
  logic [3:0]         cnt_d, cnt_q, half2_q, half3_q;
  logic [RecBits-1:0] nb_recip, rec2_q, rec3_q;
  logic               nz2_q, nz3_q;

  // One sum (a loop of 8 partial sums costs the simulator a store per step).
  assign cnt_d = 4'(mask_good_q[0]) + 4'(mask_good_q[1]) + 4'(mask_good_q[2])
                 + 4'(mask_good_q[3]) + 4'(mask_good_q[4]) + 4'(mask_good_q[5])
                 + 4'(mask_good_q[6]) + 4'(mask_good_q[7]);

  // R[n] from irnuc_pkg::dpc_recip (constant calls: a 9-entry table).
  always_comb begin : p_recip
    unique case (cnt_q)
      4'd1:    nb_recip = RecBits'(dpc_recip(OutBits, 1));
      4'd2:    nb_recip = RecBits'(dpc_recip(OutBits, 2));
      4'd3:    nb_recip = RecBits'(dpc_recip(OutBits, 3));
      4'd4:    nb_recip = RecBits'(dpc_recip(OutBits, 4));
      4'd5:    nb_recip = RecBits'(dpc_recip(OutBits, 5));
      4'd6:    nb_recip = RecBits'(dpc_recip(OutBits, 6));
      4'd7:    nb_recip = RecBits'(dpc_recip(OutBits, 7));
      4'd8:    nb_recip = RecBits'(dpc_recip(OutBits, 8));
      default: nb_recip = '0;  // n = 0: the centre passes through
    endcase
  end

  always_ff @(posedge clk_i) begin : p_count_q
    if (en) begin
      cnt_q   <= cnt_d;
      rec2_q  <= nb_recip;
      // floor((2S + n) / (2n)) = floor((S + floor(n/2)) / n)
      half2_q <= cnt_q >> 1;
      nz2_q   <= cnt_q != 4'd0;
      rec3_q  <= rec2_q;
      half3_q <= half2_q;
      nz3_q   <= nz2_q;
    end
  end

  logic               s8_valid;
  logic [NumBits-1:0] s8_sum;
  logic [CtrBits-2:0] s8_ctr;

  irnuc_add_tree #(
    .Leaves  (8),
    .Width   (NumBits),
    .SideBits(CtrBits - 1)
  ) u_sum (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (mask_valid_q),
    .leaves_i({mask_leaves_q[7], mask_leaves_q[6], mask_leaves_q[5], mask_leaves_q[4],
               mask_leaves_q[3], mask_leaves_q[2], mask_leaves_q[1], mask_leaves_q[0]}),
    .side_i  (mask_ctr_q),
    .valid_o (s8_valid),
    .sum_o   (s8_sum),
    .side_o  (s8_ctr)
  );

  // M = S + floor(n/2), with R[n] and {sof, eol, n != 0, centre bad, centre value}.
  logic               sum_valid;
  logic [NumBits-1:0] sum_m;
  logic [RecBits-1:0] sum_recip;
  logic [CtrBits-1:0] sum_ctr;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_sum_valid
    if (!rst_ni) begin
      sum_valid <= 1'b0;
    end else if (en) begin
      sum_valid <= s8_valid;
    end
  end

  always_ff @(posedge clk_i) begin : p_sum
    if (en) begin
      sum_m     <= s8_sum + NumBits'(half3_q);
      sum_recip <= rec3_q;
      sum_ctr   <= {s8_ctr[CtrBits-2 -: 2], nz3_q, s8_ctr[OutBits:0]};
    end
  end

  // ---- division by n: M * R[n], then >> K ------------------------------------------------
  logic                          mul_valid;
  logic [Parts-1:0][MulBits-1:0] prod_parts;
  logic [CtrBits-1:0]            mul_ctr;

  irnuc_mul_parts #(
    .ABits   (NumBits),
    .BBits   (RecBits),
    .SideBits(CtrBits)
  ) u_mul (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .en_i   (en),
    .valid_i(sum_valid),
    .a_i    (sum_m),
    .b_i    (sum_recip),
    .side_i (sum_ctr),
    .valid_o(mul_valid),
    .parts_o(prod_parts),
    .side_o (mul_ctr)
  );

  logic               prod_valid;
  logic [MulBits-1:0] prod;
  logic [CtrBits-1:0] prod_ctr;

  irnuc_add_tree #(
    .Leaves  (Parts),
    .Width   (MulBits),
    .SideBits(CtrBits)
  ) u_prod (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .en_i    (en),
    .valid_i (mul_valid),
    .leaves_i(prod_parts),
    .side_i  (mul_ctr),
    .valid_o (prod_valid),
    .sum_o   (prod),
    .side_o  (prod_ctr)
  );

  // ---- output ----------------------------------------------------------------------------
  logic               out_sof, out_eol, out_nonzero, out_bad;
  logic [OutBits-1:0] out_ctr, out_mean, out_d;

  assign {out_sof, out_eol, out_nonzero, out_bad, out_ctr} = prod_ctr;
  // The mean of B-bit values fits B bits; higher product bits are zero.
  assign out_mean = prod[RecShift +: OutBits];
  assign out_d    = (out_bad && out_nonzero) ? out_mean : out_ctr;

  logic unused_prod;
  assign unused_prod = ^{prod[MulBits-1:RecShift+OutBits], prod[RecShift-1:0]};

  irnuc_spill_register #(.DataBits(OutBits + 2)) u_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(prod_valid),
    .ready_o(en),
    .data_i ({out_sof, out_eol, out_d}),
    .valid_o(m_valid_o),
    .ready_i(m_ready_i),
    .data_o ({m_sof_o, m_eol_o, m_pix_data_o})
  );

`ifdef IRNUC_ASSERT
  // Protocol assertions of s_* and m_*: in u_in (unless CheckIn = 0 or InReg = 0) and u_out
  // (irnuc_spill_register), whose ports these are; the frame size at a frame start:
  if (CheckIn) begin : gen_assert_frame
    irnuc_frame_assert #(
      .MaxWidth (MaxWidth),
      .MaxHeight(MaxHeight)
    ) u_assert_frame (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .start_i (s_valid_i && s_ready_o && s_sof_i),
      .width_i (frame_width_i),
      .height_i(frame_height_i)
    );
  end
`endif

endmodule
