"""The report configuration (``report_<name>.toml`` or a TOML file): read, ``[quick]``
overrides applied, validated with the project's one schema library (jsonschema through
:mod:`irnuc.common.schema`).

Every section and key is known: a misspelled one is an error naming the file, the dotted
field and the nearest known name (never a PASS with no metrics). The ``[quick]`` overrides
are applied to a copy and validated too, also when ``--quick`` is not given, so a typo in
them is found at once.
"""

from __future__ import annotations

import copy
import hashlib
import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from irnuc.common.errors import UserError
from irnuc.common.schema import check, nearest, number, read_toml, table

REPORT_DIR = Path(__file__).resolve().parent


class ReportError(UserError):
    """A report configuration or input is invalid (names the field and the allowed values)."""


# ---------------------------------------------------------------------------------------
# Schema
# ---------------------------------------------------------------------------------------
_KELVIN = number(1.0, 1e4, unit="K")
_SEED = number(0, 2**63 - 1, integer=True)
_ROUNDING = {"enum": ["truncate", "half_up", "half_even"]}


def _ints(lo: int, hi: int, extra: tuple[str, ...] = ()) -> dict[str, Any]:
    item: dict[str, Any] = number(lo, hi, integer=True)
    if extra:
        item = {"anyOf": [item, {"enum": list(extra)}]}
    return {"type": "array", "items": item, "minItems": 1, "maxItems": 64}


_FRAMES = {
    "preset": {"type": "string", "minLength": 1},
    "seed": _SEED,
    "rows": number(3, 4096, integer=True),
    "cols": number(3, 4096, integer=True),
    "repeats": number(1, 1000, integer=True),
    "t_low": _KELVIN,
    "t_high": _KELVIN,
    "t_eval": {"type": "array", "items": _KELVIN, "minItems": 1, "maxItems": 32},
    "pipeline": {"type": "string", "minLength": 1},
    "overrides": {"type": "object"},
}
_FRAMES_REQUIRED = ("preset", "seed", "rows", "cols", "repeats", "t_low", "t_high", "t_eval",
                    "pipeline")

