"""nuc_core against two references that share no code with it: exact rational arithmetic
on Python integers (fractions.Fraction) and apytypes."""

from __future__ import annotations

import itertools
from fractions import Fraction

import apytypes as apy
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from irnuc.nuc_fixed import InputError, load_pipeline, nuc_core, pipeline_names

CONFIGS = pipeline_names()
MODES = list(itertools.product(["truncate", "half_up", "half_even"], ["saturate", "wrap"]))


def ref_fraction(x: int, g: int, o: int, cfg) -> int:
    """y from the real-valued formula: round(x*g/2^Gf + o/2^Of), then saturate or wrap."""
    v = Fraction(x * g, 2**cfg.gain_frac_bits) + Fraction(o, 2**cfg.offset_frac_bits)
    if cfg.rounding == "truncate":
        r = v.__floor__()
    elif cfg.rounding == "half_up":
        r = (v + Fraction(1, 2)).__floor__()
    else:
        r = round(v)  # Fraction.__round__ rounds ties to even
    top = 2**cfg.out_bits - 1
    if cfg.overflow == "saturate":
        return min(max(r, 0), top)
    return r % (top + 1)


_APY_Q = {"truncate": apy.QuantizationMode.TO_NEG, "half_up": apy.QuantizationMode.TIES_POS,
          "half_even": apy.QuantizationMode.TIES_EVEN}


def ref_apytypes(x: int, g: int, o: int, cfg) -> int:
    """y with apytypes' exact fixed-point arithmetic and its own quantization/overflow."""
    xa = apy.APyFixed(x, int_bits=cfg.adc_bits + 1, frac_bits=0)
    ga = apy.APyFixed(g, int_bits=cfg.gain_int_bits + 1, frac_bits=cfg.gain_frac_bits)
    ow = cfg.offset_bits
    oa = apy.APyFixed(o & ((1 << ow) - 1), int_bits=cfg.offset_int_bits,
                      frac_bits=cfg.offset_frac_bits)
    s = xa * ga + oa
    b = cfg.out_bits
    if cfg.overflow == "wrap":
        r = s.cast(int_bits=b, frac_bits=0, quantization=_APY_Q[cfg.rounding],
                   overflow=apy.OverflowMode.WRAP)
        return int(r.to_bits())  # the B-bit pattern = r mod 2^B
    r = s.cast(int_bits=b + 1, frac_bits=0, quantization=_APY_Q[cfg.rounding],
               overflow=apy.OverflowMode.SAT)
    return max(int(r.to_fraction()), 0)


def _edge_ints(lo: int, hi: int) -> st.SearchStrategy[int]:
    edges = sorted({lo, hi, min(lo + 1, hi), max(hi - 1, lo), min(max(0, lo), hi)})
    return st.one_of(st.sampled_from(edges), st.integers(lo, hi))


@st.composite
def operands(draw, cfg):
    """(x, g, o) with extremes likely and, half of the time, s an exact rounding tie."""
    x = draw(_edge_ints(0, 2**cfg.adc_bits - 1))
    g = draw(_edge_ints(0, 2**cfg.gain_bits - 1))
    ow = cfg.offset_bits
    o = draw(_edge_ints(-(2 ** (ow - 1)), 2 ** (ow - 1) - 1))
    f = cfg.frac_bits
    if f > 0 and draw(st.booleans()):
        mask = (1 << f) - 1
        half = 1 << (f - 1)
        if cfg.offset_frac_bits == f:
            # Choose the low F bits of o so that the fraction of s is exactly one half.
            need = (half - (x * g << (f - cfg.gain_frac_bits))) & mask
            o = (o & ~mask) | need
        else:
            x = 1
            need = (half - (o << (f - cfg.offset_frac_bits))) & mask
            g = (g & ~mask) | need
    return x, g, o


@pytest.mark.parametrize("name", CONFIGS)
@pytest.mark.parametrize(("rounding", "overflow"), MODES)
def test_nuc_core_matches_fraction_reference(name: str, rounding: str, overflow: str) -> None:
    cfg = load_pipeline(name).replace(rounding=rounding, overflow=overflow)

    @settings(max_examples=120, deadline=None)
    @given(st.lists(operands(cfg), min_size=1, max_size=16))
    def check(triples: list[tuple[int, int, int]]) -> None:
        x, g, o = (np.array(v, dtype=np.int64) for v in zip(*triples, strict=True))
        y = nuc_core(x, g, o, cfg)
        want = [ref_fraction(*t, cfg) for t in triples]
        assert y.tolist() == want, (triples, y.tolist(), want)

    check()


@pytest.mark.parametrize("name", CONFIGS)
@pytest.mark.parametrize(("rounding", "overflow"), MODES)
def test_nuc_core_matches_apytypes(name: str, rounding: str, overflow: str) -> None:
    cfg = load_pipeline(name).replace(rounding=rounding, overflow=overflow)

    @settings(max_examples=60, deadline=None)
    @given(operands(cfg))
    def check(t: tuple[int, int, int]) -> None:
        y = nuc_core(np.array([t[0]]), np.array([t[1]]), np.array([t[2]]), cfg)
        assert int(y[0]) == ref_apytypes(*t, cfg), t

    check()


