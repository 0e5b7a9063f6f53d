"""Which flip-flops of a top have no reset: a structural check on the Yosys netlist.

The RTL's one reset style is the asynchronous active-low ``rst_ni`` (docs/rtl.md). After
Yosys elaborates a top (pyosys, slang front end, ``SYNTHESIS`` defined), ``proc`` turns
every clocked process into flip-flop cells: a register written under the asynchronous
reset becomes an ``$adff`` / ``$adffe``, one without it a ``$dff`` / ``$dffe``. Memories
stay memories (``$mem_v2``: the line buffers, not flops). :func:`flops_without_reset`
lists the flattened names of the registers of the second kind; :func:`check` compares
them with an allow-list of patterns, each with the reason the register needs no reset
(:data:`ALLOWED`, docs/verification.md, "Registers without reset"):

* a pattern that matches no register is stale (the RTL changed): reported;
* a register that matches no pattern is a finding: a control register left out of the
  reset survives a reset with its old value.

Names are flattened hierarchical names with array indices and bit ranges dropped
(``u_tail.u_dpc.u_ctrl.gen_x[1].q`` -> ``u_tail.u_dpc.u_ctrl.gen_x.q``); patterns are
:func:`fnmatch.fnmatchcase` globs.
"""

from __future__ import annotations

import fnmatch
import json
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from irnuc.cosim import synth
from irnuc.cosim.sources import hdl_sources, top_parameters
from irnuc.nuc_fixed import PipelineConfig

#: Flip-flop cells without a reset (after ``proc``; no ``opt_dff``, so no synchronous
#: reset is inferred from logic: the RTL has none).
NO_RESET_CELLS = ("$dff", "$dffe", "$sdff", "$sdffe", "$sdffce")
#: Flip-flop cells with the asynchronous reset (the slang front end writes a register
#: reset by ``rst_ni`` as an asynchronous load of its reset value, ``$aldff``).
RESET_CELLS = ("$adff", "$adffe", "$aldff", "$aldffe", "$dffsr", "$dffsre")
#: Memory write ports: an unpacked array written without reset (a reset array would be
#: flip-flops) is a memory; listed as a register without reset by its name.
MEMORY_WRITE_CELLS = ("$memwr", "$memwr_v2", "$mem", "$mem_v2")

_DATA = ("data-path register: its valid bit (or the FSM that reads it) resets; the value "
         "is only used after new data was loaded")

_SPILL = "spill-register data: main_valid_q / skid_valid_q reset, data is read only when valid"
_DSP = ("DSP operand and product registers (MULT18X18D's own registers have no reset); "
        "irnuc_mul_parts' valid_q resets")
_TREE = "adder-tree node and side band of a level whose valid_q resets"
_LB = ("line buffer: block RAM and its read registers have no reset; rows of another frame "
       "are masked by the window's position flags, which reset")

#: Registers of each top allowed without reset: glob pattern -> reason (docs/verification.md,
#: "Registers without reset").
ALLOWED: dict[str, dict[str, str]] = {
    "nuc_dpc_top": {
        "*.main_data_q": _SPILL,
        "*.skid_data_q": _SPILL,
        "*.u_mul.gen_a.gen_b.u_dsp.a_q": _DSP,
        "*.u_mul.gen_a.gen_b.u_dsp.b_q": _DSP,
        "*.u_mul.gen_a.gen_b.u_dsp.p_q": _DSP,
        "*.u_mul.side_q": "multiplier side band; irnuc_mul_parts' valid_q resets",
        "*.gen_tree.gen_level.node_q": _TREE,
        "*.gen_tree.gen_level.side_q": _TREE,
        "u_nuc.rnd_q": "rounded NUC value; rnd_valid_q resets",
        "u_nuc.rnd_user_q": "frame markers of the rounded value; rnd_valid_q resets",
        "u_tail.u_dpc.mask_ctr_q": "DPC mask stage data; mask_valid_q resets",
        "u_tail.u_dpc.mask_leaves_q": "DPC mask stage data; mask_valid_q resets",
        "u_tail.u_dpc.mask_good_q": "DPC mask stage data; mask_valid_q resets",
        **{f"u_tail.u_dpc.{r}": ("DPC count n, floor(n/2), n != 0 and R[n] beside the neighbour "
                          "sum's levels, whose valid_q reset")
           for r in ("cnt_q", "half2_q", "half3_q", "nz2_q", "nz3_q", "rec2_q", "rec3_q")},
        **{f"u_tail.u_dpc.{r}": "DPC sum stage data (M, R[n], side band); sum_valid resets"
           for r in ("sum_m", "sum_recip", "sum_ctr")},
        "u_tail.u_dpc.win_q": ("3 x 3 window pixels: the window's valid and position flags reset "
                        "and mask every value not of the current frame"),
        "u_tail.u_dpc.u_lb.gen_inferred.mem_q": _LB,
        "u_tail.u_dpc.u_lb.gen_inferred.out_q": _LB,
        "u_tail.u_dpc.u_lb.gen_inferred.rd_data_q": _LB,
    },
}


