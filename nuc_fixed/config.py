"""Named pipeline configurations, read from ``nuc_fixed/pipelines.toml``.

This is the single reader of that file: the golden model, the RTL build (which turns a
configuration into Verilator ``-G`` parameters with :meth:`PipelineConfig.rtl_parameters`)
and the tests all go through :func:`load_pipeline`. Widths derived from a configuration
are properties here and nowhere else; ``docs/datapath.md`` defines them.
"""

from __future__ import annotations

import hashlib
import json
import tomllib
from dataclasses import asdict, dataclass
from functools import cache
from pathlib import Path

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


class ConfigError(ValueError):
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
        for field, (lo, hi) in _RANGES.items():
            value = getattr(self, field)
            if not isinstance(value, int) or isinstance(value, bool) or not lo <= value <= hi:
                raise ConfigError(
                    f"pipeline {self.name!r}: {field} = {value!r} is outside the allowed "
                    f"range {lo}..{hi} (integer)"
                )
        if self.gain_bits < 1:
            raise ConfigError(
                f"pipeline {self.name!r}: gain_int_bits + gain_frac_bits = {self.gain_bits} "
                "must be at least 1"
            )
        if self.rounding not in ROUNDING_MODES:
            raise ConfigError(
                f"pipeline {self.name!r}: rounding = {self.rounding!r} is not one of "
                f"{sorted(ROUNDING_MODES)}"
            )
        if self.overflow not in OVERFLOW_MODES:
            raise ConfigError(
                f"pipeline {self.name!r}: overflow = {self.overflow!r} is not one of "
                f"{sorted(OVERFLOW_MODES)}"
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
        text = json.dumps(self.to_dict(), sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def replace(self, **changes: object) -> PipelineConfig:
        """A validated copy with some fields changed (used by bit-width sweeps)."""
        data = self.to_dict()
        unknown = set(changes) - set(data)
        if unknown:
            raise ConfigError(f"unknown pipeline field(s): {sorted(unknown)}")
        data.update(changes)
        return PipelineConfig(**data)  # type: ignore[arg-type]


@cache
def _read_table(path: Path) -> dict[str, dict[str, object]]:
    with path.open("rb") as fh:
        return tomllib.load(fh)


def pipeline_names(path: Path = PIPELINES_TOML) -> list[str]:
    """Names of the configurations in the file, in file order."""
    return list(_read_table(path))


def load_pipeline(name: str, path: Path = PIPELINES_TOML) -> PipelineConfig:
    """Load and validate one named configuration."""
    table = _read_table(path)
    if name not in table:
        raise ConfigError(f"unknown pipeline configuration {name!r}; known: {list(table)}")
    entry = dict(table[name])
    expected = set(PipelineConfig.__dataclass_fields__) - {"name"}
    unknown = set(entry) - expected
    if unknown:
        raise ConfigError(f"pipeline {name!r}: unknown field(s) {sorted(unknown)}")
    missing = expected - set(entry) - {"description"}
    if missing:
        raise ConfigError(f"pipeline {name!r}: missing field(s) {sorted(missing)}")
    return PipelineConfig(name=name, **entry)  # type: ignore[arg-type]