@pytest.mark.parametrize(("rounding", "overflow"), MODES)
def test_minimal_exhaustive(rounding: str, overflow: str) -> None:
    """Every (x, g, o) of the minimal configuration, against the Fraction reference."""
    cfg = load_pipeline("minimal").replace(rounding=rounding, overflow=overflow)
    ow = cfg.offset_bits
    xs = np.arange(2**cfg.adc_bits)
    gs = np.arange(2**cfg.gain_bits)
    os_ = np.arange(-(2 ** (ow - 1)), 2 ** (ow - 1))
    # The output depends on x*g and o only: reference each distinct (x*g, o) pair once.
    prods = np.unique(np.multiply.outer(xs, gs))
    table = {}
    for p in prods.tolist():
        for o in os_.tolist():
            table[p, o] = ref_fraction(p, 1, o, cfg)  # x and g enter only as the product x*g
    x, g, o = np.meshgrid(xs, gs, os_, indexing="ij")
    y = nuc_core(x, g, o, cfg)
    want = np.vectorize(lambda p, oo: table[p, oo])(x * g, o)
    bad = np.argwhere(y != want)
    assert bad.size == 0, f"{len(bad)} mismatches, first at (x, g, o index) {bad[0]}"


@pytest.mark.parametrize("name", CONFIGS)
def test_extremes_and_saturation_bounds(name: str) -> None:
    cfg = load_pipeline(name)
    top = 2**cfg.out_bits - 1
    gmax = 2**cfg.gain_bits - 1
    omin, omax = -(2 ** (cfg.offset_bits - 1)), 2 ** (cfg.offset_bits - 1) - 1
    xmax = 2**cfg.adc_bits - 1
    cases = [(xmax, gmax, omax), (xmax, gmax, omin), (0, 0, omin), (0, gmax, omin),
             (0, 0, omax), (xmax, 0, 0), (1, 1, 0)]
    x, g, o = (np.array(v) for v in zip(*cases, strict=True))
    r = nuc_core(x, g, o, cfg, intermediates=True)
    assert r.y.tolist() == [ref_fraction(*c, cfg) for c in cases]
    assert r.y.min() >= 0 and r.y.max() <= top
    # The intermediates are the exact integers of docs/datapath.md.
    f = cfg.frac_bits
    for (xi, gi, oi), p, s in zip(cases, r.p.tolist(), r.s.tolist(), strict=True):
        assert p == xi * gi
        assert s == (xi * gi << (f - cfg.gain_frac_bits)) + (oi << (f - cfg.offset_frac_bits))
        assert -(2 ** (cfg.sum_bits - 1)) <= s < 2 ** (cfg.sum_bits - 1)


@pytest.mark.parametrize("name", CONFIGS)
def test_every_saturation_bound(name: str) -> None:
    """Values of r just below, at and just above both output bounds (offset-only sums)."""
    cfg = load_pipeline(name)
    top = 2**cfg.out_bits - 1
    of = cfg.offset_frac_bits
    omin, omax = -(2 ** (cfg.offset_bits - 1)), 2 ** (cfg.offset_bits - 1) - 1
    targets = [-1, 0, 1, top - 1, top, top + 1]
    o = np.clip(np.array([t << of for t in targets]), omin, omax)
    y = nuc_core(np.zeros_like(o), np.zeros_like(o), o, cfg)
    assert y.tolist() == [ref_fraction(0, 0, int(v), cfg) for v in o]


def test_output_dtype_and_stack_broadcast() -> None:
    cfg = load_pipeline("typical14")
    rng = np.random.default_rng(5)
    g = rng.integers(0, 2**cfg.gain_bits, (4, 6))
    o = rng.integers(-(2 ** (cfg.offset_bits - 1)), 2 ** (cfg.offset_bits - 1), (4, 6))
    x = rng.integers(0, 2**cfg.adc_bits, (3, 4, 6)).astype(np.uint16)
    y = nuc_core(x, g, o, cfg)
    assert y.dtype == np.uint16 and y.shape == (3, 4, 6)
    for k in range(3):
        assert np.array_equal(y[k], nuc_core(x[k], g, o, cfg))
    wide = cfg.replace(out_bits=20)
    assert nuc_core(x, g, o, wide).dtype == np.uint32


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"x": np.array([16384])}, r"x\[0\] = 16384 .*\[0, 16383\]"),
        ({"x": np.array([-1])}, r"x\[0\] = -1"),
        ({"gain": np.array([65536])}, r"gain\[0\] = 65536 .*\[0, 65535\]"),
        ({"offset": np.array([-32769])}, r"offset\[0\] = -32769 .*\[-32768, 32767\]"),
        ({"x": np.array([1.0])}, r"x has dtype float64"),
        ({"x": np.array([np.nan])}, r"x contains NaN at index \(0,\)"),
        ({"gain": np.array([1, 2])}, r"gain has shape \(2,\) but offset has shape \(1,\)"),
        ({"x": np.array([1, 2])}, r"x has shape \(2,\)"),
    ],
)
def test_bad_inputs_are_named(kwargs: dict, match: str) -> None:
    args = {"x": np.array([1]), "gain": np.array([1]), "offset": np.array([0])} | kwargs
    with pytest.raises(InputError, match=match):
        nuc_core(args["x"], args["gain"], args["offset"], "typical14")
