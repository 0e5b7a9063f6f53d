// The FFC side of irnuc_axis_top (Ffc = 1; docs/integration.md "FFC"): the shutter flag of
// each frame from FFC_CTRL, the input register of the framer's items (a registered stream
// boundary), the fork of the items into method_ffc_top's separate
// pixel and coefficient inputs, the held frames' count, FFC_STATUS busy/done, the input
// buffers of s_axis_foff and s_axis_acc, method_ffc_top itself, the output buffer of its
// corrected pixels, and the write-back streams m_axis_acc and m_axis_foff with their tlast
// (counted against the frame size) behind output buffers. Instantiated by irnuc_axis_core;
// the AXI4-Stream ports are the top's.
module irnuc_axis_ffc
  import irnuc_pkg::*;
  import irnuc_method_pkg::*;
  import irnuc_stage_pkg::*;
#(
  // irnuc-params: begin irnuc_axis_ffc (generated from nuc_fixed.methods; do not edit)
  // the base method (irnuc_pkg::method_e)
  parameter method_e     Method           = MethodTwoPoint,
  parameter int unsigned AdcBits          = 14,
  parameter int unsigned GainIntBits      = 2,
  parameter int unsigned GainFracBits     = 14,
  parameter int unsigned OffsetIntBits    = 12,
  parameter int unsigned OffsetFracBits   = 4,
  parameter int unsigned OutBits          = 14,
  parameter int unsigned Rounding         = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow         = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned MaxWidth         = 1024,
  parameter int unsigned MaxHeight        = 1024,
  parameter int unsigned KneeIntBits      = 14,
  parameter int unsigned KneeFracBits     = 2,
  parameter int unsigned LevelIntBits     = 14,
  parameter int unsigned LevelFracBits    = 4,
  parameter int unsigned QuadIntBits      = 10,
  parameter int unsigned QuadFracBits     = 6,
  parameter int unsigned SquareBits       = 18,  // bits the square of a raw code is truncated to
  parameter int unsigned ReadingBits      = 14,  // bits of the FPA sensor's reading
  parameter int unsigned Tc1IntBits       = 13,
  parameter int unsigned Tc1FracBits      = 3,
  parameter int unsigned Tc2IntBits       = 12,
  parameter int unsigned Tc2FracBits      = 4,
  parameter int unsigned Tg1IntBits       = 2,
  parameter int unsigned Tg1FracBits      = 14,
  parameter int unsigned Tg2IntBits       = 2,
  parameter int unsigned Tg2FracBits      = 14,
  parameter int unsigned TcOrder          = 2,  // order of the polynomials
  parameter bit          TcGain           = 1'b0,  // the gain is a polynomial too
  parameter int unsigned ReadingRangeBits = 11,  // Ts: v = (t - t_ref) / 2^Ts
  parameter int unsigned FfcIntBits       = 12,
  parameter int unsigned FfcFracBits      = 4,
  parameter int unsigned FfcRounding      = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned FfcOverflow      = 0,  // irnuc_pkg::overflow_e
  // N, the shutter frames of a refresh (a power of two)
  parameter int unsigned FfcFrames        = 8,
  // what the output shows during the shutter frames
  parameter bit          FfcHold          = 1'b1,
  // Derived, do not override.
  localparam int unsigned GainBits         = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits       = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits         = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits        = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits         = QuadIntBits + QuadFracBits,
  localparam int unsigned TcWordBits       = Tc1IntBits + Tc1FracBits
                                             + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0),
  localparam int unsigned TgWordBits       = (TcGain != 0) ? Tg1IntBits + Tg1FracBits
                                             + ((TcOrder == 2) ? Tg2IntBits + Tg2FracBits : 0) : 0,
  localparam int unsigned WordBits         = coef_stream_bits(Method, OffsetBits, GainBits,
                                                              KneeBits, QuadBits, TcWordBits,
                                                              TgWordBits, 32'd1),
  localparam int unsigned FrameBits        = frame_word_bits(Method, GainBits, LevelBits,
                                                             ReadingBits, 32'd1, 32'd1),
  localparam int unsigned WidthBits        = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits       = $clog2(MaxHeight + 1),
  // irnuc-params: end
  localparam int unsigned ItemFrameBits = FrameBits + 1,
  localparam int unsigned FoffWordBits  = FfcIntBits + FfcFracBits,
  localparam int unsigned AccWordBits   = AdcBits + $clog2(FfcFrames),
  localparam int unsigned FoffBits      = 8 * ((FoffWordBits + 7) / 8),
  localparam int unsigned AccBits       = 8 * ((AccWordBits + 7) / 8)
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  // The frame size the framer's frames are taken with.
  input  logic [WidthBits-1:0]            act_w_i,
  input  logic [WidthBits-1:0]            act_wm1_i,  // width - 1 and height - 1 (flops)
  input  logic [HeightBits-1:0]           act_h_i,
  input  logic [HeightBits-1:0]           act_hm1_i,
  // The method's pending frame word in, with the pending shutter flag above it out.
  input  logic [FrameBits-1:0]            pend_frame_i,
  output logic [ItemFrameBits-1:0]        pend_item_frame_o,
  // Register file: a frame start (the framer took the pending settings), FFC_CTRL, FFC_STATUS.
  input  logic                            start_i,
  input  logic                            ffc_start_i,
  input  logic [RegFfcCtrlFramesBits-1:0] ffc_frames_i,
  output logic                            ffc_busy_o,
  output logic                            ffc_done_o,
  // The framer's items (a pixel and its word).
  input  logic                            item_valid_i,
  output logic                            item_ready_o,
  input  logic [AdcBits-1:0]              item_raw_i,
  input  logic [WordBits-1:0]             item_word_i,
  input  logic                            item_sof_i,
  input  logic                            item_eol_i,
  input  logic [ItemFrameBits-1:0]        item_frame_i,
  // Corrected pixels (behind the output buffer u_pix_out).
  output logic                            m_valid_o,
  input  logic                            m_ready_i,
  output logic [OutBits-1:0]              m_data_o,
  output logic                            m_sof_o,
  output logic                            m_eol_o,
  output logic [1:0]                      core_out_o,  // items that left the core (0..2)
  output logic                            wb_busy_o,   // write-back words owed (a flop)
  output logic                            frame_err_o,
  // The FFC streams (irnuc_axis_top's ports).
  input  logic [FoffBits-1:0]             s_axis_foff_tdata,
  input  logic                            s_axis_foff_tvalid,
  output logic                            s_axis_foff_tready,
  input  logic                            s_axis_foff_tlast,
  input  logic [AccBits-1:0]              s_axis_acc_tdata,
  input  logic                            s_axis_acc_tvalid,
  output logic                            s_axis_acc_tready,
  input  logic                            s_axis_acc_tlast,
  output logic [AccBits-1:0]              m_axis_acc_tdata,
  output logic                            m_axis_acc_tvalid,
  input  logic                            m_axis_acc_tready,
  output logic                            m_axis_acc_tlast,
  output logic [FoffBits-1:0]             m_axis_foff_tdata,
  output logic                            m_axis_foff_tvalid,
  input  logic                            m_axis_foff_tready,
  output logic                            m_axis_foff_tlast
);

  // ---- the shutter flag of each frame --------------------------------------------------------
  // FFC_CTRL.start arms the run: the frames that start after it, FFC_CTRL.frames of them
  // (the value at that frame start), are shutter frames. The flag is a pending setting like
  // the frame word: the framer takes it above the frame word when a frame starts (start_i),
  // and this count moves on at the same time. NUC off (CTRL.nuc_en 0) sends the neutral frame
  // word, flag 0: such a frame counts here but is an open frame to the core.
  logic                            pend_shutter, ffc_armed_q;
  logic [RegFfcCtrlFramesBits-1:0] ffc_left_q, ffc_now;
  logic                            pix_out, core_pix_ready, core_coef_ready;

  assign ffc_now      = ffc_armed_q ? ffc_frames_i : ffc_left_q;
  assign pend_shutter = ffc_now != '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_shutter
    if (!rst_ni) begin
      ffc_armed_q <= 1'b0;
      ffc_left_q  <= '0;
    end else begin
      if (start_i) begin
        ffc_left_q <= ffc_now - RegFfcCtrlFramesBits'(pend_shutter);
      end
      if (ffc_start_i) begin
        ffc_armed_q <= 1'b1;
      end else if (start_i) begin
        ffc_armed_q <= 1'b0;
      end
    end
  end

  assign pend_item_frame_o = {pend_shutter, pend_frame_i};

  // ---- the input register --------------------------------------------------------------------
  // The framer's items enter through a buffer of their own (a registered stream boundary):
  // item_ready_o is its fill flag, so the fork's decision below (the core's readies, the
  // sides already served) never reaches the framer's output register, whose every data bit
  // it enabled (the critical path across the chip), and the items reach the fork from flops
  // placed beside it. One cycle more of latency; one item per clock.
  localparam int unsigned ItemBits = ItemFrameBits + 2 + WordBits + AdcBits;
  logic                     in_valid, in_ready, in_sof, in_eol;
  logic [AdcBits-1:0]       in_raw;
  logic [WordBits-1:0]      in_word;
  logic [ItemFrameBits-1:0] in_frame;

  irnuc_axis_buffer #(.DataBits(ItemBits)) u_item_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(item_valid_i),
    .ready_o(item_ready_o),
    .data_i ({item_frame_i, item_sof_i, item_eol_i, item_word_i, item_raw_i}),
    .valid_o(in_valid),
    .ready_i(in_ready),
    .data_o ({in_frame, in_sof, in_eol, in_word, in_raw})
  );
  // ---- the fork ------------------------------------------------------------------------------
  // method_ffc_top: its pixel and coefficient inputs are separate spill registers that
  // drain at different times, so the item (from u_item_in) is forked: each side is offered
  // the item until it took it, and the item is taken when both have. The pixel reaches the core's
  // join through two two-entry buffers (its input register and its mode stage), the word
  // through one (u_coef_in): alone, the word would wait a cycle at the join, fill its
  // buffer (ready 0) and make the fork skip a cycle in four. u_coef_fork gives the word
  // a second buffer of the same cycles: both sides fill and drain in lockstep, one item
  // per clock.
  logic pix_took_q, coef_took_q, fork_pix_valid, fork_coef_valid, pix_take, coef_take;
  logic                coef_fork_valid, coef_fork_ready;
  logic [WordBits-1:0] coef_fork_word;
  logic foff_valid, foff_ready, acc_valid, acc_ready;
  logic [FoffWordBits-1:0] foff_data;
  logic [AccWordBits-1:0]  acc_data;
  logic                    macc_valid, macc_ready, mfoff_valid, mfoff_ready;
  logic [AccWordBits-1:0]  macc_data;
  logic [FoffWordBits-1:0] mfoff_data;
  logic                    item_shutter, item_take, target_valid, target_kept;
  logic [OutBits+FfcFracBits-1:0] target;

  assign fork_pix_valid  = in_valid && !pix_took_q;
  assign fork_coef_valid = in_valid && !coef_took_q;
  assign pix_take   = fork_pix_valid && core_pix_ready;
  assign coef_take  = fork_coef_valid && core_coef_ready;
  assign in_ready   = (pix_took_q || core_pix_ready) && (coef_took_q || core_coef_ready);
  assign item_take  = in_valid && in_ready;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_fork
    if (!rst_ni) begin
      pix_took_q  <= 1'b0;
      coef_took_q <= 1'b0;
    end else if (item_take) begin
      pix_took_q  <= 1'b0;
      coef_took_q <= 1'b0;
    end else begin
      pix_took_q  <= pix_took_q || pix_take;
      coef_took_q <= coef_took_q || coef_take;
    end
  end

  // A held frame (ffc_output hold: a shutter frame once an open frame went to the core)
  // is never output: its items leave the core's count as they enter it (the framer's
  // drain before a new frame size); the same rule as ffc_ctrl's, on the flag the core
  // reads at sof.
  logic       held_q, held_e, open_q;
  logic [1:0] core_out_q;
  assign item_shutter = in_frame[ItemFrameBits-1];
  assign held_e       = in_sof ? (FfcHold != 0) && item_shutter && open_q : held_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_held
    if (!rst_ni) begin
      held_q <= 1'b0;
      open_q <= 1'b0;
    end else if (item_take && in_sof) begin
      held_q <= held_e;
      open_q <= open_q || !item_shutter;
    end
  end
  // The framer counts an item out a cycle late (a flop: the fork's take and the output's
  // ready do not reach the framer's in-flight adder); its drain waits a cycle longer.
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_core_out
    if (!rst_ni) begin
      core_out_q <= '0;
    end else begin
      // Both in one cycle (the last open frame leaving as a held one enters): two.
      core_out_q <= {1'b0, pix_out} + {1'b0, item_take && held_e};
    end
  end
  assign core_out_o = core_out_q;

  // ---- write-back words owed: the framer's drain waits for them -------------------------------
  // The write-back streams' tlast counts against the frame size the framer holds, and the
  // framer's count of items in flight lets a held item go as it enters the core, a shown
  // one as its pixel leaves: an m_axis_acc or m_axis_foff word can still be inside (or
  // behind backpressure) then. So a new frame size also waits until every item that owes
  // a write-back word has delivered it. Which frames owe words is the core's sequencer's
  // decision, made again here by a copy of it on the same frame starts and shutter flags
  // (acc_first / acc_add: m_acc; refresh: m_foff; never both). Counted a cycle late from
  // flops like the framer's flight count: the item's take and the ports' handshakes each
  // reach one flop. The busy flag is the count or an item counting in (flops only: no adder
  // before it), so it is up the cycle after the take, before the framer's own count could
  // let the held item go (that takes two), and it clears a cycle after the count.
  localparam int unsigned OweBits = axis_flight_bits(MaxWidth);
  ffc_mode_t          owe_mode;
  logic               owe_frame_q, owe_e, owe_in_q, wb_busy_q;
  logic [1:0]         owe_out_q, owe_step;
  logic [OweBits-1:0] owe_q, owe_d;

  ffc_ctrl #(
    .FfcFrames(FfcFrames),
    .Hold     (FfcHold != 0)
  ) u_owe_ctrl (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .shutter_i(item_shutter),
    .take_i   (item_take && in_sof),
    .mode_o   (owe_mode)
  );

  assign owe_e    = in_sof ? owe_mode.acc_first || owe_mode.acc_add || owe_mode.refresh
                           : owe_frame_q;
  assign owe_step = {1'b0, owe_in_q} - owe_out_q;
  assign owe_d    = owe_q + {{(OweBits - 2){owe_step[1]}}, owe_step};

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_owe
    if (!rst_ni) begin
      owe_frame_q <= 1'b0;
      owe_in_q    <= 1'b0;
      owe_out_q   <= '0;
      owe_q       <= '0;
      wb_busy_q   <= 1'b0;
    end else begin
      if (item_take && in_sof) begin
        owe_frame_q <= owe_e;
      end
      owe_in_q  <= item_take && owe_e;
      owe_out_q <= {1'b0, m_axis_acc_tvalid && m_axis_acc_tready}
                   + {1'b0, m_axis_foff_tvalid && m_axis_foff_tready};
      owe_q     <= owe_d;
      wb_busy_q <= owe_q != '0 || owe_in_q;
    end
  end
  assign wb_busy_o = wb_busy_q;
  logic unused_owe;  // the read, mean and hold flags do not owe words
  assign unused_owe = ^{owe_mode.acc_rd, owe_mode.mean, owe_mode.hold};

  // FFC_STATUS: busy from FFC_CTRL.start until its run finished: the refresh frame's
  // last new offset taken on m_axis_foff (done, IRQ_STATUS.ffc_done), or, for a run
  // shorter than FfcFrames (no refresh), the next open frame reaching the core, or at
  // once for FFC_CTRL.frames = 0. begun_q: the run's first shutter frame reached the core;
  // ended_q: then an open frame (the run is over; a full run's refresh may still come).
  // The run reads its events a cycle late, from flops: a frame's first item taken by the
  // fork (sof_q, with its shutter flag) and the refresh's last word (refresh_q), so the
  // fork's take and the write-back handshake each reach one flop, not the run's state and
  // done. begin_ok_q: a shutter frame reaching the core then begins the run (busy, the
  // start taken by a frame, no new FFC_CTRL.start in that cycle: the start wins).
  localparam int unsigned RunBits = $clog2(FfcFrames + 1);
  logic [RunBits-1:0] run_q;
  logic               busy_q, begun_q, ended_q, open_sof, short_end, refreshed, none;
  logic               done_e, done_q, none_q;
  logic               sof_q, sof_shutter_q, begin_ok_q, refresh_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_events
    if (!rst_ni) begin
      sof_q         <= 1'b0;
      sof_shutter_q <= 1'b0;
      begin_ok_q    <= 1'b0;
      refresh_q     <= 1'b0;
    end else begin
      sof_q         <= item_take && in_sof;
      sof_shutter_q <= item_shutter;
      begin_ok_q    <= busy_q && !ffc_armed_q && !ffc_start_i;
      refresh_q     <= m_axis_foff_tvalid && m_axis_foff_tready && m_axis_foff_tlast;
    end
  end

  assign open_sof  = sof_q && !sof_shutter_q;
  assign short_end = open_sof && begun_q && !ended_q && run_q < RunBits'(FfcFrames);
  assign refreshed = begun_q && refresh_q;
  assign none      = none_q;  // FFC_CTRL.frames = 0: the frame start of the cycle before

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_run
    if (!rst_ni) begin
      run_q   <= '0;
      busy_q  <= 1'b0;
      begun_q <= 1'b0;
      ended_q <= 1'b0;
    end else begin
      if (sof_q) begin
        run_q <= !sof_shutter_q ? '0
               : (run_q == RunBits'(FfcFrames)) ? run_q : run_q + RunBits'(1);
      end
      if (ffc_start_i) begin
        busy_q  <= 1'b1;
        begun_q <= 1'b0;
        ended_q <= 1'b0;
      end else begin
        if (begun_q && open_sof) begin
          ended_q <= 1'b1;
        end
        if (ffc_done_o) begin
          busy_q <= 1'b0;
        end
        if (begin_ok_q && sof_q && sof_shutter_q) begin
          begun_q <= 1'b1;
        end
      end
    end
  end
  // done is registered (done_q: the event of the cycle before), so that the run's state
  // reaches the register file's flops from a flop; busy clears with it. A start in the
  // cycle of done_q begins a new run instead (as a start in the event's cycle does). No
  // second event while done_q ends the run: with frames of one pixel and FFC_CTRL.frames =
  // 0 the "no frames" end came at two frame starts in a row (irnuc formal, axis_top_ffc14:
  // a_done_once); busy_q already gated the second, so the ports are unchanged.
  assign done_e = busy_q && !done_q && !ffc_start_i && (refreshed || short_end || none);
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_done
    if (!rst_ni) begin
      done_q <= 1'b0;
      none_q <= 1'b0;
    end else begin
      done_q <= done_e;
      none_q <= start_i && ffc_armed_q && ffc_frames_i == '0;
    end
  end
  assign ffc_busy_o = busy_q;
  assign ffc_done_o = done_q && busy_q && !ffc_start_i;

  irnuc_axis_buffer #(.DataBits(WordBits)) u_coef_fork (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(fork_coef_valid),
    .ready_o(core_coef_ready),
    .data_i (in_word),
    .valid_o(coef_fork_valid),
    .ready_i(coef_fork_ready),
    .data_o (coef_fork_word)
  );

  irnuc_axis_buffer #(.DataBits(FoffWordBits)) u_foff_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_axis_foff_tvalid),
    .ready_o(s_axis_foff_tready),
    .data_i (s_axis_foff_tdata[FoffWordBits-1:0]),
    .valid_o(foff_valid),
    .ready_i(foff_ready),
    .data_o (foff_data)
  );

  irnuc_axis_buffer #(.DataBits(AccWordBits)) u_acc_in (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(s_axis_acc_tvalid),
    .ready_o(s_axis_acc_tready),
    .data_i (s_axis_acc_tdata[AccWordBits-1:0]),
    .valid_o(acc_valid),
    .ready_i(acc_ready),
    .data_o (acc_data)
  );

  // The core's pixels out, into the output buffer u_pix_out (below).
  logic               pix_valid, pix_ready, pix_sof, pix_eol;
  logic [OutBits-1:0] pix_data;

  // The core's frame size: copies of the framer's (flops beside the core, a cycle behind:
  // the framer takes a new size with a frame's first item once the core is drained, and
  // that item reaches the core through two registers, u_out and u_item_in).
  logic [WidthBits-1:0]  core_w_q;
  logic [HeightBits-1:0] core_h_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_core_size
    if (!rst_ni) begin
      core_w_q <= WidthBits'(MaxWidth);
      core_h_q <= HeightBits'(MaxHeight);
    end else begin
      core_w_q <= act_w_i;
      core_h_q <= act_h_i;
    end
  end

  method_ffc_top #(

    // irnuc-params: forward method_ffc_top (generated from nuc_fixed.methods; do not edit)
    .Method           (Method),
    .AdcBits          (AdcBits),
    .GainIntBits      (GainIntBits),
    .GainFracBits     (GainFracBits),
    .OffsetIntBits    (OffsetIntBits),
    .OffsetFracBits   (OffsetFracBits),
    .OutBits          (OutBits),
    .Rounding         (Rounding),
    .Overflow         (Overflow),
    .MaxWidth         (MaxWidth),
    .MaxHeight        (MaxHeight),
    .KneeIntBits      (KneeIntBits),
    .KneeFracBits     (KneeFracBits),
    .LevelIntBits     (LevelIntBits),
    .LevelFracBits    (LevelFracBits),
    .QuadIntBits      (QuadIntBits),
    .QuadFracBits     (QuadFracBits),
    .SquareBits       (SquareBits),
    .ReadingBits      (ReadingBits),
    .Tc1IntBits       (Tc1IntBits),
    .Tc1FracBits      (Tc1FracBits),
    .Tc2IntBits       (Tc2IntBits),
    .Tc2FracBits      (Tc2FracBits),
    .Tg1IntBits       (Tg1IntBits),
    .Tg1FracBits      (Tg1FracBits),
    .Tg2IntBits       (Tg2IntBits),
    .Tg2FracBits      (Tg2FracBits),
    .TcOrder          (TcOrder),
    .TcGain           (TcGain),
    .ReadingRangeBits (ReadingRangeBits),
    .FfcIntBits       (FfcIntBits),
    .FfcFracBits      (FfcFracBits),
    .FfcRounding      (FfcRounding),
    .FfcOverflow      (FfcOverflow),
    .FfcFrames        (FfcFrames),
    .FfcHold          (FfcHold)
    // irnuc-params: end
  ) u_core (
    .clk_i             (clk_i),
    .rst_ni            (rst_ni),
    .frame_width_i     (core_w_q),
    .frame_height_i    (core_h_q),
    .s_pix_valid_i     (fork_pix_valid),
    .s_pix_ready_o     (core_pix_ready),
    .s_pix_data_i      (in_raw),
    .s_pix_sof_i       (in_sof),
    .s_pix_eol_i       (in_eol),
    .s_pix_frame_i     (in_frame[FrameBits-1:0]),
    .s_pix_shutter_i   (item_shutter),
    .s_coef_valid_i    (coef_fork_valid),
    .s_coef_ready_o    (coef_fork_ready),
    .s_coef_data_i     (coef_fork_word),
    .s_foff_valid_i    (foff_valid),
    .s_foff_ready_o    (foff_ready),
    .s_foff_data_i     (foff_data),
    .s_acc_valid_i     (acc_valid),
    .s_acc_ready_o     (acc_ready),
    .s_acc_data_i      (acc_data),
    .m_acc_valid_o     (macc_valid),
    .m_acc_ready_i     (macc_ready),
    .m_acc_data_o      (macc_data),
    .m_foff_valid_o    (mfoff_valid),
    .m_foff_ready_i    (mfoff_ready),
    .m_foff_data_o     (mfoff_data),
    .m_pix_valid_o     (pix_valid),
    .m_pix_ready_i     (pix_ready),
    .m_pix_data_o      (pix_data),
    .m_pix_sof_o       (pix_sof),
    .m_pix_eol_o       (pix_eol),
    .ffc_target_valid_o(target_valid),
    .ffc_target_o      (target),
    .ffc_kept_o        (target_kept),
    .frame_err_o       (frame_err_o)
  );

  // The corrected pixels leave through an output buffer of their own (a registered stream
  // boundary): the DPC's output register inside the core then sees a fill flag as its ready,
  // not m_axis_video_tready, and is placed beside the DPC rather than at the port (tcffc14:
  // its valid drives the DPC's enables). One cycle more of latency; one pixel per clock.
  // The framer counts a pixel out of the core as it leaves this buffer (pix_out).
  irnuc_axis_buffer #(.DataBits(OutBits + 2)) u_pix_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(pix_valid),
    .ready_o(pix_ready),
    .data_i ({pix_sof, pix_eol, pix_data}),
    .valid_o(m_valid_o),
    .ready_i(m_ready_i),
    .data_o ({m_sof_o, m_eol_o, m_data_o})
  );

  // The write-back streams: tlast on each frame's last word, counted against the frame
  // size the frames are taken with, behind an output buffer (every output a flop).
  logic macc_last, mfoff_last;

  // They count against copies of the frame size (flops beside the counters, a cycle behind
  // the framer's: a new size is taken with a frame's first item, which reaches the
  // write-back streams many cycles later, after the old frames' words). The end of a line
  // and the last line are flags of their own (eol_q, row_last_q: the counters' next state and
  // tlast hang on flops, no compare on the path): stepped with a word from width - 2 and
  // height - 2 (the next position's compare made a word early), refreshed from the position
  // while no word passes (a new size: current two cycles after it).
  logic [1:0][WidthBits-1:0]  col_q;
  logic [1:0][HeightBits-1:0] row_q;
  logic [1:0]                 wb_beat, wb_last, eol_q, row_last_q;
  logic [WidthBits-1:0]       wb_wm1_q, wb_wm2_q;
  logic [HeightBits-1:0]      wb_hm1_q, wb_hm2_q;
  logic                       wb_w1_q, wb_h1_q;  // width 1, height 1

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_wb_size
    if (!rst_ni) begin
      wb_wm1_q <= WidthBits'(MaxWidth - 1);
      wb_hm1_q <= HeightBits'(MaxHeight - 1);
      wb_wm2_q <= WidthBits'(MaxWidth - 2);
      wb_hm2_q <= HeightBits'(MaxHeight - 2);
      wb_w1_q  <= MaxWidth == 1;
      wb_h1_q  <= MaxHeight == 1;
    end else begin
      wb_wm1_q <= act_wm1_i;
      wb_hm1_q <= act_hm1_i;
      // Width 1: all ones, a column the count never reaches (the line ends at every word).
      wb_wm2_q <= act_wm1_i - WidthBits'(1);
      wb_hm2_q <= act_hm1_i - HeightBits'(1);
      wb_w1_q  <= act_wm1_i == '0;
      wb_h1_q  <= act_hm1_i == '0;
    end
  end

  assign wb_beat = {mfoff_valid && mfoff_ready, macc_valid && macc_ready};
  for (genvar k = 0; k < 2; k++) begin : gen_wb_last
    assign wb_last[k] = eol_q[k] && row_last_q[k];
    always_ff @(posedge clk_i or negedge rst_ni) begin : p_count
      if (!rst_ni) begin
        col_q[k]      <= '0;
        row_q[k]      <= '0;
        eol_q[k]      <= MaxWidth == 1;
        row_last_q[k] <= MaxHeight == 1;
      end else if (wb_beat[k]) begin
        col_q[k] <= eol_q[k] ? '0 : col_q[k] + WidthBits'(1);
        eol_q[k] <= eol_q[k] ? wb_w1_q : col_q[k] == wb_wm2_q;
        if (eol_q[k]) begin
          row_q[k]      <= wb_last[k] ? '0 : row_q[k] + HeightBits'(1);
          row_last_q[k] <= row_last_q[k] ? wb_h1_q : row_q[k] == wb_hm2_q;
        end else begin
          row_last_q[k] <= row_q[k] == wb_hm1_q;
        end
      end else begin
        eol_q[k]      <= col_q[k] == wb_wm1_q;
        row_last_q[k] <= row_q[k] == wb_hm1_q;
      end
    end
  end
  assign macc_last  = wb_last[0];
  assign mfoff_last = wb_last[1];

  logic [AccWordBits-1:0]  macc_out;
  logic [FoffWordBits-1:0] mfoff_out;

  irnuc_axis_buffer #(.DataBits(AccWordBits + 1)) u_acc_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(macc_valid),
    .ready_o(macc_ready),
    .data_i ({macc_last, macc_data}),
    .valid_o(m_axis_acc_tvalid),
    .ready_i(m_axis_acc_tready),
    .data_o ({m_axis_acc_tlast, macc_out})
  );
  irnuc_axis_buffer #(.DataBits(FoffWordBits + 1)) u_foff_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(mfoff_valid),
    .ready_o(mfoff_ready),
    .data_i ({mfoff_last, mfoff_data}),
    .valid_o(m_axis_foff_tvalid),
    .ready_i(m_axis_foff_tready),
    .data_o ({m_axis_foff_tlast, mfoff_out})
  );
  assign m_axis_acc_tdata  = AccBits'(macc_out);
  assign m_axis_foff_tdata = FoffBits'(mfoff_out);

  // Not used: the input tlast (the core counts the words of a frame by its size), the
  // target the core computed and whether its refresh kept the offsets (no good pixel: the
  // refresh frame's m_axis_foff then carries the words it read; no register shows it yet).
  logic unused_ffc;
  assign unused_ffc = ^{s_axis_foff_tlast, s_axis_acc_tlast, target_valid, target, target_kept};
  if (FoffBits > FoffWordBits) begin : gen_foff_pad
    logic unused_foff;
    assign unused_foff = ^s_axis_foff_tdata[FoffBits-1:FoffWordBits];
  end
  if (AccBits > AccWordBits) begin : gen_acc_pad
    logic unused_acc;
    assign unused_acc = ^s_axis_acc_tdata[AccBits-1:AccWordBits];
  end
  assign pix_out = m_valid_o && m_ready_i;

