// Frames the AXI4-Stream video input for the core and joins each pixel with its coefficient
// word (docs/integration.md "Frames and markers").
//
// Video (UG934: tuser[0] = start of frame on a frame's first pixel, tlast = end of line on
// a line's last pixel) is counted against the programmed frame size, so the core always
// gets whole frames of exactly that size, with its own sof/eol:
//   AxisWait   a beat with start of frame opens a frame; any other beat is dropped
//              (sof_late, counted once per run of dropped beats);
//   AxisFrame  beats are pixels. A start of frame inside a frame (sof_early) closes the
//              frame first: filler pixels (raw code 0) up to its last pixel, then the beat
//              opens the next frame. tlast before the line's last pixel (eol_early): filler
//              pixels complete the line. No tlast on the line's last pixel (eol_late): the
//              line ends there and the beats up to the next tlast are dropped;
//   AxisPad    filler pixels (the input waits);
//   AxisDrop   beats dropped up to a tlast (a start of frame there ends the drop).
// UG934 recommends passing early markers on (shorter lines or frames); the core's 3x3
// window and its one-word-per-pixel coefficient stream need the programmed geometry, so
// here they are padded instead, and counted.
//
// The frame start takes the pending settings (frame size, enables, the frame word of the
// method's registers): the registers change what the core does only at a frame start. A
// changed frame size (size_dirty_i) first waits until the previous frame has left the core
// (no item between this module's output and the core's output), so the core sees every
// frame with its own size.
//
// Coefficients: one word per pixel, fillers included, in raster order. With coef_sync
// (CTRL.coef_sync) the word's tlast must mark the frame's last pixel: early (coef_early),
// the frame's remaining pixels get the neutral word (unity gain, zero offset, not bad) and
// no word is taken; late (coef_late), the words up to the next tlast are dropped before the
// next frame's first pixel. Either way the next frame starts aligned with the stream.
// With nuc_en = 0 a pixel gets unity gain and zero offset; with dpc_en = 0 its bad flag is
// cleared (the word is taken all the same).
//
// Every decision comes from registers (the input registers of the top, this module's
// state, counters and flags); the output is a spill register, so every output is a flop
// but the word, which is masked behind it (NUC off, DPC off, filler). The decision to send
// an item (fire) fans out widely: it is the AND of two flops, go_q (the word and the output
// allow an item) and item_q (a pixel or a filler is there), each made a cycle ahead with and
// without an item sent (the input buffers' fill and the video buffer's head after a pop or
// not, from their input sides), so the input buffers' pops are one gate behind it; the
// count of items in flight follows it a cycle late.
module irnuc_axis_framer
  import irnuc_pkg::*;
