"""ffc (a stage): flat-field correction, a per-pixel offset term refreshed from N = 2^n
shutter frames by the base method's own core (docs/methods.md, docs/datapath.md "ffc")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.spec import (
    FormatSpec,
    MemoryLayout,
    ParamSpec,
    Register,
    RegisterSlot,
    StageSpec,
    memory,
)
from irnuc.nuc_fixed.widths import W, core_widths, ffc_shift, input_x, shl, sub

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig


@dataclass(frozen=True)
class Ffc(StageSpec):
    def check(self, cfg: PipelineConfig, src: str) -> None:
        n = cfg.ffc_frames
        if n is not None and n & (n - 1):
            raise ConfigError(f"{src}: ffc_frames = {n} must be a power of two "
                              "(the mean is a shift)")

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        c = cfg.format("ffc")
        acc = cfg.adc_bits + ffc_shift(cfg)
        return [memory("ffc_offset", [("ffc", c.bits, c.signed, str(c))], source="runtime"),
                memory("ffc_acc", [("acc", acc, False, f"U{acc}.0")], source="runtime",
                       reads_per_frame=0)]

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        c = cfg.format("ffc")
        return [Register("ffc_target", cfg.out_bits + c.frac_bits, False,
                         f"U{cfg.out_bits}.{c.frac_bits}", source="runtime",
                         meaning="output level the FFC flattens the shutter to")]

    def widths(self, cfg: PipelineConfig) -> dict[str, W | int]:
        n = ffc_shift(cfg)
        c = cfg.format("ffc")
        ref = core_widths(cfg, input_x(cfg, refresh=True), False)
        fr = max(int(ref["F"]), c.frac_bits)
        s_ref = ref["s"]
        assert isinstance(s_ref, W)
        s_ref = shl(s_ref, fr - int(ref["F"]))
        tgt = W(cfg.out_bits + c.frac_bits + fr - c.frac_bits, False)
        dr = sub(tgt, s_ref)
        return {"ffc.acc": W(cfg.adc_bits + n, False), "ffc.F": fr,
                **{f"ffc.refresh.{k}": v for k, v in ref.items() if isinstance(v, W)},
                "ffc.refresh.s_aligned": s_ref,
                "ffc.target": W(cfg.out_bits + c.frac_bits, False),
                "ffc.diff": dr, "ffc.rounded": W(dr.bits + 1 - (fr - c.frac_bits), True),
                "ffc.delta": W(c.bits, True)}


STAGE = Ffc(
    name="ffc", doc="flat-field correction refreshed from shutter frames", place="sum",
    readings=("shutter",),
    formats=(FormatSpec("ffc", True, "FFC offset correction, output codes (per pixel, "
                        "written by the FFC)", computed=True, rtl_modes=("rounding", "overflow"),
                        sv_default=(12, 4)),),
    params=(ParamSpec.range("ffc_frames", 1, 1024, "frames", "N, the shutter frames of a "
                            "refresh (a power of two)", "FfcFrames", 8),
            ParamSpec("ffc_output", {"enum": ["hold", "pass"]}, "what the output shows "
                      "during the shutter frames", "FfcHold", rtl_type="bit", sv_default=1,
                      to_rtl=lambda v: int(v == "hold"))),
    # Its correction is an extra term of the sum, whatever forms the rest.
    bases=None, rtl_bases=("one_point", "two_point", "quadratic", "tc_offset"),
    excludes=("blind_drift",),
    rtl_top="method_ffc_top", rtl_flag="Ffc", rtl_wrapper="irnuc_axis_ffc",
    rtl_files=("ffc_ctrl.sv", "ffc_mean.sv", "ffc_sums.sv", "ffc_refresh.sv"),
    slots=(RegisterSlot("FfcTargetRegBits", "ffc_target", "OutBits + FfcFracBits"),),
)
