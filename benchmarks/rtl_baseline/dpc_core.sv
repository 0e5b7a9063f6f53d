// Defective-pixel correction, docs/datapath.md section "DPC".
//
// A bad pixel is replaced by floor((2S + n) / (2n)) = floor((S + floor(n/2)) / n), the
// half-up rounded mean of its n in-frame good neighbours (sum S); with n = 0 it passes.
// Neighbours outside the frame are masked, never padded.
//
// Structure: two line buffers (MaxWidth entries of B+1 bits: value and bad flag) and a
// 3x3 window. Every accepted item (a pixel, or a "phantom" while flushing) shifts one
// column into the window; the window is centred one row and one column behind the input,
// so once W+1 items have entered, each further item emits exactly one output, in raster
// order. The in-frame masks come from an output position counter.
//
// Frame boundaries: after the last pixel of a frame, the W+1 outputs still owed are
// either pushed out by the next frame's pixels (the next frame's first pixel is already
// valid and has the same width and height: no bubble) or by W+1 phantom items that the
// core generates itself (input stalled meanwhile). The frame size is sampled at the
// first pixel after reset or after a flush.
//
// Pipeline: window register -> neighbour sum/count -> reciprocal multiply -> output.
module dpc_core #(
  parameter int unsigned OutBits    = 14,
  parameter int unsigned MaxWidth   = 1024,
  parameter int unsigned MaxHeight  = 1024,
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
  // frame size, or the frame size was outside its legal range.
  output logic                  frame_err_o
);

  localparam int unsigned AddrBits = (MaxWidth > 1) ? $clog2(MaxWidth) : 1;
  localparam int unsigned LeadBits = $clog2(MaxWidth + 2);
  localparam int unsigned EntBits  = OutBits + 1;  // {bad, value}
  // Neighbour sum and the rounded numerator M = S + floor(n/2) < 2^(B+3).
  localparam int unsigned NumBits  = OutBits + 3;
  // Reciprocal shift K = (B+3) + 3: with R = ceil(2^K/n), n <= 8 and M < 2^(B+3) the
  // error M*(R*n - 2^K) < 8*2^(B+3) = 2^K, so (M*R) >> K == floor(M/n) exactly
  // (cocotb_tests/test_dpc_core.py checks every M for every n).
  localparam int unsigned RecShift = NumBits + 3;
  localparam int unsigned RecBits  = RecShift + 1;
  localparam int unsigned MulBits  = NumBits + RecBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (OutBits >= 1 && OutBits <= 24)
      else $fatal(1, "dpc_core: OutBits = %0d outside 1..24", OutBits);
    assert (MaxWidth >= 1 && MaxWidth <= 65535)
      else $fatal(1, "dpc_core: MaxWidth = %0d outside 1..65535", MaxWidth);
    assert (MaxHeight >= 1 && MaxHeight <= 65535)
      else $fatal(1, "dpc_core: MaxHeight = %0d outside 1..65535", MaxHeight);
  end
