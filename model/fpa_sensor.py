"""The camera's temperature sensors (the on-die FPA sensor, the housing sensor) and the
per-frame fields every frame file carries.

A camera's correction hardware never sees the true focal-plane (substrate) temperature:
it sees the reading of a temperature sensor on the die, an unsigned code of ``bits`` bits
with a step of ``lsb_K`` kelvin, code 0 at ``zero_K``. The reading is what a
temperature-dependent correction method (``tc_offset``, ``table_interp``) evaluates, so
the golden model, the RTL and the calibration all take this integer code, never a float.
A second sensor reads the housing (or the lens, or the shutter: ``node``) the same way.
Either may lag what it measures (``lag_s``: a first-order lag, exact between frames).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from irnuc.model.validate import ConfigError, check_array, check_choice, check_int, check_scalar

#: Per-frame fields stored with the codes of every frame file (plain runs store them
#: constant): name -> (dtype, unit, meaning).
FRAME_FIELDS: dict[str, tuple[str, str, str]] = {
    "time_s": ("float64", "s", "time of the frame since the start of the sequence"),
    "fpa_K": ("float64", "K", "true FPA (substrate) temperature"),
    "fpa_reading": ("int64", "code", "reading of the on-die FPA temperature sensor"),
    "T_cam_K": ("float64", "K", "housing temperature (the optics' too unless lens_K differs)"),
    "scene_K": ("float64", "K", "scene base temperature"),
    "shutter": ("bool", "", "True while the shutter is closed (uniform source)"),
    "ambient_K": ("float64", "K", "ambient (air) temperature around the camera"),
    "lens_K": ("float64", "K", "lens temperature"),
    "shutter_K": ("float64", "K", "shutter temperature"),
    "housing_reading": ("int64", "code", "reading of the housing (lens, shutter) temperature sensor"),
}

#: Stream keys that separate the sensors' noise draws from the other seeded stages.
SENSOR_STREAM = 0x66706173
HOUSING_SENSOR_STREAM = 0x686F7573
#: The nodes a housing sensor may be mounted on (its ``node``) and their frame fields.
SENSOR_NODES = {"housing": "T_cam_K", "lens": "lens_K", "shutter": "shutter_K"}


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
    lag_s : float
        Time constant of the sensor's own lag behind what it measures, s (0: none).
    """

    bits: int = 14
    lsb_K: float = 0.01
    zero_K: float = 223.15
    offset_K: float = 0.0
    noise_K: float = 0.0
    lag_s: float = 0.0

    #: Prefix of its fields (messages, frame-file keys) and the stream of its noise.
    PREFIX = "fpa_sensor"
    STREAM = SENSOR_STREAM

    def __post_init__(self) -> None:
        p = self.PREFIX
        check_int(f"{p}.bits", self.bits, 1, 24)
        check_scalar(f"{p}.lsb_K", self.lsb_K, 0.0, 100.0, lo_open=True, unit="K")
        check_scalar(f"{p}.zero_K", self.zero_K, 0.0, 1000.0, unit="K")
        check_scalar(f"{p}.offset_K", self.offset_K, -100.0, 100.0, unit="K")
        check_scalar(f"{p}.noise_K", self.noise_K, 0.0, 100.0, unit="K")
        check_scalar(f"{p}.lag_s", self.lag_s, 0.0, 1e8, unit="s")

    @property
    def max_code(self) -> int:
        return (1 << self.bits) - 1

    def read(self, temp_K: np.ndarray | float, seed: int = 0, first_frame: int = 0,
             warn: str = "") -> np.ndarray:
        """Readings (int64 codes, clamped to [0, 2^bits - 1]) of temperatures, K.

        Frame ``first_frame + i`` draws its noise from its own stream of ``seed``, so the
        readings do not depend on how a sequence is split into chunks. With ``warn`` (a
        name for the message), a RuntimeWarning counts the readings clamped at either end.
        """
        t = np.atleast_1d(check_array("temperature", temp_K, 0.0, None, lo_open=True, unit="K"))
        t = t + self.offset_K
        if self.noise_K > 0.0:
            noise = np.array([
                np.random.default_rng(np.random.SeedSequence(
                    seed, spawn_key=(self.STREAM, first_frame + i))).standard_normal()
                for i in range(t.size)])
            t = t + self.noise_K * noise.reshape(t.shape)
        code = np.rint((t - self.zero_K) / self.lsb_K)
        clamped = int(np.count_nonzero((code < 0) | (code > self.max_code)))
        if clamped and warn:
            lo, hi = self.temperature(0), self.temperature(self.max_code)
            warnings.warn(f"{warn}: {clamped} of {t.size} reading(s) clamped at the sensor's "
                          f"range {float(lo):.4g}..{float(hi):.4g} K ({self.PREFIX}.zero_K, "
                          f".lsb_K, .bits)", RuntimeWarning, stacklevel=2)
        return np.clip(code, 0, self.max_code).astype(np.int64)

    def sensed(self, time_s: np.ndarray, temp_K: np.ndarray) -> np.ndarray:
        """The temperature the sensor follows through its own lag (exact between frames,
        the measured temperature linear between them), K."""
        if self.lag_s <= 0.0 or np.size(temp_K) < 2:
            return np.asarray(temp_K, dtype=np.float64)
        from irnuc.model.profiles import first_order_lag

        return first_order_lag(np.asarray(time_s, np.float64), np.asarray(temp_K, np.float64),
                               self.lag_s, None)

    def temperature(self, code: np.ndarray | int) -> np.ndarray:
        """The temperature a reading stands for, K (``zero_K + code * lsb_K``)."""
        return self.zero_K + np.asarray(code, dtype=np.float64) * self.lsb_K

    def arrays(self) -> dict[str, np.ndarray]:
        """The sensor's settings as the arrays a frame file stores (``<prefix>_<field>``)."""
        p = self.PREFIX
        return {f"{p}_bits": np.int64(self.bits), f"{p}_lsb_K": np.float64(self.lsb_K),
                f"{p}_zero_K": np.float64(self.zero_K),
                f"{p}_offset_K": np.float64(self.offset_K),
                f"{p}_noise_K": np.float64(self.noise_K), f"{p}_lag_s": np.float64(self.lag_s)}

    @classmethod
    def from_dict(cls, table: dict, path: str | None = None) -> FpaSensor:
        """A sensor from a TOML table (keys of the dataclass; unknown keys refused)."""
        from irnuc.common.schema import nearest

        path = path or cls.PREFIX
        known = tuple(cls.__dataclass_fields__)
        if not isinstance(table, dict):
            raise ConfigError(f"{path} = {table!r} must be a table")
        for key in table:
            if key not in known:
                raise ConfigError(f"{path}.{key} is not a known field{nearest(str(key), known)}"
                                  f" (known here: {', '.join(known)})")
        try:
            return cls(**{k: table[k] for k in known if k in table})
        except ConfigError as exc:
            msg = str(exc)
            if path != cls.PREFIX and msg.startswith(cls.PREFIX + "."):
                msg = path + msg[len(cls.PREFIX):]
            raise ConfigError(msg) from None


