"""Mutation testing of the RTL: does the co-simulation suite notice a wrong design?

A :class:`Mutant` is one small, plausible change to one ``hdl/`` file (a constant off by
one, a dropped term in a condition, swapped neighbours, a handshake or marker change, a
reset value, flush and line-buffer addressing). :func:`run_mutants` applies each to a copy
of ``hdl/``, builds ``nuc_dpc_top`` from it and runs the mutation suite (every cocotb test
of ``cocotb_tests/tb_top.py``, one simulation) on the mutant's configuration:

* **killed**: a test failed (or an RTL assertion fired, or the build or simulation broke);
  the first failing test is the killing test;
* **survived**: every test passed;
* **equivalent**: survived, and the catalogue carries the argument why no test can tell
  the mutant from the design at the ports of ``nuc_dpc_top``;
* **invalid**: the mutant did not build (a catalogue error, not a kill; not counted).

Results are cached in the irnuc cache by the digest of the RTL sources, the mutant and
the testbench sources; :func:`cached_summary` returns the latest campaign of the current
RTL sources (the report shows it). Mutants run on the sweep's executor (worker processes,
in-process, or a Dask cluster). Mutation testing runs testbenches, so it sits above them
(the ``irnuc.verif`` layer, which imports the testbench it runs).
"""

from __future__ import annotations

import json
import shutil
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import irnuc.cocotb_tests
import irnuc.cosim
import irnuc.nuc_fixed
from irnuc.cocotb_tests import tb_top
from irnuc.common.cache import cache_dir
from irnuc.common.digest import digest, files_digest
from irnuc.common.errors import UserError
from irnuc.common.io import write_text_atomic
from irnuc.cosim.sources import HDL_DIR, SIM_HDL_DIR

#: The testbench module every mutant runs against.
SUITE_MODULE = tb_top.__name__
SUITE_TOP = "nuc_dpc_top"
#: Wall-time limit of one mutant's simulation (a mutant may hang the stream).
RUN_TIMEOUT = 300.0


@dataclass(frozen=True)
class Mutant:
    """One change to one RTL file: ``find`` (occurring exactly once) becomes ``replace``."""

    id: str
    file: str
    find: str
    replace: str
    what: str
    #: configuration: a named pipeline and mode changes (the mutated code must be elaborated)
    config: str = "minimal"
    changes: tuple[tuple[str, str], ...] = ()
    #: why no test can kill it (then "equivalent" when it survives)
    equivalent: str | None = None
    #: further (find, replace) pairs in the same file, for a change at several sites
    also: tuple[tuple[str, str], ...] = ()

    def apply(self, text: str) -> str:
        for find, replace in ((self.find, self.replace), *self.also):
            n = text.count(find)
            if n != 1:
                raise UserError(f"mutant {self.id}: the text to change occurs {n} times in "
                                f"{self.file} (expected once); update the catalogue")
            text = text.replace(find, replace)
        return text

    def pipeline(self):
        from irnuc.nuc_fixed import load_pipeline

        cfg = load_pipeline(self.config)
        return cfg.replace(**dict(self.changes)) if self.changes else cfg


