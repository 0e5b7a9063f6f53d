// Frame and flush control of dpc_core: which item enters the 3x3 window, where the line
// buffer is read and written, which output position the window centres on.
//
// Items: every cycle with en_i high, at most one item enters the window: the waiting
// pixel, or a "phantom" (an item outside the frame, value 0) that the core makes itself
// to push the last outputs of a frame out. The window is centred one row and one column
// behind the newest item, so the first W+1 items after Idle emit nothing and every
// further item emits exactly one output, in raster order.
//
// FSM (irnuc_pkg::dpc_state_e):
//   DpcIdle   no output owed. A pixel starts a frame: the frame size is sampled.
//   DpcFrame  pixels of the frame are taken; the last one (last row, last column) -> Tail.
//   DpcTail   the frame is complete, W+1 outputs are owed. If the next frame's first pixel
//             is already waiting and the frame size is unchanged, it is taken at once
//             (back-to-back frames, no bubble) -> Frame (or Tail for a one-pixel frame);
//             otherwise the first phantom is taken -> Flush.
//   DpcFlush  phantoms (input not ready) until W+1 have entered -> Idle.
//
// Every decision comes from registers: the frame size inputs are registered (and compared
// with the latched size one cycle ahead), every "counter at its last value" flag is
// computed one step ahead, so en_i, the waiting pixel's valid and this state decide an
// item in two levels of logic, and whether one enters at all (take_o, the enable of the
// window, the line buffer and the counters) in one. The line buffer's read address is a
// register loaded with the next cycle's address.
module dpc_ctrl
  import irnuc_pkg::*;
#(
  parameter int unsigned MaxWidth   = 1024,
  parameter int unsigned MaxHeight  = 1024,
  // Derived, do not override.
  localparam int unsigned WidthBits  = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits = $clog2(MaxHeight + 1),
  localparam int unsigned AddrBits   = (MaxWidth > 1) ? $clog2(MaxWidth) : 1
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Run-time frame size (registered here).
  input  logic [WidthBits-1:0]  frame_width_i,
  input  logic [HeightBits-1:0] frame_height_i,
  // The pipeline moves this cycle (the core's output register has room).
  input  logic                  en_i,
  // The waiting pixel (the core's input register) and its markers, checked here.
  input  logic                  pix_valid_i,
  input  logic                  pix_sof_i,
  input  logic                  pix_eol_i,
  output logic                  pix_ready_o,
  // An item enters the window this cycle; it is a phantom when phantom_o.
  output logic                  take_o,
  output logic                  phantom_o,
  // Line buffer (both with take_o): read the column of the item after the next one, write
  // the previous item's column; the read data are stale when W <= 3 (see dpc_core).
  output logic [AddrBits-1:0]   lb_rd_addr_o,
  output logic [AddrBits-1:0]   lb_wr_addr_o,
  output logic                  lb_w1_o,
  output logic                  lb_w2_o,
  output logic                  lb_w3_o,
  // The window holds an output position (registered with the window) and its borders.
  output logic                  win_valid_o,
  output logic                  win_top_o,
  output logic                  win_bottom_o,
  output logic                  win_left_o,
  output logic                  win_right_o,
  output logic                  win_sof_o,
  output logic                  win_eol_o,
  // Sticky until reset: a marker disagreed with the counted position, or the frame size
  // was outside 1..MaxWidth x 1..MaxHeight at a frame start.
  output logic                  frame_err_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax)
      else $fatal(1, "dpc_ctrl: MaxWidth = %0d outside %0d..%0d", MaxWidth, MaxWidthMin,
                  MaxWidthMax);
    assert (MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "dpc_ctrl: MaxHeight = %0d outside %0d..%0d", MaxHeight, MaxHeightMin,
                  MaxHeightMax);
  end
