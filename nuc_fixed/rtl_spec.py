"""The one spec of what the RTL and the Python side share: constants, parameter ranges,
mode encodings and word layouts, each written here once.

* Python reads them from here: the pipeline configuration's ranges and modes
  (:mod:`irnuc.nuc_fixed.config`), the coefficient word (``PipelineConfig.word_fields``),
  the DPC reciprocal (:func:`irnuc.nuc_fixed.dpc.reciprocal_table`), the co-simulation's
  pipeline-stage model (:func:`pipeline_stages`, used by ``irnuc.cosim.coverage``) and
  ``irnuc synth``'s frame limit.
* ``hdl/irnuc_pkg.sv`` carries them in a generated block (:func:`sv_package_block`,
  between the ``irnuc-spec`` markers), and the package probe
  (``cosim/hdl/irnuc_pkg_probe.sv``) is generated whole (:func:`sv_probe`): one port per
  constant and enum literal, the pack and unpack of every word layout, and tables of the
  package's width functions. ``python -m irnuc.cosim.spec_files --write`` regenerates both;
  ``tests/test_rtl_spec.py`` fails while either is stale, and ``cocotb_tests/tb_pkg.py``
  reads every item back from the simulated RTL and compares it with this module.

To add a constant, a range, an enum or a word layout (a per-method coefficient word): add it
to :data:`CONSTANTS`, :data:`RANGES`, :data:`ENUMS` or :data:`LAYOUTS`, regenerate, and use
the generated name in the RTL (docs/architecture.md, "Shared constants"). The AXI4-Lite
register map is written in SystemRDL, ``nuc_fixed/registers.rdl`` (docs/regmap.md); its
offsets, field positions and resets become :data:`REGISTER_CONSTANTS` (part of
:data:`CONSTANTS`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from irnuc.nuc_fixed import regmap as _regmap

# ---------------------------------------------------------------------------------------
# Items
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Constant:
    """One integer constant: ``localparam int unsigned <name> = <value>;`` in the package."""

    name: str  # SystemVerilog name (UpperCamelCase)
    value: int
    doc: str


@dataclass(frozen=True)
class Range:
    """The legal range of one RTL parameter (a pipeline field): ``<name>Min`` and
    ``<name>Max`` in the package; every module taking the parameter asserts it, and
    :mod:`irnuc.nuc_fixed.config` checks it before any work."""

    name: str   # the SystemVerilog parameter
    field: str  # the PipelineConfig field
    lo: int
    hi: int
    unit: str


@dataclass(frozen=True)
class EnumLiteral:
    key: str   # the Python name (a configuration value)
    name: str  # the SystemVerilog literal
    code: int
    doc: str


@dataclass(frozen=True)
class Enum:
    """A SystemVerilog enum of the package and its Python names (configuration values)."""

    name: str  # the typedef, ``<prefix>_e``
    bits: int
    literals: tuple[EnumLiteral, ...]
    doc: str

    @property
    def prefix(self) -> str:
        return self.name.removesuffix("_e")

    @property
    def count_name(self) -> str:
        """The package constant holding the number of literals (``RoundingCount``)."""
        return "".join(w.title() for w in self.prefix.split("_")) + "Count"

    @property
    def codes(self) -> dict[str, int]:
        """Python name -> code."""
        return {lit.key: lit.code for lit in self.literals}


@dataclass(frozen=True)
class Field:
    """A field of a word: its width is a package-function argument named after an RTL
    parameter (``"GainBits"``) or a number of bits; ``format`` is the coefficient format
    giving a named width and the field's sign in a configuration (``"gain"``; empty for a
    flag of a fixed width)."""

    name: str
    width: str | int
    doc: str
    format: str = ""


@dataclass(frozen=True)
class WordLayout:
    """A packed word, fields from the least significant bit up.

    The package gets ``<name>_bits(...)`` (the word width), ``<name>_<field>_lsb(...)``
    per field, and the class ``<name> #(...)::word_t`` (a packed struct, most significant
    field first), all parameterised by the field widths named by parameters.
    """

    name: str
    version: int
    fields: tuple[Field, ...]
    doc: str

    @property
    def parameters(self) -> tuple[str, ...]:
        """The parameters the widths are named by, in the order of the fields."""
        return tuple(dict.fromkeys(f.width for f in self.fields if isinstance(f.width, str)))

    def layout(self, **widths: int) -> dict[str, tuple[int, int]]:
        """Field -> (lsb, width) for the given parameter values (``GainBits=16, ...``)."""
        missing = set(self.parameters) - set(widths)
        if missing:
            raise TypeError(f"{self.name}: give {sorted(missing)}")
        out, lsb = {}, 0
        for f in self.fields:
            w = widths[f.width] if isinstance(f.width, str) else f.width
            out[f.name] = (lsb, int(w))
            lsb += int(w)
        return out

    def bits(self, **widths: int) -> int:
        return sum(w for _, w in self.layout(**widths).values())


# ---------------------------------------------------------------------------------------
# The spec
# ---------------------------------------------------------------------------------------

#: Operand chunk of the multipliers: an unsigned 17-bit chunk fits the signed 18 x 18
#: multiplier of an ECP5 (MULT18X18D) and the 25 x 18 one of a 7-series (DSP48E1).
MUL_CHUNK_BITS = 17
#: Largest frame width and height (and line-buffer depth): 16-bit frame-size ports.
FRAME_DIM_MAX = 65535
#: The DPC divides M < 2^(B+3) by n = 1..8 as (M * R[n]) >> K with K = B + this.
DPC_RECIP_GUARD_BITS = 6
#: Widest sum of the NUC datapath: the golden model computes in int64 and keeps one bit.
SUM_BITS_MAX = 62
#: Leaves of the DPC's adder tree: 8 neighbour values and floor(n/2) (dpc_core's u_sum).
DPC_SUM_LEAVES = 9
#: Register stages of one multiply: the DSP block's input and output registers
#: (irnuc_dsp_mul; ECP5's MULT18X18D is instantiated with both).
MUL_STAGES = 2

#: The AXI4-Lite register map of irnuc_axis_top (nuc_fixed/registers.rdl, read by
#: :mod:`irnuc.nuc_fixed.regmap`): its identity, every offset, field position and width and
#: numeric reset value, as package constants (``RegCtrlOffset``, ``RegCtrlNucEnLsb``, ...).
REGISTER_CONSTANTS: tuple[Constant, ...] = tuple(
    Constant(name, value, doc) for name, value, doc in _regmap.sv_constants())

CONSTANTS: tuple[Constant, ...] = (
    Constant("MulChunkBits", MUL_CHUNK_BITS,
             "operand chunk of the multipliers (one DSP block per partial product)"),
    Constant("FrameDimMax", FRAME_DIM_MAX,
             "largest frame width and height, and line-buffer depth"),
    Constant("DpcRecipGuardBits", DPC_RECIP_GUARD_BITS,
             "DPC reciprocal shift K = OutBits + this"),
    Constant("SumBitsMax", SUM_BITS_MAX, "widest NUC sum (int64 golden model, one spare bit)"),
    *REGISTER_CONSTANTS,
)

RANGES: tuple[Range, ...] = (
    Range("AdcBits", "adc_bits", 1, 24, "bits"),
    Range("GainIntBits", "gain_int_bits", 0, 16, "bits"),
    Range("GainFracBits", "gain_frac_bits", 0, 32, "bits"),
    Range("OffsetIntBits", "offset_int_bits", 1, 32, "bits"),
    Range("OffsetFracBits", "offset_frac_bits", 0, 32, "bits"),
    Range("OutBits", "out_bits", 1, 24, "bits"),
    Range("MaxWidth", "max_width", 1, FRAME_DIM_MAX, "pixels"),
    Range("MaxHeight", "max_height", 1, FRAME_DIM_MAX, "pixels"),
)
#: PipelineConfig field -> (lo, hi).
PIPELINE_RANGES: dict[str, tuple[int, int]] = {r.field: (r.lo, r.hi) for r in RANGES}

ROUNDING = Enum("rounding_e", 2, (
    EnumLiteral("truncate", "RoundTruncate", 0, "floor: s >>> F"),
    EnumLiteral("half_up", "RoundHalfUp", 1, "ties toward +infinity"),
    EnumLiteral("half_even", "RoundHalfEven", 2, "ties to the even integer"),
), "rounding of the NUC sum (module parameter Rounding)")
OVERFLOW = Enum("overflow_e", 1, (
    EnumLiteral("saturate", "OverflowSaturate", 0, "clamp to 0 .. 2^B - 1"),
    EnumLiteral("wrap", "OverflowWrap", 1, "keep the low B bits"),
), "overflow of the NUC output (module parameter Overflow)")
#: Configuration value -> RTL code.
ROUNDING_MODES: dict[str, int] = ROUNDING.codes
OVERFLOW_MODES: dict[str, int] = OVERFLOW.codes

COEF_WORD = WordLayout("coef_word", 1, (
    Field("gain", "GainBits", "gain code, unsigned", "gain"),
    Field("offset", "OffsetBits", "offset code, two's complement", "offset"),
    Field("bad", 1, "defective-pixel flag"),
), "coefficient word of the two-point NUC, memory image version 1")
# The calibration memories of the other methods (memory image version 2) and their frame
# words are written in their methods (nuc_fixed/methods, ``MethodSpec.layouts``), and so is
# blind_drift's frame word; LAYOUTS collects them in registry order.


def _registry_items() -> tuple[Enum, tuple[WordLayout, ...]]:
    """``method_e`` and every word layout, from the method registry (``nuc_fixed.methods``,
    imported here on first use: the registry's methods import this module)."""
    from irnuc.nuc_fixed import methods

    method = Enum("method_e", max(1, (len(methods.BASES) - 1).bit_length()), tuple(
        EnumLiteral(m.name, f"Method{_camel(m.name)}", code, m.doc)
        for code, m in enumerate(methods.BASES.values())),
        "base correction method (parameter Method of the tops; the order of the registry, "
        "nuc_fixed.methods.BASES)")
    layouts: dict[str, WordLayout] = {COEF_WORD.name: COEF_WORD}
    for part in (*methods.BASES.values(), *methods.STAGES.values()):
        for lay in part.layouts:
            layouts.setdefault(lay.name, lay)
    return method, tuple(layouts.values())


def _camel(name: str) -> str:
    return "".join(w[:1].upper() + w[1:] for w in name.split("_"))


def _lazy(name: str) -> Any:
    """A registry-built item inside this module (a global lookup does not reach
    ``__getattr__``)."""
    return __getattr__(name)


def __getattr__(name: str) -> object:
    """``METHOD``, ``ENUMS`` and ``LAYOUTS``: built from the method registry on first use."""
    if name in ("METHOD", "ENUMS", "LAYOUTS"):
        method, layouts = _registry_items()
        # Not cached: a method registered later (a test's) is in the next answer.
        values = {"METHOD": method, "ENUMS": (ROUNDING, OVERFLOW, method), "LAYOUTS": layouts}
        return values[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# ---------------------------------------------------------------------------------------
# Functions of the package, in Python (the probe compares them over their ranges)
# ---------------------------------------------------------------------------------------

def clog2(n: int) -> int:
    """SystemVerilog's ``$clog2``: the bits to count ``n`` values (0 for n <= 1)."""
    return max(0, int(n) - 1).bit_length()


def mul_chunks(bits: int) -> int:
    """``irnuc_pkg::mul_chunks``: MulChunkBits-bit chunks of a ``bits``-bit operand."""
    return -(-int(bits) // MUL_CHUNK_BITS)


def mul_parts(a_bits: int, b_bits: int) -> int:
    """``irnuc_pkg::mul_parts``: partial products (DSP blocks) of an a x b multiply."""
    return mul_chunks(a_bits) * mul_chunks(b_bits)


def dpc_recip_shift(out_bits: int) -> int:
    """``irnuc_pkg::dpc_recip_shift``: K of the DPC division."""
    return int(out_bits) + DPC_RECIP_GUARD_BITS


def dpc_recip(out_bits: int, n: int) -> int:
    """``irnuc_pkg::dpc_recip``: R[n] = ceil(2^K / n), R[0] = 0."""
    return 0 if n == 0 else -(-(1 << dpc_recip_shift(out_bits)) // int(n))


def pipeline_stages(top: str, adc_bits: int, gain_bits: int, out_bits: int) -> list[str]:
    """The register stages an item passes in ``top`` (``nuc_core``, ``dpc_core``,
    ``nuc_dpc_top``), in order, one name per register (docs/rtl.md, "Architecture"),
    ending with ``flush`` for the DPC's flush state where the top has a DPC.

    From the RTL's structure: a multiply is :data:`MUL_STAGES` registers (the DSP block's
    input and output registers, irnuc_dsp_mul); nuc_core's sum tree has clog2(parts + 1)
    levels, dpc_core registers its neighbour mask before its sum tree of
    clog2(DPC_SUM_LEAVES) levels, its product tree has clog2(parts); ``tb_top``'s
    ``reset_each_stage`` checks the top's latency against this model in simulation.
    """
    nuc = (["nuc_input"] + ["nuc_product"] * MUL_STAGES
           + ["nuc_sum"] * clog2(mul_parts(adc_bits, gain_bits) + 1)
           + ["nuc_round", "nuc_output"])
    num_bits, rec_bits = out_bits + 3, dpc_recip_shift(out_bits) + 1
    dpc = (["dpc_input", "dpc_window", "dpc_mask"] + ["dpc_sum"] * clog2(DPC_SUM_LEAVES)
           + ["dpc_multiply"] * MUL_STAGES
           + ["dpc_product"] * clog2(mul_parts(num_bits, rec_bits)) + ["dpc_output"])
    if top == "nuc_core":
        stages = nuc
    elif top == "dpc_core":
        stages = [*dpc, "flush"]
    elif top == "nuc_dpc_top":
        stages = ["top_input", *nuc, *dpc, "flush"]
    else:
        raise ValueError(f"no stage model for {top!r}; known: nuc_core, dpc_core, nuc_dpc_top")
    seen: dict[str, int] = {}
    out = []
    for s in stages:  # a stage of several registers: s_1, s_2, ...
        seen[s] = seen.get(s, 0) + 1
        out.append(f"{s}_{seen[s]}" if stages.count(s) > 1 else s)
    return out


# ---------------------------------------------------------------------------------------
# Generated SystemVerilog
# ---------------------------------------------------------------------------------------

BEGIN = "// irnuc-spec: begin (generated from irnuc.nuc_fixed.rtl_spec; do not edit)"
END = "// irnuc-spec: end"
#: Table sizes of the probe: operand widths of mul_chunks, output widths of dpc_recip_shift.
PROBE_MUL_BITS = 64
PROBE_OUT_BITS = 24


def _snake(name: str) -> str:
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower()


def _args(params: tuple[str, ...]) -> str:
    return ", ".join(f"input int unsigned {_snake(p)}" for p in params)


def _function(name: str, params: tuple[str, ...]) -> list[str]:
    """The head of a package function of the given width parameters (wrapped past 100
    characters)."""
    head = f"  function automatic int unsigned {name}("
    args = _args(params)
    if len(head) + len(args) + 2 <= 100:
        return [f"{head}{args});"]
    tails = [","] * (len(params) - 1) + [");"]
    return [head, *(f"    {a}{t}" for a, t in zip(args.split(", "), tails, strict=True))]


def _width_expr(width: str | int) -> str:
    return _snake(width) if isinstance(width, str) else f"32'd{width}"


def _layout_sv(lay: WordLayout) -> list[str]:
    params = lay.parameters
    lines = [f"  // ---- {lay.name}, version {lay.version}: {lay.doc}",
             "  // (fields from bit 0 up: "
             + ", ".join(f"{f.name} [{f.width}]" for f in lay.fields) + ")",
             *_function(f"{lay.name}_bits", params),
             "    return " + " + ".join(_width_expr(f.width) for f in lay.fields) + ";",
             "  endfunction"]
    for i, f in enumerate(lay.fields):
        below = lay.fields[:i]
        used = tuple(dict.fromkeys(b.width for b in below if isinstance(b.width, str)))
        expr = " + ".join(_width_expr(b.width) for b in below) or "32'd0"
        lines += [*_function(f"{lay.name}_{f.name}_lsb", used),
                  f"    return {expr};",
                  "  endfunction"]
    lines += ["  /* verilator lint_off DECLFILENAME */  // a class in the package",
              f"  virtual class {lay.name} #("]
    lines += [f"    parameter int unsigned {p} = 1" + ("," if j < len(params) - 1 else "")
              for j, p in enumerate(params)]
    lines += ["  );", "    typedef struct packed {"]
    for f in reversed(lay.fields):
        vec = "" if f.width == 1 else (f"[{f.width}-1:0] " if isinstance(f.width, str)
                                       else f"[{f.width - 1}:0] ")
        lines.append(f"      logic {vec}{f.name};  // {f.doc}")
    lines += ["    } word_t;", "  endclass", "  /* verilator lint_on DECLFILENAME */"]
    return lines


def sv_package_block() -> str:
    """The generated block of ``hdl/irnuc_pkg.sv``, markers included."""
    lines = [f"  {BEGIN}",
             "  // Each module uses some of these: no warning for the others.",
             "  /* verilator lint_off UNUSEDPARAM */", "  // ---- constants"]
    for c in CONSTANTS:
        decl = f"  localparam int unsigned {c.name} = {c.value};"
        # The comment beside the declaration when both fit a line, else above it.
        one = f"{decl}  // {c.doc}"
        lines += [one] if len(one) <= 100 else [f"  // {c.doc}", decl]
    lines.append("  // ---- legal parameter ranges (asserted by every module taking them)")
    for r in RANGES:
        lines.append(f"  localparam int unsigned {r.name}Min = {r.lo};")
        lines.append(f"  localparam int unsigned {r.name}Max = {r.hi};  // {r.unit}")
    for e in _lazy("ENUMS"):
        lines += [f"  // ---- {e.doc}", f"  typedef enum logic [{e.bits - 1}:0] {{"]
        for i, lit in enumerate(e.literals):
            sep = "," if i < len(e.literals) - 1 else ""
            lines.append(f"    {lit.name} = {e.bits}'d{lit.code}{sep}  // {lit.doc}")
        lines.append(f"  }} {e.name};")
        lines.append(f"  localparam int unsigned {e.count_name} = {len(e.literals)};")
    for lay in _lazy("LAYOUTS"):
        lines += _layout_sv(lay)
    lines += ["  /* verilator lint_on UNUSEDPARAM */", f"  {END}"]
    return "\n".join(lines) + "\n"


def replace_block(text: str, block: str) -> str:
    """``text`` with its generated block (markers included) replaced by ``block``."""
    start = text.find(f"  {BEGIN}")
    end = text.find(f"  {END}")
    if start < 0 or end < start:
        raise ValueError("no irnuc-spec markers in the package")
    return text[:start] + block + text[end + len(f"  {END}") + 1:]


#: Parameters of the probe (a subset of the pipeline's): the widths the layouts need.
PROBE_PARAMETERS: dict[str, int] = {"KneeBits": 16, "QuadBits": 16, "Tc1Bits": 16, "Tc2Bits": 16,
                                    "Tg1Bits": 16, "Tg2Bits": 16, "ReadingBits": 14,
                                    "Th1Bits": 18, "ThxBits": 18, "Th2Bits": 16,
                                    "HousingBits": 14,
                                    "GainIntBits": 2, "GainFracBits": 14, "OffsetIntBits": 12,
                                    "OffsetFracBits": 4, "OutBits": 14, "BaseBits": 16,
                                    "SumBits": 28, "DriftGainBits": 25}
#: Derived probe parameters that name layout widths.
_PROBE_DERIVED: dict[str, str] = {"GainBits": "GainIntBits + GainFracBits",
                                  "OffsetBits": "OffsetIntBits + OffsetFracBits"}


def probe_port(kind: str, name: str) -> str:
    """The probe's output port for a constant (``const``), a range end (``min``/``max``), an
    enum literal (``enum``) or an enum's literal count (``count``)."""
    return {"const": f"const_{_snake(name)}_o", "min": f"min_{_snake(name)}_o",
            "max": f"max_{_snake(name)}_o", "enum": f"enum_{name.lower()}_o",
            "count": f"count_{name}_o"}[kind]


def layout_port(lay: WordLayout, what: str, field: str = "") -> str:
    """Probe ports of a layout: ``word_i/word_o`` (a word in, the packed word out),
    ``field_i/field_o`` (a field in, a field of the word out), ``lsb`` and ``bits``."""
    return {"word_i": f"{lay.name}_word_i", "word_o": f"{lay.name}_word_o",
            "field_i": f"{lay.name}_{field}_i", "field_o": f"{lay.name}_{field}_o",
            "lsb": f"{lay.name}_{field}_lsb_o", "bits": f"{lay.name}_bits_o"}[what]


def sv_probe() -> str:
    """The whole simulation-only probe module ``irnuc_pkg_probe`` (cosim/hdl/)."""
    params = [f"  parameter int unsigned {k} = {v}," for k, v in PROBE_PARAMETERS.items()]
    derived = [f"  localparam int unsigned {k} = {v}," for k, v in _PROBE_DERIVED.items()]
    derived.append("  localparam int unsigned RecBits = dpc_recip_shift(OutBits) + 1")
    ports: list[str] = []
    body: list[str] = []
    for c in CONSTANTS:
        ports.append(f"  output logic [31:0] {probe_port('const', c.name)},")
        body.append(f"  assign {probe_port('const', c.name)} = 32'({c.name});")
    for r in RANGES:
        for end in ("min", "max"):
            ports.append(f"  output logic [31:0] {probe_port(end, r.name)},")
            body.append(f"  assign {probe_port(end, r.name)} = 32'({r.name}{end.title()});")
    for e in _lazy("ENUMS"):
        for lit in e.literals:
            ports.append(f"  output logic [{e.bits - 1}:0] {probe_port('enum', lit.name)},")
            body.append(f"  assign {probe_port('enum', lit.name)} = {lit.name};")
        ports.append(f"  output logic [7:0] {probe_port('count', e.name)},")
        ports.append(f"  output logic [31:0] {probe_port('const', e.count_name)},")
        body += [f"  assign {probe_port('const', e.count_name)} = 32'({e.count_name});",
                 f"  {e.name} {e.prefix}_any;",
                 f"  assign {e.prefix}_any = {e.literals[0].name};",
                 f"  assign {probe_port('count', e.name)} = 8'({e.prefix}_any.num());",
                 f"  logic unused_{e.prefix};",
                 f"  assign unused_{e.prefix} = ^{e.prefix}_any;  // num() is of the type"]
    for lay in _lazy("LAYOUTS"):
        args = ", ".join(lay.parameters)
        t = f"{lay.name}_t"
        bits = f"{lay.name}_bits({args})"
        ports += [f"  input  logic [{bits}-1:0] {layout_port(lay, 'word_i')},",
                  f"  output logic [{bits}-1:0] {layout_port(lay, 'word_o')},",
                  f"  output logic [7:0] {layout_port(lay, 'bits')},"]
        body += [f"  typedef {lay.name}#({args})::word_t {t};",
                 f"  {t} {lay.name}_packed, {lay.name}_unpacked;",
                 f"  assign {layout_port(lay, 'word_o')} = {lay.name}_packed;",
                 f"  assign {lay.name}_unpacked = {t}'({layout_port(lay, 'word_i')});",
                 f"  assign {layout_port(lay, 'bits')} = 8'($bits({t}));"]
        pack = []
        for f in lay.fields:
            vec = "" if f.width == 1 else f"[{f.width}-1:0] "
            used = ", ".join(dict.fromkeys(
                b.width for b in lay.fields[:lay.fields.index(f)] if isinstance(b.width, str)))
            ports += [f"  input  logic {vec}{layout_port(lay, 'field_i', f.name)},",
                      f"  output logic {vec}{layout_port(lay, 'field_o', f.name)},",
                      f"  output logic [7:0] {layout_port(lay, 'lsb', f.name)},"]
            pack.append(f"    {lay.name}_packed.{f.name} = {layout_port(lay, 'field_i', f.name)};")
            body += [f"  assign {layout_port(lay, 'field_o', f.name)} = "
                     f"{lay.name}_unpacked.{f.name};",
                     f"  assign {layout_port(lay, 'lsb', f.name)} = "
                     f"8'({lay.name}_{f.name}_lsb({used}));"]
        body += [f"  always_comb begin : p_pack_{lay.name}", f"    {lay.name}_packed = '0;",
                 *pack, "  end"]
    ports += [f"  output logic [{PROBE_MUL_BITS}:1][7:0] mul_chunks_o,",
              f"  output logic [{PROBE_OUT_BITS}:1][7:0] dpc_recip_shift_o,",
              "  input  logic [3:0] recip_n_i,",
              "  output logic [RecBits-1:0] recip_o"]
    body += [f"  for (genvar b = 1; b <= {PROBE_MUL_BITS}; b++) begin : gen_mul_chunks",
             "    assign mul_chunks_o[b] = 8'(mul_chunks(b));", "  end",
             f"  for (genvar b = 1; b <= {PROBE_OUT_BITS}; b++) begin : gen_recip_shift",
             "    assign dpc_recip_shift_o[b] = 8'(dpc_recip_shift(b));", "  end",
             "  // The DPC table as dpc_core builds it: constant calls of dpc_recip.",
             "  logic [8:0][RecBits-1:0] recip_table;",
             "  for (genvar n = 0; n <= 8; n++) begin : gen_recip",
             "    assign recip_table[n] = RecBits'(dpc_recip(OutBits, n));", "  end",
             "  assign recip_o = (recip_n_i <= 4'd8) ? recip_table[recip_n_i] : '0;"]
    head = ["// Simulation-only probe of hdl/irnuc_pkg.sv, generated from",
            "// irnuc.nuc_fixed.rtl_spec (python -m irnuc.cosim.spec_files --write); do not edit.",
            "// Every constant, range, enum literal and word layout of the package is on a port,",
            "// so that cocotb_tests/tb_pkg.py compares them with the Python side by simulation.",
            "// Not part of the design.",
            "module irnuc_pkg_probe", "  import irnuc_pkg::*;", "#("]
    return "\n".join([*head, *params, "  // Derived, do not override.", *derived, ") (",
                      *ports, ");", "", *body, "", "endmodule"]) + "\n"


def probe_values() -> dict[str, int]:
    """What the probe's constant, range and enum ports must read (port -> value)."""
    out = {probe_port("const", c.name): c.value for c in CONSTANTS}
    for r in RANGES:
        out[probe_port("min", r.name)] = r.lo
        out[probe_port("max", r.name)] = r.hi
    for e in _lazy("ENUMS"):
        out.update({probe_port("enum", lit.name): lit.code for lit in e.literals})
        out[probe_port("count", e.name)] = len(e.literals)
        out[probe_port("const", e.count_name)] = len(e.literals)
    return out


__all__ = [
    "COEF_WORD", "CONSTANTS", "DPC_RECIP_GUARD_BITS", "DPC_SUM_LEAVES", "FRAME_DIM_MAX",
    "MUL_CHUNK_BITS", "MUL_STAGES", "OVERFLOW", "OVERFLOW_MODES",
    "PIPELINE_RANGES", "RANGES", "REGISTER_CONSTANTS", "ROUNDING", "ROUNDING_MODES",
    "SUM_BITS_MAX", "Constant", "Enum", "EnumLiteral", "Field", "Range", "WordLayout", "clog2",
    "dpc_recip", "dpc_recip_shift", "mul_chunks", "mul_parts", "pipeline_stages",
    "sv_package_block", "sv_probe",
]