#(
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned MaxWidth       = 1024,
  parameter int unsigned MaxHeight      = 1024,
  parameter int unsigned FrameBits      = 1,  // the frame word (method registers), >= 1
  // The coefficient word of the core (default: the two-point word) and its neutral
  // values: NeutralWord replaces a word's bits outside BadMask (the bad flags) when NUC is
  // off and is the whole word of a filler; NeutralFrame replaces the frame word when NUC
  // is off (irnuc_axis_top sets them per method, docs/integration.md).
  parameter int unsigned WordBits       = coef_word_bits(GainIntBits + GainFracBits,
                                                         OffsetIntBits + OffsetFracBits),
  parameter logic [WordBits-1:0] NeutralWord = WordBits'(
    (GainIntBits > 0) ? (64'd1 << GainFracBits) : ((64'd1 << (GainIntBits + GainFracBits)) - 1)),
  parameter logic [WordBits-1:0] BadMask = WordBits'(64'd1 << coef_word_bad_lsb(
    GainIntBits + GainFracBits, OffsetIntBits + OffsetFracBits)),
  parameter logic [FrameBits-1:0] NeutralFrame = '0,
  // Derived, do not override.
  localparam int unsigned WidthBits     = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits    = $clog2(MaxHeight + 1),
  // Items between this module's output and the core's output.
  localparam int unsigned FlightBits    = axis_flight_bits(MaxWidth)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // Video beats (from the input register of s_axis_video).
  input  logic                  vid_valid_i,
  output logic                  vid_ready_o,
  input  logic [AdcBits-1:0]    vid_data_i,
  input  logic                  vid_sof_i,
  input  logic                  vid_eol_i,
  // Coefficient words (from the input register of s_axis_coef).
  input  logic                  coef_valid_i,
  output logic                  coef_ready_o,
  input  logic [WordBits-1:0]   coef_data_i,
  input  logic                  coef_last_i,
  // The coefficient input buffer's input side (u_coef_in's valid_i and ready_o = not full):
  // its fill a cycle ahead, for the registered half of the decision (go_q).
  input  logic                  coef_in_valid_i,
  input  logic                  coef_in_ready_i,
  // The video input buffer's input side (u_vid_in's valid_i, ready_o = not full, and the
  // beat's start of frame): its head a cycle ahead, for the registered item (item_q).
  input  logic                  vid_in_valid_i,
  input  logic                  vid_in_ready_i,
  input  logic                  vid_in_sof_i,
  // Pending settings (the register file); *_m1 = value - 1, *_is1 = value is 1.
  input  logic [WidthBits-1:0]  pend_width_i,
  input  logic [HeightBits-1:0] pend_height_i,
  input  logic [WidthBits-1:0]  pend_width_m1_i,
  input  logic [HeightBits-1:0] pend_height_m1_i,
  input  logic                  pend_width_is1_i,
  input  logic                  pend_height_is1_i,
  input  logic                  size_dirty_i,
  input  logic                  size_write_i,  // FRAME_SIZE changes now (size_dirty_i next)
  input  logic                  pend_nuc_en_i,
  input  logic                  pend_dpc_en_i,
  input  logic                  pend_coef_sync_i,
  input  logic [FrameBits-1:0]  pend_frame_i,
  // pend_frame_i is not ready (table_interp's weight computed): no frame starts in the
  // next cycle (from flops, like size_write_i; 0 for the other methods).
  input  logic                  hold_i,
  // The frame being corrected: its size (to the core) and its last line's index.
  output logic [WidthBits-1:0]  act_width_o,
  output logic [WidthBits-1:0]  act_width_m1_o,
  output logic [HeightBits-1:0] act_height_o,
  output logic [HeightBits-1:0] act_height_m1_o,
  // Items to the core: the pixel, its word, its markers and the frame word.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [AdcBits-1:0]    m_raw_o,
  output logic [WordBits-1:0]   m_word_o,
  output logic                  m_sof_o,
  output logic                  m_eol_o,
  output logic [FrameBits-1:0]  m_frame_o,
  // Items that left the core this cycle, 0 to 2: an m_axis_video transfer, and (FFC
  // compositions) an item of a held frame, which leaves the count as it enters the core.
  input  logic [1:0]            core_out_i,
  // FFC compositions: write-back words still owed (a flop; 0 without FFC). A new frame
  // size waits for them too: the write-back streams' tlast counts against the size.
  input  logic                  wb_busy_i,
  // A frame starts now (its first item is sent): the pending settings are taken.
  output logic                  start_o,
  // Events, one cycle each (registered), for the register file.
  output logic                  frame_start_o,
  output logic                  beat_o,       // a beat was taken (pixel or dropped)
  output logic                  drop_o,       // ... and dropped
  output logic                  pad_o,        // a filler pixel was sent
  output logic                  sof_early_o,
  output logic                  sof_late_o,
  output logic                  eol_early_o,
  output logic                  eol_late_o,
  output logic                  coef_early_o,
  output logic                  coef_late_o,
  output logic                  in_frame_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (MaxWidth >= MaxWidthMin && MaxWidth <= MaxWidthMax)
      else $fatal(1, "irnuc_axis_framer: MaxWidth = %0d outside %0d..%0d", MaxWidth,
                  MaxWidthMin, MaxWidthMax);
    assert (MaxHeight >= MaxHeightMin && MaxHeight <= MaxHeightMax)
      else $fatal(1, "irnuc_axis_framer: MaxHeight = %0d outside %0d..%0d", MaxHeight,
                  MaxHeightMin, MaxHeightMax);
    assert (FrameBits >= 1)
      else $fatal(1, "irnuc_axis_framer: FrameBits = %0d must be at least 1", FrameBits);
  end