@dataclass(frozen=True)
class ResetReport:
    """Registers without reset of one top and configuration, against the allow-list."""

    top: str
    config: str
    with_reset: tuple[str, ...]
    without_reset: tuple[str, ...]
    unexpected: tuple[str, ...]    # without reset and allowed by no pattern
    stale: tuple[str, ...]         # patterns that match no register without reset

    @property
    def passed(self) -> bool:
        return not self.unexpected and not self.stale


_INDEX = re.compile(r"\[[^\]]*\]")


def _clean(name: str) -> str:
    return _INDEX.sub("", name.lstrip("\\")).replace(" ", "")


def registers(netlist: Mapping, module: str) -> dict[str, set[str]]:
    """``{"reset": names, "no_reset": names}`` of the flop cells of one module of a Yosys
    JSON netlist: the names of the nets each cell's Q output drives (public names only,
    indices dropped)."""
    mod = netlist["modules"][module]
    names: dict[int, list[str]] = {}
    for name, net in mod.get("netnames", {}).items():
        if net.get("hide_name"):
            continue
        for bit in net.get("bits", []):
            if isinstance(bit, int):
                names.setdefault(bit, []).append(_clean(name))
    out: dict[str, set[str]] = {"reset": set(), "no_reset": set()}
    for cname, cell in mod.get("cells", {}).items():
        kind = cell.get("type", "")
        if kind in MEMORY_WRITE_CELLS:
            out["no_reset"].add(_clean(str(cell.get("parameters", {}).get("MEMID", cname))))
            continue
        if kind not in NO_RESET_CELLS and kind not in RESET_CELLS:
            continue
        if cname.startswith("$driver$"):  # slang names a register's cell after it
            got = {_clean(cname[len("$driver$"):])}
        else:
            got = {n for bit in cell.get("connections", {}).get("Q", [])
                   if isinstance(bit, int) for n in names.get(bit, [])} or {_clean(cname)}
        out["no_reset" if kind in NO_RESET_CELLS else "reset"] |= got
    return out


def netlist(sources: Sequence[str | Path], top: str, params: Mapping[str, int],
            workdir: str | Path) -> dict:
    """The flattened Yosys netlist of ``top`` after ``proc`` (a JSON dict)."""
    wd = Path(workdir).resolve()
    out = wd / "resets.json"
    out.unlink(missing_ok=True)
    synth._run_yosys(wd, "resets", [
        synth._read_slang(sources, top, params),
        f"hierarchy -top {top}",
        "proc",
        "flatten",
        "opt_clean",
        f"write_json {out}",
    ])
    return json.loads(out.read_text())


def check(top: str, cfgs: PipelineConfig | Sequence[PipelineConfig], workdir: str | Path,
          allowed: Mapping[str, str] | None = None) -> ResetReport:
    """Registers of ``top`` without reset, over one or several configurations (what a
    configuration elaborates differs: a two-level DPC product tree, ...), against the
    allow-list (``ALLOWED[top]``). A pattern is stale when it matches no register of any
    of the configurations."""
    allowed = ALLOWED.get(top, {}) if allowed is None else allowed
    cfgs = [cfgs] if isinstance(cfgs, PipelineConfig) else list(cfgs)
    regs: dict[str, set[str]] = {"reset": set(), "no_reset": set()}
    for i, cfg in enumerate(cfgs):
        got = registers(netlist(hdl_sources(top), top, top_parameters(top, cfg),
                                Path(workdir) / f"c{i}"), top)
        for k in regs:
            regs[k] |= got[k]
    without = sorted(regs["no_reset"])
    unexpected = [r for r in without if not any(fnmatch.fnmatchcase(r, p) for p in allowed)]
    stale = [p for p in allowed if not any(fnmatch.fnmatchcase(r, p) for r in without)]
    return ResetReport(top, ", ".join(c.name for c in cfgs), tuple(sorted(regs["reset"])),
                       tuple(without), tuple(unexpected), tuple(stale))


def format_report(rep: ResetReport, allowed: Mapping[str, str] | None = None) -> str:
    """One line per register without reset, with its reason or UNEXPECTED; stale patterns."""
    allowed = ALLOWED.get(rep.top, {}) if allowed is None else allowed
    lines = []
    for r in rep.without_reset:
        why = next((w for p, w in allowed.items() if fnmatch.fnmatchcase(r, p)), None)
        lines.append(f"{r}: {why}" if why else f"{r}: UNEXPECTED (no reset, not allowed)")
    lines += [f"{p}: STALE (matches no register without reset)" for p in rep.stale]
    return "\n".join(lines)


__all__ = ["ALLOWED", "NO_RESET_CELLS", "RESET_CELLS", "ResetReport", "check",
           "format_report", "netlist", "registers"]
