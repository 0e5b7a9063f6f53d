"""Tests of model.fpa: array layout and per-pixel parameter spread."""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import optimize, stats

from irnuc.model import fpa
from irnuc.model.fpa import (
    ACTIVE,
    BLIND,
    BOUNDARY,
    SPREAD_DISTRIBUTIONS,
    ArrayLayout,
    draw_pixel_parameters,
)
from irnuc.model.validate import ConfigError

# ---------------------------------------------------------------------------------------
# Layout
# ---------------------------------------------------------------------------------------


def padded_reference(h, w, boundary, blind):
    """Expected kind map built independently, by padding the active area ring by ring."""
    ut, ub, ul, ur = boundary
    bt, bb, bl, br = blind
    km = np.full((h, w), ACTIVE, dtype=np.uint8)
    km = np.pad(km, ((ut, ub), (ul, ur)), constant_values=BOUNDARY)
    return np.pad(km, ((bt, bb), (bl, br)), constant_values=BLIND)


def test_asymmetric_rings_by_hand():
    # Active 2x3, boundary (top 0, bottom 3, left 2, right 1), blind (top 1, bottom 0,
    # left 0, right 2). Written out pixel by pixel: A = active, b = boundary, X = blind.
    lay = ArrayLayout(2, 3, boundary=(0, 3, 2, 1), blind=(1, 0, 0, 2))
    picture = [
        "XXXXXXXX",
        "bbAAAbXX",
        "bbAAAbXX",
        "bbbbbbXX",
        "bbbbbbXX",
        "bbbbbbXX",
    ]
    code = {"A": ACTIVE, "b": BOUNDARY, "X": BLIND}
    expected = np.array([[code[ch] for ch in line] for line in picture], dtype=np.uint8)
    assert (lay.rows, lay.cols) == (6, 8)
    km = lay.kind_map()
    assert km.dtype == np.uint8
    np.testing.assert_array_equal(km, expected)
    assert lay.active_slice == (slice(1, 3), slice(2, 5))
    assert lay.optical_centre == (1.5, 3.0)
    np.testing.assert_array_equal(lay.blind_row_indices, [0])
    np.testing.assert_array_equal(lay.blind_col_indices, [6, 7])


RING_CASES = [
    ((0, 0, 0, 0), (0, 0, 0, 0)),
    ((1, 1, 1, 1), (1, 1, 1, 1)),
    ((0, 3, 2, 1), (0, 3, 2, 1)),
    ((2, 0, 0, 4), (3, 1, 0, 2)),
    ((0, 0, 0, 0), (2, 2, 2, 2)),
    ((5, 5, 5, 5), (0, 0, 0, 0)),
]


@pytest.mark.parametrize(("boundary", "blind"), RING_CASES)
@pytest.mark.parametrize(("h", "w"), [(1, 1), (4, 7), (5, 6), (1, 9)])
def test_layout_against_padding(h, w, boundary, blind):
    lay = ArrayLayout(h, w, boundary, blind)
    expected = padded_reference(h, w, boundary, blind)
    km = lay.kind_map()
    np.testing.assert_array_equal(km, expected)
    assert km.shape == (lay.rows, lay.cols) == lay.shape

    # Counting: the active slice holds exactly the active pixels.
    assert np.count_nonzero(km == ACTIVE) == h * w
    assert np.all(km[lay.active_slice] == ACTIVE)
    assert km[lay.active_slice].shape == (h, w)

    # Centre = mean position of the active pixels.
    rc = np.argwhere(expected == ACTIVE).mean(axis=0)
    assert lay.optical_centre == pytest.approx((rc[0], rc[1]), abs=1e-12)

    # Entirely blind rows / columns, found by scanning the reference.
    np.testing.assert_array_equal(
        lay.blind_row_indices, np.flatnonzero((expected == BLIND).all(axis=1))
    )
    np.testing.assert_array_equal(
        lay.blind_col_indices, np.flatnonzero((expected == BLIND).all(axis=0))
    )
    assert lay.blind_row_indices.size == blind[0] + blind[1]
    assert lay.blind_col_indices.size == blind[2] + blind[3]


