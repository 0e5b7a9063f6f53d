"""Pipeline configurations: the named ones of ``nuc_fixed/pipelines.toml`` and user files.

This is the single reader of those files: the golden model, the RTL build (which turns a
configuration into Verilator ``-G`` parameters with :meth:`PipelineConfig.rtl_parameters`)
and the tests all go through :func:`load_pipeline`. Every field is checked against
:data:`PIPELINE_SCHEMA` (unknown fields are refused with the nearest known name). Widths
derived from a configuration are properties here and nowhere else; ``docs/datapath.md``
defines them.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, fields
from functools import cache
from pathlib import Path
from typing import Any

from irnuc.common import schema
from irnuc.common.digest import digest
from irnuc.common.errors import UserError
from irnuc.common.io import PLAIN_NAME

PIPELINES_TOML = Path(__file__).with_name("pipelines.toml")

ROUNDING_MODES: dict[str, int] = {"truncate": 0, "half_up": 1, "half_even": 2}
OVERFLOW_MODES: dict[str, int] = {"saturate": 0, "wrap": 1}

# Legal ranges, checked before any work; the RTL asserts the same ranges.
_RANGES: dict[str, tuple[int, int]] = {
    "adc_bits": (1, 24),
    "gain_int_bits": (0, 16),
    "gain_frac_bits": (0, 32),
    "offset_int_bits": (1, 32),
    "offset_frac_bits": (0, 32),
    "out_bits": (1, 24),
    "max_width": (1, 65535),
    "max_height": (1, 65535),
}


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
    },
    required=[*_RANGES, "rounding", "overflow"],
)


class ConfigError(UserError):
    """A configuration field is missing or outside its legal range."""


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

    def __post_init__(self) -> None:
        try:
            schema.check(self.to_dict(), PIPELINE_SCHEMA, source=f"pipeline {self.name!r}")
        except schema.SchemaError as exc:
            raise ConfigError(str(exc)) from None
        if self.gain_bits < 1:
            raise ConfigError(
                f"pipeline {self.name!r}: gain_int_bits + gain_frac_bits = {self.gain_bits} "
                "must be at least 1"
            )
        if self.sum_bits > 62:
            # The golden model computes in int64; keep one bit of headroom for rounding.
            raise ConfigError(
                f"pipeline {self.name!r}: the datapath sum needs {self.sum_bits} bits; "
                "the allowed maximum is 62"
            )

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
        """Common fraction width of the sum, F = max(Gf, Of)."""
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

    @property
    def word_bits(self) -> int:
        """Coefficient word width: gain, offset and the bad flag."""
        return self.gain_bits + self.offset_bits + 1

    @property
    def word_fields(self) -> dict[str, tuple[int, int]]:
        """Coefficient word layout (docs/datapath.md): field -> (lsb, width).

        The one place the layout is written: packing, unpacking, the kernels, the manifest
        and the RTL's word struct (checked in simulation) all follow it.
        """
        gw, ow = self.gain_bits, self.offset_bits
        return {"gain": (0, gw), "offset": (gw, ow), "bad": (gw + ow, 1)}

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
        return asdict(self)

    def digest(self) -> str:
        """A short hash of every field, for build caches and report provenance."""
        return digest(self.to_dict())

    def replace(self, **changes: object) -> PipelineConfig:
        """A validated copy with some fields changed (used by bit-width sweeps)."""
        data = self.to_dict()
        unknown = set(changes) - set(data)
        if unknown:
            raise ConfigError(f"unknown pipeline field(s): {sorted(unknown)}")
        data.update(changes)
        return PipelineConfig(**data)  # type: ignore[arg-type]

    def to_toml(self) -> str:
        """This configuration as a pipeline TOML table (``load_pipeline`` reads it back)."""
        lines = [f"[{self.name}]"]
        for k, v in self.to_dict().items():
            if k == "name":
                continue
            # JSON string syntax is a valid TOML basic string (quotes and escapes included).
            lines.append(f"{k} = {json.dumps(v)}" if isinstance(v, str) else f"{k} = {v}")
        return "\n".join(lines) + "\n"


@cache
def _read_table(path: Path) -> dict[str, dict[str, object]]:
    return schema.read_toml(path)


def pipeline_names(path: Path = PIPELINES_TOML) -> list[str]:
    """Names of the configurations in the file, in file order."""
    return list(_read_table(path))


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
