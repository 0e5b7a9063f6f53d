"""Analogue-to-digital converter: N bits over [v_low, v_high], clamped at both ends."""

from __future__ import annotations

import numpy as np

from irnuc.common.errors import UserError
from irnuc.model.core import adc as _k
from irnuc.model.validate import ConfigError, check_choice, check_int, check_scalar

ADC_ROUNDING = ("nearest", "floor")


class NonFiniteVoltageError(UserError):
    """The ADC was given NaN or infinite voltages (a ``ValueError``, as every
    :class:`~irnuc.common.errors.UserError`)."""


def adc_dtype(bits: int) -> type:
    """Smallest unsigned integer dtype that holds ``bits``-bit codes."""
    return np.uint16 if bits <= 16 else np.uint32


def adc_convert(v: np.ndarray, bits: int, v_low: float, v_high: float,
                rounding: str = "nearest", rails: tuple[float, float] | None = None) -> np.ndarray:
    """Convert voltages to codes.

    Parameters
    ----------
    v : ndarray
        Input voltages, V; every value must be finite.
    bits : int
        Resolution, 1..24. The LSB is (v_high - v_low) / 2**bits.
    v_low, v_high : float
        Input range, V; v_low maps to code 0, voltages at or above
        v_high - LSB/2 map to the top code 2**bits - 1.
    rounding : str
        ``nearest`` (round half up) or ``floor``.
    rails : (float, float), optional
        Rails of the stage that drives the ADC, V; the input is clipped to them first.

    Returns
    -------
    ndarray
        Codes, uint16 for bits <= 16 else uint32, clamped to [0, 2**bits - 1].

    Raises
    ------
    NonFiniteVoltageError
        If any voltage is NaN or infinite (the reference implementation turned those into
        full-scale codes).
    """
    bits = check_int("adc.bits", bits, 1, 24)
    v_low = check_scalar("adc.v_low", v_low, unit="V")
    v_high = check_scalar("adc.v_high", v_high, unit="V")
    if not v_low < v_high:
        raise ConfigError(f"adc.v_low = {v_low:g} V must be below adc.v_high = {v_high:g} V")
    check_choice("adc.rounding", rounding, ADC_ROUNDING)
    lo, hi = rails if rails is not None else (-np.inf, np.inf)
    v = np.ascontiguousarray(v, dtype=np.float64)
    out = np.empty(v.shape, adc_dtype(bits))
    bad = _k.convert(v.reshape(-1), float(lo), float(hi), v_low, (1 << bits) / (v_high - v_low),
                     float((1 << bits) - 1), rounding == "nearest", out.reshape(-1))
    if bad:
        finite = np.isfinite(v)
        idx = tuple(int(i) for i in np.argwhere(~finite)[0])
        raise NonFiniteVoltageError(
            f"ADC input has {int((~finite).sum())} non-finite voltage(s); first {v[idx]!r} at "
            f"index {idx}")
    return out
