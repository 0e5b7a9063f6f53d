"""tc_housing: tc_offset's polynomials with the housing sensor's reading as a second variable.

The offset is a quadratic in the FPA reading and the housing reading,

    o(t, h) = c0 + c1·v + c2·v² + h1·w' + hx·v·w' + h2·w'²,
    v = (t − t_ref)/2^Ts, w' = (h − h_ref)/2^Hs, each clamped to (−1, 1),

(the gain as tc_offset's: fixed, or with ``tc_gain`` a polynomial in v), fitted per pixel
on a plan over FPA x housing (``plan.housing_offset``). The model shows why all three
housing terms (docs/methods.md, "tc_housing"): over FPA 288..308 K x housing offset
−5..+5 K the worst per-point offset pattern a per-pixel least-squares fit leaves is
154 codes with the FPA terms only, 20 with + w', 1.8 with + v·w', 0.5 with + w'²
(24 x 32 pixels of the default sensor). The RTL is tc_offset's front with the housing
terms switched on (``tc_poly``'s and ``tc_reading``'s ``Housing``): one function per RTL
module, :func:`~irnuc.nuc_fixed.tempcomp.tc_reading` and
:func:`~irnuc.nuc_fixed.tempcomp.tc_coeffs`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.fit import FormatRangeError, check_readings
from irnuc.nuc_fixed.methods.bins import U_BINS
from irnuc.nuc_fixed.methods.tc_offset import (
    _TC_BITS,
    _TG_BITS,
    TcOffset,
    _order,
    fit_polynomials,
    reading_regressors,
)
from irnuc.nuc_fixed.methods.tc_offset import METHOD as TC_OFFSET
from irnuc.nuc_fixed.plan import PlanError
from irnuc.nuc_fixed.rtl_spec import COEF_WORD, Field, WordLayout
from irnuc.nuc_fixed.spec import (
    Block,
    Classes,
    FormatSpec,
    Frame,
    MemoryLayout,
    ParamSpec,
    Points,
    Register,
    RegisterSlot,
    Word,
    word_memory,
)
from irnuc.nuc_fixed.tempcomp import HOUSING_TERMS, TcReading, tc_reading
from irnuc.nuc_fixed.widths import W

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.cores import CoreResult
    from irnuc.nuc_fixed.method_top import MethodCoefficients

TH_WORD = WordLayout("housing_word", 2, (
    Field("th1", "Th1Bits", "offset change per w', two's complement", "th1"),
    Field("thx", "ThxBits", "offset change per v·w', two's complement", "thx"),
    Field("th2", "Th2Bits", "offset change per w'^2, two's complement", "th2"),
), "tc_housing's housing terms of the offset polynomial")
FRAME_TC_HOUSING = WordLayout("frame_tc_housing", 2, (
    Field("reading", "ReadingBits", "the frame's FPA reading, unsigned"),
    Field("t_ref", "ReadingBits", "the FPA reading the polynomials are centred at, unsigned"),
    Field("housing_reading", "HousingBits", "the frame's housing reading, unsigned"),
    Field("h_ref", "HousingBits", "the housing reading the polynomials are centred at, "
          "unsigned"),
), "tc_housing's frame word (method_dpc_top's s_pix_frame_i, read with the frame's first "
   "pixel)")


def housing_regressors(cfg: PipelineConfig, readings: list[int], housing: list[int],
                       t_ref: int, h_ref: int) -> np.ndarray:
    """[1, v(, v2), w', v·w', w'^2] of each point as the datapath computes them (the
    :func:`~irnuc.nuc_fixed.tempcomp.tc_reading` integers over their fraction bits)."""
    ts = int(cfg.reading_range_bits or 1)
    hs = int(cfg.housing_range_bits or 1)
    lim = (1 << hs) - 1
    rows = []
    for t, h in zip(readings, housing, strict=True):
        if abs(h - h_ref) > lim:
            raise FormatRangeError(
                f"pipeline {cfg.name!r}: a housing point reads {h - h_ref:+d} codes from the "
                f"reference housing reading {h_ref}; housing_range_bits = {hs} holds +-{lim}: "
                "widen it")
        tr = tc_reading(t, t_ref, cfg, h, h_ref)
        rows.append([tr.w / 2.0**hs, tr.uw / 2.0**ts, tr.w2 / 2.0**hs])
    fpa = reading_regressors(cfg, readings, t_ref)
    return np.concatenate([fpa, np.asarray(rows)], axis=1)


@dataclass(frozen=True)
class TcHousing(TcOffset):
    def used_formats(self, cfg: PipelineConfig) -> tuple[str, ...]:
        return (*super().used_formats(cfg), *HOUSING_TERMS)

    def offset_names(self, cfg: PipelineConfig) -> list[str]:
        return [*super().offset_names(cfg), *HOUSING_TERMS]

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        mems = super().memories(cfg)
        # coeffs, tc, th (then tg): the stream word's order.
        return [*mems[:2], word_memory(TH_WORD, "th", cfg), *mems[2:]]

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        h = int(cfg.housing_bits or 1)
        return [*super().registers(cfg),
                Register("h_ref", h, False, f"U{h}.0",
                         meaning="housing reading at which the polynomials are centred")]

    def frame_reading(self, c: MethodCoefficients, frame: Frame) -> TcReading:
        return tc_reading(int(frame["fpa"]), int(c.registers["t_ref"]), c.cfg,
                          int(frame["housing"]), int(c.registers["h_ref"]))

    def variable_widths(self, cfg: PipelineConfig) -> dict[str, W]:
        ts = int(cfg.reading_range_bits or 1)
        hs = int(cfg.housing_range_bits or 1)
        return {**super().variable_widths(cfg), "w": W(hs + 1, True), "uw": W(ts + 1, True),
                "w2": W(hs, False)}

    def check(self, cfg: PipelineConfig, src: str) -> None:
        super().check(cfg, src)
        if (cfg.housing_range_bits is not None and cfg.housing_bits is not None
                and cfg.housing_range_bits > cfg.housing_bits):
            raise ConfigError(f"{src}: housing_range_bits = {cfg.housing_range_bits} must be "
                              f"at most housing_bits = {cfg.housing_bits} (a reading differs "
                              "from h_ref by less than 2^housing_bits)")

    def check_plan(self, cfg: PipelineConfig, plan: Any, source: str) -> None:
        if len(set(plan.housing_offset)) < 3:
            raise PlanError(f"{source}: method {cfg.method!r} fits w', v·w' and w'^2 in the "
                            "housing reading: the plan needs at least 3 housing temperatures "
                            "per FPA temperature (plan.housing_offset, e.g. [-5, 0, 5]); it "
                            f"has {len(set(plan.housing_offset))}")

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        # Every (FPA, housing) point: the gain as tc_offset's, the offset per point and its
        # polynomial in the datapath's own v, v^2, w', v·w', w'^2.
        n_p = means.shape[0]
        readings = [pts.point_reading(p) for p in range(n_p)]
        housing = [pts.point_housing_reading(p) for p in range(n_p)]
        if min(readings) < 0:
            raise PlanError(f"{pts.source}: method {cfg.method!r} needs the FPA reading of "
                            "every frame (fpa_reading); the frames lack it")
        if any(h is None for h in housing) or len(set(housing)) < 3:
            raise PlanError(f"{pts.source}: method {cfg.method!r} fits w', v·w' and w'^2 in "
                            "the housing reading: the plan needs at least 3 housing "
                            "temperatures per FPA temperature (plan.housing_offset, e.g. "
                            f"[-5, 0, 5]); the points read {sorted(set(housing), key=str)}")
        distinct = sorted(set(readings))
        check_readings(cfg, distinct, distinct.index(readings[pts.reference]), pts.source)
        order = _order(cfg)
        if len(set(readings)) < order + 1:
            raise PlanError(f"{pts.source}: tc_order = {order} needs at least {order + 1} "
                            f"FPA temperatures; the plan has {len(set(readings))}")
        t_ref = readings[pts.reference]
        h_ref = int(housing[pts.reference])
        q.register("t_ref", None, t_ref, bits=int(cfg.reading_bits or 1))
        q.register("h_ref", None, h_ref, bits=int(cfg.housing_bits or 1))
        reg = housing_regressors(cfg, readings, [int(h) for h in housing], t_ref, h_ref)
        if np.linalg.matrix_rank(reg) < reg.shape[1]:
            raise PlanError(f"{pts.source}: method {cfg.method!r} fits {reg.shape[1]} terms in "
                            "the FPA and the housing readings but the plan's points do not "
                            "separate them (the housing follows the FPA): image every FPA "
                            "temperature at 3 housing temperatures (plan.housing_offset, e.g. "
                            "[-5, 0, 5])")
        fit_polynomials(cfg, means, t, q, reg, list(HOUSING_TERMS))

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        t_ref, h_ref = int(f["t_ref"]), int(f["h_ref"])
        lim = (1 << int(cfg.reading_range_bits or 1)) - 1
        hlim = (1 << int(cfg.housing_range_bits or 1)) - 1
        t = min(max(int(frame["fpa"]), t_ref - lim), t_ref + lim)
        h = min(max(int(frame["housing"]), h_ref - hlim), h_ref + hlim)
        hr = housing_regressors(cfg, [t], [h], t_ref, h_ref)[0]
        order = _order(cfg)
        names = [f"tc.{n}" for n in ["tc1", "tc2"][:order]] + [f"th.{n}" for n in HOUSING_TERMS]
        o = f["coeffs.offset"] + sum(r * f[n] for r, n in zip(hr[1:], names, strict=True))
        g = f["coeffs.gain"]
        if cfg.tc_gain:
            gn = ["tg1", "tg2"][:order]
            g = g + sum(r * f[f"tg.{n}"] for r, n in zip(hr[1:order + 1], gn, strict=True))
        return g * x + o

    # ---- verification ------------------------------------------------------------------
    def coverage_points(self, cfg: PipelineConfig) -> Points:
        points, crosses = super().coverage_points(cfg)
        return {**points, "tc.w": U_BINS}, crosses

    def coverage_classes(self, c: MethodCoefficients, raw: np.ndarray, frame: Frame,
                         res: CoreResult) -> Classes:
        out = super().coverage_classes(c, raw, frame, res)
        lim = (1 << int(c.cfg.housing_range_bits or 1)) - 1
        diff = int(frame["housing"]) - int(c.registers["h_ref"])
        out["tc.w"] = {U_BINS[0 if diff < -lim else 4 if diff > lim else 1 if diff < 0
                              else 3 if diff > 0 else 2]}
        return out

    def housing_marks(self, c: MethodCoefficients) -> list[int]:
        """h_ref and the housing clamps (the stimulus's housing readings)."""
        lim = (1 << int(c.cfg.housing_range_bits or 1)) - 1
        h = int(c.registers["h_ref"])
        return [h, h - lim - 1, h - lim, h + lim, h + lim + 1, h - 1, h + 1]

    def draw_register(self, r: Register, rng: np.random.Generator, lo: int, hi: int
                      ) -> object | None:
        if r.name == "h_ref":
            mid = (hi + 1) // 2
            return int(np.clip(mid + rng.integers(-(hi // 8) - 1, hi // 8 + 2), lo, hi))
        return super().draw_register(r, rng, lo, hi)


_TH_BITS = "Th1IntBits + Th1FracBits + ThxIntBits + ThxFracBits + Th2IntBits + Th2FracBits"

METHOD = TcHousing(
    name="tc_housing", doc="offset polynomial in the FPA and the housing readings",
    core="lin", readings=("fpa", "housing"),
    formats=(*TC_OFFSET.formats,
             FormatSpec("th1", True, "offset change per 2^housing_range_bits housing codes, "
                        "output codes", sv_default=(15, 3)),
             FormatSpec("thx", True, "offset change per 2^reading_range_bits FPA codes times "
                        "2^housing_range_bits housing codes, output codes",
                        sv_default=(14, 4)),
             FormatSpec("th2", True, "offset change per (2^housing_range_bits housing codes)^2, "
                        "output codes", sv_default=(12, 4))),
    params=(*TC_OFFSET.params,
            ParamSpec.range("housing_range_bits", 1, 20, "bits",
                            "Hs: w' = (h - h_ref) / 2^Hs", "HousingRangeBits", 11)),
    layouts=(TH_WORD, FRAME_TC_HOUSING),
    stream=(Word("coeffs", COEF_WORD), Block("tc", "TcWordBits"), Block("th", "ThWordBits"),
            Block("tg", "TgWordBits")),
    frame_word=(Word("frame", FRAME_TC_HOUSING),),
    rtl_module="method_tc_offset", rtl_front_flags=("Housing",),
    rtl_checked=("tc_poly", "tc_reading", "nuc_core"),
    rtl_files=("tc_reading.sv", "tc_poly.sv"),
    rtl_derived=(("TcWordBits", _TC_BITS), ("ThWordBits", _TH_BITS), ("TgWordBits", _TG_BITS)),
    rtl_base_params=("Rounding",), rtl_front_registered=True,
    slots=(RegisterSlot("TRefRegBits", "t_ref", "ReadingBits"),
           RegisterSlot("HRefRegBits", "h_ref", "HousingBits")),
)
