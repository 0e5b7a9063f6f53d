"""Two-point calibration: coefficients against an independent computation, equal
responses, saturation counts and the needed-range report."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from irnuc.nuc_fixed import ConfigError, InputError, load_pipeline, nuc_core
from irnuc.nuc_fixed.badpix import Reason, load_thresholds
from irnuc.nuc_fixed.calibrate import calibrate, summary_text
from irnuc.nuc_fixed.synthetic import synth_frames

CFG = load_pipeline("typical14")


def _stacks(resp: np.ndarray, base: np.ndarray, m: int = 4, seed: int = 0):
    """Noise-free-ish integer stacks with exact per-pixel means base and base + resp."""
    rng = np.random.default_rng(seed)
    lo = np.repeat(base[None], m, axis=0).astype(np.int64)
    hi = np.repeat((base + resp)[None], m, axis=0).astype(np.int64)
    # +-1 code dither that averages to zero keeps the means exact and the std small.
    d = rng.integers(0, 2, base.shape) * 2 - 1
    lo[0] += d
    lo[1] -= d
    hi[0] -= d
    hi[1] += d
    return lo, hi


def test_coefficients_match_independent_computation() -> None:
    rng = np.random.default_rng(3)
    resp = rng.integers(3600, 4400, (12, 16))
    base = rng.integers(2500, 3500, (12, 16))
    lo, hi = _stacks(resp, base)
    targets = (3000.0, 7000.0)
    cal = calibrate(lo, hi, CFG, targets=targets, rounding="half_even")
    assert not cal.bad.any()
    gf, of = CFG.gain_frac_bits, CFG.offset_frac_bits
    for r, c in [(0, 0), (5, 7), (11, 15)]:
        g = Fraction(4000) / int(resp[r, c])
        want_g = round(g * 2**gf)  # Fraction rounds half to even
        assert cal.gain_code[r, c] == want_g
        # The float offset uses the float gain; compare it within one code of the exact one.
        o = Fraction(3000) - g * int(base[r, c])
        assert abs(int(cal.offset_code[r, c]) - round(o * 2**of)) <= 1
    # Applying the NUC to the calibration means lands on the targets (within rounding).
    for x, t in ((base, 3000), (base + resp, 7000)):
        y = nuc_core(x, cal.gain_code, cal.offset_code, CFG).astype(float)
        assert np.abs(y - t).max() <= 1.0


def test_equal_responses_are_flagged_not_infinite() -> None:
    rng = np.random.default_rng(4)
    resp = rng.integers(3800, 4200, (8, 8))
    resp[2, 3] = 0
    resp[7, 7] = 0
    base = rng.integers(2500, 3500, (8, 8))
    lo, hi = _stacks(resp, base)
    cal = calibrate(lo, hi, CFG)
    for p in [(2, 3), (7, 7)]:
        assert cal.bad[p] and cal.reasons[p] & Reason.EQUAL_RESPONSE
        assert cal.gain_code[p] == cal.summary["fill_codes"]["gain"]
    assert np.isfinite(cal.gain).all() and np.isfinite(cal.offset).all()
    assert cal.summary["reasons"]["EQUAL_RESPONSE"] == 2
    assert int(cal.bad.sum()) == 2


def test_saturation_counted_and_needed_range_reported() -> None:
    rng = np.random.default_rng(5)
    resp = rng.integers(900, 1100, (10, 10))
    base = rng.integers(1000, 2000, (10, 10))
    lo, hi = _stacks(resp, base)
    span = 3.9 * 1000.0  # gains 3.5 .. 4.3: U2.14 tops out just below 4
    cal = calibrate(lo, hi, CFG, targets=(2000.0, 2000.0 + span))
    gains = span / resp
    top = (2**CFG.gain_bits - 1) / 2**CFG.gain_frac_bits
    n_over = int((np.round(gains * 2**CFG.gain_frac_bits) > 2**CFG.gain_bits - 1).sum())
    assert n_over > 0
    assert cal.summary["gain_saturated"] == n_over
    assert cal.summary["reasons"]["GAIN_RANGE"] == n_over
    assert ((cal.reasons & Reason.GAIN_RANGE) != 0).sum() == n_over
    g = cal.summary["gain"]
    assert g["min"] == pytest.approx(gains.min()) and g["max"] == pytest.approx(gains.max())
    assert g["max"] > top and g["int_bits_needed"] == 3  # 4.3 needs three integer bits
    assert "saturated" in summary_text(cal)


def test_default_targets_are_scaled_frame_means() -> None:
    s = synth_frames(shape=(16, 20), repeats=4, defect_fraction=0.0, seed=2, adc_bits=8,
                     base=60.0, codes_per_kelvin=1.0, offset_spread=3.0, noise=0.5)
    cfg = load_pipeline("minimal")  # A = 8, B = 6: targets are the means / 4
    cal = calibrate(s.codes[:4], s.codes[4:], cfg)
    lo_mean = s.codes[:4].astype(float).mean(axis=0)
    good = ~cal.bad
    # The targets come from the response pre-screen, a superset of the final good pixels.
    assert cal.summary["targets"][0] == pytest.approx(lo_mean[good].mean() / 4, rel=0.02)


def test_sensor_without_defects_flags_almost_nothing() -> None:
    s = synth_frames(shape=(24, 32), repeats=4, defect_fraction=0.0, seed=8)
    cal = calibrate(s.codes[:4], s.codes[4:], CFG)
    assert cal.bad.sum() <= 1  # a 4.5-sigma offset test may take one pixel of 768
    assert cal.summary["residual"]["low"]["rms"] < 1.0


@pytest.mark.parametrize(
    ("lo", "hi", "err", "match"),
    [
        (np.full((2, 4, 4), np.nan), np.zeros((2, 4, 4)), InputError, "NaN"),
        (np.zeros((2, 4, 4), float), np.zeros((2, 4, 4)), InputError, "dtype float64"),
        (np.zeros((2, 4, 4), int), np.zeros((2, 4, 5), int), InputError, "must match"),
        (np.full((2, 4, 4), 2**14), np.zeros((2, 4, 4), int), InputError, r"\[0, 16383\]"),
        (np.zeros((2, 4, 4), int), np.zeros((2, 4, 4), int), ValueError, "no usable pixel"),
    ],
)
def test_bad_inputs(lo: np.ndarray, hi: np.ndarray, err: type, match: str) -> None:
    with pytest.raises(err, match=match):
        calibrate(lo, hi, CFG)


def test_swapped_temperatures_and_bad_targets() -> None:
    rng = np.random.default_rng(6)
    lo, hi = _stacks(rng.integers(900, 1100, (6, 6)), rng.integers(1000, 2000, (6, 6)))
    with pytest.raises(ValueError, match="swapped"):
        calibrate(hi, lo, CFG)
    with pytest.raises(ConfigError, match="target high = 20000"):
        calibrate(lo, hi, CFG, targets=(100.0, 20000.0))
    with pytest.raises(ConfigError, match="rounding = 'nearest'"):
        calibrate(lo, hi, CFG, rounding="nearest")
    with pytest.raises(ConfigError, match="low_response = 2"):
        load_thresholds(overrides={"low_response": 2.0})