def _m(id: str, file: str, find: str, replace: str, what: str, **kw: Any) -> Mutant:
    return Mutant(id, file, find, replace, what, **kw)


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
    _m("mul_side_no_enable", "irnuc_mul_parts.sv", "    if (en_i) side_q <= side_i;",
       "    side_q <= side_i;", "multiplier side band moves while stalled"),
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
       ": (frame_width_i == geo_w_q) && (frame_height_i == geo_h_q);",
       ": (frame_width_i == geo_w_q);",
       "a new frame counts as the same size when only its height changed"),
    _m("ctrl_same_no_width", "dpc_ctrl.sv",
       ": (frame_width_i == geo_w_q) && (frame_height_i == geo_h_q);",
       ": (frame_height_i == geo_h_q);",
       "a new frame counts as the same size when only its width changed"),
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
       "(col_q + WidthBits'(1) == geo_wm2_q);", "end of row one column early"),
    _m("ctrl_ahead_start", "dpc_ctrl.sv", "fw_is3_q ? WidthBits'(0) : WidthBits'(3);",
       "fw_is3_q ? WidthBits'(0) : WidthBits'(2);",
       "line-buffer look-ahead starts one column late"),
    _m("ctrl_idle_read_col", "dpc_ctrl.sv", ": AddrBits'(2))", ": AddrBits'(1))",
       "line-buffer read address in Idle off by one",
       equivalent="the mutated branch is taken for W >= 3, where the word read in Idle is "
                  "that of item 2 of the new frame, in row 0: it holds rows -2 and -1, which "
                  "reach only window row 0 while the centre is row -1 (no output) or row 0 "
                  "(masked by the top border) and are written back only into row -1 "
                  "slots; no output code, flag or marker depends on it"),
    _m("ctrl_flush_short", "dpc_ctrl.sv",
       "if (take_phantom && cur_col_last) ph_wrapped_q <= 1'b1;",
       "if (take_phantom) ph_wrapped_q <= 1'b1;", "the flush ends after two phantoms"),
    _m("ctrl_tail_no_flush", "dpc_ctrl.sv",
       "assign accept       = !flush && !(tail && !same_q);", "assign accept       = !flush;",
       "a frame of another size is taken without flushing the previous one"),
    _m("ctrl_row_last_width", "dpc_ctrl.sv", "or_last_q  <= (or_q == geo_hm2_q);",
       "or_last_q  <= (or_q == HeightBits'(geo_wm2_q));",
       "last output row found with the width"),
    _m("ctrl_top_is_bottom", "dpc_ctrl.sv", "win_top_q    <= or_first_q;",
       "win_top_q    <= or_last_q;", "top border flag from the last row"),
    _m("ctrl_write_current_col", "dpc_ctrl.sv", "assign lb_wr_addr_o  = prev_col_q;",
       "assign lb_wr_addr_o  = AddrBits'(col_q);",
       "line buffer written at the current column, not the previous item's"),
    # ---- dpc_core ------------------------------------------------------------------------
    _m("dpc_rows_swapped", "dpc_core.sv", "{col_top, col_mid} = lb_next_q;",
       "{col_mid, col_top} = lb_next_q;", "line-buffer rows swapped (neighbours swapped)"),
    _m("dpc_no_right_mask", "dpc_core.sv",
       "(c == 0 && win_left) || (c == 2 && win_right));", "(c == 0 && win_left));",
       "the right border is not masked"),
    _m("dpc_w3_from_ram", "dpc_core.sv",
       "{col_top, col_mid} = {win_q[1][0], win_q[2][0]};", "{col_top, col_mid} = lb_next_q;",
       "W = 3 reads the stale line-buffer word"),
    _m("dpc_no_rounding", "dpc_core.sv", "nb_leaves[8] = NumBits'(nb_count >> 1);",
       "nb_leaves[8] = '0;", "the mean is truncated instead of rounded half up"),
    _m("dpc_n0_corrected", "dpc_core.sv",
       "assign out_d    = (out_bad && out_nonzero) ? out_mean : out_ctr;",
       "assign out_d    = out_bad ? out_mean : out_ctr;",
       "a bad pixel without good neighbours is replaced by 0"),
    _m("dpc_recip_8_as_7", "dpc_core.sv", "4'd8:    nb_recip = RecBits'(dpc_recip(OutBits, 8));",
       "4'd8:    nb_recip = RecBits'(dpc_recip(OutBits, 7));", "n = 8 divides by 7"),
    # ---- nuc_dpc_top ---------------------------------------------------------------------
    _m("top_coef_without_pixel", "nuc_dpc_top.sv",
       "assign coef_ready = nuc_in_ready && pix_valid;", "assign coef_ready = nuc_in_ready;",
       "a coefficient word is taken without its pixel"),
    _m("top_markers_swapped", "nuc_dpc_top.sv",
       ".s_sof_i       (nuc_user[2]),\n    .s_eol_i       (nuc_user[1]),",
       ".s_sof_i       (nuc_user[1]),\n    .s_eol_i       (nuc_user[2]),",
       "sof and eol swapped on the way to dpc_core"),
)


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