SCHEMA: dict[str, Any] = table({
    "name": {"type": "string"},
    "sensor": table(_FRAMES, _FRAMES_REQUIRED),
    "sweep": table({
        **_FRAMES,
        "gain_frac_bits": _ints(0, 32),
        "offset_frac_bits": _ints(0, 32, ("same",)),
        "gain_int_bits": _ints(0, 16, ("auto",)),
        "offset_int_bits": _ints(1, 32, ("auto",)),
        "coeff_rounding": {"type": "array", "items": _ROUNDING, "minItems": 1},
        "rounding": {"type": "array", "items": _ROUNDING, "minItems": 1},
        "max_error": number(0.0, 1e12, lo_open=True),
        "error_metric": {"enum": ["err_max_lsb", "err_rms_lsb", "residual_nu",
                                  "residual_nu_adc_lsb", "radial_rms_lsb"]},
        "workers": number(0, 256, integer=True),
        "frame_rate_hz": number(0.0, 1e5, lo_open=True, unit="Hz"),
    }, (*_FRAMES_REQUIRED, "gain_frac_bits", "offset_frac_bits", "max_error")),
    "synth": table({
        "fit_points": number(3, 16, integer=True),
        "candidates": number(0, 16, integer=True),
        "workers": number(0, 16, integer=True),
        "speed": {"enum": [6, 7, 8]},
        "freq_mhz": number(1.0, 1000.0, unit="MHz"),
        "seed": number(0, 2**31 - 1, integer=True),
        "dsp_lut_equivalent": number(0, 100_000),
    }),
    "paper": table({
        "preset": {"type": "string", "minLength": 1},
        "seed": _SEED,
        "rows": number(3, 4096, integer=True),
        "cols": number(3, 4096, integer=True),
        "frac_bits": _ints(0, 32),
        "grid_temps": {"type": "array", "items": _KELVIN, "minItems": 1, "maxItems": 16},
        "t_low": _KELVIN,
        "t_high": _KELVIN,
        "reference_nu": {"type": "array", "items": number(0.0, 1e6), "minItems": 1},
        "table1": table({
            "rows": number(3, 4096, integer=True),
            "cols": number(3, 4096, integer=True),
            "temps": {"type": "array", "items": _KELVIN, "minItems": 1, "maxItems": 16},
            "tolerances": {"type": "array", "items": number(0.0, 1.0, lo_open=True),
                           "minItems": 1, "maxItems": 16},
            "skimming": {"type": "array", "items": {"enum": ["row", "column", "none"]},
                         "minItems": 1},
        }, ("rows", "cols", "temps", "tolerances", "skimming")),
    }, ("preset", "seed", "rows", "cols", "frac_bits", "grid_temps", "reference_nu")),
    "cosim": table({
        "pipelines": {"type": "array", "minItems": 1, "maxItems": 8,
                      "items": {"type": "string", "minLength": 1}},
        "tests": {"type": "array", "minItems": 1, "maxItems": 32,
                  "items": {"type": "string", "minLength": 1}},
        "timeout_base": number(1.0, 86400.0, unit="s"),
        "jobs": number(1, 16, integer=True),
        "waves": {"type": "boolean"},
        "coverage": {"type": "boolean"},
        "seed": number(0, 2**31 - 1, integer=True),
    }, ("pipelines", "tests")),
    "temperature": table({
        "preset": {"type": "string", "minLength": 1},
        "seed": _SEED,
        "rows": number(3, 512, integer=True),
        "cols": number(3, 512, integer=True),
        "overrides": {"type": "object"},
        "fpa_K": {"type": "array", "items": _KELVIN, "minItems": 2, "maxItems": 2},
        "fpa_step_K": number(0.01, 100.0, unit="K"),
        "scene_K": {"type": "array", "items": _KELVIN, "minItems": 1, "maxItems": 16},
        "ramp_K_per_min": number(0.0, 100.0, lo_open=True, unit="K/min"),
        "methods": {"type": "array", "minItems": 1, "maxItems": 32,
                    "items": {"type": "string", "minLength": 1}},
        "frac_bits": _ints(0, 24),
        "ffc_periods_min": {"type": "array", "items": number(0.0, 1e4, lo_open=True, unit="min"),
                            "minItems": 0, "maxItems": 16},
        "ffc_changes_K": {"type": "array", "items": number(0.0, 100.0, lo_open=True, unit="K"),
                          "minItems": 0, "maxItems": 16},
        "ffc_either": {"type": "array", "minItems": 0, "maxItems": 16,
                       "items": {"type": "array", "minItems": 2, "maxItems": 2,
                                 "items": number(0.0, 1e4, lo_open=True)}},
        "scenarios": {"type": "array", "minItems": 1, "maxItems": 16,
                      "items": {"type": "string", "minLength": 1}},
        "node_K": number(0.01, 10.0, unit="K"),
        "node_max_s": number(1.0, 1e5, unit="s"),
        "max_peaks": number(1, 10_000, integer=True),
        "housing_offset_K": {"type": "array", "items": number(-50.0, 50.0, unit="K"),
                             "minItems": 1, "maxItems": 16},
        "cosim_scenario": {"type": "string", "minLength": 1},
        "cosim_min_pixels": number(1, 10**9, integer=True),
        "tolerance_netd": number(0.0, 1e3, lo_open=True),
        "tolerance_mK": number(0.0, 1e6, lo_open=True, unit="mK"),
        "frame_rate_hz": number(0.0, 1e5, lo_open=True, unit="Hz"),
        "bandwidth_frame": {"type": "array", "items": number(1, 16384, integer=True),
                            "minItems": 2, "maxItems": 2},
        "noise_frames": number(2, 1000, integer=True),
        "workers": number(0, 256, integer=True),
        "synth": {"type": "boolean"},
        "cosim": {"type": "boolean"},
        "cosim_frames": number(1, 10_000, integer=True),
        "cosim_rows": number(3, 4096, integer=True),
        "cosim_cols": number(3, 4096, integer=True),
        "cosim_seed": number(0, 2**31 - 1, integer=True),
        "ffc_every": number(2, 10_000, integer=True),
        "dsp_lut_equivalent": number(0, 100_000),
        "synth_seeds": number(1, 64, integer=True),
        "anchors": {"type": "boolean"},
        "place": {"type": "boolean"},
    }),
    "precision": table({
        "quick": {"type": "boolean"},
        "components": {"type": "array", "items": {"type": "string"}, "minItems": 1},
    }),
    "quick": {"type": "object"},
})


