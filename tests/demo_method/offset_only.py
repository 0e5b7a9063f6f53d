"""offset_only: y = x + o, a per-pixel offset at unity gain (dark-frame subtraction): a method
module as ``nuc_fixed/methods/<name>.py`` would hold it (docs/architecture.md, "Add a
method"), registered by the tests at run time (``nuc_fixed.methods.register_method``)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.fit import ls_fixed_gain
from irnuc.nuc_fixed.rtl_spec import Field, WordLayout
from irnuc.nuc_fixed.spec import Frame, MemoryLayout, MethodSpec, Word, word_memory

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.method_top import MethodCoefficients

#: The method's RTL front, beside this module (hdl/method_offset_only.sv in a real addition).
FRONT = Path(__file__).with_name("method_offset_only.sv")

COEF_OFFSET_ONLY = WordLayout("coef_offset_only", 2, (
    Field("offset", "OffsetBits", "offset code, two's complement", "offset"),
    Field("bad", 1, "defective-pixel flag"),
), "coefficient word of offset_only (the gain is 1.0)")


@dataclass(frozen=True)
class OffsetOnly(MethodSpec):
    def check(self, cfg: PipelineConfig, src: str) -> None:
        if cfg.gain_int_bits < 1:
            raise ConfigError(f"{src}: gain_int_bits = 0 cannot hold the unity gain")

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        return [word_memory(COEF_OFFSET_ONLY, "coeffs", cfg)]

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        return {"gain": np.int64(1 << c.cfg.gain_frac_bits),
                "offset": c.fields["coeffs"]["offset"], "bad": c.fields["coeffs"]["bad"]}

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        # The least-squares offset at unity gain over every scene.
        q.field("coeffs.offset", "offset", ls_fixed_gain(means[pts.reference], t, 1.0))

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        return x + f["coeffs.offset"]


METHOD = OffsetOnly(
    name="offset_only", doc="per-pixel offset, unity gain (dark-frame subtraction)", core="lin",
    layouts=(COEF_OFFSET_ONLY,),
    stream=(Word("coeffs", COEF_OFFSET_ONLY),),
    rtl_module="method_offset_only", rtl_checked=("nuc_core",),
)
