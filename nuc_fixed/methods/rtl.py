"""The SystemVerilog written from the method registry (docs/architecture.md, "Generated
SystemVerilog").

``python -m irnuc.cosim.spec_files --write`` puts the text of this module into the design,
``--check`` (``tests/test_rtl_spec.py``) fails while any of it is stale:

* :func:`method_pkg_block`: the generated block of ``hdl/irnuc_method_pkg.sv``: per method
  the coefficient-stream and frame-word widths, the neutral words and the bad-flag mask
  (``unique case`` over ``method_e``, from ``MethodSpec.stream`` / ``frame_word``), the core
  kind of each method and the bases each stage's top composes with;
* :func:`header`: the parameter header of a top or a method front (the block between
  ``// irnuc-params: begin <module>`` and ``// irnuc-params: end``): ``parameter method_e
  Method``, the base widths and modes, the formats and parameters of the methods and stages
  the module takes (:data:`MODULES`), the derived widths; :func:`forward`: the parameters an
  instantiation passes on (``// irnuc-params: forward <module>``);
* :func:`frame_coefficients`: ``hdl/frame_coefficients.sv`` whole: ``method_e`` to the
  method's front, every front behind the same ports;
* :func:`slot_block`: irnuc_axis_top's frame word from the register slots
  (``// irnuc-params: frame`` .. ``end``).

A top's parameters stay scalars (``-G`` sets them); the names are those of
``cosim.sources.top_parameters``, from the same registry.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

from irnuc.nuc_fixed import methods, regmap
from irnuc.nuc_fixed.rtl_spec import WordLayout
from irnuc.nuc_fixed.spec import Block, FormatSpec, MethodSpec, ParamSpec, Word

BEGIN = "// irnuc-params: begin"
END = "// irnuc-params: end"
FORWARD = "// irnuc-params: forward"
FRAME = "// irnuc-params: frame"
PORTS = "// irnuc-params: ports"
GENERATED = "(generated from nuc_fixed.methods; do not edit)"


def snake(name: str) -> str:
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower()


def camel(name: str) -> str:
    return "".join(w[:1].upper() + w[1:] for w in name.split("_"))


#: The core kinds (``MethodSpec.core``) and their ``irnuc_method_pkg::core_kind_e``
#: literals, in the order of their codes.
CORE_KINDS = {"lin": "CoreLin", "quad": "CoreQuad", "pwl": "CorePwl"}


def literal(m: MethodSpec) -> str:
    """The ``method_e`` literal of a method (``MethodTcOffset``)."""
    return f"Method{camel(m.name)}"


# ---- parameters -----------------------------------------------------------------------------

@dataclass(frozen=True)
class SvParam:
    """One parameter of a header: ``parameter <type> <name> = <default>,  // <comment>``."""

    name: str
    type: str
    default: str
    comment: str = ""


_RND = "irnuc_pkg::rounding_e"
_OVF = "irnuc_pkg::overflow_e"
COEF = (SvParam("GainIntBits", "int unsigned", "2"), SvParam("GainFracBits", "int unsigned", "14"),
        SvParam("OffsetIntBits", "int unsigned", "12"),
        SvParam("OffsetFracBits", "int unsigned", "4"))
BASE = (SvParam("AdcBits", "int unsigned", "14"), *COEF, SvParam("OutBits", "int unsigned", "14"),
        SvParam("Rounding", "int unsigned", "1", _RND),
        SvParam("Overflow", "int unsigned", "0", _OVF),
        SvParam("MaxWidth", "int unsigned", "1024"), SvParam("MaxHeight", "int unsigned", "1024"))
_BASE_BY_NAME = {p.name: p for p in BASE}


def method_param() -> SvParam:
    plain = next(m for m in methods.BASES.values() if m.plain)
    return SvParam("Method", "method_e", literal(plain), "the base method (irnuc_pkg::method_e)")


def format_params(f: FormatSpec, modes: bool = True) -> list[SvParam]:
    out = [SvParam(f"{f.sv}IntBits", "int unsigned", str(f.sv_default[0])),
           SvParam(f"{f.sv}FracBits", "int unsigned", str(f.sv_default[1]))]
    if modes and "rounding" in f.rtl_modes:
        out.append(SvParam(f"{f.sv}Rounding", "int unsigned", "1", _RND))
    if modes and "overflow" in f.rtl_modes:
        out.append(SvParam(f"{f.sv}Overflow", "int unsigned", "0", _OVF))
    return out


def param_param(p: ParamSpec) -> SvParam:
    assert p.rtl is not None
    default = f"1'b{p.sv_default}" if p.rtl_type == "bit" else str(p.sv_default)
    return SvParam(p.rtl, p.rtl_type, default, p.doc)


