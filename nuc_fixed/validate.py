"""Input checks for the golden-model API, run before any work.

Every failure raises :class:`InputError` (a :class:`ValueError`) whose message names the
argument, the offending value and its position, and the allowed range.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from irnuc.common.errors import UserError
from irnuc.nuc_fixed.config import ConfigError, PipelineConfig, load_pipeline


class InputError(UserError):
    """An array argument has the wrong shape, dtype or values out of range."""


def as_config(cfg: PipelineConfig | str) -> PipelineConfig:
    """Accept a :class:`PipelineConfig` or the name of one in ``pipelines.toml``."""
    if isinstance(cfg, PipelineConfig):
        return cfg
    if isinstance(cfg, str):
        return load_pipeline(cfg)
    raise ConfigError(f"cfg = {cfg!r} is neither a PipelineConfig nor a configuration name")


def int_array(name: str, value: Any, lo: int, hi: int, *, allow_bool: bool = False) -> np.ndarray:
    """Return ``value`` as an integer ndarray whose elements all lie in [lo, hi].

    Parameters
    ----------
    name : str
        Argument name used in error messages.
    value : array_like
        Integer codes. Float arrays are refused (even when integral), NaN is named.
    lo, hi : int
        Inclusive allowed range.
    allow_bool : bool
        Accept a boolean array (read as 0/1).
    """
    try:
        arr = np.asarray(value)
    except (ValueError, TypeError) as exc:  # ragged nested lists and the like
        raise InputError(f"{name} is not an array of integers ({exc})") from None
    if arr.dtype.byteorder not in ("=", "|"):
        # A big- or little-endian array of the other order: convert once, here.
        arr = arr.astype(arr.dtype.newbyteorder("="))
    if arr.dtype == np.bool_:
        if not allow_bool:
            raise InputError(f"{name} has dtype bool; an integer dtype is required")
        arr = arr.view(np.uint8)
    elif not np.issubdtype(arr.dtype, np.integer):
        if np.issubdtype(arr.dtype, np.floating) and arr.size and np.isnan(arr).any():
            idx = tuple(int(i) for i in np.argwhere(np.isnan(arr))[0])
            raise InputError(
                f"{name} contains NaN at index {idx} ({int(np.isnan(arr).sum())} NaN value(s)); "
                f"integer codes in [{lo}, {hi}] are required"
            )
        raise InputError(
            f"{name} has dtype {arr.dtype}; an integer dtype with codes in [{lo}, {hi}] is required"
        )
    if arr.size == 0:
        raise InputError(f"{name} is empty (shape {arr.shape}); at least one code in "
                         f"[{lo}, {hi}] is required")
    amin, amax = arr.min(), arr.max()
    if int(amin) < lo or int(amax) > hi:
        bad = (arr < lo) | (arr > hi)
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise InputError(
            f"{name}[{', '.join(map(str, idx))}] = {int(arr[idx])} is outside the allowed range "
            f"[{lo}, {hi}] ({int(bad.sum())} value(s) out of range)"
        )
    return arr


def bool_array(name: str, value: Any) -> np.ndarray:
    """Return ``value`` as a bool ndarray; integer arrays must hold only 0 and 1."""
    arr = np.asarray(value)
    if arr.dtype == np.bool_:
        if arr.size == 0:
            raise InputError(f"{name} is empty (shape {arr.shape}); a bad-pixel map is required")
        return arr
    return int_array(name, arr, 0, 1).astype(np.bool_)


def check_frame_shape(name: str, shape: tuple[int, ...], cfg: PipelineConfig) -> tuple[int, int]:
    """Check that the last two axes of ``shape`` are a legal frame; return (H, W)."""
    if len(shape) not in (2, 3):
        raise InputError(f"{name} has shape {shape}; (H, W) or (N, H, W) is required")
    h, w = shape[-2], shape[-1]
    if not (1 <= h <= cfg.max_height and 1 <= w <= cfg.max_width):
        raise InputError(
            f"{name} frame size is {h} x {w} (H x W); pipeline {cfg.name!r} allows "
            f"1..{cfg.max_height} rows and 1..{cfg.max_width} columns"
        )
    return h, w
