"""The formal campaign of ``irnuc formal``: proofs of the integration layer and the faults
planted to show that each property can fail (docs/formal.md).

A :class:`Proof` is a harness of ``hdl/formal/`` (the design under proof, its environment's
assumptions, the property modules) with its parameters and an engine
(:mod:`irnuc.cosim.formal`): ``pdr`` proves the properties for every reachable state,
``kind`` by k-induction, ``bmc`` up to a stated depth. Each proof is also given a cover run
(the harness's ``c_*`` covers must be reachable: a proof over an environment that can do
nothing proves nothing).

A :class:`Fault` is a change to the design (a catalogue mutant or a change of its own)
planted in a copy of ``hdl/``; its proof's harness runs with only the named property kept,
and the fault is *detected* when that property fails (a counterexample, written as a VCD).
Every property of the property modules has at least one planted fault
(:func:`unplanted_properties`).

Results are cached by content (the HDL and formal sources, the harness, parameters, engine,
depth, fault and tool versions) under ``~/.cache/irnuc/formal``; a complete campaign is kept
as the latest summary of these sources (:func:`cached_summary`, which the report shows).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape, quoteattr

from irnuc.common.cache import cache_dir, read_cached_json
from irnuc.common.digest import digest, files_digest
from irnuc.common.errors import UserError
from irnuc.common.io import write_text_atomic
from irnuc.cosim import formal as fv
from irnuc.cosim.sources import HDL_DIR, hdl_sources, register_file_parameters, top_parameters
from irnuc.verif.catalogue import catalogue

#: The frame size of the proofs that take a configuration (the register file, the top):
#: its widths and modes, at a maximum frame of 3 x 2 pixels (every counter, the drain and
#: the line logic at a size a solver goes through; the widths are the configuration's).
PROOF_SIZE = (3, 2)
#: The depth of the bounded register-semantics checks (ABC's bmc3): reset, then a write and
#: a read of the followed register with events beside them (one transaction at a time: a
#: write is answered 3 cycles after its request, 5 after its handshakes, a read 4 after, a
#: write then a read back 11 cycles from reset at the earliest); PDR finds no invariant for
#: the followed register's mirror against 32-bit counters in hours. minimal: 40 s.
REGMAP_DEPTH = 16
#: The bound of irnuc_axis_top's checks is measured, not chosen: its covers are reached
#: first (ABC's bmc3 on the cover model, up to TOP_DEPTH steps), and the assertions are
#: checked through the step of the last one, the first pixel of the second frame out
#: (``c_next_sof``: a start of frame right after a finished frame). minimal: its first
#: pixel out at step 24, the frame's last at 29, the next frame's first at 30, so 31 steps;
#: drift14 (the slowest start) its first pixel at 54.
TOP_DEPTH = 64
#: Configurations whose covers need more steps than TOP_DEPTH. drift14: at 3 x 2 its frames
#: leave 52 cycles apart at the earliest (every input valid from reset, every output
#: ready: a simulation at the proof size, whose first frame matches the cover's steps 54
#: and 59 one cycle later, puts the next frame's first pixel at step 106). A frame's blind
#: item goes to blind_drift only after the frame before's first pixel has left the core
#: (irnuc_axis_core's blind_busy_q), its drift code comes MW + 5 = 30 cycles later (25 bits
#: of DRIFT_GAIN, one a cycle) and its first pixel leaves about 20 cycles after that (the
#: DPC window at 3 pixels a line): so c_next_sof needs 107 steps, not 64.
TOP_DEPTHS: dict[str, int] = {"drift14": 112}
#: The time budgets (seconds of ABC's bmc3, its ``-T``) of one irnuc_axis_top proof: its
#: covers, then its assertions: the fourteen fit a shared 2-core machine in about an hour
#: (two at a time); where the measured bound is not reached in the budget the proof is a
#: bounded pass to the steps finished (recorded as its depth, the measured bound beside
#: it): no counterexample of that length exists.
TOP_COVER_BUDGET = 90.0
TOP_BUDGET = 300.0
#: Longer budgets for some configurations: ffc14 and table14, where the top's proofs found
#: defects, checked past their first pixel out; drift14's and tcffc14's covers, which need
#: more than 64 steps (their searches stopped by the budget, not by the cap).
TOP_BUDGETS: dict[str, float] = {}
TOP_COVER_BUDGETS: dict[str, float] = {"drift14": 300.0, "tcffc14": 300.0}
#: The register file's assertions inside irnuc_axis_top (its own checks, the top's AXI4-Lite
#: checker on s_axil and the harness's slave rules): s_axil is the register file's port,
#: and axil_regs_<config> proves these rules by PDR for any hardware-side inputs (so for
#: the top's); left out of the top's bounded check, they made it 4 times slower.
TOP_REGFILE_CHECKS = "u_regs.* u_assert_axil.* u_fv.u_axil.*"


@dataclass(frozen=True)
class Proof:
    """One proof: harness ``hdl/formal/<harness>.sv`` around ``design`` (a key of
    ``irnuc.cosim.sources.MODULE_FILES``)."""

    id: str
    harness: str
    design: str
    what: str
    engine: str = "pdr"
    #: bounded depth (bmc) or k (kind); for pdr the depth of a counterexample's replay; for
    #: bmc3 with covers the most steps the covers may take (the bound is measured from them)
    depth: int = 20
    #: depth of the cover run (0: none)
    cover: int = 20
    params: tuple[tuple[str, int], ...] = ()
    #: a pipeline configuration whose parameters the harness takes (at PROOF_SIZE)
    config: str | None = None
    #: the formal top when the harness binds its properties into the design
    top: str | None = None
    #: in the test suite (a few seconds)
    quick: bool = False
    #: the harness imports the configuration's register map (irnuc_fv_map)
    regmap: bool = False
    #: assertions left out of this proof (Yosys name patterns, space-separated; another
    #: proof has them)
    exclude: str = ""
    #: more files of hdl/ the harness instantiates (after the design's)
    files: tuple[str, ...] = ()
    #: bmc3's time budgets (seconds; 0: none) of the covers and of the assertions: a
    #: bounded search stopped by its budget passes to the steps it finished
    cover_budget: float = 0.0
    budget: float = 0.0

    @property
    def formal_top(self) -> str:
        return self.top or self.harness

    def parameters(self) -> dict[str, int]:
        if self.config is None:
            return dict(self.params)
        from irnuc.nuc_fixed import load_pipeline

        cfg = load_pipeline(self.config).replace(max_width=PROOF_SIZE[0],
                                                 max_height=PROOF_SIZE[1])
        if self.design == "irnuc_axil_regs":
            return {**register_file_parameters(cfg), **dict(self.params)}
        return {**top_parameters(self.design, cfg), **dict(self.params)}


@dataclass(frozen=True)
class Fault:
    """A fault planted in ``file`` (``find`` becomes ``replace``, exactly once; or the
    change of catalogue mutant ``mutant``) that property ``property`` of proof ``proof``
    must detect."""

    id: str
    proof: str
    property: str
    what: str
    file: str = ""
    find: str = ""
    replace: str = ""
    mutant: str | None = None
    quick: bool = False

    def change(self) -> tuple[str, list[tuple[str, str]]]:
        """(file, [(find, replace), ...])."""
        if self.mutant is not None:
            m = catalogue([self.mutant])[0]
            return m.file, [(m.find, m.replace), *m.also]
        return self.file, [(self.find, self.replace)]


def _configs() -> list[str]:
    from irnuc.nuc_fixed import pipeline_names

    return list(pipeline_names(method=None))


def _proofs() -> tuple[Proof, ...]:
    out = [
        Proof("spill_register", "fv_spill_register", "irnuc_spill_register",
              "irnuc_spill_register: AXI4-Stream rules out, every item once and in order, "
              "at most two inside", params=(("DataBits", 4),), quick=True),
        Proof("axis_buffer", "fv_axis_buffer", "irnuc_axis_buffer",
              "irnuc_axis_buffer with head bits: the same, and its head register",
              params=(("DataBits", 5), ("HeadBits", 2)), quick=True),
        Proof("axis_buffer_nohead", "fv_axis_buffer", "irnuc_axis_buffer",
              "irnuc_axis_buffer without head bits", params=(("DataBits", 5), ("HeadBits", 0))),
        Proof("axis_framer", "fv_axis_framer", "irnuc_axis_framer",
              "irnuc_axis_framer at 3 x 2: AXI4-Stream rules and video framing of the items "
              "to the core for any input video, its own checks", cover=20, quick=True,
              files=("irnuc_axis_buffer.sv",)),
        Proof("ffc_ctrl", "fv_ffc_ctrl", "ffc_ctrl",
              "ffc_ctrl, 4 frames with hold: every frame's mode as the reference's",
              params=(("FfcFrames", 4), ("Hold", 1)), cover=24, quick=True),
        Proof("ffc_ctrl_n1", "fv_ffc_ctrl", "ffc_ctrl", "ffc_ctrl, 1 frame, no hold",
              params=(("FfcFrames", 1), ("Hold", 0)), cover=24),
        Proof("ffc_ctrl_n8", "fv_ffc_ctrl", "ffc_ctrl", "ffc_ctrl, 8 frames with hold (ffc14)",
              params=(("FfcFrames", 8), ("Hold", 1)), cover=30),
    ]
    for name in _configs():
        out.append(Proof(f"axil_regs_{name}", "fv_axil_regs", "irnuc_axil_regs",
                         f"irnuc_axil_regs of {name}: AXI4-Lite slave rules, its own checks",
                         config=name, cover=12, quick=name == "minimal", regmap=True,
                         exclude="u_regs.*"))
    for name in _configs():
        out.append(Proof(f"axil_regmap_{name}", "fv_axil_regs", "irnuc_axil_regs",
                         f"irnuc_axil_regs of {name}: the register semantics of "
                         f"docs/registers.md (responses, reset values, strobes, W1C against "
                         f"an event, counters, STATUS.pending), for {REGMAP_DEPTH} cycles from "
                         f"reset", engine="bmc3", depth=REGMAP_DEPTH, cover=0, config=name,
                         regmap=True))
    for name in _configs():
        out.append(Proof(f"axis_top_{name}", "fv_axis_top", "irnuc_axis_top",
                         f"irnuc_axis_top of {name} at {PROOF_SIZE[0]} x {PROOF_SIZE[1]}: "
                         f"every stream port's rules, video framing out, the design's checks "
                         f"(s_axil's and the register file's: axil_regs_{name}), from reset "
                         f"through the first pixel of the second frame out (the covers' last "
                         f"step)",
                         engine="bmc3", depth=TOP_DEPTHS.get(name, TOP_DEPTH),
                         cover=TOP_DEPTHS.get(name, TOP_DEPTH), config=name,
                         top="irnuc_axis_top", exclude=TOP_REGFILE_CHECKS,
                         cover_budget=TOP_COVER_BUDGETS.get(name, TOP_COVER_BUDGET),
                         budget=TOP_BUDGETS.get(name, TOP_BUDGET)))
    return tuple(out)


PROOFS: tuple[Proof, ...] = _proofs()

_BLOCK = "irnuc_axil_regblock.sv"
_REGS_FILE = "irnuc_axil_regs.sv"
_REGS = "axil_regs_minimal"
_REGS_FFC = "axil_regs_ffc14"
_MAP = "axil_regmap_minimal"
_MAP_FFC = "axil_regmap_ffc14"

#: The planted faults: at least one per property (tests/test_formal.py checks it).
FAULTS: tuple[Fault, ...] = (
    # ---- AXI4-Stream rules (irnuc_fv_stream) and data integrity (irnuc_fv_order) ----------
    Fault("spill_drops_stalled", "spill_register", "u_out.a_valid_held",
          "the output register reloads whatever the ready: an item waiting is replaced",
          file="irnuc_spill_register.sv", find="assign main_load = ~main_valid_q | ready_i;",
          replace="assign main_load = 1'b1;", quick=True),
    Fault("spill_data_moves", "spill_register", "u_out.a_data_stable",
          "the output data follows the skid register while stalled",
          file="irnuc_spill_register.sv", find="  assign data_o  = main_data_q;",
          replace="  assign data_o  = skid_valid_q ? skid_data_q : main_data_q;"),
    Fault("spill_reset_valid", "spill_register", "u_out.a_reset_idle",
          "reset leaves the main register valid (catalogue)", mutant="spill_reset_valid"),
    Fault("spill_skid_order", "spill_register", "u_order.a_order",
          "the main register refills from the input, not the skid register (catalogue)",
          mutant="spill_skid_order", quick=True),
    Fault("buffer_never_full", "axis_buffer", "u_order.a_capacity",
          "the buffer takes a third item over an unread one (catalogue)",
          mutant="ax_buffer_never_full"),
    Fault("buffer_read_stuck", "axis_buffer", "u_order.a_order",
          "the buffer keeps reading the same entry after a pop (catalogue)",
          mutant="ax_buffer_read_stuck"),
    Fault("spill_ready_half_rate", "spill_register", "u_order.a_no_phantom",
          "ready only with both registers empty, the registers unchanged: an item taken "
          "while ready is low leaves twice (catalogue)", mutant="spill_ready_half_rate"),
    Fault("buffer_head_stale", "axis_buffer", "u_dut.a_head",
          "the head register keeps the older entry's markers after a pop (catalogue)",
          mutant="ax_buffer_head_stale"),
    # ---- video framing (irnuc_fv_video) on the framer's items ------------------------------
    Fault("framer_no_sof", "axis_framer", "u_video.a_sof",
          "the items to the core never carry the start of frame",
          file="irnuc_axis_framer.sv",
          find=".data_i ({frame, starting, xl_q, nuc_off, dpc_off, raw, word_in}),",
          replace=".data_i ({frame, 1'b0, xl_q, nuc_off, dpc_off, raw, word_in}),", quick=True),
    Fault("framer_zero_size", "axis_framer", "u_video.a_size",
          "a frame start takes a width of 0 as the active width",
          file="irnuc_axis_framer.sv", find="      act_w_q     <= pend_width_i;",
          replace="      act_w_q     <= '0;"),
    Fault("framer_no_drain", "axis_framer", "u_video.a_eol",
          "a new frame size starts before the previous frame has left the core (catalogue)",
          mutant="ax_start_ignores_drain"),
    Fault("framer_out_free", "axis_framer", "u_video.a_sof",
          "the decision's copy of the output register's ready misses an item (catalogue)",
          mutant="ax_out_free_ignores_fire"),
    # ---- ffc_ctrl against its reference ----------------------------------------------------
    Fault("ffc_first_without_shutter", "ffc_ctrl", "a_acc_first",
          "acc_first without the shutter flag", file="ffc_ctrl.sv",
          find="mode_o.acc_first = shutter_i && first_q;", replace="mode_o.acc_first = first_q;",
          quick=True),
    Fault("ffc_add_past_n", "ffc_ctrl", "a_acc_add",
          "the run keeps accumulating past N frames", file="ffc_ctrl.sv",
          find="add_q     <= count_d != '0 && count_d < CountBits'(FfcFrames);",
          replace="add_q     <= count_d != '0;"),
    Fault("ffc_mean_late", "ffc_ctrl", "a_mean", "the mean pass a frame late",
          file="ffc_ctrl.sv", find="last_q    <= count_d == CountBits'(FfcFrames - 1);",
          replace="last_q    <= count_d == CountBits'(FfcFrames);"),
    Fault("ffc_refresh_sticks", "ffc_ctrl", "a_refresh",
          "the refresh pass repeats in every frame after the first", file="ffc_ctrl.sv",
          find="pending_q <= mode_o.mean;", replace="pending_q <= mode_o.mean || pending_q;"),
    Fault("ffc_refresh_no_read", "ffc_ctrl", "a_acc_rd",
          "the refresh frame does not read the accumulator", file="ffc_ctrl.sv",
          find="mode_o.acc_rd    = mode_o.acc_add || pending_q;",
          replace="mode_o.acc_rd    = mode_o.acc_add;"),
    Fault("ffc_hold_forgets", "ffc_ctrl", "a_hold",
          "hold forgets the open frame after a shutter frame", file="ffc_ctrl.sv",
          find="open_q    <= open_q || !shutter_i;", replace="open_q    <= !shutter_i;"),
    # ---- AXI4-Lite slave rules (irnuc_fv_axil) on the register file: its CPU interface is
    #      the generated irnuc_axil_regblock.sv's (the template cosim/templates/
    #      regblock_axi4lite.sv), the faults planted in that file -----------------------------
    Fault("regs_b_at_reset", _REGS, "u_axil.a_reset_idle",
          "BVALID high out of reset", file=_BLOCK,
          find="            axil_bvalid    <= '0;", replace="            axil_bvalid    <= '1;",
          quick=True),
    Fault("regs_b_drops", _REGS, "u_axil.a_b_held",
          "BVALID drops without BREADY", file=_BLOCK,
          find="end else if(s_axil_bready) begin\n                axil_bvalid <= '0;",
          replace="end else if(1'b1) begin\n                axil_bvalid <= '0;"),
    Fault("regs_second_write", _REGS, "u_axil.a_b_stable",
          "the next request issued while a response waits: a second write's answer replaces "
          "the first's BRESP", file=_BLOCK,
          find="                axil_busy      <= '1;", replace="                axil_busy      <= '0;"),
    Fault("regs_r_drops", _REGS, "u_axil.a_r_held",
          "RVALID drops without RREADY", file=_BLOCK,
          find="end else if(s_axil_rready) begin\n                axil_rvalid <= '0;",
          replace="end else if(1'b1) begin\n                axil_rvalid <= '0;"),
    Fault("regs_rdata_live", _REGS, "u_axil.a_r_stable",
          "RDATA follows the read-back while RVALID waits for RREADY (an escaped class; "
          "catalogue)", mutant="ax_rdata_live", quick=True),
    Fault("regs_b_without_data", _REGS, "u_axil.a_b_request",
          "a write issued with its address only: answered before its data was taken",
          file=_BLOCK,
          find="assign axil_issue_wr = !axil_busy && axil_aw_held && axil_w_held && "
               "!axil_issue_rd;",
          replace="assign axil_issue_wr = !axil_busy && axil_aw_held && !axil_issue_rd;"),
    Fault("regs_bresp_exokay", _REGS, "u_axil.a_bresp_legal",
          "a refused write answered EXOKAY", file=_BLOCK,
          find="assign s_axil_bresp   = axil_berr ? 2'b10 : 2'b00;",
          replace="assign s_axil_bresp   = axil_berr ? 2'b01 : 2'b00;"),
    Fault("regs_rresp_exokay", _REGS, "u_axil.a_rresp_legal",
          "a refused read answered EXOKAY", file=_BLOCK,
          find="assign s_axil_rresp   = axil_rerr ? 2'b10 : 2'b00;",
          replace="assign s_axil_rresp   = axil_rerr ? 2'b01 : 2'b00;"),
    Fault("regs_r_without_ar", _REGS, "u_axil.a_r_request",
          "the read address register fills without ARVALID: a read answered with no request",
          file=_BLOCK,
          find="assign axil_ar_held_d = axil_ar_held ? !axil_take_rd : s_axil_arvalid;",
          replace="assign axil_ar_held_d = axil_ar_held ? !axil_take_rd : 1'b1;"),
    Fault("regs_awready_always", _REGS, "u_axil.a_open",
          "AWREADY always high: write addresses taken while one is held are lost (never "
          "answered)", file=_BLOCK,
          find="axil_aw_ready <= !axil_aw_held_d;", replace="axil_aw_ready <= 1'b1;"),
    Fault("regs_ffc_awready_always", _REGS_FFC, "u_axil.a_open",
          "the same on the FFC register file", file=_BLOCK,
          find="axil_aw_ready <= !axil_aw_held_d;", replace="axil_aw_ready <= 1'b1;"),
    Fault("regs_two_at_once", _REGS, "a_one_transaction",
          "a write issued while a read is in progress (two transactions at once)",
          file=_BLOCK,
          find="assign axil_issue_wr = !axil_busy && axil_aw_held && axil_w_held && "
               "!axil_issue_rd;",
          replace="assign axil_issue_wr = axil_aw_held && axil_w_held && !axil_issue_rd;"),
    # ---- register semantics (irnuc_fv_regs): the classes the suite let escape, the response
    #      rules of the generated block (docs/regmap.md) -----------------------------------------
    Fault("regs_ro_write_okay", _MAP, "u_regs.a_bresp",
          "a write to a read-only register (VERSION) answered OKAY (an escaped class)",
          file=_BLOCK,
          find="is_valid_rw |= (ahead_wr_addr == 12'h4) & !1'b1;",
          replace="is_valid_rw |= (ahead_wr_addr == 12'h4);", quick=True),
    Fault("regs_reserved_ro_okay", _MAP, "u_regs.a_bresp",
          "a write to FFC_STATUS, reserved and read-only on minimal, answered OKAY (catalogue)",
          mutant="ax_ffc_status_ro_okay"),
    Fault("regs_ffc_status_ro_okay", _MAP_FFC, "u_regs.a_bresp",
          "FFC_STATUS (read-only) written OKAY on an FFC configuration (catalogue)",
          mutant="ax_ffc_status_ro_okay"),
    Fault("regs_size_no_slverr", _MAP, "u_regs.a_bresp",
          "an illegal FRAME_SIZE write answered OKAY (catalogue)", mutant="ax_size_no_slverr"),
    Fault("regs_unmapped_read_okay", _MAP, "u_regs.a_rresp",
          "every read answered OKAY (outside the map too)", file=_BLOCK,
          find="axil_rerr   <= cpuif_rd_err;", replace="axil_rerr   <= 1'b0;"),
    Fault("regs_command_read_okay", _MAP, "u_regs.a_rresp",
          "a read of COMMAND (write only) answered OKAY", file=_BLOCK,
          find="is_valid_rw |= (ahead_rd_addr == 12'h28) & 1'b0;",
          replace="is_valid_rw |= (ahead_rd_addr == 12'h28);"),
    Fault("regs_refused_read_data", _MAP, "u_regs.a_rdata_refused",
          "a read answered SLVERR returns 1, not 0", file=_BLOCK,
          find="if(cpuif_rd_ack) axil_rdata <= cpuif_rd_data;",
          replace="if(cpuif_rd_ack) axil_rdata <= cpuif_rd_data | 32'(cpuif_rd_err);"),
    Fault("regs_ctrl_reset", _MAP, "u_regs.a_reset_value",
          "CTRL.nuc_en resets to 0, not 1 (a reset value: an escaped class)", file=_BLOCK,
          find="field_storage.CTRL.nuc_en.value <= 1'h1;",
          replace="field_storage.CTRL.nuc_en.value <= 1'h0;"),
    Fault("regs_frame_max", _MAP, "u_regs.a_const",
          "FRAME_MAX reads a width one short", file=_REGS_FILE,
          find="assign hwif_in.FRAME_MAX.width.next        = RegFrameMaxWidthBits'(MaxWidth);",
          replace="assign hwif_in.FRAME_MAX.width.next        = "
                  "RegFrameMaxWidthBits'(MaxWidth - 1);"),
    Fault("regs_ctrl_strobes", _MAP, "u_regs.a_rw",
          "CTRL.nuc_en ignores the byte strobes (an unwritten lane's field is written: an "
          "escaped class)", file=_BLOCK,
          find="next_c = (field_storage.CTRL.nuc_en.value & ~decoded_wr_biten[0:0]) | "
               "(decoded_wr_data[0:0] & decoded_wr_biten[0:0]);",
          replace="next_c = decoded_wr_data[0:0];", quick=True),
    Fault("regs_ffc_frames_strobes", _MAP_FFC, "u_regs.a_rw",
          "FFC_CTRL.frames ignores the byte strobes (catalogue)",
          mutant="ax_ffc_frames_strobes"),
    Fault("regs_w1c_clear_wins", _MAP, "u_regs.a_w1c",
          "a W1C clear wins over an event in the same cycle (an escaped class)", file=_BLOCK,
          find="if(hwif_in.STATUS.sof_early.hwset) begin // HW Set",
          replace="if(hwif_in.STATUS.sof_early.hwset && !(decoded_reg_strb.STATUS && "
                  "decoded_req_is_wr && decoded_wr_data[0] && decoded_wr_biten[0])) begin",
          quick=True),
    Fault("regs_counts_idle", _MAP, "u_regs.a_count",
          "the traffic counters count every cycle (catalogue)", mutant="ax_traffic_counts_idle"),
    Fault("regs_pending_sticks", _MAP, "u_regs.a_pending",
          "STATUS.pending stays 1 after the frame start that took the write (catalogue)",
          mutant="ax_pending_sticks"),
)


def _by_id(items: Sequence[Any], ids: Sequence[str], what: str) -> list[Any]:
    from irnuc.common.schema import nearest

    known = {x.id: x for x in items}
    out = []
    for i in ids:
        if i not in known:
            raise UserError(f"--only {i}: no such {what}{nearest(i, list(known))} "
                            f"(irnuc formal --list)")
        out.append(known[i])
    return out


def select(only: Sequence[str] = (), *, quick: bool = False, faults: bool = True,
           configs: Sequence[str] | None = None) -> tuple[list[Proof], list[Fault]]:
    """The proofs and faults of a campaign: ``only`` (ids of either), else all (``quick``:
    those of the test suite; ``configs``: the configuration proofs of these only);
    ``faults=False`` leaves the faults out."""
    if only:
        ids = set(only)
        bad = ids - {p.id for p in PROOFS} - {f.id for f in FAULTS}
        if bad:
            _by_id([*PROOFS, *FAULTS], sorted(bad), "proof or planted fault")
        proofs = [p for p in PROOFS if p.id in ids]
        return proofs, [f for f in FAULTS if f.id in ids] if faults else []
    proofs = [p for p in PROOFS if (p.quick or not quick)
              and (configs is None or p.config is None or p.config in configs)]
    chosen = [f for f in FAULTS if f.quick or not quick] if faults else []
    return proofs, chosen


# ---- properties and their faults ----------------------------------------------------------

_ASSERT = re.compile(r"^\s*(a_\w+):\s*assert\b", re.M)


def properties() -> dict[str, list[str]]:
    """The properties of each property module and harness (``hdl/formal``): file stem ->
    the labels of its assertions."""
    out = {}
    for p in sorted(fv.FORMAL_DIR.glob("*.sv")):
        labels = _ASSERT.findall(p.read_text())
        if labels:
            out[p.stem] = sorted(set(labels))
    return out


def unplanted_properties() -> list[str]:
    """``<file>.<label>`` of every property that no planted fault is expected to fail
    (a property that never fails checks nothing: empty when the catalogue is complete)."""
    planted = {f.property.rsplit(".", 1)[-1] for f in FAULTS}
    return [f"{stem}.{label}" for stem, labels in properties().items() for label in labels
            if label not in planted]


# ---- running ----------------------------------------------------------------------------------

def formal_digest() -> str:
    """Digest of the RTL and the formal sources (``hdl/*.sv``, ``hdl/formal/*.sv``)."""
    return files_digest(sorted(HDL_DIR.glob("*.sv")) + sorted(fv.FORMAL_DIR.glob("*.sv")))


def _key(proof: Proof, fault: Fault | None, params: dict[str, int], srcs: list[Path]) -> str:
    d = asdict(proof)
    for k in ("cover_budget", "budget"):
        if not d[k]:
            del d[k]  # the keys of the proofs without budgets as before the fields existed
    return digest({"sources": files_digest(srcs), "proof": d, "params": params,
                   "fault": asdict(fault) if fault else None,
                   "change": fault.change() if fault else None, "tools": fv.tool_versions()})


def _keep_only(label: str) -> str:
    """The Yosys command that deletes every assertion but ``label`` (its instance path and
    name, e.g. ``u_order.a_order``; the generate and process scopes between are matched)."""
    glob = ".*".join(label.split("."))
    return f"delete t:$check r:FLAVOR=assert %i n:{glob} n:*.{glob} %u %d"


def _drop(patterns: str) -> str:
    """The Yosys command that deletes the assertions whose name matches one of
    ``patterns`` (space-separated)."""
    names = patterns.split()
    sel = " ".join(f"n:{p}" for p in names) + " %u" * (len(names) - 1)
    return f"delete t:$check r:FLAVOR=assert %i {sel} %i"


def _prepare(proof: Proof, fault: Fault | None, work: Path, *, links: bool = False
             ) -> tuple[dict[str, int], list[Path], Path]:
    """The parameters, the model's sources (the fault planted in a copy of hdl/ under
    ``work``, the generated map there) and the result's cache file of a proof or fault
    (``links``: the copy's unchanged files are links, enough for the key)."""
    params = proof.parameters()
    hdl = None
    if fault is not None:
        hdl = work / "hdl"
        shutil.copytree(HDL_DIR, hdl, ignore=shutil.ignore_patterns("*.py", "__pycache__"),
                        copy_function=os.symlink if links else shutil.copy2)
        file, changes = fault.change()
        text = (hdl / file).read_text()
        for find, replace in changes:
            n = text.count(find)
            if n != 1:
                raise UserError(f"planted fault {fault.id}: the text to change occurs {n} "
                                f"times in {file} (expected once); update "
                                f"irnuc/verif/formal.py")
            text = text.replace(find, replace)
        (hdl / file).unlink()  # a link's target is the RTL itself: never written through
        (hdl / file).write_text(text)
    generated = []
    if proof.regmap:
        from irnuc.nuc_fixed import load_pipeline
        from irnuc.verif.formal_regmap import package

        cfg = load_pipeline(proof.config).replace(max_width=PROOF_SIZE[0],
                                                  max_height=PROOF_SIZE[1])
        generated.append(work / "irnuc_fv_map.sv")
        generated[0].write_text(package(cfg))
    design = [*hdl_sources(proof.design, hdl),
              *((hdl or HDL_DIR) / f for f in proof.files)]
    srcs = fv.formal_sources(design, proof.harness,
                             (hdl / "formal") if hdl else None, generated)
    key = _key(proof, fault, params, srcs)
    name = (fault or proof).id
    return params, srcs, cache_dir("formal", "results") / f"{name}-{key}.json"


def run_proof(proof: Proof, fault: Fault | None = None, *, use_cache: bool = True) -> dict:
    """Run one proof (with ``fault`` planted: its property only, bounded); a JSON-ready
    result, cached by content. A fault's result has ``detected``."""
    work = Path(tempfile.mkdtemp(prefix=f"{(fault or proof).id}.", dir=cache_dir("formal",
                                                                                  "work")))
    try:
        params, srcs, cache = _prepare(proof, fault, work)
        name = (fault or proof).id
        key = cache.stem.removeprefix(f"{name}-")
        if use_cache and cache.is_file():
            out = json.loads(cache.read_text())
            out["cached"] = True
            return out
        t0 = time.perf_counter()
        engine = "bmc" if fault is not None else proof.engine
        extra = ([_keep_only(fault.property)] if fault is not None else
                 [_drop(proof.exclude)] if proof.exclude else [])
        cover, depth = None, proof.depth
        if measured_bound(proof) and fault is not None:
            engine = "bmc3"  # to TOP_DEPTH: it stops at the first failure
        elif measured_bound(proof):
            # The covers first, by bmc3 on the cover model: the bound is the step of the
            # last one.
            cmodels = fv.write_models(srcs, proof.formal_top, params, work / "cover",
                                      covers=True)
            cover = fv.bmc3_covers(cmodels["aig"], proof.cover, work / "cover",
                                   budget=proof.cover_budget or None)
            if cover.status == "covered":
                depth = max(cover.covers.values()) + 1
        models = fv.write_models(srcs, proof.formal_top, params, work / "model",
                                 aiger=engine in ("pdr", "bmc3"), extra=extra)
        res = fv.check(models, engine, depth, work / "model",
                       budget=(proof.budget or None) if fault is None else None)
        checks = _check_labels(models["smt2"])
        if fault is None and proof.cover and cover is None:
            cover = fv.check(models, "cover", proof.cover, work / "cover")
        out = {"id": name, "proof": proof.id, "harness": proof.harness, "top": proof.formal_top,
               "config": proof.config, "params": params, "engine": engine,
               "depth": None if engine == "pdr" else res.depth if res.wanted else depth,
               "wanted": res.wanted,
               "status": res.status, "failed": res.failed, "step": res.step,
               "message": res.message, "seconds": round(time.perf_counter() - t0, 2),
               "solver_seconds": res.seconds, "asserts": len(checks["assert"]),
               "assumes": len(checks["assume"]), "cached": False, "vcd": None}
        if cover is not None:
            out["cover"] = {"status": cover.status, "depth": cover.depth or proof.cover,
                            "wanted": cover.wanted, "steps": cover.covers,
                            "total": len(checks["cover"])}
        if fault is not None:
            out |= {"property": fault.property, "what": fault.what, "mutant": fault.mutant,
                    "detected": res.status == "failed" and _matches(fault.property, res.failed)}
        else:
            out["what"] = proof.what
            # A cover search its budget stopped is no failure when it reached a cover
            # (the environment is live); the unreached ones are named in its message.
            out["ok"] = res.ok and (cover is None or cover.ok
                                    or (cover.wanted is not None and bool(cover.covers)))
            if cover is not None and not cover.ok:
                out["message"] = "; ".join(x for x in (res.message, cover.message) if x)
        vcd = res.vcd if res.status == "failed" else None
        if vcd and Path(vcd).is_file():
            dest = cache_dir("formal", "traces") / f"{name}-{key}.vcd"
            shutil.copyfile(vcd, dest)
            out["vcd"] = str(dest)
        write_text_atomic(cache, json.dumps(out, indent=1))
        return out
    finally:
        shutil.rmtree(work, ignore_errors=True)


def measured_bound(proof: Proof) -> bool:
    """A bmc3 proof with covers (its harness's cover model, fv.COVER_DEFINE): its bound is
    measured from the covers' steps (:data:`TOP_DEPTH`)."""
    return proof.engine == "bmc3" and proof.cover > 0


def _matches(label: str, failed: Sequence[str]) -> bool:
    want = label.split(".")
    for f in failed:
        got = f.split(".")
        if got[-1] == want[-1] and [p for p in got[:-1] if p in want[:-1]] == want[:-1]:
            return True
    return False


def _check_labels(smt2: Path) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {"assert": [], "assume": [], "cover": []}
    for line in Path(smt2).read_text(errors="replace").splitlines():
        m = re.match(r"; yosys-smt2-(assert|assume|cover) \d+ (\S+)", line)
        if m:
            out[m.group(1)].append(m.group(2))
    return out


def _job(kind: str, proof: dict, fault: dict | None, use_cache: bool) -> dict:
    p = Proof(**{**proof, "params": tuple(tuple(x) for x in proof["params"]),
                 "files": tuple(proof["files"])})
    return run_proof(p, Fault(**fault) if fault else None, use_cache=use_cache)


def run_campaign(proofs: Sequence[Proof], faults: Sequence[Fault] = (), *, workers: int = 1,
                 scheduler: str | None = None, use_cache: bool = True,
                 progress: Callable[[int, int], None] | None = None) -> dict:
    """Run the proofs and planted faults (on the sweep's executor); the summary, also
    cached as the latest campaign when every proof and fault ran (:func:`cached_summary`)."""
    from irnuc.common.executor import open_executor

    by_id = {p.id: p for p in PROOFS}
    jobs = [("proof", asdict(p), None) for p in proofs]
    jobs += [("fault", asdict(by_id[f.proof]), asdict(f)) for f in faults]
    results = []
    with open_executor(workers, scheduler) as handle:
        futures = [handle.executor.submit(_job, *j, use_cache) for j in jobs]
        for i, fut in enumerate(futures):
            results.append(fut.result())
            if progress is not None:
                progress(i + 1, len(futures))
    summary = summarize(results[:len(proofs)], results[len(proofs):])
    summary["complete"] = ({p.id for p in proofs} == {p.id for p in PROOFS}
                           and {f.id for f in faults} == {f.id for f in FAULTS})
    path = cache_dir("formal") / f"summary-{formal_digest()}.json"
    if summary["complete"] or not path.is_file():
        write_text_atomic(path, json.dumps(summary, indent=1))
    return summary


def summarize(proofs: Sequence[dict], faults: Sequence[dict]) -> dict:
    """Counts (proved, bounded passes, failed, unknown; faults detected / missed) and the
    results."""
    proved = [r for r in proofs if r["status"] == "proved"]
    bounded = [r for r in proofs if r["status"] == "passed"]
    bad = [r["id"] for r in proofs if not r.get("ok")]
    missed = [r["id"] for r in faults if not r.get("detected")]
    return {"digest": formal_digest(), "proofs": list(proofs), "faults": list(faults),
            "proved": len(proved), "bounded": len(bounded), "not_ok": bad,
            "detected": len(faults) - len(missed), "missed": missed,
            "unplanted": unplanted_properties(),
            "ok": not bad and not missed,
            "seconds": round(sum(r.get("seconds", 0) for r in [*proofs, *faults]), 2)}


def cached_summary() -> dict | None:
    """The latest formal campaign of the current sources, or None."""
    return read_cached_json(cache_dir("formal") / f"summary-{formal_digest()}.json")


def current_results(proofs: Sequence[Proof] = PROOFS, faults: Sequence[Fault] = FAULTS
                    ) -> dict:
    """The campaign as the cache holds it for the current sources, nothing run: every
    proof's and planted fault's result on exactly these sources (however many ``irnuc
    formal`` runs produced them), and the ones without a result, ``missing`` (status
    ``not run``: never counted as holding). The summary of :func:`summarize` with
    ``missing`` and ``complete``."""
    by_id = {p.id: p for p in PROOFS}
    found: list[dict] = []
    missing: list[str] = []
    with tempfile.TemporaryDirectory(prefix="collect.", dir=cache_dir("formal", "work")) as tmp:
        for k, (proof, fault) in enumerate([*((p, None) for p in proofs),
                                            *((by_id[f.proof], f) for f in faults)]):
            work = Path(tmp) / str(k)
            work.mkdir()
            _, _, cache = _prepare(proof, fault, work, links=True)
            res = read_cached_json(cache) if cache.is_file() else None
            if isinstance(res, dict):
                found.append(res)
                continue
            item = fault or proof
            missing.append(item.id)
            found.append({"id": item.id, "proof": proof.id, "config": proof.config,
                          "engine": proof.engine if fault is None else "bmc",
                          "depth": None, "status": "not run", "ok": False,
                          "detected": False, "seconds": 0.0, "message": "no result on "
                          "these sources (irnuc formal --only " + item.id + ")",
                          "what": item.what, "property": getattr(item, "property", None)})
            shutil.rmtree(work, ignore_errors=True)
    summary = summarize(found[:len(proofs)], found[len(proofs):])
    summary |= {"missing": missing, "complete": not missing}
    summary["missed"] = [x for x in summary["missed"] if x not in missing]
    summary["not_ok"] = [x for x in summary["not_ok"] if x not in missing]
    summary["ok"] = summary["ok"] and not missing
    return summary


def junit(summary: dict) -> str:
    """The campaign as JUnit XML: one test case per proof and per planted fault (a fault
    that is not detected fails)."""
    cases = []
    for r in summary["proofs"]:
        cases.append(_case("formal.proof", r, r.get("ok", False),
                           f"{r['status']}: {r['message']}" + (
                               f"; cover {r['cover']['status']}" if r.get("cover") else "")))
    for r in summary["faults"]:
        cases.append(_case("formal.fault", r, r.get("detected", False),
                           f"{r['property']} did not fail ({r['status']}: {r['message']})"))
    n_fail = sum("<failure" in c for c in cases)
    return ("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<testsuites>\n"
            f"<testsuite name=\"irnuc formal\" tests=\"{len(cases)}\" failures=\"{n_fail}\" "
            f"errors=\"0\" time=\"{summary['seconds']}\">\n" + "".join(cases)
            + "</testsuite>\n</testsuites>\n")


def _case(cls: str, r: dict, ok: bool, message: str) -> str:
    head = (f"  <testcase classname={quoteattr(cls)} name={quoteattr(r['id'])} "
            f"time=\"{r.get('seconds', 0)}\"")
    if ok:
        return head + "/>\n"
    trace = f" (trace {r['vcd']})" if r.get("vcd") else ""
    return (head + ">\n    <failure message=" + quoteattr(message[:500]) + ">"
            + escape(message + trace) + "</failure>\n  </testcase>\n")


__all__ = [
    "FAULTS",
    "PROOFS",
    "PROOF_SIZE",
    "REGMAP_DEPTH",
    "TOP_BUDGET",
    "TOP_COVER_BUDGET",
    "TOP_DEPTH",
    "TOP_DEPTHS",
    "TOP_REGFILE_CHECKS",
    "Fault",
    "Proof",
    "cached_summary",
    "current_results",
    "formal_digest",
    "junit",
    "measured_bound",
    "properties",
    "run_campaign",
    "run_proof",
    "select",
    "summarize",
    "unplanted_properties",
]