@settings(max_examples=60, deadline=None)
@given(
    h=st.integers(1, 6),
    w=st.integers(1, 6),
    boundary=st.tuples(*[st.integers(0, 4)] * 4),
    blind=st.tuples(*[st.integers(0, 4)] * 4),
)
def test_layout_property(h, w, boundary, blind):
    lay = ArrayLayout(h, w, boundary, blind)
    expected = padded_reference(h, w, boundary, blind)
    np.testing.assert_array_equal(lay.kind_map(), expected)
    rows_idx = lay.blind_row_indices
    cols_idx = lay.blind_col_indices
    # Row skimming reads the blind columns of each row; they exist on every row.
    assert np.all(lay.kind_map()[:, cols_idx] == BLIND)
    assert np.all(lay.kind_map()[rows_idx, :] == BLIND)


def test_scalar_rings_and_from_dict():
    lay = ArrayLayout(3, 4, boundary=1, blind=2)
    assert lay.boundary == (1, 1, 1, 1) and lay.blind == (2, 2, 2, 2)
    lay2 = ArrayLayout.from_dict(
        {"active_rows": 3, "active_cols": 4, "boundary": [1, 1, 1, 1], "blind": 2}
    )
    assert lay2 == lay
    assert ArrayLayout.from_dict({"active_rows": 3, "active_cols": 4}).shape == (3, 4)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"active_rows": 0, "active_cols": 4}, "fpa.active_rows"),
        ({"active_rows": 4, "active_cols": -1}, "fpa.active_cols"),
        ({"active_rows": 4.0, "active_cols": 4}, "fpa.active_rows"),
        ({"active_rows": 4, "active_cols": 4, "blind": (1, 1, -1, 1)}, "fpa.blind[2]"),
        ({"active_rows": 4, "active_cols": 4, "boundary": (1, 1, 1)}, "fpa.boundary"),
        ({"active_rows": 4, "active_cols": 4, "boundary": (0, 0, 0, 1.5)}, "fpa.boundary[3]"),
        ({"active_rows": 4, "active_cols": 4, "blind": True}, "fpa.blind"),
    ],
)
def test_layout_validation(kwargs, field):
    with pytest.raises(ConfigError, match="^" + re.escape(field) + " "):
        ArrayLayout(**kwargs)


def test_layout_from_dict_errors():
    with pytest.raises(ConfigError, match=r"cam\.fpa\.ring"):
        ArrayLayout.from_dict({"active_rows": 2, "active_cols": 2, "ring": 1}, path="cam.fpa")
    with pytest.raises(ConfigError, match=r"fpa\.active_cols is missing"):
        ArrayLayout.from_dict({"active_rows": 2})
    with pytest.raises(ConfigError, match=r"fpa\.blind\[0\] = -2"):
        ArrayLayout.from_dict({"active_rows": 2, "active_cols": 2, "blind": [-2, 0, 0, 0]})


# ---------------------------------------------------------------------------------------
# Per-pixel spread
# ---------------------------------------------------------------------------------------

BIG = ArrayLayout(1000, 1000)  # 1e6 pixels for moment checks


def scipy_reference(distribution: str, nominal: float, tol: float):
    """scipy.stats distribution with mean `nominal` and std `tol*nominal`, found by a root
    search on scipy's own moments (independent of the closed forms in model.fpa)."""
    if distribution == "lognormal":

        def cv(s):
            m, v = stats.lognorm(s).stats("mv")
            return np.sqrt(v) / m - tol

        s = optimize.brentq(cv, 1e-6, 5.0, xtol=1e-14)
        return stats.lognorm(s, scale=nominal / stats.lognorm(s).mean())
    if distribution == "gamma":

        def cv(a):
            m, v = stats.gamma(a).stats("mv")
            return np.sqrt(v) / m - tol

        a = optimize.brentq(cv, 1e-3, 1e8, xtol=1e-12)
        return stats.gamma(a, scale=nominal / stats.gamma(a).mean())
    if distribution == "normal_truncated":
        # Defined as the paper's normal with the non-positive tail removed.
        return stats.truncnorm(-1.0 / tol, np.inf, loc=nominal, scale=tol * nominal)
    raise AssertionError(distribution)