`endif

  // ---- reciprocal table ----------------------------------------------------------------
  typedef logic [RecBits-1:0] rec_t;
  function automatic rec_t recip(input int unsigned n);
    longint unsigned num;
    num = (longint'(1) << RecShift) + longint'(n) - 1;
    return rec_t'(num / longint'(n));
  endfunction

  // ---- pipeline handshake -------------------------------------------------------------
  logic win_valid_q, sum_valid_q, out_valid_q;
  logic win_ready, sum_ready, out_ready;

  assign out_ready = ~out_valid_q | m_ready_i;
  assign sum_ready = ~sum_valid_q | out_ready;
  assign win_ready = ~win_valid_q | sum_ready;

  // ---- input side state ----------------------------------------------------------------
  logic [WidthBits-1:0]  geo_w_q, cur_w;
  logic [HeightBits-1:0] geo_h_q, cur_h;
  logic [WidthBits-1:0]  col_q;   // column of the next item (pixels and phantoms)
  logic [HeightBits-1:0] row_q;   // row of the next real pixel
  logic [LeadBits-1:0]   lead_q;  // items accepted before the first output, up to W+1
  logic                  tail_q;  // last pixel of a frame accepted, outputs still owed
  logic                  flush_q; // phantom items being generated
  logic [WidthBits-1:0]  pc_q;    // phantom items generated in this flush
  logic                  err_q;

  logic fresh, geo_same, phantom_req, take_real, take_phantom, take;
  logic col_last, row_last, last_phantom, emit, geo_bad;
  logic exp_sof, exp_eol;

  // After reset or a flush no output is owed and a new frame size may be sampled.
  assign fresh    = (lead_q == '0) && !tail_q && !flush_q;
  assign cur_w    = fresh ? frame_width_i : geo_w_q;
  assign cur_h    = fresh ? frame_height_i : geo_h_q;
  assign geo_same = (frame_width_i == geo_w_q) && (frame_height_i == geo_h_q);
  // Flush when the frame is complete and its successor is not already waiting.
  assign phantom_req  = flush_q || (tail_q && !(s_valid_i && geo_same));
  assign s_ready_o    = win_ready && !phantom_req;
  assign take_real    = s_valid_i && s_ready_o;
  assign take_phantom = phantom_req && win_ready;
  assign take         = take_real || take_phantom;
  assign col_last     = (col_q == cur_w - WidthBits'(1));
  assign row_last     = (row_q == cur_h - HeightBits'(1));
  assign last_phantom = (pc_q == geo_w_q);
  assign emit         = (lead_q == LeadBits'(geo_w_q) + LeadBits'(1));
  assign exp_sof      = (row_q == '0) && (col_q == '0);
  assign exp_eol      = col_last;
  logic w_over, h_over;
  assign geo_bad = (cur_w == '0) || w_over || (cur_h == '0) || h_over;
  // A size port of all ones may already be the largest legal size: then no check.
  if (MaxWidth == (2 ** WidthBits) - 1) begin : gen_w_full
    assign w_over = 1'b0;
  end else begin : gen_w_check
    assign w_over = (cur_w > WidthBits'(MaxWidth));
  end
  if (MaxHeight == (2 ** HeightBits) - 1) begin : gen_h_full
    assign h_over = 1'b0;
  end else begin : gen_h_check
    assign h_over = (cur_h > HeightBits'(MaxHeight));
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_input_state
    if (!rst_ni) begin
      geo_w_q <= WidthBits'(1);
      geo_h_q <= HeightBits'(1);
      col_q   <= '0;
      row_q   <= '0;
      lead_q  <= '0;
      tail_q  <= 1'b0;
      flush_q <= 1'b0;
      pc_q    <= '0;
      err_q   <= 1'b0;
    end else begin
      if (take_real) begin
        if (fresh) begin
          geo_w_q <= frame_width_i;
          geo_h_q <= frame_height_i;
        end
        if ((s_sof_i != exp_sof) || (s_eol_i != exp_eol) || geo_bad) begin
          err_q <= 1'b1;
        end
        col_q <= col_last ? '0 : col_q + WidthBits'(1);
        if (col_last) begin
          row_q <= row_last ? '0 : row_q + HeightBits'(1);
        end
        tail_q <= col_last && row_last;
        if (!emit) lead_q <= lead_q + LeadBits'(1);
      end else if (take_phantom) begin
        if (last_phantom) begin
          // Every owed output has entered the window: back to the fresh state.
          flush_q <= 1'b0;
          tail_q  <= 1'b0;
          pc_q    <= '0;
          col_q   <= '0;
          row_q   <= '0;
          lead_q  <= '0;
        end else begin
          flush_q <= 1'b1;
          pc_q    <= pc_q + WidthBits'(1);
          col_q   <= col_last ? '0 : col_q + WidthBits'(1);
          if (!emit) lead_q <= lead_q + LeadBits'(1);
        end
      end
    end
  end

`ifndef SYNTHESIS
  // Same reset style as the state it watches; nothing is checked while in reset.
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_geo_check
    if (!rst_ni) begin
    end else if (take_real) begin
      assert (!geo_bad)
        else $error("dpc_core: frame size %0d x %0d outside 1..%0d x 1..%0d",
                    cur_w, cur_h, MaxWidth, MaxHeight);
    end
  end
