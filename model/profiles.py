"""Temperature profiles of a drift sequence: a value (K) as a function of time (s).

A profile is a TOML table with ``profile = NAME`` and that profile's keys; every key is
checked, with its dotted name, before any work (:func:`parse_profile`):

* ``constant``: ``value`` (K);
* ``ramp``: ``start`` (K) and ``rate`` (K/min), optionally ``delay`` (s: held at ``start``
  until then) and ``stop`` (K: held once reached);
* ``step``: ``before`` (K), ``after`` (K) and ``at`` (s);
* ``sine``: ``mean`` (K), ``amplitude`` (K) and ``period`` (s), optionally ``phase`` (deg);
* ``table``: ``file``, a CSV of ``time,value`` rows (s, K; an optional header line and ``#``
  comments), times strictly increasing, linear between rows, held beyond both ends;
* ``lag`` (the FPA or the housing): a first-order lag behind another temperature of the
  sequence (``follows``: the FPA follows the housing by default, or the ambient; the
  housing follows the ambient by default, or the FPA), dT/dt = (T_followed + ``offset`` -
  T) / ``time_constant`` (s), from ``start`` (K, default the followed one's first value).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.common.errors import UserError
from irnuc.common.schema import nearest
from irnuc.model.validate import ConfigError, check_scalar

#: Keys of each profile: (required, optional).
PROFILE_KEYS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "constant": (("value",), ()),
    "ramp": (("start", "rate"), ("delay", "stop")),
    "step": (("before", "after", "at"), ()),
    "sine": (("mean", "amplitude", "period"), ("phase",)),
    "table": (("file",), ()),
    "lag": (("time_constant",), ("start", "offset", "follows")),
}

_T_RANGE = (0.0, 1e5)  # any temperature a profile may state, K (ranges are checked later)
_TIME_RANGE = (0.0, 1e9)  # s


@dataclass(frozen=True)
class Profile:
    """One checked profile (see the module docstring).

    Attributes
    ----------
    kind : str
        Key of :data:`PROFILE_KEYS`.
    params : dict
        Its keys as floats (``table``: ``times`` and ``values`` arrays, ``file`` path).
    path : str
        Dotted name of its table, for messages (``sequence.fpa``).
    """

    kind: str
    params: Mapping[str, Any]
    path: str

    def values(self, t: np.ndarray, follow: np.ndarray | None = None) -> np.ndarray:
        """The profile at times ``t`` (s, increasing), K.

        ``follow`` (K at the same times) is the temperature a ``lag`` profile follows.
        """
        p = self.params
        t = np.asarray(t, dtype=np.float64)
        if self.kind == "constant":
            return np.full(t.shape, p["value"])
        if self.kind == "ramp":
            tr = np.maximum(t - p.get("delay", 0.0), 0.0)
            out = p["start"] + p["rate"] / 60.0 * tr
            if "stop" in p:
                out = (np.minimum(out, p["stop"]) if p["rate"] >= 0
                       else np.maximum(out, p["stop"]))
            return out
        if self.kind == "step":
            return np.where(t < p["at"], p["before"], p["after"]).astype(np.float64)
        if self.kind == "sine":
            phase = math.radians(p.get("phase", 0.0))
            return p["mean"] + p["amplitude"] * np.sin(2.0 * math.pi * t / p["period"] + phase)
        if self.kind == "table":
            return np.interp(t, p["times"], p["values"])
        assert self.kind == "lag"
        if follow is None:
            raise ConfigError(f"{self.path}: profile 'lag' needs the temperature it follows")
        return first_order_lag(t, np.asarray(follow, dtype=np.float64) + p.get("offset", 0.0),
                               p["time_constant"], p.get("start"))

    def describe(self) -> str:
        """One line: the profile and its parameters."""
        keys = ", ".join(f"{k} = {v:g}" for k, v in self.params.items()
                         if isinstance(v, float))
        extra = f", file = {self.params['file']}" if self.kind == "table" else ""
        return f"{self.kind} ({keys}{extra})"


def first_order_lag(t: np.ndarray, u: np.ndarray, tau: float, start: float | None) -> np.ndarray:
    """y with tau dy/dt = u - y, y(t_0) = start (default u(t_0)), u linear between samples.

    Exact for an input that is linear between the sample times (first-order hold): over a
    step h with u going from u0 to u1 and d = exp(-h/tau),
    y1 = u1 + (y0 - u0) d - (u1 - u0) (tau/h) (1 - d).
    """
    y = np.empty(t.shape)
    if t.size == 0:
        return y
    y[0] = u[0] if start is None else start
    for k in range(1, t.size):
        h = t[k] - t[k - 1]
        d = math.exp(-h / tau)
        slope_term = (u[k] - u[k - 1]) * (tau / h) * (-math.expm1(-h / tau)) if h > 0 else 0.0
        y[k] = u[k] + (y[k - 1] - u[k - 1]) * d - slope_term
    return y


def _number(path: str, key: str, value: Any, lo: float | None, hi: float | None,
            unit: str, lo_open: bool = False) -> float:
    if isinstance(value, bool):
        raise ConfigError(f"{path}.{key} = {value!r} is not a number")
    return check_scalar(f"{path}.{key}", value, lo, hi, lo_open=lo_open, unit=unit)


def parse_profile(table: Any, path: str, base_dir: Path | None = None,
                  allow_lag: bool = False) -> Profile:
    """A :class:`Profile` from a TOML table; :class:`ConfigError` naming the key otherwise.

    Parameters
    ----------
    table : dict
        ``{"profile": NAME, ...}``; a bare number is a ``constant``.
    path : str
        Dotted name of the table (``sequence.fpa``).
    base_dir : Path, optional
        Folder a ``table`` profile's relative ``file`` is read from (the TOML's).
    allow_lag : bool
        Whether ``lag`` is allowed here (the FPA and the housing).
    """
    if isinstance(table, (int, float)) and not isinstance(table, bool):
        table = {"profile": "constant", "value": table}
    if not isinstance(table, Mapping):
        raise ConfigError(f"{path} = {table!r} must be a table with a profile (or a number)")
    kinds = [k for k in PROFILE_KEYS if allow_lag or k != "lag"]
    kind = table.get("profile")
    if kind is None:
        raise ConfigError(f"{path}.profile is required (one of {', '.join(kinds)})")
    if kind not in kinds:
        raise ConfigError(f"{path}.profile = {kind!r} is not one of {', '.join(kinds)}"
                          f"{nearest(str(kind), kinds)}")
    required, optional = PROFILE_KEYS[kind]
    known = ("profile", *required, *optional)
    for key in table:
        if key not in known:
            raise ConfigError(f"{path}.{key} is not a known field of profile {kind!r}"
                              f"{nearest(str(key), known)} (known here: {', '.join(known)})")
    for key in required:
        if key not in table:
            raise ConfigError(f"{path}.{key} is required by profile {kind!r}")
    if kind == "table":
        return _table_profile(table["file"], path, base_dir)
    units = {"rate": ("K/min", -1e6, 1e6), "delay": ("s", *_TIME_RANGE), "at": ("s", *_TIME_RANGE),
             "amplitude": ("K", 0.0, 1e4), "phase": ("deg", -360.0, 360.0),
             "offset": ("K", -100.0, 100.0)}
    params: dict[str, Any] = {}
    for key in (*required, *optional):
        if key not in table:
            continue
        if key == "follows":
            v = table[key]
            if v not in ("housing", "ambient", "fpa"):
                raise ConfigError(f"{path}.follows = {v!r} is not one of housing, ambient, fpa")
            params[key] = v
        elif key in ("period", "time_constant"):
            params[key] = _number(path, key, table[key], 0.0, _TIME_RANGE[1], "s", lo_open=True)
        elif key in units:
            unit, lo, hi = units[key]
            params[key] = _number(path, key, table[key], lo, hi, unit)
        else:  # a temperature
            params[key] = _number(path, key, table[key], *_T_RANGE, "K", lo_open=True)
    return Profile(kind, params, path)


def _table_profile(file: Any, path: str, base_dir: Path | None) -> Profile:
    """A ``table`` profile from its CSV file (time s, value K), checked row by row."""
    if not isinstance(file, str) or not file:
        raise ConfigError(f"{path}.file = {file!r} must be a file name (a CSV of time,value)")
    p = Path(file)
    if not p.is_absolute() and base_dir is not None:
        p = base_dir / p
    where = f"{path}.file = {file!r}"
    if not p.is_file():
        raise ConfigError(f"{where}: no such file ({p})")
    from irnuc.common.io import OutputError, read_bytes_capped

    try:  # capped, and refused inside the output folder being replaced
        text = read_bytes_capped(p, f"{path}.file").decode()
    except OutputError:
        raise
    except (UserError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{where}: {str(exc).removeprefix(f'{path}.file {p}: ')}") from None
    times: list[float] = []
    values: list[float] = []
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        cells = [c.strip() for c in line.split(",")]
        try:
            t, v = (float(c) for c in cells)
        except ValueError:
            if not times and not values:  # a header line
                continue
            raise ConfigError(f"{where}: line {number} ({raw.strip()!r}) is not two numbers "
                              "time,value") from None
        if not (math.isfinite(t) and math.isfinite(v)):
            raise ConfigError(f"{where}: line {number} holds a non-finite number")
        if times and not t > times[-1]:
            raise ConfigError(f"{where}: time is not increasing at line {number} ({t:g} s "
                              f"after {times[-1]:g} s); the table must be monotonic in time")
        if not v > 0:
            raise ConfigError(f"{where}: line {number}: value {v:g} K is not above 0 K")
        times.append(t)
        values.append(v)
    if len(times) < 2:
        raise ConfigError(f"{where}: needs at least two rows time,value (s, K); it has "
                          f"{len(times)}")
    return Profile("table", {"file": str(p), "times": np.array(times),
                             "values": np.array(values)}, path)


def check_range(path: str, profile: Profile, values: np.ndarray, times: np.ndarray,
                lo: float, hi: float, what: str) -> None:
    """ConfigError naming the profile if ``values`` (K, at ``times`` s) leave [lo, hi]."""
    bad = np.flatnonzero(~((values >= lo) & (values <= hi)))
    if bad.size:
        k = int(bad[0])
        raise ConfigError(
            f"{path}: the {profile.kind} profile reaches {values[k]:.6g} K at t = "
            f"{times[k]:.6g} s, outside the model's range [{lo:g}, {hi:g}] K ({what})")
