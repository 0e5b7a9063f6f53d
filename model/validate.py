"""Input checks shared by every API function of the model.

A bad value is reported before any work, as a :class:`~irnuc.common.errors.ConfigError`
(the one class of every layer, re-exported here) whose message names the field, the value
and the allowed range.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from irnuc.common.errors import ConfigError

__all__ = ["ConfigError", "check_array", "check_choice", "check_frame_period", "check_int",
           "check_scalar"]

def _interval(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    left = "(" if lo_open else "["
    right = ")" if hi_open else "]"
    lo_s = "-inf" if lo is None else f"{lo:g}"
    hi_s = "inf" if hi is None else f"{hi:g}"
    return f"{left}{lo_s}, {hi_s}{right}"


def check_scalar(
    field: str,
    value: Any,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
) -> float:
    """Return ``value`` as a float if it is finite and inside the interval, else raise."""
    unit_s = f" {unit}" if unit else ""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    # A number only: true is not 1 and "30" is not 30 (a TOML string is a typo).
    if isinstance(value, bool | np.bool_) or not isinstance(value, int | float | np.integer
                                                              | np.floating):
        raise ConfigError(f"{field} = {value!r} is not a number")
    x = float(value)
    allowed = _interval(lo, hi, lo_open, hi_open)
    if not math.isfinite(x):
        raise ConfigError(f"{field} = {value!r}{unit_s} is not finite; allowed range {allowed}{unit_s}")
    if (lo is not None and (x < lo or (lo_open and x == lo))) or (
        hi is not None and (x > hi or (hi_open and x == hi))
    ):
        raise ConfigError(f"{field} = {x:g}{unit_s} is outside the allowed range {allowed}{unit_s}")
    return x


def check_int(field: str, value: Any, lo: int | None = None, hi: int | None = None) -> int:
    """Return ``value`` as an int if it is an integer inside [lo, hi], else raise."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ConfigError(f"{field} = {value!r} is not an integer")
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise ConfigError(
            f"{field} = {v} is outside the allowed range {_interval(lo, hi, False, False)}"
        )
    return v


def _holds_non_number(value: Any) -> bool:
    """Whether a (nested) list or tuple holds a boolean, a string or another non-number
    (numpy would convert a boolean mixed with numbers to 1.0)."""
    if isinstance(value, list | tuple):
        return any(_holds_non_number(v) for v in value)
    return isinstance(value, bool | np.bool_ | str | bytes)


def check_array(
    field: str,
    value: Any,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
) -> np.ndarray:
    """Return ``value`` as a float64 array if every element is finite and in range."""
    unit_s = f" {unit}" if unit else ""
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise ConfigError(f"{field} = {value!r} is not numeric") from None
    # Numbers only: booleans and strings would convert (True to 1, "30" to 30).
    if raw.dtype.kind not in "iuf" or _holds_non_number(value):
        raise ConfigError(f"{field} = {value!r} is not numeric")
    arr = raw.astype(np.float64)
    allowed = _interval(lo, hi, lo_open, hi_open)
    bad = ~np.isfinite(arr)
    if lo is not None:
        bad |= (arr <= lo) if lo_open else (arr < lo)
    if hi is not None:
        bad |= (arr >= hi) if hi_open else (arr > hi)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0]) if arr.ndim else ()
        first = float(arr[idx] if arr.ndim else arr[()])
        where = f" at index {idx}" if arr.ndim else ""
        raise ConfigError(
            f"{field} = {first:g}{unit_s}{where} is outside the allowed range {allowed}{unit_s}"
            f" ({int(bad.sum())} bad value(s))"
        )
    return arr


def check_choice(field: str, value: Any, choices: dict[str, Any] | tuple[str, ...]) -> str:
    """Return ``value`` if it names one of ``choices``, else raise listing them."""
    if value not in choices:
        raise ConfigError(f"{field} = {value!r} is not one of {sorted(choices)}")
    return str(value)


def check_frame_period(period: float, t_int: float, pulse_start: float = 0.0,
                       what: str = "the frame period") -> None:
    """Every thermal model pulses each pixel once per frame period: a period shorter than
    ``pulse_start + t_int`` (s) is refused, with one message whichever model asks."""
    need = pulse_start + t_int
    if period < need * (1.0 - 1e-12):
        start = "pulse_start + " if pulse_start else ""
        raise ConfigError(
            f"{what}: a frame period of {period:.6g} s is shorter than the bias pulse "
            f"({start}bolometer.t_int = {need:.6g} s); every thermal model (steady, lagged, "
            f"transient) needs the pulse inside the frame: at most {1.0 / need:.6g} frames/s")
