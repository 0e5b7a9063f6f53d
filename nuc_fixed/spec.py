"""The types of the correction-method registry (``nuc_fixed/methods``, docs/architecture.md
"Correction methods: one registry").

A base method is a :class:`MethodSpec`, a stage a :class:`StageSpec`: frozen dataclasses
whose fields are what the method *is* (its formats, parameters, readings, core kind, RTL
front and stream words) and whose methods are what it *does* in each layer (its memories
and registers for a configuration, its golden per-frame coefficients, fit, widths, coverage
bins and stimulus hints). Each method is one module of ``nuc_fixed/methods`` holding one
subclass and its instance; the layers loop over the registry and never compare names.

The memory and register layouts (:class:`CoeffFormat`, :class:`Field`,
:class:`MemoryLayout`, :class:`Register`) live here too: a configuration's
(``PipelineConfig.memories`` / ``registers``) are built by the methods from them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.common import schema
from irnuc.nuc_fixed.rtl_spec import WordLayout

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.cores import CoreResult
    from irnuc.nuc_fixed.method_top import MethodCoefficients
    from irnuc.nuc_fixed.widths import InputX, W

#: The per-frame readings of a frame by name (``{"fpa": 8123}``): the golden model's
#: argument wherever a method's per-frame values depend on them.
Frame = Mapping[str, int]
#: Coverage bins hit by a frame: {coverpoint: {bin, ...}}.
Classes = dict[str, set[str]]
#: Coverpoints {name: bins} and removed bins {name: {bin: reason}}.
Points = tuple[dict[str, tuple[str, ...]], dict[str, dict[str, str]]]


def sv_name(text: str) -> str:
    """``drift_gain`` -> ``DriftGain``: the SystemVerilog spelling of a Python name."""
    return "".join(p[:1].upper() + p[1:] for p in text.replace(".", "_").split("_") if p)


# ---- formats, memory words, registers ---------------------------------------------------

@dataclass(frozen=True)
class CoeffFormat:
    """The fixed-point format of one coefficient (``docs/datapath.md``, "Formats").

    ``int_bits`` includes the sign bit of a signed format. ``rounding`` is how a value is
    brought to this format (by calibration for a stored coefficient, by the datapath for
    a computed one), ``overflow`` what happens outside its range.
    """

    name: str
    int_bits: int
    frac_bits: int
    signed: bool
    rounding: str = "half_even"
    overflow: str = "saturate"

    @property
    def bits(self) -> int:
        return self.int_bits + self.frac_bits

    def __str__(self) -> str:
        return f"{'S' if self.signed else 'U'}{self.int_bits}.{self.frac_bits}"

    def to_dict(self) -> dict[str, object]:
        return {"int_bits": self.int_bits, "frac_bits": self.frac_bits, "signed": self.signed,
                "rounding": self.rounding, "overflow": self.overflow}


@dataclass(frozen=True)
class Field:
    """One field of a memory word: bits ``[lsb + width - 1 : lsb]``."""

    name: str
    lsb: int
    width: int
    signed: bool
    format: str  # "U2.14", "S12.4", "flag", ...

    @property
    def msb(self) -> int:
        return self.lsb + self.width - 1


@dataclass(frozen=True)
class MemoryLayout:
    """A per-pixel memory: one word per pixel, raster order.

    ``source`` is ``calibration`` (written by ``irnuc calibrate`` into a memory image) or
    ``runtime`` (written by the hardware, e.g. the FFC accumulator; starts at zero).
    ``reads_per_frame`` is how many words per pixel each frame reads from the memories of
    this kind (table_interp reads two of its K tables).
    """

    name: str
    fields: tuple[Field, ...]
    source: str = "calibration"
    reads_per_frame: int = 1

    @property
    def word_bits(self) -> int:
        return sum(f.width for f in self.fields)

    def field(self, name: str) -> Field:
        for f in self.fields:
            if f.name == name:
                return f
        raise KeyError(name)

    def to_dict(self) -> dict[str, object]:
        return {"word_bits": self.word_bits, "source": self.source,
                "fields": {f.name: {"msb": f.msb, "lsb": f.lsb, "width": f.width,
                                    "signed": f.signed, "format": f.format}
                           for f in self.fields}}


def memory(name: str, spec: list[tuple[str, int, bool, str]], **kw: Any) -> MemoryLayout:
    """A memory from (field, width, signed, format text), bit 0 first."""
    out, lsb = [], 0
    for fname, width, signed, fmt in spec:
        out.append(Field(fname, lsb, width, signed, fmt))
        lsb += width
    return MemoryLayout(name, tuple(out), **kw)


def word_memory(word: WordLayout, name: str, cfg: PipelineConfig, **kw: Any) -> MemoryLayout:
    """A memory whose word is the spec's layout ``word`` (``rtl_spec``), every field's width
    and sign those of its coefficient format in ``cfg`` (``flag`` fields: one bit)."""
    spec = []
    for f in word.fields:
        if f.format:
            c = cfg.format(f.format)
            spec.append((f.name, c.bits, c.signed, str(c)))
        else:
            spec.append((f.name, int(f.width), False, "flag"))
    return memory(name, spec, **kw)


@dataclass(frozen=True)
class Register:
    """A global register (one value, or ``count`` values, per camera or per frame)."""

    name: str
    width: int
    signed: bool
    format: str
    count: int = 1
    source: str = "calibration"  # or "runtime" (per frame, from the frame's fields)
    meaning: str = ""


@dataclass(frozen=True)
class RegisterSlot:
    """A method register's slot in irnuc_axil_regs: the width parameter ``param``
    (``GainRegBits``) holds the width of ``register`` where the configuration has it, else
    ``absent``; ``count`` (``TableReadings``) its count. ``sv_width`` / ``sv_count`` are
    their SystemVerilog expressions in a top (for the generated slot widths)."""

    param: str
    register: str
    sv_width: str
    absent: int = 0
    count: str = ""
    sv_count: str = ""


# ---- what a method declares ---------------------------------------------------------------

@dataclass(frozen=True)
class FormatSpec:
    """A named coefficient format (``formats.<name>`` of a pipeline).

    ``computed``: a value the datapath computes (its rounding and overflow are datapath
    modes; a stored coefficient always saturates). ``rtl_modes``: which of ``rounding`` and
    ``overflow`` the RTL takes as ``<Name>Rounding`` / ``<Name>Overflow``. ``sv_default``:
    the RTL parameters' defaults (int bits, frac bits). ``rtl_scope``: which RTL needs its
    parameters (``front``: the method's front; ``core``: the core of its kind, e.g.
    quad_core's quadratic term, also on every front's ports; ``wrapper``: only
    irnuc_axis_top; a stage's: its top).
    """

    name: str
    signed: bool
    meaning: str
    computed: bool = False
    rtl_modes: tuple[str, ...] = ()
    sv_default: tuple[int, int] = (1, 0)
    rtl_scope: str = "front"

    @property
    def sv(self) -> str:
        """The SystemVerilog prefix: ``DriftGain`` (``DriftGainIntBits``, ...)."""
        return sv_name(self.name)


@dataclass(frozen=True)
class ParamSpec:
    """A method parameter: a ``PipelineConfig`` field and its SystemVerilog parameter.

    ``schema`` is the field's JSON schema (its range and unit), ``rtl`` the RTL
    parameter (None: not one), ``rtl_type`` its SystemVerilog type (``int unsigned`` or
    ``bit``), ``to_rtl`` the value the RTL gets (default ``int(value)``), ``rtl_scope``
    which RTL needs it (as :class:`FormatSpec`).
    """

    field: str
    schema: Mapping[str, Any]
    doc: str
    rtl: str | None = None
    rtl_type: str = "int unsigned"
    sv_default: int = 0
    to_rtl: Callable[[Any], int] = int
    rtl_scope: str = "front"

    @classmethod
    def range(cls, field_: str, lo: int, hi: int, unit: str, doc: str, rtl: str | None,
              sv_default: int, rtl_scope: str = "front") -> ParamSpec:
        return cls(field_, schema.number(lo, hi, integer=True, unit=unit), doc, rtl,
                   sv_default=sv_default, rtl_scope=rtl_scope)


@dataclass(frozen=True)
class ReadingSpec:
    """A per-frame reading a method or stage takes (``fpa``, ``blind``, ``shutter``).

    ``frame_field`` is the frame file's field (``fpa_reading``), ``inputs_field`` the
    :class:`~irnuc.nuc_fixed.method_top.FrameInputs` attribute, ``params`` the parameters it
    brings (``reading_bits``), ``register`` its runtime register (the value the RTL latches
    per frame) for a configuration, ``slot`` that register's slot in irnuc_axil_regs.
    """

    name: str
    frame_field: str
    inputs_field: str
    doc: str
    params: tuple[ParamSpec, ...] = ()
    register: Callable[[PipelineConfig], Register] | None = None
    slot: RegisterSlot | None = None


@dataclass(frozen=True)
class Word:
    """A part of a stream word: the spec layout ``layout`` (one of the method's memories,
    ``memory``), its width parameters bound to the top's localparams of the same name."""

    memory: str
    layout: WordLayout

    @property
    def sv_args(self) -> tuple[str, ...]:
        return self.layout.parameters


@dataclass(frozen=True)
class Block:
    """A part of a stream word with no fields the wrapper needs: ``memory`` (a memory, a
    register or a reading of the method) ``sv_bits`` wide (a localparam of the top), gain
    ``gain``: the field is a gain (the neutral word sets it to 1.0)."""

    memory: str
    sv_bits: str
    gain: bool = False


StreamPart = Word | Block


# ---- what a base method and a stage share --------------------------------------------------

@dataclass(frozen=True)
class PartSpec:
    """What a base method and a stage both declare: ``name``, ``doc`` (one line),
    ``formats`` and ``params`` (those it may use), ``readings`` (the per-frame readings it
    takes, by name), ``layouts`` (its memory and frame words, generated into ``irnuc_pkg``),
    ``rtl_files`` (the RTL files it needs beyond the packages, in dependency order),
    ``rtl_derived`` (SystemVerilog localparams: (name, expression)), ``slots`` (its
    registers' slots in the register file); and what it does to a configuration: the formats
    and parameters it uses, its checks, memories, registers and widths."""

    name: str
    doc: str
    formats: tuple[FormatSpec, ...] = ()
    params: tuple[ParamSpec, ...] = ()
    readings: tuple[str, ...] = ()
    layouts: tuple[WordLayout, ...] = ()
    rtl_files: tuple[str, ...] = ()
    rtl_derived: tuple[tuple[str, str], ...] = ()
    slots: tuple[RegisterSlot, ...] = ()

    def used_formats(self, cfg: PipelineConfig) -> tuple[str, ...]:
        """The names in ``formats`` a configuration uses."""
        return tuple(f.name for f in self.formats)

    def used_params(self, cfg: PipelineConfig) -> tuple[str, ...]:
        """The parameters a configuration must set."""
        return tuple(p.field for p in self.params)

    def check(self, cfg: PipelineConfig, src: str) -> None:
        """Checks beyond the schema (ConfigError naming ``src``)."""

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        """Its per-pixel memories for ``cfg``, in order."""
        return []

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        """Its registers for ``cfg`` (the readings' come from the readings)."""
        return []

    def widths(self, cfg: PipelineConfig) -> dict[str, W | int]:
        """Its intermediate widths beyond the core's, by dotted name (docs/datapath.md)."""
        return {}


# ---- a frame's coefficients as expressions (the fused golden path) ------------------------

@dataclass(frozen=True)
class Term:
    """One term of a :class:`CoefExpr`: ``field * mul << shift``.

    ``field``: per-pixel codes (H, W), or None for the constant 1 (a register, a frame's
    value); ``fmt``: the format whose code range the field's codes (or, without a field,
    ``mul``) must lie in (checked before any work), None: unchecked (a frame's factor).
    """

    field: np.ndarray | None
    mul: int = 1
    shift: int = 0
    fmt: str | None = None


@dataclass(frozen=True)
class CoefExpr:
    """One per-pixel coefficient of a frame, as the fused kernels compute it:
    ``c = CLAMP(base + ROUND_k(sum of terms), lo, hi)`` (``k = round_bits``, ROUND by
    ``rounding``; no ``base``: 0; ``lo``/``hi`` None: no clamp). A stored code is one term
    (:meth:`of`); tc_offset's polynomial is three terms, rounded and saturated;
    table_interp's interpolation two, rounded, plus the lower table as ``base``."""

    terms: tuple[Term, ...]
    round_bits: int = 0
    rounding: str = "truncate"
    base: Term | None = None
    lo: int | None = None
    hi: int | None = None

    @classmethod
    def of(cls, value: Any, fmt: str) -> CoefExpr:
        """The codes ``value`` as they are: per-pixel codes (H, W), or one value."""
        a = np.asarray(value)
        if a.ndim:
            return cls((Term(a, fmt=fmt),))
        if not np.issubdtype(a.dtype, np.integer):
            raise TypeError(f"coefficient {fmt!r} is {value!r}; integer codes are required")
        return cls((Term(None, int(a), fmt=fmt),))


@dataclass(frozen=True)
class FrameExpressions:
    """A frame's coefficients for the fused path: the core's inputs by name (those of
    :meth:`MethodSpec.frame_coefficients`) as :class:`CoefExpr`, and the frame's bad
    flags (the DPC's): a map, or maps whose OR it is (table_interp's pair)."""

    coefs: dict[str, CoefExpr]
    bad: np.ndarray | tuple[np.ndarray, ...]


# ---- the base method ----------------------------------------------------------------------

@dataclass(frozen=True)
class MethodSpec(PartSpec):
    """A base correction method (one datapath per pixel).

    Beyond :class:`PartSpec`: ``core`` (the core kind: ``lin``, ``quad`` or ``pwl``;
    ``nuc_fixed.cores.CORES``), ``scenes`` (calibration scenes it needs), ``stream`` /
    ``frame_word`` (its RTL stream words, bit 0 first), ``rtl_module`` (its front,
    ``hdl/<rtl_module>.sv``), ``rtl_checked`` (the modules its datapath is checked in on its
    own), ``rtl_base_params`` (base parameters its front takes beyond the gain and offset
    formats: tc_offset's ``Rounding``), ``rtl_front_registered`` (its front is a pipeline
    whose outputs are flops: tc_offset's, table_interp's; the others pass through),
    ``corner_registers`` (registers the corner stimulus puts at 0 and their largest code),
    ``plain`` (the configuration without stages is the plain two-point NUC: memory image
    version 1, ``nuc_dpc_top``), ``rtl_front_flags`` (the 1-bit parameters its instance of
    a front it shares with another method sets, each to 1: tc_housing is tc_offset's front
    with ``Housing``; the front declares them, default 0). Its memories (the first holds the
    bad flags) it must give.
    """

    core: str = "lin"
    scenes: int = 2
    stream: tuple[StreamPart, ...] = ()
    frame_word: tuple[StreamPart, ...] = ()
    rtl_module: str = ""
    rtl_checked: tuple[str, ...] = ()
    rtl_base_params: tuple[str, ...] = ()
    rtl_front_registered: bool = False
    corner_registers: tuple[str, ...] = ()
    plain: bool = False
    rtl_front_flags: tuple[str, ...] = ()

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        """Its per-pixel memories for ``cfg``, in order (the first holds the bad flags)."""
        raise NotImplementedError

    # ---- golden model ----------------------------------------------------------------
    def check_coefficients(self, c: MethodCoefficients) -> None:
        """Checks of a calibration beyond the memories' and registers' ranges."""

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        """The per-pixel coefficient codes (and the registers) the core of its kind takes
        in a frame with these readings (lin: gain, offset; quad: + quad; pwl: gain_lo,
        gain_hi, knee, level), and every method the frame's bad flags ``bad`` (the DPC's;
        table_interp: the OR of the pair's)."""
        raise NotImplementedError

    def frame_expressions(self, c: MethodCoefficients, frame: Frame) -> FrameExpressions:
        """The same coefficients as expressions the fused kernels evaluate per pixel in
        the pass that corrects the frame (``nuc_fixed.fused``). By default the codes of
        :meth:`frame_coefficients` as they are; a method computing them per frame
        (tc_offset, table_interp) gives its formula, which must equal
        :meth:`frame_coefficients` bit for bit (tests/test_fused.py)."""
        from irnuc.nuc_fixed.cores import CORE_INPUTS

        fc = self.frame_coefficients(c, frame)
        return FrameExpressions({n: CoefExpr.of(fc[n], fmt) for n, fmt in CORE_INPUTS[self.core]},
                                fc["bad"])

    # ---- calibration -------------------------------------------------------------------
    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        """Fit its coefficients on the points' per-pixel means ``means`` (P, S, H, W) to
        the targets ``t`` and quantize them with ``q`` (``nuc_fixed.fit``)."""
        raise NotImplementedError

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        """Its real-valued output for (drift-corrected) raw ``x`` with the float fit ``f``."""
        raise NotImplementedError

    # ---- RTL streams -------------------------------------------------------------------
    def frame_fields(self) -> tuple[str, ...]:
        """The frame word's fields, bit 0 first (each a register, a reading's register or a
        value :meth:`frame_values` computes)."""
        return tuple(n for p in self.frame_word
                     for n in ([f.name for f in p.layout.fields] if isinstance(p, Word)
                               else [p.memory]))

    def frame_values(self, cfg: PipelineConfig, values: Mapping[str, Any]) -> dict[str, int]:
        """The frame word's fields from the calibration registers and the readings'
        registers (``reading``) by name."""
        return {n: int(values[n]) for n in self.frame_fields()}

    def stream_words(self, c: MethodCoefficients, frame: Frame
                     ) -> tuple[list[tuple[np.ndarray, int]], Any]:
        """The memory words of the coefficient stream word, bit 0 first, as (uint64 words
        (H, W), bits), for a frame with these readings, and per-frame data the frame word
        needs (None)."""
        words = c.words()
        return [(words[name], m.word_bits) for name, m in self.stream_memories(c.cfg)], None

    def stream_key(self, c: MethodCoefficients, frame: Frame) -> Any:
        """What decides the coefficient stream of a frame (its image in the bulk harness):
        one image for every frame by default."""
        return None

    def stream_memories(self, cfg: PipelineConfig) -> list[tuple[str, MemoryLayout]]:
        """The memories of the coefficient stream word, bit 0 first, each by its stream name
        and layout."""
        mems = cfg.memories
        return [(p.memory, mems[p.memory]) for p in self.stream if p.memory in mems]

    def from_frame_word(self, cfg: PipelineConfig, fields: dict[str, dict[str, np.ndarray]],
                        values: Mapping[str, int]
                        ) -> tuple[dict[str, dict[str, np.ndarray]], dict[str, Any]] | None:
        """A frame's memories and register values (the readings' registers included) from
        its stream word's memories (``fields``) and its frame word's fields (``values``),
        when they are not the fields themselves (None): the inverse of
        :meth:`frame_values` where that computes."""
        return None

    def dma_images(self, c: MethodCoefficients) -> dict[str, bytes]:
        """Images beyond the memories that ``irnuc calibrate`` writes for a DMA."""
        return {}

    # ---- verification ------------------------------------------------------------------
    def coverage_points(self, cfg: PipelineConfig) -> Points:
        """Its coverpoints {name: bins} and the removed bins {name: {bin: reason}}."""
        return {}, {}

    def coverage_classes(self, c: MethodCoefficients, raw: np.ndarray, frame: Frame,
                         res: CoreResult) -> Classes:
        """The bins of its coverpoints one frame hits (``res``: the core on the frame)."""
        return {}

    def axis_points(self, cfg: PipelineConfig) -> dict[str, tuple[str, ...]]:
        """Coverpoints of its own part of ``irnuc_axis_top`` without a stage (replacing the
        wrapper's stream points; none by default)."""
        return {}

    def reading_marks(self, c: MethodCoefficients) -> list[int]:
        """The readings where its per-frame values change behaviour (stimulus)."""
        return []

    def housing_marks(self, c: MethodCoefficients) -> list[int]:
        """The housing readings where its per-frame values change behaviour (stimulus; a
        method that takes the ``housing`` reading)."""
        return []

    def draw_register(self, r: Register, rng: np.random.Generator, lo: int, hi: int
                      ) -> object | None:
        """A random value of a calibration register with a shape of its own (None: any
        code in [lo, hi])."""
        return None

    def check_readings(self, cfg: PipelineConfig, readings: list[int], reference: int,
                       source: str, sensor: str) -> None:
        """Refuse FPA readings of the calibration points (one per FPA point) it cannot
        calibrate from (``nuc_fixed.fit.check_readings``); a method without a reading
        takes any."""

    def check_plan(self, cfg: PipelineConfig, plan: Any, source: str) -> None:
        """Refuse a calibration plan (``nuc_fixed.plan.CalibrationPlan``) it cannot
        calibrate from, before the simulation (tc_housing: without housing offsets); any
        plan by default."""

    def corner(self, c: MethodCoefficients, raw: np.ndarray, rng: np.random.Generator,
               index: int) -> None:
        """Put some pixels of corner frame ``index`` on its breakpoints (in place)."""


# ---- the stages ---------------------------------------------------------------------------

@dataclass(frozen=True)
class StageSpec(PartSpec):
    """A stage composed with a base method (``two_point+ffc``).

    Beyond :class:`PartSpec`: ``place`` (where it acts: ``input``, on the core's input;
    ``sum``, a term of the core's sum), ``bases`` (the base methods the golden model
    composes it with; None: every one), ``rtl_bases`` (those its RTL top ``rtl_top``
    implements), ``excludes`` (stages it does not go with), ``rtl_flag`` (irnuc_axis_top's
    ``bit`` parameter building its top), ``rtl_wrapper`` (the module of irnuc_axis_top's
    core holding its top: irnuc_axis_ffc).
    """

    place: str = "sum"
    bases: tuple[str, ...] | None = None
    rtl_bases: tuple[str, ...] = ()
    excludes: tuple[str, ...] = ()
    rtl_top: str = ""
    rtl_flag: str = ""
    rtl_wrapper: str = ""

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, good: np.ndarray,
            q: Any) -> None:
        """Fit and quantize its calibration registers (after the base method's)."""

    def input_x(self, cfg: PipelineConfig) -> InputX | None:
        """The core's input after this stage (``place == "input"``)."""
        return None


__all__ = ["Block", "Classes", "CoeffFormat", "Field", "FormatSpec", "Frame", "MemoryLayout",
           "MethodSpec", "ParamSpec", "PartSpec", "Points", "ReadingSpec", "Register",
           "RegisterSlot",
           "StageSpec", "StreamPart", "Word", "memory", "sv_name", "word_memory"]
