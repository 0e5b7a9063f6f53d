"""``blind_drift``: the drift of the blind-pixel mean since calibration, per frame.

Blind (skimming, boundary) pixels see the shield, not the scene, so their mean follows the
offset drift of the array with the FPA and housing temperature. Once per frame the RTL
module sums the frame's K blind codes and turns the change of that sum since calibration
into a drift code delta (ADC codes, Df fraction bits), which
:func:`irnuc.nuc_fixed.cores.drift_sub` subtracts from every raw code of the frame before
the gain. Global, not per row: see docs/methods.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.cores import code_range
from irnuc.nuc_fixed.fixed import apply_overflow, round_shift
from irnuc.nuc_fixed.validate import InputError, as_config, int_array


@dataclass(frozen=True)
class DriftResult:
    """Per-frame values: the blind sum (unsigned), its change (signed) and delta (signed)."""

    bsum: np.ndarray
    bd: np.ndarray
    delta: np.ndarray


def blind_sums(blind_codes: object, cfg: PipelineConfig) -> np.ndarray:
    """Sum of each frame's blind codes (N,) from (N, K) codes in [0, 2^A - 1], K <= blind_max."""
    b = int_array("blind_codes", blind_codes, 0, (1 << cfg.adc_bits) - 1)
    if b.ndim == 1:
        b = b[None]
    if b.ndim != 2 or not 1 <= b.shape[1] <= int(cfg.blind_max or 0):
        raise InputError(f"blind_codes has shape {b.shape}; (N, K) with 1 <= K <= blind_max "
                         f"= {cfg.blind_max} is required")
    return b.astype(np.int64).sum(axis=1)


def blind_drift(blind_codes: object, blind_ref: int, drift_gain: int,
                cfg: PipelineConfig | str) -> DriftResult:
    """``blind_drift``: delta = OVF_D(ROUND_(Mf - Df)((sum(b) - blind_ref) * m)).

    Parameters
    ----------
    blind_codes : integer array_like, (N, K) or (K,)
        The blind pixel codes of each frame.
    blind_ref : int
        The blind sum at calibration (register ``blind_ref``, unsigned).
    drift_gain : int
        m, ADC codes of drift per code of blind-sum change (format ``drift_gain``): the
        calibrated coupling of the array's offset to the blind pixels divided by K.

    Returns
    -------
    DriftResult
        bsum, bd and delta, each (N,) int64; delta in the ``drift`` format with its
        rounding and overflow.
    """
    cfg = as_config(cfg)
    return drift_from_sums(blind_sums(blind_codes, cfg), blind_ref, drift_gain, cfg)


def drift_from_sums(bsum: object, blind_ref: int, drift_gain: int,
                    cfg: PipelineConfig | str) -> DriftResult:
    """:func:`blind_drift` from each frame's blind sum, as a register holds it
    (``irnuc_axis_top``'s BLIND_SUM, U SB.0: any SB-bit value, not only sums of
    ``blind_max`` codes; the RTL's bd has SB + 1 bits either way).

    Parameters
    ----------
    bsum : integer array_like, (N,)
        The blind sum of each frame, in [0, 2^SB - 1].
    blind_ref, drift_gain : int
        As in :func:`blind_drift`.
    """
    cfg = as_config(cfg)
    bsum = int_array("blind_sum", bsum, 0, (1 << cfg.blind_sum_bits) - 1).reshape(-1)
    ref = int(int_array("blind_ref", blind_ref, 0, (1 << cfg.blind_sum_bits) - 1))
    lo, hi = code_range(cfg, "drift_gain")
    m = int(int_array("drift_gain", drift_gain, lo, hi))
    df, mf = cfg.format("drift"), cfg.format("drift_gain")
    bd = bsum - ref
    r = np.asarray(round_shift(np.ascontiguousarray(bd * np.int64(m)),
                               mf.frac_bits - df.frac_bits, df.rounding), dtype=np.int64)
    dlo, dhi = code_range(cfg, "drift")
    delta = np.asarray(apply_overflow(r, dlo, dhi, df.overflow), dtype=np.int64)
    return DriftResult(bsum=bsum, bd=bd, delta=delta)
