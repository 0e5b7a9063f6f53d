"""The files generated from the register map ``nuc_fixed/registers.rdl`` with PeakRDL.

* the register block ``hdl/irnuc_axil_regblock.sv`` and its package
  ``hdl/irnuc_axil_regblock_pkg.sv`` (peakrdl-regblock: the AXI4-Lite slave, the address
  decode, the registers it stores and the read-back; :func:`regblock_texts`), and the block
  of ``hdl/irnuc_axil_regs.sv`` between the ``irnuc-regmap`` markers that connects the
  method registers' hardware interface to that module's generic slot logic
  (:func:`wrapper_block`);
* the C header ``firmware/irnuc_regs.h`` (peakrdl-cheader, :func:`c_header`);
* the IP-XACT description ``hdl/irnuc_regs.xml`` (peakrdl-ipxact, :func:`ipxact`);
* the Python register model of the testbenches (peakrdl-python, :func:`python_model`:
  generated into the irnuc cache, not into the sources).

The committed ones are those of the map's default parameters (typical14's reset values;
the register block reads every configuration value from its wrapper's parameters, so one
block serves every build); ``irnuc regmap --pipeline NAME`` writes the C header, the
IP-XACT and the Markdown of one configuration. ``python -m irnuc.cosim.spec_files
--check`` compares the committed files with what the tools make now (the PeakRDL versions
are pinned in pyproject.toml for that).
"""

from __future__ import annotations

import importlib
import importlib.util
import re
import sys
import tempfile
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any

from irnuc.common.errors import ToolError
from irnuc.cosim.sources import HDL_DIR
from irnuc.nuc_fixed import regmap

if TYPE_CHECKING:
    from systemrdl.node import RootNode

#: The generated register block and its package (one module per file).
REGBLOCK_MODULE = "irnuc_axil_regblock"
REGBLOCK = HDL_DIR / f"{REGBLOCK_MODULE}.sv"
REGBLOCK_PKG = HDL_DIR / f"{REGBLOCK_MODULE}_pkg.sv"
#: The hand-written wrapper whose slot wiring is generated (between the markers).
WRAPPER = HDL_DIR / "irnuc_axil_regs.sv"
BEGIN = "  // irnuc-regmap: begin (generated from nuc_fixed/registers.rdl; do not edit)"
END = "  // irnuc-regmap: end"
#: The IP-XACT description of the map (installed with the RTL, irnuc.hdl).
IPXACT = HDL_DIR / "irnuc_regs.xml"
#: The firmware folder of a checkout: the C header and the driver example.
FIRMWARE_DIR = HDL_DIR.parent / "firmware"
C_HEADER = FIRMWARE_DIR / "irnuc_regs.h"

#: peakrdl-regblock's options (docs/regmap.md, "The register block").
REGBLOCK_OPTIONS: dict[str, Any] = {
    "module_name": REGBLOCK_MODULE,
    "package_name": f"{REGBLOCK_MODULE}_pkg",
    "reuse_hwif_typedefs": False,   # struct names from the paths (readable, stable)
    "default_reset_activelow": True,  # rst_ni: asynchronous, active low
    "default_reset_async": True,
    "err_if_bad_addr": True,        # SLVERR outside the map
    "err_if_bad_rw": True,          # SLVERR for a write to RO / a read of WO
    "retime_read_fanin": True,      # a flop inside the read-back fan-in (Fmax)
    # The external registers' requests stay combinational (from the decode): a retimed
    # request is a non-blocking write into hwif_out, which Verilator cannot mix with the
    # struct's continuous assignments (BLKANDNBLK); irnuc_axil_regs registers FRAME_SIZE's.
    "retime_external_reg": False,
}
#: Warnings of Verilator's -Wall that the generated module raises and that are the
#: generator's style, switched off around it only.
_LINT_OFF = ("MULTIDRIVEN", "UNUSEDSIGNAL", "UNUSEDPARAM", "GENUNNAMED", "DECLFILENAME",
             "WIDTHEXPAND", "WIDTHTRUNC", "UNOPTFLAT")