@dataclass(frozen=True)
class HousingSensor(FpaSensor):
    """A temperature sensor on the housing (``node``: ``housing``, ``lens`` or ``shutter``),
    read like the FPA sensor (``housing_reading``)."""

    node: str = "housing"

    PREFIX = "housing_sensor"
    STREAM = HOUSING_SENSOR_STREAM

    def __post_init__(self) -> None:
        super().__post_init__()
        check_choice(f"{self.PREFIX}.node", self.node, tuple(SENSOR_NODES))

    def arrays(self) -> dict[str, np.ndarray]:
        return {**super().arrays(), f"{self.PREFIX}_node": np.array(self.node)}


#: Nominal frame rate of a plain run (no sequence), Hz: its frames are stamped n / rate.
PLAIN_FRAME_RATE = 30.0


def frame_fields(time_s: np.ndarray, fpa_K: np.ndarray, T_cam_K: np.ndarray,
                 scene_K: np.ndarray, shutter: np.ndarray, sensor: FpaSensor,
                 seed: int = 0, *, ambient_K: np.ndarray | None = None,
                 lens_K: np.ndarray | None = None, shutter_K: np.ndarray | None = None,
                 housing_sensor: HousingSensor | None = None) -> dict[str, np.ndarray]:
    """The per-frame fields (:data:`FRAME_FIELDS`) of N frames, with the sensors' readings.

    Parameters
    ----------
    time_s, fpa_K, T_cam_K, scene_K : ndarray
        (N,) time (s), FPA, housing and scene temperature (K) of each frame.
    shutter : ndarray
        (N,) bool, True while the shutter is closed.
    sensor : FpaSensor
        The on-die sensor; its readings are drawn from ``seed``.
    ambient_K, lens_K, shutter_K : ndarray, optional
        (N,) K; default the housing's (a camera in equilibrium with its surroundings).
    housing_sensor : HousingSensor, optional
        The housing sensor (default :class:`HousingSensor`), reading its ``node``.

    A reading clamped at its sensor's range is counted in a RuntimeWarning.
    """
    n = np.shape(time_s)[0]
    fields = {"time_s": time_s, "fpa_K": fpa_K, "T_cam_K": T_cam_K, "scene_K": scene_K,
              "shutter": shutter,
              "ambient_K": T_cam_K if ambient_K is None else ambient_K,
              "lens_K": T_cam_K if lens_K is None else lens_K,
              "shutter_K": T_cam_K if shutter_K is None else shutter_K}
    out = {}
    for name, value in fields.items():
        arr = np.asarray(value, dtype=FRAME_FIELDS[name][0])
        if arr.shape != (n,):
            raise ConfigError(f"{name} has shape {arr.shape}; expected ({n},)")
        out[name] = arr
    hs = housing_sensor or HousingSensor()
    if n:
        out["fpa_reading"] = sensor.read(sensor.sensed(out["time_s"], out["fpa_K"]), seed=seed,
                                         warn="the FPA temperature sensor")
        node = out[SENSOR_NODES[hs.node]]
        out["housing_reading"] = hs.read(hs.sensed(out["time_s"], node), seed=seed,
                                         warn=f"the {hs.node} temperature sensor")
    else:
        out["fpa_reading"] = np.empty(0, np.int64)
        out["housing_reading"] = np.empty(0, np.int64)
    return {name: out[name] for name in FRAME_FIELDS}


def constant_fields(scene_K: np.ndarray, T_substrate: float, T_cam: float,
                    sensor: FpaSensor | None = None, seed: int = 0,
                    frame_rate: float = PLAIN_FRAME_RATE,
                    housing_sensor: HousingSensor | None = None) -> dict[str, np.ndarray]:
    """The per-frame fields of a plain run: constant FPA and housing temperatures (K; the
    ambient, lens and shutter at the housing's), shutter open, frames ``frame_rate`` (Hz)
    apart."""
    n = np.shape(scene_K)[0]
    return frame_fields(np.arange(n) / frame_rate, np.full(n, float(T_substrate)),
                        np.full(n, float(T_cam)), np.asarray(scene_K, dtype=np.float64),
                        np.zeros(n, bool), sensor or FpaSensor(), seed,
                        housing_sensor=housing_sensor)
