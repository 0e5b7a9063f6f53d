"""quadratic: y = g·x + o + q·(x/2^A)², the square truncated to ``square_bits`` so both
multiplies fit one DSP (docs/methods.md, docs/datapath.md "quadratic")."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.nuc_fixed.fit import ls_fixed_gain, ls_line, quadratic_fit
from irnuc.nuc_fixed.methods.bins import FLOOR_BINS, SIGN_BINS, X_BINS, hit
from irnuc.nuc_fixed.rtl_spec import COEF_WORD, Field, WordLayout
from irnuc.nuc_fixed.spec import (
    Classes,
    FormatSpec,
    Frame,
    MemoryLayout,
    MethodSpec,
    ParamSpec,
    Points,
    Word,
    word_memory,
)
from irnuc.nuc_fixed.widths import core_frac, square_shift

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.cores import CoreResult
    from irnuc.nuc_fixed.method_top import MethodCoefficients

QUAD_WORD = WordLayout("quad_word", 2, (
    Field("quad", "QuadBits", "quadratic term at x = 2^A, two's complement", "quad"),
), "quadratic's second memory")


def floor_bits(cfg: PipelineConfig) -> int:
    """K = QPf - F: the bits the quadratic term drops (0: exact)."""
    qpf = cfg.format("quad").frac_bits + 2 * cfg.adc_bits - square_shift(cfg)
    return max(0, qpf - core_frac(cfg, 0, False))


@dataclass(frozen=True)
class Quadratic(MethodSpec):
    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        return [word_memory(COEF_WORD, "coeffs", cfg), word_memory(QUAD_WORD, "quad", cfg)]

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        return {**c.fields["coeffs"], "quad": c.fields["quad"]["quad"]}

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        x = means[pts.reference]
        qq, _, _ = quadratic_fit(x, t, cfg.adc_bits)
        qv = q.field("quad.quad", "quad", qq)
        # The line through what the quantized quadratic term leaves.
        rest = t.reshape(-1, 1, 1) - qv * (x / float(1 << cfg.adc_bits)) ** 2
        g, _ = ls_line(x, rest)
        gq = q.field("coeffs.gain", "gain", g)
        q.field("coeffs.offset", "offset", ls_fixed_gain(x, rest, gq))

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        return (f["quad.quad"] * (x / float(1 << cfg.adc_bits)) ** 2 + f["coeffs.gain"] * x
                + f["coeffs.offset"])

    def coverage_points(self, cfg: PipelineConfig) -> Points:
        points: dict[str, tuple[str, ...]] = {"quadratic.quad": SIGN_BINS, "quadratic.x": X_BINS}
        removed: dict[str, dict[str, str]] = {}
        if floor_bits(cfg) > 0:
            points["quadratic.floor"] = FLOOR_BINS
        else:
            removed["quadratic.floor"] = {b: "QPf <= F: the term is never floored"
                                          for b in FLOOR_BINS}
        return points, removed

    def coverage_classes(self, c: MethodCoefficients, raw: np.ndarray, frame: Frame,
                         res: CoreResult) -> Classes:
        cfg = c.cfg
        out: Classes = {}
        q = c.fields["quad"]["quad"]
        hit(out, "quadratic.quad", SIGN_BINS, np.sign(q) + 1)
        hit(out, "quadratic.x", X_BINS, np.where(raw == 0, 0, np.where(
            raw == (1 << cfg.adc_bits) - 1, 1, 2)))
        k = floor_bits(cfg)
        if k > 0:
            qp = q * ((raw * raw) >> square_shift(cfg))
            hit(out, "quadratic.floor", FLOOR_BINS, (qp & ((1 << k) - 1)) != 0)
        return out


METHOD = Quadratic(
    name="quadratic", doc="gain, offset and a quadratic term", core="quad", scenes=3,
    formats=(FormatSpec("quad", True, "quadratic term at full-scale input, output codes "
                        "(per pixel)", sv_default=(10, 6), rtl_scope="core"),),
    params=(ParamSpec.range("square_bits", 1, 24, "bits", "bits the square of a raw code is "
                            "truncated to", "SquareBits", 18, rtl_scope="core"),),
    layouts=(QUAD_WORD,),
    stream=(Word("coeffs", COEF_WORD), Word("quad", QUAD_WORD)),
    rtl_module="method_quadratic", rtl_checked=("quad_core",),
)
