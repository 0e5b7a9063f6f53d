"""Image-quality metrics of a corrected frame (definitions in ``docs/reports.md``).

All functions take float or integer arrays of one frame (H, W) and a boolean mask of the
pixels to measure (the good pixels: flagged bad pixels are excluded, DPC is not applied).
Errors are in output LSB (codes of the NUC output), non-uniformity is dimensionless.
"""

from __future__ import annotations

import math

import numpy as np


def nonuniformity(y: np.ndarray, mask: np.ndarray) -> float:
    """Residual non-uniformity: spatial standard deviation over spatial mean (ddof 0)."""
    v = np.asarray(y, dtype=np.float64)[mask]
    mean = float(v.mean())
    return float(v.std()) / mean if mean != 0 else float("nan")


def radial_profile(err: np.ndarray, mask: np.ndarray,
                   centre: tuple[float, float] | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Azimuthal mean of ``err`` in one-pixel-wide rings around ``centre``.

    Parameters
    ----------
    err : (H, W) array
        Error image (output LSB).
    mask : (H, W) bool
        Pixels that take part.
    centre : (row, col), optional
        Optical axis in pixel coordinates; default the array centre ((H-1)/2, (W-1)/2),
        which is where the model puts the axis (docs/model.md, cos^4 falloff).

    Returns
    -------
    radius, mean, count : ndarray
        Ring radius (pixels), mean error in the ring, number of pixels; empty rings dropped.
    """
    h, w = err.shape
    cy, cx = centre if centre is not None else ((h - 1) / 2.0, (w - 1) / 2.0)
    yy, xx = np.mgrid[0:h, 0:w]
    ring = np.floor(np.hypot(yy - cy, xx - cx) + 0.5).astype(np.int64)[mask]
    e = np.asarray(err, dtype=np.float64)[mask]
    count = np.bincount(ring)
    total = np.bincount(ring, weights=e)
    keep = count > 0
    radius = np.nonzero(keep)[0].astype(np.float64)
    return radius, total[keep] / count[keep], count[keep]


def radial_artefact(err: np.ndarray, mask: np.ndarray,
                    centre: tuple[float, float] | None = None) -> tuple[float, float]:
    """The ring (cos^4) artefact of an error image.

    Returns ``(radial_rms, radial_fraction)``: the pixel-weighted standard deviation of the
    azimuthally averaged error over the rings (output LSB), and its square over the
    variance of the error (0: no radial structure, 1: the error is a function of the
    radius only). Averaging a ring of n pixels leaves about sigma/sqrt(n) of an
    unstructured error, so a purely random error gives a small, non-zero value.
    """
    _, mean, count = radial_profile(err, mask, centre)
    if count.sum() == 0:
        return 0.0, 0.0
    overall = float((mean * count).sum() / count.sum())
    radial_var = float((count * (mean - overall) ** 2).sum() / count.sum())
    total_var = float(np.asarray(err, dtype=np.float64)[mask].var())
    frac = radial_var / total_var if total_var > 0 else 0.0
    return math.sqrt(radial_var), min(frac, 1.0)


def psnr_db(rms: float, out_bits: int) -> float | None:
    """Peak signal-to-noise ratio of an error of ``rms`` LSB at ``out_bits``; None if rms is 0."""
    if rms <= 0:
        return None
    return 20.0 * math.log10(((1 << out_bits) - 1) / rms)


def frame_metrics(y: np.ndarray, y_ref: np.ndarray, x: np.ndarray, mask: np.ndarray,
                  adc_bits: int, out_bits: int,
                  centre: tuple[float, float] | None = None) -> dict[str, float | None]:
    """Every per-frame metric of a quantized NUC output against the float NUC.

    Parameters
    ----------
    y : (H, W) int array
        Fixed-point NUC output (output codes).
    y_ref : (H, W) float array
        Unquantized float NUC ``gain * x + offset`` (output codes, neither rounded nor clipped).
    x : (H, W) int array
        Raw ADC codes.
    mask : (H, W) bool
        Pixels measured (good pixels).
    adc_bits, out_bits : int
        Widths of x and y; an output LSB is 2^(A - B) ADC LSB.
    """
    yf = np.asarray(y, dtype=np.float64)
    err = yf - y_ref
    e = err[mask]
    rms = float(np.sqrt(np.mean(e**2)))
    radial_rms, radial_frac = radial_artefact(err, mask, centre)
    to_adc = 2.0 ** (adc_bits - out_bits)
    return {
        "residual_nu": nonuniformity(yf, mask),
        "residual_nu_adc_lsb": float(yf[mask].std()) * to_adc,
        "float_nu": nonuniformity(y_ref, mask),
        "raw_nu": nonuniformity(x, mask),
        "raw_nu_adc_lsb": float(np.asarray(x, dtype=np.float64)[mask].std()),
        "err_max_lsb": float(np.abs(e).max()),
        "err_rms_lsb": rms,
        "err_mean_lsb": float(e.mean()),
        "psnr_db": psnr_db(rms, out_bits),
        "radial_rms_lsb": radial_rms,
        "radial_fraction": radial_frac,
    }


def pareto_front(cost: np.ndarray, error: np.ndarray) -> np.ndarray:
    """Indices of the points not dominated in (cost, error), both minimised, by cost.

    A point is dominated when another has cost <= and error <=, one of them strictly.
    Ties in both are kept once (the first index).
    """
    cost = np.asarray(cost, dtype=np.float64)
    error = np.asarray(error, dtype=np.float64)
    order = np.lexsort((error, cost))
    front: list[int] = []
    best = math.inf
    for i in order:
        if error[i] < best:
            front.append(int(i))
            best = float(error[i])
    return np.asarray(front, dtype=np.int64)


def precision_recall(found: np.ndarray, truth: np.ndarray) -> dict[str, float | int]:
    """Precision and recall of a detected bad-pixel map against the ground truth."""
    found = np.asarray(found, dtype=bool)
    truth = np.asarray(truth, dtype=bool)
    tp = int((found & truth).sum())
    fp = int((found & ~truth).sum())
    fn = int((~found & truth).sum())
    return {
        "true_positives": tp,
        "false_positives": fp,
        "false_negatives": fn,
        "precision": tp / (tp + fp) if tp + fp else 1.0,
        "recall": tp / (tp + fn) if tp + fn else 1.0,
    }


# ---- residuals in millikelvin of scene temperature (the one home of the conversion) -------

#: The scene step (each side, K) of the local responsivity of a corrected image.
SLOPE_STEP_K = 0.5


class TemperatureScale:
    """The calibration's map between scene temperature and output level: each calibration
    scene's target level, linear in the in-band radiance between them (the raw signal is
    linear in radiance) and beyond the end scenes. ``level(T)`` gives the level of a scene
    (K -> output codes), ``temperature(level)`` the scene a level reads (output codes -> K).

    Parameters
    ----------
    targets : sequence of float
        Output level of each calibration scene (output codes), increasing.
    scenes : sequence of float
        The calibration scenes, K, increasing.
    band : (float, float)
        The sensor's band, m (``radiometry.band``).
    """

    def __init__(self, targets, scenes, band) -> None:
        from irnuc.model.radiometry import band_radiance, band_radiance_at

        self._L = lambda T: np.asarray(band_radiance(np.atleast_1d(np.asarray(T, float)),
                                                     tuple(band)), dtype=np.float64)
        # one temperature at a time, the band checked once: the root finder's thousands
        # of calls (the same values as _L)
        self._L1 = band_radiance_at(tuple(band))
        self.targets = np.asarray(targets, dtype=np.float64)
        self.scenes = np.asarray(scenes, dtype=np.float64)
        self.radiance = self._L(self.scenes)

    def _segment(self, x: float, xs: np.ndarray) -> int:
        return int(np.clip(np.searchsorted(xs, x) - 1, 0, len(xs) - 2))

    def level(self, T: float) -> float:
        """Output level of a scene at T (K)."""
        L = self._L1(T)
        i = self._segment(L, self.radiance)
        L0, L1 = self.radiance[i], self.radiance[i + 1]
        t0, t1 = self.targets[i], self.targets[i + 1]
        return float(t0 + (t1 - t0) * (L - L0) / (L1 - L0))

    def temperature(self, level: float) -> float:
        """The scene temperature (K) whose level is ``level`` (output codes)."""
        from scipy.optimize import brentq

        i = self._segment(level, self.targets)
        L0, L1 = self.radiance[i], self.radiance[i + 1]
        t0, t1 = self.targets[i], self.targets[i + 1]
        L = L0 + (L1 - L0) * (level - t0) / (t1 - t0)
        if not L > 0:
            return float("nan")
        lo, hi = 1.0, 1e4
        return float(brentq(lambda T: self._L1(T) - L, lo, hi, xtol=1e-9, rtol=1e-13))


def slope_scenes(scenes, step: float = SLOPE_STEP_K) -> list[float]:
    """The scene temperatures (K) of the frames :func:`residuals_mK` needs: each scene,
    then the scene minus and plus ``step``."""
    return [float(t) for s in scenes for t in (s, s - step, s + step)]


def residuals_mK(y: np.ndarray, good: np.ndarray, scenes, scale: TemperatureScale,
                 step: float = SLOPE_STEP_K) -> list[dict[str, float]]:
    """The fixed pattern and the level error of corrected uniform scenes, in mK of scene
    temperature: the one conversion every study and the report use.

    Parameters
    ----------
    y : (3 S, H, W) array
        Corrected frames of the camera in one state (FPA, housing, the same coefficients),
        three per scene in the order of :func:`slope_scenes`: the scene, minus and plus
        ``step``.
    good : (H, W) bool
        The pixels measured.
    scenes : sequence of float
        The S scene temperatures, K.
    scale : TemperatureScale
        The calibration's temperature scale (the level error's reference).

    Returns, per scene: ``fpn_lsb`` (spatial std over good pixels, output LSB), the local
    responsivity ``responsivity_codes_per_K`` (the mean's change between the scene minus
    and plus ``step``, over 2 step: the corrected image's own slope at this FPA, housing and
    scene), ``fpn_mK`` = 1000 fpn_lsb / responsivity, ``level_lsb`` (the image's mean
    minus the scene's calibrated level) and ``level_error_mK`` (the scene the mean reads on
    the calibration's scale minus the scene).
    """
    yf = np.asarray(y, dtype=np.float64)
    out = []
    for k, s in enumerate(scenes):
        f, lo, hi = yf[3 * k], yf[3 * k + 1], yf[3 * k + 2]
        resp = float(hi[good].mean() - lo[good].mean()) / (2.0 * step)
        mean = float(f[good].mean())
        fpn_lsb = float(f[good].std())
        out.append({"scene_K": float(s), "fpn_lsb": fpn_lsb,
                    "responsivity_codes_per_K": resp,
                    "fpn_mK": 1e3 * fpn_lsb / resp if resp > 0 else float("inf"),
                    "level_lsb": mean - scale.level(float(s)),
                    "level_error_mK": 1e3 * (scale.temperature(mean) - float(s))})
    return out
