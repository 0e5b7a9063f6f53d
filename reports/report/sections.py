"""The report's results, typed: what each phase gives the page, the status checks and the later
phases, read-only; JSON (``summary.json``) only through :meth:`Record.to_json`.

A phase stores one :class:`Section` (``Report.sections[name]``): the report's own results as
typed fields (the sweep's :class:`Recommendation` with its :class:`CosimCheck` and
:class:`SynthCheck`, the co-simulation's counts, ...) and the study's tables beside them as
read-only mappings and tuples (``data``). A later phase that adds to an earlier section (the
synthesis to the sweep, the co-simulation to the recommendation) stores a new section made
with :func:`dataclasses.replace`; nothing is changed in place. The page reads the fields by
name (a template's ``s.sweep.recommended.cosim.passed``; a field the section does not type
is its data's: ``s.sweep.points``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

#: Field metadata: leave the field out of the JSON while it is None (a key the section had
#: only once a later phase set it).
OMIT = {"omit_none": True}


def frozen(value: Any) -> Any:
    """A JSON-like value made read-only: mappings as ``MappingProxyType``, lists as tuples,
    recursively (records stay as they are)."""
    if isinstance(value, Record):
        return value
    if isinstance(value, Mapping):
        return MappingProxyType({k: frozen(v) for k, v in value.items()})
    if isinstance(value, list | tuple):
        return tuple(frozen(v) for v in value)
    return value


def thaw(value: Any) -> Any:
    """The JSON-ready copy of a value: records by :meth:`Record.to_json`, mappings as dicts,
    tuples as lists."""
    if isinstance(value, Record):
        return value.to_json()
    if isinstance(value, Mapping):
        return {k: thaw(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [thaw(v) for v in value]
    return value


@dataclass(frozen=True)
class Record:
    """A typed result; its JSON is its fields (``data``'s keys first, for a section).
    ``record[name]``, ``record.get(name)`` and ``name in record`` read its fields (a field
    left out of the JSON while None reads as absent): the page reads records and the JSON's
    mappings alike."""

    def _typed(self) -> tuple[str, ...]:
        return tuple(f.name for f in dataclasses.fields(self) if f.name != "data")

    def _absent(self, key: str) -> bool:
        f = next(f for f in dataclasses.fields(self) if f.name == key)
        return getattr(self, key) is None and bool(f.metadata.get("omit_none"))

    def __getitem__(self, key: str) -> Any:
        if key in self._typed() and not self._absent(key):
            return getattr(self, key)
        raise KeyError(key)

    def get(self, key: str, default: Any = None) -> Any:
        try:
            return self[key]
        except KeyError:
            return default

    def __contains__(self, key: object) -> bool:
        return isinstance(key, str) and key in self._typed() and not self._absent(key)

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name == "data":
                out.update(thaw(v))
            elif not (v is None and f.metadata.get("omit_none")):
                out[f.name] = thaw(v)
        return out


@dataclass(frozen=True)
class Section(Record):
    """A phase's result: typed fields (subclasses) and the study's tables (``data``, read
    only). ``section[name]`` and ``section.get(name)`` read a field or, failing that, the
    data (the page's templates read both with dots)."""

    data: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))

    def __post_init__(self) -> None:
        object.__setattr__(self, "data", frozen(self.data))

    def __getitem__(self, key: str) -> Any:
        if key in self._typed():
            return super().__getitem__(key)
        return self.data[key]

    def __contains__(self, key: object) -> bool:
        return super().__contains__(key) or key in self.data

    def keys(self) -> Iterator[str]:
        yield from self.data
        yield from (k for k in self._typed() if not self._absent(k))

    @classmethod
    def of(cls, values: Mapping[str, Any], **typed: Any) -> Section:
        """A section of ``values``: the keys that are fields of ``cls`` typed, the others
        its data."""
        names = {f.name for f in dataclasses.fields(cls)} - {"data"}
        fields_ = {k: values[k] for k in names if k in values}
        data = {k: v for k, v in values.items() if k not in names}
        return cls(data=data, **{**fields_, **typed})


# ---- the sweep ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class CosimCheck(Record):
    """The co-simulation of a configuration the report recommends (its tests in the
    co-simulation phase)."""

    passed: int
    failed: int
    pixels: int
    mismatches: int
    tests: tuple[str, ...]


@dataclass(frozen=True)
class SynthCheck(Record):
    """``irnuc synth`` of the recommended configuration."""

    fmax_mhz: float
    xc7: Mapping[str, Any]
    ecp5: Mapping[str, Any]
    device: str | None
    speed: int | None
    target_mhz: float | None
    critical_path: tuple[Any, ...]

    def __post_init__(self) -> None:
        for name in ("xc7", "ecp5", "critical_path"):
            object.__setattr__(self, name, frozen(getattr(self, name)))


@dataclass(frozen=True)
class Recommendation(Section):
    """The sweep's recommended widths: the point's record (``data``: its formats, bits,
    errors, edges, pipeline) and what the later phases found: its co-simulation, its
    synthesis and its datapath cost."""

    cosim: CosimCheck | None = None
    synth: SynthCheck | None = None
    datapath_cost: float | None = field(default=None, metadata=OMIT)


@dataclass(frozen=True)
class SweepSection(Section):
    """The bit-width sweep: its tolerance, its points (each with its hardware cost once
    synthesized), the recommendation, the synthesis and the fronts."""

    tolerance: Mapping[str, Any] = field(default_factory=dict)
    points: tuple[Mapping[str, Any], ...] = ()
    recommended: Recommendation | None = None
    synth: Mapping[str, Any] | None = field(default=None, metadata=OMIT)
    pareto_memory: tuple[int, ...] | None = field(default=None, metadata=OMIT)
    pareto_datapath: tuple[int, ...] | None = field(default=None, metadata=OMIT)

    def __post_init__(self) -> None:
        super().__post_init__()
        for name in ("tolerance", "points", "synth", "pareto_memory", "pareto_datapath"):
            object.__setattr__(self, name, frozen(getattr(self, name)))


# ---- the co-simulation -------------------------------------------------------------------------

@dataclass(frozen=True)
class CosimSection(Section):
    """The co-simulation (the suite this report ran, or an ingested JUnit file): the counts
    the status reads, the rest as data (cases, configurations, coverage, mutation)."""

    tests: int = 0
    passed: int = 0
    failed: int = 0
    error: int = 0
    timeout: int | None = field(default=None, metadata=OMIT)
    pixels: int | None = field(default=None, metadata=OMIT)
    mismatches: int | None = field(default=None, metadata=OMIT)


__all__ = ["OMIT", "CosimCheck", "CosimSection", "Recommendation", "Record", "Section",
           "SweepSection", "SynthCheck", "frozen", "thaw"]
