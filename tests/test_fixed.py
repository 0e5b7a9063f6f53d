"""FixedFormat, round_shift and apply_overflow against Fraction / apytypes references."""

from __future__ import annotations

from fractions import Fraction

import apytypes as apy
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from irnuc.nuc_fixed import ConfigError, FixedFormat, apply_overflow, round_shift
from irnuc.nuc_fixed.config import load_pipeline
from irnuc.nuc_fixed.fixed import gain_format, offset_format

ROUNDINGS = ["truncate", "half_up", "half_even"]


def ref_round(v: Fraction, rounding: str) -> int:
    if rounding == "truncate":
        return v.__floor__()
    if rounding == "half_up":
        return (v + Fraction(1, 2)).__floor__()
    return round(v)


@pytest.mark.parametrize(
    ("fmt", "lo", "hi", "vlo", "vhi"),
    [
        (FixedFormat(2, 14), 0, 2**16 - 1, 0.0, 4 - 2**-14),
        (FixedFormat(12, 4, signed=True), -(2**15), 2**15 - 1, -2048.0, 2048 - 2**-4),
        (FixedFormat(0, 3), 0, 7, 0.0, 7 / 8),
        (FixedFormat(1, 0, signed=True), -1, 0, -1.0, 0.0),
    ],
)
def test_ranges(fmt: FixedFormat, lo: int, hi: int, vlo: float, vhi: float) -> None:
    assert (fmt.min_code, fmt.max_code, fmt.min_value, fmt.max_value) == (lo, hi, vlo, vhi)


def test_matches_apytypes_signed_range() -> None:
    fmt = FixedFormat(5, 3, signed=True)
    a_max = apy.APyFixed((1 << 7) - 1, int_bits=5, frac_bits=3)
    a_min = apy.APyFixed(1 << 7, int_bits=5, frac_bits=3)
    assert float(a_max) == fmt.max_value and float(a_min) == fmt.min_value


@pytest.mark.parametrize("rounding", ROUNDINGS)
@pytest.mark.parametrize("signed", [False, True])
@settings(max_examples=150, deadline=None)
@given(num=st.integers(-(2**40), 2**40), den_bits=st.integers(0, 12))
def test_quantize_matches_fraction(rounding: str, signed: bool, num: int, den_bits: int) -> None:
    fmt = FixedFormat(6, 5, signed=signed)
    v = Fraction(num, 2**den_bits) / 2**20  # exactly representable in float64
    code, over = fmt.quantize(np.array([float(v)]), rounding)
    want = ref_round(v * 2**fmt.frac_bits, rounding)
    assert bool(over[0]) == (not fmt.min_code <= want <= fmt.max_code)
    assert int(code[0]) == min(max(want, fmt.min_code), fmt.max_code)


@pytest.mark.parametrize("rounding", ROUNDINGS)
def test_quantize_ties_and_wrap(rounding: str) -> None:
    fmt = FixedFormat(3, 1, signed=True)  # codes -8..7, step 0.5
    vals = np.array([0.25, 0.75, -0.25, -0.75, 1.25])
    want = [ref_round(Fraction(v) * 2, rounding) for v in vals.tolist()]
    assert fmt.to_code(vals, rounding).tolist() == want
    codes, over = fmt.quantize(np.array([4.0, -4.5]), rounding, overflow="wrap")
    assert codes.tolist() == [-8, 7] and over.tolist() == [True, True]


def test_quantize_refuses_nan_and_saturates_inf() -> None:
    fmt = FixedFormat(4, 4)
    with pytest.raises(ConfigError, match="NaN at index"):
        fmt.to_code(np.array([1.0, np.nan]))
    codes, over = fmt.quantize(np.array([np.inf, -np.inf]))
    assert codes.tolist() == [fmt.max_code, 0] and over.all()


@pytest.mark.parametrize("rounding", ROUNDINGS)
@settings(max_examples=150, deadline=None)
@given(s=st.integers(-(2**60), 2**60), shift=st.integers(0, 30))
def test_round_shift_matches_fraction(rounding: str, s: int, shift: int) -> None:
    want = ref_round(Fraction(s, 2**shift), rounding)
    assert round_shift(s, shift, rounding) == want
    assert int(round_shift(np.array([s], dtype=np.int64), shift, rounding)[0]) == want


@settings(max_examples=150, deadline=None)
@given(r=st.integers(-(2**40), 2**40), bits=st.integers(1, 20))
def test_apply_overflow(r: int, bits: int) -> None:
    top = 2**bits - 1
    assert apply_overflow(r, 0, top, "saturate") == min(max(r, 0), top)
    assert apply_overflow(r, 0, top, "wrap") == r % 2**bits
    lo = -(2 ** (bits - 1))
    wrapped = apply_overflow(r, lo, -lo - 1, "wrap")
    assert lo <= wrapped < -lo and (wrapped - r) % 2**bits == 0


@pytest.mark.parametrize(
    ("fmt", "lo", "hi", "need"),
    [
        (FixedFormat(2, 14), 0.0, 1.5, 1),
        (FixedFormat(2, 14), 0.0, 5.0, 3),
        (FixedFormat(2, 14), 0.0, 0.4, 0),
        (FixedFormat(12, 4, signed=True), -2048.0, 2047.0, 12),
        (FixedFormat(12, 4, signed=True), -2049.0, 10.0, 13),
        (FixedFormat(12, 4, signed=True), -1.0, 2048.0, 13),
    ],
)
def test_bits_needed(fmt: FixedFormat, lo: float, hi: float, need: int) -> None:
    assert fmt.bits_needed(lo, hi) == need
    # The answer holds both ends, one bit less does not.
    wide = FixedFormat(need, fmt.frac_bits, fmt.signed)
    assert not wide.quantize(np.array([lo, hi]), "half_up")[1].any()
    if need > (1 if fmt.signed else 0):
        narrow = FixedFormat(need - 1, fmt.frac_bits, fmt.signed)
        assert narrow.quantize(np.array([lo, hi]), "half_up")[1].any()


def test_config_formats_and_bad_format() -> None:
    cfg = load_pipeline("typical14")
    assert str(gain_format(cfg)) == "U2.14" and str(offset_format(cfg)) == "S12.4"
    with pytest.raises(ConfigError, match="int_bits = 0"):
        FixedFormat(0, 4, signed=True)
    with pytest.raises(ConfigError, match=r"allowed range 1\.\.64"):
        FixedFormat(40, 30)
