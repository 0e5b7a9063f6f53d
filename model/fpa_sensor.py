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

from irnuc.model.validate import ConfigError, check_array, check_int, check_scalar

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

    def arrays(self) -> dict[str, np.ndarray]:
        """The sensor's settings as the arrays a frame file stores (``fpa_sensor_<field>``)."""
        return {"fpa_sensor_bits": np.int64(self.bits), "fpa_sensor_lsb_K": np.float64(self.lsb_K),
                "fpa_sensor_zero_K": np.float64(self.zero_K),
                "fpa_sensor_offset_K": np.float64(self.offset_K),
                "fpa_sensor_noise_K": np.float64(self.noise_K)}

    @classmethod
    def from_dict(cls, table: dict, path: str = "fpa_sensor") -> FpaSensor:
        """A sensor from a TOML table (keys of the dataclass; unknown keys refused)."""
        known = tuple(cls.__dataclass_fields__)
        if not isinstance(table, dict):
            raise ConfigError(f"{path} = {table!r} must be a table")
        for key in table:
            if key not in known:
                raise ConfigError(f"{path}.{key} is not a known field (known here: "
                                  f"{', '.join(known)})")
        try:
            return cls(**{k: table[k] for k in known if k in table})
        except ConfigError as exc:  # named by where the table is (sequence.fpa_sensor.bits)
            raise ConfigError(str(exc).replace("fpa_sensor.", f"{path}.", 1)) from None


#: Nominal frame rate of a plain run (no sequence), Hz: its frames are stamped n / rate.
PLAIN_FRAME_RATE = 30.0


def frame_fields(time_s: np.ndarray, fpa_K: np.ndarray, T_cam_K: np.ndarray,
                 scene_K: np.ndarray, shutter: np.ndarray, sensor: FpaSensor,
                 seed: int = 0) -> dict[str, np.ndarray]:
    """The per-frame fields (:data:`FRAME_FIELDS`) of N frames, with the sensor's readings.

    Parameters
    ----------
    time_s, fpa_K, T_cam_K, scene_K : ndarray
        (N,) time (s), FPA, housing and scene temperature (K) of each frame.
    shutter : ndarray
        (N,) bool, True while the shutter is closed.
    sensor : FpaSensor
        The on-die sensor; its readings are drawn from ``seed``.
    """
    n = np.shape(time_s)[0]
    fields = {"time_s": time_s, "fpa_K": fpa_K, "T_cam_K": T_cam_K, "scene_K": scene_K,
              "shutter": shutter}
    out = {}
    for name, value in fields.items():
        arr = np.asarray(value, dtype=FRAME_FIELDS[name][0])
        if arr.shape != (n,):
            raise ConfigError(f"{name} has shape {arr.shape}; expected ({n},)")
        out[name] = arr
    out["fpa_reading"] = sensor.read(out["fpa_K"], seed=seed) if n else np.empty(0, np.int64)
    return {name: out[name] for name in FRAME_FIELDS}


def constant_fields(scene_K: np.ndarray, T_substrate: float, T_cam: float,
                    sensor: FpaSensor | None = None, seed: int = 0,
                    frame_rate: float = PLAIN_FRAME_RATE) -> dict[str, np.ndarray]:
    """The per-frame fields of a plain run: constant FPA and housing temperatures (K),
    shutter open, frames ``frame_rate`` (Hz) apart."""
    n = np.shape(scene_K)[0]
    return frame_fields(np.arange(n) / frame_rate, np.full(n, float(T_substrate)),
                        np.full(n, float(T_cam)), np.asarray(scene_K, dtype=np.float64),
                        np.zeros(n, bool), sensor or FpaSensor(), seed)
