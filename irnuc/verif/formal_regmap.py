"""The register map of one configuration as a SystemVerilog package for the register-file
proofs of ``irnuc formal`` (``irnuc_fv_map``, read by ``hdl/formal/irnuc_fv_regs.sv``).

Generated from the map's one source through its model (:class:`irnuc.nuc_fixed.regmap.
RegisterModel`: presence, field masks, reset values, responses) and the hardware events each
live field follows (docs/registers.md: the counters count their events, the W1C status bits
are set by theirs, an event in a clear's cycle wins; ``STATUS.pending`` is set by a write to
a shadowed register and cleared by a frame start, a write in the start's cycle winning).
The checker is written against the AXI4-Lite interface and this package, not against a
register file's internals: any register file behind ``s_axil`` with the register file's
event inputs is held to it.
"""

from __future__ import annotations

#: The register file's event inputs, in the order of the checker's event vector ev_i.
EVENTS = ("frame_start", "frame_out", "beat", "pix_out", "drop", "pad", "sof_early",
          "sof_late", "eol_early", "eol_late", "coef_early", "coef_late", "ffc_done")
_ERRORS = ("sof_early", "sof_late", "eol_early", "eol_late", "coef_early", "coef_late")
#: (register, field) -> the event it counts.
COUNT_EVENTS = {("FRAMES_IN", "count"): "frame_start", ("FRAMES_OUT", "count"): "frame_out",
                ("PIXELS_IN", "count"): "beat", ("PIXELS_OUT", "count"): "pix_out",
                ("DROPPED", "count"): "drop", ("PADDED", "count"): "pad",
                ("SOF_ERRORS", "early"): "sof_early", ("SOF_ERRORS", "late"): "sof_late",
                ("EOL_ERRORS", "early"): "eol_early", ("EOL_ERRORS", "late"): "eol_late",
                ("COEF_ERRORS", "early"): "coef_early", ("COEF_ERRORS", "late"): "coef_late"}
#: (register, field) -> the events that set it (W1C, hardware-set).
SET_EVENTS = {**{("STATUS", e): (e,) for e in _ERRORS}, ("IRQ_STATUS", "error"): _ERRORS,
              ("IRQ_STATUS", "frame_done"): ("frame_out",),
              ("IRQ_STATUS", "ffc_done"): ("ffc_done",)}
#: Kinds of register (the checker's property per kind).
KINDS = {"const": 0, "rw": 1, "w1c": 2, "count": 3}


def _hex(v: int) -> str:
    return f"32'h{v & 0xFFFF_FFFF:08x}"


