"""Focal-plane array: pixel layout (active, boundary and blind rings) and per-pixel spread.

The array is built from the outside in: blind (skimming) rings outermost, then boundary
rings, then the active area that the NUC hardware sees. See ``docs/fpa.md``.

Per-pixel parameters (reference resistance, thermal conductance, heat capacity, ...) are
drawn around their nominal values with a relative standard deviation ``tolerance``, from a
strictly positive distribution (lognormal by default) whose mean and standard deviation are
exactly the nominal value and ``tolerance * nominal``.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from irnuc.model.validate import ConfigError, check_choice, check_int, check_scalar

__all__ = [
    "ACTIVE",
    "BLIND",
    "BOUNDARY",
    "NOMINAL_RANGE",
    "SPREAD_DISTRIBUTIONS",
    "ArrayLayout",
    "draw_pixel_parameters",
    "parameter_stream",
]

#: Pixel kinds in :meth:`ArrayLayout.kind_map`.
ACTIVE: int = 0
BOUNDARY: int = 1
BLIND: int = 2

_SIDES = ("top", "bottom", "left", "right")


def _check_rings(field: str, value: Any) -> tuple[int, int, int, int]:
    """Return ``value`` as a 4-tuple of non-negative ints (top, bottom, left, right)."""
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        # One number means the same ring width on every side.
        value = (value,) * 4
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 4:
        raise ConfigError(
            f"{field} = {value!r} must be 4 non-negative integers (top, bottom, left, right)"
        )
    return tuple(check_int(f"{field}[{i}]", v, 0) for i, v in enumerate(value))  # type: ignore[return-value]


@dataclass(frozen=True)
class ArrayLayout:
    """Geometry of the focal-plane array.

    Parameters
    ----------
    active_rows, active_cols : int
        Size (H, W) of the active image the NUC hardware sees, pixels, each >= 1.
    boundary : tuple of 4 int
        Rings of boundary pixels per side (top, bottom, left, right), each >= 0. An int
        means the same width on every side.
    blind : tuple of 4 int
        Rings of blind (skimming) pixels per side (top, bottom, left, right), each >= 0.
        Blind rows span the full width of the array and blind columns its full height.

    Notes
    -----
    Coordinates are full-array pixel indices (row, col), origin at the top-left pixel of
    the outermost ring.
    """

    active_rows: int
    active_cols: int
    boundary: tuple[int, int, int, int] = (0, 0, 0, 0)
    blind: tuple[int, int, int, int] = (0, 0, 0, 0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "active_rows", check_int("fpa.active_rows", self.active_rows, 1))
        object.__setattr__(self, "active_cols", check_int("fpa.active_cols", self.active_cols, 1))
        object.__setattr__(self, "boundary", _check_rings("fpa.boundary", self.boundary))
        object.__setattr__(self, "blind", _check_rings("fpa.blind", self.blind))

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], path: str = "fpa") -> ArrayLayout:
        """Build a layout from a TOML table with keys ``active_rows``, ``active_cols``,
        ``boundary`` and ``blind`` (the last two optional, default 0).

        Unknown keys raise :class:`ConfigError` naming ``f"{path}.{key}"``. Other keys of
        the ``fpa`` table belong to the caller, so pass only the layout keys.
        """
        known = ("active_rows", "active_cols", "boundary", "blind")
        for key in d:
            if key not in known:
                raise ConfigError(f"{path}.{key} is not a known key; known keys: {list(known)}")
        for key in known[:2]:
            if key not in d:
                raise ConfigError(f"{path}.{key} is missing")
        return cls(
            active_rows=check_int(f"{path}.active_rows", d["active_rows"], 1),
            active_cols=check_int(f"{path}.active_cols", d["active_cols"], 1),
            boundary=_check_rings(f"{path}.boundary", d.get("boundary", 0)),
            blind=_check_rings(f"{path}.blind", d.get("blind", 0)),
        )

    # -- sizes --------------------------------------------------------------------------
    @property
    def rows(self) -> int:
        """Total number of rows of the full array (active + boundary + blind)."""
        return (
            self.active_rows + self.boundary[0] + self.boundary[1] + self.blind[0] + self.blind[1]
        )

    @property
    def cols(self) -> int:
        """Total number of columns of the full array (active + boundary + blind)."""
        return (
            self.active_cols + self.boundary[2] + self.boundary[3] + self.blind[2] + self.blind[3]
        )

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)`` of the full array."""
        return (self.rows, self.cols)

    @property
    def active_shape(self) -> tuple[int, int]:
        """``(active_rows, active_cols)``."""
        return (self.active_rows, self.active_cols)

    # -- regions ------------------------------------------------------------------------
    @property
    def active_slice(self) -> tuple[slice, slice]:
        """The active area inside the full array, as ``(row_slice, col_slice)``."""
        r0 = self.blind[0] + self.boundary[0]
        c0 = self.blind[2] + self.boundary[2]
        return (slice(r0, r0 + self.active_rows), slice(c0, c0 + self.active_cols))

    def kind_map(self) -> np.ndarray:
        """Pixel kind of every pixel of the full array.

        Returns
        -------
        numpy.ndarray
            ``(rows, cols)`` uint8: :data:`ACTIVE` (0), :data:`BOUNDARY` (1), :data:`BLIND` (2).
        """
        bt, bb, bl, br = self.blind
        km = np.full((self.rows, self.cols), BLIND, dtype=np.uint8)
        km[bt : self.rows - bb, bl : self.cols - br] = BOUNDARY
        km[self.active_slice] = ACTIVE
        return km

    @property
    def optical_centre(self) -> tuple[float, float]:
        """Centre of the active area, ``(row, col)`` in full-array pixel-index coordinates.

        For an even size the centre falls half-way between two pixels.
        """
        rs, cs = self.active_slice
        return (rs.start + (self.active_rows - 1) / 2.0, cs.start + (self.active_cols - 1) / 2.0)

    @property
    def blind_row_indices(self) -> np.ndarray:
        """Full-array indices (int64, ascending) of the rows that are entirely blind."""
        return np.r_[0 : self.blind[0], self.rows - self.blind[1] : self.rows].astype(np.int64)

    @property
    def blind_col_indices(self) -> np.ndarray:
        """Full-array indices (int64, ascending) of the columns that are entirely blind."""
        return np.r_[0 : self.blind[2], self.cols - self.blind[3] : self.cols].astype(np.int64)