def _regblock_cpuif() -> type:
    """The register block's CPU interface: irnuc's AXI4-Lite slave
    (``cosim/templates/regblock_axi4lite.sv``, the port names of peakrdl-regblock's
    flattened AXI4-Lite interface and one more input, ``hwif_wr_err``: a write acknowledged
    by an external register while it is 1 is answered SLVERR, FRAME_SIZE's value check).
    regblock's own AXI4-Lite slave reaches the address decode through its request
    multiplexer and its readies through logic; on ECP5 that read path closed at 108 MHz
    (docs/regmap.md, "The register block")."""
    from peakrdl_regblock.cpuif.axi4lite import AXI4Lite_Cpuif_flattened

    class IrnucAxi4Lite(AXI4Lite_Cpuif_flattened):
        template_path = "templates/regblock_axi4lite.sv"

        @property
        def port_declaration(self) -> str:
            return super().port_declaration + ",\ninput wire hwif_wr_err"

    IrnucAxi4Lite.__module__ = __name__  # the template is found beside this file
    return IrnucAxi4Lite


def _readback_split(span: int, data_bytes: int) -> int:
    """The low address bits (byte address) the retimed read-back's first stage decodes.

    peakrdl-regblock splits the word-address bits of the whole window
    (``address_width``, 12 bits: 10 word bits) in the middle, so its first stage chose
    among the 32 words of each 128-byte bank (a 5-bit compare, then a 32-way fan-in before
    the retiming flop: the wrapper's longest path on ECP5, docs/rtl.md) and the second among
    32 banks of which the map fills four. irnuc splits the word bits of the map's span
    instead (``0x1c4`` bytes: 7 word bits), so the first stage chooses among the 8 words of a
    32-byte bank and the second among 16 banks (the window's bits above the span select
    banks that are always 0). Both stages keep every address bit: no aliasing."""
    unused = max(data_bytes.bit_length() - 1, 0)
    relevant = max((span - 1).bit_length() - unused, 2)
    return relevant // 2 + unused


def _regblock_readback() -> type:
    """peakrdl-regblock's read-back generator with irnuc's split of the retimed fan-in
    (:func:`_readback_split`); everything else, the templates and the multiplexer
    generator included, is regblock's."""
    from peakrdl_regblock.readback import Readback
    from peakrdl_regblock.readback.readback_mux_generator import RetimedReadbackMuxGenerator

    class IrnucReadback(Readback):
        def get_2stage_implementation(self) -> str:
            if self.ds.has_external_block:
                raise ToolError("the register map has an external block: irnuc's read-back "
                                "split (irnuc.cosim.regfiles) does not handle one")
            low = _readback_split(self.ds.top_node.size, self.exp.cpuif.data_width_bytes)
            mux = RetimedReadbackMuxGenerator(self.exp).get_content(self.ds.top_node)
            if not mux:
                return self.get_empty_implementation()
            context = {
                "readback_mux": mux,
                "ext_block_readback_mux": None,
                "cpuif": self.exp.cpuif,
                "ds": self.ds,
                "low_addr_width": low,
                "high_addr_width": self.ds.addr_width - low,
                "get_always_ff_event": self.exp.dereferencer.get_always_ff_event,
                "get_resetsignal": self.exp.dereferencer.get_resetsignal,
            }
            template = self.exp.jj_env.get_template("readback/templates/readback_with_rt.sv")
            return _readback_ahead(template.render(context), low)

    return IrnucReadback


#: A compare of the first read-back stage: the request's low address with a register's.
_RD_LOW = "ad_low(rd_mux_addr) == ad_low("
_RD_STAGE1 = "// readback stage 1\n"  # unindented: regblock indents the block


