"""Band radiance against independent references (mpmath polylog closed form and quadrature)."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from irnuc.model import ConfigError, band_radiance
from irnuc.model.core.constants import C_LIGHT, H_PLANCK, K_BOLTZMANN
from irnuc.model.radiometry import band_radiance_detailed

mp.mp.dps = 50


def _tail_polylog(x):
    """int_x^inf t^3/(e^t - 1) dt in closed form with polylogarithms."""
    z = mp.exp(-x)
    return x**3 * (-mp.log(1 - z)) + 3 * x**2 * mp.polylog(2, z) + 6 * x * mp.polylog(3, z) \
        + 6 * mp.polylog(4, z)


def reference_radiance(T, lo=8e-6, hi=14e-6):
    h, c, k, T = mp.mpf(H_PLANCK), mp.mpf(C_LIGHT), mp.mpf(K_BOLTZMANN), mp.mpf(T)
    x1, x2 = h * c / (mp.mpf(lo) * k * T), h * c / (mp.mpf(hi) * k * T)
    return 2 * k**4 * T**4 / (h**3 * c**2) * (_tail_polylog(x2) - _tail_polylog(x1))


def reference_quad(T, lo=8e-6, hi=14e-6):
    """Planck's law integrated over wavelength (eq. 2) by mpmath quadrature."""
    h, c, k, T = mp.mpf(H_PLANCK), mp.mpf(C_LIGHT), mp.mpf(K_BOLTZMANN), mp.mpf(T)
    planck = lambda lam: 2 * h * c**2 / lam**5 / mp.expm1(h * c / (lam * k * T))  # noqa: E731
    return mp.quad(planck, mp.linspace(mp.mpf(lo), mp.mpf(hi), 5))


TEMPS = [50.0, 77.0, 150.0, 250.0, 300.0, 350.0, 400.0, 500.0, 1000.0, 1500.0, 3000.0,
         5000.0, 7500.0, 10000.0]


@pytest.mark.parametrize("T", TEMPS)
def test_matches_polylog_closed_form(T):
    got = band_radiance(T)
    ref = reference_radiance(T)
    assert abs((mp.mpf(float(got)) - ref) / ref) < 1e-12


@pytest.mark.parametrize("T", [t for t in TEMPS if t <= 5000.0])
def test_paper_series_matches_where_it_does_not_cancel(T):
    got = band_radiance(T, method="series")
    ref = reference_radiance(T)
    assert abs((mp.mpf(float(got)) - ref) / ref) < 1e-12


def test_paper_series_cancels_when_hot_and_hybrid_does_not():
    # At 10000 K the two tails of eq. 4 are ~4000 times the band: rounding is amplified.
    ref = reference_radiance(10000.0)
    err = {m: abs(float((mp.mpf(float(band_radiance(10000.0, method=m))) - ref) / ref))
           for m in ("series", "hybrid")}
    assert err["hybrid"] < 1e-14 < err["series"] < 1e-10


@pytest.mark.parametrize("T", [60.0, 300.0, 2000.0, 9000.0])
def test_matches_planck_quadrature(T):
    got = float(band_radiance(T))
    ref = reference_quad(T)
    assert abs((mp.mpf(got) - ref) / ref) < 1e-12


def test_other_band():
    got = float(band_radiance(500.0, band=(3e-6, 5e-6)))
    ref = reference_radiance(500.0, 3e-6, 5e-6)
    assert abs((mp.mpf(got) - ref) / ref) < 1e-12


def test_random_temperatures_vectorised():
    rng = np.random.default_rng(3)
    temps = np.exp(rng.uniform(np.log(50.0), np.log(10000.0), 40)).reshape(5, 8)
    got = band_radiance(temps)
    assert got.shape == (5, 8)
    for t, g in zip(temps.ravel(), got.ravel(), strict=True):
        ref = reference_radiance(t)
        assert abs((mp.mpf(float(g)) - ref) / ref) < 1e-12


def test_fixed_hundred_terms_reproduces_reference_implementation_error():
    # The issue measured the reference's fixed 100 terms: 4.6e-11 off at 5000 K, 2.8e-6 at 10000 K.
    got = band_radiance(np.array([5000.0, 10000.0]), method="series", n_terms=100)
    err = [abs(float((mp.mpf(float(g)) - reference_radiance(t)) / reference_radiance(t)))
           for g, t in zip(got, (5000.0, 10000.0), strict=True)]
    assert 2e-11 < err[0] < 1e-10
    assert 1e-6 < err[1] < 1e-5


def test_terms_follow_tolerance():
    loose = band_radiance_detailed(5000.0, rtol=1e-4, method="series").terms
    tight = band_radiance_detailed(5000.0, rtol=1e-12, method="series").terms
    assert loose < tight
    ref = reference_radiance(5000.0)
    got = band_radiance(5000.0, rtol=1e-4, method="series")
    assert abs(float((mp.mpf(float(got)) - ref) / ref)) < 1e-4


def test_hybrid_needs_few_terms_when_hot():
    assert band_radiance_detailed(10000.0).terms < 60
    assert band_radiance_detailed(10000.0, method="series").terms > 200


def test_emissivity_scales():
    assert band_radiance(320.0, emissivity=0.25) == pytest.approx(0.25 * band_radiance(320.0),
                                                                  rel=1e-15)


def test_monotonic_in_temperature():
    t = np.linspace(50.0, 10000.0, 500)
    assert np.all(np.diff(band_radiance(t)) > 0)


