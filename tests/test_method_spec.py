"""The correction methods' part of the shared-constants spec against the golden model's
configuration: the method enum against ``BASE_METHODS`` and every memory word layout of the
spec (generated into ``irnuc_pkg``) against ``PipelineConfig.memories`` of every base-method
configuration of ``pipelines.toml`` and of the tc_offset order-1 variant; the stream words
of ``method_dpc_top`` (``irnuc.cosim.stream``) against the memories."""

from __future__ import annotations

import pytest

from irnuc.cosim.stream import coef_stream_bits, frame_word_bits, stream_memories
from irnuc.nuc_fixed import PipelineConfig, load_pipeline, pipeline_names, rtl_spec
from irnuc.nuc_fixed.config import BASE_METHODS


def _method_configs() -> list[PipelineConfig]:
    cfgs = [load_pipeline(n) for n in pipeline_names(method=None)]
    cfgs = [c for c in cfgs if not c.stages]
    d = load_pipeline("tcgain14").to_dict()
    d["formats"] = {k: v for k, v in d["formats"].items() if k not in ("tc2", "tg2")}
    return [*cfgs, PipelineConfig(**{**d, "tc_order": 1, "name": "tcgain14_order1"})]


def _widths(cfg: PipelineConfig) -> dict[str, int]:
    """The layout width parameters of ``cfg`` (names of the spec's fields)."""
    out = {"GainBits": cfg.gain_bits, "OffsetBits": cfg.offset_bits}
    for f in cfg.formats:
        out[f"{f.name[:1].upper()}{f.name[1:]}Bits"] = f.bits
    if cfg.reading_bits is not None:
        out["ReadingBits"] = cfg.reading_bits
    return out


def test_method_enum_is_the_base_method_order() -> None:
    assert tuple(rtl_spec.METHOD.codes) == BASE_METHODS
    assert list(rtl_spec.METHOD.codes.values()) == list(range(len(BASE_METHODS)))


#: docs/datapath.md's words, written out again: per method, memory -> fields from bit 0 up,
#: each with its width parameter (or a number of bits).
_WORDS: dict[str, dict[str, list[tuple[str, str | int]]]] = {
    "one_point": {"coeffs": [("offset", "OffsetBits"), ("bad", 1)]},
    "two_point": {"coeffs": [("gain", "GainBits"), ("offset", "OffsetBits"), ("bad", 1)]},
    "piecewise": {"coeffs": [("gain_lo", "GainBits"), ("gain_hi", "GainBits"),
                             ("knee", "KneeBits"), ("bad", 1)]},
    "quadratic": {"coeffs": [("gain", "GainBits"), ("offset", "OffsetBits"), ("bad", 1)],
                  "quad": [("quad", "QuadBits")]},
    "tc_offset": {"coeffs": [("gain", "GainBits"), ("offset", "OffsetBits"), ("bad", 1)],
                  "tc": [("tc1", "Tc1Bits"), ("tc2", "Tc2Bits")],
                  "tg": [("tg1", "Tg1Bits"), ("tg2", "Tg2Bits")]},
    "table_interp": {"table": [("gain", "GainBits"), ("offset", "OffsetBits"), ("bad", 1)]},
    "tc_housing": {"coeffs": [("gain", "GainBits"), ("offset", "OffsetBits"), ("bad", 1)],
                   "tc": [("tc1", "Tc1Bits"), ("tc2", "Tc2Bits")],
                   "th": [("th1", "Th1Bits"), ("thx", "ThxBits"), ("th2", "Th2Bits")],
                   "tg": [("tg1", "Tg1Bits"), ("tg2", "Tg2Bits")]},
}


@pytest.mark.parametrize("cfg", _method_configs(), ids=lambda c: c.name)
def test_memory_layouts_are_the_configurations(cfg: PipelineConfig) -> None:
    """Field names, order, LSBs and widths of every calibration memory of the method (built
    from the spec's word layouts) against the words written out above."""
    widths = _widths(cfg)
    seen = 0
    for mem in cfg.memories.values():
        if mem.source != "calibration":
            continue
        spec = _WORDS[cfg.base_method]["table" if mem.name.startswith("table") else mem.name]
        spec = spec[: int(cfg.tc_order or 2)] if mem.name in ("tc", "tg") else spec
        want, lsb = {}, 0
        for name, w in spec:
            bits = widths[w] if isinstance(w, str) else w
            want[name] = (lsb, bits)
            lsb += bits
        assert {f.name: (f.lsb, f.width) for f in mem.fields} == want, (cfg.name, mem.name)
        seen += 1
    assert seen == len([m for m in cfg.memories.values() if m.source == "calibration"]) > 0


def test_every_method_layout_is_in_the_package() -> None:
    """Every word layout a method or stage declares is generated into irnuc_pkg."""
    from irnuc.nuc_fixed import methods

    names = {lay.name for lay in rtl_spec.LAYOUTS}
    for part in methods.every_part():
        assert {lay.name for lay in part.layouts} <= names, part.name
    assert "coef_word" in names and len(names) == len(rtl_spec.LAYOUTS)


@pytest.mark.parametrize("cfg", _method_configs(), ids=lambda c: c.name)
def test_stream_words_concatenate_the_memories(cfg: PipelineConfig) -> None:
    """The coefficient word is the calibration memories read per pixel (table_interp: two
    tables), the frame word holds the method's registers of the frame."""
    mems = [m for m in cfg.memories.values() if m.source == "calibration"]
    reads = sum(m.word_bits for m in mems if not m.name.startswith("table"))
    reads += 2 * next((m.word_bits for m in mems if m.name.startswith("table")), 0)
    assert coef_stream_bits(cfg) == reads
    assert len(stream_memories(cfg)) == (2 if cfg.base_method == "table_interp" else len(mems))
    regs = cfg.registers
    want = {"one_point": regs.get("gain"), "piecewise": regs.get("level")}
    frame = frame_word_bits(cfg)
    if cfg.base_method in want:
        assert frame == want[cfg.base_method].width
    elif cfg.base_method == "tc_offset":
        assert frame == regs["reading"].width + regs["t_ref"].width
    elif cfg.base_method == "tc_housing":
        assert frame == (regs["reading"].width + regs["t_ref"].width
                         + regs["housing_reading"].width + regs["h_ref"].width)
    elif cfg.base_method == "table_interp":
        assert frame == cfg.format("weight").bits
    else:
        assert frame == 1