# ---------------------------------------------------------------------------------------
# Loading
# ---------------------------------------------------------------------------------------
def input_file(path: str | Path, flag: str, what: str) -> Path:
    """A file the user names with ``flag``: a one-line :class:`ReportError` when it is
    missing or a folder."""
    p = Path(path)
    if not p.exists():
        raise ReportError(f"{flag} {path}: no such file")
    if p.is_dir():
        raise ReportError(f"{flag} {path}: is a folder, not {what}")
    return p


def embedded_names() -> list[str]:
    return sorted(p.stem.removeprefix("report_") for p in REPORT_DIR.glob("report_*.toml"))


def config_path(name_or_path: str) -> Path:
    """The file of an embedded configuration name, or the path given."""
    path = REPORT_DIR / f"report_{name_or_path}.toml"
    if "/" not in name_or_path and path.is_file():
        return path
    p = Path(name_or_path)
    if p.suffix == ".toml" or p.exists() or "/" in name_or_path:
        return p
    known = embedded_names()
    raise ReportError(f"--config {name_or_path!r} is neither an embedded configuration "
                      f"({', '.join(known)}){nearest(name_or_path, known)} nor a TOML file")


def _set_dotted(d: dict[str, Any], dotted: str, value: Any, source: str) -> None:
    keys = dotted.split(".")
    cur = d
    for i, k in enumerate(keys[:-1]):
        nxt = cur.get(k)
        if not isinstance(nxt, dict):
            where = ".".join(keys[:i + 1])
            raise ReportError(f"{source}: quick override {dotted!r}: {where} is not a table "
                              "of the configuration")
        cur = nxt
    cur[keys[-1]] = value


#: The sections that run a phase: a configuration without any checks nothing.
PHASE_SECTIONS = ("sensor", "sweep", "paper", "temperature", "cosim", "precision")
#: Model fields a section sets by its own keys (never by ``overrides`` beside them).
_FRAME_FIELDS = {"fpa.active_rows": "rows", "fpa.active_cols": "cols"}


def _check_frames(cfg: Mapping[str, Any], source: str) -> None:
    """Each section that simulates frames: its preset, its overrides (one model field set
    one way only) and its pipeline, all before the first progress line."""
    from irnuc import model
    from irnuc.nuc_fixed import load_pipeline

    for sec in ("sensor", "sweep", "paper"):
        s = cfg.get(sec)
        if not s:
            continue
        known = model.preset_names()
        if s["preset"] not in known:
            raise ReportError(f"{source}: {sec}.preset = {s['preset']!r} is not a sensor preset"
                              f"{nearest(s['preset'], known)} (known: {', '.join(known)})")
        over = dict(s.get("overrides") or {})
        for key, field in _FRAME_FIELDS.items():
            if key in over:
                raise ReportError(f"{source}: {sec}.overrides[{key!r}] = {over[key]!r} beside "
                                  f"{sec}.{field} = {s[field]!r}: set the frame size with "
                                  f"{sec}.{field} only")
        frame = {"fpa.active_rows": s["rows"], "fpa.active_cols": s["cols"]}
        try:
            model.load_preset(s["preset"], {**frame, **over})
        except UserError as exc:
            raise ReportError(f"{source}: {sec}.overrides: {exc}") from None
        if "pipeline" in s:
            try:
                load_pipeline(s["pipeline"])
            except UserError as exc:
                raise ReportError(f"{source}: {sec}.pipeline: {exc}") from None