`endif

  // ---- state ----------------------------------------------------------------------------
  axis_vid_state_e  vst_q, vst_d;
  axis_coef_state_e cst_q, cst_d;
  // Position of the next item, counted down: columns and lines left after it, and whether
  // it is the last of its line / the last line.
  logic [WidthBits-1:0]  xr_q, xr_d;
  logic [HeightBits-1:0] yr_q, yr_d;
  logic                  xl_q, xl_d, yl_q, yl_d;
  logic                  pad_frame_q, pad_frame_d;  // AxisPad up to the frame's end
  logic                  done_q, done_d;            // AxisDrop after the frame's last pixel
  logic                  late_q, late_d;            // AxisWait: this run's sof_late is counted
  // The active frame's settings.
  logic [WidthBits-1:0]  act_w_q, act_wm1_q;
  logic [HeightBits-1:0] act_h_q, act_hm1_q;
  logic                  act_nuc_q, act_dpc_q, act_sync_q;
  // The size the position registers load at a line's end and at a frame's end: the pending
  // size while waiting (the last such cycle is the start, which takes it into act_*), held
  // in a frame (a_line_size). At a frame's end it stands for the pending size: unchanged
  // unless size_dirty_i, and then no frame starts before a cycle of waiting reloads the
  // position from the pending size (wait_ok_d).
  logic [WidthBits-1:0]  lw_m1_q;
  logic [HeightBits-1:0] lh_m1_q;
  logic                  lw_is1_q, lh_is1_q;
  // Items in flight to the core's output, and the drain before a new frame size.
  logic [FlightBits-1:0] flight_q;
  logic                  fire_q, empty_q, drained_q;
  // The states one-hot (copies of vst_q, cst_q for the item decision).
  logic                  s_wait_q, s_frame_q, s_pad_q, s_drop_q;
  // Waiting and free to start a frame (s_wait_q && start_ok, registered).
  logic                  wait_ok_q, wait_ok_d;
  logic                  c_normal_q, c_fill_q, c_skip_q;
  // The one-hot flags' next values, each decoded before `fire`'s multiplexer.
  logic                  s_wait_d, s_frame_d, s_pad_d, s_drop_d, c_normal_d, c_fill_d, c_skip_d;

  // ---- what happens this cycle ----------------------------------------------------------
  logic start_ok, starting, pix_item, pad_item, item, word_ok, go, fire, start_fire;
  logic take_beat, drop_beat, take_coef, last;
  logic eff_nuc, eff_dpc, eff_sync;
  logic out_ready;   // u_out's ready (its skid register empty): drives its data registers
  logic out_free_q;  // a copy of it for the item decision, a flop of its own (a_out_free)
  // go a cycle ahead (a_go): the word and the output allow an item, from a flop. Its next
  // value is made with and without an item sent (the coefficient buffer's fill after a take
  // or not, the output register's ready), `fire` picking one at the end like the states'.
  logic go_q, go_d;
  // item a cycle ahead (a_item): a pixel or a filler is there to send, from a flop. Its next
  // value is made with and without an item sent (the video buffer's head after a pop or not:
  // its input side and in_sof_q), `fire` picking one at the end, so `fire` is one gate of
  // two flops and the input buffers' pops one level behind it.
  logic item_q, item_d;
  // The start of frame of the last beat pushed into the video buffer: when the buffer is
  // full, its younger entry's, the head after a pop.
  logic in_sof_q;

  // A new frame size waits for the drain (drained_q is at least a cycle after the write,
  // so the position registers are preloaded from the new size).
  // start_ok (registered as wait_ok_q below).
  assign start_ok = !size_dirty_i || drained_q;
  assign starting = s_wait_q;
  // A pixel: vid_valid_i && (vid_sof_i ? wait_ok_q : s_frame_q); a filler: s_pad_q. The two
  // exclude each other (the states are one-hot), so the pixel is the item outside AxisPad.
  assign item     = item_q;  // pix_item || pad_item, registered (a_item)
  assign pad_item = s_pad_q;
  assign pix_item = item && !s_pad_q;
  assign word_ok  = (c_normal_q && coef_valid_i) || c_fill_q;
  assign go       = go_q;  // word_ok && out_free_q, registered (a_go)
  assign fire     = go && item;
  // A frame's first item (fire && starting) straight from flops: waiting, only a start of
  // frame is an item (the states are one-hot: a_start_fire).
  assign start_fire = go && item && s_wait_q;
  assign last     = xl_q && yl_q;

  // The start item takes the pending settings; the others the active ones.
  assign eff_nuc  = starting ? pend_nuc_en_i : act_nuc_q;
  assign eff_dpc  = starting ? pend_dpc_en_i : act_dpc_q;
  assign eff_sync = starting ? pend_coef_sync_i : act_sync_q;

  // Beats dropped: without start of frame while waiting; in AxisDrop, except a start of
  // frame (it opens the next frame, or closes this one early).
  assign drop_beat = vid_valid_i && !vid_sof_i && (starting || s_drop_q);
  assign take_beat = (fire && pix_item) || drop_beat;
  assign take_coef = (fire && c_normal_q) || (c_skip_q && coef_valid_i);

  assign vid_ready_o  = take_beat;
  assign coef_ready_o = take_coef;
  assign start_o      = start_fire;

  // ---- next state ---------------------------------------------------------------------------
  // Each register's next value with and without an item sent, from registers only; `fire`
  // picks one at the end (the deepest signal passes a single multiplexer).
  always_comb begin : p_next
    // Position: one step per item. The frame's last item, and waiting, load the pending
    // size: the position of the next frame's first pixel.
    logic [WidthBits-1:0]  xr_f, xr_n;
    logic [HeightBits-1:0] yr_f, yr_n;
    logic                  xl_f, yl_f, xl_n, yl_n;
    axis_vid_state_e       vst_f, vst_n;
    axis_coef_state_e      cst_f, cst_n;
    logic                  pad_frame_f, pad_frame_n, done_f;
    logic                  coef_push, coef_any_pop, coef_any_keep, pop_f, pop_n, go_f, go_n;
    logic                  vpop_valid, vpop_sof, vkeep_valid, vkeep_sof, v_f_valid, v_f_sof;
    logic                  v_n_valid, v_n_sof, wait_free, wait_ok_f, wait_ok_n, item_f, item_n;

    if (starting) begin
      {xr_n, xl_n, yr_n, yl_n} = {pend_width_m1_i, pend_width_is1_i, pend_height_m1_i,
                                  pend_height_is1_i};
    end else begin
      {xr_n, xl_n, yr_n, yl_n} = {xr_q, xl_q, yr_q, yl_q};
    end
    if (xl_q) begin
      xr_f = lw_m1_q;
      xl_f = lw_is1_q;
      yr_f = yl_q ? lh_m1_q : yr_q - HeightBits'(1);
      yl_f = yl_q ? lh_is1_q : (yr_q == HeightBits'(1));
    end else begin
      xr_f = xr_q - WidthBits'(1);
      xl_f = (xr_q == WidthBits'(1));
      yr_f = yr_q;
      yl_f = yl_q;
    end

    // Video, no item sent: a start of frame inside a frame closes it (sof_early); a drop
    // ends with a tlast (or with a start of frame after the frame's last pixel).
    vst_n       = vst_q;
    pad_frame_n = pad_frame_q;
    unique case (vst_q)
      AxisFrame: begin
        if (vid_valid_i && vid_sof_i) begin
          vst_n       = AxisPad;
          pad_frame_n = 1'b1;
        end
      end
      AxisDrop: begin
        if (vid_valid_i && vid_sof_i) begin
          vst_n       = done_q ? AxisWait : AxisPad;
          pad_frame_n = 1'b1;
        end else if (drop_beat && vid_eol_i) begin
          vst_n = done_q ? AxisWait : AxisFrame;
        end
      end
      default: ;
    endcase
    // Video, an item sent: a pixel's own tlast (early: pad the line; missing on the line's
    // last pixel: drop up to the next tlast); the frame's last item closes it.
    vst_f       = AxisFrame;
    pad_frame_f = pad_frame_q;
    done_f      = done_q;
    if (s_pad_q) begin
      if (last) begin
        vst_f = AxisWait;
      end else if (!(xl_q && !pad_frame_q)) begin
        vst_f = AxisPad;
      end
    end else if (vid_eol_i && !xl_q) begin
      vst_f       = AxisPad;
      pad_frame_f = 1'b0;
    end else if (!vid_eol_i && xl_q) begin
      vst_f  = AxisDrop;
      done_f = yl_q;
    end else if (last) begin
      vst_f = AxisWait;
    end

    // Coefficients (with coef_sync): tlast early, fill the frame; missing, skip to one.
    cst_n = cst_q;
    if (c_skip_q && coef_valid_i && coef_last_i) begin  // take_coef without fire
      cst_n = CoefNormal;
    end
    cst_f = cst_q;
    if (c_fill_q) begin
      cst_f = last ? CoefNormal : CoefFill;
    end else if (c_normal_q && eff_sync && coef_last_i && !last) begin
      cst_f = CoefFill;
    end else if (c_normal_q && eff_sync && !coef_last_i && last) begin
      cst_f = CoefSkip;
    end

    xr_d        = fire ? xr_f : xr_n;
    xl_d        = fire ? xl_f : xl_n;
    yr_d        = fire ? yr_f : yr_n;
    yl_d        = fire ? yl_f : yl_n;
    vst_d       = fire ? vst_f : vst_n;
    cst_d       = fire ? cst_f : cst_n;
    pad_frame_d = fire ? pad_frame_f : pad_frame_n;
    done_d      = fire ? done_f : done_q;
    s_wait_d    = fire ? (vst_f == AxisWait) : (vst_n == AxisWait);
    s_frame_d   = fire ? (vst_f == AxisFrame) : (vst_n == AxisFrame);
    s_pad_d     = fire ? (vst_f == AxisPad) : (vst_n == AxisPad);
    s_drop_d    = fire ? (vst_f == AxisDrop) : (vst_n == AxisDrop);
    c_normal_d  = fire ? (cst_f == CoefNormal) : (cst_n == CoefNormal);
    c_fill_d    = fire ? (cst_f == CoefFill) : (cst_n == CoefFill);
    c_skip_d    = fire ? (cst_f == CoefSkip) : (cst_n == CoefSkip);
    late_d      = starting ? (late_q || drop_beat) && !fire : 1'b0;

    // start_ok of the next cycle (a_wait_ok), where the next state waits: no frame-size write
    // now (it sets size_dirty_i next; the position registers are loaded from the old size at
    // this edge) and the size clean, or, waiting, the core empty or a frame's first item sent
    // (the frame start clears size_dirty_i: a one-pixel frame waits again).
    wait_free = !size_write_i && !hold_i;  // hold_i: table_interp's weight computed
    wait_ok_f = (vst_f == AxisWait) && wait_free && (!size_dirty_i || starting);
    wait_ok_n = (vst_n == AxisWait) && wait_free && (!size_dirty_i || (starting && empty_q));
    wait_ok_d = fire ? wait_ok_f : wait_ok_n;

    // item of the next cycle: the video buffer's head next cycle, after a pop (a pixel sent, or
    // a beat dropped) or not. Popped: the younger entry when the buffer is full (the last beat
    // pushed), else a beat pushed now. Kept: the head held, else a beat pushed now.
    vpop_valid  = !vid_in_ready_i || vid_in_valid_i;
    vpop_sof    = vid_in_ready_i ? vid_in_sof_i : in_sof_q;
    vkeep_valid = vid_valid_i || vid_in_valid_i;
    vkeep_sof   = vid_valid_i ? vid_sof_i : vid_in_sof_i;
    // An item sent pops the video buffer unless it is a filler; no beat is dropped then.
    v_f_valid   = s_pad_q ? vkeep_valid : vpop_valid;
    v_f_sof     = s_pad_q ? vkeep_sof : vpop_sof;
    v_n_valid   = drop_beat ? vpop_valid : vkeep_valid;
    v_n_sof     = drop_beat ? vpop_sof : vkeep_sof;
    item_f = (v_f_valid && (v_f_sof ? wait_ok_f : (vst_f == AxisFrame))) || (vst_f == AxisPad);
    item_n = (v_n_valid && (v_n_sof ? wait_ok_n : (vst_n == AxisFrame))) || (vst_n == AxisPad);
    item_d = fire ? item_f : item_n;

    // go of the next cycle. The coefficient buffer holds a word next cycle: after a take,
    // the other entry or one pushed now (pop implies a word held); else the one held or one
    // pushed now. A word is taken with an item in CoefNormal, and in CoefSkip without one.
    // The output register's ready (out_free_q's next value) without and with an item sent.
    coef_push     = coef_in_valid_i && coef_in_ready_i;
    coef_any_pop  = coef_push || !coef_in_ready_i;
    coef_any_keep = coef_push || coef_valid_i;
    pop_f         = c_normal_q || (c_skip_q && coef_valid_i);
    pop_n         = c_skip_q && coef_valid_i;
    go_f = (((cst_f == CoefNormal) && (pop_f ? coef_any_pop : coef_any_keep))
            || (cst_f == CoefFill)) && (!m_valid_o || m_ready_i);
    go_n = (((cst_n == CoefNormal) && (pop_n ? coef_any_pop : coef_any_keep))
            || (cst_n == CoefFill)) && (!m_valid_o || m_ready_i || out_free_q);
    go_d = fire ? go_f : go_n;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      vst_q       <= AxisWait;
      cst_q       <= CoefNormal;
      s_wait_q    <= 1'b1;
      wait_ok_q   <= 1'b1;
      s_frame_q   <= 1'b0;
      s_pad_q     <= 1'b0;
      s_drop_q    <= 1'b0;
      c_normal_q  <= 1'b1;
      c_fill_q    <= 1'b0;
      c_skip_q    <= 1'b0;
      // The position of the reset size's first pixel (FRAME_SIZE resets to MaxWidth x
      // MaxHeight): a frame may start in the first cycle after reset (irnuc formal found
      // the first item's eol set there from the former reset values 0 / 1).
      xr_q        <= WidthBits'(MaxWidth - 1);
      yr_q        <= HeightBits'(MaxHeight - 1);
      xl_q        <= (MaxWidth == 1);
      yl_q        <= (MaxHeight == 1);
      pad_frame_q <= 1'b0;
      done_q      <= 1'b0;
      late_q      <= 1'b0;
      go_q        <= 1'b0;  // no word held after reset
      item_q      <= 1'b0;  // no beat held after reset
      in_sof_q    <= 1'b0;
    end else begin
      vst_q       <= vst_d;
      cst_q       <= cst_d;
      s_wait_q    <= s_wait_d;
      wait_ok_q   <= wait_ok_d;
      s_frame_q   <= s_frame_d;
      s_pad_q     <= s_pad_d;
      s_drop_q    <= s_drop_d;
      c_normal_q  <= c_normal_d;
      c_fill_q    <= c_fill_d;
      c_skip_q    <= c_skip_d;
      xr_q        <= xr_d;
      yr_q        <= yr_d;
      xl_q        <= xl_d;
      yl_q        <= yl_d;
      pad_frame_q <= pad_frame_d;
      done_q      <= done_d;
      late_q      <= late_d;
      go_q        <= go_d;
      item_q      <= item_d;
      if (vid_in_valid_i && vid_in_ready_i) begin
        in_sof_q <= vid_in_sof_i;
      end
    end
  end

  // ---- the active settings: taken with a frame's first item -----------------------------
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_active
    if (!rst_ni) begin
      act_w_q     <= WidthBits'(MaxWidth);
      act_wm1_q   <= WidthBits'(MaxWidth - 1);
      act_h_q     <= HeightBits'(MaxHeight);
      act_hm1_q   <= HeightBits'(MaxHeight - 1);
      act_nuc_q   <= 1'b1;
      act_dpc_q   <= 1'b1;
      act_sync_q  <= 1'b1;
    end else if (start_fire) begin
      act_w_q     <= pend_width_i;
      act_wm1_q   <= pend_width_m1_i;
      act_h_q     <= pend_height_i;
      act_hm1_q   <= pend_height_m1_i;
      act_nuc_q   <= pend_nuc_en_i;
      act_dpc_q   <= pend_dpc_en_i;
      act_sync_q  <= pend_coef_sync_i;
    end
  end

  // The line and frame size of the position registers (loaded while waiting: the enable is
  // a flop, not the start decision).
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_line_size
    if (!rst_ni) begin
      lw_m1_q  <= WidthBits'(MaxWidth - 1);
      lw_is1_q <= (MaxWidth == 1);
      lh_m1_q  <= HeightBits'(MaxHeight - 1);
      lh_is1_q <= (MaxHeight == 1);
    end else if (s_wait_q) begin
      lw_m1_q  <= pend_width_m1_i;
      lw_is1_q <= pend_width_is1_i;
      lh_m1_q  <= pend_height_m1_i;
      lh_is1_q <= pend_height_is1_i;
    end
  end

  assign act_width_o     = act_w_q;
  assign act_width_m1_o  = act_wm1_q;
  assign act_height_o    = act_h_q;
  assign act_height_m1_o = act_hm1_q;

  // ---- items in flight: the drain before a new frame size --------------------------------
  // flight_q counts the items sent up to the cycle before last (fire_q: the last cycle's)
  // less those that left the core: the items in flight are flight_q + fire_q, and `fire`
  // reaches no carry chain.
  logic [FlightBits-1:0] flight_d;
  logic                  drained_d;

  // One adder: flight_q plus the step fire_q - core_out_i (1, 0, -1 or -2; two bits, sign
  // extended), both from flops.
  logic [1:0] flight_step;
  assign flight_step = {1'b0, fire_q} - core_out_i;

  always_comb begin : p_flight
    flight_d = flight_q + {{(FlightBits - 2){flight_step[1]}}, flight_step};
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_drain
    if (!rst_ni) begin
      flight_q  <= '0;
      fire_q    <= 1'b0;
      empty_q   <= 1'b1;
      drained_q <= 1'b0;
    end else begin
      flight_q  <= flight_d;
      fire_q    <= fire;
      // An item leaves only when one is in flight.
      empty_q   <= (flight_q == '0) && !fire_q && !fire && !wb_busy_i;
      drained_q <= drained_d;
    end
  end

  // wait_ok_d: in p_next (neither start_fire nor drained_d enters it: `fire` passes the next
  // state's multiplexer only).
  assign drained_d = empty_q && size_dirty_i && starting && !fire && !size_write_i;

  // ---- the item: pixel or filler, and its word -------------------------------------------
  // The word enters the output register as it comes with two flags, and
  // NUC off / DPC off / filler are applied behind it: the wide word's path from the input
  // buffer passes one multiplexer, not the masks too (docs/rtl.md).
  logic [WordBits-1:0]  word_in, out_word, word;
  logic                 nuc_off, dpc_off, out_nuc_off, out_dpc_off;
  logic [FrameBits-1:0] frame;

  // A filler's word (CoefFill) needs no zeroing: both its flags are set, so the masks
  // behind the register give the neutral word whatever it holds (the fill decode no
  // longer fans out to every word bit).
  assign word_in = coef_data_i;
  assign nuc_off = c_fill_q || !eff_nuc;
  assign dpc_off = c_fill_q || !eff_dpc;

  always_comb begin : p_word
    word = out_word;
    if (out_nuc_off) begin
      word = (word & BadMask) | (NeutralWord & ~BadMask);
    end
    if (out_dpc_off) begin
      word = word & ~BadMask;
    end
  end

  // The frame word goes with a frame's first item (the core reads it at sof).
  assign frame = !starting ? '0 : pend_nuc_en_i ? pend_frame_i : NeutralFrame;

  logic [AdcBits-1:0] raw;
  assign raw = pad_item ? '0 : vid_data_i;

  irnuc_spill_register #(.DataBits(FrameBits + 4 + AdcBits + WordBits)) u_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(fire),
    .ready_o(out_ready),
    .data_i ({frame, starting, xl_q, nuc_off, dpc_off, raw, word_in}),
    .valid_o(m_valid_o),
    .ready_i(m_ready_i),
    .data_o ({m_frame_o, m_sof_o, m_eol_o, out_nuc_off, out_dpc_off, m_raw_o, out_word})
  );

  assign m_word_o = word;

  // u_out's ready for the decision: the skid register's valid flag drives the enables and
  // multiplexers of every data bit of u_out (a net of a few hundred loads); this copy, the
  // complement of that flag (distinct flops: synthesis keeps both), drives the decision only.
  // u_out's main register takes an item when it is empty or its item leaves (the skid
  // register empties then); else an item sent fills the skid register.
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_out_free
    if (!rst_ni) begin
      out_free_q <= 1'b1;
    end else begin
      out_free_q <= !m_valid_o || m_ready_i || (out_free_q && !fire);
    end
  end

  // ---- events ---------------------------------------------------------------------------
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_events
    if (!rst_ni) begin
      frame_start_o <= 1'b0;
      beat_o        <= 1'b0;
      drop_o        <= 1'b0;
      pad_o         <= 1'b0;
      sof_early_o   <= 1'b0;
      sof_late_o    <= 1'b0;
      eol_early_o   <= 1'b0;
      eol_late_o    <= 1'b0;
      coef_early_o  <= 1'b0;
      coef_late_o   <= 1'b0;
      in_frame_o    <= 1'b0;
    end else begin
      frame_start_o <= start_fire;
      beat_o        <= take_beat;
      drop_o        <= drop_beat;
      pad_o         <= fire && pad_item;
      sof_early_o   <= vid_valid_i && vid_sof_i && (s_frame_q || (s_drop_q && !done_q));
      sof_late_o    <= drop_beat && starting && !late_q;
      eol_early_o   <= fire && pix_item && vid_eol_i && !xl_q;
      eol_late_o    <= fire && pix_item && !vid_eol_i && xl_q;
      coef_early_o  <= fire && c_normal_q && eff_sync && coef_last_i && !last;
      coef_late_o   <= fire && c_normal_q && eff_sync && !coef_last_i && last;
      in_frame_o    <= (vst_d != AxisWait);
    end
  end

`ifdef IRNUC_ASSERT
  // Protocol assertions of the input and output streams: in the spill registers of the top
  // (vid, coef) and u_out. The count of items in flight never wraps:
  logic armed_q;  // from the second edge after reset
  logic hold_q;   // hold_i of the cycle before (wait_ok_q's)
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_hold
    hold_q <= hold_i;
  end
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_flight_range: assert (32'(core_out_i) <= 32'(flight_q) + 32'(fire_q))
        else $error("irnuc_axis_framer: an item left the core that was never sent");
      a_line_size: assert (starting ? (!wait_ok_q || {lw_m1_q, lw_is1_q, lh_m1_q, lh_is1_q}
                                          == {pend_width_m1_i, pend_width_is1_i,
                                              pend_height_m1_i, pend_height_is1_i})
                           : ({lw_m1_q, lh_m1_q} == {act_wm1_q, act_hm1_q}))
        else $error("irnuc_axis_framer: the position registers' line size is not the frame's");
      a_out_free: assert (out_free_q == out_ready)
        else $error("irnuc_axis_framer: out_free_q is not u_out's ready");
      a_go: assert (go_q == (word_ok && out_free_q))
        else $error("irnuc_axis_framer: go_q is not 'the word and the output allow an item'");
      a_item: assert (item_q == ((vid_valid_i && (vid_sof_i ? wait_ok_q : s_frame_q)) || s_pad_q))
        else $error("irnuc_axis_framer: item_q is not 'a pixel or a filler to send'");
      a_wait_ok: assert (wait_ok_q == (starting && start_ok && !hold_q))
        else $error("irnuc_axis_framer: wait_ok_q is not 'waiting, and the frame size drained'");
      a_start_fire: assert (start_fire == (fire && starting))
        else $error("irnuc_axis_framer: start_fire is not a frame's first item");
      a_vid_onehot: assert ({s_wait_q, s_frame_q, s_pad_q, s_drop_q}
                            == {vst_q == AxisWait, vst_q == AxisFrame, vst_q == AxisPad,
                                vst_q == AxisDrop})
        else $error("irnuc_axis_framer: the one-hot video state is not vst_q");
      a_coef_onehot: assert ({c_normal_q, c_fill_q, c_skip_q}
                             == {cst_q == CoefNormal, cst_q == CoefFill, cst_q == CoefSkip})
        else $error("irnuc_axis_framer: the one-hot coefficient state is not cst_q");
    end
  end
`endif

endmodule
