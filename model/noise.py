"""Temporal noise (optional, off by default, seeded).

Per frame and pixel, at the integrator output:

* Johnson noise of the bolometer, sqrt(4 k T R df) with df = 1 / (2 t_int) (the noise
  bandwidth of an integrator of length t_int), times the integrator gain;
* readout noise, a fixed standard deviation, V;
* 1/f (flicker) noise: the sum of ``FLICKER_OCTAVES`` first-order autoregressive processes
  with correlation times of 1, 2, 4, ... frames, each of unit variance, scaled to
  ``flicker_sigma``; their summed spectrum falls as about 1/f between 1/2^K and 1/2 of the
  frame rate;
* the extra noise of pixels with a NOISY defect.

Every frame draws from its own stream, derived from the seed and the absolute frame index,
so the bits do not depend on how a batch is split into chunks.
"""

from __future__ import annotations

import numpy as np

from irnuc.model.core.constants import K_BOLTZMANN

FLICKER_OCTAVES = 8
#: Stream key that separates noise draws from the other seeded stages.
NOISE_STREAM = 0x6E6F6973
#: Stream of the reference (shielded) pixels read out beside the image: their draws never
#: change the image's.
REFERENCE_STREAM = 0x72656670


def frame_rng(seed: int, frame: int, stream: int = NOISE_STREAM) -> np.random.Generator:
    """The generator of one frame's noise (of the image, or of another ``stream``)."""
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(stream, frame)))


def johnson_sigma(v_bolo: np.ndarray, temperature: np.ndarray, bias_current: float,
                  t_int: float, gain: float) -> np.ndarray:
    """Johnson noise at the integrator output, V: gain * sqrt(4 k T R / (2 t_int)).

    Parameters
    ----------
    v_bolo : ndarray
        Bolometer voltage I R, V (gives R).
    temperature : ndarray
        Bolometer temperature, K.
    bias_current, t_int, gain : float
        A, s, V/V.
    """
    resistance = v_bolo / bias_current
    return gain * np.sqrt(4.0 * K_BOLTZMANN * temperature * resistance / (2.0 * t_int))


class FlickerState:
    """State of the 1/f generator: one AR(1) value per octave and pixel."""

    def __init__(self, shape: tuple[int, ...]) -> None:
        self.values: np.ndarray | None = None
        self.shape = shape
        self.rho = np.exp(-1.0 / 2.0 ** np.arange(FLICKER_OCTAVES))

    def step(self, rng: np.random.Generator) -> np.ndarray:
        """Advance one frame; returns unit-variance 1/f-like noise of ``shape``."""
        w = rng.standard_normal((FLICKER_OCTAVES, *self.shape))
        if self.values is None:
            self.values = w  # start in the stationary distribution
        else:
            r = self.rho.reshape((-1,) + (1,) * len(self.shape))
            self.values = r * self.values + np.sqrt(1.0 - r * r) * w
        return self.values.sum(axis=0) / np.sqrt(FLICKER_OCTAVES)


def add_noise(v: np.ndarray, sigma: np.ndarray | float, seed: int, first_frame: int,
              flicker_sigma: float = 0.0, flicker: FlickerState | None = None) -> np.ndarray:
    """v plus white noise of standard deviation ``sigma`` (V) and optional flicker, per frame.

    ``v`` is (N, H, W); ``sigma`` broadcasts to it. Frame k of ``v`` is absolute frame
    ``first_frame + k`` for the choice of random stream.
    """
    out = np.empty_like(v)
    sigma = np.broadcast_to(sigma, v.shape)
    for k in range(v.shape[0]):
        rng = frame_rng(seed, first_frame + k)
        out[k] = v[k] + sigma[k] * rng.standard_normal(v.shape[1:])
        if flicker is not None and flicker_sigma > 0.0:
            out[k] += flicker_sigma * flicker.step(rng)
    return out


def add_noise_at(v: np.ndarray, index: np.ndarray, sigma: np.ndarray, seed: int,
                 first_frame: int, *, copy: bool = True) -> np.ndarray:
    """v plus white noise on some pixels only (one draw per such pixel and frame).

    Used when temporal noise is off but some pixels have a NOISY defect: the other pixels
    need no draw at all. ``index`` holds the flat (row-major) positions of those pixels in
    a frame and ``sigma`` their standard deviations, V; frames are seeded as in
    :func:`add_noise`. ``copy`` False adds in place (a C-ordered array the caller owns).
    """
    out = v.copy() if copy else v
    flat = out.reshape(v.shape[0], -1)
    for k in range(v.shape[0]):
        rng = frame_rng(seed, first_frame + k)
        flat[k, index] += sigma * rng.standard_normal(index.size)
    return out
