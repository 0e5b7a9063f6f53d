"""Pipeline configurations: the named ones of ``nuc_fixed/pipelines.toml`` and user files.

This is the single reader of those files: the golden model, the RTL build (which turns a
configuration into Verilator ``-G`` parameters with :meth:`PipelineConfig.rtl_parameters`)
and the tests all go through :func:`load_pipeline`. Every field is checked against
:data:`PIPELINE_SCHEMA` (unknown fields are refused with the nearest known name). Widths
derived from a configuration are properties here and nowhere else; ``docs/datapath.md``
defines them.

A configuration names its correction ``method`` (``docs/methods.md``): a base method
(default ``two_point``) optionally followed by stages, written ``"two_point+blind_drift"``;
both are things of the method registry (``nuc_fixed.methods``: :attr:`PipelineConfig.base`
and :attr:`PipelineConfig.parts`), which also gives the schema's method parameters and
formats, the checks, the memories and the registers. The base fields (ADC, gain, offset and
output widths, rounding, overflow, frame size) are those of the two-point datapath; every
other coefficient has a named format in ``formats`` (integer and fraction bits, signedness,
rounding, overflow) and every method parameter is a field of its own.
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
from irnuc.nuc_fixed.spec import CoeffFormat, MemoryLayout, Register

PIPELINES_TOML = Path(__file__).with_name("pipelines.toml")




# Legal ranges, checked before any work; the RTL asserts the same ranges (rtl_spec).
_RANGES: dict[str, tuple[int, int]] = rtl_spec.PIPELINE_RANGES


def _registry() -> Any:
    """The method registry, imported on first use: its methods import this module."""
    from irnuc.nuc_fixed import methods

    return methods


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


def _pipeline_schema() -> dict[str, Any]:
    """The schema of one pipeline table (docs/datapath.md, "Symbols"): the base fields and
    every parameter and format of the registry's methods and stages."""
    reg = _registry()
    return _schema_of(tuple(reg.BASES), tuple(reg.STAGES))


@cache
def _schema_of(bases: tuple[str, ...], stages: tuple[str, ...]) -> dict[str, Any]:
    """:func:`_pipeline_schema` for the registry holding these methods (a test may add one)."""
    reg = _registry()
    return schema.table(
        {
            **{k: schema.number(lo, hi, integer=True,
                                unit="bits" if k.endswith("bits") else "pixels")
               for k, (lo, hi) in _RANGES.items()},
            "rounding": {"enum": list(ROUNDING_MODES)},
            "overflow": {"enum": list(OVERFLOW_MODES)},
            "description": {"type": "string"},
            # A name labels files and folders (synthesis, builds): never a path.
            "name": {"type": "string", "minLength": 1, "pattern": PLAIN_NAME,
                     "x-pattern-text": "a plain name (letters, digits, '_', '.', '-'; no path)"},
            "method": {"type": "string", "minLength": 1},
            **{k: dict(p.schema) for k, p in reg.all_params().items()},
            "formats": {"type": "object", "propertyNames": {"enum": list(reg.all_formats())},
                        "additionalProperties": _FORMAT_SCHEMA},
        },
        required=[*_RANGES, "rounding", "overflow"],
    )


