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


@pytest.mark.parametrize("cfg", _method_configs(), ids=lambda c: c.name)
def test_memory_layouts_are_the_configurations(cfg: PipelineConfig) -> None:
    """Field names, order, LSBs and widths of every calibration memory of the method."""
    widths = _widths(cfg)
    seen = 0
    for mem in cfg.memories.values():
        if mem.source != "calibration":
            continue
        lay = rtl_spec.memory_layout(cfg.base_method, mem.name, int(cfg.tc_order or 2))
        want = {f.name: (f.lsb, f.width) for f in mem.fields}
        got = lay.layout(**{p: widths[p] for p in lay.parameters})
        assert got == want, (cfg.name, mem.name, lay.name)
        seen += 1
    assert seen == len([m for m in cfg.memories.values() if m.source == "calibration"]) > 0


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
    elif cfg.base_method == "table_interp":
        assert frame == cfg.format("weight").bits
    else:
        assert frame == 1


def test_unknown_memory_is_refused() -> None:
    with pytest.raises(KeyError, match="no layout"):
        rtl_spec.memory_layout("quadratic", "ffc_acc")
