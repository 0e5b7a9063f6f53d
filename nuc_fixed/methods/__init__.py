"""The correction-method registry: every base method, stage and reading, written once.

One module per base method (:data:`BASES`, in the order of ``method_e``'s encoding) and
per stage (:data:`STAGES`), each holding a :class:`~irnuc.nuc_fixed.spec.MethodSpec` or
:class:`~irnuc.nuc_fixed.spec.StageSpec`; the readings a frame can carry
(:data:`READINGS`); the composition rules (:func:`parse_method`). Every layer asks the
registry (``cfg.base``, ``cfg.parts``, :func:`base`, :func:`needs`, ...) instead of
comparing method names. docs/architecture.md ("Correction methods: one registry") has the
design and the walkthrough that adds a method.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

from irnuc.common import schema
from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.methods import (
    blind_drift,
    ffc,
    one_point,
    piecewise,
    quadratic,
    table_interp,
    tc_housing,
    tc_offset,
    two_point,
)
from irnuc.nuc_fixed.methods.readings import READINGS
from irnuc.nuc_fixed.spec import (
    FormatSpec,
    MethodSpec,
    ParamSpec,
    Register,
    RegisterSlot,
    StageSpec,
)

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig

#: The base methods by name, in the order of ``method_e`` (one list of methods).
BASES: dict[str, MethodSpec] = {m.name: m for m in (
    one_point.METHOD, two_point.METHOD, piecewise.METHOD, quadratic.METHOD, tc_offset.METHOD,
    table_interp.METHOD, tc_housing.METHOD)}
#: The stages by name, in their canonical order in a method (``two_point+blind_drift``).
STAGES: dict[str, StageSpec] = {s.name: s for s in (blind_drift.STAGE, ffc.STAGE)}

Part = MethodSpec | StageSpec


def register_method(spec: MethodSpec) -> None:
    """Add a base method (a test's demonstration method; a shipped one is listed in
    :data:`BASES` above). Its code in ``method_e`` is its position."""
    if spec.name in BASES or spec.name in STAGES:
        raise ValueError(f"a method or stage {spec.name!r} is registered already")
    BASES[spec.name] = spec


def unregister_method(name: str) -> None:
    """Remove a method added by :func:`register_method` (a shipped one stays)."""
    if name in _SHIPPED:
        raise ValueError(f"{name!r} is a shipped method")
    BASES.pop(name, None)


_SHIPPED = frozenset(BASES)


def base(name: str) -> MethodSpec:
    """The base method ``name`` (KeyError if there is none)."""
    return BASES[name]


def stage(name: str) -> StageSpec:
    return STAGES[name]


def parse_method(text: str, source: str = "method") -> tuple[str, tuple[str, ...]]:
    """``"two_point+blind_drift"`` -> ``("two_point", ("blind_drift",))``, checked.

    The first name is the base method; the others are stages, each at most once, returned
    in the canonical order of :data:`STAGES`; each stage composes with the base
    (``StageSpec.bases``) and with the other stages (``StageSpec.excludes``).
    """
    names = [p.strip() for p in str(text).split("+")]
    first, stages = names[0], names[1:]
    known = list(BASES)
    if first not in BASES:
        hint = " (a stage; put a base method first)" if first in STAGES else ""
        raise ConfigError(f"{source} = {text!r}: {first!r} is not a base method{hint}; known: "
                          f"{', '.join(known)}{schema.nearest(first, known)}")
    for s in stages:
        if s not in STAGES:
            raise ConfigError(f"{source} = {text!r}: {s!r} is not a stage; known: "
                              f"{', '.join(STAGES)}{schema.nearest(s, list(STAGES))}")
        bases = STAGES[s].bases
        if bases is not None and first not in bases:
            raise ConfigError(f"{source} = {text!r}: {s} composes only with "
                              f"{', '.join(bases)} (docs/methods.md)")
    if len(set(stages)) != len(stages):
        raise ConfigError(f"{source} = {text!r}: a stage is named twice")
    for s in stages:
        clash = [o for o in STAGES[s].excludes if o in stages]
        if clash:
            a, b = sorted((s, clash[0]), key=list(STAGES).index)
            raise ConfigError(f"{source} = {text!r}: {a} and {b} together are not "
                              "supported (docs/methods.md)")
    return first, tuple(s for s in STAGES if s in stages)


def parts(cfg: PipelineConfig) -> tuple[Part, ...]:
    """The base method and the stages of a configuration, in order."""
    return (BASES[cfg.base_method], *(STAGES[s] for s in cfg.stages))


def every_part() -> tuple[Part, ...]:
    """Every base method and stage, in registry order."""
    return (*BASES.values(), *STAGES.values())


def readings_of(part: Part) -> tuple[str, ...]:
    return part.readings


def params_of(part: Part) -> tuple[ParamSpec, ...]:
    """A method's or stage's parameters: those of its readings, then its own."""
    out: dict[str, ParamSpec] = {}
    for r in part.readings:
        out.update({p.field: p for p in READINGS[r].params})
    out.update({p.field: p for p in part.params})
    return tuple(out.values())


def all_params() -> dict[str, ParamSpec]:
    """Every parameter of every method, stage and reading (field -> spec), registry order."""
    out: dict[str, ParamSpec] = {}
    for part in every_part():
        for p in params_of(part):
            out.setdefault(p.field, p)
    return out


def all_formats() -> dict[str, FormatSpec]:
    """Every named format of every method and stage (name -> spec), registry order."""
    out: dict[str, FormatSpec] = {}
    for part in every_part():
        for f in part.formats:
            out.setdefault(f.name, f)
    return out


def used_params(cfg: PipelineConfig) -> tuple[str, ...]:
    """The parameters a configuration must set (the others must be unset)."""
    out: list[str] = []
    for part in parts(cfg):
        for r in part.readings:
            out += [p.field for p in READINGS[r].params]
        out += part.used_params(cfg)
    return tuple(dict.fromkeys(out))


def used_formats(cfg: PipelineConfig) -> tuple[str, ...]:
    """The names in ``formats`` a configuration uses."""
    return tuple(dict.fromkeys(n for part in parts(cfg) for n in part.used_formats(cfg)))


def needs(cfg: PipelineConfig) -> tuple[str, ...]:
    """The per-frame fields (of a frame file) the configuration reads, in order:
    ``fpa_reading``, ``blind_codes``, ``shutter``."""
    return tuple(dict.fromkeys(READINGS[r].frame_field for part in parts(cfg)
                               for r in part.readings))


def takes(cfg: PipelineConfig, reading: str) -> bool:
    """Whether the configuration's base method or a stage takes the reading ``reading``."""
    return any(reading in part.readings for part in parts(cfg))


