"""Functional coverage of the correction methods in RTL (``method_dpc_top``, ``interp_weight``).

The coverpoints of :class:`MethodCoverageModel` extend :class:`~irnuc.cosim.coverage
.CoverageModel` (the stream, frame and reset points) with the method's own, every bin
decided from the golden model's values of what was driven and checked:

============================ ===================================================================
``method.round``             the core's sum s below / at (even, odd) / above one half, on
                             good pixels with r in range (where it reaches the output)
``method.range``             r below 0, in range, above 2^B - 1
``method.frame_word``        at a frame boundary the frame word changed, changed with a frame
                             shorter than the pipeline (4 pixels or fewer), stayed
``one_point.gain``           the gain register 0, its largest code, another
``piecewise.segment``        x below, at, above the pixel's knee
``piecewise.level``          the level register 0, its largest code, another
``quadratic.quad``           q negative, 0, positive
``quadratic.floor``          the quadratic term exact, or floored (QPf > F, dropped bits != 0)
``quadratic.x``              x = 0, x = 2^A - 1, another
``tc.u``                     t - t_ref clamped low, negative, 0, positive, clamped high
``tc.offset`` / ``tc.gain``  the polynomial below, in, above the coefficient's code range
``tc.round``                 the offset polynomial's fraction below / at / above one half
``table.weight``             w = 0, w = 2^Wf, between
``table.region``             the reading below the first table, between, above the last
``table.diff``               g_(j+1) - g_j negative, 0, positive
``table.round``              w * dg's fraction below / at (even, odd) / above one half
``table.bad``                a pixel flagged bad in table j only, in table j + 1 only, in both
                             (DPC replaces it in each case)
``iw.region``                interp_weight: reading below, at a table reading, between, above
``iw.round``                 interp_weight: remainder below / at / above half the span
``iw.error``                 interp_weight: table readings that do not increase
============================ ===================================================================

Unreachable bins are removed with the reason (``removed``), as in the base model.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np

from irnuc.cosim.coverage import RANGE_BINS, ROUND_BINS, CoverageModel
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.fixed import round_shift
from irnuc.nuc_fixed.method_top import MethodCoefficients, base_core, frame_coefficients
from irnuc.nuc_fixed.tempcomp import interp_weight, tc_reading
from irnuc.nuc_fixed.widths import core_frac, square_shift

__all__ = ["METHOD_TOPS", "MethodCoverageModel", "frame_classes", "method_points",
           "weight_classes"]

#: The tops whose coverage model is :class:`MethodCoverageModel`.
METHOD_TOPS = ("method_dpc_top", "interp_weight")

FRAME_WORD_BINS = ("changed", "changed_tiny", "same")
LEVEL_BINS = ("zero", "max", "other")
SEGMENT_BINS = ("below_knee", "at_knee", "above_knee")
SIGN_BINS = ("negative", "zero", "positive")
FLOOR_BINS = ("exact", "floored")
X_BINS = ("zero", "max", "other")
U_BINS = ("clamped_low", "negative", "zero", "positive", "clamped_high")
TABLE_BAD_BINS = ("lower_only", "upper_only", "both")
SAT_BINS = ("sat_low", "in_range", "sat_high")
HALF_BINS = ("below_half", "tie", "above_half")
WEIGHT_BINS = ("zero", "one", "between")
REGION_BINS = ("below", "between", "above")
IW_REGION_BINS = ("below", "at_reading", "between", "above")
#: The frame a boundary change counts as short: fewer pixels than any method's pipeline.
TINY_FRAME = 4


def _round_class(s: np.ndarray, f: int) -> np.ndarray:
    """ROUND_BINS index of every value with f > 0 fraction bits."""
    frac = s & ((1 << f) - 1)
    half = 1 << (f - 1)
    odd = (s >> f) & 1
    return np.where(frac < half, 0, np.where(frac > half, 3, 1 + odd))


def _three(v: np.ndarray, lo: int, hi: int) -> np.ndarray:
    """0 below lo, 1 in [lo, hi], 2 above hi."""
    return np.where(v < lo, 0, np.where(v > hi, 2, 1))


def _level(v: int, bits: int) -> str:
    return "zero" if v == 0 else "max" if v == (1 << bits) - 1 else "other"


def frame_classes(coeffs: MethodCoefficients, raw: np.ndarray, reading: int | None
                  ) -> dict[str, set[str]]:
    """The bins one frame hits: {coverpoint: {bin, ...}} (golden-model values)."""
    cfg = coeffs.cfg
    base = cfg.base_method
    raw = np.asarray(raw, dtype=np.int64)
    out: dict[str, set[str]] = {}

    def hit(point: str, labels: Sequence[str], idx: np.ndarray | Sequence[int]) -> None:
        out.setdefault(point, set()).update(labels[int(k)] for k in np.unique(idx))

    fc = frame_coefficients(coeffs, reading)
    res = base_core(coeffs, fc, raw)
    if res.frac > 0:
        # Only where the rounding reaches the output: a good pixel (DPC replaces a bad
        # one) whose result is in range (OUT would clip the difference away).
        seen = ~np.asarray(fc["bad"], dtype=bool) & (res.r >= 0) & (res.r < (1 << cfg.out_bits))
        hit("method.round", ROUND_BINS, _round_class(res.s[..., seen], res.frac))
    hit("method.range", RANGE_BINS, _three(res.r, 0, (1 << cfg.out_bits) - 1))
    f = coeffs.fields
    if base == "one_point":
        out["one_point.gain"] = {_level(int(coeffs.registers["gain"]), cfg.gain_bits)}
    elif base == "piecewise":
        kf = cfg.format("knee").frac_bits
        d = (raw << kf) - f["coeffs"]["knee"]
        hit("piecewise.segment", SEGMENT_BINS, np.sign(d) + 1)
        out["piecewise.level"] = {_level(int(coeffs.registers["level"]),
                                         cfg.format("level").bits)}
    elif base == "quadratic":
        q = f["quad"]["quad"]
        hit("quadratic.quad", SIGN_BINS, np.sign(q) + 1)
        hit("quadratic.x", X_BINS, np.where(raw == 0, 0, np.where(
            raw == (1 << cfg.adc_bits) - 1, 1, 2)))
        k = _floor_bits(cfg)
        if k > 0:
            qp = q * ((raw * raw) >> square_shift(cfg))
            hit("quadratic.floor", FLOOR_BINS, (qp & ((1 << k) - 1)) != 0)
    elif base == "tc_offset":
        _tc_classes(coeffs, reading, hit, out)
    elif base == "table_interp":
        _table_classes(coeffs, reading, hit, out)
    return out


def _floor_bits(cfg: PipelineConfig) -> int:
    """K = QPf - F: the bits the quadratic term drops (0: exact)."""
    qpf = cfg.format("quad").frac_bits + 2 * cfg.adc_bits - square_shift(cfg)
    return max(0, qpf - core_frac(cfg, 0, False))


def _tc_classes(coeffs: MethodCoefficients, reading: int | None, hit, out) -> None:
    cfg = coeffs.cfg
    t_ref = int(coeffs.registers["t_ref"])
    ts = int(cfg.reading_range_bits or 1)
    lim = (1 << ts) - 1
    diff = int(reading) - t_ref  # type: ignore[arg-type]
    u_bin = (0 if diff < -lim else 4 if diff > lim else 1 if diff < 0 else 3 if diff > 0
             else 2)
    out["tc.u"] = {U_BINS[u_bin]}
    tr = tc_reading(int(reading), t_ref, cfg)  # type: ignore[arg-type]
    cs = coeffs.fields["coeffs"]
    tc = {**coeffs.fields["tc"], **coeffs.fields.get("tg", {})}
    order = int(cfg.tc_order or 1)

    def poly(c0: np.ndarray, base: str, names: list[str]) -> tuple[np.ndarray, int]:
        # The polynomial before its rounding, at Fo fraction bits (docs/datapath.md
        # "tc_poly"), and Fo - base fraction bits.
        fo = max(cfg.format(base).frac_bits, *(cfg.format(n).frac_bits + ts for n in names))
        acc = c0 << (fo - cfg.format(base).frac_bits)
        for n, v in zip(names, (tr.u, tr.u2), strict=False):
            acc = acc + ((tc[n] * v) << (fo - cfg.format(n).frac_bits - ts))
        return acc, fo - cfg.format(base).frac_bits

    so, k = poly(cs["offset"], "offset", ["tc1", "tc2"][:order])
    ro = np.asarray(round_shift(np.ascontiguousarray(so), k, cfg.rounding))
    half = 1 << (cfg.offset_bits - 1)
    hit("tc.offset", SAT_BINS, _three(ro, -half, half - 1))
    if k > 0:
        frac = so & ((1 << k) - 1)
        hit("tc.round", HALF_BINS, np.sign(frac - (1 << (k - 1))) + 1)
    if cfg.tc_gain:
        sg, kg = poly(cs["gain"], "gain", ["tg1", "tg2"][:order])
        rg = np.asarray(round_shift(np.ascontiguousarray(sg), kg, cfg.rounding))
        hit("tc.gain", SAT_BINS, _three(rg, 0, (1 << cfg.gain_bits) - 1))


def _table_classes(coeffs: MethodCoefficients, reading: int | None, hit, out) -> None:
    cfg = coeffs.cfg
    rs = list(coeffs.registers["table_readings"])
    iw = interp_weight(int(reading), rs, cfg)  # type: ignore[arg-type]
    wf = cfg.format("weight").frac_bits
    out["table.weight"] = {"zero" if iw.w == 0 else "one" if iw.w == 1 << wf else "between"}
    t = int(reading)  # type: ignore[arg-type]
    out["table.region"] = {"below" if t < rs[0] else "above" if t > rs[-1] else "between"}
    g0 = coeffs.fields[f"table{iw.j}"]["gain"]
    dg = coeffs.fields[f"table{iw.j + 1}"]["gain"] - g0
    hit("table.diff", SIGN_BINS, np.sign(dg) + 1)
    if wf > 0:
        hit("table.round", ROUND_BINS, _round_class(dg * iw.w, wf))
    lo = coeffs.fields[f"table{iw.j}"]["bad"]
    up = coeffs.fields[f"table{iw.j + 1}"]["bad"]
    kinds = np.flatnonzero([(lo & ~up).any(), (~lo & up).any(), (lo & up).any()])
    hit("table.bad", TABLE_BAD_BINS, kinds)


def weight_classes(reading: int, table_readings: Sequence[int], cfg: PipelineConfig
                   ) -> dict[str, set[str]]:
    """The bins of one ``interp_weight`` computation (strictly increasing readings)."""
    rs = [int(v) for v in table_readings]
    if any(b <= a for a, b in itertools.pairwise(rs)):
        return {"iw.error": {"order"}}
    t = int(reading)
    region = ("below" if t < rs[0] else "above" if t > rs[-1] else
              "at_reading" if t in rs else "between")
    iw = interp_weight(t, rs, cfg)
    span = rs[iw.j + 1] - rs[iw.j]
    num = min(max(t - rs[iw.j], 0), span) << cfg.format("weight").frac_bits
    rem2 = 2 * (num % span)
    return {"iw.region": {region},
            "iw.round": {HALF_BINS[int(np.sign(rem2 - span)) + 1]}}


def method_points(cfg: PipelineConfig, top: str = "method_dpc_top"
                  ) -> tuple[dict[str, tuple[str, ...]], dict[str, dict[str, str]]]:
    """The method coverpoints of ``top`` on ``cfg``: {name: bins} and the removed bins
    {name: {bin: reason}}."""
    points: dict[str, tuple[str, ...]] = {}
    removed: dict[str, dict[str, str]] = {}
    if top == "interp_weight":
        return {"iw.region": IW_REGION_BINS, "iw.round": HALF_BINS, "iw.error": ("order",)}, {}
    base = cfg.base_method
    if core_frac(cfg, 0, False) > 0:
        points["method.round"] = ROUND_BINS
    else:
        removed["method.round"] = {b: "F = 0: nothing is rounded" for b in ROUND_BINS}
    points["method.range"] = RANGE_BINS
    if base in ("two_point", "quadratic"):
        points["method.frame_word"] = ("same",)
        removed["method.frame_word"] = {b: f"{base} has no frame word"
                                        for b in FRAME_WORD_BINS if b != "same"}
    else:
        points["method.frame_word"] = FRAME_WORD_BINS
    if base == "one_point":
        points["one_point.gain"] = LEVEL_BINS
    elif base == "piecewise":
        points["piecewise.segment"] = SEGMENT_BINS
        points["piecewise.level"] = LEVEL_BINS
    elif base == "quadratic":
        points["quadratic.quad"] = SIGN_BINS
        points["quadratic.x"] = X_BINS
        if _floor_bits(cfg) > 0:
            points["quadratic.floor"] = FLOOR_BINS
        else:
            removed["quadratic.floor"] = {b: "QPf <= F: the term is never floored"
                                          for b in FLOOR_BINS}
    elif base == "tc_offset":
        points["tc.u"] = U_BINS
        points["tc.offset"] = SAT_BINS
        if cfg.tc_gain:
            points["tc.gain"] = SAT_BINS
        ts = int(cfg.reading_range_bits or 1)
        names = ["tc1", "tc2"][: int(cfg.tc_order or 1)]
        if max(cfg.offset_frac_bits, *(cfg.format(n).frac_bits + ts for n in names)) \
                > cfg.offset_frac_bits:
            points["tc.round"] = HALF_BINS
    elif base == "table_interp":
        points["table.weight"] = WEIGHT_BINS
        points["table.region"] = REGION_BINS
        points["table.diff"] = SIGN_BINS
        points["table.bad"] = TABLE_BAD_BINS
        if cfg.format("weight").frac_bits > 0:
            points["table.round"] = ROUND_BINS
    return points, removed


class MethodCoverageModel(CoverageModel):
    """The coverpoints of ``method_dpc_top`` (or ``interp_weight``) on one configuration:
    the base model's stream points, frame sizes and transitions, a reset mid-frame, and
    :func:`method_points`."""

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        super().__init__(top, cfg, prefix)
        point = self.add_point
        points, removed = method_points(cfg, top)
        if top == "method_dpc_top":
            points |= {"frame.size": ("1x1", "1xN", "Nx1", "small"),
                       "frame.transition": ("same_size", "width_only", "height_only", "both",
                                            "after_idle"),
                       "reset.mid_frame": ("reset",)}
        for name, bins in points.items():
            point(name, bins)
        self.removed.update(removed)

    def sample_classes(self, classes: dict[str, set[str]]) -> None:
        for name, labels in classes.items():
            for b in sorted(labels):
                self.sample(name, b)

    def sample_frame(self, coeffs: MethodCoefficients, raw: np.ndarray,
                     reading: int | None) -> None:
        """The method's bins of one frame that was driven and checked."""
        from irnuc.cosim.coverage import frame_size_class

        self.sample_classes(frame_classes(coeffs, raw, reading))
        h, w = np.shape(raw)
        size = frame_size_class(h, w, self.cfg)
        self.sample("frame.size", size if size in ("1x1", "1xN", "Nx1") else "small")

    def sample_boundary(self, word_before: int, word_after: int, pixels_after: int) -> None:
        """A frame boundary: did the frame word change (and was the new frame short)?"""
        if word_before == word_after:
            self.sample("method.frame_word", "same")
        else:
            self.sample("method.frame_word",
                        "changed_tiny" if pixels_after <= TINY_FRAME else "changed")
