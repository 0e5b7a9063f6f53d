"""Two-point calibration: float coefficients, bad pixels, quantized codes and a report.

gain = (T_hi - T_lo) / (X_hi - X_lo) and offset = T_lo - gain * X_lo per pixel, where X
are the per-pixel means over M frames at the low and high blackbody temperature and T the
target output levels (output codes). The default targets are the mean of X over the
pixels not flagged by the response checks, scaled by 2^(B - A) so that the output uses
the same fraction of its full scale as the input.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from irnuc.nuc_fixed.badpix import (
    DetectionThresholds,
    Reason,
    detect_offset_outliers,
    detect_response,
    load_thresholds,
    reason_names,
    stack_stats,
)
from irnuc.nuc_fixed.config import ROUNDING_MODES, ConfigError, PipelineConfig
from irnuc.nuc_fixed.dpc import uncorrectable
from irnuc.nuc_fixed.fixed import gain_format, offset_format
from irnuc.nuc_fixed.memimage import pack_words
from irnuc.nuc_fixed.nuc import nuc_core
from irnuc.nuc_fixed.validate import InputError, as_config, check_frame_shape, int_array

#: Memory of the work on frames besides the frames themselves, per ADC code and per pixel
#: of a frame, above measured peaks (docs/robustness.md): calibration selects the two
#: stacks and takes float64 statistics (per code), then some twenty float64 maps (per
#: pixel); correction makes the output codes and their compressed file.
CALIBRATE_WORK_BYTES = {"per_code": 12.0, "per_pixel": 1500.0}
CORRECT_WORK_BYTES = {"per_code": 8.0, "per_pixel": 128.0}

# Reasons that make the float coefficients meaningless (excluded from the needed range).
_NOT_CALIBRATABLE = (Reason.STUCK | Reason.RAIL | Reason.EQUAL_RESPONSE | Reason.UNRESPONSIVE
                     | Reason.OVER_RESPONSIVE)


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`calibrate` (all per-pixel arrays are (H, W)).

    Attributes
    ----------
    gain_code, offset_code : int64
        Quantized coefficients; flagged pixels hold the median code of the good pixels.
    bad : bool
        Defective-pixel map.
    reasons : uint16
        :class:`~nuc_fixed.badpix.Reason` bits per pixel (0 = good).
    gain, offset : float64
        Unquantized coefficients (output codes per ADC code, output codes); 0 where the
        gain is undefined (equal responses). Never inf or NaN.
    summary : dict
        Targets, medians, saturation counts, needed ranges, counts per reason.
    """

    cfg: PipelineConfig
    gain_code: np.ndarray
    offset_code: np.ndarray
    bad: np.ndarray
    reasons: np.ndarray
    gain: np.ndarray
    offset: np.ndarray
    summary: dict[str, object] = field(default_factory=dict)

    def words(self) -> np.ndarray:
        """Coefficient words (memory image version 1) of this calibration."""
        return pack_words(self.gain_code, self.offset_code, self.bad, self.cfg)


def _stack(name: str, frames: object, cfg: PipelineConfig) -> np.ndarray:
    a = int_array(name, frames, 0, (1 << cfg.adc_bits) - 1)
    if a.ndim == 2:
        a = a[None]
    check_frame_shape(name, a.shape, cfg)
    if a.shape[0] < 1:
        raise InputError(f"{name} holds no frame; at least 1 is required")
    return a


def _needed(fmt, values: np.ndarray) -> dict[str, object]:
    if values.size == 0:
        return {"min": None, "max": None, "int_bits_needed": None}
    lo, hi = float(values.min()), float(values.max())
    if not fmt.signed and lo < 0:
        bits = None  # an unsigned format cannot hold a negative gain at any width
    else:
        bits = fmt.bits_needed(lo, hi)
    return {"min": lo, "max": hi, "int_bits_needed": bits, "int_bits": fmt.int_bits,
            "frac_bits": fmt.frac_bits, "format": str(fmt)}


