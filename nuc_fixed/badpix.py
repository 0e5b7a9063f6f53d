"""Bad-pixel detection from two-temperature calibration stacks: thresholds and reasons.

A pixel may be flagged for several reasons at once; :class:`Reason` is a bit set stored
as uint16 per pixel. Thresholds live in ``nuc_fixed/detection.toml``.
"""

from __future__ import annotations

import enum
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.common import schema
from irnuc.nuc_fixed.config import ConfigError
from irnuc.nuc_fixed.validate import InputError

DETECTION_TOML = Path(__file__).with_name("detection.toml")


class Reason(enum.IntFlag):
    """Why a pixel is flagged (bit set, uint16 per pixel)."""

    UNRESPONSIVE = 1      # response far below the median (includes zero or negative)
    OVER_RESPONSIVE = 2   # response far above the median
    STUCK = 4             # the same code in every frame at both temperatures
    RAIL = 8              # at code 0 or 2^A - 1 in the calibration frames
    NOISY = 16            # temporal std far above the median
    OFFSET_OUTLIER = 32   # offset far from the median offset
    GAIN_RANGE = 64       # gain not representable in the gain format (negative or too large)
    OFFSET_RANGE = 128    # offset not representable in the offset format
    EQUAL_RESPONSE = 256  # identical mean response at both temperatures: gain undefined
    COEFF_RANGE = 512     # another coefficient of the method not representable in its format


def reason_names(code: int) -> list[str]:
    """Names of the reasons set in ``code``."""
    return [r.name for r in Reason if code & r]  # type: ignore[misc]


#: Schema of a thresholds table (``detection.toml``; meanings and units there).
THRESHOLDS_SCHEMA: dict[str, Any] = schema.table(
    {
        "low_response": schema.number(0.0, 1.0, unit="x median response"),
        "high_response": schema.number(1.0, 1e6, unit="x median response"),
        "noisy_factor": schema.number(1.0, 1e6, unit="x median std"),
        "noisy_min_std": schema.number(0.0, 1e9, unit="ADC codes"),
        "offset_sigma": schema.number(0.0, 1e6, unit="robust sigma"),
        "offset_min": schema.number(0.0, 1.0, unit="of 2^B"),
        "offset_window": {**schema.number(3, 15, integer=True, unit="pixels"),
                          "enum": [3, 5, 7, 9, 11, 13, 15]},
        "rail_fraction": schema.number(0.0, 1.0),
    },
    required=["low_response", "high_response", "noisy_factor", "noisy_min_std",
              "offset_sigma", "offset_min", "offset_window", "rail_fraction"],
)


@dataclass(frozen=True)
class DetectionThresholds:
    """Detection thresholds (see ``detection.toml`` for meanings and units)."""

    low_response: float
    high_response: float
    noisy_factor: float
    noisy_min_std: float
    offset_sigma: float
    offset_min: float
    offset_window: int
    rail_fraction: float

    def __post_init__(self) -> None:
        try:
            schema.check(self.to_dict(), THRESHOLDS_SCHEMA, source="detection thresholds")
        except schema.SchemaError as exc:
            raise ConfigError(str(exc)) from None

    def to_dict(self) -> dict[str, float]:
        return asdict(self)


def load_thresholds(path: str | Path | None = None, section: str = "default",
                    overrides: dict[str, float] | None = None) -> DetectionThresholds:
    """Read thresholds from a TOML file (default: ``nuc_fixed/detection.toml``).

    ``overrides`` (``{field: value}``) change single entries; every field is checked
    against :data:`THRESHOLDS_SCHEMA`, unknown ones refused with the nearest known name.
    """
    p = Path(path) if path is not None else DETECTION_TOML
    table = schema.read_toml(p)
    if section not in table:
        raise ConfigError(f"{p}: no [{section}] table; found {', '.join(table) or 'none'}")
    if not isinstance(table[section], dict):
        raise ConfigError(f"{p}: [{section}] must be a table of thresholds, not "
                          f"{type(table[section]).__name__}")
    entry = dict(table[section])
    try:
        schema.check(entry, THRESHOLDS_SCHEMA, source=str(p), prefix=section)
        entry |= dict(overrides or {})
        schema.check(entry, THRESHOLDS_SCHEMA, source="--set", prefix="")
    except schema.SchemaError as exc:
        raise ConfigError(str(exc)) from None
    return DetectionThresholds(**entry)


@dataclass(frozen=True)
class StackStats:
    """Per-pixel statistics of a low and a high calibration stack (float64, (H, W))."""

    mean_lo: np.ndarray
    mean_hi: np.ndarray
    std_lo: np.ndarray
    std_hi: np.ndarray
    stuck: np.ndarray       # bool: one code in all frames of both stacks
    rail_frac: np.ndarray   # fraction of frames (both stacks) at a rail
    n_frames: int           # the smaller of the two stack sizes

    @property
    def response(self) -> np.ndarray:
        return self.mean_hi - self.mean_lo