@pytest.mark.parametrize("distribution", ["lognormal", "gamma"])
@pytest.mark.parametrize("tol", [0.02, 0.1, 0.5, 1.0])
def test_moments(distribution, tol):
    nominal = 7.5e4
    x = draw_pixel_parameters(BIG, {"R": nominal}, {"R": tol}, seed=11, distribution=distribution)[
        "R"
    ]
    n = x.size
    ref = scipy_reference(distribution, nominal, tol)
    mean, var, _skew, kurt = ref.stats("mvsk")
    # The reference really has the requested first two moments.
    assert mean == pytest.approx(nominal, rel=1e-9)
    assert np.sqrt(var) == pytest.approx(tol * nominal, rel=1e-6)
    # Sample mean within 5 standard errors.
    assert abs(x.mean() - nominal) < 5 * np.sqrt(var / n)
    # Sample std within 5 standard errors (delta method with the excess kurtosis).
    se_rel_std = 0.5 * np.sqrt((float(kurt) + 2.0) / n)
    assert abs(x.std() / (tol * nominal) - 1.0) < 5 * se_rel_std


@pytest.mark.parametrize("distribution", sorted(SPREAD_DISTRIBUTIONS))
@pytest.mark.parametrize("tol", [0.05, 0.5, 1.0])
def test_distribution_shape_ks(distribution, tol):
    lay = ArrayLayout(100, 200)
    x = draw_pixel_parameters(lay, {"g": 1e-7}, {"g": tol}, seed=5, distribution=distribution)["g"]
    ref = scipy_reference(distribution, 1e-7, tol)
    assert stats.kstest(x.ravel(), ref.cdf).pvalue > 1e-4


@pytest.mark.parametrize("distribution", sorted(SPREAD_DISTRIBUTIONS))
def test_positive_at_full_tolerance(distribution):
    out = draw_pixel_parameters(
        BIG,
        {"R_ref": 1e5, "g": 1e-7, "C": 1e-9},
        {"R_ref": 1.0, "g": 1.0, "C": 1.0},
        seed=2024,
        distribution=distribution,
    )
    for x in out.values():
        assert x.shape == (1000, 1000) and x.dtype == np.float64
        assert np.all(np.isfinite(x))
        assert np.all(x > 0)


def test_paper_normal_would_go_negative():
    # The defect this module exists to avoid: a plain normal at tolerance 0.3 over 1e6
    # pixels has P(x <= 0) = Phi(-3.33) ~ 4e-4, i.e. hundreds of negative resistances.
    rng = np.random.default_rng(0)
    assert np.count_nonzero(rng.normal(1.0, 0.3, 10**6) <= 0) > 100
    x = draw_pixel_parameters(BIG, {"R": 1.0}, {"R": 0.3}, seed=0)["R"]
    assert x.min() > 0


def test_full_array_shape_includes_rings():
    lay = ArrayLayout(4, 5, boundary=(0, 3, 2, 1), blind=(1, 0, 0, 2))
    out = draw_pixel_parameters(lay, {"R_ref": 1e5}, {"R_ref": 0.01}, seed=1)
    assert out["R_ref"].shape == (lay.rows, lay.cols)


def test_reproducible_bits_and_order_independent():
    lay = ArrayLayout(30, 40, blind=1)
    nom = {"R_ref": 1e5, "g": 1e-7, "C": 1e-9}
    tol = {"R_ref": 0.05, "g": 0.1, "C": 0.2}
    for dist in SPREAD_DISTRIBUTIONS:
        a = draw_pixel_parameters(lay, nom, tol, 99, dist)
        b = draw_pixel_parameters(
            lay, dict(reversed(nom.items())), dict(reversed(tol.items())), 99, dist
        )
        assert set(a) == set(nom)
        for k in nom:
            assert a[k].tobytes() == b[k].tobytes()
        c = draw_pixel_parameters(lay, nom, tol, 100, dist)
        assert not np.array_equal(a["R_ref"], c["R_ref"])