def calibrate(
    frames_lo: np.ndarray,
    frames_hi: np.ndarray,
    cfg: PipelineConfig | str,
    thresholds: DetectionThresholds | None = None,
    targets: tuple[float, float] | None = None,
    rounding: str = "half_even",
) -> Calibration:
    """Two-point NUC coefficients and bad-pixel map from two calibration stacks.

    Parameters
    ----------
    frames_lo, frames_hi : integer array_like, (M, H, W) or (H, W)
        Raw ADC codes at the low and the high blackbody temperature (M may differ).
    cfg : PipelineConfig or str
    thresholds : DetectionThresholds, optional
        Default: ``nuc_fixed/detection.toml``.
    targets : (float, float), optional
        Output levels (output codes) at the low and high temperature; default: the frame
        means scaled by 2^(B - A).
    rounding : {"truncate", "half_up", "half_even"}
        Rounding of the float coefficients to codes (saturating).
    """
    cfg = as_config(cfg)
    if rounding not in ROUNDING_MODES:
        raise ConfigError(f"rounding = {rounding!r} is not one of {sorted(ROUNDING_MODES)}")
    th = thresholds if thresholds is not None else load_thresholds()
    lo = _stack("frames_lo", frames_lo, cfg)
    hi = _stack("frames_hi", frames_hi, cfg)
    if lo.shape[1:] != hi.shape[1:]:
        raise InputError(f"frames_lo frames are {lo.shape[1:]} but frames_hi frames are "
                         f"{hi.shape[1:]}; they must match")
    stats = stack_stats(lo, hi, cfg.adc_bits)
    reasons, med_resp = detect_response(stats, th)

    scale = 2.0 ** (cfg.out_bits - cfg.adc_bits)
    pre_good = reasons == 0
    if targets is None:
        t_lo = float(stats.mean_lo[pre_good].mean()) * scale
        t_hi = float(stats.mean_hi[pre_good].mean()) * scale
    else:
        try:
            tv = np.asarray(targets, dtype=np.float64)
        except (TypeError, ValueError):
            tv = np.array([np.nan])
        if tv.shape != (2,) or not np.isfinite(tv).all():
            raise ConfigError(f"targets = {targets!r} must be two finite numbers (output codes)")
        t_lo, t_hi = (float(t) for t in tv)
    full_out = float(2**cfg.out_bits)
    for nm, t in (("target low", t_lo), ("target high", t_hi)):
        if not 0.0 <= t <= full_out - 1:
            raise ConfigError(f"{nm} = {t:g} output codes is outside [0, {full_out - 1:g}]")

    resp = stats.response
    defined = resp != 0
    # Equal responses would divide by zero: leave gain 0 there (already flagged).
    gain = np.divide(t_hi - t_lo, resp, out=np.zeros_like(resp), where=defined)
    offset = np.where(defined, t_lo - gain * stats.mean_lo, 0.0)

    gfmt, ofmt = gain_format(cfg), offset_format(cfg)
    gcode, ocode, gover, oover = quantize_coefficients(gain, offset, cfg, rounding)
    gover &= defined
    oover &= defined
    reasons[gover] |= np.uint16(Reason.GAIN_RANGE)
    reasons[oover] |= np.uint16(Reason.OFFSET_RANGE)
    usable = reasons == 0
    outl, off_sigma, off_limit = detect_offset_outliers(offset, usable, th, full_out)
    reasons[outl & defined] |= np.uint16(Reason.OFFSET_OUTLIER)
    bad = reasons != 0
    good = ~bad
    gcode_out, ocode_out, (gfill, ofill) = fill_flagged(gcode, ocode, bad)  # fails if none good

    calibratable = (reasons & int(_NOT_CALIBRATABLE)) == 0
    counts = {r.name: int(((reasons & int(r)) != 0).sum()) for r in Reason}
    # Residual of the quantized NUC at the calibration points, over good pixels.
    res = {}
    for nm, mean, t in (("low", stats.mean_lo, t_lo), ("high", stats.mean_hi, t_hi)):
        x = np.clip(np.rint(mean), 0, (1 << cfg.adc_bits) - 1).astype(np.int64)
        y = nuc_core(x, gcode_out, ocode_out, cfg).astype(np.float64)
        err = y[good] - t
        res[nm] = {"target": t, "rms": float(np.sqrt(np.mean(err**2))),
                   "max_abs": float(np.abs(err).max())}
    h, w = resp.shape
    summary: dict[str, object] = {
        "config": cfg.name,
        "frame": [h, w],
        "frames_low": int(lo.shape[0]),
        "frames_high": int(hi.shape[0]),
        "rounding": rounding,
        "targets": [t_lo, t_hi],
        "median_response": med_resp,
        "offset_local_sigma": off_sigma,
        "offset_outlier_limit": off_limit,
        "thresholds": th.to_dict(),
        "gain": _needed(gfmt, gain[calibratable]),
        "offset": _needed(ofmt, offset[calibratable]),
        "gain_good": _needed(gfmt, gain[good]),
        "offset_good": _needed(ofmt, offset[good]),
        "gain_saturated": int((gover & calibratable).sum()),
        "offset_saturated": int((oover & calibratable).sum()),
        "gain_saturated_all": int(gover.sum()),
        "offset_saturated_all": int(oover.sum()),
        "bad_pixels": int(bad.sum()),
        "bad_fraction": float(bad.mean()),
        "uncorrectable": int(uncorrectable(bad).sum()),
        "reasons": counts,
        "fill_codes": {"gain": gfill, "offset": ofill},
        "residual": res,
    }
    return Calibration(cfg=cfg, gain_code=gcode_out, offset_code=ocode_out, bad=bad,
                       reasons=reasons, gain=gain, offset=offset, summary=summary)


