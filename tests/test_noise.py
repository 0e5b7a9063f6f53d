"""Temporal noise: Johnson formula, 1/f shape, seeding by absolute frame index."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc import model
from irnuc.model.noise import FlickerState, add_noise, frame_rng, johnson_sigma


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


def test_flicker_spectrum_falls_with_frequency():
    state = FlickerState((200,))
    x = np.stack([state.step(frame_rng(1, k)) for k in range(1024)])  # (frames, pixels)
    assert x.std() == pytest.approx(1.0, rel=0.15)
    psd = (np.abs(np.fft.rfft(x - x.mean(axis=0), axis=0)) ** 2).mean(axis=1)
    low, high = psd[1:9].mean(), psd[256:512].mean()
    assert low > 20 * high  # white noise would give a ratio near 1


def test_noise_raises_temporal_std_of_frames(small_cfg):
    cfg = small_cfg(**{"noise.enabled": True, "noise.readout_sigma": 1e-3, "noise.johnson": False})
    fr = model.simulate(cfg, [300.0] * 40, seed=1)
    lsb = 3.3 / 2**14
    assert fr.codes.astype(float).std(axis=0).mean() == pytest.approx(1e-3 / lsb, rel=0.15)
