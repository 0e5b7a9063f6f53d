"""``dpc_core``: defective-pixel correction, bit-exact to ``docs/datapath.md``."""

from __future__ import annotations

import numpy as np

from irnuc.nuc_fixed import _kernels, rtl_spec
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


def neighbour_counts(bad: np.ndarray) -> np.ndarray:
    """Number of good in-frame 8-neighbours of every pixel (0..8), as DPC counts them."""
    b = np.ascontiguousarray(bool_array("bad", bad))
    if b.ndim != 2:
        raise InputError(f"bad has shape {b.shape}; (H, W) is required")
    counts = np.empty(b.shape, dtype=np.int64)
    _kernels.neighbour_counts(b, counts)
    return counts


def uncorrectable(bad: np.ndarray) -> np.ndarray:
    """Bad pixels with no good in-frame neighbour (DPC passes them through uncorrected)."""
    b = bool_array("bad", bad)
    return b & (neighbour_counts(b) == 0)


def reciprocal_table(out_bits: int) -> tuple[int, list[int]]:
    """The RTL's DPC division: shift K and table ``R[n] = ceil(2^K / n)``, n = 0..8.

    ``dpc_core`` divides M = S + floor(n/2) (< 2^(B+3)) by n as ``(M * R[n]) >> K`` with
    K = B + 6 (docs/datapath.md; :func:`irnuc.nuc_fixed.rtl_spec.dpc_recip_shift`);
    ``R[0]`` is unused (0). Exact because M * (R[n] n - 2^K) < 2^(B+3) * 8 = 2^K. The
    golden model divides exactly; the tests prove this table equal for every M and read
    the RTL's table back from the simulator.
    """
    lo, hi = rtl_spec.PIPELINE_RANGES["out_bits"]
    if isinstance(out_bits, bool) or not isinstance(out_bits, int) or not lo <= out_bits <= hi:
        raise InputError(f"out_bits = {out_bits!r} is outside the allowed range {lo}..{hi} (int)")
    return rtl_spec.dpc_recip_shift(out_bits), [rtl_spec.dpc_recip(out_bits, n)
                                                for n in range(9)]
