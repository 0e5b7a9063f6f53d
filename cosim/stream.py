"""What a testbench drives into a method's streams (docs/rtl.md "Methods"): the per-pixel
coefficient words and the per-frame word of ``method_dpc_top`` (and of the tops around a
base method), built from a method's calibration (``nuc_fixed.method_top``).

The words themselves are the method's (``nuc_fixed.streams``, from ``MethodSpec.stream``
and ``MethodSpec.frame_word``, from which ``irnuc_method_pkg``'s width functions are
generated too); ``cocotb_tests/tb_method.py`` reads the RTL's widths back from every
simulated ``method_dpc_top`` and compares them with :func:`coef_stream_bits` and
:func:`frame_word_bits`.

Words wider than 64 bits occur (tcgain14: 97 bits), so they are Python ints, or uint64
limbs (little-endian) for the bulk harness.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from irnuc.nuc_fixed import methods, streams
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.method_top import MethodCoefficients

__all__ = ["FrameDrive", "coef_stream_bits", "frame_drive", "frame_word", "frame_word_bits",
           "limbs", "stream_limbs", "stream_memories", "stream_parts"]


def stream_memories(cfg: PipelineConfig) -> list[str]:
    """The memories in the coefficient word, bit 0 first (table_interp: ``lower`` and
    ``upper``, the frame's tables j and j + 1): the base method's stream
    (``MethodSpec.stream_memories``; a stage's runtime memories have streams of their own,
    :mod:`irnuc.cosim.stages`)."""
    return [name for name, _ in cfg.base.stream_memories(cfg)]


def coef_stream_bits(cfg: PipelineConfig) -> int:
    """Bits of one coefficient word of ``method_dpc_top`` (``s_coef_data_i``)."""
    return streams.coef_stream_bits(cfg)


def frame_word_bits(cfg: PipelineConfig) -> int:
    """Bits of the frame word of ``method_dpc_top`` (``s_pix_frame_i``)."""
    return streams.frame_word_bits(cfg)


@dataclass(frozen=True)
class FrameDrive:
    """What the testbench drives for one frame: the frame word and the coefficient words.

    Attributes
    ----------
    frame_word : int
        ``s_pix_frame_i`` (read with the frame's first pixel).
    words : (H, W) object array of int
        ``s_coef_data_i`` per pixel, raster order.
    interp : object or None
        The method's per-frame data behind the words (``MethodSpec.stream_words``;
        table_interp: the frame's j and w), else None.
    """

    frame_word: int
    words: np.ndarray
    interp: Any = None


def stream_parts(coeffs: MethodCoefficients, reading: Any = None
                 ) -> tuple[list[tuple[np.ndarray, int]], Any]:
    """The memory words of the coefficient word, bit 0 first, as (uint64 words (H, W),
    bits) pairs, for a frame with this reading (the FPA reading, or the frame's readings by
    name); and the method's per-frame data (table_interp's j and w)."""
    return streams.stream_words(coeffs, methods.frame(coeffs.cfg, reading))


def frame_word(coeffs: MethodCoefficients, reading: Any = None, interp: Any = None) -> int:
    """The frame word (``s_pix_frame_i``) of a frame with this reading."""
    cfg = coeffs.cfg
    fr = methods.frame(cfg, reading)
    return streams.frame_word(cfg, methods.register_values(cfg, coeffs.registers, fr))


def frame_drive(coeffs: MethodCoefficients, reading: Any = None) -> FrameDrive:
    """The frame word and coefficient words (Python ints) of a frame with this FPA reading
    (needed by the methods that take it) for the calibration ``coeffs``."""
    parts, extra = stream_parts(coeffs, reading)
    words = np.zeros(parts[0][0].shape, dtype=object)
    shift = 0
    for w, bits in parts:
        words = words + (np.asarray(w, dtype=np.uint64).astype(object) << shift)
        shift += bits
    return FrameDrive(frame_word=frame_word(coeffs, reading, extra), words=words, interp=extra)


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