def _part_params(part: methods.Part, scopes: Sequence[str]) -> list[SvParam]:
    """A method's or stage's parameters in these scopes: its readings', formats', own."""
    out: list[SvParam] = []
    for r in part.readings:
        out += [param_param(p) for p in methods.READINGS[r].params
                if p.rtl and p.rtl_scope in scopes]
    for f in part.formats:
        if f.rtl_scope in scopes:
            out += format_params(f)
    out += [param_param(p) for p in part.params if p.rtl and p.rtl_scope in scopes]
    return out


def _kind_formats() -> list[FormatSpec]:
    """The formats of the core kinds' coefficients beyond gain and offset (quad, knee,
    level): on the ports of every front."""
    return [f for m in methods.BASES.values() for f in m.formats if f.rtl_scope == "core"]


def _unique(params: Iterable[SvParam]) -> list[SvParam]:
    return list({p.name: p for p in params}.values())


@dataclass(frozen=True)
class ModuleSpec:
    """What a generated header holds.

    ``bases``: the methods whose front parameters the module takes (every method's core
    parameters come with any: the kinds' coefficients); ``stages``: the stages whose
    parameters it takes; ``flags``: the stages' ``bit`` flags (irnuc_axis_top builds the
    stage's top); ``wrapper``: the parameters only irnuc_axis_top needs; ``coef`` /
    ``frame``: the names of the stream widths (None: none); ``size``: the frame-size port
    widths (WidthBits, HeightBits).
    """

    name: str
    method: bool = True
    bases: str | tuple[str, ...] = "all"
    stages: tuple[str, ...] = ()
    flags: bool = False
    wrapper: bool = False
    coef: str | None = "CoefBits"
    frame: str | None = "FrameBits"
    size: bool = True
    doc: dict[str, str] = field(default_factory=dict)

    def base_specs(self) -> list[MethodSpec]:
        if self.bases == "all":
            return list(methods.BASES.values())
        return [methods.BASES[b] for b in self.bases]


def modules() -> dict[str, ModuleSpec]:
    """The tops with a generated header (their names are their files')."""
    out = [ModuleSpec("nuc_dpc_top", method=False, bases=(), coef=None, frame=None),
           ModuleSpec("method_dpc_top")]
    for s in methods.STAGES.values():  # each stage's top, and its part of the AXI core
        out.append(ModuleSpec(s.rtl_top, bases=s.rtl_bases, stages=(s.name,)))
        if s.rtl_wrapper:
            out.append(ModuleSpec(s.rtl_wrapper, bases=s.rtl_bases, stages=(s.name,),
                                  coef="WordBits"))
    out += [ModuleSpec("irnuc_axis_core", stages=tuple(methods.STAGES), flags=True,
                       coef="WordBits", frame="BaseFrameBits"),
            ModuleSpec("irnuc_axis_top", stages=tuple(methods.STAGES), flags=True,
                       wrapper=True, coef="WordBits", frame="BaseFrameBits")]
    return {m.name: m for m in out}


def top_params(spec: ModuleSpec) -> list[SvParam]:
    """The parameters of a top, in order: Method, the base, the methods', the stages'."""
    out = [method_param()] if spec.method else []
    out += list(BASE)
    if not spec.method:
        return out
    scopes = ("front", "core", "wrapper") if spec.wrapper else ("front", "core")
    for m in methods.BASES.values():
        if m in spec.base_specs():
            out += _part_params(m, scopes)
        else:  # the kinds' coefficient formats only (the fronts' port widths)
            out += [p for f in m.formats if f.rtl_scope == "core" for p in format_params(f)]
    for name in spec.stages:
        s = methods.STAGES[name]
        out += _part_params(s, ("front", "core", "wrapper", "stage"))
        if spec.flags:
            out.append(SvParam(s.rtl_flag, "bit", "1'b0", f"1: the core is {s.rtl_top}"))
    return _unique(out)


def front_params(m: MethodSpec) -> list[SvParam]:
    """The parameters of a method's front: the gain and offset formats, the kinds'
    coefficient formats (its ports), its own front parameters (its readings' where its
    words are sized by them: tc_offset's frame word holds the reading), UserBits."""
    out = list(COEF) + [p for f in _kind_formats() for p in format_params(f, modes=False)]
    out += [_BASE_BY_NAME[n] for n in m.rtl_base_params]
    sized = set(_args([m.stream, m.frame_word]))
    reading = {p.rtl for r in m.readings for p in methods.READINGS[r].params}
    out += [p for p in _part_params(m, ("front",)) if p.name not in reading or p.name in sized]
    out.append(SvParam("UserBits", "int unsigned", "1", "side band passed with the pixel"))
    return _unique(out)


def front_methods(module: str) -> list[MethodSpec]:
    """The base methods whose front is ``module``: one, or several sharing it, told apart
    by their ``rtl_front_flags`` (tc_offset and tc_housing: ``method_tc_offset``)."""
    return [m for m in methods.BASES.values() if m.rtl_module == module]


