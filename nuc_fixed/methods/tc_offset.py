"""tc_offset: the offset (and, with ``tc_gain``, the gain) a polynomial in the frame's FPA
reading, o(t) = c0 + c1·v + c2·v², v = (t − t_ref)/2^Ts clamped to (−1, 1)
(docs/methods.md, docs/datapath.md "tc_offset")."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.fit import (
    FormatRangeError,
    check_reading_codes,
    check_readings,
    ls_line,
    ls_poly,
)
from irnuc.nuc_fixed.fixed import round_shift
from irnuc.nuc_fixed.methods.bins import HALF_BINS, SAT_BINS, U_BINS, hit, three
from irnuc.nuc_fixed.plan import PlanError
from irnuc.nuc_fixed.rtl_spec import COEF_WORD, Field, WordLayout
from irnuc.nuc_fixed.spec import (
    Block,
    Classes,
    FormatSpec,
    Frame,
    FrameExpressions,
    MemoryLayout,
    MethodSpec,
    ParamSpec,
    Points,
    Register,
    RegisterSlot,
    Word,
    word_memory,
)
from irnuc.nuc_fixed.tempcomp import (
    VARIABLES,
    TcReading,
    tc_coeffs,
    tc_exprs,
    tc_reading,
    term_shift,
    variable,
)
from irnuc.nuc_fixed.widths import W, add, mul, shl, sub

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.cores import CoreResult
    from irnuc.nuc_fixed.method_top import MethodCoefficients

TC_WORD_1 = WordLayout("tc_word1", 2, (
    Field("tc1", "Tc1Bits", "offset change per v, two's complement", "tc1"),
), "tc_offset's offset polynomial of order 1")
TC_WORD_2 = WordLayout("tc_word2", 2, (
    Field("tc1", "Tc1Bits", "offset change per v, two's complement", "tc1"),
    Field("tc2", "Tc2Bits", "offset change per v^2, two's complement", "tc2"),
), "tc_offset's offset polynomial of order 2")
TG_WORD_1 = WordLayout("tg_word1", 2, (
    Field("tg1", "Tg1Bits", "gain change per v, two's complement", "tg1"),
), "tc_offset's gain polynomial of order 1 (tc_gain)")
TG_WORD_2 = WordLayout("tg_word2", 2, (
    Field("tg1", "Tg1Bits", "gain change per v, two's complement", "tg1"),
    Field("tg2", "Tg2Bits", "gain change per v^2, two's complement", "tg2"),
), "tc_offset's gain polynomial of order 2 (tc_gain)")
FRAME_TC_OFFSET = WordLayout("frame_tc_offset", 2, (
    Field("reading", "ReadingBits", "the frame's FPA reading, unsigned"),
    Field("t_ref", "ReadingBits", "the reading the polynomials are centred at, unsigned"),
), "tc_offset's frame word (method_dpc_top's s_pix_frame_i, read with the frame's first "
   "pixel)")


def _order(cfg: PipelineConfig) -> int:
    return int(cfg.tc_order or 1)


def reading_regressors(cfg: PipelineConfig, readings: list[int], t_ref: int) -> np.ndarray:
    """[1, v, v2] of each point as the datapath computes them (u clamped, u2 floored)."""
    ts = int(cfg.reading_range_bits or 1)
    lim = (1 << ts) - 1
    rows = []
    for t in readings:
        u = t - t_ref
        if abs(u) > lim:
            raise FormatRangeError(
                f"pipeline {cfg.name!r}: an FPA point reads {u:+d} codes from the reference "
                f"reading {t_ref}; reading_range_bits = {ts} holds +-{lim}: widen it")
        rows.append([1.0, u / 2.0**ts, ((u * u) >> ts) / 2.0**ts])
    return np.asarray(rows)[:, : _order(cfg) + 1]


def fit_polynomials(cfg: PipelineConfig, means: np.ndarray, t: np.ndarray, q: Any,
                    reg: np.ndarray, extra: list[str]) -> None:
    """Fit and quantize the gain and the offset polynomials on every point (means
    (P, S, H, W), targets t (S,)). ``reg`` (P, 1 + order + len(extra)): the regressors as
    the datapath computes them, [1, v(, v2)] then one column per ``extra`` offset term.

    The common gain over all points (or the gain per point, then its polynomial in the
    FPA's columns only), then the offset per point and its polynomial.
    """
    order = _order(cfg)
    readings = np.arange(means.shape[0])
    xbar = means.mean(axis=1)  # (P, H, W)
    tbar = float(np.mean(t))
    freg = reg[:, : order + 1]
    if cfg.tc_gain:
        gp = np.stack([ls_line(means[p], t)[0] for p in range(means.shape[0])])
        gc = ls_poly(readings, gp, freg)
        vals = [q.field("coeffs.gain", "gain", gc[0])]
        vals += [q.field(f"tg.{n}", n, gc[i + 1])
                 for i, n in enumerate(["tg1", "tg2"][:order])]
        g_at = np.einsum("pk,khw->phw", freg, np.stack(vals))
    else:
        xc = means - means.mean(axis=1, keepdims=True)       # (P, S, H, W)
        tc = (t - tbar).reshape(1, -1, 1, 1)
        sxx = (xc * xc).sum(axis=(0, 1))
        g = np.divide((xc * tc).sum(axis=(0, 1)), sxx, out=np.zeros_like(sxx),
                      where=sxx > 0)
        g_at = np.broadcast_to(q.field("coeffs.gain", "gain", g), xbar.shape)
    oc = ls_poly(readings, tbar - g_at * xbar, reg)
    q.field("coeffs.offset", "offset", oc[0])
    for i, n in enumerate(["tc1", "tc2"][:order]):
        q.field(f"tc.{n}", n, oc[i + 1])
    for i, n in enumerate(extra):
        q.field(f"th.{n}", n, oc[order + 1 + i])


@dataclass(frozen=True)
class TcOffset(MethodSpec):
    def used_formats(self, cfg: PipelineConfig) -> tuple[str, ...]:
        order = _order(cfg)
        return (*["tc1", "tc2"][:order], *(["tg1", "tg2"][:order] if cfg.tc_gain else []))

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        order = _order(cfg)
        mems = [word_memory(COEF_WORD, "coeffs", cfg),
                word_memory((TC_WORD_1, TC_WORD_2)[order - 1], "tc", cfg)]
        if cfg.tc_gain:
            mems.append(word_memory((TG_WORD_1, TG_WORD_2)[order - 1], "tg", cfg))
        return mems

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        r = int(cfg.reading_bits or 1)
        return [Register("t_ref", r, False, f"U{r}.0",
                         meaning="reading at which the polynomials are centred")]

    def offset_names(self, cfg: PipelineConfig) -> list[str]:
        """The offset polynomial's coefficients (formats), in the datapath's order."""
        return ["tc1", "tc2"][:_order(cfg)]

    def frame_reading(self, c: MethodCoefficients, frame: Frame) -> TcReading:
        """The frame's ``tc_reading``."""
        return tc_reading(int(frame["fpa"]), int(c.registers["t_ref"]), c.cfg)

    def _polys(self, c: MethodCoefficients) -> dict[str, Any]:
        return {**c.fields["tc"], **c.fields.get("tg", {}), **c.fields.get("th", {})}

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        cs = c.fields["coeffs"]
        g, o = tc_coeffs(cs["gain"], cs["offset"], self._polys(c), self.frame_reading(c, frame),
                         c.cfg)
        return {"gain": g, "offset": o, "bad": cs["bad"]}

    def frame_expressions(self, c: MethodCoefficients, frame: Frame) -> FrameExpressions:
        # The polynomials of frame_coefficients, evaluated per pixel in the fused pass.
        cs = c.fields["coeffs"]
        g, o = tc_exprs(cs["gain"], cs["offset"], self._polys(c), self.frame_reading(c, frame),
                        c.cfg)
        return FrameExpressions({"gain": g, "offset": o}, cs["bad"])

    def variable_widths(self, cfg: PipelineConfig) -> dict[str, W]:
        """The widths of the polynomials' variables (tc_reading's outputs)."""
        ts = int(cfg.reading_range_bits or 1)
        return {"u": W(ts + 1, True), "u2": W(ts, False)}

    def widths(self, cfg: PipelineConfig) -> dict[str, W | int]:
        r = int(cfg.reading_bits or 1)
        var = self.variable_widths(cfg)
        out: dict[str, W | int] = {"tc.diff": sub(W(r, False), W(r, False))}
        out |= {f"tc.{k}": v for k, v in var.items()}
        for kind, base_fmt, names in (("o", cfg.format("offset"), self.offset_names(cfg)),
                                      ("g", cfg.format("gain"), ["tg1", "tg2"][: _order(cfg)])):
            if kind == "g" and not cfg.tc_gain:
                continue
            fo = max(base_fmt.frac_bits, *(term_shift(n, cfg) for n in names))
            terms = [shl(W(base_fmt.bits, base_fmt.signed), fo - base_fmt.frac_bits)]
            for n in names:
                c = cfg.format(n)
                prod = mul(W(c.bits, True), var[VARIABLES[n][0]])
                out[f"tc.{kind}.{c.name}_prod"] = prod
                terms.append(shl(prod, fo - term_shift(n, cfg)))
            acc = add(*terms)
            out |= {f"tc.{kind}.F": fo, f"tc.{kind}.sum": acc,
                    f"tc.{kind}.rounded": W(acc.bits + 1 - (fo - base_fmt.frac_bits), True)}
        return out

    def check(self, cfg: PipelineConfig, src: str) -> None:
        if (cfg.reading_range_bits is not None and cfg.reading_bits is not None
                and cfg.reading_range_bits > cfg.reading_bits):
            raise ConfigError(f"{src}: reading_range_bits = {cfg.reading_range_bits} must be "
                              f"at most reading_bits = {cfg.reading_bits} (a reading differs "
                              "from t_ref by less than 2^reading_bits)")

    def check_readings(self, cfg: PipelineConfig, readings: list[int], reference: int,
                       source: str, sensor: str) -> None:
        order = _order(cfg)
        if len(readings) < order + 1:
            raise PlanError(f"{source}: tc_order = {order} needs at least {order + 1} FPA "
                            f"temperatures; the plan has {len(readings)}")
        check_reading_codes(cfg, readings, order + 1,
                            f"tc_order = {cfg.tc_order} fits {order + 1} distinct readings",
                            source, sensor)
        lim = (1 << int(cfg.reading_range_bits or 1)) - 1
        far = [r for r in readings if abs(r - readings[reference]) > lim]
        if far:
            raise FormatRangeError(f"{source}: {sensor} reads {far[0]} at an FPA point, "
                                   f"{far[0] - readings[reference]:+d} codes from the "
                                   f"reference reading {readings[reference]}; pipeline "
                                   f"{cfg.name!r} has reading_range_bits = "
                                   f"{cfg.reading_range_bits} (+-{lim}): widen it, or "
                                   "calibrate over a smaller FPA range")

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        # The common gain over all points (or the gain per point, then its polynomial),
        # then the offset per point and its polynomial in the datapath's own v and v^2.
        readings = [pts.point_reading(p) for p in range(means.shape[0])]
        if min(readings) < 0:
            raise PlanError(f"{pts.source}: method {cfg.method!r} needs the FPA reading of "
                            "every frame (fpa_reading); the frames lack it")
        check_readings(cfg, readings, pts.reference, pts.source)
        t_ref = readings[pts.reference]
        q.register("t_ref", None, t_ref, bits=int(cfg.reading_bits or 1))
        order = _order(cfg)
        if means.shape[0] < order + 1:
            raise PlanError(f"{pts.source}: tc_order = {order} needs at least {order + 1} "
                            f"FPA temperatures; the plan has {means.shape[0]}")
        fit_polynomials(cfg, means, t, q, reading_regressors(cfg, readings, t_ref), [])

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        t = int(frame["fpa"])
        lim = (1 << int(cfg.reading_range_bits or 1)) - 1
        t_ref = int(f["t_ref"])
        reg = reading_regressors(cfg, [min(max(t, t_ref - lim), t_ref + lim)], t_ref)[0]
        names = ["tc1", "tc2"][: _order(cfg)]
        o = f["coeffs.offset"] + sum(r * f[f"tc.{n}"] for r, n in zip(reg[1:], names, strict=False))
        g = f["coeffs.gain"]
        if cfg.tc_gain:
            gn = ["tg1", "tg2"][: _order(cfg)]
            g = g + sum(r * f[f"tg.{n}"] for r, n in zip(reg[1:], gn, strict=False))
        return g * x + o

    # ---- verification ------------------------------------------------------------------
    def coverage_points(self, cfg: PipelineConfig) -> Points:
        points: dict[str, tuple[str, ...]] = {"tc.u": U_BINS, "tc.offset": SAT_BINS}
        if cfg.tc_gain:
            points["tc.gain"] = SAT_BINS
        names = self.offset_names(cfg)
        if max(cfg.offset_frac_bits, *(term_shift(n, cfg) for n in names)) \
                > cfg.offset_frac_bits:
            points["tc.round"] = HALF_BINS
        return points, {}

    def coverage_classes(self, c: MethodCoefficients, raw: np.ndarray, frame: Frame,
                         res: CoreResult) -> Classes:
        cfg = c.cfg
        out: Classes = {}
        reading = int(frame["fpa"])
        t_ref = int(c.registers["t_ref"])
        ts = int(cfg.reading_range_bits or 1)
        lim = (1 << ts) - 1
        diff = reading - t_ref
        u_bin = (0 if diff < -lim else 4 if diff > lim else 1 if diff < 0 else 3 if diff > 0
                 else 2)
        out["tc.u"] = {U_BINS[u_bin]}
        tr = self.frame_reading(c, frame)
        cs = c.fields["coeffs"]
        tc = {**c.fields["tc"], **c.fields.get("tg", {}), **c.fields.get("th", {})}

        def poly(c0: np.ndarray, base: str, names: list[str]) -> tuple[np.ndarray, int]:
            # The polynomial before its rounding, at Fo fraction bits (docs/datapath.md
            # "tc_poly"), and Fo - base fraction bits.
            fo = max(cfg.format(base).frac_bits, *(term_shift(n, cfg) for n in names))
            acc = c0 << (fo - cfg.format(base).frac_bits)
            for n in names:
                acc = acc + ((tc[n] * variable(n, tr)) << (fo - term_shift(n, cfg)))
            return acc, fo - cfg.format(base).frac_bits

        order = _order(cfg)
        so, k = poly(cs["offset"], "offset", self.offset_names(cfg))
        ro = np.asarray(round_shift(np.ascontiguousarray(so), k, cfg.rounding))
        half = 1 << (cfg.offset_bits - 1)
        hit(out, "tc.offset", SAT_BINS, three(ro, -half, half - 1))
        if k > 0:
            frac = so & ((1 << k) - 1)
            hit(out, "tc.round", HALF_BINS, np.sign(frac - (1 << (k - 1))) + 1)
        if cfg.tc_gain:
            sg, kg = poly(cs["gain"], "gain", ["tg1", "tg2"][:order])
            rg = np.asarray(round_shift(np.ascontiguousarray(sg), kg, cfg.rounding))
            hit(out, "tc.gain", SAT_BINS, three(rg, 0, (1 << cfg.gain_bits) - 1))
        return out

    def reading_marks(self, c: MethodCoefficients) -> list[int]:
        # t_ref and the clamps.
        lim = (1 << int(c.cfg.reading_range_bits or 1)) - 1
        t = int(c.registers["t_ref"])
        return [t, t - lim - 1, t - lim, t + lim, t + lim + 1, t - 1, t + 1]

    def draw_register(self, r: Register, rng: np.random.Generator, lo: int, hi: int
                      ) -> object | None:
        if r.name != "t_ref":
            return None
        # Near the middle of the reading range, so both clamps can be reached.
        mid = (hi + 1) // 2
        return int(np.clip(mid + rng.integers(-(hi // 8) - 1, hi // 8 + 2), lo, hi))


_TC_BITS = "Tc1IntBits + Tc1FracBits + ((TcOrder == 2) ? Tc2IntBits + Tc2FracBits : 0)"
_TG_BITS = ("(TcGain != 0) ? Tg1IntBits + Tg1FracBits + ((TcOrder == 2) ? Tg2IntBits "
            "+ Tg2FracBits : 0) : 0")

METHOD = TcOffset(
    name="tc_offset", doc="coefficients polynomial in the FPA reading", core="lin",
    readings=("fpa",),
    formats=(
        FormatSpec("tc1", True, "offset change per 2^reading_range_bits reading codes, output "
                   "codes", sv_default=(13, 3)),
        FormatSpec("tc2", True, "offset change per (2^reading_range_bits reading codes)^2, "
                   "output codes", sv_default=(12, 4)),
        FormatSpec("tg1", True, "gain change per 2^reading_range_bits reading codes",
                   sv_default=(2, 14)),
        FormatSpec("tg2", True, "gain change per (2^reading_range_bits reading codes)^2",
                   sv_default=(2, 14)),
    ),
    params=(
        ParamSpec.range("tc_order", 1, 2, "", "order of the polynomials", "TcOrder", 2),
        ParamSpec("tc_gain", {"type": "boolean"}, "the gain is a polynomial too", "TcGain",
                  rtl_type="bit", sv_default=0),
        ParamSpec.range("reading_range_bits", 1, 20, "bits", "Ts: v = (t - t_ref) / 2^Ts",
                        "ReadingRangeBits", 11),
    ),
    layouts=(TC_WORD_1, TC_WORD_2, TG_WORD_1, TG_WORD_2, FRAME_TC_OFFSET),
    stream=(Word("coeffs", COEF_WORD), Block("tc", "TcWordBits"), Block("tg", "TgWordBits")),
    frame_word=(Word("frame", FRAME_TC_OFFSET),),
    rtl_module="method_tc_offset", rtl_checked=("tc_poly", "tc_reading", "nuc_core"),
    rtl_files=("tc_reading.sv", "tc_poly.sv"),
    rtl_derived=(("TcWordBits", _TC_BITS), ("TgWordBits", _TG_BITS)),
    rtl_base_params=("Rounding",), rtl_front_registered=True,
    slots=(RegisterSlot("TRefRegBits", "t_ref", "ReadingBits"),),
)
