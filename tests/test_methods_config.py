"""The `method` key, coefficient formats and memory layouts of pipeline configurations."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from irnuc.nuc_fixed import ConfigError, load_pipeline, pipeline_names
from irnuc.nuc_fixed.config import BASE_METHODS, STAGES, PipelineConfig, parse_method
from irnuc.nuc_fixed.layout import layouts_dict, pack_memory, rtl_package, unpack_memory

ALL = pipeline_names(method=None)


def test_every_method_and_stage_has_a_14_bit_configuration() -> None:
    cfgs = [load_pipeline(n) for n in ALL]
    for m in BASE_METHODS:
        assert any(c.base_method == m and c.adc_bits == 14 for c in cfgs), m
    for s in STAGES:
        assert any(s in c.stages and c.adc_bits == 14 for c in cfgs), s
    methods = {c.method for c in cfgs}
    assert {"two_point+blind_drift", "tc_offset+ffc", "quadratic+ffc"} <= methods


def test_two_point_configurations_are_unchanged() -> None:
    # The default filter keeps today's callers (the RTL tests) on two-point configurations,
    # and a two-point configuration's dictionary has no method fields (digests unchanged).
    assert pipeline_names() == ["typical14", "wide16", "minimal"]
    cfg = load_pipeline("typical14")
    assert cfg.method == "two_point" and "method" not in cfg.to_dict()
    assert set(cfg.to_dict()) == {"name", "adc_bits", "gain_int_bits", "gain_frac_bits",
                                  "offset_int_bits", "offset_frac_bits", "out_bits", "rounding",
                                  "overflow", "max_width", "max_height", "description"}
    assert cfg.word_fields == {"gain": (0, 16), "offset": (16, 16), "bad": (32, 1)}
    assert cfg.digest() == PipelineConfig(**cfg.to_dict()).digest()


@pytest.mark.parametrize("name", ALL)
def test_round_trips(tmp_path: Path, name: str) -> None:
    cfg = load_pipeline(name)
    assert PipelineConfig(**cfg.to_dict()) == cfg
    f = tmp_path / "p.toml"
    f.write_text(cfg.to_toml())
    assert load_pipeline(str(f)) == cfg
    assert hash(cfg) == hash(PipelineConfig(**cfg.to_dict()))


@pytest.mark.parametrize(("method", "match"), [
    ("three_point", "'three_point' is not a base method"),
    ("two_pont", "did you mean 'two_point'"),
    ("ffc", "a stage; put a base method first"),
    ("two_point+shutter", "'shutter' is not a stage"),
    ("piecewise+blind_drift", "blind_drift composes only with one_point, two_point"),
    ("two_point+ffc+ffc", "named twice"),
    ("two_point+blind_drift+ffc", "not supported"),
])
def test_bad_methods(method: str, match: str) -> None:
    with pytest.raises(ConfigError, match=re.escape(match)):
        parse_method(method)


def _entry(**kw) -> dict:
    base = load_pipeline("quadratic14").to_dict()
    base.pop("name")
    base.update(kw)
    return base


@pytest.mark.parametrize(("change", "match"), [
    ({"square_bits": None}, "square_bits is required but missing"),
    ({"tables": 3}, "tables is not used by this method"),
    ({"formats": {}}, "formats.quad is required but missing"),
    ({"formats": {"quad": {"int_bits": 10, "frac_bits": 6, "signed": False}}},
     "formats.quad.signed = false"),
    ({"formats": {"quad": {"int_bits": 10, "frac_bits": 6, "signed": True},
                  "knee": {"int_bits": 14, "frac_bits": 2, "signed": False}}},
     "formats.knee is not used by this method"),
    ({"formats": {"quad": {"int_bits": 10, "frac_bits": 6, "signed": True, "overflow": "wrap"}}},
     "formats.quad.overflow = 'wrap'"),
    ({"formats": {"quad": {"int_bits": 10, "frac_bits": 6, "signed": True, "roundng": "x"}}},
     "did you mean 'rounding'"),
    ({"formats": {"quadd": {"int_bits": 10, "frac_bits": 6, "signed": True}}}, "quadd"),
    ({"formats": {"quad": {"int_bits": 30, "frac_bits": 30, "signed": True}}},
     "the allowed maximum is 62"),
    ({"method": "table_interp"}, "square_bits is not used by this method"),
    ({"method": "table_interp", "square_bits": None, "formats": {
        "weight": {"int_bits": 1, "frac_bits": 15, "signed": False}}},
     "reading_bits is required but missing"),
])
def test_bad_method_fields_are_named(tmp_path: Path, change: dict, match: str) -> None:
    entry = _entry(**change)
    entry = {k: v for k, v in entry.items() if v is not None}
    with pytest.raises(ConfigError, match=re.escape(match)):
        PipelineConfig(name="t", **entry)
    # The same from a TOML file: the message names the file.
    f = tmp_path / "bad.toml"
    f.write_text(_toml(entry))
    with pytest.raises(ConfigError, match=re.escape(match)):
        load_pipeline(str(f))


def _toml(entry: dict) -> str:
    import json

    lines = ["[t]"]
    for k, v in entry.items():
        if k == "formats":
            for n, fd in v.items():
                body = ", ".join(f"{kk} = {json.dumps(vv)}" for kk, vv in fd.items())
                lines.append(f"formats.{n} = {{ {body} }}")
        else:
            lines.append(f"{k} = {json.dumps(v)}")
    return "\n".join(lines) + "\n"


def test_other_checks() -> None:
    with pytest.raises(ConfigError, match="ffc_frames = 6 must be a power of two"):
        load_pipeline("ffc14").replace(ffc_frames=6)
    with pytest.raises(ConfigError, match=re.escape("formats.knee.int_bits = 12 must be at least adc_bits")):
        load_pipeline("piecewise14").replace(formats={"knee": {"int_bits": 12}})
    with pytest.raises(ConfigError, match=re.escape("cannot hold 1.0")):
        load_pipeline("table14").replace(formats={"weight": {"int_bits": 0, "frac_bits": 15}})
    with pytest.raises(ConfigError, match=re.escape("drift_gain.frac_bits = 1 must be at least")):
        load_pipeline("drift14").replace(formats={"drift_gain": {"frac_bits": 1}})
    with pytest.raises(ConfigError, match="tg1 is required"):
        load_pipeline("tcoffset14").replace(tc_gain=True)
    with pytest.raises(ConfigError, match="the golden model's uint64 words hold at most 64"):
        load_pipeline("piecewise14").replace(formats={"knee": {"frac_bits": 20}})


@pytest.mark.parametrize("name", ALL)
def test_layouts_pack_like_bit_strings(name: str) -> None:
    cfg = load_pipeline(name)
    rng = np.random.default_rng(9)
    for mem in cfg.memories.values():
        vals = {}
        bits = ""
        for f in mem.fields:
            lo = -(1 << (f.width - 1)) if f.signed else 0
            v = int(rng.integers(lo, lo + (1 << f.width)))
            vals[f.name] = np.array([v])
            bits = format(v % (1 << f.width), f"0{f.width}b") + bits  # MSB first
        word = pack_memory(vals, mem)
        assert int(word[0]) == int(bits, 2) and len(bits) == mem.word_bits
        back = unpack_memory(word, mem)
        assert {k: int(v[0]) for k, v in back.items()} == {k: int(v[0]) for k, v in vals.items()}
    # The generated RTL package names every field with its LSB and width.
    pkg = rtl_package(cfg)
    assert pkg.startswith("// Generated") and f"package irnuc_{name}_pkg;" in pkg
    for mem in cfg.memories.values():
        assert f"}} {mem.name}_word_t;" in pkg
        for f in mem.fields:
            stem = "".join(p[:1].upper() + p[1:] for p in f"{mem.name}_{f.name}".split("_"))
            assert f"localparam int unsigned {stem}Lsb = {f.lsb};" in pkg
            assert f"localparam int unsigned {stem}Bits = {f.width};" in pkg
    d = layouts_dict(cfg)
    assert d["method"] == cfg.method and set(d["memories"]) == set(cfg.memories)


def test_two_point_layout_is_version_1() -> None:
    cfg = load_pipeline("typical14")
    m = cfg.memories["coeffs"]
    assert [(f.name, f.lsb, f.width) for f in m.fields] == [("gain", 0, 16), ("offset", 16, 16),
                                                          ("bad", 32, 1)]
    pkg = rtl_package(cfg)
    assert "localparam int unsigned CoeffsOffsetLsb = 16;" in pkg
    assert "logic signed [15:0] offset;  // S12.4" in pkg