def shared_front_params(module: str) -> list[SvParam]:
    """The parameters of front ``module``: those of every method it serves, the 1-bit
    flags that tell them apart (default 0: the method without flags), UserBits."""
    ms = front_methods(module)
    out = [p for m in ms for p in front_params(m) if p.name != "UserBits"]
    out += [SvParam(f, "bit", "1'b0", f"1: {m.name}") for m in ms for f in m.rtl_front_flags]
    out.append(SvParam("UserBits", "int unsigned", "1", "side band passed with the pixel"))
    return _unique(out)


def _front_switch(ms: Sequence[MethodSpec], expr: Callable[[MethodSpec], str]) -> str:
    """``expr`` of the method a shared front's flags select (the one without flags when
    none is set)."""
    default = [m for m in ms if not m.rtl_front_flags]
    out = expr(default[0]) if default else "32'd1"
    for m in reversed([m for m in ms if m.rtl_front_flags]):
        cond = " && ".join(f"{f} != 0" for f in m.rtl_front_flags)
        out = f"({cond}) ? ({expr(m)}) : ({out})"
    return out


def dispatch_params() -> list[SvParam]:
    """frame_coefficients' parameters: Method and every front's."""
    out = [method_param()]
    for m in methods.BASES.values():
        out += [p for p in front_params(m) if p.name != "UserBits"]
    out.append(SvParam("UserBits", "int unsigned", "1", "side band passed with the pixel"))
    return _unique(out)


# ---- widths of the stream words ------------------------------------------------------------

def _part_bits(p: Word | Block) -> str:
    return f"{p.layout.name}_bits({', '.join(p.layout.parameters)})" if isinstance(p, Word) \
        else p.sv_bits


def stream_bits_expr(parts: Sequence[Word | Block]) -> str:
    """The width of a stream word in the top's names (one unused bit when empty)."""
    return " + ".join(_part_bits(p) for p in parts) or "32'd1"


def _args(parts_of: Iterable[Sequence[Word | Block]]) -> list[str]:
    """The width names the parts use, in first-use order (the functions' arguments)."""
    out: dict[str, None] = {}
    for parts in parts_of:
        for p in parts:
            names = p.layout.parameters if isinstance(p, Word) else \
                tuple(re.findall(r"\b[A-Z]\w*Bits\b", p.sv_bits))
            out.update(dict.fromkeys(names))
    return list(out)


def stream_args() -> list[str]:
    return _args(m.stream for m in methods.BASES.values())


def frame_args() -> list[str]:
    return _args(m.frame_word for m in methods.BASES.values())


def _snake_expr(expr: str) -> str:
    return re.sub(r"\b[A-Z]\w*Bits\b", lambda m_: snake(m_.group(0)), expr)


def _field_lsb(lay: WordLayout, name: str) -> str:
    i = next(k for k, f in enumerate(lay.fields) if f.name == name)
    used = dict.fromkeys(f.width for f in lay.fields[:i] if isinstance(f.width, str))
    return f"{lay.name}_{name}_lsb({', '.join(snake(u) for u in used)})"


def _positions(parts: Sequence[Word | Block], pick: str) -> list[str]:
    """The LSB expressions (function arguments' names) of the fields of the stream that are
    gains (``pick = "gain"``) or bad flags (``"bad"``)."""
    out, offset = [], []
    for p in parts:
        base = " + ".join(offset)
        if isinstance(p, Word):
            for f in p.layout.fields:
                if (pick == "gain" and f.name in ("gain", "gain_lo", "gain_hi")) or \
                        (pick == "bad" and f.name == "bad"):
                    lsb = _field_lsb(p.layout, f.name)
                    out.append(f"{base} + {lsb}" if base else lsb)
        elif pick == "gain" and p.gain:
            out.append(base or "32'd0")
        offset.append(_snake_expr(_part_bits(p)))
    return out


def _case(name: str, ret: str, args: list[str], cases: list[tuple[str, list[str]]],
          doc: list[str], local: tuple[str, str] | None = None) -> list[str]:
    """A package function: ``unique case (method)`` over every method, the last as default
    (``local``: a variable of the return type set first, (name, value))."""
    head = f"  function automatic {ret} {name}("
    params = ["input method_e     method", *(f"input int unsigned {a}" for a in args)]
    lines = [*(f"  // {d}" for d in doc), head]
    lines += [f"    {p}{',' if i < len(params) - 1 else ');'}" for i, p in enumerate(params)]
    width = max(len(c) for c, _ in cases) + 1
    if local is not None:
        lines += [f"    {ret.removeprefix('automatic ')} {local[0]};", f"    {local[0]} = {local[1]};"]
    lines.append("    unique case (method)")
    for i, (lit, body) in enumerate(cases):
        label = (lit + ":") if i < len(cases) - 1 else "default:"
        first, *rest = body
        head = f"      {label.ljust(width)} return "
        lines += wrap(head, first, ";" if not rest else "")
        for j, r in enumerate(rest):
            lines += wrap(" " * (len(head) - 2), r, ";" if j == len(rest) - 1 else "")
    lines += ["    endcase", "  endfunction", ""]
    return lines