def _readback_ahead(text: str, low: int) -> str:
    """The retimed read-back (:func:`_regblock_readback`) with its first stage's address
    compares a cycle ahead: ``rd_mux_addr`` is the request's address (:data:`_RD_MUX_HELD`),
    loaded from the taken holding register (``ahead_rd_addr``, ``ahead_wr_addr``:
    :func:`_predecode`), so a one-hot flop of its low address loaded in the same cycle
    (``readback_low_q``) replaces each ``ad_low(rd_mux_addr) == ad_low(X)`` by
    ``readback_low_q[ad_low(X)]``: the same select in every cycle. Raises
    :class:`ToolError` if the generated text is not of that shape."""
    if text.count(_RD_STAGE1) != 1 or _RD_LOW not in text:
        raise ToolError("peakrdl-regblock's read-back is not the one irnuc.cosim.regfiles "
                        "decodes ahead: update it")
    lines = text.split("\n")
    for i, ln in enumerate(lines):
        if _RD_LOW in ln:
            head, _, rest = ln.partition(_RD_LOW)
            # The register's address runs to the parenthesis closing ad_low(.
            depth, end = 1, 0
            while depth and end < len(rest):
                depth += {"(": 1, ")": -1}.get(rest[end], 0)
                end += 1
            if depth or not head.rstrip().endswith("if(") or rest[end:] != ") begin":
                raise ToolError("peakrdl-regblock's read-back compares the address in a form "
                                "irnuc.cosim.regfiles does not decode ahead: update it:\n" + ln)
            lines[i] = f"{head}readback_low_q[ad_low({rest[:end]}]{rest[end:]}"
    text = "\n".join(lines)
    if "rd_mux_addr" in text.split(_RD_STAGE1)[1].split("readback_data_rt_c = ")[0]:
        raise ToolError("peakrdl-regblock's read-back reads rd_mux_addr in its first stage "
                        "where irnuc.cosim.regfiles does not decode it ahead: update it")
    ahead = (
        "// irnuc: the first stage's address compares ahead: rd_mux_addr is the request's\n"
        "// address, loaded from the taken holding register, so a one-hot flop of its low\n"
        "// address loads from the same register in the same cycle and selects each\n"
        "// register's word where the compare of rd_mux_addr would (docs/regmap.md).\n"
        f"logic [{(1 << low) - 1}:0] readback_low_q;\n"
        "always_ff @(posedge clk) begin\n"
        f"    if(axil_take_rd) readback_low_q <= {1 << low}'(1) << ad_low(ahead_rd_addr);\n"
        f"    else if(axil_take_wr) readback_low_q <= {1 << low}'(1) << ad_low(ahead_wr_addr);\n"
        "end\n\n")
    return text.replace(_RD_STAGE1, ahead + _RD_STAGE1)


def _regblock_root() -> RootNode:
    from peakrdl_regblock.udps import ALL_UDPS

    return regmap.elaborate(udps=tuple(ALL_UDPS))


def _tool_version(dist: str) -> str:
    from importlib.metadata import version

    return version(dist)


def _sv_head(what: str) -> list[str]:
    return [f"// {what}: generated from nuc_fixed/registers.rdl by peakrdl-regblock "
            f"{_tool_version('peakrdl-regblock')}",
            "// (python -m irnuc.cosim.spec_files --write); do not edit. What it implements "
            "and why",
            "// the rest is hand-written in irnuc_axil_regs: docs/regmap.md.",
            "/* verilator lint_off " + " */\n/* verilator lint_off ".join(_LINT_OFF) + " */"]


#: The one line of the generated module irnuc changes (:func:`regblock_texts`): the read
#: address of an external register's read is held by the CPU interface.
_RD_MUX = "    assign rd_mux_addr = decoded_req ? decoded_addr : pending_rd_addr;"
_RD_MUX_HELD = """\
    // irnuc: its CPU interface holds cpuif_addr from a request until the next one, which
    // waits for the response: the address held for an external read (pending_rd_addr) is
    // cpuif_addr, and the multiplexer between them (its select is the request and the
    // stall logic) is not built (on ECP5 the read path's longest; docs/regmap.md).
    assign rd_mux_addr = decoded_addr;
`ifndef SYNTHESIS
    always_ff @(posedge clk) begin
        if(external_pending) begin
            assert_rd_addr_held: assert(pending_rd_addr == decoded_addr)
                else $error("irnuc: cpuif_addr changed while an external access was pending");
        end
    end
`endif"""


#: The second: the request's stall mask. irnuc's CPU interface issues a request only after
#: the last one's response was taken, so neither stall (a write in the cycle after a read;
#: an external register's acknowledge still owed) is ever up with a request.
_REQ_MASK = """\
    assign cpuif_req_masked = cpuif_req
                            & !(!cpuif_req_is_wr & cpuif_req_stall_rd)
                            & !(cpuif_req_is_wr & cpuif_req_stall_wr);"""
