"""piecewise: two gains meeting at a per-pixel knee, y = L + g·(x − k), g = g_lo at and
below the knee, g_hi above; L one register (docs/methods.md, docs/datapath.md
"piecewise")."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.fit import piecewise_fit
from irnuc.nuc_fixed.methods.bins import LEVEL_BINS, SEGMENT_BINS, hit, level
from irnuc.nuc_fixed.rtl_spec import Field, WordLayout
from irnuc.nuc_fixed.spec import (
    Block,
    Classes,
    FormatSpec,
    Frame,
    MemoryLayout,
    MethodSpec,
    Points,
    Register,
    RegisterSlot,
    Word,
    word_memory,
)

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.cores import CoreResult
    from irnuc.nuc_fixed.method_top import MethodCoefficients

COEF_PIECEWISE = WordLayout("coef_piecewise", 2, (
    Field("gain_lo", "GainBits", "gain at and below the knee, unsigned", "gain"),
    Field("gain_hi", "GainBits", "gain above the knee, unsigned", "gain"),
    Field("knee", "KneeBits", "knee, ADC codes, unsigned", "knee"),
    Field("bad", 1, "defective-pixel flag"),
), "coefficient word of piecewise")


@dataclass(frozen=True)
class Piecewise(MethodSpec):
    def check(self, cfg: PipelineConfig, src: str) -> None:
        k = cfg.format("knee")
        if k.int_bits < cfg.adc_bits:
            raise ConfigError(f"{src}: formats.knee.int_bits = {k.int_bits} must be at least "
                              f"adc_bits = {cfg.adc_bits} (a knee is an ADC code)")

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        return [word_memory(COEF_PIECEWISE, "coeffs", cfg)]

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        lf = cfg.format("level")
        return [Register("level", lf.bits, False, str(lf),
                         meaning="output at every pixel's knee, output codes")]

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        return {**c.fields["coeffs"], "level": int(c.registers["level"])}

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        # The knee at the middle scene's code, the level its target; each segment's gain
        # the least-squares slope through the quantized knee.
        x = means[pts.reference]
        mid = len(t) // 2
        kq = q.field("coeffs.knee", "knee", x[mid])
        lv = q.register("level", "level", float(t[mid]))
        _, _, g_lo, g_hi = piecewise_fit(x, t, knee=kq, level=lv)
        q.field("coeffs.gain_lo", "gain", g_lo)
        q.field("coeffs.gain_hi", "gain", g_hi)

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        k = f["coeffs.knee"]
        g = np.where(x <= k, f["coeffs.gain_lo"], f["coeffs.gain_hi"])
        return f["level"] + g * (x - k)

    def coverage_points(self, cfg: PipelineConfig) -> Points:
        return {"piecewise.segment": SEGMENT_BINS, "piecewise.level": LEVEL_BINS}, {}

    def coverage_classes(self, c: MethodCoefficients, raw: np.ndarray, frame: Frame,
                         res: CoreResult) -> Classes:
        cfg = c.cfg
        out: Classes = {}
        d = (raw << cfg.format("knee").frac_bits) - c.fields["coeffs"]["knee"]
        hit(out, "piecewise.segment", SEGMENT_BINS, np.sign(d) + 1)
        out["piecewise.level"] = {level(int(c.registers["level"]), cfg.format("level").bits)}
        return out

    def corner(self, c: MethodCoefficients, raw: np.ndarray, rng: np.random.Generator,
               index: int) -> None:
        # Knees exactly at some pixels' codes (d = 0).
        kf = c.cfg.format("knee").frac_bits
        at = rng.random(raw.shape) < 0.25
        c.fields["coeffs"]["knee"] = np.where(at, raw << kf, c.fields["coeffs"]["knee"])


METHOD = Piecewise(
    name="piecewise", doc="two gains meeting at a per-pixel knee", core="pwl", scenes=3,
    formats=(FormatSpec("knee", False, "piecewise breakpoint, ADC codes (per pixel)",
                        sv_default=(14, 2), rtl_scope="core"),
             FormatSpec("level", False, "piecewise output at the breakpoint, output codes "
                        "(register)", sv_default=(14, 4), rtl_scope="core")),
    layouts=(COEF_PIECEWISE,),
    stream=(Word("coeffs", COEF_PIECEWISE),),
    frame_word=(Block("level", "LevelBits"),),
    rtl_module="method_piecewise", rtl_checked=("pwl_core",),
    slots=(RegisterSlot("LevelRegBits", "level", "LevelBits"),),
    corner_registers=("level",),
)