def stack_stats(lo: np.ndarray, hi: np.ndarray, adc_bits: int) -> StackStats:
    """Statistics of validated integer stacks ``lo`` (M_lo, H, W) and ``hi`` (M_hi, H, W)."""
    full = (1 << adc_bits) - 1

    def std(a: np.ndarray) -> np.ndarray:
        return a.astype(np.float64).std(axis=0, ddof=1 if a.shape[0] > 1 else 0)

    vmin = np.minimum(lo.min(axis=0), hi.min(axis=0))
    vmax = np.maximum(lo.max(axis=0), hi.max(axis=0))
    at_rail = ((lo == 0) | (lo == full)).sum(axis=0) + ((hi == 0) | (hi == full)).sum(axis=0)
    return StackStats(
        mean_lo=lo.mean(axis=0, dtype=np.float64), mean_hi=hi.mean(axis=0, dtype=np.float64),
        std_lo=std(lo), std_hi=std(hi), stuck=vmin == vmax,
        rail_frac=at_rail / float(lo.shape[0] + hi.shape[0]),
        n_frames=min(lo.shape[0], hi.shape[0]),
    )


def detect_response(stats: StackStats, th: DetectionThresholds) -> tuple[np.ndarray, float]:
    """Reasons from the responses and noise alone, and the median response (codes).

    The median is taken over pixels that are neither stuck, at a rail, nor of equal
    response. Raises ValueError if that median is not positive (the two stacks are
    swapped or do not respond).
    """
    reasons = np.zeros(stats.mean_lo.shape, dtype=np.uint16)
    resp = stats.response
    reasons[stats.stuck] |= np.uint16(Reason.STUCK)
    reasons[stats.rail_frac > th.rail_fraction] |= np.uint16(Reason.RAIL)
    reasons[resp == 0] |= np.uint16(Reason.EQUAL_RESPONSE)
    usable = reasons == 0
    if not usable.any():
        raise InputError("no usable pixel: every pixel is stuck, at a rail or of equal response")
    med = float(np.median(resp[usable]))
    if not med > 0:
        raise InputError(
            f"median response (mean high - mean low) = {med:g} codes; it must be positive: "
            "are the low and high temperature frames swapped?"
        )
    reasons[resp < th.low_response * med] |= np.uint16(Reason.UNRESPONSIVE)
    reasons[resp > th.high_response * med] |= np.uint16(Reason.OVER_RESPONSIVE)
    if stats.n_frames > 1:
        std = np.maximum(stats.std_lo, stats.std_hi)
        med_std = float(np.median(std[reasons == 0])) if (reasons == 0).any() else 0.0
        limit = max(th.noisy_factor * med_std, th.noisy_min_std)
        reasons[std > limit] |= np.uint16(Reason.NOISY)
    return reasons, med


def local_median(values: np.ndarray, usable: np.ndarray, window: int) -> np.ndarray:
    """Median of the usable pixels in the ``window`` x ``window`` box around each pixel.

    Only in-frame usable pixels count (no padding: a border pixel has a smaller window,
    so its own value is never replicated). NaN where a window holds no usable pixel.
    """
    r = window // 2
    h, w = values.shape
    padded = np.full((h + 2 * r, w + 2 * r), np.nan)
    padded[r:r + h, r:r + w] = np.where(usable, values, np.nan)
    win = np.lib.stride_tricks.sliding_window_view(padded, (window, window))
    out = np.full((h, w), np.nan)
    has = (~np.isnan(win)).any(axis=(2, 3))
    out[has] = np.nanmedian(win[has], axis=(1, 2))
    return out


def detect_offset_outliers(offset: np.ndarray, usable: np.ndarray, th: DetectionThresholds,
                           full_scale: float) -> tuple[np.ndarray, float, float]:
    """Offsets (output codes) far from the median offset of their neighbourhood.

    The reference is the median of the usable pixels in the ``offset_window`` box (so
    smooth shading and row/column structure do not count), the spread the robust sigma
    (1.4826 MAD) of those local differences over the usable pixels. Returns the outlier
    mask, the robust sigma and the limit used (output codes).
    """
    if not usable.any():
        return np.zeros(offset.shape, bool), 0.0, 0.0
    ref = local_median(offset, usable, th.offset_window)
    diff = np.where(np.isnan(ref), 0.0, offset - np.nan_to_num(ref))
    d_use = diff[usable]
    sigma = 1.4826 * float(np.median(np.abs(d_use - np.median(d_use))))
    limit = max(th.offset_sigma * sigma, th.offset_min * full_scale)
    return np.abs(diff) > limit, sigma, limit
