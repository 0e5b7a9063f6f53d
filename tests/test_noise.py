"""Temporal noise: Johnson formula, the counter-based normals (against scipy), 1/f shape,
seeding by absolute frame index."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc import model
from irnuc.model.noise import VossState, add_noise, johnson_sigma, normals


def test_johnson_sigma_formula():
    k = 1.380649e-23
    got = johnson_sigma(np.array([1.5]), np.array([306.0]), 1.5e-5, 6e-5, 40.0)
    assert got[0] == pytest.approx(40.0 * np.sqrt(4 * k * 306.0 * 1e5 / (2 * 6e-5)), rel=1e-14)


def test_white_noise_has_requested_std_and_is_split_independent():
    v = np.zeros((6, 50, 50))
    a = add_noise(v, 0.01, seed=3, first_frame=0)
    assert a.std() == pytest.approx(0.01, rel=0.03)
    b = np.concatenate([add_noise(v[:2], 0.01, 3, 0), add_noise(v[2:], 0.01, 3, 2)])
    np.testing.assert_array_equal(a, b)


def test_flicker_spectrum_falls_as_one_over_f():
    # Voss-McCartney over 8 octaves: unit variance, and a power per octave that stays
    # nearly constant (1/f) down the octaves (white noise would double it every octave).
    state = VossState((400,), 0x1234)
    x = np.stack([state.step(1, k) for k in range(2048)])  # (frames, pixels)
    assert x.std() == pytest.approx(1.0, rel=0.1)
    psd = (np.abs(np.fft.rfft(x - x.mean(axis=0), axis=0)) ** 2).mean(axis=1)
    f = np.fft.rfftfreq(2048)
    # power in octaves [f0, 2 f0): 1/f gives equal power per octave
    per_octave = [psd[(f >= lo) & (f < 2 * lo)].sum() for lo in (1 / 128, 1 / 64, 1 / 32,
                                                                 1 / 16, 1 / 8)]
    assert max(per_octave) / min(per_octave) < 2.0
    low, high = psd[(f > 0) & (f < 1 / 64)].mean(), psd[f > 0.25].mean()
    assert low > 20 * high


def test_normals_match_the_normal_distribution_and_every_split():
    # The ziggurat draws against scipy's normal: mean, variance, KS, and the tail beyond
    # the ziggurat's base layer (r = 3.44) where the exact tail method takes over.
    from scipy import stats

    z = normals(5, 0, 0x77, (1000, 1000)).ravel()
    n = z.size
    assert abs(z.mean()) < 4 / np.sqrt(n)
    assert abs(z.var() - 1) < 4 * np.sqrt(2 / n)
    assert stats.kstest(z[:200_000], "norm").pvalue > 1e-3
    for t in (1.0, 3.0, 3.5, 4.0):
        p = 2 * stats.norm.sf(t)
        assert abs((np.abs(z) > t).mean() - p) < 5 * np.sqrt(p / n)
    # a draw depends on (seed, frame, stream, index) only: any shape, any thread count
    import numba

    a = normals(5, 0, 0x77, (50, 40))
    b = normals(5, 0, 0x77, (40, 50)).ravel()
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        c = normals(5, 0, 0x77, (2000,))
    finally:
        numba.set_num_threads(before)
    np.testing.assert_array_equal(a.ravel(), b)
    np.testing.assert_array_equal(a.ravel(), c)
    assert not np.array_equal(a, normals(5, 1, 0x77, (50, 40)))


def test_noise_raises_temporal_std_of_frames(small_cfg):
    cfg = small_cfg(**{"noise.enabled": True, "noise.readout_sigma": 1e-3, "noise.johnson": False})
    fr = model.simulate(cfg, [300.0] * 40, seed=1)
    lsb = 3.3 / 2**14
    assert fr.codes.astype(float).std(axis=0).mean() == pytest.approx(1e-3 / lsb, rel=0.15)