def _or_terms(terms: list[str], zero: str) -> list[str]:
    return [terms[0], *(f"| {t}" for t in terms[1:])] if terms else [zero]


def method_pkg_block() -> str:
    """The generated block of ``hdl/irnuc_method_pkg.sv``, markers included."""
    bases = list(methods.BASES.values())
    sargs, fargs = stream_args(), frame_args()
    sa, fa = [snake(a) for a in sargs], [snake(a) for a in fargs]
    lines = [f"  {BEGIN} irnuc_method_pkg {GENERATED}",
             "  /* verilator lint_off UNUSEDSIGNAL */  // each method uses some arguments", ""]
    lines += _case("coef_stream_bits", "int unsigned", sa,
                   [(literal(m), [_snake_expr(stream_bits_expr(m.stream))]) for m in bases],
                   ["The coefficient stream word of each method (s_coef of method_dpc_top): its",
                    "memories' words concatenated, the first at bit 0 (MethodSpec.stream)."])
    lines += _case("frame_word_bits", "int unsigned", fa,
                   [(literal(m), [_snake_expr(stream_bits_expr(m.frame_word))]) for m in bases],
                   ["The frame word of each method (s_pix_frame_i, read with the frame's first",
                    "pixel; MethodSpec.frame_word): one unused bit where it has none."])
    one = ("one", "unity_gain(gain_int_bits, gain_frac_bits)")
    word = "logic [StreamWordMax-1:0]"
    lines += _case("neutral_stream_word", word, ["gain_int_bits", "gain_frac_bits", *sa],
                   [(literal(m), _or_terms([f"(one << ({p}))" for p in _positions(m.stream,
                                                                                 "gain")],
                                           "'0")) for m in bases],
                   ["The coefficient word of NUC off and of a filler pixel (irnuc_axis_top):",
                    "every gain field 1.0 (unity_gain), every other field 0."], one)
    lines += _case("stream_bad_mask", word, sa,
                   [(literal(m), _or_terms([f"(bit0 << ({p}))"
                                            for p in _positions(m.stream, "bad")], "'0"))
                    for m in bases],
                   ["The bits of the coefficient word that are bad flags."],
                   ("bit0", "StreamWordMax'(1)"))
    lines += _case("neutral_frame_word", word, ["gain_int_bits", "gain_frac_bits", *fa],
                   [(literal(m), _or_terms([f"(one << ({p}))" for p in
                                            _positions(m.frame_word, "gain")], "'0"))
                    for m in bases],
                   ["The frame word of NUC off: every gain field (one_point's gain) 1.0."], one)
    lines += ["  // The core kind of each method (MethodSpec.core): the sum core_sum and",
              "  // method_core form.",
              "  function automatic core_kind_e core_kind(input method_e method);",
              "    unique case (method)"]
    kinds = CORE_KINDS
    width = max(len(literal(m)) for m in bases) + 1
    for i, m in enumerate(bases):
        label = (literal(m) + ":") if i < len(bases) - 1 else "default:"
        lines.append(f"      {label.ljust(width)} return {kinds[m.core]};")
    lines += ["    endcase", "  endfunction", ""]
    lines += ["  // The plain method (MethodSpec.plain): without a stage, irnuc_axis_top builds it",
              "  // around nuc_dpc_top, the core of memory image version 1.",
              "  function automatic bit method_plain(input method_e method);",
              *wrap("    return ", " || ".join(f"method == {literal(m)}" for m in bases
                                             if m.plain) or "1'b0", ";"),
              "  endfunction", ""]
    lines += ["  // The methods whose front is a pipeline ending in flops (MethodSpec",
              "  // .rtl_front_registered: tc_poly, table_interp); the others pass through.",
              "  function automatic bit front_registered(input method_e method);",
              *wrap("    return ", " || ".join(f"method == {literal(m)}" for m in bases
                                             if m.rtl_front_registered) or "1'b0", ";"),
              "  endfunction", ""]
    for s in methods.STAGES.values():
        lines += [f"  // The base methods {s.rtl_top} composes {s.name} with (StageSpec.rtl_bases).",
                  f"  function automatic bit {s.name}_composes(input method_e method);",
                  *wrap("    return ", " || ".join(f"method == {literal(methods.BASES[b])}"
                                                for b in s.rtl_bases) or "1'b0", ";"),
                  "  endfunction", ""]
    lines += ["  /* verilator lint_on UNUSEDSIGNAL */", f"  {END}"]
    return "\n".join(lines) + "\n"


# ---- headers -----------------------------------------------------------------------------

def _derived_format(name: str, have: set[str]) -> str | None:
    """``KneeBits`` -> ``KneeIntBits + KneeFracBits`` where the module has those."""
    stem = name.removesuffix("Bits")
    if f"{stem}IntBits" in have and f"{stem}FracBits" in have:
        return f"{stem}IntBits + {stem}FracBits"
    return None


