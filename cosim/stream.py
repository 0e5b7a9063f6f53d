"""The streams of ``method_dpc_top`` (docs/rtl.md "Methods"): the per-pixel coefficient word
and the per-frame word, built from a method's calibration (``nuc_fixed.method_top``).

The Python side of ``irnuc_method_pkg::coef_stream_bits`` / ``frame_word_bits``, written
from ``PipelineConfig.memories`` and ``registers`` (the one place the layouts are written);
``cocotb_tests/tb_method_pkg.py`` reads the RTL's widths back and compares.

* coefficient word: the calibration memories' words concatenated in the order of
  ``PipelineConfig.memories``, the first at bit 0; table_interp: the words of tables j and
  j + 1 of the frame (j at bit 0);
* frame word: one_point ``gain``, piecewise ``level``, tc_offset the spec's
  ``frame_tc_offset`` (``reading``, ``t_ref``), table_interp the frame's weight w; nothing
  (one 0 bit) otherwise.

Every memory word's layout is the spec's (:func:`irnuc.nuc_fixed.rtl_spec.memory_layout`,
generated into ``irnuc_pkg``), which ``tests/test_method_spec.py`` checks against
``PipelineConfig.memories``.

Words wider than 64 bits occur (tcgain14: 97 bits), so they are Python ints, or uint64
limbs (little-endian) for the bulk harness.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.nuc_fixed import rtl_spec
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.method_top import MethodCoefficients
from irnuc.nuc_fixed.tempcomp import InterpWeight, interp_weight

__all__ = ["FrameDrive", "coef_stream_bits", "frame_drive", "frame_word", "frame_word_bits",
           "limbs", "stream_limbs", "stream_memories", "stream_parts"]


def stream_memories(cfg: PipelineConfig) -> list[str]:
    """The memories in the coefficient word, bit 0 first (table_interp: ``lower`` and
    ``upper``, the frame's tables j and j + 1)."""
    if cfg.stages:
        raise ValueError(f"method {cfg.method!r}: the RTL streams the base methods only")
    if cfg.base_method == "table_interp":
        return ["lower", "upper"]
    return [m.name for m in cfg.memories.values() if m.source == "calibration"]


def _word_bits(cfg: PipelineConfig, name: str) -> int:
    mem = cfg.memories["table0" if name in ("lower", "upper") else name]
    return mem.word_bits


def coef_stream_bits(cfg: PipelineConfig) -> int:
    """Bits of one coefficient word of ``method_dpc_top`` (``s_coef_data_i``)."""
    return sum(_word_bits(cfg, n) for n in stream_memories(cfg))


def frame_word_bits(cfg: PipelineConfig) -> int:
    """Bits of the frame word of ``method_dpc_top`` (``s_pix_frame_i``)."""
    base = cfg.base_method
    regs = cfg.registers
    if base == "one_point":
        return regs["gain"].width
    if base == "piecewise":
        return regs["level"].width
    if base == "tc_offset":
        return rtl_spec.FRAME_TC_OFFSET.bits(ReadingBits=regs["reading"].width)
    if base == "table_interp":
        return cfg.format("weight").bits
    return 1


@dataclass(frozen=True)
class FrameDrive:
    """What the testbench drives for one frame: the frame word and the coefficient words.

    Attributes
    ----------
    frame_word : int
        ``s_pix_frame_i`` (read with the frame's first pixel).
    words : (H, W) object array of int
        ``s_coef_data_i`` per pixel, raster order.
    interp : InterpWeight or None
        table_interp: the frame's j and w.
    """

    frame_word: int
    words: np.ndarray
    interp: InterpWeight | None = None


def stream_parts(coeffs: MethodCoefficients, reading: int | None = None
                 ) -> tuple[list[tuple[np.ndarray, int]], InterpWeight | None]:
    """The memory words of the coefficient word, bit 0 first, as (uint64 words (H, W),
    bits) pairs, for a frame with this reading; and table_interp's j and w."""
    cfg = coeffs.cfg
    mems = coeffs.words()
    if cfg.base_method == "table_interp":
        iw = interp_weight(int(reading), coeffs.registers["table_readings"], cfg)  # type: ignore[arg-type]
        bits = cfg.memories["table0"].word_bits
        return [(mems[f"table{iw.j}"], bits), (mems[f"table{iw.j + 1}"], bits)], iw
    return [(mems[n], cfg.memories[n].word_bits) for n in stream_memories(cfg)], None


def frame_word(coeffs: MethodCoefficients, reading: int | None = None,
               interp: InterpWeight | None = None) -> int:
    """The frame word (``s_pix_frame_i``) of a frame with this reading."""
    cfg = coeffs.cfg
    base = cfg.base_method
    if base == "one_point":
        return int(coeffs.registers["gain"])
    if base == "piecewise":
        return int(coeffs.registers["level"])
    if base == "tc_offset":
        lay = rtl_spec.FRAME_TC_OFFSET.layout(ReadingBits=cfg.registers["reading"].width)
        return ((int(reading) << lay["reading"][0])  # type: ignore[arg-type]
                | (int(coeffs.registers["t_ref"]) << lay["t_ref"][0]))
    if base == "table_interp":
        iw = interp or interp_weight(int(reading), coeffs.registers["table_readings"], cfg)  # type: ignore[arg-type]
        return int(iw.w)
    return 0


def frame_drive(coeffs: MethodCoefficients, reading: int | None = None) -> FrameDrive:
    """The frame word and coefficient words (Python ints) of a frame with this FPA reading
    (needed by tc_offset and table_interp) for the calibration ``coeffs``."""
    parts, iw = stream_parts(coeffs, reading)
    words = np.zeros(parts[0][0].shape, dtype=object)
    shift = 0
    for w, bits in parts:
        words = words + (np.asarray(w, dtype=np.uint64).astype(object) << shift)
        shift += bits
    return FrameDrive(frame_word=frame_word(coeffs, reading, iw), words=words, interp=iw)


def stream_limbs(coeffs: MethodCoefficients, reading: int | None = None) -> np.ndarray:
    """The coefficient words of a frame as uint64 limbs, bit 0 first: (H, W, L), L =
    ceil(bits / 64) (the bulk harness's image)."""
    parts, _ = stream_parts(coeffs, reading)
    total = sum(bits for _, bits in parts)
    n = max(1, -(-total // 64))
    h, w = parts[0][0].shape
    out = np.zeros((h, w, n), dtype=np.uint64)
    off = 0
    for words, bits in parts:
        v = np.asarray(words, dtype=np.uint64)
        for k in range(n):
            lo = 64 * k
            if off >= lo + 64 or off + bits <= lo:
                continue
            sh = off - lo
            out[:, :, k] |= (v << np.uint64(sh)) if sh >= 0 else (v >> np.uint64(-sh))
        off += bits
    return out


def limbs(words: np.ndarray, bits: int) -> np.ndarray:
    """Words (Python ints) as little-endian uint64 limbs: shape (..., ceil(bits / 64))."""
    n = max(1, -(-bits // 64))
    flat = np.asarray(words, dtype=object).reshape(-1)
    out = np.empty((flat.size, n), dtype=np.uint64)
    mask = (1 << 64) - 1
    for k in range(n):
        out[:, k] = [(int(v) >> (64 * k)) & mask for v in flat]
    return out.reshape(*np.shape(words), n)
