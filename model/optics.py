"""Optics: camera equation for the centre pixel (paper eq. 9-12) and cos^4 falloff (eq. 13).

Deviation from the paper: eq. 12 uses the *field of view* as the angle of the light cone that
reaches a pixel. That cone is set by the aperture, not the field of view: for a lens obeying
the sine condition, sin(theta) = 1 / (2 N) with N the working F-number. The default method
``f_number`` uses that; ``paper_fov`` reproduces eq. 12 as printed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from irnuc.model.core import optics as _k
from irnuc.model.validate import ConfigError, check_choice, check_int, check_scalar

#: Cone (projected solid angle / pi) methods, selected by name.
CONE_METHODS = {"f_number": _k.cone_factor_f_number, "paper_fov": _k.cone_factor_paper_fov}


def cone_factor(method: str = "f_number", *, f_number: float | None = None,
                fov: float | None = None) -> float:
    """sin^2 of the image-side cone half-angle, dimensionless.

    Parameters
    ----------
    method : str
        ``f_number`` (sin theta = 1/(2N)) or ``paper_fov`` (sin^2(FOV/2), eq. 12 as printed).
    f_number : float
        Working F-number, >= 0.5 (sin theta <= 1), for ``f_number``.
    fov : float
        Full field of view, rad, in (0, pi), for ``paper_fov``.
    """
    check_choice("optics.cone_method", method, CONE_METHODS)
    if method == "f_number":
        return _k.cone_factor_f_number(check_scalar("optics.f_number", f_number, 0.5, 100.0))
    return _k.cone_factor_paper_fov(
        check_scalar("optics.fov", fov, 0.0, math.pi, lo_open=True, hi_open=True, unit="rad"))


def focal_length_from_fov(fov: float, sensor_width: float) -> float:
    """Focal length, m, that gives a full field of view ``fov`` (rad) over ``sensor_width`` (m).

    Inverse of FOV = 2 arctan(l / (2 f)) (paper eq. 7).
    """
    fov = check_scalar("optics.fov", fov, 0.0, math.pi, lo_open=True, hi_open=True, unit="rad")
    width = check_scalar("sensor_width", sensor_width, 0.0, None, lo_open=True, unit="m")
    return width / (2.0 * math.tan(0.5 * fov))


def centre_pixel_power(radiance: float | np.ndarray, area: float, cone: float,
                       transmission: float = 1.0) -> np.ndarray:
    """Power on the centre pixel, W (paper eq. 12): P = pi tau L A sin^2(theta).

    Parameters
    ----------
    radiance : float or ndarray
        Scene in-band radiance, W m^-2 sr^-1.
    area : float
        Sensitive area of the pixel (pitch^2 times fill factor), m^2.
    cone : float
        sin^2 of the cone half-angle, from :func:`cone_factor`.
    transmission : float
        Optics transmission tau in [0, 1].
    """
    return math.pi * transmission * np.asarray(radiance, dtype=np.float64) * area * cone


def cos4_map(rows: int, cols: int, pitch: float, focal_length: float,
             centre: tuple[float, float] | None = None) -> np.ndarray:
    """cos^4 falloff of every pixel of a rows x cols array (paper eq. 13).

    Parameters
    ----------
    rows, cols : int
        Array size, pixels (>= 1).
    pitch : float
        Pixel pitch, m.
    focal_length : float
        Distance from the exit pupil to the array, m.
    centre : (float, float), optional
        Where the optical axis meets the array, in pixel-index units (row, col). Default: the
        geometric centre ((rows - 1) / 2, (cols - 1) / 2).

    Returns
    -------
    ndarray
        (rows, cols) float64, 1 on the axis, falling as cos^4 of the off-axis angle.
    """
    rows = check_int("rows", rows, 1)
    cols = check_int("cols", cols, 1)
    pitch = check_scalar("fpa.pitch", pitch, 0.0, 1e-3, lo_open=True, unit="m")
    focal_length = check_scalar("optics.focal_length", focal_length, 0.0, 10.0, lo_open=True,
                                unit="m")
    cr, cc = _check_centre(centre, rows, cols)
    _check_cos4_memory(rows, cols)
    out = np.empty((rows, cols), np.float64)
    return _k.cos4_map(rows, cols, float(cr), float(cc), pitch, focal_length, out)


def _check_centre(centre: Any, rows: int, cols: int) -> tuple[float, float]:
    """The optical centre (row, col): two finite numbers, default the geometric centre."""
    if centre is None:
        return (rows - 1) / 2.0, (cols - 1) / 2.0
    try:
        cr, cc = centre
    except (TypeError, ValueError):
        raise ConfigError(f"centre = {centre!r} must be two numbers (row, col) in pixel-index "
                          "units") from None
    return check_scalar("centre[0]", cr), check_scalar("centre[1]", cc)


def _check_cos4_memory(rows: int, cols: int) -> None:
    from irnuc.common.memory import check_memory

    # The map itself (float64) and its temporaries in the callers (coupling products).
    check_memory(rows * cols * 8 * 3, f"cos4_map: rows x cols = {rows} x {cols}",
                 "use a smaller array")