def reading_registers(cfg: PipelineConfig, part: Part) -> list[Register]:
    """The runtime registers of a part's readings (``reading`` of ``fpa``)."""
    return [reg(cfg) for r in part.readings if (reg := READINGS[r].register) is not None]


def frame(cfg: PipelineConfig, reading: int | Mapping[str, int] | None) -> dict[str, int]:
    """A frame's readings by name from an FPA reading (an int, or None for a method
    without one) or a mapping of readings: the golden model's per-frame argument."""
    if reading is None:
        return {}
    if isinstance(reading, Mapping):
        return {k: int(v) for k, v in reading.items()}
    return {"fpa": int(reading)}


def frame_key(cfg: PipelineConfig, fr: Mapping[str, int]) -> tuple[int, ...]:
    """What decides a frame's coefficients: its base method's readings."""
    return tuple(int(fr[r]) for r in BASES[cfg.base_method].readings if r in fr)


def register_values(cfg: PipelineConfig, registers: Mapping[str, Any],
                    fr: Mapping[str, int]) -> dict[str, Any]:
    """Calibration registers and the frame's readings by register name (``reading``)."""
    out = dict(registers)
    for r in BASES[cfg.base_method].readings:
        reg = READINGS[r].register
        if reg is not None and r in fr:
            out[reg(cfg).name] = int(fr[r])
    return out


def reading_of_register(cfg: PipelineConfig, name: str) -> str | None:
    """The reading whose runtime register is ``name`` (``fpa`` of ``reading``)."""
    for r in BASES[cfg.base_method].readings:
        reg = READINGS[r].register
        if reg is not None and reg(cfg).name == name:
            return r
    return None


def rtl_parameters(cfg: PipelineConfig, what: Iterable[Part] | None = None) -> dict[str, int]:
    """The SystemVerilog parameters of the formats and parameters of ``what`` (default: the
    configuration's base method and stages) for ``cfg``: ``<Name>IntBits``,
    ``<Name>FracBits``, the modes of a computed format, every parameter with an RTL name
    (those ``cfg`` sets)."""
    from irnuc.nuc_fixed.rtl_spec import OVERFLOW_MODES, ROUNDING_MODES

    chosen = tuple(parts(cfg) if what is None else what)
    names = {f.name for p in chosen for f in p.formats}
    fields = {p.field for part in chosen for p in params_of(part)}
    specs = all_formats()
    out: dict[str, int] = {}
    for f in cfg.formats:
        if f.name not in names:
            continue
        spec = specs[f.name]
        out[f"{spec.sv}IntBits"] = f.int_bits
        out[f"{spec.sv}FracBits"] = f.frac_bits
        if "rounding" in spec.rtl_modes:
            out[f"{spec.sv}Rounding"] = ROUNDING_MODES[f.rounding]
        if "overflow" in spec.rtl_modes:
            out[f"{spec.sv}Overflow"] = OVERFLOW_MODES[f.overflow]
    for name, p in all_params().items():
        value = getattr(cfg, name)
        if name in fields and value is not None and p.rtl:
            out[p.rtl] = int(p.to_rtl(value))
    return out


def all_slots() -> tuple[RegisterSlot, ...]:
    """Every register slot of irnuc_axil_regs a method, stage or reading declares."""
    out: dict[str, RegisterSlot] = {}
    for r in READINGS.values():
        if r.slot is not None:
            out.setdefault(r.slot.param, r.slot)
    for part in every_part():
        for s in part.slots:
            out.setdefault(s.param, s)
    return tuple(out.values())


def slot_parameters(cfg: PipelineConfig) -> dict[str, int]:
    """The register file's slot parameters for ``cfg``: each slot's width (``absent`` where
    the configuration has no such register) and count."""
    regs = cfg.registers
    out: dict[str, int] = {}
    for s in all_slots():
        reg = regs.get(s.register)
        out[s.param] = reg.width if reg is not None else s.absent
        if s.count:
            out[s.count] = reg.count if reg is not None else 0
    return out


__all__ = [
    "BASES",
    "READINGS",
    "STAGES",
    "Part",
    "all_formats",
    "all_params",
    "all_slots",
    "base",
    "every_part",
    "frame",
    "frame_key",
    "needs",
    "params_of",
    "parse_method",
    "parts",
    "reading_of_register",
    "reading_registers",
    "register_method",
    "register_values",
    "rtl_parameters",
    "slot_parameters",
    "stage",
    "takes",
    "unregister_method",
    "used_formats",
    "used_params",
]