def rtl_digest() -> str:
    """Digest of the current RTL sources (every ``hdl/*.sv``)."""
    return files_digest(sorted(HDL_DIR.glob("*.sv")))


def _suite_digest() -> str:
    """What a mutant's verdict depends on besides the RTL: the Python of the testbenches and
    their helpers, the golden model and the co-simulation layer (not the pytest files), and
    the simulation-only HDL."""
    dirs = [Path(pkg.__file__).resolve().parent
            for pkg in (irnuc.cocotb_tests, irnuc.cosim, irnuc.nuc_fixed)]
    files = [p for d in dirs for p in sorted(d.glob("*.py"))
             if not p.name.startswith(("test_", "conftest"))]
    return files_digest(files + sorted(SIM_HDL_DIR.glob("*.sv")))


def _mutant_key(m: Mutant) -> str:
    d = asdict(m)
    if not d["also"]:
        del d["also"]  # keys of one-site mutants as before the field existed
    return digest({"rtl": rtl_digest(), "suite": _suite_digest(), "mutant": d})


@dataclass
class MutantResult:
    id: str
    file: str
    what: str
    config: str
    status: str  # killed, survived, equivalent, invalid
    killed_by: str | None = None
    message: str = ""
    equivalent: str | None = None
    seconds: float = 0.0
    cached: bool = False