def __getattr__(name: str) -> Any:
    """The registry's lists under their former names (built on first use)."""
    reg = _registry()
    if name == "BASE_METHODS":
        return tuple(reg.BASES)
    if name == "STAGES":
        return tuple(reg.STAGES)
    if name == "STAGE_BASES":
        return {s.name: s.bases or tuple(reg.BASES) for s in reg.STAGES.values()}
    if name == "PARAMS":
        return tuple(reg.all_params())
    if name == "FORMAT_NAMES":
        return {n: (f.signed, f.meaning) for n, f in reg.all_formats().items()}
    if name == "PIPELINE_SCHEMA":
        return _pipeline_schema()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def parse_method(text: str, source: str = "method") -> tuple[str, tuple[str, ...]]:
    """``"two_point+blind_drift"`` -> ``("two_point", ("blind_drift",))``, checked
    (``nuc_fixed.methods.parse_method``)."""
    return _registry().parse_method(text, source)


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
    housing_bits: int | None = None
    housing_range_bits: int | None = None
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
                schema.check(dict(fm), _pipeline_schema()["properties"]["formats"],
                             source=f"pipeline {self.name!r}", prefix="formats")
            except schema.SchemaError as exc:
                raise ConfigError(str(exc)) from None
            fm = tuple(CoeffFormat(name=k, **v) for k, v in fm.items())
        elif not all(isinstance(f, CoeffFormat) for f in fm):
            raise ConfigError(f"pipeline {self.name!r}: formats must map names to tables")
        object.__setattr__(self, "formats", tuple(sorted(fm, key=lambda f: f.name)))
        try:
            schema.check(self.to_dict(), _pipeline_schema(), source=f"pipeline {self.name!r}")
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
            if mem.word_bits > 64 and not self.plain:
                raise ConfigError(
                    f"pipeline {self.name!r}: memory {mem.name!r} has {mem.word_bits}-bit "
                    "words; the golden model's uint64 words hold at most 64")

    # ---- method ----------------------------------------------------------------------
    def _check_method(self, base: str, stages: tuple[str, ...]) -> None:
        reg = _registry()
        src = f"pipeline {self.name!r} (method {self.method!r})"
        needed_params = reg.used_params(self)
        for p in reg.all_params():
            v = getattr(self, p)
            if p in needed_params and v is None:
                raise ConfigError(f"{src}: {p} is required but missing")
            if p not in needed_params and v is not None:
                raise ConfigError(f"{src}: {p} is not used by this method")
        want = set(self.format_names_needed())
        have = {f.name for f in self.formats}
        if want - have:
            raise ConfigError(f"{src}: formats.{sorted(want - have)[0]} is required but missing")
        if have - want:
            raise ConfigError(f"{src}: formats.{sorted(have - want)[0]} is not used by this "
                              f"method (it uses {', '.join(sorted(want)) or 'no extra format'})")
        specs = reg.all_formats()
        for f in self.formats:
            spec = specs[f.name]
            if f.signed != spec.signed:
                raise ConfigError(f"{src}: formats.{f.name}.signed = {str(f.signed).lower()}; "
                                  f"{f.name} ({spec.meaning}) must be "
                                  f"{'signed' if spec.signed else 'unsigned'}")
            if f.bits < 1 or (f.signed and f.int_bits < 1):
                raise ConfigError(f"{src}: formats.{f.name} = {f} needs at least one bit"
                                  + (" of integer (the sign)" if f.signed else ""))
        for f in self.formats:
            if not specs[f.name].computed and f.overflow != "saturate":
                raise ConfigError(f"{src}: formats.{f.name}.overflow = {f.overflow!r}; a stored "
                                  "coefficient saturates (calibration flags the pixel)")
        for part in reg.parts(self):
            part.check(self, src)

    def format_names_needed(self) -> tuple[str, ...]:
        """The names in ``formats`` this configuration's method uses."""
        return _registry().used_formats(self)

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

    @property
    def base(self) -> Any:
        """The base method (``nuc_fixed.methods``' :class:`~irnuc.nuc_fixed.spec.MethodSpec`)."""
        return _registry().base(self.base_method)

    @property
    def parts(self) -> tuple[Any, ...]:
        """The base method and the stages (:class:`~irnuc.nuc_fixed.spec.StageSpec`), in order."""
        return _registry().parts(self)

    @property
    def plain(self) -> bool:
        """The plain two-point NUC: no stage, the base ``MethodSpec.plain`` (memory image
        version 1, ``nuc_dpc_top``)."""
        return not self.stages and bool(self.base.plain)

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
        """Every per-pixel memory of the method and its word layout (docs/datapath.md): the
        base method's, then the stages' (``MethodSpec.memories``, ``StageSpec.memories``).

        Packing, unpacking, the kernels, the manifest and the generated RTL package
        (``nuc_fixed.layout.rtl_package``) follow it.
        """
        return {m.name: m for part in self.parts for m in part.memories(self)}

    @property
    def registers(self) -> dict[str, Register]:
        """Global registers of the method: per part, its readings' runtime registers and its
        calibration constants and per-frame inputs."""
        reg = _registry()
        return {r.name: r for part in self.parts
                for r in (*reg.reading_registers(self, part), *part.registers(self))}

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
        params = tuple(_registry().all_params())
        out: dict[str, object] = {f.name: getattr(self, f.name) for f in fields(self)
                                  if f.name not in ("method", "formats", *params)}
        if self.method != "two_point":
            out["method"] = self.method
        for p in params:
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
        schema.check(entry, _pipeline_schema(), source=source, prefix=name)
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