def _derived(names: Iterable[str], have: set[str], own: dict[str, str]) -> list[tuple[str, str]]:
    """Localparams for the width names the module uses and can form (in order)."""
    out = []
    for n in names:
        if n in have:
            continue
        expr = own.get(n) or _derived_format(n, have)
        if expr is not None:
            out.append((n, expr))
            have.add(n)
    return out


def _call(fn: str, first: str, args: list[str], have: set[str]) -> str:
    vals = [a if a in have else "32'd1" for a in args]
    return f"{fn}({', '.join([first, *vals])})"


def _split_top(expr: str) -> tuple[str, list[str], str] | None:
    """``f(a, b, c)`` -> (``f(``, [a, b, c], ``)``) when the whole expression is one call,
    else ``a + b + c`` -> ("", [a, "+ b", "+ c"], "") at the top level; None if neither."""
    def top_split(text: str, sep: str) -> list[str]:
        parts, depth, cur = [], 0, ""
        i = 0
        while i < len(text):
            ch = text[i]
            depth += ch in "([{"
            depth -= ch in ")]}"
            if depth == 0 and text.startswith(sep, i):
                parts.append(cur)
                cur = ""
                i += len(sep)
                continue
            cur += ch
            i += 1
        return [*parts, cur]

    m = re.match(r"^(\w+\()(.*)(\))$", expr)
    if m and len(top_split(m.group(2), ")")) == 1:  # the call's parenthesis ends the text
        args = top_split(m.group(2), ", ")
        if len(args) > 1:
            return m.group(1), [a + "," for a in args[:-1]] + [args[-1]], m.group(3)
    for op in (" || ", " | ", " + "):
        terms = top_split(expr, op)
        if len(terms) > 1:
            return "", [terms[0], *(f"{op.strip()} {t}" for t in terms[1:])], ""
    return None


def wrap(head: str, expr: str, tail: str, width: int = 100) -> list[str]:
    """``head + expr + tail`` on lines of at most ``width`` characters where it can be
    broken (the arguments of a call, the terms of a sum), continued under the expression."""
    line = head + expr + tail
    if len(line) <= width:
        return [line]
    split = _split_top(expr)
    if split is None:
        return [line]
    pre, items, post = split
    indent = " " * (len(head) + len(pre))
    out, cur = [], head + pre
    for i, item in enumerate(items):
        piece = item + (post + tail if i == len(items) - 1 else "")
        if cur.strip() and len(cur) + len(piece) + (0 if cur.endswith(("(", " ")) else 1) > width \
                and cur != head + pre:
            out.append(cur.rstrip())
            cur = indent + piece
        else:
            sep = "" if cur.endswith("(") or cur == head + pre else " "
            cur = cur + sep + piece
    out.append(cur)
    return out


def _param_lines(params: Sequence[SvParam], derived: Sequence[tuple[str, ...]],
                 last: bool) -> list[str]:
    width = max([len(p.name) for p in params] + [len(d[0]) for d in derived] + [16])
    tw = max([len(p.type) for p in params] + [len(d[2]) for d in derived if len(d) > 2] + [12])
    items: list[tuple[str, str]] = []
    for p in params:
        items.append((f"  parameter {p.type.ljust(tw)} {p.name.ljust(width)} = {p.default}",
                      p.comment))
    if derived:
        items.append(("  // Derived, do not override.", ""))
    for n, e, *typ in derived:
        t = typ[0] if typ else "int unsigned"
        items.append((f"  localparam {t.ljust(tw)} {n.ljust(width)} = \0{e}", ""))
    out = []
    real = [i for i, (t, _) in enumerate(items) if not t.lstrip().startswith("//")]
    for i, (text, comment) in enumerate(items):
        sep = "" if (last and i == real[-1]) or text.lstrip().startswith("//") else ","
        if "\0" in text:
            head, expr = text.split("\0")
            out += wrap(head, expr, sep)
            continue
        line = text + sep
        if comment and len(line) + len(comment) + 5 <= 100:
            line += f"  // {comment}"
        elif comment:
            out.append(f"  // {comment}")
        out.append(line)
    return out


