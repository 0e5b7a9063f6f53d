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

from irnuc.cosim.coverage import CoverageModel
from irnuc.nuc_fixed import methods
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.method_top import MethodCoefficients, base_core, frame_coefficients
from irnuc.nuc_fixed.methods.bins import (
    FRAME_WORD_BINS,
    HALF_BINS,
    RANGE_BINS,
    ROUND_BINS,
    hit,
    round_class,
    three,
)
from irnuc.nuc_fixed.tempcomp import interp_weight
from irnuc.nuc_fixed.widths import core_frac

__all__ = ["METHOD_TOPS", "MethodCoverageModel", "frame_classes", "method_points",
           "weight_classes"]

#: The tops whose coverage model is :class:`MethodCoverageModel`.
METHOD_TOPS = ("method_dpc_top", "interp_weight")

IW_REGION_BINS = ("below", "at_reading", "between", "above")
#: The frame a boundary change counts as short: fewer pixels than any method's pipeline.
TINY_FRAME = 4


def frame_classes(coeffs: MethodCoefficients, raw: np.ndarray, reading: int | None
                  ) -> dict[str, set[str]]:
    """The bins one frame hits: {coverpoint: {bin, ...}} (golden-model values): the core's
    rounding and range, and the method's own (``MethodSpec.coverage_classes``)."""
    cfg = coeffs.cfg
    raw = np.asarray(raw, dtype=np.int64)
    out: dict[str, set[str]] = {}
    frame = methods.frame(cfg, reading)
    fc = frame_coefficients(coeffs, frame)
    res = base_core(coeffs, fc, raw)
    if res.frac > 0:
        # Only where the rounding reaches the output: a good pixel (DPC replaces a bad
        # one) whose result is in range (OUT would clip the difference away).
        seen = ~np.asarray(fc["bad"], dtype=bool) & (res.r >= 0) & (res.r < (1 << cfg.out_bits))
        hit(out, "method.round", ROUND_BINS, round_class(res.s[..., seen], res.frac))
    hit(out, "method.range", RANGE_BINS, three(res.r, 0, (1 << cfg.out_bits) - 1))
    for point, bins in cfg.base.coverage_classes(coeffs, raw, frame, res).items():
        out.setdefault(point, set()).update(bins)
    return out


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
    {name: {bin: reason}}: the core's rounding and range, the frame word's changes, and the
    method's own (``MethodSpec.coverage_points``)."""
    points: dict[str, tuple[str, ...]] = {}
    removed: dict[str, dict[str, str]] = {}
    if top == "interp_weight":
        return {"iw.region": IW_REGION_BINS, "iw.round": HALF_BINS, "iw.error": ("order",)}, {}
    base = cfg.base
    if core_frac(cfg, 0, False) > 0:
        points["method.round"] = ROUND_BINS
    else:
        removed["method.round"] = {b: "F = 0: nothing is rounded" for b in ROUND_BINS}
    points["method.range"] = RANGE_BINS
    if not base.frame_word:
        points["method.frame_word"] = ("same",)
        removed["method.frame_word"] = {b: f"{base.name} has no frame word"
                                        for b in FRAME_WORD_BINS if b != "same"}
    else:
        points["method.frame_word"] = FRAME_WORD_BINS
    own, own_removed = base.coverage_points(cfg)
    points |= own
    removed |= own_removed
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
