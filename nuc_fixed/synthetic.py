"""Seeded synthetic calibration frames with planted defects (a stand-in for ``model``).

A linear sensor: code = offset_i + gain_i * k * (T - T0) + noise, with per-pixel gain and
offset spread, Gaussian temporal noise and defects of the kinds the physics model plants
(``irnuc.model.DefectKind``, the physics model's ground-truth codes).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.model.defects import DefectKind


@dataclass(frozen=True)
class SynthFrames:
    """Same fields as ``model.simulate`` results."""

    codes: np.ndarray        # (len(temps) * M, H, W) uint16, temperature-major
    temps: np.ndarray        # (len(temps) * M,) float64 kelvin
    defect_kind: np.ndarray  # (H, W) uint8, DefectKind
    adc_bits: int


def synth_frames(
    shape: tuple[int, int] = (48, 64),
    temps: tuple[float, ...] = (300.0, 400.0),
    repeats: int = 8,
    adc_bits: int = 14,
    defect_fraction: float = 0.02,
    seed: int = 1,
    gain_spread: float = 0.05,
    offset_spread: float = 150.0,
    noise: float = 2.0,
    codes_per_kelvin: float = 40.0,
    base: float = 3000.0,
) -> SynthFrames:
    """Synthetic frames (ADC codes) with planted defects.

    Parameters
    ----------
    shape : (H, W)
    temps : kelvin, one block of ``repeats`` frames per temperature
    repeats : frames per temperature (M)
    adc_bits : ADC width A
    defect_fraction : fraction of pixels given a defect (kinds drawn uniformly)
    seed : every random draw comes from ``numpy.random.default_rng(seed)``
    gain_spread : relative std of the per-pixel responsivity
    offset_spread : std of the per-pixel offset, ADC codes
    noise : temporal noise std, ADC codes
    codes_per_kelvin : mean responsivity, ADC codes per kelvin
    base : mean code at 300 K
    """
    rng = np.random.default_rng(seed)
    h, w = shape
    full = (1 << adc_bits) - 1
    gain = rng.normal(1.0, gain_spread, shape)
    offset = base + rng.normal(0.0, offset_spread, shape)
    sigma = np.full(shape, noise)
    kind = np.zeros(shape, dtype=np.uint8)
    n_def = round(defect_fraction * h * w)
    where = rng.choice(h * w, size=n_def, replace=False)
    kinds = rng.integers(1, len(DefectKind), size=n_def)
    kind.flat[where] = kinds
    gain[kind == DefectKind.LOW_RESP] *= 0.2
    gain[kind == DefectKind.HIGH_RESP] *= 2.5
    gain[kind == DefectKind.DEAD] = 0.0
    offset[kind == DefectKind.HOT] += 2500.0
    offset[kind == DefectKind.COLD] -= 2500.0
    sigma[kind == DefectKind.NOISY] *= 10.0
    constant = {DefectKind.STUCK_LOW: 0, DefectKind.STUCK_HIGH: full}
    stuck_value = rng.integers(1, full, shape)
    frames, tlist = [], []
    for t in temps:
        mean = offset + gain * codes_per_kelvin * (t - 300.0)
        for _ in range(repeats):
            f = mean + sigma * rng.standard_normal(shape)
            f[kind == DefectKind.DEAD] = offset[kind == DefectKind.DEAD]  # no signal, no noise
            for k, v in constant.items():
                f[kind == k] = v
            f[kind == DefectKind.STUCK_VALUE] = stuck_value[kind == DefectKind.STUCK_VALUE]
            frames.append(np.clip(np.rint(f), 0, full).astype(np.uint16))
            tlist.append(float(t))
    return SynthFrames(codes=np.stack(frames), temps=np.array(tlist), defect_kind=kind,
                       adc_bits=adc_bits)
