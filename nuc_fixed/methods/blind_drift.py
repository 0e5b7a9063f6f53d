"""blind_drift (a stage): x' = (x << Df) − δ before the gain, δ the change of the frame's
blind pixel sum since calibration times a coupling (docs/methods.md, docs/datapath.md
"blind_drift")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.plan import PlanError
from irnuc.nuc_fixed.rtl_spec import Field, WordLayout
from irnuc.nuc_fixed.spec import (
    FormatSpec,
    ParamSpec,
    Register,
    RegisterSlot,
    StageSpec,
)
from irnuc.nuc_fixed.widths import InputX, W, diff_unsigned, mul, sub

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig

FRAME_BLIND_DRIFT = WordLayout("frame_blind_drift", 1, (
    Field("base", "BaseBits", "the base method's frame word (one_point's gain; two_point: "
          "one unused bit)"),
    Field("blind_sum", "SumBits", "the frame's blind pixel sum, unsigned"),
    Field("blind_ref", "SumBits", "the blind pixel sum at calibration, unsigned"),
    Field("drift_gain", "DriftGainBits", "drift per code of blind sum change, two's "
          "complement"),
), "blind_drift's frame word in irnuc_axis_top (the framer's, taken at a frame start from "
   "the shadowed registers)")


@dataclass(frozen=True)
class BlindDrift(StageSpec):
    def check(self, cfg: PipelineConfig, src: str) -> None:
        d, m = cfg.format("drift"), cfg.format("drift_gain")
        if m.frac_bits < d.frac_bits:
            raise ConfigError(f"{src}: formats.drift_gain.frac_bits = {m.frac_bits} must "
                              f"be at least formats.drift.frac_bits = {d.frac_bits}")

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        sb = cfg.blind_sum_bits
        mf = cfg.format("drift_gain")
        return [Register("blind_sum", sb, False, f"U{sb}.0", source="runtime",
                         meaning="sum of the frame's blind pixel codes"),
                Register("blind_ref", sb, False, f"U{sb}.0",
                         meaning="blind pixel sum at calibration"),
                Register("drift_gain", mf.bits, True, str(mf),
                         meaning="drift (ADC codes) per code of blind sum change")]

    def input_x(self, cfg: PipelineConfig) -> InputX:
        # x' = (x << Df) - delta: signed, Df fraction bits.
        d = cfg.format("drift")
        return InputX(sub(W(cfg.adc_bits + d.frac_bits, False), W(d.bits, True)), d.frac_bits)

    def widths(self, cfg: PipelineConfig) -> dict[str, W | int]:
        d, m = cfg.format("drift"), cfg.format("drift_gain")
        sb = W(cfg.blind_sum_bits, False)
        bd = diff_unsigned(sb, sb)
        return {"drift.bsum": sb, "drift.bd": bd, "drift.dp": mul(bd, W(m.bits, True)),
                "drift.delta": W(d.bits, True), "drift.x": self.input_x(cfg).w}

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, good: np.ndarray,
            q: Any) -> None:
        """blind_ref (the blind sum at the reference point) and drift_gain = k / K.

        k, how many ADC codes the image moves per code of the blind mean, is measured when
        the plan changes the housing temperature alone (``drift_cam``): the least-squares
        slope of the mean active code against the mean blind code over those points and the
        reference point's middle scene. Without them k = 1, as the paper repository takes it.
        """
        if pts.blind_codes is None:
            raise PlanError(f"{pts.source}: method {cfg.method!r} needs the blind pixel codes "
                            "of every frame (blind_codes); the frames lack them")
        b = pts.blind_codes.astype(np.float64)               # (P, S, M, K)
        kb = b.shape[-1]
        if kb > int(cfg.blind_max or 0):
            raise PlanError(f"{pts.source}: {kb} blind pixels per frame; pipeline "
                            f"{cfg.name!r} has blind_max = {cfg.blind_max}")
        ref = pts.reference
        q.register("blind_ref", None, float(b[ref].sum(axis=-1).mean()),
                   bits=cfg.blind_sum_bits)
        k, source = 1.0, "paper repository (k = 1): the plan has no drift_cam points"
        if pts.drift_codes is not None and pts.drift_blind is not None:
            mid = means.shape[1] // 2
            xs = [means[ref, mid][good].mean()] + [d.mean(axis=0)[good].mean()
                                                   for d in pts.drift_codes]
            bs = [b[ref, mid].mean()] + [float(d.mean()) for d in pts.drift_blind]
            if np.ptp(bs) > 0:
                k = float(np.polyfit(bs, xs, 1)[0])
                source = (f"fit over the housing at "
                          f"{', '.join(f'{t:g}' for t in pts.drift_cam_K)} K "
                          f"(FPA {pts.fpa_K[ref]:g} K)")
        q.floats["drift_coupling"] = k
        q.floats["drift_coupling_source"] = source
        q.register("drift_gain", "drift_gain", k / kb)


_BLIND_MAX = ParamSpec.range("blind_max", 1, 1 << 20, "pixels",
                             "the most blind pixels a frame has", "BlindMax", 8192)

STAGE = BlindDrift(
    name="blind_drift", doc="the blind pixels' drift subtracted before the gain",
    place="input", readings=("blind",),
    formats=(FormatSpec("drift", True, "blind drift subtracted from the raw code, ADC codes "
                        "(per frame)", computed=True, rtl_modes=("rounding", "overflow"),
                        sv_default=(14, 2)),
             FormatSpec("drift_gain", True, "ADC codes of drift per code of the blind sum "
                        "(register)", sv_default=(1, 24))),
    params=(_BLIND_MAX,),
    # The bases whose input goes straight into one gain multiply (docs/methods.md).
    bases=("one_point", "two_point"), rtl_bases=("one_point", "two_point"),
    excludes=("ffc",),
    layouts=(FRAME_BLIND_DRIFT,),
    rtl_top="method_drift_top", rtl_flag="Drift",
    rtl_derived=(("BlindBits", "blind_sum_bits(AdcBits, BlindMax)"),
                 ("DriftGainBits", "DriftGainIntBits + DriftGainFracBits")),
    rtl_files=("blind_drift.sv", "drift_sub.sv"),
    slots=(RegisterSlot("BlindSumRegBits", "blind_sum", "BlindBits"),
           RegisterSlot("BlindRefRegBits", "blind_ref", "BlindBits"),
           RegisterSlot("DriftGainRegBits", "drift_gain", "DriftGainBits")),
)