def quantize_coefficients(gain: np.ndarray, offset: np.ndarray, cfg: PipelineConfig,
                          rounding: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Float gains (output codes per ADC code) and offsets (output codes) to the codes of
    ``cfg``'s gain and offset formats, rounded with ``rounding``, saturating.

    Returns (gain codes, offset codes, gain saturated, offset saturated), all (H, W).
    """
    gcode, gover = gain_format(cfg).quantize(gain, rounding)
    ocode, oover = offset_format(cfg).quantize(offset, rounding)
    return gcode, ocode, gover, oover


def fill_flagged(gain_code: np.ndarray, offset_code: np.ndarray, bad: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, tuple[int, int]]:
    """Flagged pixels get the median codes of the good ones, so that an uncorrectable pixel
    still looks plausible; returns the filled codes and the (gain, offset) fill codes.
    Raises :class:`InputError` when no pixel is good."""
    good = ~np.asarray(bad, dtype=bool)
    if not good.any():
        raise InputError("every pixel was flagged bad; check the thresholds and the frames")
    gfill, ofill = int(np.median(gain_code[good])), int(np.median(offset_code[good]))
    return np.where(good, gain_code, gfill), np.where(good, offset_code, ofill), (gfill, ofill)


def summary_text(cal: Calibration) -> str:
    """A short human-readable report of a calibration."""
    s = cal.summary
    lines = [
        f"irnuc calibration, pipeline {s['config']}, frame {s['frame'][1]} x {s['frame'][0]} "
        f"(W x H), {s['frames_low']} + {s['frames_high']} frames",
        f"targets (output codes): low {s['targets'][0]:.3f}, high {s['targets'][1]:.3f}; "
        f"median response {s['median_response']:.3f} ADC codes",
    ]
    for key in ("gain", "offset"):
        for sub, label in ((key, "calibratable pixels"), (key + "_good", "good pixels")):
            d = s[sub]
            if d["min"] is None:
                continue
            lines.append(
                f"{key} ({label}): needed range [{d['min']:.6g}, {d['max']:.6g}] -> "
                f"{d['int_bits_needed']} integer bits at {d['frac_bits']} fraction bits "
                f"(format {d['format']})"
            )
        lines.append(f"{key}: {s[key + '_saturated']} coefficient(s) of calibratable pixels "
                     f"saturated ({s[key + '_saturated_all']} of all pixels)")
    lines.append(f"bad pixels: {s['bad_pixels']} ({100 * s['bad_fraction']:.3f} %), "
                 f"uncorrectable: {s['uncorrectable']}")
    for name, n in s["reasons"].items():
        if n:
            lines.append(f"  {name:16s} {n}")
    for nm in ("low", "high"):
        r = s["residual"][nm]
        lines.append(f"residual at {nm}: rms {r['rms']:.3f}, max |e| {r['max_abs']:.3f} codes")
    return "\n".join(lines) + "\n"


__all__ = ["Calibration", "calibrate", "fill_flagged", "quantize_coefficients", "reason_names",
           "summary_text"]