`endif

  // ---- registered frame size and its flags --------------------------------------------
  logic [WidthBits-1:0]  fw_q, fw_m2_q;
  logic [HeightBits-1:0] fh_q, fh_m2_q;
  logic                  fw_is1_q, fw_is2_q, fw_is3_q, fw_is4_q, fw_bad_q;
  logic                  fh_is1_q, fh_is2_q, fh_bad_q;
  logic                  w_over, h_over;

  // A size port of all ones may already be the largest legal size: then no upper check.
  if (MaxWidth == (2 ** WidthBits) - 1) begin : gen_w_full
    assign w_over = 1'b0;
  end else begin : gen_w_check
    assign w_over = (frame_width_i > WidthBits'(MaxWidth));
  end
  if (MaxHeight == (2 ** HeightBits) - 1) begin : gen_h_full
    assign h_over = 1'b0;
  end else begin : gen_h_check
    assign h_over = (frame_height_i > HeightBits'(MaxHeight));
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_size_in
    if (!rst_ni) begin
      fw_q     <= WidthBits'(1);
      fw_m2_q  <= '1;
      fw_is1_q <= 1'b1;
      fw_is2_q <= 1'b0;
      fw_is3_q <= 1'b0;
      fw_is4_q <= 1'b0;
      fw_bad_q <= 1'b0;
      fh_q     <= HeightBits'(1);
      fh_m2_q  <= '1;
      fh_is1_q <= 1'b1;
      fh_is2_q <= 1'b0;
      fh_bad_q <= 1'b0;
    end else begin
      fw_q     <= frame_width_i;
      fw_m2_q  <= frame_width_i - WidthBits'(2);
      fw_is1_q <= (frame_width_i == WidthBits'(1));
      fw_is2_q <= (frame_width_i == WidthBits'(2));
      fw_is3_q <= (frame_width_i == WidthBits'(3));
      fw_is4_q <= (frame_width_i == WidthBits'(4));
      fw_bad_q <= (frame_width_i == '0) || w_over;
      fh_q     <= frame_height_i;
      fh_m2_q  <= frame_height_i - HeightBits'(2);
      fh_is1_q <= (frame_height_i == HeightBits'(1));
      fh_is2_q <= (frame_height_i == HeightBits'(2));
      fh_bad_q <= (frame_height_i == '0) || h_over;
    end
  end

  // ---- state ----------------------------------------------------------------------------
  dpc_state_e state_q, state_d;
  logic       idle, tail, flush;

  // Latched frame size (sampled at a frame start from Idle).
  logic [WidthBits-1:0]  geo_w_q, geo_wm2_q;
  logic [HeightBits-1:0] geo_h_q, geo_hm2_q;
  logic                  geo_w_is1_q, geo_w_is2_q, geo_w_is3_q, geo_h_is1_q;
  // The registered size equals the latched one: same, made from three flops (below).
  logic                  same;

  // Input position: column of the next item (pixels and phantoms), row of the next pixel.
  logic [WidthBits-1:0]  col_q;
  logic [AddrBits-1:0]   prev_col_q;
  logic [HeightBits-1:0] row_q;
  logic                  col_last_q, row_last_q;
  // Items since Idle: a full row has entered (wrapped), then one more (emit: from now on
  // every item emits an output). Phantoms: a full row of them has entered.
  logic                  wrapped_q, emit_q, ph_wrapped_q;

  // Output position the next emitting item centres the window on.
  logic [WidthBits-1:0]  oc_q;
  logic [HeightBits-1:0] or_q;
  logic                  oc_first_q, oc_last_q, or_first_q, or_last_q;

  logic                  err_q;

  assign idle  = (state_q == DpcIdle);
  assign tail  = (state_q == DpcTail);
  assign flush = (state_q == DpcFlush);

  // ---- which item enters --------------------------------------------------------------
  logic accept, phantom_req, take_pix, take_phantom, take, last_phantom;
  logic cur_col_last, cur_row_last, frame_last, sample;

  // A pixel is accepted in Idle and Frame, and in Tail when the frame size is unchanged.
  assign accept       = !flush && !(tail && !same);
  assign phantom_req  = flush || (tail && !(pix_valid_i && same));
  assign pix_ready_o  = en_i && accept;
  assign take_pix     = pix_valid_i && pix_ready_o;
  assign take_phantom = en_i && phantom_req;
  // take = take_pix || take_phantom, written in one level: in Tail either the pixel or a
  // phantom enters, in Flush a phantom, in Idle and Frame the waiting pixel. It enables the
  // window, the line buffer and every counter, so its depth is the core's clock period.
  assign take         = en_i && (pix_valid_i || tail || flush);
  // ph_wrapped_q is set only in Flush or by the phantom that enters it, and cleared by the
  // last phantom, so it implies Flush, where every item is a phantom (a_wrapped_in_flush).
  assign last_phantom = take && ph_wrapped_q;
  // In Idle no phantom is made: every item taken is a pixel.
  assign sample       = idle && take;

  // In Idle the registered frame size applies (it is sampled with the first pixel).
  assign cur_col_last = idle ? fw_is1_q : col_last_q;
  assign cur_row_last = idle ? fh_is1_q : row_last_q;
  assign frame_last   = cur_col_last && cur_row_last;

  always_comb begin : p_next_state
    state_d = state_q;
    unique case (state_q)
      DpcIdle, DpcFrame: begin
        if (take_pix) state_d = frame_last ? DpcTail : DpcFrame;
      end
      DpcTail: begin
        if (take_pix) begin
          state_d = frame_last ? DpcTail : DpcFrame;
        end else if (take_phantom) begin
          state_d = DpcFlush;
        end
      end
      DpcFlush: begin
        if (last_phantom) state_d = DpcIdle;
      end
      default: state_d = DpcIdle;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      state_q <= DpcIdle;
    end else begin
      state_q <= state_d;
    end
  end

  // ---- frame size ------------------------------------------------------------------------
  // same = "the registered size equals the latched one". Both of its candidates are
  // compared one cycle ahead, each against its own register, and kept apart: the size
  // inputs against the registered size (what the latched size becomes when this cycle
  // samples) and against the latched size (when it does not); the sample decision (behind
  // en_i, the core's output register) only loads a flop of its own, and the three flops
  // pick same in one level. Selecting the compared size by sample before one compare made
  // en_i -> sample -> compare -> same one path of 6-7 LUT levels (docs/rtl.md).
  logic same_new_q, same_geo_q, sampled_q;

  assign same = sampled_q ? same_new_q : same_geo_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_geometry
    if (!rst_ni) begin
      geo_w_q     <= WidthBits'(1);
      geo_wm2_q   <= '1;
      geo_w_is1_q <= 1'b1;
      geo_w_is2_q <= 1'b0;
      geo_w_is3_q <= 1'b0;
      geo_h_q     <= HeightBits'(1);
      geo_hm2_q   <= '1;
      geo_h_is1_q <= 1'b1;
      same_new_q  <= 1'b0;
      same_geo_q  <= 1'b0;
      sampled_q   <= 1'b0;
    end else begin
      if (sample) begin
        geo_w_q     <= fw_q;
        geo_wm2_q   <= fw_m2_q;
        geo_w_is1_q <= fw_is1_q;
        geo_w_is2_q <= fw_is2_q;
        geo_w_is3_q <= fw_is3_q;
        geo_h_q     <= fh_q;
        geo_hm2_q   <= fh_m2_q;
        geo_h_is1_q <= fh_is1_q;
      end
      // same of the next cycle: next registered size == next latched size (fw_q after a
      // sample, geo_w_q otherwise).
      same_new_q <= (frame_width_i == fw_q) && (frame_height_i == fh_q);
      same_geo_q <= (frame_width_i == geo_w_q) && (frame_height_i == geo_h_q);
      sampled_q  <= sample;
    end
  end

  // ---- input position ------------------------------------------------------------------
  logic col_next_last, row_next_last;

  // The flag of the next column when the column advances (not at a wrap): in Idle the
  // column is 0, so "next is last" means W = 2.
  assign col_next_last = idle ? fw_is2_q : (col_q == geo_wm2_q);
  assign row_next_last = idle ? fh_is2_q : (row_q == geo_hm2_q);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_position
    if (!rst_ni) begin
      col_q        <= '0;
      prev_col_q   <= '0;
      col_last_q   <= 1'b0;
      row_q        <= '0;
      row_last_q   <= 1'b0;
      wrapped_q    <= 1'b0;
      emit_q       <= 1'b0;
      ph_wrapped_q <= 1'b0;
    end else if (take) begin
      prev_col_q <= AddrBits'(col_q);
      if (last_phantom) begin
        // Every owed output has entered the window: back to Idle, column 0.
        col_q        <= '0;
        col_last_q   <= 1'b0;
        wrapped_q    <= 1'b0;
        emit_q       <= 1'b0;
        ph_wrapped_q <= 1'b0;
      end else begin
        if (cur_col_last) begin
          col_q      <= '0;
          col_last_q <= idle ? fw_is1_q : geo_w_is1_q;
        end else begin
          col_q      <= col_q + WidthBits'(1);
          col_last_q <= col_next_last;
        end
        wrapped_q <= wrapped_q || cur_col_last;
        emit_q    <= emit_q || wrapped_q;
        if (take_phantom && cur_col_last) ph_wrapped_q <= 1'b1;
      end
      if (take_pix && cur_col_last) begin
        if (cur_row_last) begin
          row_q      <= '0;
          row_last_q <= idle ? fh_is1_q : geo_h_is1_q;
        end else begin
          row_q      <= row_q + HeightBits'(1);
          row_last_q <= row_next_last;
        end
      end else if (sample) begin
        // Row 0 of a frame with the new size.
        row_last_q <= fh_is1_q;
      end
    end
  end

  // ---- line buffer read address: the item after the next one ----------------------------
  // The read is two items ahead (its data pass a register before they are used, see
  // dpc_core), so the address has a counter of its own, ahead_q, two columns ahead of col_q
  // and a register, like its "last column" flag. In Idle the next frame's size is that of
  // the size inputs; at the frame start the counter jumps to column 3 mod W.
  logic [WidthBits-1:0] ahead_q, ahead_d;
  logic                 ahead_last_q, ahead_last_d;
  logic [AddrBits-1:0]  rd_col_q;
  logic                 fw_short_d;

  always_comb begin : p_read_address_next
    ahead_d      = ahead_q;
    ahead_last_d = ahead_last_q;
    if (sample) begin
      ahead_d      = fw_is1_q ? WidthBits'(0) : fw_is2_q ? WidthBits'(1) :
                     fw_is3_q ? WidthBits'(0) : WidthBits'(3);
      ahead_last_d = fw_is1_q || fw_is2_q || fw_is4_q;
    end else if (take) begin
      if (ahead_last_q) begin
        ahead_d      = '0;
        ahead_last_d = geo_w_is1_q;
      end else begin
        ahead_d      = ahead_q + WidthBits'(1);
        ahead_last_d = (ahead_q == geo_wm2_q);
      end
    end
  end

  // The read address is a register of its own, loaded with the next cycle's address, so
  // the memory's address pins (LUT RAM: its read multiplexer) come straight from a flop.
  // In Idle: column 2 of the new frame (0 when W <= 2; the width of the size inputs, which
  // fw_is1_q/fw_is2_q hold in the next cycle). The reads of the last two phantoms of a
  // flush, for the next frame's items 0 and 1 (row 0: the rows above are masked), use the
  // old size; their data are never used.
  assign fw_short_d = (frame_width_i == WidthBits'(1)) || (frame_width_i == WidthBits'(2));

  // The next state is Idle when Idle takes no pixel or the last phantom enters (in Flush
  // last_phantom = take && ph_wrapped_q): written from take and flops, not from state_d.
  logic                idle_d;
  logic [AddrBits-1:0] idle_col;

  assign idle_d   = idle ? !take : last_phantom;
  assign idle_col = fw_short_d ? AddrBits'(0) : AddrBits'(2);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_read_address
    if (!rst_ni) begin
      ahead_q      <= '0;
      ahead_last_q <= 1'b0;
      rd_col_q     <= '0;
    end else begin
      ahead_q      <= ahead_d;
      ahead_last_q <= ahead_last_d;
      rd_col_q     <= idle_d ? idle_col : AddrBits'(ahead_d);
    end
  end

  // ---- output position (one step per emitting item) ---------------------------------------
  logic win_valid_q, win_top_q, win_bottom_q, win_left_q, win_right_q, win_sof_q, win_eol_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_output_position
    if (!rst_ni) begin
      oc_q         <= '0;
      or_q         <= '0;
      oc_first_q   <= 1'b1;
      oc_last_q    <= 1'b0;
      or_first_q   <= 1'b1;
      or_last_q    <= 1'b0;
      win_valid_q  <= 1'b0;
      win_top_q    <= 1'b0;
      win_bottom_q <= 1'b0;
      win_left_q   <= 1'b0;
      win_right_q  <= 1'b0;
      win_sof_q    <= 1'b0;
      win_eol_q    <= 1'b0;
    end else begin
      if (en_i) win_valid_q <= take && emit_q;
      if (sample) begin
        // A frame starts from Idle: the output position is (0, 0), its last flags follow
        // the new size (the first output comes W+1 items later).
        oc_last_q <= fw_is1_q;
        or_last_q <= fh_is1_q;
      end
      if (take && emit_q) begin
        // The window now centres on (or_q, oc_q).
        win_top_q    <= or_first_q;
        win_bottom_q <= or_last_q;
        win_left_q   <= oc_first_q;
        win_right_q  <= oc_last_q;
        win_sof_q    <= or_first_q && oc_first_q;
        win_eol_q    <= oc_last_q;
        if (oc_last_q) begin
          oc_q       <= '0;
          oc_first_q <= 1'b1;
          oc_last_q  <= geo_w_is1_q;
          if (or_last_q) begin
            or_q       <= '0;
            or_first_q <= 1'b1;
            or_last_q  <= geo_h_is1_q;
          end else begin
            or_q       <= or_q + HeightBits'(1);
            or_first_q <= 1'b0;
            or_last_q  <= (or_q == geo_hm2_q);
          end
        end else begin
          oc_q       <= oc_q + WidthBits'(1);
          oc_first_q <= 1'b0;
          oc_last_q  <= (oc_q == geo_wm2_q);
        end
      end
    end
  end

  // ---- framing check ---------------------------------------------------------------------
  logic exp_sof, marker_bad;

  // A pixel taken in Idle or Tail starts a frame; eol belongs on the last column.
  assign exp_sof    = idle || tail;
  assign marker_bad = (pix_sof_i != exp_sof) || (pix_eol_i != cur_col_last);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_error
    if (!rst_ni) begin
      err_q <= 1'b0;
    end else if (take_pix && (marker_bad || (idle && (fw_bad_q || fh_bad_q)))) begin
      err_q <= 1'b1;
    end
  end

  // ---- outputs ---------------------------------------------------------------------------
  assign take_o        = take;
  assign phantom_o     = phantom_req;
  assign lb_rd_addr_o  = rd_col_q;
  assign lb_wr_addr_o  = prev_col_q;
  assign lb_w1_o       = geo_w_is1_q;
  assign lb_w2_o       = geo_w_is2_q;
  assign lb_w3_o       = geo_w_is3_q;
  assign win_valid_o   = win_valid_q;
  assign win_top_o     = win_top_q;
  assign win_bottom_o  = win_bottom_q;
  assign win_left_o    = win_left_q;
  assign win_right_o   = win_right_q;
  assign win_sof_o     = win_sof_q;
  assign win_eol_o     = win_eol_q;
  assign frame_err_o   = err_q;

`ifdef IRNUC_ASSERT
  // a_wrapped_in_flush: the invariant last_phantom and idle_d rely on (ph_wrapped_q implies
  // Flush). Its antecedent guards the assertion, so it executes only while ph_wrapped_q
  // is set: at full rate the simulator skips it (Verilator queries its assertion enable
  // once per executed assertion).
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q && ph_wrapped_q) begin
      a_wrapped_in_flush: assert (flush)
        else $error("dpc_ctrl: the phantom row wrapped outside Flush");
    end
  end
`endif

endmodule
