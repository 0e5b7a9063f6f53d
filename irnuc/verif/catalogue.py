"""The mutation catalogue: every mutant of the RTL, with its configuration, suite and (for
an equivalent one) the argument why no test can kill it (:mod:`irnuc.verif.mutate` runs
them)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from irnuc.cocotb_tests import tb_ffc, tb_interp_weight, tb_method, tb_stage
from irnuc.common.errors import UserError
from irnuc.verif.catalogue_axis import AXIS_MUTANTS
from irnuc.verif.mutant import PKG_FILE, PKG_SUITE, PKG_TOP, SUITE_MODULE, SUITE_TOP, Mutant

#: Why a mutant of the line buffer's addresses is equivalent on a maximum width of 3 or less.
_LB_UNUSED = ("every legal frame is then at most 3 wide, and for a latched width of 1, 2 or "
              "3 dpc_core takes the column word from the window (lb_w1/lb_w2/lb_w3), never "
              "from the line buffer's read data, so no line-buffer address reaches an "
              "output; the branch that differs (the look-ahead start 3, the RAM data) is "
              "used only after an illegal width 0, which frame_err_o flags and after which "
              "the outputs are unspecified")


#: Why a mutant of the frame-size bookkeeping is equivalent on one-pixel-wide (or -high, or
#: 1 x 1) frames; the sizes other than the one legal value are illegal.
_AFTER_ILLEGAL = ("a frame of another size is illegal there, flagged by frame_err_o, after "
                  "which the outputs are unspecified")
_ONE_WIDE_SAME = ("every legal frame is then 1 wide: the widths compared are equal, so "
                  "leaving them out changes nothing; " + _AFTER_ILLEGAL)
_ONE_HIGH_SAME = ("every legal frame is then 1 high: the heights compared are equal, so "
                  "leaving them out changes nothing; " + _AFTER_ILLEGAL)
_ONE_WIDE_LAST = ("every legal frame is then 1 wide: every column is the row's last "
                  "(cur_col_last is 1 in Idle from fw_is1_q and after every take from "
                  "col_last_q <= fw_is1_q / geo_w_is1_q), so the branch of a column that is "
                  "not the last, and the test of the last column, never decide anything; "
                  + _AFTER_ILLEGAL)
_ONE_HIGH_LAST = ("every legal frame is then 1 high: the output row is always the first and "
                  "the last (or_last_q is loaded from fh_is1_q / geo_h_is1_q, both 1, and the "
                  "branch of a row that is not the last is never taken); " + _AFTER_ILLEGAL)
_ONE_PIXEL = ("every legal frame is then 1 x 1: a new frame is always of the same size, so "
              "no frame has to wait for a flush; " + _AFTER_ILLEGAL)


def _m(id: str, file: str, find: str, replace: str, what: str, **kw: Any) -> Mutant:
    return Mutant(id, file, find, replace, what, **kw)


_METHOD = {"top": "method_dpc_top", "suite": tb_method.__name__}
_IW = {"top": "interp_weight", "suite": tb_interp_weight.__name__,
       "config": "table14"}


def _mm(id: str, file: str, find: str, replace: str, what: str, config: str, **kw: Any
        ) -> Mutant:
    """A mutant run in method_dpc_top (tb_method) on a method configuration."""
    return Mutant(id, file, find, replace, what, config=config, **{**_METHOD, **kw})


_DRIFT = {"top": "method_drift_top", "suite": tb_stage.__name__,
          "config": "drift14"}
_FFC = {"top": "method_ffc_top", "suite": tb_ffc.__name__, "config": "ffc14"}


def _ms(id: str, file: str, find: str, replace: str, what: str, stage: dict, **kw: Any
        ) -> Mutant:
    """A mutant run in a stage top with its testbench (``stage``: _DRIFT or _FFC)."""
    return Mutant(id, file, find, replace, what, **{**stage, **kw})


_HALF_UP = (("rounding", "half_up"),)
_WRAP = (("rounding", "truncate"), ("overflow", "wrap"))

#: The catalogue: every design module of hdl/ (the simulation-only checkers
#: irnuc_stream_assert / irnuc_frame_assert are checked by tb_protocol's violation tests).
CATALOGUE: tuple[Mutant, ...] = (
    # ---- irnuc_pkg -------------------------------------------------------------------------
    _m("pkg_recip_floor", "irnuc_pkg.sv",
       "num = (64'd1 << dpc_recip_shift(out_bits)) + longint'(n) - 64'd1;",
       "num = (64'd1 << dpc_recip_shift(out_bits));",
       "DPC reciprocal rounded down instead of up (floor(2^K/n))"),
    _m("pkg_recip_shift_plus1", "irnuc_pkg.sv", "localparam int unsigned DpcRecipGuardBits = 6;",
       "localparam int unsigned DpcRecipGuardBits = 7;",
       "DPC reciprocal shift K = B + 7 instead of B + 6",
       equivalent="with K = B + 7, R[n] = ceil(2^K/n) still gives M (R[n] n - 2^K) < 2^(B+3) "
                  "* 8 < 2^K, so (M R[n]) >> K = floor(M/n) exactly: the same output for "
                  "every input (only tb_pkg's table comparison notices the new table)"),
    # On typical14 the DPC's 17 x 21 multiply becomes 2 x 2 parts instead of 1 x 2: the
    # same products one stage later (on minimal, with 11 x 15 bits, it would be equivalent).
    _m("pkg_chunk_16", "irnuc_pkg.sv", "localparam int unsigned MulChunkBits = 17;",
       "localparam int unsigned MulChunkBits = 16;",
       "multiplier chunks of 16 bits: the same products, one adder stage more on typical14",
       config="typical14"),
    # ---- irnuc_spill_register -----------------------------------------------------------
    _m("spill_ready_half_rate", "irnuc_spill_register.sv", "assign ready_o = ~skid_valid_q;",
       "assign ready_o = ~skid_valid_q & ~main_valid_q;",
       "ready only when both registers are empty, the registers unchanged: an item is "
       "taken while ready is low (duplicated)"),
    # Three sites: ready only when both registers are empty, and the registers load only
    # then (the skid register never): every item once, at half rate.
    _m("spill_half_rate", "irnuc_spill_register.sv",
       "      main_valid_q <= skid_valid_q | valid_i;",
       "      main_valid_q <= skid_valid_q | (valid_i & ~main_valid_q);",
       "the main register loads only when it was empty (with ready_o to match): half "
       "throughput, no item lost or duplicated",
       also=(("    end else if (valid_i && !skid_valid_q) begin",
              "    end else if (1'b0) begin"),
             ("assign ready_o = ~skid_valid_q;",
              "assign ready_o = ~skid_valid_q & ~main_valid_q;"))),
    _m("spill_skid_order", "irnuc_spill_register.sv",
       "main_data_q <= skid_valid_q ? skid_data_q : data_i;", "main_data_q <= data_i;",
       "the main register refills from the input, not from the skid register"),
    _m("spill_reset_valid", "irnuc_spill_register.sv",
       "      main_valid_q <= 1'b0;\n      skid_valid_q <= 1'b0;\n    end else if (main_load)",
       "      main_valid_q <= 1'b1;\n      skid_valid_q <= 1'b0;\n    end else if (main_load)",
       "reset leaves the main register valid"),
    _m("spill_skid_hold", "irnuc_spill_register.sv", "    if (!skid_valid_q) begin\n",
       "    if (1'b1) begin\n", "the skid register follows the input while full"),
    # ---- irnuc_add_tree -----------------------------------------------------------------
    _m("add_tree_subtract", "irnuc_add_tree.sv",
       "if (en_i) node_q[k] <= node_in[2*k] + node_in[2*k+1];",
       "if (en_i) node_q[k] <= node_in[2*k] - node_in[2*k+1];", "adder tree subtracts"),
    _m("add_tree_valid_no_enable", "irnuc_add_tree.sv",
       "end else if (en_i) begin\n          valid_q <= valid_in;",
       "end else begin\n          valid_q <= valid_in;",
       "valid moves while the pipeline is stalled"),
    _m("add_tree_side_no_enable", "irnuc_add_tree.sv", "        if (en_i) side_q <= side_in;",
       "        side_q <= side_in;", "side band moves while the pipeline is stalled"),
    # ---- irnuc_mul_parts ----------------------------------------------------------------
    _m("mul_part_shift", "irnuc_mul_parts.sv", "<< (ALsb + BLsb);", "<< (ALsb + BLsb + 1);",
       "partial product placed one bit too high"),
    _m("mul_side_no_enable", "irnuc_mul_parts.sv",
       "    if (en_i) begin\n      side_q[0] <= side_i;",
       "    if (1'b1) begin\n      side_q[0] <= side_i;",
       "multiplier side band moves while stalled"),
    # ---- irnuc_line_buffer --------------------------------------------------------------
    _m("lb_read_always", "irnuc_line_buffer.sv", "    if (rd_en_i) begin",
       "    if (1'b1) begin", "the line buffer reads while no item is taken"),
    _m("lb_skip_column0", "irnuc_line_buffer.sv", "    if (wr_en_i) begin",
       "    if (wr_en_i && wr_addr_i != '0) begin", "column 0 is never written"),
    # ---- nuc_core ------------------------------------------------------------------------
    _m("nuc_half_up_no_inc", "nuc_core.sv", "    assign inc = sum_s[FracBits-1];",
       "    assign inc = 1'b0;", "half_up rounds down", changes=_HALF_UP),
    _m("nuc_half_even_no_odd", "nuc_core.sv",
       "assign inc = sum_s[FracBits-1] & (sticky | sum_s[FracBits]);",
       "assign inc = sum_s[FracBits-1] & sticky;", "half_even: ties of odd integers dropped"),
    _m("nuc_half_even_no_sticky", "nuc_core.sv",
       "assign inc = sum_s[FracBits-1] & (sticky | sum_s[FracBits]);",
       "assign inc = sum_s[FracBits-1] & sum_s[FracBits];",
       "half_even: the bits below the half are ignored"),
    _m("nuc_sat_low_value", "nuc_core.sv", "        out_d = '0;\n      end else if (too_big)",
       "        out_d = OutBits'(1);\n      end else if (too_big)",
       "saturation below zero gives 1"),
    _m("nuc_sat_high_bit", "nuc_core.sv", "assign too_big = |rnd_q[RndBits-2:OutBits];",
       "assign too_big = |rnd_q[RndBits-2:OutBits+1];",
       "saturation above 2^B - 1 misses its lowest bit"),
    _m("nuc_wrap_msb", "nuc_core.sv", "      assign out_d = rnd_q[OutBits-1:0];",
       "      assign out_d = {1'b0, rnd_q[OutBits-2:0]};", "wrap loses the top bit",
       changes=_WRAP),
    _m("nuc_offset_align", "nuc_core.sv", "<< (FracBits - OffsetFracBits);",
       "<< (FracBits - OffsetFracBits + 1);", "offset aligned one bit too high"),
    _m("nuc_offset_unsigned", "nuc_core.sv", "SumBits'($signed(mul_offset))",
       "SumBits'(mul_offset)", "offset zero-extended instead of sign-extended"),
    _m("nuc_round_unsigned", "nuc_core.sv",
       "rnd_q      <= RndBits'($signed(sum_s[SumBits-1:FracBits])) + RndBits'(inc);",
       "rnd_q      <= RndBits'(sum_s[SumBits-1:FracBits]) + RndBits'(inc);",
       "the shifted sum is not sign-extended"),
    # ---- dpc_ctrl ------------------------------------------------------------------------
    _m("ctrl_same_no_height", "dpc_ctrl.sv",
       "same_geo_q <= (frame_width_i == geo_w_q) && (frame_height_i == geo_h_q);",
       "same_geo_q <= (frame_width_i == geo_w_q);",
       "a new frame counts as the same size when only its height changed",
       equivalent_when=(("max_height", 1, _ONE_HIGH_SAME),)),
    _m("ctrl_same_no_width", "dpc_ctrl.sv",
       "same_geo_q <= (frame_width_i == geo_w_q) && (frame_height_i == geo_h_q);",
       "same_geo_q <= (frame_height_i == geo_h_q);",
       "a new frame counts as the same size when only its width changed",
       equivalent_when=(("max_width", 1, _ONE_WIDE_SAME),)),
    _m("ctrl_sof_unchecked", "dpc_ctrl.sv",
       "assign marker_bad = (pix_sof_i != exp_sof) || (pix_eol_i != cur_col_last);",
       "assign marker_bad = (pix_eol_i != cur_col_last);", "sof marker not checked"),
    _m("ctrl_eol_unchecked", "dpc_ctrl.sv",
       "assign marker_bad = (pix_sof_i != exp_sof) || (pix_eol_i != cur_col_last);",
       "assign marker_bad = (pix_sof_i != exp_sof);", "eol marker not checked"),
    _m("ctrl_height_unchecked", "dpc_ctrl.sv", "(idle && (fw_bad_q || fh_bad_q))",
       "(idle && fw_bad_q)", "an illegal height does not set frame_err_o"),
    _m("ctrl_width_zero_legal", "dpc_ctrl.sv",
       "fw_bad_q <= (frame_width_i == '0) || w_over;", "fw_bad_q <= w_over;",
       "width 0 counts as legal"),
    _m("ctrl_err_reset", "dpc_ctrl.sv", "      err_q <= 1'b0;\n    end else if",
       "      err_q <= 1'b1;\n    end else if", "frame_err_o set by reset"),
    _m("ctrl_col_next_last", "dpc_ctrl.sv", "(col_q == geo_wm2_q);",
       "(col_q + WidthBits'(1) == geo_wm2_q);", "end of row one column early",
       equivalent_when=(("max_width", 1, _ONE_WIDE_LAST),)),
    _m("ctrl_ahead_start", "dpc_ctrl.sv", "fw_is3_q ? WidthBits'(0) : WidthBits'(3);",
       "fw_is3_q ? WidthBits'(0) : WidthBits'(2);",
       "line-buffer look-ahead starts one column late",
       equivalent_when=(("max_width", 3, _LB_UNUSED),)),
    _m("ctrl_idle_read_col", "dpc_ctrl.sv", ": AddrBits'(2);", ": AddrBits'(1);",
       "line-buffer read address in Idle off by one",
       equivalent="the mutated branch is taken for W >= 3, where the word read in Idle is "
                  "that of item 2 of the new frame, in row 0: it holds rows -2 and -1, which "
                  "reach only window row 0 while the centre is row -1 (no output) or row 0 "
                  "(masked by the top border) and are written back only into row -1 "
                  "slots; no output code, flag or marker depends on it"),
    _m("ctrl_read_col_late", "dpc_ctrl.sv", ": AddrBits'(ahead_d);", ": AddrBits'(ahead_q);",
       "line-buffer read address register loaded with this cycle's look-ahead column, not the "
       "next one (the address one item late)",
       equivalent_when=(("max_width", 3, _LB_UNUSED),)),
    _m("ctrl_take_no_tail", "dpc_ctrl.sv",
       "assign take         = en_i && (pix_valid_i || tail || flush);",
       "assign take         = en_i && (pix_valid_i || flush);",
       "in Tail with no pixel waiting no phantom is taken: the frame's last outputs wait for "
       "the next frame"),
    _m("ctrl_flush_short", "dpc_ctrl.sv",
       "if (take_phantom && cur_col_last) ph_wrapped_q <= 1'b1;",
       "if (take_phantom) ph_wrapped_q <= 1'b1;", "the flush ends after two phantoms",
       equivalent_when=(("max_width", 1, _ONE_WIDE_LAST),)),
    _m("ctrl_tail_no_flush", "dpc_ctrl.sv",
       "assign accept       = !flush && !(tail && !same);", "assign accept       = !flush;",
       "a frame of another size is taken without flushing the previous one",
       equivalent_when=(("max_frame_pixels", 1, _ONE_PIXEL),)),
    _m("ctrl_row_last_width", "dpc_ctrl.sv", "or_last_q  <= (or_q == geo_hm2_q);",
       "or_last_q  <= (or_q == HeightBits'(geo_wm2_q));",
       "last output row found with the width",
       equivalent_when=(("max_height", 1, _ONE_HIGH_LAST),)),
    _m("ctrl_top_is_bottom", "dpc_ctrl.sv", "win_top_q    <= or_first_q;",
       "win_top_q    <= or_last_q;", "top border flag from the last row",
       equivalent_when=(("max_height", 1, _ONE_HIGH_LAST),)),
    _m("ctrl_write_current_col", "dpc_ctrl.sv", "assign lb_wr_addr_o  = prev_col_q;",
       "assign lb_wr_addr_o  = AddrBits'(col_q);",
       "line buffer written at the current column, not the previous item's",
       equivalent_when=(("max_width", 3, _LB_UNUSED),)),
    # ---- dpc_core ------------------------------------------------------------------------
    _m("dpc_rows_swapped", "dpc_core.sv", "{col_top, col_mid} = lb_next;",
       "{col_mid, col_top} = lb_next;", "line-buffer rows swapped (neighbours swapped)"),
    _m("dpc_no_right_mask", "dpc_core.sv",
       "(c == 0 && win_left) || (c == 2 && win_right));", "(c == 0 && win_left));",
       "the right border is not masked"),
    _m("dpc_w3_from_ram", "dpc_core.sv",
       "{col_top, col_mid} = {win_q[1][0], win_q[2][0]};", "{col_top, col_mid} = lb_next;",
       "W = 3 reads the stale line-buffer word"),
    _m("dpc_no_rounding", "dpc_core.sv", "half2_q <= cnt_q >> 1;",
       "half2_q <= '0;", "the mean is truncated instead of rounded half up"),
    _m("dpc_n0_corrected", "dpc_core.sv",
       "assign out_d    = (out_bad && out_nonzero) ? out_mean : out_ctr;",
       "assign out_d    = out_bad ? out_mean : out_ctr;",
       "a bad pixel without good neighbours is replaced by 0"),
    _m("dpc_recip_8_as_7", "dpc_core.sv", "4'd8:    nb_recip = RecBits'(dpc_recip(OutBits, 8));",
       "4'd8:    nb_recip = RecBits'(dpc_recip(OutBits, 7));", "n = 8 divides by 7"),
    _m("dpc_recip_early", "dpc_core.sv", "sum_recip <= rec3_q;", "sum_recip <= rec2_q;",
       "R[n] taken one stage early, beside the next item's sum"),
    # ---- irnuc_dsp_mul, the multipliers' registers (behaviour of the DSP blocks) ----------
    _m("dsp_no_input_reg", "irnuc_dsp_mul.sv", "      p_q <= 36'(64'(a_q) * 64'(b_q));",
       "      p_q <= 36'(64'(a_i) * 64'(b_i));", "the product skips the DSP's input register (one "
       "stage early against its valid and side band)"),
    _m("dsp_no_enable", "irnuc_dsp_mul.sv", "    if (en_i) begin\n      a_q <= a_i;",
       "    if (1'b1) begin\n      a_q <= a_i;", "the DSP registers move while stalled"),
    _m("mul_valid_one_stage", "irnuc_mul_parts.sv", "assign valid_o = valid_q[1];",
       "assign valid_o = valid_q[0];", "the product's valid one stage early"),
    _mm("mul_a_top_unsigned", "irnuc_mul_parts.sv",
        "      assign a_chunk = 18'($signed(a_i[ALsb +: AWide]));",
        "      assign a_chunk = 18'(a_i[ALsb +: AWide]);",
        "the top chunk of a signed A operand zero-extended (tc_poly: tc1 * u with tc1 < 0 in a "
        "16-bit chunk; pwl_core's 18-bit difference fills its chunk, where the two agree)",
        "tcoffset14"),
    _mm("mul_b_top_unsigned", "irnuc_mul_parts.sv",
        "        assign b_chunk = 18'($signed(b_i[BLsb +: BWide]));",
        "        assign b_chunk = 18'(b_i[BLsb +: BWide]);",
        "the top chunk of a signed B operand zero-extended (tc_poly: c1 * u with u < 0)",
        "tcoffset14"),
    # ---- irnuc_round, irnuc_clip (the methods' rounding and saturation) ------------------
    _mm("round_half_up_no_inc", "irnuc_round.sv", "    assign inc = s_i[FracBits-1];",
        "    assign inc = 1'b0;", "half_up rounds down (pwl_core)", "piecewise14"),
    _mm("round_half_even_no_odd", "irnuc_round.sv",
        "assign inc = s_i[FracBits-1] & (sticky | s_i[FracBits]);",
        "assign inc = s_i[FracBits-1] & sticky;", "half_even: ties of odd integers dropped",
        "quadratic14", changes=(("rounding", "half_even"),)),
    _mm("round_half_even_no_sticky", "irnuc_round.sv",
        "assign inc = s_i[FracBits-1] & (sticky | s_i[FracBits]);",
        "assign inc = s_i[FracBits-1] & s_i[FracBits];",
        "half_even: the bits below the half are ignored", "quadratic14",
        changes=(("rounding", "half_even"),)),
    _mm("round_unsigned", "irnuc_round.sv",
        "assign r_o = OutBits'($signed(s_i[InBits-1:FracBits])) + OutBits'(inc);",
        "assign r_o = OutBits'(s_i[InBits-1:FracBits]) + OutBits'(inc);",
        "the shifted sum is not sign-extended", "quadratic14"),
    _mm("clip_low_value", "irnuc_clip.sv", "        y_o = '0;\n      end else if (too_big)",
        "        y_o = OutBits'(1);\n      end else if (too_big)",
        "saturation below zero gives 1", "piecewise14"),
    _mm("clip_high_bit", "irnuc_clip.sv", "assign too_big = |v_i[InBits-2:OutBits];",
        "assign too_big = |v_i[InBits-2:OutBits+1];",
        "saturation above the range misses its lowest bit", "quadratic14"),
    _mm("clip_signed_min", "irnuc_clip.sv",
        "          y_o = OutBits'(1) << (OutBits - 1);     // the most negative code",
        "          y_o = '0;", "signed saturation below the range gives 0 (tc_poly's offset)",
        "tcoffset14"),
    _mm("clip_signed_negative_fit", "irnuc_clip.sv",
        "assign fits = (v_i[InBits-1:OutBits-1] == '0) || (v_i[InBits-1:OutBits-1] == '1);",
        "assign fits = (v_i[InBits-1:OutBits-1] == '0);",
        "every negative offset saturates (tc_poly)", "tcoffset14"),
    _mm("clip_wrap_msb", "irnuc_clip.sv", "    assign y_o = OutBits'($signed(v_i));\n    logic "
        "unused_neg;\n    assign unused_neg = neg;\n  end else if",
        "    assign y_o = OutBits'(v_i[OutBits-2:0]);\n    logic "
        "unused_neg;\n    assign unused_neg = neg;\n  end else if",
        "wrap loses the top bit", "piecewise14", changes=_WRAP),
    # ---- pwl_core --------------------------------------------------------------------------
    _mm("pwl_segments_swapped", "pwl_core.sv", "(xa <= ka) ? in_gain_lo : in_gain_hi;",
        "(xa >= ka) ? in_gain_lo : in_gain_hi;", "the two segments' gains swapped",
        "piecewise14"),
    _mm("pwl_segment_at_knee", "pwl_core.sv", "(xa <= ka) ? in_gain_lo : in_gain_hi;",
        "(xa < ka) ? in_gain_lo : in_gain_hi;", "x at the knee takes g_hi",
        "piecewise14",
        equivalent="at the knee d = 0, so d * g = 0 whichever gain is taken: the same sum, "
                   "the same output for every input"),
    _mm("pwl_level_align", "pwl_core.sv", "SumBits'(mul_level) << LShift;",
        "SumBits'(mul_level) << (LShift + 1);", "the level aligned one bit too high",
        "piecewise14"),
    _mm("pwl_level_signed", "pwl_core.sv", "SumBits'(mul_level) << LShift;",
        "SumBits'($signed(mul_level)) << LShift;",
        "the level sign-extended (levels of 2^(LW-1) and above go negative)", "piecewise14"),
    _mm("pwl_knee_align", "pwl_core.sv", "assign xa = DiffBits'(in_pix) << DBits;",
        "assign xa = DiffBits'(in_pix) << (DBits - 1);",
        "x aligned to the knee with one fraction bit too few", "piecewise14"),
    # ---- quad_core -------------------------------------------------------------------------
    _mm("quad_square_shift", "quad_core.sv", "assign sq_xq = sq_xsq[XsqBits-1:SqShift];",
        "assign sq_xq = XqBits'(sq_xsq >> (SqShift + 1));",
        "the square shifted one bit too far", "quadratic14"),
    _mm("quad_q_unsigned", "quad_core.sv",
        "    .ABits   (QuadBits),\n    .BBits   (XqBits),\n    .ASigned (1'b1),",
        "    .ABits   (QuadBits),\n    .BBits   (XqBits),\n    .ASigned (1'b0),",
        "the quadratic term read as unsigned", "quadratic14"),
    _mm("quad_qp_align", "quad_core.sv", "qp_parts[k] << (FracBits + ExtFrac - QpFrac);",
        "qp_parts[k] << (FracBits + ExtFrac - QpFrac + 1);",
        "the quadratic term aligned one bit too high", "quadratic14"),
    _mm("quad_floor_off", "quad_core.sv", "assign sum_s = sum_ext[ExtBits-1:ExtFrac];",
        "assign sum_s = SumBits'(sum_ext >> (ExtFrac - 1));",
        "one floored bit too few dropped", "quadratic14"),
    _mm("quad_offset_unsigned", "quad_core.sv", "ExtBits'($signed(mul_offset))",
        "ExtBits'(mul_offset)", "the offset zero-extended", "quadratic14"),
    # ---- tc_reading, tc_poly -------------------------------------------------------------
    _mm("tc_diff_swapped", "tc_reading.sv",
        "diff_q      <= $signed(CmpBits'(reading_i)) - $signed(CmpBits'(t_ref_i));",
        "diff_q      <= $signed(CmpBits'(t_ref_i)) - $signed(CmpBits'(reading_i));",
        "u = t_ref - t", "tcoffset14"),
    _mm("tc_clamp_value", "tc_reading.sv", "        u_q <= UBits'(Lim);",
        "        u_q <= UBits'(Lim - 1);", "the upper clamp one code low", "tcoffset14"),
    _mm("tc_no_low_clamp", "tc_reading.sv", "      end else if (diff_q < -Lim) begin",
        "      end else if (1'b0) begin", "readings far below t_ref are not clamped",
        "tcoffset14"),
    _mm("tc_u2_shift", "tc_reading.sv",
        "assign u2_o = Square ? sq_sum[2*ReadingRangeBits-1:ReadingRangeBits] : '0;",
        "assign u2_o = Square ? sq_sum[2*ReadingRangeBits-2:ReadingRangeBits-1] : '0;",
        "u2 shifted one bit too little", "tcoffset14"),
    # tc_housing's housing variable and terms (tc_reading's and tc_poly's Housing).
    _mm("th_diff_swapped", "tc_reading.sv",
        "hdiff_q <= $signed(HCmpBits'(housing_i)) - $signed(HCmpBits'(h_ref_i));",
        "hdiff_q <= $signed(HCmpBits'(h_ref_i)) - $signed(HCmpBits'(housing_i));",
        "w = h_ref - h", "tchousing14"),
    _mm("th_clamp_value", "tc_reading.sv", "          w_q <= WBits'(HLim);",
        "          w_q <= WBits'(HLim - 1);", "the housing's upper clamp one code low",
        "tchousing14"),
    _mm("th_uw_shift", "tc_reading.sv",
        "assign uw_o = uw_sum[ReadingRangeBits+HousingRangeBits:HousingRangeBits];",
        "assign uw_o = uw_sum[ReadingRangeBits+HousingRangeBits-1:HousingRangeBits-1];",
        "the cross variable u*w shifted one bit too little", "tchousing14"),
    _mm("th_w2_from_u", "tc_reading.sv", "      .a_i    (w_q),\n        .b_i    (w_q),",
        "      .a_i    (u_q),\n        .b_i    (w_q),", "w2 formed from u*w instead of w*w",
        "tchousing14"),
    _mm("th_word_at_tc", "method_tc_offset.sv",
        "assign th      = s_coef_i[TwoPointBits + TcWordBits +: ThPortBits];",
        "assign th      = s_coef_i[TwoPointBits +: ThPortBits];",
        "tc_housing's housing word read from the tc word's bits", "tchousing14"),
    _mm("th_housing_is_h_ref", "method_tc_offset.sv", "assign housing = fw.housing_reading;",
        "assign housing = fw.h_ref;", "the frame's housing reading replaced by H_REF (w = 0)",
        "tchousing14"),
    _mm("th_h1_align", "tc_poly.sv",
        "assign o_leaves[1 + P1 + P2 + k] = h1_parts[k] << H1Shift;",
        "assign o_leaves[1 + P1 + P2 + k] = h1_parts[k] << (H1Shift + 1);",
        "the housing's linear term aligned one bit too high", "tchousing14"),
    _mm("th_hx_dropped", "tc_poly.sv",
        "assign o_leaves[1 + P1 + P2 + PH1 + k] = hx_parts[k] << HxShift;",
        "assign o_leaves[1 + P1 + P2 + PH1 + k] = '0;", "the cross term v·w' dropped",
        "tchousing14"),
    _mm("th_h2_w2_signed", "tc_poly.sv",
        "      .ABits   (Th2Bits),\n      .BBits   (W2Bits),\n      .ASigned (1'b1),\n"
        "      .BSigned (1'b0),",
        "      .ABits   (Th2Bits),\n      .BBits   (W2Bits),\n      .ASigned (1'b1),\n"
        "      .BSigned (1'b1),",
        "w2 read as signed in the housing's quadratic term", "tchousing14"),
    _mm("tc_c1_align", "tc_poly.sv", "assign o_leaves[1 + k] = c1_parts[k] << O1Shift;",
        "assign o_leaves[1 + k] = c1_parts[k] << (O1Shift + 1);",
        "the linear offset term aligned one bit too high", "tcoffset14"),
    _mm("tc_c2_dropped", "tc_poly.sv",
        "assign o_leaves[1 + P1 + k] = c2_parts[k] << O2Shift;",
        "assign o_leaves[1 + P1 + k] = '0;", "the quadratic offset term dropped",
        "tcoffset14"),
    _mm("tc_offset_round_frac", "tc_poly.sv", "    .FracBits(O0Shift),",
        "    .FracBits(O0Shift - 1),", "the offset polynomial rounded one bit too few",
        "tcoffset14"),
    _mm("tc_g2_u2_signed", "tc_poly.sv",
        "        .ABits   (Tg2Bits),\n        .BBits   (U2Bits),\n        .ASigned (1'b1),\n"
        "        .BSigned (1'b0),",
        "        .ABits   (Tg2Bits),\n        .BBits   (U2Bits),\n        .ASigned (1'b1),\n"
        "        .BSigned (1'b1),",
        "u2 read as signed in the gain polynomial", "tcgain14"),
    _mm("tc_gain_clip_signed", "tc_poly.sv",
        "    .OutBits  (GainBits),\n    .OutSigned(1'b0),",
        "    .OutBits  (GainBits),\n    .OutSigned(1'b1),",
        "the gain polynomial saturated as a signed code", "tcgain14"),
    # ---- table_interp, interp_weight -----------------------------------------------------
    _mm("ti_diff_swapped", "table_interp.sv",
        "dg_q          <= DgBits'(in_gain1) - DgBits'(in_gain0);",
        "dg_q          <= DgBits'(in_gain0) - DgBits'(in_gain1);",
        "the gain difference reversed", "table14"),
    _mm("ti_offset_unsigned", "table_interp.sv",
        "DoBits'($signed(in_offset1)) - DoBits'($signed(in_offset0))",
        "DoBits'(in_offset1) - DoBits'(in_offset0)",
        "the offsets zero-extended before their difference", "table14"),
    _mm("ti_round_truncate", "table_interp.sv",
        "    .InBits  (PgBits),\n    .FracBits(WeightFracBits),\n    .Rounding(WeightRounding)",
        "    .InBits  (PgBits),\n    .FracBits(WeightFracBits),\n    .Rounding(0)",
        "the gain interpolation truncated instead of the weight's rounding", "table14"),
    _m("iw_select_strict", "interp_weight.sv", "if (table_readings_i[i] <= t_q) begin",
       "if (table_readings_i[i] < t_q) begin",
       "a reading equal to a table's reading picks the table below", **_IW),
    _m("iw_clamp_top", "interp_weight.sv", "end else if (above_q[ReadingBits-1:0] >= span_q) begin",
       "end else if (above_q[ReadingBits-1:0] > span_q) begin",
       "num = span is divided instead of taken as 1 (seen only when the weight truncates: "
       "the division leaves 2^Wf - 1 and a remainder that rounds up to 2^Wf)",
       **{**_IW, "changes": (("formats", (("weight", (("rounding", "truncate"),)),)),)}),
    _m("iw_half_even_no_odd", "interp_weight.sv",
       "(twice_rem == {2'b00, span_q} && quot_q[0]);", "(twice_rem == {2'b00, span_q});",
       "half_even weights round ties up (a tie needs a span of 2^(Wf+1) or more: 8-bit "
       "readings with Wf = 6; table14's 14-bit readings with Wf = 15 never tie)",
       **{**_IW, "changes": (("tables", 2), ("reading_bits", 8), ("formats", (
           ("weight", (("rounding", "half_even"), ("frac_bits", 6))),)))}),
    _m("iw_no_order_check", "interp_weight.sv",
       "      if (table_readings_i[i + 1] <= table_readings_i[i]) begin",
       "      if (1'b0) begin", "unordered table readings not flagged", **_IW),
    _m("iw_bit_position", "interp_weight.sv",
       "quot_fit = quot_q | (WBits'(1'b1) << (count_q - CountBits'(1)));",
       "quot_fit = quot_q | (WBits'(1'b1) << count_q);",
       "quotient bits one place too high", **_IW),
    # ---- method_dpc_top, the DPC and line buffer of the methods ------------------------
    _mm("top_frame_every_pixel", "method_dpc_top.sv",
        "assign frame = pix_sof ? pix_frame : frame_q;", "assign frame = pix_frame;",
        "every pixel's frame word is used, not the first pixel's", "onepoint14"),
    _mm("top_frame_latch_any", "method_dpc_top.sv", "end else if (join_take && pix_sof) begin",
        "end else if (join_take) begin",
        "the held frame word follows every pixel", "piecewise14"),
    # The methods' fronts (hdl/method_<name>.sv), run in method_dpc_top.
    _mm("top_tc_reading_ref_swapped", "method_tc_offset.sv",
        "    assign reading = fw.reading;\n    assign t_ref   = fw.t_ref;\n    assign housing = '0;",
        "    assign reading = fw.t_ref;\n    assign t_ref   = fw.reading;\n    assign housing = '0;",
        "the reading and t_ref swapped", "tcoffset14"),
    _mm("top_quad_field", "method_quadratic.sv", "assign m_quad_o    = w.quad.quad;",
        "assign m_quad_o    = s_coef_i[coef_word_bits(GainBits, OffsetBits) - 1 +: QuadBits];",
        "the quad word read one bit low", "quadratic14"),
    _mm("top_one_point_bad", "method_one_point.sv",
        "assign m_user_o    = {s_user_i, w.bad};",
        "assign m_user_o    = {s_user_i, s_coef_i[OffsetBits-1]};",
        "one_point's bad flag from the offset's sign", "onepoint14"),
    _mm("top_table_weight_low", "method_table_interp.sv",
        ".s_weight_i (s_frame_i[WeightFracBits:0]),",
        ".s_weight_i ({1'b0, s_frame_i[WeightFracBits-1:0]}),",
        "w = 2^Wf read as 0", "table14"),
    _mm("top_table_bad_lower_only", "method_table_interp.sv",
        ".s_user_i   ({s_user_i, w.lower.bad | w.upper.bad}),",
        ".s_user_i   ({s_user_i, w.lower.bad}),",
        "table_interp's DPC takes table j's bad flag only (a pixel bad in table j + 1 is "
        "interpolated from its coefficients and not replaced)", "table14"),
    _mm("top_two_point_bad", "method_two_point.sv",
        "assign m_user_o    = {s_user_i, w.bad};", "assign m_user_o    = {s_user_i, 1'b0};",
        "two_point's bad flag dropped (no pixel replaced)", "typical14"),
    _mm("top_pwl_gains_swapped", "method_piecewise.sv",
        "assign m_gain_o    = w.gain_lo;", "assign m_gain_o    = w.gain_hi;",
        "piecewise's gain below the knee read from the gain above it", "piecewise14"),
    # frame_coefficients (the configured method's front) and method_core (its kind's core).
    _mm("fc_front_of_other_method", "frame_coefficients.sv",
        "if (Method == MethodOnePoint) begin : gen_one_point",
        "if (Method == MethodOnePoint || Method == MethodTwoPoint) begin : gen_one_point",
        "two_point's words read by one_point's front", "typical14"),
    _mm("mc_pwl_gain_hi_from_lo", "method_core.sv", ".s_gain_hi_i (s_gain_hi_i),",
        ".s_gain_hi_i (s_gain_i),", "pwl_core's gain above the knee wired to the one below",
        "piecewise14"),
    _m("dpc_mask_no_enable", "dpc_core.sv",
       "    if (en) begin\n      mask_leaves_q <= nb_leaves;",
       "    if (1'b1) begin\n      mask_leaves_q <= nb_leaves;",
       "the DPC's neighbour mask register moves while stalled"),
    _m("lb_no_output_reg", "irnuc_line_buffer.sv", "    assign rd_data_o = out_q;",
       "    assign rd_data_o = rd_data_q;",
       "the line buffer's output register bypassed (the word one item early)"),
    # ---- the stages: blind_drift (method_drift_top), ffc (method_ffc_top) -------------------
    _ms("bd_sign_bit_positive", "blind_drift.sv", "addend = bd_neg_q;",
        "addend = ProdBits'(bd_q);", "the drift gain's sign bit weighs +2^(MW-1)", _DRIFT),
    _ms("bd_sum_not_restarted", "blind_drift.sv",
        "bsum_q <= in_last ? '0 : bsum_next[SumBits-1:0];",
        "bsum_q <= bsum_next[SumBits-1:0];",
        "the blind sum runs on across frames", _DRIFT),
    _ms("bd_ref_halved", "blind_drift.sv", "ref_q       <= blind_ref_i;",
        "ref_q       <= blind_ref_i >> 1;", "blind_ref read one bit low", _DRIFT),
    _ms("bd_last_while_busy", "blind_drift.sv",
        "assign in_ready  = !in_last || state_q == BdIdle;", "assign in_ready  = 1'b1;",
        "a frame's last item taken while the multiplier is busy", _DRIFT),
    _ms("ds_no_frac_shift", "drift_sub.sv", "(XBits'(x_i) << DriftFracBits)", "XBits'(x_i)",
        "x not aligned to delta's fraction bits", _DRIFT),
    _ms("ds_delta_zero_extended", "drift_sub.sv", "XBits'($signed(delta_i))",
        "XBits'(delta_i)", "a negative delta zero-extended", _DRIFT),
    _ms("cs_offset_unsigned", "core_sum.sv",
        "assign leaves[Parts] = SumBits'($signed(mul_offset)) << (FracBits - OffsetFracBits);",
        "assign leaves[Parts] = SumBits'(mul_offset) << (FracBits - OffsetFracBits);",
        "the linear core's offset zero-extended", _DRIFT),
    _ms("co_round_no_enable", "core_out.sv",
        "    if (en_o) begin\n      rnd_q      <= rnd_d;",
        "    if (1'b1) begin\n      rnd_q      <= rnd_d;",
        "the rounding register moves while the output stalls", _DRIFT),
    _ms("dt_delta_latched_only", "method_drift_top.sv",
        "assign delta = pix_sof ? drift : delta_q;", "assign delta = delta_q;",
        "a frame's first pixel takes the previous frame's delta", _DRIFT),
    _ms("fc_count_kept_when_open", "ffc_ctrl.sv",
        "assign count_d = !shutter_i ? '0 :", "assign count_d = !shutter_i ? count_q :",
        "an open frame does not end the shutter run", _FFC),
    _ms("fc_hold_before_open", "ffc_ctrl.sv",
        "mode_o.hold      = Hold && shutter_i && open_q;",
        "mode_o.hold      = Hold && shutter_i;",
        "shutter frames held before any open frame was output", _FFC),
    _ms("fm_no_half", "ffc_mean.sv", "num_q   <= (NumBits'(sum_q) << 1) + NumBits'(n_q);",
        "num_q   <= (NumBits'(sum_q) << 1);", "the target truncated, not rounded half up",
        _FFC),
    _ms("fm_bad_counted", "ffc_mean.sv", "end else if (valid_i && good_i) begin",
        "end else if (valid_i) begin", "bad pixels in the target's mean", _FFC),
    _ms("fm_over_missed", "ffc_mean.sv",
        "over_q  <= over_q || (CanOver && fits && count_q > CountBits'(TBits));",
        "over_q  <= over_q;", "a quotient above the target's range not clamped", _FFC),
    _ms("fm_start_in_flight", "ffc_mean.sv",
        "assign start      = request_i && !started_q && flight_zero_q && !enter_q;",
        "assign start      = request_i && !started_q && !enter_q;",
        "the division starts with mean pixels still in flight", _FFC),
    _ms("fm_flight_zero_late", "ffc_mean.sv",
        "                       || (flight_one && valid_i && !enter_q);",
        "                       || 1'b0;",
        "the in-flight count's zero flag misses the last mean pixel's arrival", _FFC),
    _ms("fm_enter_not_counted", "ffc_mean.sv",
        "flight_q      <= flight_q + FlightBits'(enter_q) - FlightBits'(valid_i);",
        "flight_q      <= flight_q - FlightBits'(valid_i);",
        "the in-flight count misses the delayed entries (enter_q): the division never starts",
        _FFC),
    # Session 33 (Fmax): the zero flag counts flight_q only, start asks !enter_q; started_q
    # clears a cycle after the frame start (taken_q).
    _ms("fm_start_ignores_enter", "ffc_mean.sv",
        "assign start      = request_i && !started_q && flight_zero_q && !enter_q;",
        "assign start      = request_i && !started_q && flight_zero_q;",
        "the division starts in the cycle after a mean pixel entered (still in flight)",
        _FFC),
    _ms("fm_started_never_cleared", "ffc_mean.sv", "taken_q       <= frame_taken_i;",
        "taken_q       <= 1'b0;",
        "the started flag is never cleared: a later refresh frame takes the old target "
        "without a new division", _FFC),
    _ms("fr_refresh_uses_old", "ffc_refresh.sv",
        "c_c_q       <= (r_refresh_q && !keep_i) ? dc_d : r_c_q;",
        "c_c_q       <= r_c_q;", "the refresh frame corrected with the old words", _FFC),
    _ms("fr_keep_ignored", "ffc_refresh.sv",
        "c_c_q       <= (r_refresh_q && !keep_i) ? dc_d : r_c_q;",
        "c_c_q       <= r_refresh_q ? dc_d : r_c_q;",
        "a refresh without a target (no good pixel in its mean frame) writes corrections "
        "towards 0 instead of keeping them", _FFC),
    _ms("fm_empty_never", "ffc_mean.sv", "none_q  <= n_q == '0;", "none_q  <= 1'b0;",
        "a mean frame without a good pixel is taken as a target of 0", _FFC),
    _ms("fr_dc_truncated", "ffc_refresh.sv", ".Rounding(FfcRounding)\n  ) u_round_dc (",
        ".Rounding(0)\n  ) u_round_dc (", "the refresh's dc truncated, not rounded", _FFC),
    _ms("fs_first_frame_adds", "ffc_sums.sv",
        "assign acc_new = s1_first_q ? AccBits'(s1_x_q) : s1_acc_q + AccBits'(s1_x_q);",
        "assign acc_new = s1_acc_q + AccBits'(s1_x_q);",
        "a run's first frame adds to a stale accumulator", _FFC),
    _ms("fs_refresh_adds_x", "ffc_sums.sv", "s1_xa_q    <= refresh_i ? '0 : x_i;",
        "s1_xa_q    <= x_i;", "the refresh pass sums acc + x, not the accumulator read",
        _FFC),
    _ms("fs_ahead_first_frame_adds", "ffc_sums.sv",
        "assign acc_new_d = first_i ? AccBits'(x_i) : acc_i + AccBits'(x_i);",
        "assign acc_new_d = acc_i + AccBits'(x_i);",
        "tc_offset + ffc: a run's first frame adds to a stale accumulator", _FFC,
        config="tcffc14"),
    _ms("ft_refresh_no_wait", "method_ffc_top.sv",
        "assign tgt_e    = pix_sof && ctrl_mode.refresh;", "assign tgt_e    = 1'b0;",
        "a refresh frame's first pixel does not wait for the target", _FFC),
    _ms("ft_fork_forgets_sent", "method_ffc_top.sv",
        "sent_q <= sent_q | (dest_valid & dest_ready);", "sent_q <= sent_q;",
        "the output fork sends an item again to a stream that took it", _FFC),
    # The fronts in method_ffc_top (frame_coefficients).
    _ms("fk_quad_dropped", "method_quadratic.sv", "assign m_quad_o    = w.quad.quad;",
        "assign m_quad_o    = '0;", "quadratic + ffc without the quadratic term", _FFC,
        config="quadffc14"),
    _ms("fk_tg_dropped", "method_tc_offset.sv",
        "assign tg = s_coef_i[TgLsb +: TgWordBits];",
        "assign tg = '0;", "tc_offset + ffc (tc_gain): the gain polynomial dropped", _FFC,
        config="tcffc14"),
    # ---- nuc_dpc_top ---------------------------------------------------------------------
    _m("top_coef_without_pixel", "nuc_dpc_top.sv",
       "assign coef_ready = nuc_in_ready && pix_valid;", "assign coef_ready = nuc_in_ready;",
       "a coefficient word is taken without its pixel"),
    _m("top_markers_swapped", "nuc_dpc_top.sv",
       ".s_sof_i       (nuc_user[2]),\n    .s_eol_i       (nuc_user[1]),",
       ".s_sof_i       (nuc_user[1]),\n    .s_eol_i       (nuc_user[2]),",
       "sof and eol swapped on the way to dpc_core"),
    # dpc_tail (the DPC and frame check of every top).
    _m("tail_size_swapped", "dpc_tail.sv",
       ".frame_width_i (frame_width_i),\n    .frame_height_i(frame_height_i),",
       ".frame_width_i (frame_height_i),\n    .frame_height_i(frame_width_i),",
       "the frame's width and height swapped on the way to dpc_core"),
    *AXIS_MUTANTS,
)


#: Stage mutants killed at their own top that are equivalent through irnuc_axis_top: the
#: wrapper's drive of the stage never makes their condition (docs/mutation.md).
_WRAPPER_EQUIVALENT = {
    "bd_last_while_busy":
        "through irnuc_axis_core every blind item is flagged last and is offered only once "
        "the previous frame's first pixel has left method_drift_top (blind_busy_q); that "
        "pixel was joined with the previous delta, which blind_drift pushed into u_out as "
        "its state returned to BdIdle, and only a last item taken in BdIdle leaves it: "
        "every item meets state BdIdle, so in_ready is 1 whenever in_valid is",
}


def _through_wrapper(stage: tuple[Mutant, ...]) -> tuple[Mutant, ...]:
    """The stage tops' mutants again through irnuc_axis_top (``<id>_axis``: method_ffc_top's
    with tb_axis_ffc, method_drift_top's with tb_axis_method, on the same configuration):
    the wrapper's suites must notice a wrong stage too, not only the stage's own suite. An
    equivalent mutant stays equivalent (the wrapper sees the stage top only at its ports),
    and those of :data:`_WRAPPER_EQUIVALENT` are equivalent through the wrapper only."""
    from dataclasses import replace

    suites = {"method_ffc_top": "irnuc.cocotb_tests.tb_axis_ffc",
              "method_drift_top": "irnuc.cocotb_tests.tb_axis_method"}
    return tuple(replace(m, id=f"{m.id}_axis", top="irnuc_axis_top", suite=suites[m.top],
                         what=f"{m.what} (through irnuc_axis_top)",
                         equivalent=m.equivalent or _WRAPPER_EQUIVALENT.get(m.id))
                 for m in stage if m.top in suites)


CATALOGUE = (*CATALOGUE, *_through_wrapper(CATALOGUE))


def catalogue(only: Sequence[str] | None = None) -> list[Mutant]:
    """The catalogue, or the mutants named in ``only`` (in that order)."""
    if not only:
        return list(CATALOGUE)
    by_id = {m.id: m for m in CATALOGUE}
    from irnuc.common.schema import nearest

    unknown = [i for i in only if i not in by_id]
    if unknown:
        raise UserError(f"--only {unknown[0]}: no such mutant{nearest(unknown[0], list(by_id))} "
                        "(irnuc mutate --list shows the catalogue)")
    twice = sorted({i for i in only if list(only).count(i) > 1})
    if twice:
        raise UserError(f"--only {twice[0]}: given more than once")
    return [by_id[i] for i in only]


__all__ = ["CATALOGUE", "PKG_FILE", "PKG_SUITE", "PKG_TOP", "SUITE_MODULE", "SUITE_TOP",
           "Mutant", "catalogue"]
