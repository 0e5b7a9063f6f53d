"""The words of the RTL's streams for a configuration's method, one home for the Python side.

``method_dpc_top`` (and every top around a base method) takes per pixel one *coefficient
word* (``s_coef``) and per frame one *frame word* (``s_pix_frame_i``, read with the frame's
first pixel). Both are the method's (``MethodSpec.stream``, ``MethodSpec.frame_word``,
symbolic: the spec's layouts and width names), from which ``irnuc_method_pkg``'s width
functions are generated too (``nuc_fixed.methods.rtl``):

* coefficient word: the memories of ``MethodSpec.stream_memories`` concatenated, the first
  at bit 0 (table_interp: the frame's tables j and j + 1, ``lower`` and ``upper``);
* frame word: the fields of ``MethodSpec.frame_word`` from bit 0 up (one_point the gain
  register, piecewise the level, tc_offset the spec's ``frame_tc_offset``: reading, t_ref;
  table_interp the weight); one unused bit where the method has none.

A field of the frame word is a calibration register, a reading's runtime register
(``reading``) or a value the method computes (``MethodSpec.frame_values``: table_interp's
weight); its width is the register's, or the format's of that name.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from irnuc.nuc_fixed.config import MemoryLayout, PipelineConfig
from irnuc.nuc_fixed.spec import Block, Word


def stream_layouts(cfg: PipelineConfig) -> list[tuple[MemoryLayout, int]]:
    """The memories of the coefficient word and the bit each starts at
    (``MethodSpec.stream_memories``, the first at bit 0)."""
    out, lsb = [], 0
    for _, m in cfg.base.stream_memories(cfg):
        out.append((m, lsb))
        lsb += m.word_bits
    return out


def coef_stream_bits(cfg: PipelineConfig) -> int:
    """Bits of one coefficient word (``s_coef_data_i``; irnuc_axis_top's CONFIG.word_bits)."""
    return sum(m.word_bits for m, _ in stream_layouts(cfg))


def _width(cfg: PipelineConfig, name: str) -> int:
    """Bits of a frame-word field: a register's width, else the format's."""
    regs = cfg.registers
    return regs[name].width if name in regs else cfg.format(name).bits


def frame_layout(cfg: PipelineConfig) -> list[tuple[str, int, int, bool]]:
    """The frame word's fields, bit 0 first: (name, lsb, bits, is a gain)."""
    out, lsb = [], 0
    for part in cfg.base.frame_word:
        items = ([(f.name, False) for f in part.layout.fields] if isinstance(part, Word)
                 else [(part.memory, isinstance(part, Block) and part.gain)])
        for name, gain in items:
            bits = _width(cfg, name)
            out.append((name, lsb, bits, gain))
            lsb += bits
    return out


def frame_word_bits(cfg: PipelineConfig) -> int:
    """Bits of the frame word (``s_pix_frame_i``): one unused bit where there is none."""
    return sum(bits for _, _, bits, _ in frame_layout(cfg)) or 1


def frame_word(cfg: PipelineConfig, values: Mapping[str, Any]) -> int:
    """The frame word from the method's register values by name (calibration registers and
    the readings' registers: ``gain``, ``reading``, ``t_ref``, ``table_readings``, ...)."""
    vals = cfg.base.frame_values(cfg, values)
    word = 0
    for name, lsb, bits, _ in frame_layout(cfg):
        word |= (int(vals[name]) & ((1 << bits) - 1)) << lsb
    return word


def frame_fields(cfg: PipelineConfig, word: int) -> dict[str, int]:
    """The frame word's fields by name (unsigned codes)."""
    return {name: (int(word) >> lsb) & ((1 << bits) - 1)
            for name, lsb, bits, _ in frame_layout(cfg)}


def neutral_gain(cfg: PipelineConfig) -> int:
    """The gain code of the neutral word: 1.0 (2^Gf) when the format holds it, else its
    largest code (U0.Gf)."""
    return (1 << cfg.gain_frac_bits) if cfg.gain_int_bits > 0 else (1 << cfg.gain_bits) - 1


def neutral_word(cfg: PipelineConfig) -> int:
    """The coefficient word of a filler pixel, and the value of a word's fields but the bad
    flags with NUC off: gain fields (``gain``, ``gain_lo``, ``gain_hi``) at
    :func:`neutral_gain`, every other field 0."""
    w = 0
    for m, base in stream_layouts(cfg):
        for f in m.fields:
            if f.name in ("gain", "gain_lo", "gain_hi"):
                w |= neutral_gain(cfg) << (base + f.lsb)
    return w


def bad_mask(cfg: PipelineConfig) -> int:
    """The bits of the coefficient word that are bad flags."""
    return sum(1 << (base + f.lsb) for m, base in stream_layouts(cfg) for f in m.fields
               if f.name == "bad")


def neutral_frame(cfg: PipelineConfig) -> int:
    """The frame word with NUC off: every gain field (one_point's gain register) 1.0
    (:func:`neutral_gain`), every other field 0 (table_interp: weight 0, the lower table,
    neutral as well)."""
    return sum(neutral_gain(cfg) << lsb for _, lsb, _, gain in frame_layout(cfg) if gain)


def stream_words(coeffs: Any, frame: Mapping[str, int]
                 ) -> tuple[list[tuple[np.ndarray, int]], Any]:
    """The memory words of a frame's coefficient word, bit 0 first, as (uint64 words (H, W),
    bits) pairs, and the method's per-frame data (``MethodSpec.stream_words``)."""
    return coeffs.cfg.base.stream_words(coeffs, frame)


__all__ = ["bad_mask", "coef_stream_bits", "frame_fields", "frame_layout", "frame_word",
           "frame_word_bits", "neutral_frame", "neutral_gain", "neutral_word",
           "stream_layouts", "stream_words"]