def run_mutant(m: Mutant, *, use_cache: bool = True, timeout: float = RUN_TIMEOUT) -> dict:
    """Apply, build and run one mutant; a JSON-ready :class:`MutantResult` (cached)."""
    from irnuc import cosim
    from irnuc.cosim.coverage import config_label

    key = _mutant_key(m)
    cache = cache_dir("mutate", "mutants") / f"{m.id}-{key}.json"
    if use_cache and cache.is_file():
        out = json.loads(cache.read_text())
        out["cached"] = True
        return out
    cfg = m.pipeline()
    t0 = time.perf_counter()
    work = Path(tempfile.mkdtemp(prefix=f"{m.id}.", dir=cache_dir("mutate", "work")))
    bld = None
    try:
        hdl = work / "hdl"
        shutil.copytree(HDL_DIR, hdl, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
        f = hdl / m.file
        f.write_text(m.apply(f.read_text()))
        killed_by, message, invalid = None, "", False
        try:
            bld = cosim.build(SUITE_TOP, cfg, hdl_dir=hdl)
        except cosim.RtlError as exc:
            invalid, message = True, str(exc)[:600]
            _remove_failed_builds(hdl)
        if bld is not None:
            xml = work / "results.xml"
            try:
                res = cosim.read_results(cosim.run(bld, SUITE_MODULE, results_xml=xml,
                                                   timeout=timeout))
                fired = cosim.assertion_failures(xml)
                failed = [r for r in res.values() if not r.passed]
                if failed:
                    killed_by = failed[0].name
                    message = (fired[0] if fired else failed[0].message)[:600]
            except cosim.SimulationTimeout as exc:
                killed_by, message = "timeout", str(exc)[:600]
            except cosim.RtlError as exc:
                killed_by, message = "simulation", str(exc)[:600]
        status = ("invalid" if invalid else "killed" if killed_by else
                  "equivalent" if m.equivalent else "survived")
        out = asdict(MutantResult(id=m.id, file=m.file, what=m.what, config=config_label(cfg),
                                  status=status, killed_by=killed_by, message=message,
                                  equivalent=m.equivalent,
                                  seconds=round(time.perf_counter() - t0, 2)))
    finally:
        shutil.rmtree(work, ignore_errors=True)
        if bld is not None:
            shutil.rmtree(bld.build_dir, ignore_errors=True)
    write_text_atomic(cache, json.dumps(out, indent=1))
    return out


def baseline_check(mutants: Sequence[Mutant]) -> None:
    """The design itself must pass the mutation suite on every configuration the mutants
    use (else every mutant would look killed); raises :class:`RtlError` otherwise."""
    from irnuc import cosim

    seen: set[str] = set()
    for m in mutants:
        cfg = m.pipeline()
        if cfg.digest() in seen:
            continue
        seen.add(cfg.digest())
        bld = cosim.build(SUITE_TOP, cfg)
        xml = cache_dir("mutate", "baseline") / f"{cfg.name}-{cfg.digest()[:8]}.xml"
        res = cosim.read_results(cosim.run(bld, SUITE_MODULE, results_xml=xml,
                                           timeout=RUN_TIMEOUT))
        bad = [r.name for r in res.values() if not r.passed]
        if bad or not res:
            raise cosim.RtlError(f"the unmutated design fails the mutation suite on "
                                 f"{cfg.name} ({', '.join(bad) or 'no result'}); see {xml}")


def _remove_failed_builds(hdl: Path) -> None:
    """Remove the build folders of a mutant copy that did not build (no stamp file)."""
    from irnuc.cosim.build import sim_build_dir

    for spec in sim_build_dir().glob("*/irnuc_build_spec.json"):
        try:
            if str(hdl) in spec.read_text():
                shutil.rmtree(spec.parent, ignore_errors=True)
        except OSError:
            continue


def _job(m: dict, use_cache: bool) -> dict:
    return run_mutant(Mutant(**{**m, "changes": tuple(tuple(c) for c in m["changes"]),
                                "also": tuple(tuple(c) for c in m["also"])}),
                      use_cache=use_cache)


def summarize(results: Sequence[dict], total_catalogue: int | None = None) -> dict:
    """killed / survived / equivalent counts, score and the per-mutant table."""
    killed = [r for r in results if r["status"] == "killed"]
    survived = [r for r in results if r["status"] == "survived"]
    equivalent = [r for r in results if r["status"] == "equivalent"]
    invalid = [r for r in results if r["status"] == "invalid"]
    non_eq = len(killed) + len(survived)
    return {
        "rtl_digest": rtl_digest(), "total": len(results),
        "catalogue_size": total_catalogue if total_catalogue is not None else len(CATALOGUE),
        "killed": len(killed), "survived": len(survived), "equivalent": len(equivalent),
        "invalid": [r["id"] for r in invalid],
        "score": round(len(killed) / non_eq, 4) if non_eq else 1.0,
        "survivors": [r["id"] for r in survived],
        "equivalents": {r["id"]: r["equivalent"] for r in equivalent},
        "killing_tests": {r["id"]: r["killed_by"] for r in killed},
        "mutants": list(results),
    }


def run_mutants(mutants: Sequence[Mutant] | None = None, *, workers: int = 1,
                scheduler: str | None = None, use_cache: bool = True,
                progress: Callable[[int, int], None] | None = None) -> dict:
    """Run mutants (default: the whole catalogue) on the sweep's executor; the summary.

    The summary is also cached as the latest campaign of the current RTL sources
    (:func:`cached_summary`) when the whole catalogue ran.
    """
    from irnuc.common.executor import open_executor

    mutants = list(CATALOGUE if mutants is None else mutants)
    results = []
    with open_executor(workers, scheduler) as handle:  # a bad --scheduler fails first
        baseline_check(mutants)
        futures = [handle.executor.submit(_job, asdict(m), use_cache) for m in mutants]
        for i, fut in enumerate(futures):
            results.append(fut.result())
            if progress is not None:
                progress(i + 1, len(futures))
    summary = summarize(results)
    summary["complete"] = {m.id for m in mutants} == {m.id for m in CATALOGUE}
    path = cache_dir("mutate") / f"summary-{rtl_digest()}.json"
    if summary["complete"] or not path.is_file():
        write_text_atomic(path, json.dumps(summary, indent=1))
    return summary


def cached_summary() -> dict | None:
    """The latest mutation campaign for the current RTL sources (killed, survived,
    equivalent with reasons, total, score, killing test per mutant), or None."""
    path = cache_dir("mutate") / f"summary-{rtl_digest()}.json"
    if not path.is_file():
        return None
    try:
        return json.loads(path.read_text())
    except (OSError, json.JSONDecodeError):
        return None


__all__ = ["CATALOGUE", "Mutant", "cached_summary", "catalogue", "rtl_digest", "run_mutant",
           "run_mutants", "summarize"]