_REQ_MASK_NONE = """\
    // irnuc: its CPU interface issues a request only after the last one's response was
    // taken (one transaction at a time), so neither stall is up with a request and the mask
    // is not built: it sat in front of every address decode, the write strobes' and the
    // write response's (on ECP5 the wrapper's longest paths; docs/regmap.md).
    assign cpuif_req_masked = cpuif_req;
`ifndef SYNTHESIS
    always_ff @(posedge clk) begin
        if(cpuif_req) begin
            assert_req_not_stalled: assert(cpuif_req_is_wr ? !cpuif_req_stall_wr : !cpuif_req_stall_rd)
                else $error("irnuc: a request reached the register block while it stalls");
        end
    end
`endif"""
#: The lines of the generated module irnuc replaces, each found exactly once.
_REPLACED = ((_RD_MUX, _RD_MUX_HELD), (_REQ_MASK, _REQ_MASK_NONE))

#: The third: the address decode. peakrdl-regblock decodes the request's address in the
#: cycle of the request: the error and external flags and every register's strobe, each
#: through the compare of the address with a register's (on ECP5 the wrapper's longest
#: paths: the write response's error flag, external_pending, the fields' write enables).
#: irnuc's CPU interface loads the request's address and direction from a holding register
#: (axil_araddr or axil_awaddr), which holds it from the cycle before the request issues
#: until it is taken (axil_take_rd/axil_take_wr). irnuc decodes each holding register
#: every cycle into flops (:data:`_PREDECODE_HEAD`), loads the taken one's into the
#: request's decode flops when the request's address loads, and gates those by the
#: request's flag: the same values in the same cycles, no compare after a flop.
_DECODE_HEAD = """\
    always_comb begin
        automatic logic is_valid_addr;
        automatic logic is_valid_rw;
        automatic logic is_external;
        is_external = '0;
        is_valid_addr = '0;
        is_valid_rw = '0;
"""
_DECODE_TAIL = """\
        decoded_err = (~is_valid_addr | (is_valid_addr & ~is_valid_rw)) & decoded_req;
        decoded_req_is_external = is_external;
    end
"""
_PREDECODE_HEAD = """\
    // irnuc: the decode two steps ahead. A request's address waits in its holding register
    // (axil_araddr, axil_awaddr) from the cycle before it issues until it is taken into the
    // request's flops (axil_take_rd, axil_take_wr): each holding register's decode (with the
    // request's direction, 0 and 1) is registered every cycle (ahead_rd_*, ahead_wr_*) and
    // the taken one's loads with the request's address (predecode_*_q, the decode of the
    // request's flops); the strobes, decoded_err and decoded_req_is_external are these flops
    // gated by the request, the values the decode would give from the request's flops
    // (docs/regmap.md).
    logic [11:0] ahead_rd_addr, ahead_wr_addr;
    logic        ahead_rd_err_d, ahead_rd_err_q, ahead_rd_ext_d, ahead_rd_ext_q;
    logic        ahead_wr_err_d, ahead_wr_err_q, ahead_wr_ext_d, ahead_wr_ext_q;
    logic        predecode_err_q, predecode_ext_q;
    decoded_reg_strb_t ahead_rd_strb_d, ahead_rd_strb_q, ahead_wr_strb_d, ahead_wr_strb_q;
    decoded_reg_strb_t predecode_strb_q;
    assign ahead_rd_addr = {axil_araddr[11:2], 2'b0};
    assign ahead_wr_addr = {axil_awaddr[11:2], 2'b0};
"""
_PREDECODE_TAIL = """\
    always_ff @(posedge clk) begin
        ahead_rd_strb_q <= ahead_rd_strb_d;
        ahead_rd_err_q  <= ahead_rd_err_d;
        ahead_rd_ext_q  <= ahead_rd_ext_d;
        ahead_wr_strb_q <= ahead_wr_strb_d;
        ahead_wr_err_q  <= ahead_wr_err_d;
        ahead_wr_ext_q  <= ahead_wr_ext_d;
        if(axil_take_rd) begin
            predecode_strb_q <= ahead_rd_strb_q;
            predecode_err_q  <= ahead_rd_err_q;
            predecode_ext_q  <= ahead_rd_ext_q;
        end else if(axil_take_wr) begin
            predecode_strb_q <= ahead_wr_strb_q;
            predecode_err_q  <= ahead_wr_err_q;
            predecode_ext_q  <= ahead_wr_ext_q;
        end
    end
"""
_DECODE_FLAGS = ("is_valid_addr |=", "is_valid_rw |=", "is_external |=")