def test_extremely_cold_underflows_to_zero_not_nan():
    got = band_radiance(np.array([1.0, 2.0]))
    assert got[0] == 0.0  # ~1e-440 W m^-2 sr^-1: below float64
    assert np.isfinite(got).all() and got[1] > 0


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"T": 0.0}, "T"),
        ({"T": -5.0}, "T"),
        ({"T": np.nan}, "T"),
        ({"T": np.inf}, "T"),
        ({"T": [300.0, 0.0]}, "T"),
        ({"T": 300.0, "band": (14e-6, 8e-6)}, "band"),
        ({"T": 300.0, "band": (0.0, 8e-6)}, "band[0]"),
        ({"T": 300.0, "rtol": -1e-12}, "rtol"),
        ({"T": 300.0, "rtol": 0.5}, "rtol"),
        ({"T": 300.0, "emissivity": 1.5}, "emissivity"),
        ({"T": 300.0, "method": "magic"}, "method"),
        ({"T": 300.0, "n_terms": 10}, "n_terms"),
        ({"T": 300.0, "method": "series", "n_terms": 0}, "n_terms"),
    ],
)
def test_bad_input_names_the_field(kwargs, field):
    with pytest.raises(ConfigError) as info:
        band_radiance(**kwargs)
    assert str(info.value).startswith(field + " ") or f" {field} " in str(info.value)


# ---- narrow bands, cold and hot limits (against the study's mpmath references) -----------

NARROW_BANDS = [(8e-6 - 1e-12, 8e-6 + 1e-12), (7.999e-6, 8.001e-6), (10e-6, 10.05e-6)]


@pytest.mark.parametrize("band", NARROW_BANDS)
@pytest.mark.parametrize("T", [20.0, 77.0, 300.0, 3000.0, 1e5])
def test_narrow_band_relative_error_below_1e_12(band, T):
    # A 1 pm band loses 7 digits when formed as the difference of two tails; the hybrid
    # method integrates it directly. Reference: 80-digit mpmath series (independent).
    from irnuc.reports.studies.precision import band_radiance_mp

    ref = band_radiance_mp(T, band, as_mpf=True)
    got = float(band_radiance(T, band=band))
    assert abs((mp.mpf(got) - ref) / ref) < 1e-12


def test_narrow_band_cancels_in_the_paper_series():
    # The paper's difference of tails loses digits on a 1 pm band: the reason for quadrature.
    from irnuc.reports.studies.precision import band_radiance_mp

    # The lost digits are rounding noise: at one temperature they may happen to cancel, so
    # the largest error over several is the measure (1e-10 to 2e-8 here).
    band = NARROW_BANDS[0]
    errs = []
    for T in (100.0, 300.0, 400.0, 3000.0):
        ref = band_radiance_mp(T, band, as_mpf=True)
        got = mp.mpf(float(band_radiance(T, band=band, method="series")))
        errs.append(abs(float((got - ref) / ref)))
    assert max(errs) > 1e-10


@pytest.mark.parametrize("T", [1e-300, 1e-100, 1e-5, 0.5, 1.0, 1.4, 1.5, 2.0, 3.0])
def test_cold_limit_is_zero_or_the_right_tiny_value(T):
    # 0 < T <= 1e-100 used to give 0 * inf = NaN. Where the true radiance is a normal
    # float64 the relative error is <= 1e-12; below, 0 or the nearest subnormal.
    from irnuc.reports.studies.precision import band_radiance_mp

    got = float(band_radiance(T))
    ref = band_radiance_mp(T, as_mpf=True)
    assert math.isfinite(got) and got >= 0.0
    if ref >= 2.2250738585072014e-308:
        assert abs((mp.mpf(got) - ref) / ref) < 1e-12
    else:
        assert abs(mp.mpf(got) - ref) <= 2 * 4.95e-324


@pytest.mark.parametrize("T", [1e5, 1e7, 1e9])
def test_hot_limit_against_mpmath(T):
    from irnuc.reports.studies.precision import band_radiance_mp

    ref = band_radiance_mp(T, as_mpf=True)
    assert abs((mp.mpf(float(band_radiance(T))) - ref) / ref) < 1e-12


def test_hotter_than_the_allowed_range_is_an_error():
    with pytest.raises(ConfigError, match=r"^T = 2e\+09 K .*allowed range"):
        band_radiance(2e9)


def test_study_reference_agrees_with_quadrature_where_polylog_underflows():
    # Below ~15 K mpmath's polylog(1, q) underflows to 0; the series reference does not.
    from irnuc.reports.studies.precision import band_radiance_mp, band_radiance_quad_mp

    for T in (1.0, 5.0, 12.0):
        a = band_radiance_mp(T, as_mpf=True)
        b = band_radiance_quad_mp(T)
        assert abs((a - b) / a) < mp.mpf(10) ** -30


def test_band_radiance_at_one_temperature_matches_the_checked_api_and_mpmath() -> None:
    """The root finder's form (band checked once, one T at a time) gives band_radiance's
    bits, mpmath's polylog value to 1e-12, and the same one-line errors."""
    from irnuc.model.radiometry import band_radiance_at

    for band in ((8e-6, 14e-6), (3e-6, 5e-6)):
        at = band_radiance_at(band)
        for T in (1.0, 77.0, 280.0, 300.5, 1234.5, 6000.0):
            assert at(T) == float(band_radiance(T, band))
        ref = reference_radiance(300.0, *band)
        assert abs((mp.mpf(at(300.0)) - ref) / ref) < 1e-12
    half = band_radiance_at((8e-6, 14e-6), emissivity=0.5)
    assert half(300.0) == float(band_radiance(300.0, (8e-6, 14e-6), emissivity=0.5))
    for bad in (0.0, -1.0, float("nan"), 2e9):
        with pytest.raises(ConfigError, match=r"T = .* outside the allowed range"):
            band_radiance_at()(bad)
    with pytest.raises(ConfigError, match="band"):
        band_radiance_at((14e-6, 8e-6))