def _module_derived(spec: ModuleSpec, params: list[SvParam]) -> list[tuple[str, ...]]:
    have = {p.name for p in params}
    own = {n: e for m in methods.BASES.values() for n, e in m.rtl_derived}
    out = [("GainBits", "GainIntBits + GainFracBits"),
           ("OffsetBits", "OffsetIntBits + OffsetFracBits")]
    have |= {"GainBits", "OffsetBits"}
    if spec.method:
        kinds = [f"{f.sv}Bits" for f in _kind_formats()]
        chosen_own = {n: e for m in spec.base_specs() for n, e in m.rtl_derived}
        out += _derived([*kinds, *stream_args(), *frame_args()], have,
                        {**own, **chosen_own} if spec.bases == "all" else chosen_own)
        if spec.coef:
            out.append((spec.coef, _call("coef_stream_bits", "Method", stream_args(), have)))
        if spec.frame:
            out.append((spec.frame, _call("frame_word_bits", "Method", frame_args(), have)))
    if spec.size:
        out += [("WidthBits", "$clog2(MaxWidth + 1)"), ("HeightBits", "$clog2(MaxHeight + 1)")]
    if spec.wrapper:  # the register slots' widths, and the stages' widths they use
        out += [d for s in spec.stages for d in methods.STAGES[s].rtl_derived]
        out += slot_widths()
        # The method's neutral words (NUC off, filler pixels; docs/integration.md).
        sargs = [a if a in have else "32'd1" for a in stream_args()]
        fargs = [a if a in have else "32'd1" for a in frame_args()]
        w, f = spec.coef, spec.frame
        out += [("NeutralWord", f"{w}'(neutral_stream_word(Method, GainIntBits, GainFracBits, "
                 f"{', '.join(sargs)}))", f"logic [{w}-1:0]"),
                ("BadMask", f"{w}'(stream_bad_mask(Method, {', '.join(sargs)}))",
                 f"logic [{w}-1:0]"),
                ("NeutralBaseFrame", f"{f}'(neutral_frame_word(Method, GainIntBits, "
                 f"GainFracBits, {', '.join(fargs)}))", f"logic [{f}-1:0]")]
    return out


def header(module: str, last: bool) -> str:
    """The generated header block of ``module`` (a top of :func:`modules` or a method's
    front), markers included; ``last``: nothing follows it in the parameter list."""
    ms = front_methods(module)
    if ms:
        params = shared_front_params(module)
        have = {p.name for p in params} | {"GainBits", "OffsetBits"}
        derived = [("GainBits", "GainIntBits + GainFracBits"),
                   ("OffsetBits", "OffsetIntBits + OffsetFracBits")]
        derived += _derived([f"{f.sv}Bits" for f in _kind_formats()], have, {})
        derived += _derived([*_args(m.stream for m in ms), *_args(m.frame_word for m in ms)],
                            have, {n: e for m in ms for n, e in m.rtl_derived})
        derived += [("CoefBits", _front_switch(ms, lambda m: stream_bits_expr(m.stream))),
                    ("FrameBits", _front_switch(ms, lambda m: stream_bits_expr(m.frame_word)))]
    else:
        spec = modules()[module]
        params = top_params(spec)
        derived = _module_derived(spec, params)
    body = _param_lines(params, derived, last)
    return "\n".join([f"  {BEGIN} {module} {GENERATED}", *body, f"  {END}"]) + "\n"


def parameters_of(module: str) -> list[str]:
    """The parameter names (not localparams) of a generated header."""
    if front_methods(module):
        return [p.name for p in shared_front_params(module)]
    if module == "frame_coefficients":
        return [p.name for p in dispatch_params()]
    return [p.name for p in top_params(modules()[module])]


def forward(target: str, have: Sequence[str], indent: str, last: bool,
            params: Sequence[str] | None = None) -> str:
    """The parameters an instantiation of ``target`` passes on: each of ``target``'s
    parameters (``params``, default its generated header's) the enclosing module declares
    (``have``), by name (UserBits, the side band, is each instance's own)."""
    names = [n for n in (parameters_of(target) if params is None else params)
             if n in have and n != "UserBits"]
    width = max([len(n) for n in names] + [1])
    lines = [f"{indent}{FORWARD} {target} {GENERATED}"]
    for i, n in enumerate(names):
        sep = "" if last and i == len(names) - 1 else ","
        lines.append(f"{indent}.{n.ljust(width)} ({n}){sep}")
    lines.append(f"{indent}{END}")
    return "\n".join(lines) + "\n"


# ---- the dispatch of the fronts ---------------------------------------------------------------

FRONT_PORTS = """  input  logic                  clk_i,
  input  logic                  rst_ni,
  // The pixel's coefficient word and its frame's word (read at sof by the top), side band.
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [CoefBits-1:0]   s_coef_i,
  input  logic [FrameBits-1:0]  s_frame_i,
  input  logic [UserBits-1:0]   s_user_i,
  // The coefficients of the core of the method's kind (core_sum's ports: lin gain, offset;
  // quad also quad; pwl gain (g_lo), gain_hi, knee, level; the others 0) and {user, bad}.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [GainBits-1:0]   m_gain_o,
  output logic [GainBits-1:0]   m_gain_hi_o,
  output logic [OffsetBits-1:0] m_offset_o,
  output logic [QuadBits-1:0]   m_quad_o,
  output logic [KneeBits-1:0]   m_knee_o,
  output logic [LevelBits-1:0]  m_level_o,
  output logic [UserBits:0]     m_user_o
"""
_FRONT_CONNECT = ("clk_i", "rst_ni", "s_valid_i", "s_ready_o", "s_coef_i", "s_frame_i",
                  "s_user_i", "m_valid_o", "m_ready_i", "m_gain_o", "m_gain_hi_o", "m_offset_o",
                  "m_quad_o", "m_knee_o", "m_level_o", "m_user_o")


