"""two_point: y = g·x + o, a per-pixel gain and offset: the classic factory NUC
(docs/methods.md, docs/datapath.md)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.nuc_fixed.fit import ls_fixed_gain, ls_line
from irnuc.nuc_fixed.rtl_spec import COEF_WORD
from irnuc.nuc_fixed.spec import Frame, MemoryLayout, MethodSpec, Word, word_memory

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.method_top import MethodCoefficients


@dataclass(frozen=True)
class TwoPoint(MethodSpec):
    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        return [word_memory(COEF_WORD, "coeffs", cfg)]

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        return dict(c.fields["coeffs"])

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        # The least-squares line over every scene (two scenes: the two-point formula).
        x = means[pts.reference]
        g, _ = ls_line(x, t)
        gq = q.field("coeffs.gain", "gain", g)
        q.field("coeffs.offset", "offset", ls_fixed_gain(x, t, gq))

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        return f["coeffs.gain"] * x + f["coeffs.offset"]


METHOD = TwoPoint(
    name="two_point", doc="per-pixel gain and offset", core="lin", plain=True,
    stream=(Word("coeffs", COEF_WORD),),
    rtl_module="method_two_point", rtl_checked=("nuc_core",),
)