def test_streams_independent_per_name():
    lay = ArrayLayout(200, 200)
    base = draw_pixel_parameters(lay, {"R_ref": 1e5, "g": 1e-7}, {"R_ref": 0.1, "g": 0.1}, 7)
    # Changing g's tolerance or adding a parameter leaves R_ref bit-identical.
    other = draw_pixel_parameters(
        lay, {"R_ref": 1e5, "g": 1e-7, "eps": 0.8}, {"R_ref": 0.1, "g": 0.3, "eps": 0.02}, 7
    )
    assert base["R_ref"].tobytes() == other["R_ref"].tobytes()
    assert not np.array_equal(base["g"], other["g"])
    # Two parameters with equal nominal/tolerance are uncorrelated, not copies.
    same = draw_pixel_parameters(lay, {"a": 1.0, "b": 1.0}, {"a": 0.1, "b": 0.1}, 7)
    r = np.corrcoef(same["a"].ravel(), same["b"].ravel())[0, 1]
    assert abs(r) < 5 / np.sqrt(same["a"].size)


def test_zero_tolerance_exact_and_no_draws(monkeypatch):
    def no_stream(*_args, **_kwargs):
        raise AssertionError("a random stream was created")

    monkeypatch.setattr(fpa, "parameter_stream", no_stream)
    lay = ArrayLayout(3, 4, blind=(0, 0, 1, 1))
    out = draw_pixel_parameters(lay, {"R_ref": 1e5, "C": 2e-9}, {"R_ref": 0.0}, seed=3)
    np.testing.assert_array_equal(out["R_ref"], np.full((3, 6), 1e5))
    np.testing.assert_array_equal(out["C"], np.full((3, 6), 2e-9))  # missing tolerance -> 0


@pytest.mark.parametrize(
    ("nominal", "tolerance", "dist", "pattern"),
    [
        ({"R_ref": 1e5}, {"R_ref": -0.1}, "lognormal", r"fpa\.tolerance\.R_ref = -0\.1 .*\[0, 1\]"),
        ({"R_ref": 1e5}, {"R_ref": 1.5}, "lognormal", r"fpa\.tolerance\.R_ref = 1\.5 .*\[0, 1\]"),
        ({"R_ref": 0.0}, {}, "lognormal", r"fpa\.nominal\.R_ref = 0 "),
        ({"g": -1e-7}, {}, "lognormal", r"fpa\.nominal\.g = -1e-07 "),
        ({"g": float("nan")}, {}, "lognormal", r"fpa\.nominal\.g"),
        ({"g": "big"}, {}, "lognormal", r"fpa\.nominal\.g = 'big' is not a number"),
        ({"g": 1e-7}, {"G": 0.1}, "lognormal", r"fpa\.tolerance\.G has no nominal"),
        ({"g": 1e-7}, {"g": 0.1}, "normal", r"fpa\.distribution = 'normal' is not one of"),
    ],
)
def test_spread_validation(nominal, tolerance, dist, pattern):
    with pytest.raises(ConfigError, match=pattern):
        draw_pixel_parameters(ArrayLayout(2, 2), nominal, tolerance, 1, dist)


def test_spread_validation_seed_and_path():
    with pytest.raises(ConfigError, match=r"^seed = -1 "):
        draw_pixel_parameters(ArrayLayout(2, 2), {"g": 1.0}, {}, -1)
    with pytest.raises(ConfigError, match=r"^sensor\.tolerance\.g"):
        draw_pixel_parameters(ArrayLayout(2, 2), {"g": 1.0}, {"g": 2.0}, 1, path="sensor")