def frame_coefficients() -> str:
    """``hdl/frame_coefficients.sv``: the configured method's front (``MethodSpec
    .rtl_module``), every front behind the same ports."""
    params = dispatch_params()
    have = {p.name for p in params} | {"GainBits", "OffsetBits"}
    derived = [("GainBits", "GainIntBits + GainFracBits"),
               ("OffsetBits", "OffsetIntBits + OffsetFracBits")]
    derived += _derived([f"{f.sv}Bits" for f in _kind_formats()], have, {})
    own = {n: e for m in methods.BASES.values() for n, e in m.rtl_derived}
    derived += _derived([*stream_args(), *frame_args()], have, own)
    derived += [("CoefBits", _call("coef_stream_bits", "Method", stream_args(), have)),
                ("FrameBits", _call("frame_word_bits", "Method", frame_args(), have))]
    lines = ["// The frame's coefficients of a pixel (nuc_fixed.method_top.frame_coefficients):",
             "// the configured method's front (hdl/method_<name>.sv, MethodSpec.rtl_module),",
             "// every front behind these ports: the pixel's coefficient word and its frame's",
             "// word in, the coefficients of the core of the method's kind and the pixel's bad",
             "// flag out (m_user_o = {s_user_i, bad}). A front that computes per frame",
             "// (tc_offset, table_interp) is a pipeline; the others pass through",
             "// combinationally (s_ready_o = m_ready_i, no state).",
             "//",
             "// Generated from the method registry (nuc_fixed.methods.rtl.frame_coefficients,",
             "// python -m irnuc.cosim.spec_files --write); do not edit.",
             "module frame_coefficients",
             "  import irnuc_pkg::*;",
             "  import irnuc_method_pkg::*;",
             "#(",
             *_param_lines(params, derived, True),
             ") (", f"  {PORTS} {GENERATED}", FRONT_PORTS.rstrip("\n"), f"  {END}", ");", "",
             "`ifndef SYNTHESIS",
             "  initial begin : p_param_ranges",
             "    assert (UserBits >= 1)",
             "      else $fatal(1, \"frame_coefficients: UserBits = %0d, at least 1\", UserBits);",
             "  end",
             "`endif", ""]
    bases = list(methods.BASES.values())
    for i, m in enumerate(bases):
        cond = f"if (Method == {literal(m)}) begin : gen_{m.name}"
        lines.append(f"  {cond}" if i == 0 else
                     f"  end else {cond}" if i < len(bases) - 1 else
                     f"  end else begin : gen_{m.name}")
        names = [p.name for p in front_params(m) if p.name != "UserBits"]
        width = max(len(n) for n in [*names, *m.rtl_front_flags, "UserBits"])
        lines.append(f"    {m.rtl_module} #(")
        lines += [f"      .{n.ljust(width)} ({n})," for n in names]
        lines += [f"      .{f.ljust(width)} (1'b1)," for f in m.rtl_front_flags]
        lines.append(f"      .{'UserBits'.ljust(width)} (UserBits)")
        lines.append("    ) u_front (")
        pw = max(len(p) for p in _FRONT_CONNECT)
        lines += [f"      .{p.ljust(pw)} ({p}){',' if k < len(_FRONT_CONNECT) - 1 else ''}"
                  for k, p in enumerate(_FRONT_CONNECT)]
        lines.append("    );")
    lines += ["  end", "", "endmodule"]
    return "\n".join(lines) + "\n"


# ---- irnuc_axis_top's frame word from the register slots ------------------------------------

def _slot_index() -> dict[str, int]:
    """Register name -> its slot of irnuc_axil_regs' slot_o (the map's 64-bit registers in
    map order)."""
    rmap = regmap.register_map()
    names = [r.config_register for r in rmap.registers if r.word == "lo"]
    return {n: k for k, n in enumerate(dict.fromkeys(names)) if n is not None}


def slot_block() -> str:
    """irnuc_axis_top's frame word of the configured method from its registers (the slots
    of irnuc_axil_regs) or, for a value the wrapper computes, the signal ``frame_<name>``
    (table_interp's weight from irnuc_axis_table)."""
    slots = _slot_index()
    lines = [f"  {FRAME} {GENERATED}"]
    bases = [m for m in methods.BASES.values()]
    first = True
    for m in bases:
        if not m.frame_word:
            continue
        lines.append(f"  {'if' if first else 'end else if'} (Method == {literal(m)}) begin : "
                     f"gen_frame_{m.name}")
        first = False
        parts = []
        for k, p in enumerate(m.frame_word):
            if isinstance(p, Word):
                t = f"{p.layout.name}#({', '.join(p.layout.parameters)})::word_t"
                lines.append(f"    {t} part{k};")
                for f in p.layout.fields:
                    w = f.width if isinstance(f.width, str) else str(f.width)
                    lines.append(f"    assign part{k}.{f.name} = {_slot_value(f.name, w, slots)};")
                parts.append(f"part{k}")
            else:
                parts.append(_slot_value(p.memory, p.sv_bits, slots))
        cat = parts[0] if len(parts) == 1 else "{" + ", ".join(reversed(parts)) + "}"
        lines.append(f"    assign base_frame = BaseFrameBits'({cat});")
    lines += ["  end else begin : gen_frame_none", "    assign base_frame = '0;", "  end",
              f"  {END}"]
    return "\n".join(lines) + "\n"


