"""In-band blackbody radiance (paper section 3.1, eq. 1-4).

The paper integrates Planck's law over the sensor band with a series whose term count was
fixed at 100 in the reference implementation (4.6e-11 off at 5000 K, 2.8e-6 off at
10000 K). Here the number of terms follows from a rigorous remainder bound for a requested
relative tolerance, and hot scenes switch to a lower-integral series so that the band is
never the difference of two nearly equal tails (see :mod:`model.core.radiometry`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.model.core import radiometry as _k
from irnuc.model.validate import ConfigError, check_array, check_choice, check_int, check_scalar

#: Methods of :func:`band_radiance`, selected by name.
#: ``hybrid``: the paper's tail series (eq. 3-4) where it converges fast, the Bernoulli
#: lower-integral series for hot scenes (x < 2), Gauss-Legendre quadrature of the band
#: itself when it is narrow (x1 - x2 <= 2); adaptive term count. The default.
#: ``series``: the paper's eq. 4 as written (difference of two tail series), adaptive term
#: count, or exactly ``n_terms`` terms when given (the reference implementation used 100).
BAND_RADIANCE_METHODS: dict[str, int] = {"hybrid": 0, "series": 1}

#: Hottest accepted temperature, K: far above any scene, and T^4 stays finite.
T_MAX = 1e9

#: Default sensor band of the long-wave infrared, metres.
LWIR_BAND: tuple[float, float] = (8e-6, 14e-6)


@dataclass(frozen=True)
class RadianceResult:
    """Band radiance with the series cost, for work-precision studies.

    Attributes
    ----------
    radiance : ndarray
        In-band radiance, W m^-2 sr^-1.
    terms : ndarray
        Series terms summed per temperature.
    """

    radiance: np.ndarray
    terms: np.ndarray


def check_band(band: tuple[float, float], field: str = "band") -> tuple[float, float]:
    """Validate a wavelength band (lo, hi) in metres, 100 nm to 1 mm, lo < hi."""
    try:
        lo, hi = band
    except (TypeError, ValueError):
        raise ConfigError(f"{field} = {band!r} must be a pair (lo, hi) in metres") from None
    lo = check_scalar(f"{field}[0]", lo, 1e-7, 1e-3, unit="m")
    hi = check_scalar(f"{field}[1]", hi, 1e-7, 1e-3, unit="m")
    if not lo < hi:
        raise ConfigError(f"{field} = ({lo:g}, {hi:g}) m: the lower edge must be below the upper")
    return lo, hi


def band_radiance_detailed(
    T: float | np.ndarray,
    band: tuple[float, float] = LWIR_BAND,
    *,
    emissivity: float = 1.0,
    rtol: float = 1e-12,
    method: str = "hybrid",
    n_terms: int | None = None,
) -> RadianceResult:
    """In-band radiance and the number of series terms used.

    Same parameters as :func:`band_radiance`.
    """
    temps = check_array("T", T, 0.0, T_MAX, lo_open=True, unit="K")
    lo, hi = check_band(band)
    emissivity = check_scalar("emissivity", emissivity, 0.0, 1.0)
    rtol = check_scalar("rtol", rtol, 1e-15, 0.1, unit="(relative)")
    code = BAND_RADIANCE_METHODS[check_choice("method", method, BAND_RADIANCE_METHODS)]
    n_fixed = 0
    if n_terms is not None:
        if method != "series":
            raise ConfigError(f"n_terms = {n_terms!r} is only allowed with method='series'")
        n_fixed = check_int("n_terms", n_terms, 1, _k.MAX_TERMS)
    flat = np.ascontiguousarray(temps.ravel())
    radiance = np.empty_like(flat)
    terms = np.empty(flat.shape, np.int64)
    status = np.empty(flat.shape, np.int64)
    _k.band_radiance_batch(flat, lo, hi, rtol, _k.BERNOULLI_COEF, code, n_fixed, radiance,
                           terms, status)
    if status.any():
        worst = float(flat[status != 0].max())
        raise ConfigError(
            f"T = {worst:g} K: the paper series did not reach rtol = {rtol:g} within "
            f"{_k.MAX_TERMS} terms; use method='hybrid'"
        )
    radiance *= emissivity
    return RadianceResult(radiance.reshape(temps.shape), terms.reshape(temps.shape))


def band_radiance_at(band: tuple[float, float] = LWIR_BAND, *, emissivity: float = 1.0,
                     rtol: float = 1e-12, method: str = "hybrid"):
    """:func:`band_radiance` of one temperature at a time, the band and options checked
    once: for loops that call it thousands of times (a root finder inverting a radiance,
    :class:`irnuc.reports.studies.metrics.TemperatureScale`). The same kernel and the same
    values as ``float(band_radiance(T, band, ...))``.

    Parameters: as :func:`band_radiance` (``band`` in m, ``rtol`` relative), without
    ``n_terms``. Returns a function of T (K, a float in (0, 1e9]) giving the in-band
    radiance, W m^-2 sr^-1.
    """
    lo, hi = check_band(band)
    emissivity = check_scalar("emissivity", emissivity, 0.0, 1.0)
    rtol = check_scalar("rtol", rtol, 1e-15, 0.1, unit="(relative)")
    code = BAND_RADIANCE_METHODS[check_choice("method", method, BAND_RADIANCE_METHODS)]
    radiance = np.empty(1)
    terms = np.empty(1, np.int64)
    status = np.empty(1, np.int64)

    def at(T: float) -> float:
        t = float(T)
        if not 0.0 < t <= T_MAX:  # NaN too
            check_array("T", t, 0.0, T_MAX, lo_open=True, unit="K")  # its message
        flat = np.array([t])
        _k.band_radiance_batch(flat, lo, hi, rtol, _k.BERNOULLI_COEF, code, 0, radiance,
                               terms, status)
        if status[0]:
            raise ConfigError(f"T = {t:g} K: the paper series did not reach rtol = {rtol:g} "
                              f"within {_k.MAX_TERMS} terms; use method='hybrid'")
        return float(radiance[0] * emissivity)

    return at


def band_radiance(
    T: float | np.ndarray,
    band: tuple[float, float] = LWIR_BAND,
    *,
    emissivity: float = 1.0,
    rtol: float = 1e-12,
    method: str = "hybrid",
    n_terms: int | None = None,
) -> np.ndarray:
    """In-band radiance of a grey body (paper eq. 2-4).

    Parameters
    ----------
    T : float or array_like
        Temperature, K, in (0, 1e9] (any shape). Radiances below the float64 range
        (e.g. ~1e-440 at 1 K in the LWIR) are exactly 0; never NaN.
    band : (float, float)
        Band edges (lambda1, lambda2), m, 1e-7 <= lambda1 < lambda2 <= 1e-3.
    emissivity : float
        Emissivity of the source, dimensionless, in [0, 1].
    rtol : float
        Requested relative tolerance of the series, in [1e-15, 0.1]. Narrow bands
        (``hybrid``) are integrated by quadrature to about 1e-15 whatever rtol.
    method : str
        Key of :data:`BAND_RADIANCE_METHODS`.
    n_terms : int, optional
        With ``method='series'``: sum exactly this many terms instead of choosing them.

    Returns
    -------
    ndarray
        Radiance, W m^-2 sr^-1, same shape as ``T``.
    """
    return band_radiance_detailed(
        T, band, emissivity=emissivity, rtol=rtol, method=method, n_terms=n_terms
    ).radiance