def _check_precision(cfg: Mapping[str, Any], source: str) -> None:
    comps = (cfg.get("precision") or {}).get("components")
    if comps:
        from irnuc.reports.studies.precision import component_names

        try:
            component_names(comps)
        except UserError as exc:
            raise ReportError(f"{source}: precision.{exc}") from None


def _check_temperature(cfg: Mapping[str, Any], source: str) -> None:
    """The ``[temperature]`` section: its preset, overrides and methods resolved, its
    ranges ordered, before any work."""
    t = cfg.get("temperature")
    if t is None:
        return
    from irnuc import model
    from irnuc.nuc_fixed import load_pipeline

    known = model.preset_names()
    preset = t.get("preset", "default")
    if preset not in known:
        raise ReportError(f"{source}: temperature.preset = {preset!r} is not a sensor preset"
                          f"{nearest(preset, known)} (known: {', '.join(known)})")
    over = dict(t.get("overrides") or {})
    for key in ("environment.T_substrate", "environment.T_cam", *_FRAME_FIELDS):
        if key in over:
            raise ReportError(f"{source}: temperature.overrides[{key!r}]: set by the sign-off "
                              "(temperature.fpa_K, temperature.rows/cols), not by an override")
    try:
        model.load_preset(preset, over)
    except UserError as exc:
        raise ReportError(f"{source}: temperature.overrides: {exc}") from None
    lo, hi = t.get("fpa_K", (288.0, 308.0))
    if not lo < hi:
        raise ReportError(f"{source}: temperature.fpa_K = [{lo:g}, {hi:g}]: the first must be "
                          "below the second")
    for name in t.get("methods", ()):
        try:
            load_pipeline(name)
        except (ValueError, UserError) as exc:
            raise ReportError(f"{source}: temperature.methods: {exc}") from None
    if "scenarios" in t or "cosim_scenario" in t:
        from irnuc.model.sequence import scenario_names

        names = scenario_names()
        for name in [*t.get("scenarios", ()), *([t["cosim_scenario"]] if "cosim_scenario" in t else [])]:
            if name not in names:
                raise ReportError(f"{source}: temperature.scenarios: {name!r} is not a shipped "
                                  f"scenario{nearest(name, names)} (known: {', '.join(names)})")
    if "tolerance_mK" in t and "tolerance_netd" in t:
        raise ReportError(f"{source}: temperature.tolerance_mK and temperature.tolerance_netd "
                          "both given: set the tolerance one way")


def check_runs_something(cfg: Mapping[str, Any], source: str, *, no_cosim: bool = False,
                         junit: bool = False) -> None:
    """A report that would run no phase is an error, never a PASS that checked nothing
    (an empty file, one holding only ``name``, only ``[cosim]`` with ``--no-cosim``)."""
    ran = [s for s in PHASE_SECTIONS if s in cfg and not (s == "cosim" and no_cosim)]
    if not ran and not junit:
        why = " (its [cosim] is skipped by --no-cosim)" if no_cosim and "cosim" in cfg else ""
        raise ReportError(f"{source}: no phase to run{why}; a report needs at least one of "
                          f"[{'], ['.join(PHASE_SECTIONS)}] (a run that checks nothing is "
                          "not a pass)")


