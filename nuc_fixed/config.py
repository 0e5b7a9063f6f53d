"""Pipeline configurations: the named ones of ``nuc_fixed/pipelines.toml`` and user files.

This is the single reader of those files: the golden model, the RTL build (which turns a
configuration into Verilator ``-G`` parameters with :meth:`PipelineConfig.rtl_parameters`)
and the tests all go through :func:`load_pipeline`. Every field is checked against
:data:`PIPELINE_SCHEMA` (unknown fields are refused with the nearest known name). Widths
derived from a configuration are properties here and nowhere else; ``docs/datapath.md``
defines them.

A configuration names its correction ``method`` (``docs/methods.md``): a base method
(:data:`BASE_METHODS`, default ``two_point``) optionally followed by stages
(:data:`STAGES`), written ``"two_point+blind_drift"``. The base fields (ADC, gain,
offset and output widths, rounding, overflow, frame size) are those of the two-point
datapath; every other coefficient has a named format in ``formats`` (integer and fraction
bits, signedness, rounding, overflow) and every method parameter is a field of its own.
The memories of a method and the layout of their words are :attr:`PipelineConfig.memories`,
its global registers :attr:`PipelineConfig.registers`: written once, here.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, fields
from functools import cache
from pathlib import Path
from typing import Any

from irnuc.common import schema
from irnuc.common.digest import digest
from irnuc.common.errors import ConfigError
from irnuc.common.io import PLAIN_NAME
from irnuc.nuc_fixed import rtl_spec
from irnuc.nuc_fixed.rtl_spec import OVERFLOW_MODES, ROUNDING_MODES

PIPELINES_TOML = Path(__file__).with_name("pipelines.toml")


#: Base correction methods (one per pixel datapath) and the stages that compose with them.
BASE_METHODS: tuple[str, ...] = ("one_point", "two_point", "piecewise", "quadratic",
                                 "tc_offset", "table_interp")
STAGES: tuple[str, ...] = ("blind_drift", "ffc")
#: Bases a stage composes with (docs/methods.md says why blind_drift takes only these).
STAGE_BASES: dict[str, tuple[str, ...]] = {
    "blind_drift": ("one_point", "two_point"),
    "ffc": BASE_METHODS,
}

# Legal ranges, checked before any work; the RTL asserts the same ranges (rtl_spec).
_RANGES: dict[str, tuple[int, int]] = rtl_spec.PIPELINE_RANGES

#: Method parameters: field -> (lo, hi, unit, the method or stage that uses it).
_PARAM_RANGES: dict[str, tuple[int, int, str, tuple[str, ...]]] = {
    "square_bits": (1, 24, "bits", ("quadratic",)),
    "tc_order": (1, 2, "", ("tc_offset",)),
    "reading_bits": (1, 24, "bits", ("tc_offset", "table_interp")),
    "reading_range_bits": (1, 20, "bits", ("tc_offset",)),
    "tables": (2, 16, "tables", ("table_interp",)),
    "blind_max": (1, 1 << 20, "pixels", ("blind_drift",)),
    "ffc_frames": (1, 1024, "frames", ("ffc",)),
}
_PARAM_OTHER: dict[str, tuple[dict[str, Any], tuple[str, ...]]] = {
    "tc_gain": ({"type": "boolean"}, ("tc_offset",)),
    "ffc_output": ({"enum": ["hold", "pass"]}, ("ffc",)),
}
PARAMS: tuple[str, ...] = (*_PARAM_RANGES, *_PARAM_OTHER)

#: Coefficient formats by name: (signed, meaning). ``gain`` and ``offset`` are the base
#: fields (gain_int_bits ...); every other format is a table in ``formats``.
FORMAT_NAMES: dict[str, tuple[bool, str]] = {
    "knee": (False, "piecewise breakpoint, ADC codes (per pixel)"),
    "level": (False, "piecewise output at the breakpoint, output codes (register)"),
    "quad": (True, "quadratic term at full-scale input, output codes (per pixel)"),
    "tc1": (True, "offset change per 2^reading_range_bits reading codes, output codes"),
    "tc2": (True, "offset change per (2^reading_range_bits reading codes)^2, output codes"),
    "tg1": (True, "gain change per 2^reading_range_bits reading codes"),
    "tg2": (True, "gain change per (2^reading_range_bits reading codes)^2"),
    "weight": (False, "table interpolation weight in [0, 1] (per frame)"),
    "drift": (True, "blind drift subtracted from the raw code, ADC codes (per frame)"),
    "drift_gain": (True, "ADC codes of drift per code of the blind sum (register)"),
    "ffc": (True, "FFC offset correction, output codes (per pixel, written by the FFC)"),
}

#: Formats of values the datapath computes (their rounding and overflow are datapath modes);
#: the others are stored coefficients, rounded by calibration and always saturated.
_COMPUTED_FORMATS = ("weight", "drift", "ffc")

_FORMAT_SCHEMA = schema.table(
    {
        "int_bits": schema.number(0, 40, integer=True, unit="bits"),
        "frac_bits": schema.number(0, 40, integer=True, unit="bits"),
        "signed": {"type": "boolean"},
        "rounding": {"enum": list(ROUNDING_MODES)},
        "overflow": {"enum": list(OVERFLOW_MODES)},
    },
    required=["int_bits", "frac_bits", "signed"],
)

#: The schema of one pipeline table (docs/datapath.md, "Symbols").
PIPELINE_SCHEMA: dict[str, Any] = schema.table(
    {
        **{k: schema.number(lo, hi, integer=True, unit="bits" if k.endswith("bits") else "pixels")
           for k, (lo, hi) in _RANGES.items()},
        "rounding": {"enum": list(ROUNDING_MODES)},
        "overflow": {"enum": list(OVERFLOW_MODES)},
        "description": {"type": "string"},
        # A name labels files and folders (synthesis, builds): never a path.
        "name": {"type": "string", "minLength": 1, "pattern": PLAIN_NAME,
                 "x-pattern-text": "a plain name (letters, digits, '_', '.', '-'; no path)"},
        "method": {"type": "string", "minLength": 1},
        **{k: schema.number(lo, hi, integer=True, unit=unit)
           for k, (lo, hi, unit, _) in _PARAM_RANGES.items()},
        **{k: s for k, (s, _) in _PARAM_OTHER.items()},
        "formats": {"type": "object", "propertyNames": {"enum": list(FORMAT_NAMES)},
                    "additionalProperties": _FORMAT_SCHEMA},
    },
    required=[*_RANGES, "rounding", "overflow"],
)


def parse_method(text: str, source: str = "method") -> tuple[str, tuple[str, ...]]:
    """``"two_point+blind_drift"`` -> ``("two_point", ("blind_drift",))``, checked.

    The first name is the base method; the others are stages, each at most once, returned
    in the canonical order of :data:`STAGES`.
    """
    names = [p.strip() for p in str(text).split("+")]
    base, stages = names[0], names[1:]
    if base not in BASE_METHODS:
        hint = " (a stage; put a base method first)" if base in STAGES else ""
        raise ConfigError(f"{source} = {text!r}: {base!r} is not a base method{hint}; known: "
                          f"{', '.join(BASE_METHODS)}{schema.nearest(base, list(BASE_METHODS))}")
    for s in stages:
        if s not in STAGES:
            raise ConfigError(f"{source} = {text!r}: {s!r} is not a stage; known: "
                              f"{', '.join(STAGES)}{schema.nearest(s, list(STAGES))}")
        if base not in STAGE_BASES[s]:
            raise ConfigError(f"{source} = {text!r}: {s} composes only with "
                              f"{', '.join(STAGE_BASES[s])} (docs/methods.md)")
    if len(set(stages)) != len(stages):
        raise ConfigError(f"{source} = {text!r}: a stage is named twice")
    if "blind_drift" in stages and "ffc" in stages:
        raise ConfigError(f"{source} = {text!r}: blind_drift and ffc together are not "
                          "supported (docs/methods.md)")
    return base, tuple(s for s in STAGES if s in stages)


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
    ``reads`` is how many words per pixel each frame reads from the memories of this kind
    (table_interp reads two of its K tables), ``writes`` how many it writes in a frame
    that writes it.
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


def _layout(name: str, spec: list[tuple[str, int, bool, str]], **kw: Any) -> MemoryLayout:
    out, lsb = [], 0
    for fname, width, signed, fmt in spec:
        out.append(Field(fname, lsb, width, signed, fmt))
        lsb += width
    return MemoryLayout(name, tuple(out), **kw)


@dataclass(frozen=True)
class PipelineConfig:
    """One named NUC + DPC configuration (see ``docs/datapath.md``)."""

    name: str
    adc_bits: int
    gain_int_bits: int
    gain_frac_bits: int
    offset_int_bits: int
    offset_frac_bits: int
    out_bits: int
    rounding: str
    overflow: str
    max_width: int
    max_height: int
    description: str = ""
    method: str = "two_point"
    square_bits: int | None = None
    tc_order: int | None = None
    tc_gain: bool | None = None
    reading_bits: int | None = None
    reading_range_bits: int | None = None
    tables: int | None = None
    blind_max: int | None = None
    ffc_frames: int | None = None
    ffc_output: str | None = None
    formats: Any = ()  # tuple[CoeffFormat, ...]; a mapping name -> table is accepted

    def __post_init__(self) -> None:
        fm = self.formats
        if isinstance(fm, Mapping):
            if not all(isinstance(v, Mapping) for v in fm.values()):
                raise ConfigError(f"pipeline {self.name!r}: formats must map names to tables")
            try:
                schema.check(dict(fm), PIPELINE_SCHEMA["properties"]["formats"],
                             source=f"pipeline {self.name!r}", prefix="formats")
            except schema.SchemaError as exc:
                raise ConfigError(str(exc)) from None
            fm = tuple(CoeffFormat(name=k, **v) for k, v in fm.items())
        elif not all(isinstance(f, CoeffFormat) for f in fm):
            raise ConfigError(f"pipeline {self.name!r}: formats must map names to tables")
        object.__setattr__(self, "formats", tuple(sorted(fm, key=lambda f: f.name)))
        try:
            schema.check(self.to_dict(), PIPELINE_SCHEMA, source=f"pipeline {self.name!r}")
        except schema.SchemaError as exc:
            raise ConfigError(str(exc)) from None
        base, stages = parse_method(self.method, f"pipeline {self.name!r}: method")
        object.__setattr__(self, "method", "+".join((base, *stages)))
        self._check_method(base, stages)
        if self.gain_bits < 1:
            raise ConfigError(
                f"pipeline {self.name!r}: gain_int_bits + gain_frac_bits = {self.gain_bits} "
                "must be at least 1"
            )
        widths = self.datapath_widths()
        what = max(widths, key=lambda k: widths[k])
        if widths[what] > rtl_spec.SUM_BITS_MAX:
            # The golden model computes in int64; keep one bit of headroom for rounding.
            name = {"core.s": "sum"}.get(what, what)
            raise ConfigError(
                f"pipeline {self.name!r}: the datapath {name} needs {widths[what]} bits; "
                f"the allowed maximum is {rtl_spec.SUM_BITS_MAX}"
            )
        for mem in self.memories.values():
            # (A two-point word beyond 64 bits is refused where words are packed, as before.)
            if mem.word_bits > 64 and self.method != "two_point":
                raise ConfigError(
                    f"pipeline {self.name!r}: memory {mem.name!r} has {mem.word_bits}-bit "
                    "words; the golden model's uint64 words hold at most 64")

    # ---- method ----------------------------------------------------------------------
    def _check_method(self, base: str, stages: tuple[str, ...]) -> None:
        src = f"pipeline {self.name!r} (method {self.method!r})"
        parts = (base, *stages)
        needed_params = [p for p, (*_, users) in _PARAM_RANGES.items() if set(users) & set(parts)]
        needed_params += [p for p, (_, users) in _PARAM_OTHER.items() if set(users) & set(parts)]
        for p in PARAMS:
            v = getattr(self, p)
            if p in needed_params and v is None:
                raise ConfigError(f"{src}: {p} is required but missing")
            if p not in needed_params and v is not None:
                raise ConfigError(f"{src}: {p} is not used by this method")
        want = set(self.format_names_needed(base, stages))
        have = {f.name for f in self.formats}
        if want - have:
            raise ConfigError(f"{src}: formats.{sorted(want - have)[0]} is required but missing")
        if have - want:
            raise ConfigError(f"{src}: formats.{sorted(have - want)[0]} is not used by this "
                              f"method (it uses {', '.join(sorted(want)) or 'no extra format'})")
        for f in self.formats:
            signed, meaning = FORMAT_NAMES[f.name]
            if f.signed != signed:
                raise ConfigError(f"{src}: formats.{f.name}.signed = {str(f.signed).lower()}; "
                                  f"{f.name} ({meaning}) must be "
                                  f"{'signed' if signed else 'unsigned'}")
            if f.bits < 1 or (f.signed and f.int_bits < 1):
                raise ConfigError(f"{src}: formats.{f.name} = {f} needs at least one bit"
                                  + (" of integer (the sign)" if f.signed else ""))
        for f in self.formats:
            if f.name not in _COMPUTED_FORMATS and f.overflow != "saturate":
                raise ConfigError(f"{src}: formats.{f.name}.overflow = {f.overflow!r}; a stored "
                                  "coefficient saturates (calibration flags the pixel)")
        if self.ffc_frames is not None and self.ffc_frames & (self.ffc_frames - 1):
            raise ConfigError(f"{src}: ffc_frames = {self.ffc_frames} must be a power of two "
                              "(the mean is a shift)")
        if (base == "tc_offset" and self.reading_range_bits is not None
                and self.reading_bits is not None and self.reading_range_bits > self.reading_bits):
            raise ConfigError(f"{src}: reading_range_bits = {self.reading_range_bits} must be "
                              f"at most reading_bits = {self.reading_bits} (a reading differs "
                              "from t_ref by less than 2^reading_bits)")
        if base == "table_interp" and self.format("weight").int_bits < 1:
            raise ConfigError(f"{src}: formats.weight = {self.format('weight')} cannot hold "
                              "1.0; int_bits must be at least 1")
        if base == "piecewise" and self.format("knee").int_bits < self.adc_bits:
            raise ConfigError(f"{src}: formats.knee.int_bits = {self.format('knee').int_bits} "
                              f"must be at least adc_bits = {self.adc_bits} (a knee is an ADC "
                              "code)")
        if "blind_drift" in stages:
            d, m = self.format("drift"), self.format("drift_gain")
            if m.frac_bits < d.frac_bits:
                raise ConfigError(f"{src}: formats.drift_gain.frac_bits = {m.frac_bits} must "
                                  f"be at least formats.drift.frac_bits = {d.frac_bits}")

    def format_names_needed(self, base: str | None = None,
                            stages: tuple[str, ...] | None = None) -> tuple[str, ...]:
        """The names in ``formats`` this configuration's method uses."""
        if base is None:
            base, stages = self.base_method, self.stages
        need: list[str] = {"piecewise": ["knee", "level"], "quadratic": ["quad"],
                           "table_interp": ["weight"]}.get(base, [])
        if base == "tc_offset":
            order = self.tc_order or 1
            need += ["tc1", "tc2"][:order]
            if self.tc_gain:
                need += ["tg1", "tg2"][:order]
        for s in stages or ():
            need += {"blind_drift": ["drift", "drift_gain"], "ffc": ["ffc"]}[s]
        return tuple(need)

    @property
    def max_frame_pixels(self) -> int:
        """Pixels of the largest frame the hardware takes (``max_width * max_height``)."""
        return self.max_width * self.max_height

    @property
    def base_method(self) -> str:
        """The base method (``two_point`` of ``two_point+ffc``)."""
        return self.method.split("+")[0]

    @property
    def stages(self) -> tuple[str, ...]:
        """The stages composed with the base method, in canonical order."""
        return tuple(self.method.split("+")[1:])

    def has(self, stage: str) -> bool:
        return stage in self.stages

    def format(self, name: str) -> CoeffFormat:
        """The format of a coefficient: ``gain``, ``offset`` or a name in ``formats``."""
        if name == "gain":
            return CoeffFormat("gain", self.gain_int_bits, self.gain_frac_bits, False)
        if name == "offset":
            return CoeffFormat("offset", self.offset_int_bits, self.offset_frac_bits, True)
        for f in self.formats:
            if f.name == name:
                return f
        raise ConfigError(f"pipeline {self.name!r} (method {self.method!r}) has no format "
                          f"{name!r}")

    # ---- derived widths (docs/datapath.md, section "Widths") --------------------------
    @property
    def gain_bits(self) -> int:
        """Total gain code width GW = Gi + Gf (unsigned)."""
        return self.gain_int_bits + self.gain_frac_bits

    @property
    def offset_bits(self) -> int:
        """Total offset code width OW = Oi + Of (two's complement)."""
        return self.offset_int_bits + self.offset_frac_bits

    @property
    def frac_bits(self) -> int:
        """Common fraction width of the two-point sum, F = max(Gf, Of)."""
        return max(self.gain_frac_bits, self.offset_frac_bits)

    @property
    def product_bits(self) -> int:
        """Width of x*g, unsigned: A + GW."""
        return self.adc_bits + self.gain_bits

    @property
    def sum_bits(self) -> int:
        """Width of the aligned signed sum s: max(A + Gi + F + 1, Oi + F) + 1."""
        f = self.frac_bits
        return max(self.adc_bits + self.gain_int_bits + f + 1, self.offset_int_bits + f) + 1

    def datapath_widths(self) -> dict[str, int]:
        """The widest intermediate of every stage of this method (bits, docs/datapath.md)."""
        from irnuc.nuc_fixed.widths import widest

        return widest(self)

    @property
    def word_bits(self) -> int:
        """Coefficient word width of the first memory (two_point: gain, offset, bad flag)."""
        return next(iter(self.memories.values())).word_bits

    @property
    def word_fields(self) -> dict[str, tuple[int, int]]:
        """Coefficient word layout of the first memory: field -> (lsb, width).

        For ``two_point`` (docs/datapath.md): gain, offset, bad. Every memory of every
        method is in :attr:`memories`; this is the view packing and the two-point kernels use.
        """
        mem = next(iter(self.memories.values()))
        return {f.name: (f.lsb, f.width) for f in mem.fields}

    @property
    def memories(self) -> dict[str, MemoryLayout]:
        """Every per-pixel memory of the method and its word layout (docs/datapath.md).

        The one place the layouts are written: packing, unpacking, the kernels, the
        manifest and the generated RTL package (``nuc_fixed.layout.rtl_package``) follow it.
        """
        gw, ow = self.gain_bits, self.offset_bits
        g = ("gain", gw, False, str(self.format("gain")))
        o = ("offset", ow, True, str(self.format("offset")))
        bad = ("bad", 1, False, "flag")
        base = self.base_method

        def fmt(name: str, field: str | None = None) -> tuple[str, int, bool, str]:
            f = self.format(name)
            return (field or name, f.bits, f.signed, str(f))

        mems: list[MemoryLayout] = []
        if base == "one_point":
            mems.append(_layout("coeffs", [o, bad]))
        elif base == "two_point":
            mems.append(_layout("coeffs", [g, o, bad]))
        elif base == "piecewise":
            mems.append(_layout("coeffs", [("gain_lo", gw, False, g[3]),
                                           ("gain_hi", gw, False, g[3]), fmt("knee"), bad]))
        elif base == "quadratic":
            mems += [_layout("coeffs", [g, o, bad]), _layout("quad", [fmt("quad")])]
        elif base == "tc_offset":
            order = int(self.tc_order or 1)
            mems += [_layout("coeffs", [g, o, bad]),
                     _layout("tc", [fmt(n) for n in ["tc1", "tc2"][:order]])]
            if self.tc_gain:
                mems.append(_layout("tg", [fmt(n) for n in ["tg1", "tg2"][:order]]))
        elif base == "table_interp":
            mems += [_layout(f"table{k}", [g, o, bad], reads_per_frame=0)
                     for k in range(self.tables or 0)]
        if self.has("ffc"):
            n = (self.ffc_frames or 1).bit_length() - 1
            acc = self.adc_bits + n
            mems += [_layout("ffc_offset", [fmt("ffc")], source="runtime"),
                     _layout("ffc_acc", [("acc", acc, False, f"U{acc}.0")], source="runtime",
                             reads_per_frame=0)]
        return {m.name: m for m in mems}

    @property
    def registers(self) -> dict[str, Register]:
        """Global registers of the method: calibration constants and per-frame inputs."""
        regs: list[Register] = []
        base = self.base_method
        if base == "one_point":
            gf = self.format("gain")
            regs.append(Register("gain", gf.bits, False, str(gf),
                                 meaning="global gain (output codes per ADC code)"))
        if base == "piecewise":
            lf = self.format("level")
            regs.append(Register("level", lf.bits, False, str(lf),
                                 meaning="output at every pixel's knee, output codes"))
        if base in ("tc_offset", "table_interp"):
            r = self.reading_bits or 1
            regs.append(Register("reading", r, False, f"U{r}.0", source="runtime",
                                 meaning="FPA sensor reading latched at the frame start"))
        if base == "tc_offset":
            r = self.reading_bits or 1
            regs.append(Register("t_ref", r, False, f"U{r}.0",
                                 meaning="reading at which the polynomials are centred"))
        if base == "table_interp":
            r = self.reading_bits or 1
            regs.append(Register("table_readings", r, False, f"U{r}.0", count=self.tables or 0,
                                 meaning="reading of each table, strictly increasing"))
        if self.has("blind_drift"):
            sb = self.blind_sum_bits
            mf = self.format("drift_gain")
            regs += [Register("blind_sum", sb, False, f"U{sb}.0", source="runtime",
                              meaning="sum of the frame's blind pixel codes"),
                     Register("blind_ref", sb, False, f"U{sb}.0",
                              meaning="blind pixel sum at calibration"),
                     Register("drift_gain", mf.bits, True, str(mf),
                              meaning="drift (ADC codes) per code of blind sum change")]
        if self.has("ffc"):
            c = self.format("ffc")
            regs.append(Register("ffc_target", self.out_bits + c.frac_bits, False,
                                 f"U{self.out_bits}.{c.frac_bits}", source="runtime",
                                 meaning="output level the FFC flattens the shutter to"))
        return {r.name: r for r in regs}

    @property
    def blind_sum_bits(self) -> int:
        """Width of the blind pixel sum: A + bit_length(blind_max)."""
        return self.adc_bits + int(self.blind_max or 1).bit_length()

    @property
    def rounding_code(self) -> int:
        return ROUNDING_MODES[self.rounding]

    @property
    def overflow_code(self) -> int:
        return OVERFLOW_MODES[self.overflow]

    def rtl_parameters(self) -> dict[str, int]:
        """The SystemVerilog parameters of ``nuc_dpc_top`` for this configuration."""
        return {
            "AdcBits": self.adc_bits,
            "GainIntBits": self.gain_int_bits,
            "GainFracBits": self.gain_frac_bits,
            "OffsetIntBits": self.offset_int_bits,
            "OffsetFracBits": self.offset_frac_bits,
            "OutBits": self.out_bits,
            "Rounding": self.rounding_code,
            "Overflow": self.overflow_code,
            "MaxWidth": self.max_width,
            "MaxHeight": self.max_height,
        }

    def to_dict(self) -> dict[str, object]:
        """Every field; the method fields only when set, so that a two-point configuration
        has the same dictionary (and digest) as before methods existed."""
        out: dict[str, object] = {f.name: getattr(self, f.name) for f in fields(self)
                                  if f.name not in ("method", "formats", *PARAMS)}
        if self.method != "two_point":
            out["method"] = self.method
        for p in PARAMS:
            if getattr(self, p) is not None:
                out[p] = getattr(self, p)
        if self.formats:
            out["formats"] = {f.name: f.to_dict() for f in self.formats}
        return out

    def digest(self) -> str:
        """A short hash of every field, for build caches and report provenance."""
        return digest(self.to_dict())

    def replace(self, **changes: object) -> PipelineConfig:
        """A validated copy with some fields changed (used by bit-width sweeps).

        ``formats`` may be given as a mapping of the formats to change:
        ``replace(formats={"quad": {"frac_bits": 10}})`` keeps the other keys.
        """
        data = self.to_dict()
        known = {f.name for f in fields(self)}
        unknown = set(changes) - known
        if unknown:
            raise ConfigError(f"unknown pipeline field(s): {sorted(unknown)}")
        fmt_changes = changes.pop("formats", None)
        data.update(changes)
        if fmt_changes is not None:
            fm = {k: dict(v) for k, v in dict(data.get("formats", {})).items()}  # type: ignore[arg-type]
            for k, v in dict(fmt_changes).items():  # type: ignore[call-overload]
                fm[k] = {**fm.get(k, {}), **dict(v)}
            data["formats"] = fm
        return PipelineConfig(**data)  # type: ignore[arg-type]

    def to_toml(self) -> str:
        """This configuration as a pipeline TOML table (``load_pipeline`` reads it back)."""
        lines = [f"[{self.name}]"]
        for k, v in self.to_dict().items():
            if k == "name":
                continue
            if k == "formats":
                for fname, fd in v.items():  # type: ignore[union-attr]
                    body = ", ".join(f"{kk} = {_toml_value(vv)}" for kk, vv in fd.items())
                    lines.append(f"formats.{fname} = {{ {body} }}")
                continue
            lines.append(f"{k} = {_toml_value(v)}")
        return "\n".join(lines) + "\n"


