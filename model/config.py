"""Sensor configuration: presets (TOML), overrides, and validation before any work.

A configuration is a nested table of sections. :data:`SCHEMA` lists every scalar field with
its type, allowed range and unit; :func:`validate` checks a whole table against it and
raises :class:`~model.validate.ConfigError` naming the dotted field, the value and the
allowed range. The FPA defect table is checked by :class:`model.defects.DefectSpec`.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from irnuc.common import schema
from irnuc.common.digest import digest
from irnuc.model.validate import ConfigError, check_frame_period

PRESET_DIR = Path(__file__).with_name("presets")


@dataclass(frozen=True)
class Field:
    """One scalar configuration field."""

    kind: str  # "float", "int", "bool", "choice", "band", "rings", "tolerances", "table"
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    unit: str = ""
    choices: tuple[str, ...] = ()
    optional: bool = False  # may be absent or None
    default: Any = None  # the value of an absent optional field


_POS = {"lo": 0.0, "lo_open": True}

#: Every field of a sensor configuration. Sections are the first part of the dotted name.
SCHEMA: dict[str, Field] = {
    # radiometry (paper section 3.1)
    "radiometry.band": Field("band", unit="m"),
    "radiometry.rtol": Field("float", 1e-15, 0.1),
    "radiometry.method": Field("choice", choices=("hybrid", "series")),
    "radiometry.scene_emissivity": Field("float", 0.0, 1.0),
    # optics (section 3.2)
    "optics.cone_method": Field("choice", choices=("f_number", "paper_fov")),
    "optics.f_number": Field("float", 0.5, 100.0),
    "optics.fov": Field("float", 0.0, math.pi, lo_open=True, hi_open=True, unit="rad",
                        optional=True),
    "optics.focal_length": Field("float", 0.0, 10.0, lo_open=True, unit="m", optional=True),
    "optics.transmission": Field("float", 0.0, 1.0),
    # focal-plane array (section 3.3)
    "fpa.active_rows": Field("int", 1, 16384),
    "fpa.active_cols": Field("int", 1, 16384),
    "fpa.boundary": Field("rings"),
    "fpa.blind": Field("rings"),
    "fpa.pitch": Field("float", 0.0, 1e-3, lo_open=True, unit="m"),
    "fpa.fill_factor": Field("float", 0.0, 1.0, lo_open=True),
    "fpa.absorptance": Field("float", 0.0, 1.0),
    "fpa.spread": Field("choice", choices=("lognormal", "gamma", "normal_truncated")),
    "fpa.tolerance": Field("tolerances"),
    "fpa.defects": Field("table"),
    # What the pixels outside the active area see (docs/model.md, "Shielded pixels"): the
    # skimming (blind) pixels a shield at the housing or at the substrate temperature; the
    # boundary pixels the scene (edge-extended) or the housing through a shield.
    "fpa.skim_shield": Field("choice", choices=("housing", "substrate"), optional=True,
                             default="housing"),
    "fpa.boundary_view": Field("choice", choices=("scene", "housing"), optional=True,
                               default="scene"),
    # bolometer (section 3.4)
    "bolometer.R_ref": Field("float", 1e-100, 1e100, unit="ohm"),
    "bolometer.T_ref": Field("float", unit="K", **_POS),
    "bolometer.tcr": Field("float", -1.0, 1.0, unit="1/K"),
    "bolometer.g": Field("float", 1e-100, 1e100, unit="W/K"),
    "bolometer.C": Field("float", 1e-100, 1e100, unit="J/K"),
    "bolometer.bias_current": Field("float", 0.0, 1.0, unit="A"),
    "bolometer.t_int": Field("float", 0.0, 10.0, lo_open=True, unit="s"),
    "bolometer.variant": Field("choice", choices=("equilibrium", "paper")),
    "bolometer.net_radiation": Field("bool"),
    "bolometer.rtol": Field("float", 1e-15, 1e-3),
    "bolometer.max_iter": Field("int", 1, 10000),
    "bolometer.runaway_temperature": Field("float", unit="K", **_POS),
    # How the bias pulse is modelled (docs/model.md, section 5): integrated in time over the
    # pulse train, its heat carried to the next pulse (default), or the paper's eq. 16 (one
    # pulse from the unbiased equilibrium, R at the pulse's mean temperature).
    # (absent: "integrated", or "self_heating" with variant = "paper")
    "bolometer.pulse": Field("choice", choices=("integrated", "self_heating"), optional=True),
    # environment
    "environment.T_substrate": Field("float", 100.0, 500.0, unit="K"),
    "environment.T_cam": Field("float", 100.0, 500.0, unit="K"),
    # readout (section 3.5)
    "readout.skimming": Field("choice", choices=("none", "row", "column")),
    "readout.gain": Field("float", 0.0, 1e6, lo_open=True, unit="V/V"),
    "readout.v_reset": Field("float", -100.0, 100.0, unit="V"),
    "readout.v_low": Field("float", -100.0, 100.0, unit="V"),
    "readout.v_high": Field("float", -100.0, 100.0, unit="V"),
    "readout.v_skim": Field("float", -1e3, 1e3, unit="V", optional=True),
    # Frames per second: every pixel is pulsed once per frame period (a drift sequence's
    # own frame_rate replaces it).
    "readout.frame_rate": Field("float", 0.0, 1e5, lo_open=True, unit="Hz", optional=True,
                                default=30.0),
    # The pixels read out beside the image as drift references (``blind_codes``).
    "readout.reference_pixels": Field("choice", choices=("boundary", "blind", "none"),
                                      optional=True, default="boundary"),
    # ADC
    "adc.bits": Field("int", 1, 24),
    "adc.v_low": Field("float", -100.0, 100.0, unit="V"),
    "adc.v_high": Field("float", -100.0, 100.0, unit="V"),
    "adc.rounding": Field("choice", choices=("nearest", "floor")),
    # temporal noise
    "noise.enabled": Field("bool"),
    "noise.johnson": Field("bool"),
    "noise.readout_sigma": Field("float", 0.0, 10.0, unit="V"),
    # 1/f noise of the readout chain at the integrator output (the bolometer's own is
    # flicker_coefficient's)
    "noise.flicker_sigma": Field("float", 0.0, 10.0, unit="V", optional=True, default=0.0),
    # The bolometer's 1/f noise, S_V(f) = k V^2 / f (docs/model.md, section 7)
    "noise.flicker_coefficient": Field("float", 0.0, 1e-6, optional=True, default=1e-13),
    # The thermal fluctuation of each pixel's temperature, k T^2 / C
    "noise.thermal_fluctuation": Field("bool", optional=True, default=True),
    # batching
    "run.chunk_frames": Field("int", 1, 100000),
}

TOLERANCE_KEYS = ("R_ref", "g", "C")


def _field_schema(spec: Field) -> dict[str, Any]:
    """The JSON Schema of one field (types, ranges, units; values checked before use)."""
    from irnuc.model.defects import KNOWN_KEYS as DEFECT_KEYS

    if spec.kind in ("float", "int"):
        return schema.number(spec.lo, spec.hi, lo_open=spec.lo_open, hi_open=spec.hi_open,
                             integer=spec.kind == "int", unit=spec.unit, nullable=spec.optional)
    if spec.kind == "bool":
        return {"type": "boolean"}
    if spec.kind == "choice":
        return {"enum": [*spec.choices, *([None] if spec.optional else [])]}
    if spec.kind == "band":
        return {"type": "array", "minItems": 2, "maxItems": 2,
                "items": schema.number(1e-7, 1e-3, unit="m")}
    if spec.kind == "rings":
        return {"type": "array", "minItems": 4, "maxItems": 4,
                "items": schema.number(0, 4096, integer=True, unit="pixels")}
    if spec.kind == "tolerances":
        return schema.table({k: schema.number(0.0, 1.0) for k in TOLERANCE_KEYS})
    if spec.kind == "table":  # the defect table: keys here, values in DefectSpec
        return {"type": "object", "propertyNames": {"enum": list(DEFECT_KEYS)}}
    raise AssertionError(spec.kind)


def sensor_schema() -> dict[str, Any]:
    """The JSON Schema of a whole sensor configuration, built from :data:`SCHEMA`."""
    sections: dict[str, dict[str, Any]] = {}
    required: dict[str, list[str]] = {}
    for name, spec in SCHEMA.items():
        section, key = name.split(".", 1)
        sections.setdefault(section, {})[key] = _field_schema(spec)
        if not spec.optional:
            required.setdefault(section, []).append(key)
    return schema.table({sec: schema.table(props, required=required.get(sec, []))
                         for sec, props in sections.items()}, required=list(sections))


_SENSOR_SCHEMA: dict[str, Any] = {}


def validate(cfg: Mapping[str, Any], source: str = "sensor configuration") -> dict[str, Any]:
    """Check every field of a nested configuration; return a normalised deep copy.

    Parameters
    ----------
    cfg : mapping
        Sections of fields (a parsed sensor TOML with its overrides).
    source : str
        Named first in error messages (the file, or the preset and its overrides).

    Raises
    ------
    ConfigError
        One line naming the dotted field, the value and the allowed range, for the first
        bad field; an unknown field or section is refused with the nearest known name.
    """
    if not _SENSOR_SCHEMA:
        _SENSOR_SCHEMA.update(sensor_schema())
    try:
        schema.check(cfg, _SENSOR_SCHEMA, source=source)
    except schema.SchemaError as exc:
        raise ConfigError(str(exc)) from None
    out: dict[str, dict[str, Any]] = {}
    for name, spec in SCHEMA.items():
        section, key = name.split(".", 1)
        value = copy.deepcopy(cfg.get(section, {}).get(key))
        if value is None:
            value = spec.default
        if spec.kind == "float" and value is not None:
            value = float(value)
        elif spec.kind == "band":
            from irnuc.model.radiometry import check_band

            value = list(check_band(tuple(value), name))
        elif spec.kind == "tolerances":
            value = {k: float(value.get(k, 0.0)) for k in TOLERANCE_KEYS}
        elif spec.kind == "table":
            value = dict(value)
        out.setdefault(section, {})[key] = value
    b = out["bolometer"]
    if b["pulse"] is None:  # the paper's variant is a property of its single-pulse model
        b["pulse"] = "self_heating" if b["variant"] == "paper" else "integrated"
    _check_relations(out)
    return out


def _check_relations(c: dict[str, dict[str, Any]]) -> None:
    """Checks that involve more than one field."""
    o = c["optics"]
    if o["fov"] is None and o["focal_length"] is None:
        raise ConfigError("optics: give either fov (rad) or focal_length (m)")
    if o["cone_method"] == "paper_fov" and o["fov"] is None:
        raise ConfigError("optics.fov is required with optics.cone_method = 'paper_fov'")
    for section in ("readout", "adc"):
        lo, hi = c[section]["v_low"], c[section]["v_high"]
        if not lo < hi:
            raise ConfigError(f"{section}.v_low = {lo:g} V must be below {section}.v_high = {hi:g} V")
    r = c["readout"]
    if not r["v_low"] <= r["v_reset"] <= r["v_high"]:
        raise ConfigError(
            f"readout.v_reset = {r['v_reset']:g} V is outside the rails "
            f"[{r['v_low']:g}, {r['v_high']:g}] V")
    b = c["bolometer"]
    check_frame_period(1.0 / r["frame_rate"], b["t_int"], what=f"readout.frame_rate = "
                       f"{r['frame_rate']:g} Hz")
    if b["variant"] == "paper" and b["pulse"] != "self_heating":
        raise ConfigError("bolometer.variant = 'paper' needs bolometer.pulse = 'self_heating' "
                          "(the paper's eq. 19 switches the scene on with one bias pulse; the "
                          "integrated pulse train looks at the scene continuously)")
    blind = c["fpa"]["blind"]
    if r["skimming"] == "row" and blind[2] + blind[3] == 0:
        raise ConfigError("readout.skimming = 'row' needs blind columns: fpa.blind[2] + fpa.blind[3] >= 1")
    if r["skimming"] == "column" and blind[0] + blind[1] == 0:
        raise ConfigError("readout.skimming = 'column' needs blind rows: fpa.blind[0] + fpa.blind[1] >= 1")
    from irnuc.model.defects import DefectSpec

    spec = DefectSpec.from_dict(c["fpa"]["defects"], path="fpa.defects")
    spec.check_frame((c["fpa"]["active_rows"], c["fpa"]["active_cols"]))


def _set_dotted(cfg: dict[str, Any], dotted: str, value: Any) -> None:
    parts = dotted.split(".")
    node = cfg
    for p in parts[:-1]:
        node = node.setdefault(p, {})
        if not isinstance(node, dict):
            raise ConfigError(f"override {dotted!r}: {p} is not a table")
    node[parts[-1]] = value


def apply_overrides(cfg: Mapping[str, Any], overrides: Mapping[str, Any] | None) -> dict[str, Any]:
    """A deep copy of ``cfg`` with dotted-key overrides, e.g. {"fpa.active_rows": 48}."""
    out = copy.deepcopy(dict(cfg))
    for key, value in (overrides or {}).items():
        _set_dotted(out, key, value)
    return out


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file; a preset may name a ``base`` preset that it changes."""
    path = Path(path)
    data = schema.read_toml(path)
    base = data.pop("base", None)
    if base is not None:
        if base not in preset_names():
            raise ConfigError(f"{path}: base = {base!r} is not one of the presets "
                              f"({', '.join(preset_names())})")
        merged = load_toml(PRESET_DIR / f"{base}.toml")
        for section, table in data.items():
            if isinstance(table, dict):
                merged.setdefault(section, {}).update(table)
            else:
                merged[section] = table
        data = merged
    return data


def preset_names() -> list[str]:
    """Names of the presets shipped with irnuc."""
    return sorted(p.stem for p in PRESET_DIR.glob("*.toml"))


def load_preset(name: str, overrides: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """A validated configuration from a named preset plus dotted-key overrides."""
    if name not in preset_names():
        raise ConfigError(f"preset = {name!r} is not one of {preset_names()}"
                          f"{schema.nearest(name, preset_names())}")
    source = f"preset {name!r}" + (" with overrides" if overrides else "")
    return validate(apply_overrides(load_toml(PRESET_DIR / f"{name}.toml"), overrides), source)


def load_config(path: str | Path, overrides: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """A validated configuration from a TOML file plus dotted-key overrides."""
    source = str(path) + (" with overrides" if overrides else "")
    return validate(apply_overrides(load_toml(path), overrides), source)


def config_digest(cfg: Mapping[str, Any]) -> str:
    """Short hash of a validated configuration (for provenance and caches)."""
    return digest(cfg)
