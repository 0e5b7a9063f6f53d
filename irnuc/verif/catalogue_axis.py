"""The mutants of the AXI wrapper (``irnuc_axis_top``: the framer, the input buffers, the
register file, the core select, the FFC side), part of :data:`irnuc.verif.catalogue.CATALOGUE`."""

from __future__ import annotations

from typing import Any

from irnuc.cocotb_tests import tb_axis, tb_axis_ffc, tb_axis_method, tb_axis_table
from irnuc.verif.mutant import Mutant

_AXIS = {"top": "irnuc_axis_top", "suite": tb_axis.__name__}
#: The wrapper around method_dpc_top, with its method testbench.
_AXM = {"suite": tb_axis_method.__name__}
#: table_interp's selection (irnuc_axis_table, TABLE_SEL), with its testbench.
_AXT = {"suite": tb_axis_table.__name__, "config": "table14"}
#: The wrapper around method_ffc_top, with its FFC testbench.
_AXF = {"suite": tb_axis_ffc.__name__, "config": "ffc14"}


def _ma(id: str, file: str, find: str, replace: str, what: str, **kw: Any) -> Mutant:
    """A mutant of the AXI wrapper, run in irnuc_axis_top with tb_axis (``**_AXM``: with
    tb_axis_method on a method configuration)."""
    return Mutant(id, file, find, replace, what, **{**_AXIS, **kw})