def package(cfg) -> str:
    """The ``irnuc_fv_map`` package of configuration ``cfg``."""
    from irnuc.nuc_fixed.regmap import OKAY, RegisterModel

    m = RegisterModel(cfg)
    rmap = m.map
    wbits = rmap.address_bits - 2
    has_ffc = cfg.has("ffc")
    info, evolve, clears = [], [], []
    command = rmap["COMMAND"]
    for r in rmap.registers:
        w = r.offset // 4
        present = m.present(r)
        value = (1 << m.value_bits(r)) - 1 if present else 0
        rw = m.field_mask(r, ("rw",))
        w1c = m.field_mask(r, ("w1c",))
        level = pending = 0
        kind = "const"
        sets, counts = [], []
        for f in r.fields:
            fmask = f.mask & value
            if (r.name, f.name) in COUNT_EVENTS:
                kind = "count"
                counts.append((f, COUNT_EVENTS[(r.name, f.name)]))
            elif (r.name, f.name) in SET_EVENTS:
                evs = [e for e in SET_EVENTS[(r.name, f.name)] if e != "ffc_done" or has_ffc]
                sets.append((f, evs))
            elif (r.name, f.name) == ("STATUS", "pending"):
                pending |= fmask
            elif f.live:
                level |= fmask  # a level the hardware drives (not modelled: not checked)
        if rw:
            kind = "rw"
        if w1c:
            kind = "w1c"
        # The responses by address and access, the model's (a fresh one for each: a write
        # of its reset value, no lane enabled, is legal on FRAME_SIZE too).
        rd_err = RegisterModel(cfg, rmap).read(r.offset)[0] != OKAY
        wr_err = RegisterModel(cfg, rmap).write(r.offset, m.reset_value(r), 0) != OKAY
        info.append(f"      {wbits}'d{w}: r = '{{1'b1, 1'b{int(present)}, "
                    f"1'b{int(wr_err)}, 1'b{int(rd_err)}, 1'b{int(bool(r.shadowed))}, "
                    f"2'd{KINDS[kind]}, {_hex(m.reset_value(r))}, {_hex(value)}, {_hex(rw)}, "
                    f"{_hex(w1c)}, {_hex(level)}, {_hex(pending)}}};  // {r.name}")
        if not present:
            continue
        terms = []
        for f, evs in sets:
            if evs:
                bit = " || ".join(f"ev[{EVENTS.index(e)}]" for e in evs)
                terms.append(f"(32'({bit}) << {f.lsb})")
        if counts:
            parts = []
            for f, e in counts:
                top = "" if f.bits == 32 else f"[{f.lsb + f.bits - 1}:{f.lsb}]"
                parts.append((f.lsb, f"v{top} + {f.bits}'(ev[{EVENTS.index(e)}])"))
            expr = "{" + ", ".join(p for _, p in sorted(parts, reverse=True)) + "}"
            evolve.append(f"      {wbits}'d{w}: n = {expr};  // {r.name}")
        elif terms:
            evolve.append(f"      {wbits}'d{w}: n = v | " + " | ".join(terms)
                          + f";  // {r.name}")
        if counts:
            clears.append(f"{wbits}'d{w}")
    clear_bit = command.field("clear_counters").lsb
    fs = rmap["FRAME_SIZE"]
    fw, fh = fs.field("width"), fs.field("height")
    lines = [
        f"// The register map of {cfg.name} for the register-file proofs of irnuc formal: "
        "generated by",
        "// irnuc.verif.formal_regmap from the map through nuc_fixed.regmap.RegisterModel "
        "(do not edit).",
        "// Not every entry is used by every check (a table of the whole map):",
        "/* verilator lint_off UNUSEDPARAM */",
        "/* verilator lint_off UNUSEDSIGNAL */",
        "package irnuc_fv_map;",
        f"  localparam int unsigned WordBits = {wbits};",
        f"  localparam int unsigned NumEvents = {len(EVENTS)};",
        f"  localparam logic [{wbits - 1}:0] FrameSizeWord = {wbits}'d{fs.offset // 4};",
        f"  localparam logic [{wbits - 1}:0] StatusWord = {wbits}'d{rmap['STATUS'].offset // 4};",
        "  localparam logic [1:0] KConst = 2'd0, KRw = 2'd1, KW1c = 2'd2, KCount = 2'd3;",
        "  typedef struct packed {",
        "    logic        mapped, present, wr_err, rd_err, shadowed;",
        "    logic [1:0]  kind;",
        "    logic [31:0] reset, value, rw, w1c, level, pending;",
        "  } reg_t;",
        "",
        f"  function automatic reg_t info(input logic [{wbits - 1}:0] w);",
        "    reg_t r;",
        "    r = '0;",
        "    case (w)",
        *info,
        "      default: ;",
        "    endcase",
        "    return r;",
        "  endfunction",
        "",
        "  // The value one cycle of events makes of v (counters count, W1C bits are set).",
        f"  function automatic logic [31:0] evolve(input logic [{wbits - 1}:0] w,",
        "                                         input logic [31:0] v,",
        "                                         input logic [NumEvents-1:0] ev);",
        "    logic [31:0] n;",
        "    n = v;",
        "    case (w)",
        *evolve,
        "      default: ;",
        "    endcase",
        "    return n;",
        "  endfunction",
        "",
        "  // A write of data to word w clears the counter at word c (COMMAND.clear_counters).",
        f"  function automatic logic clears(input logic [{wbits - 1}:0] c, "
        f"input logic [{wbits - 1}:0] w,",
        "                                  input logic [31:0] data);",
        f"    return w == {wbits}'d{command.offset // 4} && data[{clear_bit}]"
        + (" && (" + " || ".join(f"c == {x}" for x in clears) + ")" if clears else " && 1'b0")
        + ";",
        "  endfunction",
        "",
        "  // FRAME_SIZE value v is legal (1..FRAME_MAX in each dimension).",
        "  function automatic logic size_legal(input logic [31:0] v);",
        f"    return v[{fw.lsb + fw.bits - 1}:{fw.lsb}] != '0 && "
        f"v[{fw.lsb + fw.bits - 1}:{fw.lsb}] <= {fw.bits}'d{cfg.max_width}",
        f"           && v[{fh.lsb + fh.bits - 1}:{fh.lsb}] != '0 && "
        f"v[{fh.lsb + fh.bits - 1}:{fh.lsb}] <= {fh.bits}'d{cfg.max_height};",
        "  endfunction",
        "endpackage",
        "/* verilator lint_on UNUSEDSIGNAL */",
        "/* verilator lint_on UNUSEDPARAM */",
        "",
    ]
    return "\n".join(lines)


__all__ = ["COUNT_EVENTS", "EVENTS", "SET_EVENTS", "package"]