`endif

  // ---- line buffers -------------------------------------------------------------------
  logic [EntBits-1:0] lb_top_q [MaxWidth];  // row two above the incoming item
  logic [EntBits-1:0] lb_mid_q [MaxWidth];  // row just above the incoming item
  logic [EntBits-1:0] col_top, col_mid, col_new;
  logic [AddrBits-1:0] addr;

  assign addr    = AddrBits'(col_q);
  assign col_top = lb_top_q[addr];
  assign col_mid = lb_mid_q[addr];
  // Phantom rows lie outside the frame; their content is masked, zero keeps it tidy.
  assign col_new = take_real ? {s_bad_i, s_pix_data_i} : '0;

  always_ff @(posedge clk_i) begin : p_line_buffers
    if (take) begin
      lb_top_q[addr] <= col_mid;
      lb_mid_q[addr] <= col_new;
    end
  end

  // ---- output position counter and window ----------------------------------------------
  logic [WidthBits-1:0]  oc_q;
  logic [HeightBits-1:0] or_q;
  logic                  oc_last, or_last;
  // win_q[row][col]: row 0 top, col 0 left (oldest column).
  logic [EntBits-1:0]    win_q [3][3];
  logic                  m_top_q, m_bot_q, m_left_q, m_right_q, w_sof_q, w_eol_q;

  assign oc_last = (oc_q == geo_w_q - WidthBits'(1));
  assign or_last = (or_q == geo_h_q - HeightBits'(1));

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_window
    if (!rst_ni) begin
      win_valid_q <= 1'b0;
      oc_q        <= '0;
      or_q        <= '0;
      m_top_q     <= 1'b0;
      m_bot_q     <= 1'b0;
      m_left_q    <= 1'b0;
      m_right_q   <= 1'b0;
      w_sof_q     <= 1'b0;
      w_eol_q     <= 1'b0;
      for (int r = 0; r < 3; r++) begin
        for (int c = 0; c < 3; c++) begin
          win_q[r][c] <= '0;
        end
      end
    end else begin
      if (take) begin
        for (int r = 0; r < 3; r++) begin
          win_q[r][0] <= win_q[r][1];
          win_q[r][1] <= win_q[r][2];
        end
        win_q[0][2] <= col_top;
        win_q[1][2] <= col_mid;
        win_q[2][2] <= col_new;
        win_valid_q <= emit;
        if (emit) begin
          // Flags of the output position the window now centres on.
          m_top_q   <= (or_q == '0);
          m_bot_q   <= or_last;
          m_left_q  <= (oc_q == '0);
          m_right_q <= oc_last;
          w_sof_q   <= (or_q == '0) && (oc_q == '0);
          w_eol_q   <= oc_last;
          oc_q      <= oc_last ? '0 : oc_q + WidthBits'(1);
          if (oc_last) or_q <= or_last ? '0 : or_q + HeightBits'(1);
        end
      end else if (sum_ready) begin
        win_valid_q <= 1'b0;
      end
      // After a flush the counters restart with the next frame.
      if (take_phantom && last_phantom) begin
        oc_q <= '0;
        or_q <= '0;
      end
    end
  end

  // ---- neighbour count and sum -----------------------------------------------------------
  logic [3:0]         nb_count;
  logic [NumBits-1:0] nb_sum, nb_num;

  always_comb begin : p_neighbours
    logic in_frame, good;
    nb_count = '0;
    nb_sum   = '0;
    for (int r = 0; r < 3; r++) begin
      for (int c = 0; c < 3; c++) begin
        in_frame = !((r == 0 && m_top_q) || (r == 2 && m_bot_q) ||
                     (c == 0 && m_left_q) || (c == 2 && m_right_q));
        good     = in_frame && !win_q[r][c][OutBits] && !(r == 1 && c == 1);
        if (good) begin
          nb_count = nb_count + 4'd1;
          nb_sum   = nb_sum + NumBits'(win_q[r][c][OutBits-1:0]);
        end
      end
    end
    // floor((2S + n) / (2n)) = floor((S + floor(n/2)) / n)
    nb_num = nb_sum + NumBits'(nb_count >> 1);
  end

  logic [NumBits-1:0] num_q;
  logic [3:0]         cnt_q;
  logic [OutBits-1:0] ctr_q;
  logic               ctr_bad_q, s_sof_q, s_eol_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_sum_stage
    if (!rst_ni) begin
      sum_valid_q <= 1'b0;
      num_q       <= '0;
      cnt_q       <= '0;
      ctr_q       <= '0;
      ctr_bad_q   <= 1'b0;
      s_sof_q     <= 1'b0;
      s_eol_q     <= 1'b0;
    end else if (sum_ready) begin
      sum_valid_q <= win_valid_q;
      if (win_valid_q) begin
        num_q     <= nb_num;
        cnt_q     <= nb_count;
        ctr_q     <= win_q[1][1][OutBits-1:0];
        ctr_bad_q <= win_q[1][1][OutBits];
        s_sof_q   <= w_sof_q;
        s_eol_q   <= w_eol_q;
      end
    end
  end

  // ---- division by n: multiply by the reciprocal, shift -------------------------------
  rec_t               rec;
  logic [MulBits-1:0] prod;
  logic [OutBits-1:0] mean, out_d;

  always_comb begin : p_recip
    unique case (cnt_q)
      4'd1:    rec = recip(1);
      4'd2:    rec = recip(2);
      4'd3:    rec = recip(3);
      4'd4:    rec = recip(4);
      4'd5:    rec = recip(5);
      4'd6:    rec = recip(6);
      4'd7:    rec = recip(7);
      4'd8:    rec = recip(8);
      default: rec = '0;  // n = 0: the centre passes through
    endcase
  end

  assign prod  = MulBits'(num_q) * MulBits'(rec);
  // The mean of B-bit values fits B bits; higher product bits are zero.
  assign mean  = prod[RecShift +: OutBits];
  assign out_d = (ctr_bad_q && cnt_q != 4'd0) ? mean : ctr_q;

  logic unused_prod;
  assign unused_prod = ^{prod[MulBits-1:RecShift+OutBits], prod[RecShift-1:0]};

  logic [OutBits-1:0] out_q;
  logic               o_sof_q, o_eol_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_out_stage
    if (!rst_ni) begin
      out_valid_q <= 1'b0;
      out_q       <= '0;
      o_sof_q     <= 1'b0;
      o_eol_q     <= 1'b0;
    end else if (out_ready) begin
      out_valid_q <= sum_valid_q;
      if (sum_valid_q) begin
        out_q   <= out_d;
        o_sof_q <= s_sof_q;
        o_eol_q <= s_eol_q;
      end
    end
  end

  assign m_valid_o    = out_valid_q;
  assign m_pix_data_o = out_q;
  assign m_sof_o      = o_sof_q;
  assign m_eol_o      = o_eol_q;
  assign frame_err_o  = err_q;

endmodule