#: The wrapper's mutants, in the catalogue's order.
AXIS_MUTANTS: tuple[Mutant, ...] = (
    # ---- irnuc_axis_top: the framer, the input buffers, the register file, the wrapper ----
    _ma("ax_sof_late_every_beat", "irnuc_axis_framer.sv",
        "sof_late_o    <= drop_beat && starting && !late_q;",
        "sof_late_o    <= drop_beat && starting;",
        "SOF_ERRORS.late counts every dropped beat, not each run of them once"),
    _ma("ax_dpc_off_keeps_bad", "irnuc_axis_framer.sv", "      word = word & ~BadMask;",
        "      word = word;", "CTRL.dpc_en = 0 and filler pixels keep the word's bad flag"),
    _ma("ax_no_drain", "irnuc_axis_framer.sv",
        "wait_ok_n = (vst_n == AxisWait) && wait_free && (!size_dirty_i || (starting && empty_q));",
        "wait_ok_n = (vst_n == AxisWait) && wait_free && (!size_dirty_i || starting);",
        "a new frame size starts before the previous frame has left the core"),
    _ma("ax_start_ignores_drain", "irnuc_axis_framer.sv",
        "assign start_fire = go && item && s_wait_q;",
        "assign start_fire = go && vid_valid_i && vid_sof_i && s_wait_q;",
        "the active settings and the register file take a frame start the drain still holds"),
    _ma("ax_flight_never_counts", "irnuc_axis_framer.sv", "fire_q    <= fire;",
        "fire_q    <= 1'b0;",
        "the in-flight count never counts an item sent (fire_q): no drain before a new size"),
    _ma("ax_pad_state_late", "irnuc_axis_framer.sv",
        "s_pad_q     <= s_pad_d;", "s_pad_q     <= (vst_q == AxisPad);",
        "the one-hot filler state a cycle behind the state (fillers sent a cycle late)"),
    _ma("ax_out_free_ignores_fire", "irnuc_axis_framer.sv",
        "out_free_q <= !m_valid_o || m_ready_i || (out_free_q && !fire);",
        "out_free_q <= !m_valid_o || m_ready_i || out_free_q;",
        "the decision's copy of the output register's ready misses an item that fills its "
        "skid register (a third item sent over two held)"),
    _ma("ax_go_ignores_output", "irnuc_axis_framer.sv",
        "|| (cst_f == CoefFill)) && (!m_valid_o || m_ready_i);",
        "|| (cst_f == CoefFill));",
        "the registered decision (go_q) after an item sent ignores the output register's "
        "ready: an item sent over two held"),
    _ma("ax_line_size_follows_pending", "irnuc_axis_framer.sv",
        "    end else if (s_wait_q) begin\n      lw_m1_q  <= pend_width_m1_i;",
        "    end else begin\n      lw_m1_q  <= pend_width_m1_i;",
        "the position registers' line size follows FRAME_SIZE inside a frame (a write "
        "changes the lines of the frame being sent)"),
    _ma("ax_nuc_off_frame_word", "irnuc_axis_framer.sv",
        "assign frame = !starting ? '0 : pend_nuc_en_i ? pend_frame_i : NeutralFrame;",
        "assign frame = !starting ? '0 : pend_frame_i;",
        "NUC off keeps one_point's gain register (no neutral frame word)",
        **_AXM, config="onepoint14"),
    _ma("ax_buffer_read_stuck", "irnuc_axis_buffer.sv", "rd_q <= rd_q ^ pop;",
        "rd_q <= rd_q;", "an input buffer keeps reading the same entry after a pop"),
    _ma("ax_buffer_never_full", "irnuc_axis_buffer.sv", "full_q <= any_q;",
        "full_q <= 1'b0;", "an input buffer takes a third item over an unread one"),
    _ma("ax_buffer_head_from_input", "irnuc_axis_buffer.sv",
        "assign head_next = full_q ? mem_q[!rd_q][DataBits-1:MuxBits] : data_i[DataBits-1:MuxBits];",
        "assign head_next = data_i[DataBits-1:MuxBits];",
        "an input buffer's markers (head register) after a pop with two held: the input's, not "
        "the other entry's"),
    _ma("ax_buffer_head_stale", "irnuc_axis_buffer.sv", "if (!any_q || ready_i) begin",
        "if (!any_q) begin",
        "an input buffer's markers (head register) kept after a pop: the older entry's"),
    # ---- the register file: irnuc's AXI4-Lite slave and the fields of the generated
    # register block (irnuc_axil_regblock.sv), the hand-written registers (irnuc_axil_regs.sv)
    _ma("ax_wready_late", "irnuc_axil_regblock.sv", "axil_w_ready  <= !axil_w_held_d;",
        "axil_w_ready  <= !axil_w_held;",
        "wready a cycle behind the write data register (write data taken while one is "
        "held overwrite it)"),
    _ma("ax_irq_not_enabled", "irnuc_axil_regblock.sv",
        "|(field_storage.IRQ_STATUS.frame_done.value & field_storage.IRQ_ENABLE.frame_done.value)",
        "|(field_storage.IRQ_STATUS.frame_done.value)",
        "irq_o ignores IRQ_ENABLE.frame_done"),
    _ma("ax_status_no_w1c", "irnuc_axil_regblock.sv",
        "next_c = field_storage.STATUS.eol_late.value & ~(decoded_wr_data[3:3] & "
        "decoded_wr_biten[3:3]);",
        "next_c = field_storage.STATUS.eol_late.value;",
        "STATUS.eol_late cannot be cleared (W1C)"),
    _ma("ax_size_write_never", "irnuc_axil_regs.sv",
        "assign size_write_o = size_write_q;",
        "assign size_write_o = 1'b0;",
        "a FRAME_SIZE write never raises size_dirty: no drain before a new size"),
    _ma("ax_size_not_checked", "irnuc_axil_regs.sv",
        "    end else if (size_wr_q && size_legal) begin",
        "    end else if (size_wr_q) begin",
        "an illegal FRAME_SIZE write (SLVERR) still changes the register"),
    _ma("ax_size_no_slverr", "irnuc_axil_regs.sv",
        "assign wr_err       = size_wr_q && !size_legal;",
        "assign wr_err       = 1'b0;",
        "an illegal FRAME_SIZE write is answered OKAY (the register keeps its value)"),
    _ma("ax_size_merge_ignores_strobes", "irnuc_axil_regs.sv",
        "new_w_q <= (FieldW'(width_q) & ~size_bw_q) | (size_wd_q & size_bw_q);",
        "new_w_q <= size_wd_q;",
        "a FRAME_SIZE write's width taken whole (an unwritten byte lane as 0)"),
    _ma("ax_traffic_counts_idle", "irnuc_axil_regs.sv",
        "assign hwif_in.PIXELS_IN.count.incr   = beat_i;",
        "assign hwif_in.PIXELS_IN.count.incr   = 1'b1;",
        "PIXELS_IN counts every cycle, not the beats"),
    _ma("ax_pending_sticks", "irnuc_axil_regs.sv",
        "pending_q    <= size_write_o || (pending && !start_i);",
        "pending_q    <= size_write_o || pending;",
        "STATUS.pending stays 1 after the frame start that took the write"),
    _ma("ax_frames_out_every_line", "irnuc_axis_top.sv",
        "frame_out_q <= core_valid && m_axis_video_tready && core_eol && (out_row_q == act_hm1);",
        "frame_out_q <= core_valid && m_axis_video_tready && core_eol;",
        "FRAMES_OUT and IRQ_STATUS.frame_done at every line's end"),
    _ma("ax_reading_from_t_ref", "irnuc_axis_top.sv",
        "frame_tc_offset#(ReadingBits)::word_t part0;\n"
        "    assign part0.reading = slots[2][ReadingBits-1:0];",
        "frame_tc_offset#(ReadingBits)::word_t part0;\n"
        "    assign part0.reading = slots[3][ReadingBits-1:0];",
        "tc_offset: the frame word's reading taken from T_REF", **_AXM, config="tcoffset14"),
    _ma("ax_housing_from_reading", "irnuc_axis_top.sv",
        "assign part0.housing_reading = slots[8][HousingBits-1:0];",
        "assign part0.housing_reading = slots[2][HousingBits-1:0];",
        "tc_housing: the frame word's housing reading taken from READING (the FPA's)",
        **_AXM, config="tchousing14"),
    _ma("ax_h_ref_from_t_ref", "irnuc_axis_top.sv",
        "assign part0.h_ref = slots[9][HousingBits-1:0];",
        "assign part0.h_ref = slots[3][HousingBits-1:0];",
        "tc_housing: the frame word's H_REF taken from T_REF", **_AXM, config="tchousing14"),
    # ---- the classes issue 39 found escaping, killed by the random register traffic
    #      (cocotb_tests/axil_traffic.py) and ffc_second_run --------------------------------
    _ma("ax_rdata_live", "irnuc_axil_regblock.sv",
        "if(cpuif_rd_ack) axil_rdata <= cpuif_rd_data;",
        "if(1'b1) axil_rdata <= cpuif_rd_data;",
        "RDATA follows the register block's read-back while RVALID waits for RREADY (a "
        "counter read mid frame changes under a held RREADY)"),
    _ma("ax_reset_size_m1", "irnuc_axil_regs.sv",
        "      width_m1_q   <= WidthBits'(MaxWidth - 1);",
        "      width_m1_q   <= WidthBits'(MaxWidth - 2);",
        "the reset frame size's width - 1 one short: a frame at the reset size (no FRAME_SIZE "
        "written) has lines a pixel short"),
    _ma("ax_ffc_status_ro_okay", "irnuc_axil_regblock.sv",
        "is_valid_rw |= (ahead_wr_addr == 12'h84) & !1'b1;",
        "is_valid_rw |= (ahead_wr_addr == 12'h84);",
        "a write to FFC_STATUS (read-only) answered OKAY", **_AXF),
    # The automatic mutant auto_irnuc_axil_regblock_s1_5 by hand (that draw changes with the
    # RTL): killed by the traffic's FRAME_SIZE lanes (Traffic.size_strobes).
    _ma("ax_size_biten15", "irnuc_axil_regblock.sv",
        "assign hwif_out.FRAME_SIZE.wr_biten = decoded_wr_biten;",
        "assign hwif_out.FRAME_SIZE.wr_biten = decoded_wr_biten ^ 32'h0000_8000;",
        "FRAME_SIZE's bit enable 15 inverted: the width's top bit taken from an unwritten "
        "byte lane, dropped from a written one"),
    _ma("ax_ffc_frames_strobes", "irnuc_axil_regs.sv",
        "ffc_frames_q <= (ffc_frames_q & ~hwif_out.FFC_CTRL.wr_biten.frames)\n"
        "                          | (hwif_out.FFC_CTRL.wr_data.frames & "
        "hwif_out.FFC_CTRL.wr_biten.frames);",
        "ffc_frames_q <= hwif_out.FFC_CTRL.wr_data.frames;",
        "FFC_CTRL.frames ignores the byte strobes: a lane not written is cleared", **_AXF),
    _ma("ax_table_reading_strobes", "irnuc_axil_regs.sv",
        "value_q <= TableReadingBits'((32'(value_q) & ~biten)\n"
        "                                       | (hwif_out.TABLE_READING[k].wr_data.value & "
        "biten));",
        "value_q <= TableReadingBits'(hwif_out.TABLE_READING[k].wr_data.value);",
        "TABLE_READING[k] ignores the byte strobes: a lane not written is cleared", **_AXM,
        config="table14"),
    _ma("ax_table_no_pending", "irnuc_axil_regs.sv",
        "assign table_touch[k] = |(biten & Mask);", "assign table_touch[k] = 1'b0;",
        "a TABLE_READING[k] write does not raise STATUS.pending", **_AXM, config="table14"),
    _ma("ax_ffc_second_run_ended", "irnuc_axis_ffc.sv",
        "        begun_q <= 1'b0;\n        ended_q <= 1'b0;",
        "        begun_q <= 1'b0;\n        ended_q <= ended_q;",
        "a second FFC run keeps the first run's end: a short second run is never done",
        **_AXF),
    # ---- irnuc_axis_core: the core of the method -------------------------------------------
    _ma("ax_core_eol_from_sof", "irnuc_axis_core.sv",
        ".s_pix_eol_i   (item_eol_i),\n      .s_coef_valid_i(item_valid_i),",
        ".s_pix_eol_i   (item_sof_i),\n      .s_coef_valid_i(item_valid_i),",
        "two_point: the core's end of line taken from the start of frame"),
    _ma("ax_core_frame_word_dropped", "irnuc_axis_core.sv",
        ".s_pix_frame_i (item_frame_i),", ".s_pix_frame_i ('0),",
        "method_dpc_top gets a zero frame word (one_point: gain 0)", **_AXM,
        config="onepoint14"),
    # ---- irnuc_axis_top / irnuc_axis_core around method_drift_top (blind_drift) -----------
    _ma("ax_drift_ref_from_sum", "irnuc_axis_top.sv",
        "assign fw.blind_ref  = slots[5][BlindBits-1:0];",
        "assign fw.blind_ref  = slots[4][BlindBits-1:0];",
        "blind_drift: the frame word's BLIND_REF taken from BLIND_SUM (no drift ever)", **_AXM,
        config="drift14"),
    _ma("ax_drift_sof_no_wait", "irnuc_axis_core.sv",
        "assign pass        = !item_sof_i || blind_sent_q;", "assign pass        = 1'b1;",
        "blind_drift: a frame's first pixel goes to the core before its blind item (the "
        "frame takes the previous frame's drift, or the join hangs)", **_AXM,
        config="drift14"),
    _ma("ax_drift_sent_sticks", "irnuc_axis_core.sv",
        "        end else if (core_valid && item_ready_o && item_sof_i) begin\n"
        "          blind_sent_q <= 1'b0;",
        "        end else if (1'b0) begin\n"
        "          blind_sent_q <= 1'b0;",
        "blind_drift: the blind item is sent once after reset, never again (the second "
        "frame waits for a drift code forever)", **_AXM, config="drift14"),
    # ---- irnuc_axis_ffc: the FFC side of the wrapper ---------------------------------------
    _ma("ax_ffc_run_one_short", "irnuc_axis_ffc.sv",
        "assign pend_shutter = ffc_now != '0;",
        "assign pend_shutter = ffc_now > RegFfcCtrlFramesBits'(1);",
        "FFC_CTRL.frames - 1 shutter frames after a start (a full run has no refresh)",
        **_AXF),
    _ma("ax_ffc_tlast_every_line", "irnuc_axis_ffc.sv",
        "assign wb_last[k] = eol_q[k] && row_last_q[k];",
        "assign wb_last[k] = eol_q[k];",
        "m_axis_acc / m_axis_foff: tlast on every line's last word", **_AXF),
    _ma("ax_ffc_done_not_on_refresh", "irnuc_axis_ffc.sv",
        "assign done_e = busy_q && !done_q && !ffc_start_i && (refreshed || short_end || none);",
        "assign done_e = busy_q && !done_q && !ffc_start_i && (short_end || none);",
        "FFC_STATUS.done and IRQ_STATUS.ffc_done not raised by the refresh's write-back",
        **_AXF),
    # The fork's coefficient buffer bypassed (the wrapper before session 31's fix): the same
    # words, but the word waits at the core's join and the fork skips a cycle in four.
    _ma("ax_ffc_coef_fork_bypass", "irnuc_axis_ffc.sv",
        ".s_coef_valid_i    (coef_fork_valid),", ".s_coef_valid_i    (fork_coef_valid),",
        "the fork's coefficient side straight into method_ffc_top (no u_coef_fork): "
        "frames at full rate lose one cycle in four",
        also=((".s_coef_ready_o    (coef_fork_ready),", ".s_coef_ready_o    (core_coef_ready),"),
              (".s_coef_data_i     (coef_fork_word),", ".s_coef_data_i     (in_word),"),
              (".ready_o(core_coef_ready),", ".ready_o(),")),
        **_AXF),
    # The registers of session 32 (Fmax): the item's input buffer, done a cycle late, the
    # write-back counters' size copies.
    _ma("ax_ffc_pix_unbuffered", "irnuc_axis_ffc.sv",
        ".s_pix_data_i      (in_raw),", ".s_pix_data_i      (item_raw_i),",
        "the core's pixel taken from the framer's item, not from u_item_in's (the pixel an item "
        "ahead of its word)", **_AXF),
    # Killed by ffc_short_run's FRAME_SIZE write after the held frames (the count of items
    # in flight only shows at a drain).
    _ma("ax_ffc_held_sof_unbuffered", "irnuc_axis_ffc.sv",
        "assign held_e       = in_sof ?", "assign held_e       = item_sof_i ?",
        "the held-frame decision reads the framer's sof, not the sof of the item at the fork "
        "(behind u_item_in): held items are never counted out of the core",
        **_AXF),
    # The count out of the core before session 33's fix: one item a cycle, so the last open
    # frame leaving as a held one enters lost counts, and a drain after the held frames
    # never ended.
    _ma("ax_ffc_core_out_one", "irnuc_axis_ffc.sv",
        "core_out_q <= {1'b0, pix_out} + {1'b0, item_take && held_e};",
        "core_out_q <= {1'b0, pix_out || (item_take && held_e)};",
        "an output and a held item's entry in one cycle count one item out of the core, "
        "not two: the drain before a new frame size never ends", **_AXF),
    _ma("ax_ffc_busy_clears_early", "irnuc_axis_ffc.sv",
        "        if (ffc_done_o) begin\n          busy_q <= 1'b0;",
        "        if (done_e) begin\n          busy_q <= 1'b0;",
        "FFC_STATUS.busy clears with the run's end event, a cycle before done_q: done is "
        "never raised", **_AXF),
    _ma("ax_ffc_wb_size_stuck", "irnuc_axis_ffc.sv",
        "      wb_wm1_q <= act_wm1_i;", "      wb_wm1_q <= wb_wm1_q;",
        "the write-back counters keep the reset width (MaxWidth - 1): tlast at the wrong word",
        **_AXF),
    # The registers of session 33 (Fmax): the write-back counters' end-of-line / last-line
    # flags, the run's events from flops.
    _ma("ax_ffc_wb_eol_step_late", "irnuc_axis_ffc.sv",
        "eol_q[k] <= eol_q[k] ? wb_w1_q : col_q[k] == wb_wm2_q;",
        "eol_q[k] <= eol_q[k] ? wb_w1_q : col_q[k] == wb_wm1_q;",
        "the end-of-line flag stepped from width - 1, not width - 2: lines a word too long",
        **_AXF),
    _ma("ax_ffc_wb_flags_stale", "irnuc_axis_ffc.sv",
        "        eol_q[k]      <= col_q[k] == wb_wm1_q;\n        row_last_q[k] <= row_q[k] == wb_hm1_q;",
        "        eol_q[k]      <= eol_q[k];\n        row_last_q[k] <= row_last_q[k];",
        "the write-back flags not refreshed while no word passes: a frame 1 wide or 1 tall, "
        "or the first after one, ends its lines at the old size", **_AXF),
    _ma("ax_ffc_run_sof_every_cycle", "irnuc_axis_ffc.sv",
        "sof_q         <= item_take && in_sof;", "sof_q         <= in_valid && in_sof;",
        "FFC_STATUS's run counts a frame start in every cycle its first item waits at the fork",
        **_AXF),
    _ma("ax_ffc_refresh_any_word", "irnuc_axis_ffc.sv",
        "refresh_q     <= m_axis_foff_tvalid && m_axis_foff_tready && m_axis_foff_tlast;",
        "refresh_q     <= m_axis_foff_tvalid && m_axis_foff_tready;",
        "FFC_STATUS.done with the refresh's first new offset, not its last", **_AXF),
    _ma("ax_ffc_pix_out_markers_swapped", "irnuc_axis_ffc.sv",
        ".data_i ({pix_sof, pix_eol, pix_data}),", ".data_i ({pix_eol, pix_sof, pix_data}),",
        "the pixel output buffer swaps the corrected pixels' sof and eol", **_AXF),
    # Killed by ffc_resize_in_run / ffc_resize_in_refresh (a new frame size written while a
    # run's write-back words are still in the core or held by backpressure).
    _ma("ax_ffc_drain_ignores_writeback", "irnuc_axis_framer.sv",
        "empty_q   <= (flight_q == '0) && !fire_q && !fire && !wb_busy_i;",
        "empty_q   <= (flight_q == '0) && !fire_q && !fire;",
        "a new frame size is taken before the FFC write-back words are out (their tlast "
        "counted against the new size)", **_AXF),
    _ma("ax_ffc_owe_no_add", "irnuc_axis_ffc.sv",
        "owe_mode.acc_first || owe_mode.acc_add || owe_mode.refresh",
        "owe_mode.acc_first || owe_mode.refresh",
        "a run's later shutter frames owe no m_axis_acc words to the drain", **_AXF),
    _ma("ax_ffc_owe_no_refresh", "irnuc_axis_ffc.sv",
        "owe_mode.acc_first || owe_mode.acc_add || owe_mode.refresh",
        "owe_mode.acc_first || owe_mode.acc_add",
        "the refresh frame owes no m_axis_foff words to the drain", **_AXF),
    # ---- the FFC request (irnuc_ffc_trigger in irnuc_axil_regs; tb_axis_ffc's
    # ffc_request_* sequences against nuc_fixed.ffc_policy) ------------------------------------
    _ma("ax_ffc_trigger_period_late", "irnuc_ffc_trigger.sv",
        "per_q  <= (period_i != '0) && (since_q >= period_i);",
        "per_q  <= (period_i != '0) && (since_q > period_i);",
        "FFC_PERIOD compared with > (the request a frame after since reaches the period)",
        **_AXF),
    _ma("ax_ffc_trigger_start_ignored", "irnuc_ffc_trigger.sv",
        "      if (ffc_start_i) begin\n        arm_q <= 1'b1;",
        "      if (1'b0) begin\n        arm_q <= 1'b1;",
        "an FFC_CTRL.start does not restart the count or take the reference: never re-armed",
        **_AXF),
    _ma("ax_ffc_trigger_level", "irnuc_ffc_trigger.sv",
        "req_q     <= (per_q || thr_hit) && !due_q;", "req_q     <= per_q || thr_hit;",
        "a request at every frame start while due, not once per crossing (a W1C does not "
        "hold)", **_AXF),
    _ma("ax_ffc_trigger_threshold_late", "irnuc_ffc_trigger.sv",
        "(ThresholdBits'(diff_q) >= threshold_i)", "(ThresholdBits'(diff_q) > threshold_i)",
        "FFC_THRESHOLD compared with > (a change of exactly the threshold asks for nothing)",
        **{**_AXF, "config": "tcffc14"}),
    _ma("ax_ffc_trigger_ref_not_taken", "irnuc_ffc_trigger.sv",
        "          ref_q   <= reading_i;", "          ref_q   <= ref_q;",
        "the reference reading is never taken (0): FFC_REF and the threshold against 0",
        **{**_AXF, "config": "tcffc14"}),
    # ---- table_interp: the weight and table pair from READING and TABLE_READING[k] ------------
    _ma("ax_table_no_hold", "irnuc_axis_table.sv",
        "assign hold_o   = write_i || stale_q || iw_busy;", "assign hold_o   = write_i;",
        "a frame starts while its weight is being computed (the framer is held only in the "
        "write's cycle)", **_AXT),
    _ma("ax_table_restart_lost", "irnuc_axis_table.sv",
        "stale_q <= write_i || (stale_q && !iw_start);", "stale_q <= write_i;",
        "a write while the weight is computed does not restart it: the result is that of "
        "the values interp_weight started with", **_AXT),
    _ma("ax_table_error_weight", "irnuc_axis_table.sv",
        "assign weight_o = iw_error ? '0 : iw_weight;", "assign weight_o = iw_weight;",
        "non-increasing table readings: the frame takes interp_weight's meaningless weight, "
        "not 0", **_AXT),
    _ma("ax_framer_ignores_hold", "irnuc_axis_framer.sv",
        "wait_free = !size_write_i && !hold_i;",
        "wait_free = !size_write_i;",
        "the framer starts a frame while irnuc_axis_table computes its weight", **_AXT),
    _ma("ax_table_reading_from_t_ref", "irnuc_axis_top.sv",
        ".reading_i       (slots[2][ReadingBits-1:0]),",
        ".reading_i       (slots[3][ReadingBits-1:0]),",
        "table_interp's weight computed from T_REF's slot (reserved: 0), not READING",
        **_AXM, config="table14"),
    _ma("ax_table_reading_no_restart", "irnuc_axil_regs.sv",
        "&& (|(slot_req[SlotReading] & slot_req_is_wr[SlotReading])",
        "&& (1'b0",
        "a READING write does not restart the weight (only a TABLE_READING[k] write does)",
        **_AXT),
)

__all__ = ["AXIS_MUTANTS"]
