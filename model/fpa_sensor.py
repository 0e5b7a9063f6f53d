"""The on-die FPA temperature sensor, and the per-frame fields every frame file carries.

A camera's correction hardware never sees the true focal-plane (substrate) temperature:
it sees the reading of a temperature sensor on the die, an unsigned code of ``bits`` bits
with a step of ``lsb_K`` kelvin, code 0 at ``zero_K``. The reading is what a
temperature-dependent correction method (``tc_offset``, ``table_interp``) evaluates, so
the golden model, the RTL and the calibration all take this integer code, never a float.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.model.validate import check_array, check_int, check_scalar

#: Per-frame fields stored with the codes of every frame file (plain runs store them
#: constant): name -> (dtype, unit, meaning).
FRAME_FIELDS: dict[str, tuple[str, str, str]] = {
    "time_s": ("float64", "s", "time of the frame since the start of the sequence"),
    "fpa_K": ("float64", "K", "true FPA (substrate) temperature"),
    "fpa_reading": ("int64", "code", "reading of the on-die FPA temperature sensor"),
    "T_cam_K": ("float64", "K", "housing / optics / shutter temperature"),
    "scene_K": ("float64", "K", "scene base temperature"),
    "shutter": ("bool", "", "True while the shutter is closed (uniform source)"),
}

#: Stream key that separates the sensor's noise draws from the other seeded stages.
SENSOR_STREAM = 0x66706173


@dataclass(frozen=True)
class FpaSensor:
    """An on-die FPA temperature sensor.

    Attributes
    ----------
    bits : int
        Width of the reading, bits (1..24).
    lsb_K : float
        Temperature step of one code, K (> 0).
    zero_K : float
        Temperature that reads code 0, K.
    offset_K : float
        Error of the sensor: it reads the FPA temperature plus this, K.
    noise_K : float
        RMS noise of one reading, K (>= 0); drawn per frame from the seed.
    """

    bits: int = 14
    lsb_K: float = 0.01
    zero_K: float = 223.15
    offset_K: float = 0.0
    noise_K: float = 0.0

    def __post_init__(self) -> None:
        check_int("fpa_sensor.bits", self.bits, 1, 24)
        check_scalar("fpa_sensor.lsb_K", self.lsb_K, 0.0, 100.0, lo_open=True, unit="K")
        check_scalar("fpa_sensor.zero_K", self.zero_K, 0.0, 1000.0, unit="K")
        check_scalar("fpa_sensor.offset_K", self.offset_K, -100.0, 100.0, unit="K")
        check_scalar("fpa_sensor.noise_K", self.noise_K, 0.0, 100.0, unit="K")

    @property
    def max_code(self) -> int:
        return (1 << self.bits) - 1

    def read(self, fpa_K: np.ndarray | float, seed: int = 0, first_frame: int = 0) -> np.ndarray:
        """Readings (int64 codes, clamped to [0, 2^bits - 1]) of FPA temperatures, K.

        Frame ``first_frame + i`` draws its noise from its own stream of ``seed``, so the
        readings do not depend on how a sequence is split into chunks.
        """
        t = np.atleast_1d(check_array("fpa_K", fpa_K, 0.0, None, lo_open=True, unit="K"))
        t = t + self.offset_K
        if self.noise_K > 0.0:
            noise = np.array([
                np.random.default_rng(np.random.SeedSequence(
                    seed, spawn_key=(SENSOR_STREAM, first_frame + i))).standard_normal()
                for i in range(t.size)])
            t = t + self.noise_K * noise.reshape(t.shape)
        code = np.rint((t - self.zero_K) / self.lsb_K)
        return np.clip(code, 0, self.max_code).astype(np.int64)

    def temperature(self, code: np.ndarray | int) -> np.ndarray:
        """The temperature a reading stands for, K (``zero_K + code * lsb_K``)."""
        return self.zero_K + np.asarray(code, dtype=np.float64) * self.lsb_K