def _slot_value(name: str, width: str, slots: dict[str, int]) -> str:
    if name in slots:
        return f"slots[{slots[name]}][{width}-1:0]"
    return f"frame_{name}"


def slot_widths() -> list[tuple[str, str]]:
    """irnuc_axis_top's register-slot widths: (parameter, expression): the width where the
    configured method or a built stage has the slot's register, else its ``absent``."""
    out = []
    for s in methods.all_slots():
        conds = []
        for m in methods.BASES.values():
            has = s in m.slots or any(methods.READINGS[r].slot == s for r in m.readings)
            if has:
                conds.append(f"Method == {literal(m)}")
        for st in methods.STAGES.values():
            if s in st.slots:
                conds.append(f"{st.rtl_flag}")
        cond = " || ".join(conds) or "1'b0"
        out.append((s.param, f"({cond}) ? {s.sv_width} : {s.absent}"))
        if s.count:
            out.append((s.count, f"({cond}) ? {s.sv_count} : 0"))
    return out


# ---- the generated blocks in the design's files ---------------------------------------------

_DECL = re.compile(r"\b(?:parameter|localparam)\b[^=;()]*?\b([A-Z]\w*)\s*=")


def declared(text: str) -> list[str]:
    """The parameters and localparams a module's text declares (by name)."""
    return list(dict.fromkeys(_DECL.findall(text)))


def module_parameters(module: str, hdl_dir: object) -> list[str]:
    """The parameters (not localparams) of ``module``: its generated header's, or those
    its file ``<hdl_dir>/<module>.sv`` declares."""
    from pathlib import Path

    if module in modules() or module == "frame_coefficients" or \
            module in {m.rtl_module for m in methods.BASES.values()}:
        return parameters_of(module)
    text = (Path(str(hdl_dir)) / f"{module}.sv").read_text()
    text = re.sub(r"//[^\n]*", "", text)
    head = text[re.search(rf"\bmodule\s+{module}\b", text).end():]
    if "#(" not in head.split(");")[0]:
        return []
    start = end = head.index("#(") + 1
    depth = 1
    while depth:  # to the parenthesis closing #(
        end += 1
        depth += {"(": 1, ")": -1}.get(head[end], 0)
    head = head[start:end]
    return re.findall(r"\bparameter\b[^=;()]*?\b([A-Z]\w*)\s*=", head)


def fill(text: str, hdl_dir: object) -> str:
    """``text`` (a design file) with every generated block rewritten: the headers
    (``begin <module>``), the forwarded parameter lists (``forward <module>``: the target's
    parameters the file's module declares, by name), the method fronts' port list
    (``ports``) and irnuc_axis_top's frame word (``frame``)."""
    out: list[str] = []
    lines = text.splitlines(keepends=True)
    i = 0
    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        kind = next((k for k in (BEGIN, FORWARD, FRAME, PORTS) if stripped.startswith(k)),
                    None)
        if kind is None:
            out.append(line)
            i += 1
            continue
        j = i + 1
        while not lines[j].strip().startswith(END):
            j += 1
        after = "".join(lines[j + 1:]).lstrip()
        last = after.startswith(")")
        indent = line[: len(line) - len(line.lstrip())]
        name = stripped[len(kind):].split()[0] if kind in (BEGIN, FORWARD) else ""
        if kind == BEGIN:
            block = method_pkg_block() if name == "irnuc_method_pkg" else header(name, last)
        elif kind == FRAME:
            block = slot_block()
        elif kind == PORTS:
            block = f"  {PORTS} {GENERATED}\n{FRONT_PORTS}  {END}\n"
        else:
            have = declared("".join(out))
            block = forward(name, have, indent, last, module_parameters(name, hdl_dir))
        out.append(block)
        i = j + 1
    return "".join(out)


__all__ = [
    "BASE",
    "BEGIN",
    "COEF",
    "CORE_KINDS",
    "END",
    "FORWARD",
    "FRAME",
    "FRONT_PORTS",
    "ModuleSpec",
    "SvParam",
    "declared",
    "dispatch_params",
    "fill",
    "forward",
    "frame_coefficients",
    "front_params",
    "header",
    "literal",
    "method_pkg_block",
    "module_parameters",
    "modules",
    "parameters_of",
    "slot_block",
    "slot_widths",
    "top_params",
]
