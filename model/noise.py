"""Temporal noise (on with ``noise.enabled``; seeded, counter-based).

Sources, per frame (docs/model.md, section 7):

* at the bolometer, every pixel of the array (so the skimming references carry their own
  noise into every pixel of their row or column, as the readout shares them):

  - Johnson noise, sqrt(4 k T R df) with df = 1 / (2 t_int), the noise bandwidth of an
    integrator of length t_int (``noise.johnson``);
  - 1/f noise of the resistance, S_V(f) = k V^2 / f (``noise.flicker_coefficient`` = k):
    the octaves between the frame rate's Nyquist frequency and 1/(2 t_int) are white from
    frame to frame, variance k V^2 ln(P / t_int); the ``FLICKER_OCTAVES`` octaves below it
    come from a Voss-McCartney generator (:class:`VossState`), variance k V^2 ln 2 each;
  - the thermal fluctuation of the pixel's temperature (``noise.thermal_fluctuation``),
    k T^2 / C in equilibrium, drawn before each bias pulse inside the bolometer model
    (:mod:`model.core.pulse`): it goes through the pulse like any temperature;

* at the integrator output, the active pixels: the readout noise (``noise.readout_sigma``,
  white), the readout chain's own 1/f noise (``noise.flicker_sigma``, a Voss generator) and
  the extra noise of NOISY defect pixels.

Every draw is a standard normal of :mod:`model.core.rng`: a function of the seed, the
stream of its source, the frame's absolute index and the pixel's index, so the bits do not
depend on how a run is split into chunks or on the number of threads.
"""

from __future__ import annotations

import math

import numpy as np

from irnuc.model.core import rng as _rng
from irnuc.model.core.constants import K_BOLTZMANN

#: Octaves of the Voss-McCartney 1/f generators below the frame rate's Nyquist frequency.
FLICKER_OCTAVES = 8
#: Streams (one per source) that separate the noise draws from each other and from the
#: other seeded stages.
NOISE_STREAM = 0x6E6F6973  # readout noise at the integrator output
REFERENCE_STREAM = 0x72656670  # readout noise of the reference pixels read out
THERMAL_STREAM = 0x74686572  # thermal fluctuation of each pixel before its pulse
BOLOMETER_STREAM = 0x626F6C6F  # Johnson and the fast 1/f octaves at the bolometer
FLICKER_STREAM = 0x666C6B72  # the bolometer's slow 1/f octaves
READOUT_FLICKER_STREAM = 0x72666C6B  # the readout chain's 1/f


def frame_key(seed: int, frame: int, stream: int) -> np.uint64:
    """The 64-bit key of one frame's draws of one stream (``numpy.random.SeedSequence``)."""
    ss = np.random.SeedSequence(seed, spawn_key=(stream, frame))
    return ss.generate_state(1, np.uint64)[0]


def normals(seed: int, frame: int, stream: int, shape: tuple[int, ...]) -> np.ndarray:
    """Standard normals of one frame and stream, ``shape`` (the draw of element k is a
    function of (seed, stream, frame, k) only)."""
    n = math.prod(shape)
    cols = shape[-1] if len(shape) >= 1 and shape[-1] else max(n, 1)
    out = np.empty((n // cols if cols else 0, cols))
    if out.size:
        _rng.normal_plane(frame_key(seed, frame, stream), out, _rng.ZIG_X, _rng.ZIG_F)
    return out.reshape(shape)


def normals_at(seed: int, frame: int, stream: int, index: np.ndarray) -> np.ndarray:
    """The normals of the draws ``index`` (flat indices) of one frame and stream."""
    out = np.empty(index.shape[0])
    _rng.normal_at(frame_key(seed, frame, stream), np.asarray(index, np.uint64), out,
                   _rng.ZIG_X, _rng.ZIG_F)
    return out


def frame_rng(seed: int, frame: int, stream: int = NOISE_STREAM) -> np.random.Generator:
    """A numpy generator of one frame and stream (for draws outside the frames' kernels)."""
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(stream, frame)))