#: A generated strobe line: indent, the strobe's path, the decode of the request's flops.
_STROBE = re.compile(r"^( *)decoded_reg_strb\.([\w.\[\]]+) = cpuif_req_masked & (.+);$")


def _ahead(line: str, side: str) -> str:
    """A decode line on a holding register (``side`` ``rd`` or ``wr``) and its direction
    instead of the request's flops."""
    return (line.replace("cpuif_req_masked & ", "")
            .replace("cpuif_addr", f"ahead_{side}_addr")
            .replace("cpuif_req_is_wr", "1'b1" if side == "wr" else "1'b0"))


def _predecode(body: str) -> str:
    """The generated decode block (:data:`_DECODE_HEAD`) made ahead: every line of it,
    once per holding register (:data:`_PREDECODE_HEAD`), decodes that register's address
    and direction into flops, the strobes into a struct of ``decoded_reg_strb``'s type and
    the error and external flags into theirs; the taken one's load the request's flops
    (:data:`_PREDECODE_TAIL`); the block left is the request's flag ANDed with those.
    Raises :class:`ToolError` if the generated block is not of that shape."""
    start = body.find(_DECODE_HEAD)
    end = body.find(_DECODE_TAIL, start)
    if start < 0 or body.count(_DECODE_HEAD) != 1 or end < 0 or body.count(_DECODE_TAIL) != 1:
        raise ToolError("peakrdl-regblock's address decode is not the one irnuc.cosim.regfiles "
                        "splits: update it")
    ahead: dict[str, list[str]] = {"rd": [], "wr": []}
    gated = []
    for ln in body[start + len(_DECODE_HEAD):end].splitlines(keepends=True):
        strobe = _STROBE.match(ln.rstrip("\n"))
        if strobe:
            indent, path, decode = strobe.groups()
            for side, lines in ahead.items():
                lines.append(f"{indent}ahead_{side}_strb_d.{path} = {_ahead(decode, side)};\n")
            gated.append(f"{indent}decoded_reg_strb.{path} = cpuif_req_masked"
                         f" & predecode_strb_q.{path};\n")
        elif "decoded_reg_strb" in ln:
            raise ToolError("peakrdl-regblock's address decode has a strobe line "
                            "irnuc.cosim.regfiles does not decode ahead: update it:\n" + ln)
        elif ln.strip().startswith(_DECODE_FLAGS):
            for side, lines in ahead.items():
                lines.append(_ahead(ln, side))
        else:  # a loop's head or end: in every block
            for lines in (*ahead.values(), gated):
                lines.append(ln)
    if any("cpuif_" in ln for lines in ahead.values() for ln in lines):
        raise ToolError("peakrdl-regblock's address decode reads a signal irnuc.cosim.regfiles "
                        "does not decode ahead: update it")
    blocks = "".join(
        _DECODE_HEAD + "".join(lines)
        + f"        ahead_{side}_err_d = ~is_valid_addr | ~is_valid_rw;\n"
        + f"        ahead_{side}_ext_d = is_external;\n    end\n"
        for side, lines in ahead.items())
    decode = ("    always_comb begin\n" + "".join(gated)
              + "        decoded_err = predecode_err_q & decoded_req;\n"
              + "        decoded_req_is_external = predecode_ext_q & decoded_req;\n    end\n")
    return (body[:start] + _PREDECODE_HEAD + blocks + _PREDECODE_TAIL + decode
            + body[end + len(_DECODE_TAIL):])