`ifdef IRNUC_ASSERT
  // What the registers above rely on: the write-back counters' size copies and their
  // end-of-line / last-line flags are current whenever a word is counted, the run reads
  // the fork's frame starts a cycle late, and an FFC run ends at most once in two cycles
  // (done_q holds one event).
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  // The run's count a cycle behind a reference counted on the fork's take itself.
  logic [RunBits-1:0] ref_run_q, ref_run_past_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_ref_run
    if (!rst_ni) begin
      ref_run_q      <= '0;
      ref_run_past_q <= '0;
    end else begin
      ref_run_past_q <= ref_run_q;
      if (item_take && in_sof) begin
        ref_run_q <= !item_shutter ? '0
                   : (ref_run_q == RunBits'(FfcFrames)) ? ref_run_q : ref_run_q + RunBits'(1);
      end
    end
  end
  // Per write-back stream (one labelled assertion over both: a label inside a procedural
  // loop names two checks alike, which the formal front end refuses).
  logic [1:0] wb_flags_ok;
  always_comb begin : p_wb_flags
    for (int k = 0; k < 2; k++) begin
      wb_flags_ok[k] = !wb_beat[k] || (eol_q[k] == (col_q[k] == act_wm1_i)
                                       && row_last_q[k] == (row_q[k] == act_hm1_i));
    end
  end
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_wb_size: assert (wb_beat == '0 || (wb_wm1_q == act_wm1_i && wb_hm1_q == act_hm1_i))
        else $error("irnuc_axis_ffc: a write-back word counted in the cycle after a new frame size");
      a_wb_flags: assert (wb_flags_ok == '1)
        else $error("irnuc_axis_ffc: a write-back stream's end-of-line / last-line flag disagrees with its position (streams ok: %b)",
                    wb_flags_ok);
      a_core_size: assert (!pix_take || (core_w_q == act_w_i && core_h_q == act_h_i))
        else $error("irnuc_axis_ffc: a pixel entered the core in the cycle after a new frame size");
      a_run_late: assert (run_q == ref_run_past_q)
        else $error("irnuc_axis_ffc: the FFC run's frame count is not the fork's frame starts a cycle late");
      a_owe_range: assert (32'(owe_out_q) <= 32'(owe_q) + 32'(owe_in_q))
        else $error("irnuc_axis_ffc: a write-back word left that no item owed");
      a_owe_busy: assert (!(m_axis_acc_tvalid || m_axis_foff_tvalid) || wb_busy_q)
        else $error("irnuc_axis_ffc: a write-back word waits while the framer sees none owed");
      a_done_once: assert (!(done_q && done_e))
        else $error("irnuc_axis_ffc: an FFC run ended in two consecutive cycles");
    end
  end
`endif

endmodule
