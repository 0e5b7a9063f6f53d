"""one_point: y = G·x + o, a per-pixel offset o and one global gain register G
(docs/methods.md, docs/datapath.md "one_point")."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.nuc_fixed.fit import ls_fixed_gain
from irnuc.nuc_fixed.methods.bins import LEVEL_BINS, level
from irnuc.nuc_fixed.rtl_spec import Field, WordLayout
from irnuc.nuc_fixed.spec import (
    Block,
    Classes,
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

COEF_ONE_POINT = WordLayout("coef_one_point", 2, (
    Field("offset", "OffsetBits", "offset code, two's complement", "offset"),
    Field("bad", 1, "defective-pixel flag"),
), "coefficient word of one_point (the gain is a register)")


@dataclass(frozen=True)
class OnePoint(MethodSpec):
    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        return [word_memory(COEF_ONE_POINT, "coeffs", cfg)]

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        gf = cfg.format("gain")
        return [Register("gain", gf.bits, False, str(gf),
                         meaning="global gain (output codes per ADC code)")]

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        return {"gain": np.int64(c.registers["gain"]), "offset": c.fields["coeffs"]["offset"],
                "bad": c.fields["coeffs"]["bad"]}

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        # G = 2^(B - A): the output's scale; the offset is the least-squares one for it.
        x = means[pts.reference]
        gv = q.register("gain", "gain", 2.0 ** (cfg.out_bits - cfg.adc_bits))
        q.field("coeffs.offset", "offset", ls_fixed_gain(x, t, gv))

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        return f["gain"] * x + f["coeffs.offset"]

    def coverage_points(self, cfg: PipelineConfig) -> Points:
        return {"one_point.gain": LEVEL_BINS}, {}

    def coverage_classes(self, c: MethodCoefficients, raw: np.ndarray, frame: Frame,
                         res: CoreResult) -> Classes:
        return {"one_point.gain": {level(int(c.registers["gain"]), c.cfg.gain_bits)}}


METHOD = OnePoint(
    name="one_point", doc="per-pixel offset, global gain register", core="lin",
    layouts=(COEF_ONE_POINT,),
    stream=(Word("coeffs", COEF_ONE_POINT),),
    frame_word=(Block("gain", "GainBits", gain=True),),
    rtl_module="method_one_point", rtl_checked=("nuc_core",),
    slots=(RegisterSlot("GainRegBits", "gain", "GainBits"),),
    corner_registers=("gain",),
)
