"""Coverage bins the methods share, and the classifiers that put values into them.

The co-simulation's coverage model (``irnuc.cosim.method_coverage``) collects each method's
coverpoints (``MethodSpec.coverage_points``) and the bins a frame hits
(``MethodSpec.coverage_classes``), decided from golden-model values; the names are here so
that the methods and the model share them.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from irnuc.nuc_fixed.spec import Classes

ROUND_BINS = ("below_half", "tie_even", "tie_odd", "above_half")
RANGE_BINS = ("below_zero", "in_range", "above_max")
FRAME_WORD_BINS = ("changed", "changed_tiny", "same")
LEVEL_BINS = ("zero", "max", "other")
SEGMENT_BINS = ("below_knee", "at_knee", "above_knee")
SIGN_BINS = ("negative", "zero", "positive")
FLOOR_BINS = ("exact", "floored")
X_BINS = ("zero", "max", "other")
U_BINS = ("clamped_low", "negative", "zero", "positive", "clamped_high")
SAT_BINS = ("sat_low", "in_range", "sat_high")
HALF_BINS = ("below_half", "tie", "above_half")
WEIGHT_BINS = ("zero", "one", "between")
REGION_BINS = ("below", "between", "above")
TABLE_BAD_BINS = ("lower_only", "upper_only", "both")


def round_class(s: np.ndarray, f: int) -> np.ndarray:
    """ROUND_BINS index of every value with f > 0 fraction bits."""
    frac = s & ((1 << f) - 1)
    half = 1 << (f - 1)
    odd = (s >> f) & 1
    return np.where(frac < half, 0, np.where(frac > half, 3, 1 + odd))


def three(v: np.ndarray, lo: int, hi: int) -> np.ndarray:
    """0 below lo, 1 in [lo, hi], 2 above hi."""
    return np.where(v < lo, 0, np.where(v > hi, 2, 1))


def level(v: int, bits: int) -> str:
    """A register's code: 0, its largest, another."""
    return "zero" if v == 0 else "max" if v == (1 << bits) - 1 else "other"


def hit(out: Classes, point: str, labels: Sequence[str], idx: np.ndarray | Sequence[int]
        ) -> None:
    """Add the bins ``labels[k]`` of every index in ``idx`` to ``out[point]``."""
    out.setdefault(point, set()).update(labels[int(k)] for k in np.unique(idx))