def regblock_texts() -> dict[Path, str]:
    """The register block and its package, as peakrdl-regblock writes them with irnuc's
    CPU interface (:func:`_regblock_cpuif`), two places changed (the read address
    multiplexer, :data:`_RD_MUX`, and the request's stall mask, :data:`_REQ_MASK`), a
    header naming the source and the generator's Verilator warnings switched off in the
    file."""
    from peakrdl_regblock import RegblockExporter, exporter

    root = _regblock_root()
    with tempfile.TemporaryDirectory(prefix="irnuc-regblock-") as tmp:
        # The exporter builds its read-back generator by this module-level name (regblock
        # 1.3 has no option for the split of the retimed fan-in): irnuc's for this export.
        regblock_readback = exporter.Readback
        exporter.Readback = _regblock_readback()
        try:
            RegblockExporter().export(root, tmp, cpuif_cls=_regblock_cpuif(),
                                      address_width=regmap.register_map().address_bits,
                                      **REGBLOCK_OPTIONS)
        finally:
            exporter.Readback = regblock_readback
        out = {}
        for path, what in ((REGBLOCK_PKG, "the register block's hardware interface types"),
                           (REGBLOCK, "the register block of irnuc_axil_regs")):
            body = (Path(tmp) / path.name).read_text()
            body = "\n".join(line.rstrip() for line in body.splitlines())
            if path == REGBLOCK:
                for find, replace in _REPLACED:
                    if body.count(find) != 1:
                        raise ToolError("peakrdl-regblock's text is not the one "
                                        "irnuc.cosim.regfiles replaces: update it:\n" + find)
                    body = body.replace(find, replace)
                body = _predecode(body)
            tail = "/* verilator lint_on " + " */\n/* verilator lint_on ".join(_LINT_OFF) + " */"
            out[path] = "\n".join([*_sv_head(what), body.strip("\n"), tail]) + "\n"
    return out


# ---- the wrapper's slot wiring ---------------------------------------------------------

def _sv_name(name: str) -> str:
    return "".join(w.title() for w in name.lower().split("_") if w)


def slot_groups(rmap: regmap.RegisterMap | None = None) -> list[regmap.Group]:
    """The 64-bit method register slots of the map, in map order (slot k of the wrapper)."""
    rmap = rmap or regmap.register_map()
    return [g for g in rmap.groups if g.kind == "slot"]


def wrapper_block(rmap: regmap.RegisterMap | None = None) -> str:
    """The generated block of ``hdl/irnuc_axil_regs.sv``: the slot count, each slot's width
    parameter and index, and the hardware interface of each slot word wired to the
    wrapper's arrays (slot k, word 0 = LO, 1 = HI)."""
    rmap = rmap or regmap.register_map()
    slots = slot_groups(rmap)
    widths = [f"{_sv_name(rmap[g.registers[0]].config_register or g.name)}RegBits"
              for g in slots]
    lines = [BEGIN,
             "  // The method registers' 64-bit slots (the map's register files of LO and HI; ",
             "  // NumSlots = irnuc_pkg::RegSlotCount), their widths (this module's parameters,",
             "  // 0 = not in this build) and their indices.",
             "  localparam int unsigned SlotBits [NumSlots] = '{",
             *(f"    {w}" + ("," if k < len(widths) - 1 else "") for k, w in enumerate(widths)),
             "  };"]
    lines.append("  /* verilator lint_off UNUSEDPARAM */  // the indices the module does not name")
    for k, g in enumerate(slots):
        lines.append(f"  localparam int unsigned Slot{_sv_name(g.name)} = {k};")
    lines.append("  /* verilator lint_on UNUSEDPARAM */")
    lines += ["  logic [NumSlots-1:0][1:0]       slot_req, slot_req_is_wr, slot_rd_ack, "
              "slot_wr_ack;",
              "  logic [NumSlots-1:0][1:0][31:0] slot_wr_data, slot_wr_biten, slot_rd_data;"]
    for k, g in enumerate(slots):
        for w, reg in enumerate(g.registers):
            path = f"{g.name}.{reg.split('.')[-1]}"
            lines += [f"  assign slot_req[{k}][{w}]       = hwif_out.{path}.req;",
                      f"  assign slot_req_is_wr[{k}][{w}] = hwif_out.{path}.req_is_wr;",
                      f"  assign slot_wr_data[{k}][{w}]   = hwif_out.{path}.wr_data.value;",
                      f"  assign slot_wr_biten[{k}][{w}]  = hwif_out.{path}.wr_biten.value;",
                      f"  assign hwif_in.{path}.rd_ack       = slot_rd_ack[{k}][{w}];",
                      f"  assign hwif_in.{path}.rd_data.value = slot_rd_data[{k}][{w}];",
                      f"  assign hwif_in.{path}.wr_ack       = slot_wr_ack[{k}][{w}];"]
    lines.append(END)
    return "\n".join(lines) + "\n"