def _toml_value(v: object) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    # JSON string syntax is a valid TOML basic string (quotes and escapes included).
    return json.dumps(v) if isinstance(v, str) else str(v)


@cache
def _read_table(path: Path) -> dict[str, dict[str, object]]:
    return schema.read_toml(path)


def pipeline_names(path: Path = PIPELINES_TOML, method: str | None = "two_point") -> list[str]:
    """Names of the configurations in the file, in file order.

    ``method``: only those of this method (default ``two_point``, the configurations the
    RTL of today implements); ``None`` for every configuration.
    """
    tables = _read_table(path)
    return [n for n, t in tables.items()
            if method is None or (isinstance(t, dict) and t.get("method", "two_point") == method)]


def _from_table(name: str, entry: Any, source: str) -> PipelineConfig:
    if not isinstance(entry, dict):
        raise ConfigError(f"{source}: [{name}] must be a table of pipeline fields")
    try:
        schema.check(entry, PIPELINE_SCHEMA, source=source, prefix=name)
    except schema.SchemaError as exc:
        raise ConfigError(str(exc)) from None
    known = {f.name for f in fields(PipelineConfig)}
    return PipelineConfig(**{"name": name, **{k: v for k, v in entry.items() if k in known}})


def load_pipeline(name: str | Path, path: Path = PIPELINES_TOML) -> PipelineConfig:
    """Load and validate one configuration.

    Parameters
    ----------
    name : str or Path
        A name in ``pipelines.toml`` (``typical14``), or a TOML file of the same form:
        ``my.toml`` (its only table) or ``my.toml:NAME`` (one of its tables).
    path : Path
        The file of named configurations (the shipped one by default).
    """
    text = str(name)
    file, sep, table = text.partition(":") if text.count(":") == 1 else (text, "", "")
    if isinstance(name, Path) or file.endswith(".toml") or "/" in file:
        tables = schema.read_toml(file)
        if not tables:
            raise ConfigError(f"{file}: holds no pipeline table")
        if not sep:
            if len(tables) != 1:
                raise ConfigError(f"{file}: holds {len(tables)} pipelines "
                                  f"({', '.join(tables)}); name one: {file}:NAME")
            table = next(iter(tables))
        if table not in tables:
            raise ConfigError(f"{file}: no pipeline [{table}]; found {', '.join(tables)}")
        return _from_table(table, tables[table], str(file))
    known = _read_table(path)
    if text not in known:
        raise ConfigError(f"pipeline {text!r} is neither a named configuration "
                          f"({', '.join(known)}) nor a .toml file{schema.nearest(text, list(known))}")
    return _from_table(text, known[text], str(path))