def _check_more(cfg: Mapping[str, Any], source: str) -> None:
    """What a schema cannot say: relations between fields, and the names the fields give
    (presets, pipelines, components, tests) resolved before any work."""
    _check_frames(cfg, source)
    _check_precision(cfg, source)
    _check_temperature(cfg, source)
    for sec in ("sensor", "sweep", "paper"):
        s = cfg.get(sec)
        if s and "t_low" in s and "t_high" in s and not s["t_low"] < s["t_high"]:
            raise ReportError(f"{source}: {sec}.t_low = {s['t_low']:g} K must be below "
                              f"{sec}.t_high = {s['t_high']:g} K")
    p = cfg.get("paper")
    if p and len(p["reference_nu"]) != len(p["frac_bits"]):
        raise ReportError(f"{source}: paper.reference_nu has {len(p['reference_nu'])} values but "
                          f"paper.frac_bits has {len(p['frac_bits'])}")
    c = cfg.get("cosim")
    if c:
        from irnuc.nuc_fixed import load_pipeline

        for name in c["pipelines"]:
            if name == "recommended":
                if "sweep" not in cfg:
                    raise ReportError(f"{source}: cosim.pipelines holds 'recommended' but the "
                                      "configuration has no [sweep] to recommend widths")
                continue
            try:
                load_pipeline(name)
            except (ValueError, UserError) as exc:
                raise ReportError(f"{source}: cosim.pipelines: {exc}") from None
        from irnuc.cocotb_tests import tb_top
        from irnuc.cosim import cocotb_test_names

        known = cocotb_test_names(tb_top)
        for t in c["tests"]:
            if t not in known:
                raise ReportError(f"{source}: cosim.tests holds {t!r}, not a test of "
                                  f"{tb_top.__name__}{nearest(t, known)} (known: "
                                  f"{', '.join(known)})")
    if "synth" in cfg and "sweep" not in cfg:
        raise ReportError(f"{source}: [synth] costs the sweep's points; the configuration has no [sweep]")


def _unknown_first(doc: Any, schema: Mapping[str, Any], source: str, where: str = "") -> None:
    """The first unknown key in the order of the file (a misspelled section is named by
    itself, not by a later one), with the nearest known name."""
    if not isinstance(doc, Mapping) or schema.get("additionalProperties") is not False:
        return
    known = list(schema.get("properties", {}))
    for key, value in doc.items():
        field = f"{where}.{key}" if where else str(key)
        if key not in known:
            raise ReportError(f"{source}: {field} is not a known "
                              f"{'section' if not where else 'field'}{nearest(str(key), known)} "
                              f"(known here: {', '.join(sorted(known))})")
        _unknown_first(value, schema["properties"][key], source, field)


def load_report_config(name_or_path: str = "default", quick: bool = False) -> dict[str, Any]:
    """The validated report configuration (``--quick``: its ``[quick]`` overrides applied)."""
    path = config_path(name_or_path)
    source = f"--config {path}" if path.parent != REPORT_DIR else f"--config {name_or_path}"
    cfg = read_toml(path, "--config")
    _unknown_first(cfg, SCHEMA, source)
    check(cfg, SCHEMA, source=source)
    over = dict(cfg.pop("quick", {}) or {})
    quick_cfg = copy.deepcopy(cfg)
    for k, v in over.items():
        _set_dotted(quick_cfg, k, v, source)
    check(quick_cfg, SCHEMA, source=f"{source} [quick]")
    _check_more(cfg, source)
    _check_more(quick_cfg, f"{source} [quick]")
    out = quick_cfg if quick else cfg
    out.setdefault("name", path.stem.removeprefix("report_"))
    out["quick"] = bool(quick)
    if quick:
        # what each override replaced (None: a key the full run leaves at its default), so
        # that a phase can name what --quick left out (quick_replaced)
        out["quick_overrides"] = {k: _get_dotted(cfg, k) for k in over}
    return out


def _get_dotted(d: Mapping[str, Any], dotted: str) -> Any:
    cur: Any = d
    for k in dotted.split("."):
        if not isinstance(cur, Mapping) or k not in cur:
            return None
        cur = cur[k]
    return copy.deepcopy(cur)


def quick_replaced(cfg: Mapping[str, Any], dotted: str) -> tuple[bool, Any]:
    """Whether ``--quick`` changed the field ``dotted`` of this run's configuration, and
    the value the full run has there (None: the phase's default)."""
    over = cfg.get("quick_overrides") or {}
    if not cfg.get("quick") or dotted not in over:
        return False, None
    return _get_dotted(cfg, dotted) != over[dotted], over[dotted]


def config_hash(cfg: Mapping[str, Any]) -> str:
    return hashlib.sha256(json.dumps(cfg, sort_keys=True, default=str).encode()).hexdigest()[:16]