def replace_block(text: str, block: str) -> str:
    """``text`` with its generated block (markers included) replaced by ``block``."""
    start, end = text.find(BEGIN), text.find(END)
    if start < 0 or end < start:
        raise ValueError(f"no irnuc-regmap markers in {WRAPPER.name}")
    return text[:start] + block + text[end + len(END) + 1:]


# ---- firmware and vendor tools ------------------------------------------------------------

def c_header(root: RootNode | None = None) -> str:
    """The C header of the map (peakrdl-cheader): a struct of the registers, offsets,
    field positions, masks and reset values."""
    from peakrdl_cheader.exporter import CHeaderExporter

    root = root or regmap.elaborate()
    with tempfile.TemporaryDirectory(prefix="irnuc-cheader-") as tmp:
        path = Path(tmp) / C_HEADER.name
        # Struct names from the paths (irnuc_regs__GAIN_t): the slots' types differ only by
        # their properties, and the shared ones would be named by hashes of those.
        CHeaderExporter().export(root, str(path), generate_bitfields=False,
                                 reuse_typedefs=False)
        return path.read_text()


def ipxact(root: RootNode | None = None) -> str:
    """The IP-XACT (IEEE 1685-2014) component of the map (peakrdl-ipxact)."""
    from peakrdl_ipxact import IPXACTExporter

    root = root or regmap.elaborate()
    with tempfile.TemporaryDirectory(prefix="irnuc-ipxact-") as tmp:
        path = Path(tmp) / IPXACT.name
        IPXACTExporter(vendor="irnuc", library="irnuc", version="1.0").export(
            root, str(path), component_name="irnuc_regs")
        return path.read_text()


def expected() -> dict[Path, str]:
    """Each committed file generated from the map and the text it must have."""
    out = regblock_texts()
    out[WRAPPER] = replace_block(WRAPPER.read_text(), wrapper_block())
    out[IPXACT] = ipxact()
    if FIRMWARE_DIR.is_dir():
        out[C_HEADER] = c_header()
    return out


# ---- the Python register model of the testbenches -------------------------------------------

_PY_PACKAGE = "irnuc_regs"


def python_model() -> ModuleType:
    """The peakrdl-python register model of the map (``asyncoutput``: each access awaits
    the bus), imported: the package, with ``reg_model.RegModel`` and
    ``lib.AsyncCallbackSet``. Generated once per map and generator into the irnuc cache (a
    folder per digest, written aside and renamed into place)."""
    from irnuc.common.cache import cache_dir
    from irnuc.common.digest import digest

    key = digest({"rdl": regmap.REGISTERS_RDL.read_text(),
                  "peakrdl-python": _tool_version("peakrdl-python")})
    root = cache_dir("regmodel")
    folder = root / key
    if not (folder / _PY_PACKAGE / "reg_model" / "__init__.py").is_file():
        from peakrdl_python import PythonExporter

        tmp = Path(tempfile.mkdtemp(prefix=f".{key}-", dir=root))
        PythonExporter().export(regmap.elaborate().top, str(tmp), asyncoutput=True,
                                skip_test_case_generation=True)
        try:
            tmp.rename(folder)
        except OSError:  # another process put it there first: theirs is the same
            import shutil

            shutil.rmtree(tmp, ignore_errors=True)
    loaded = sys.modules.get(_PY_PACKAGE)
    if loaded is not None and Path(loaded.__file__ or "").is_relative_to(folder):
        return loaded
    spec = importlib.util.spec_from_file_location(
        _PY_PACKAGE, folder / _PY_PACKAGE / "__init__.py",
        submodule_search_locations=[str(folder / _PY_PACKAGE)])
    if spec is None or spec.loader is None:
        raise ToolError(f"cannot import the register model generated in {folder}")
    pkg = importlib.util.module_from_spec(spec)
    sys.modules[_PY_PACKAGE] = pkg
    spec.loader.exec_module(pkg)
    importlib.import_module(f"{_PY_PACKAGE}.reg_model")
    importlib.import_module(f"{_PY_PACKAGE}.lib")
    return pkg


__all__ = ["C_HEADER", "IPXACT", "REGBLOCK", "REGBLOCK_OPTIONS", "REGBLOCK_PKG", "WRAPPER",
           "c_header", "expected", "ipxact", "python_model", "regblock_texts",
           "slot_groups", "wrapper_block"]
