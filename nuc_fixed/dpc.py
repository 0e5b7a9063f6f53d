"""``dpc_core``: defective-pixel correction, bit-exact to ``docs/datapath.md``."""

from __future__ import annotations

import numpy as np
from irnuc.nuc_fixed import _kernels
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.nuc import out_dtype
from irnuc.nuc_fixed.validate import InputError, as_config, bool_array, check_frame_shape, int_array


def dpc_core(y: np.ndarray, bad: np.ndarray, cfg: PipelineConfig | str) -> np.ndarray:
    """Replace flagged pixels by the rounded mean of their good in-frame 3x3 neighbours.

    Parameters
    ----------
    y : integer array_like, (H, W) or (N, H, W)
        NUC output codes in [0, 2^B - 1]. The frame size comes from the shape and must not
        exceed ``cfg.max_height`` x ``cfg.max_width``.
    bad : bool array_like, (H, W)
        Defective-pixel map (True = replace).
    cfg : PipelineConfig or str
        Pipeline configuration (or its name).

    Returns
    -------
    ndarray
        Corrected frames of the shape of ``y`` (uint16 if B <= 16 else uint32). Good pixels,
        and bad pixels without any good neighbour, pass unchanged.
    """
    cfg = as_config(cfg)
    ya = int_array("y", y, 0, (1 << cfg.out_bits) - 1)
    h, w = check_frame_shape("y", ya.shape, cfg)
    b = bool_array("bad", bad)
    if b.shape != (h, w):
        raise InputError(
            f"bad has shape {b.shape} but the frames of y are {(h, w)}; they must match"
        )
    out = np.array(ya.reshape(-1, h, w), dtype=out_dtype(cfg), order="C", copy=True)
    _kernels.dpc_inplace(out, np.ascontiguousarray(b))
    return out.reshape(ya.shape)


def uncorrectable(bad: np.ndarray) -> np.ndarray:
    """Bad pixels with no good in-frame neighbour (DPC passes them through uncorrected)."""
    b = np.asarray(bad, dtype=bool)
    h, w = b.shape
    good = np.zeros((h + 2, w + 2), dtype=np.int64)
    good[1:-1, 1:-1] = ~b
    # Zero border = absent neighbours: counts only in-frame good pixels.
    n = sum(good[1 + dr:h + 1 + dr, 1 + dc:w + 1 + dc]
            for dr in (-1, 0, 1) for dc in (-1, 0, 1) if dr or dc)
    return b & (n == 0)