# ---------------------------------------------------------------------------------------
# Per-pixel spread
# ---------------------------------------------------------------------------------------

#: Allowed magnitude of a nominal value: wide enough for every physical parameter in SI
#: units, narrow enough that a draw can neither overflow nor underflow to 0.
NOMINAL_RANGE: tuple[float, float] = (1e-100, 1e100)

#: A kernel draws ``shape`` values with mean ``nominal`` and relative std ``tol`` (0 < tol <= 1).
SpreadKernel = Callable[[np.random.Generator, float, float, tuple[int, ...]], np.ndarray]

_MAX_REDRAWS = 1000


def _redraw_nonpositive(x: np.ndarray, redraw: Callable[[int], np.ndarray]) -> np.ndarray:
    """Replace the values <= 0 of ``x`` by fresh draws until none is left (truncation at 0)."""
    for _ in range(_MAX_REDRAWS):
        bad = np.flatnonzero(~(x > 0.0))
        if bad.size == 0:
            return x
        x.flat[bad] = redraw(bad.size)
    raise RuntimeError("per-pixel spread: could not draw positive values")  # pragma: no cover


def _lognormal(
    rng: np.random.Generator, nominal: float, tol: float, shape: tuple[int, ...]
) -> np.ndarray:
    # Mean exactly nominal, std exactly tol*nominal: sigma_ln^2 = ln(1 + tol^2),
    # mu = ln(nominal) - sigma_ln^2 / 2. exp() of a finite draw is > 0 for the allowed
    # nominal range, so no redraw is ever needed.
    s2 = np.log1p(tol * tol)
    s = np.sqrt(s2)
    x = rng.standard_normal(shape)
    x *= s
    x += np.log(nominal) - 0.5 * s2
    np.exp(x, out=x)
    return x


def _gamma(
    rng: np.random.Generator, nominal: float, tol: float, shape: tuple[int, ...]
) -> np.ndarray:
    # Shape k = 1/tol^2, scale theta = nominal*tol^2: mean k*theta = nominal,
    # std sqrt(k)*theta = tol*nominal. k >= 1 for tol <= 1; an exact 0 (probability
    # ~1e-16 at k = 1) is redrawn.
    k = 1.0 / (tol * tol)
    theta = nominal * tol * tol
    x = rng.standard_gamma(k, shape)
    x *= theta
    return _redraw_nonpositive(x, lambda n: rng.standard_gamma(k, n) * theta)