def johnson_sigma(v_bolo: np.ndarray, temperature: np.ndarray, bias_current: float,
                  t_int: float, gain: float = 1.0) -> np.ndarray:
    """Johnson noise, V (times ``gain``): gain * sqrt(4 k T R / (2 t_int)).

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


def flicker_variances(coefficient: float, frame_period: float, t_int: float
                      ) -> tuple[float, float]:
    """(white, slow) variance of the bolometer's 1/f noise per V^2 of bias voltage: the
    octaves from the frame rate's Nyquist frequency 1/(2P) to 1/(2 t_int), white from frame
    to frame, k ln(P / t_int); the FLICKER_OCTAVES octaves below, k ln 2 each."""
    white = coefficient * math.log(max(frame_period / t_int, 1.0))
    return white, coefficient * math.log(2.0) * FLICKER_OCTAVES


class VossState:
    """A 1/f generator per pixel of ``shape`` (Voss-McCartney): FLICKER_OCTAVES values, the
    value of octave k drawn anew on every frame whose absolute index has k trailing zero
    bits (every 2^(k+1) frames), all drawn at the run's first frame (the stationary state),
    their running sum kept. The sum over sqrt(FLICKER_OCTAVES) has unit variance and a
    spectrum falling as about 1/f from the Nyquist frequency down FLICKER_OCTAVES octaves
    (within about 1.5 dB). The kernels of :mod:`model.core.stream` advance it in place
    (:meth:`plan` gives them each frame's octave and key); :meth:`step` does it in numpy."""

    def __init__(self, shape: tuple[int, ...], stream: int) -> None:
        self.shape = tuple(shape)
        self.stream = stream
        self.values: np.ndarray | None = None
        self.total: np.ndarray | None = None
        self.frame = -1

    def plan(self, seed: int, first_frame: int, n: int) -> tuple[np.ndarray, np.ndarray]:
        """(octave (n,) int64, key (n,) uint64) of frames first_frame .. + n - 1: the octave
        each draws anew (-1: none) and the key of its draws; the state starts (all octaves
        drawn) when a run begins or skips frames."""
        octave = np.full(n, -1, np.int64)
        keys = np.zeros(n, np.uint64)
        start = 0
        if self.values is None or first_frame != self.frame + 1:
            self.values = np.stack([normals(seed, first_frame, self.stream + 1 + k, self.shape)
                                    for k in range(FLICKER_OCTAVES)])
            self.total = self.values.sum(axis=0)
            start = 1
        for i in range(start, n):
            f = first_frame + i
            k = (f & -f).bit_length() - 1 if f > 0 else FLICKER_OCTAVES
            if k < FLICKER_OCTAVES:
                octave[i] = k
                keys[i] = frame_key(seed, f, self.stream)
        self.frame = first_frame + n - 1
        return octave, keys

    def step(self, seed: int, frame: int) -> np.ndarray:
        """The generator at absolute ``frame`` (unit variance, ``shape``)."""
        octave, _ = self.plan(seed, frame, 1)
        assert self.values is not None and self.total is not None
        k = int(octave[0])
        if k >= 0:
            new = normals(seed, frame, self.stream, self.shape)
            self.total += new - self.values[k]
            self.values[k] = new
        return self.total * (1.0 / math.sqrt(FLICKER_OCTAVES))

    def arrays(self) -> tuple[np.ndarray, np.ndarray]:
        """(values, total) for the kernels (after :meth:`plan`)."""
        assert self.values is not None and self.total is not None
        return self.values, self.total


def keys(seed: int, first_frame: int, n: int, stream: int) -> np.ndarray:
    """(n,) uint64: the keys of frames first_frame .. + n - 1 of a stream."""
    return np.array([frame_key(seed, first_frame + k, stream) for k in range(n)], np.uint64)


def add_noise(v: np.ndarray, sigma: np.ndarray | float, seed: int, first_frame: int,
              flicker_sigma: float = 0.0, flicker: VossState | None = None) -> np.ndarray:
    """v plus white noise of standard deviation ``sigma`` (V; a number or (H, W)) and
    optional 1/f noise of ``flicker_sigma`` (V), per frame.

    ``v`` is (N, H, W). Frame k of ``v`` is absolute frame ``first_frame + k`` for the
    choice of draws.
    """
    from irnuc.model.core import stream as _ks

    v = np.ascontiguousarray(v, dtype=np.float64)
    n = v.shape[0]
    sg = np.asarray(sigma, dtype=np.float64)
    sg = sg.reshape(1, 1) if sg.ndim == 0 else np.ascontiguousarray(np.broadcast_to(sg, v.shape[1:]))
    if flicker is not None and flicker_sigma > 0.0:
        octave, kf = flicker.plan(seed, first_frame, n)
        vals, total = flicker.arrays()
    else:
        octave, kf = np.full(n, -1, np.int64), np.zeros(n, np.uint64)
        vals, total = np.empty((0, 1, 1)), np.empty((1, 1))
    out = np.empty_like(v)
    _ks.output_noise(v, sg, keys(seed, first_frame, n, NOISE_STREAM), float(flicker_sigma),
                     octave, kf, vals, total, _rng.ZIG_X, _rng.ZIG_F, out)
    return out


def add_noise_at(v: np.ndarray, index: np.ndarray, sigma: np.ndarray, seed: int,
                 first_frame: int, *, copy: bool = True) -> np.ndarray:
    """v plus white noise on some pixels only (one draw per such pixel and frame).

    Used when temporal noise is off but some pixels have a NOISY defect: the other pixels
    need no draw at all. ``index`` holds the flat (row-major) positions of those pixels in
    a frame and ``sigma`` their standard deviations, V; the draw of a pixel is the one
    :func:`add_noise` would give it. ``copy`` False adds in place (a C-ordered array the
    caller owns).
    """
    out = v.copy() if copy else v
    flat = out.reshape(v.shape[0], -1)
    for k in range(v.shape[0]):
        flat[k, index] += sigma * normals_at(seed, first_frame + k, NOISE_STREAM, index)
    return out
