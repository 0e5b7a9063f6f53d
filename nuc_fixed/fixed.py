"""A small fixed-point format type and exact integer rounding / overflow helpers.

Conventions follow ``docs/datapath.md`` (and apytypes): a format has ``int_bits`` integer
bits and ``frac_bits`` fraction bits; for a signed format ``int_bits`` *includes* the sign
bit (two's complement). A code is the integer ``value * 2**frac_bits``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.nuc_fixed import _kernels
from irnuc.nuc_fixed.config import OVERFLOW_MODES, ROUNDING_MODES, ConfigError, PipelineConfig


def _check_mode(field: str, value: str, modes: dict[str, int]) -> str:
    if value not in modes:
        raise ConfigError(f"{field} = {value!r} is not one of {sorted(modes)}")
    return value


def round_shift(s: np.ndarray | int, shift: int, rounding: str) -> np.ndarray | int:
    """Exact integer ``ROUND(s / 2**shift)`` as written in ``docs/datapath.md``.

    This is the datapath's own kernel (:func:`irnuc.nuc_fixed._kernels.round_code`), so
    the exact-arithmetic tests of this function check the code that runs.

    Parameters
    ----------
    s : int or integer ndarray
        Value with ``shift`` fraction bits, in the int64 range with one bit of headroom.
    shift : int
        Number of fraction bits to remove, 0..62. ``shift = 0`` is the identity.
    rounding : {"truncate", "half_up", "half_even"}
        Floor, ties toward +inf, or ties to even.
    """
    mode = ROUNDING_MODES[_check_mode("rounding", rounding, ROUNDING_MODES)]
    if isinstance(shift, bool) or not isinstance(shift, int) or not 0 <= shift <= 62:
        raise ConfigError(f"shift = {shift!r} is outside the allowed range 0..62 (integer)")
    if isinstance(s, np.ndarray):
        arr = np.ascontiguousarray(s, dtype=np.int64)
        out = np.empty_like(arr)
        _kernels.round_codes(arr, shift, mode, out)
        return out
    if not -(2**62) <= int(s) < 2**62:
        raise ConfigError(f"s = {s!r} is outside the allowed range -2^62..2^62-1")
    return int(_kernels.round_code(np.int64(s), shift, mode))


def round_div(a: int, b: int, rounding: str) -> int:
    """Exact ``ROUND(a / b)`` of integers (b > 0): floor, ties up or ties to even.

    The per-frame divisions of the datapath (interpolation weight, FFC mean target) are
    written with this: an RTL divider with its remainder gives the same three modes.
    """
    mode = _check_mode("rounding", rounding, ROUNDING_MODES)
    a, b = int(a), int(b)
    if b <= 0:
        raise ConfigError(f"divisor = {b} must be positive")
    q, r = divmod(a, b)  # floor division, 0 <= r < b
    if mode == "truncate":
        return q
    if 2 * r > b or (2 * r == b and (mode == "half_up" or q & 1)):
        return q + 1
    return q


def apply_overflow(r: np.ndarray | int, lo: int, hi: int, overflow: str) -> np.ndarray | int:
    """Bring ``r`` into the code range [lo, hi] by saturation or two's-complement wrap.

    ``hi - lo + 1`` must be a power of two for ``wrap`` (a whole number of bits).
    """
    _check_mode("overflow", overflow, OVERFLOW_MODES)
    if overflow == "saturate":
        if isinstance(r, np.ndarray):
            return np.clip(r, lo, hi)
        return min(max(r, lo), hi)
    span = hi - lo + 1
    return ((r - lo) & (span - 1)) + lo


@dataclass(frozen=True)
class FixedFormat:
    """A binary fixed-point format.

    Parameters
    ----------
    int_bits : int
        Integer bits; for ``signed`` formats this count includes the sign bit.
    frac_bits : int
        Fraction bits (>= 0).
    signed : bool
        Two's complement if true, else unsigned.
    """

    int_bits: int
    frac_bits: int
    signed: bool = False

    def __post_init__(self) -> None:
        for field in ("int_bits", "frac_bits"):
            v = getattr(self, field)
            if not isinstance(v, int) or isinstance(v, bool) or not 0 <= v <= 64:
                raise ConfigError(f"{field} = {v!r} is outside the allowed range 0..64 (integer)")
        if not 1 <= self.bits <= 64:
            raise ConfigError(
                f"int_bits + frac_bits = {self.bits} is outside the allowed range 1..64"
            )
        if self.signed and self.int_bits < 1:
            raise ConfigError("int_bits = 0 is outside the allowed range 1..64 for a signed format")

    @property
    def bits(self) -> int:
        """Total code width in bits."""
        return self.int_bits + self.frac_bits

    @property
    def min_code(self) -> int:
        return -(1 << (self.bits - 1)) if self.signed else 0

    @property
    def max_code(self) -> int:
        return (1 << (self.bits - 1)) - 1 if self.signed else (1 << self.bits) - 1

    @property
    def lsb(self) -> float:
        """Value of one code step, 2**-frac_bits."""
        return 2.0**-self.frac_bits

    @property
    def min_value(self) -> float:
        return self.min_code * self.lsb

    @property
    def max_value(self) -> float:
        return self.max_code * self.lsb

    def __str__(self) -> str:
        return f"{'S' if self.signed else 'U'}{self.int_bits}.{self.frac_bits}"

    def to_value(self, codes: np.ndarray | int) -> np.ndarray | float:
        """Real value of codes (float64; exact while ``bits <= 53``)."""
        if np.ndim(codes):
            return np.asarray(codes, dtype=np.float64) * self.lsb
        return float(codes) * self.lsb

    def quantize(
        self,
        values: np.ndarray | float,
        rounding: str = "half_even",
        overflow: str = "saturate",
    ) -> tuple[np.ndarray, np.ndarray]:
        """Codes for real values, and a mask of the values that overflowed the format.

        Rounding is exact: ``v * 2**frac_bits`` is exact in float64 and the tie test
        compares the exact remainder. NaN is refused; +-inf overflows.

        Returns
        -------
        codes : int64 ndarray
        overflowed : bool ndarray
            True where the rounded code lay outside [min_code, max_code].
        """
        _check_mode("rounding", rounding, ROUNDING_MODES)
        _check_mode("overflow", overflow, OVERFLOW_MODES)
        v = np.asarray(values, dtype=np.float64)
        if np.isnan(v).any():
            idx = tuple(int(i) for i in np.argwhere(np.isnan(v))[0]) if v.ndim else ()
            raise ConfigError(f"values contain NaN at index {idx}; a finite number is required")
        scaled = np.ldexp(v, self.frac_bits)
        # Keep the rounding arithmetic inside the int64 range; anything beyond overflows anyway.
        limit = float(2**62)
        clipped = np.clip(scaled, -limit, limit)
        fl = np.floor(clipped)
        rem = clipped - fl  # exact for |x| < 2**52, and 0 beyond
        if rounding == "truncate":
            up = np.zeros(fl.shape, dtype=bool)
        elif rounding == "half_up":
            up = rem >= 0.5
        else:
            odd = np.mod(fl, 2.0) == 1.0
            up = (rem > 0.5) | ((rem == 0.5) & odd)
        r = fl.astype(np.int64) + up
        over = (r < self.min_code) | (r > self.max_code)
        codes = apply_overflow(r, self.min_code, self.max_code, overflow)
        return np.asarray(codes, dtype=np.int64), np.asarray(over)

    def to_code(
        self, values: np.ndarray | float, rounding: str = "half_even", overflow: str = "saturate"
    ) -> np.ndarray:
        """Codes for real values (see :meth:`quantize`)."""
        return self.quantize(values, rounding, overflow)[0]

    def contains(self, codes: np.ndarray | int) -> np.ndarray | bool:
        """True where a code lies in [min_code, max_code]."""
        c = np.asarray(codes)
        return (c >= self.min_code) & (c <= self.max_code)

    def bits_needed(self, lo: float, hi: float) -> int:
        """Integer bits (sign included if signed) needed to hold [lo, hi] at this frac_bits.

        The values are first rounded to nearest at this format's resolution.
        """
        clo = int(np.floor(np.ldexp(lo, self.frac_bits) + 0.5))
        chi = int(np.floor(np.ldexp(hi, self.frac_bits) + 0.5))
        if self.signed:
            need = max(chi.bit_length(), (-clo - 1).bit_length() if clo < 0 else 0) + 1
        else:
            if clo < 0:
                raise ConfigError(f"lo = {lo!r} is negative; an unsigned format cannot hold it")
            need = chi.bit_length()
        return max(need - self.frac_bits, 1 if self.signed else 0)


def gain_format(cfg: PipelineConfig) -> FixedFormat:
    """The unsigned gain format U(Gi).(Gf) of a pipeline configuration."""
    return FixedFormat(cfg.gain_int_bits, cfg.gain_frac_bits, signed=False)


def offset_format(cfg: PipelineConfig) -> FixedFormat:
    """The signed offset format S(Oi).(Of) of a pipeline configuration."""
    return FixedFormat(cfg.offset_int_bits, cfg.offset_frac_bits, signed=True)