def _normal_truncated(
    rng: np.random.Generator, nominal: float, tol: float, shape: tuple[int, ...]
) -> np.ndarray:
    # The paper's normal N(nominal, (tol*nominal)^2) with its non-positive tail removed
    # (redrawn). The moments match the paper's only while Phi(-1/tol) is negligible.
    sd = tol * nominal
    x = rng.normal(nominal, sd, shape)
    return _redraw_nonpositive(x, lambda n: rng.normal(nominal, sd, n))


#: Spread distributions by name. Every kernel returns strictly positive, finite values
#: for every tolerance in (0, 1].
SPREAD_DISTRIBUTIONS: dict[str, SpreadKernel] = {
    "lognormal": _lognormal,
    "gamma": _gamma,
    "normal_truncated": _normal_truncated,
}


def _name_key(name: str) -> int:
    """Stable 64-bit hash of a name (the same in every process, unlike ``hash``)."""
    return int.from_bytes(hashlib.blake2b(name.encode("utf-8"), digest_size=8).digest(), "little")


def parameter_stream(seed: int, name: str) -> np.random.Generator:
    """The random stream of one named quantity, independent of every other name.

    Parameters
    ----------
    seed : int
        Non-negative master seed.
    name : str
        Name of the stream, e.g. ``"fpa.spread.R_ref"``.
    """
    ss = np.random.SeedSequence(seed, spawn_key=(_name_key(name),))
    return np.random.Generator(np.random.PCG64(ss))


def draw_pixel_parameters(
    layout: ArrayLayout,
    nominal: Mapping[str, float],
    tolerance: Mapping[str, float],
    seed: int,
    distribution: str = "lognormal",
    *,
    path: str = "fpa",
) -> dict[str, np.ndarray]:
    """Draw the per-pixel value of every parameter over the full array.

    Parameters
    ----------
    layout : ArrayLayout
        Array geometry; values are drawn for every pixel (active, boundary and blind).
    nominal : mapping of str to float
        Nominal value of each parameter, in its own unit (e.g. ``R_ref`` ohm, ``g`` W/K,
        ``C`` J/K), in :data:`NOMINAL_RANGE`.
    tolerance : mapping of str to float
        Relative standard deviation of each parameter, in [0, 1]: the draws have standard
        deviation ``tolerance * nominal``. A parameter missing here gets 0 (exactly
        nominal); a key that is not in ``nominal`` is an error.
    seed : int
        Non-negative master seed. Each parameter draws from its own stream derived from
        the seed and the parameter name, so adding or changing one parameter never
        changes another.
    distribution : str
        A key of :data:`SPREAD_DISTRIBUTIONS`; ``"lognormal"`` by default.
    path : str
        Config path used in error messages (``f"{path}.tolerance.R_ref"``, ...).

    Returns
    -------
    dict of str to numpy.ndarray
        ``(layout.rows, layout.cols)`` float64 arrays, every value finite and > 0.

    Raises
    ------
    ConfigError
        On any bad argument, before any draw.
    """
    if not isinstance(layout, ArrayLayout):
        raise ConfigError(f"layout = {layout!r} is not an ArrayLayout")
    seed = check_int("seed", seed, 0)
    distribution = check_choice(f"{path}.distribution", distribution, SPREAD_DISTRIBUTIONS)
    if not isinstance(nominal, Mapping):
        raise ConfigError(f"{path}.nominal = {nominal!r} is not a table of name -> value")
    if not isinstance(tolerance, Mapping):
        raise ConfigError(f"{path}.tolerance = {tolerance!r} is not a table of name -> value")
    lo, hi = NOMINAL_RANGE
    noms: dict[str, float] = {}
    for key, val in nominal.items():
        if not isinstance(key, str) or not key:
            raise ConfigError(f"{path}.nominal key {key!r} is not a non-empty string")
        noms[key] = check_scalar(f"{path}.nominal.{key}", val, lo, hi)
    tols: dict[str, float] = {}
    for key, val in tolerance.items():
        if key not in noms:
            raise ConfigError(
                f"{path}.tolerance.{key} has no nominal value; known parameters: {sorted(noms)}"
            )
        tols[key] = check_scalar(f"{path}.tolerance.{key}", val, 0.0, 1.0)

    kernel = SPREAD_DISTRIBUTIONS[distribution]
    shape = layout.shape
    out: dict[str, np.ndarray] = {}
    for key, nom in noms.items():
        tol = tols.get(key, 0.0)
        if tol == 0.0:
            out[key] = np.full(shape, nom, dtype=np.float64)
            continue
        rng = parameter_stream(seed, f"fpa.spread.{key}")
        out[key] = np.ascontiguousarray(kernel(rng, nom, tol, shape), dtype=np.float64)
    return out
