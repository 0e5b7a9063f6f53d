"""Drift sequences: frames in time order while the FPA, the housing and the scene change.

A sequence (a TOML ``[sequence]`` table, :func:`load_sequence`) gives a frame rate and a
duration, a temperature profile (:mod:`model.profiles`) for the FPA (substrate), the
housing / optics (``T_cam``) and the scene, optionally a shutter and the on-die FPA
temperature sensor. :func:`iter_sequence` makes its frames chunk by chunk through the
configured sensor (:class:`model.pipeline.Pipeline`), the stages that depend on the FPA or
housing temperature run per frame only when those vary, and the bolometer state goes from
frame to frame as the thermal model says (``thermal``, docs/sequences.md):

* ``steady``: every frame in equilibrium with its own scene and temperatures;
* ``lagged``: every pixel's temperature before its bias pulse follows its equilibrium
  through its own thermal time constant C/g, exactly between pulses; the pulse as steady;
* ``transient``: the time-domain model (:mod:`model.transient`), its state carried across
  chunks (the bias pulse at the end of each frame period);
* ``auto`` (default): ``steady`` when the part of a change that a pixel still remembers one
  frame later, exp(-period/tau) times the largest change between two frames, is below
  ``steady_tolerance`` (K), else ``lagged``.

:func:`write_sequence` streams the frames into a frame file (:mod:`irnuc.common.framefile`)
so a sequence of any length runs in the memory of one chunk; :func:`simulate_sequence`
returns them in memory.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.common.schema import nearest, read_toml
from irnuc.model import pipeline as _pl
from irnuc.model.config import SCHEMA, apply_overrides
from irnuc.model.core import bolometer as _kb
from irnuc.model.fpa_sensor import FRAME_FIELDS, FpaSensor, HousingSensor, frame_fields
from irnuc.model.profiles import Profile, check_range, parse_profile
from irnuc.model.scenes import Scene, check_temps
from irnuc.model.thermal import ThermalNetwork
from irnuc.model.validate import (
    ConfigError,
    check_choice,
    check_frame_period,
    check_int,
    check_scalar,
)

#: The thermal models a sequence may ask for (``auto`` chooses one of the first two).
THERMAL_CHOICES = ("auto", "steady", "lagged", "transient")
SEQUENCE_KEYS = ("frame_rate", "duration", "thermal", "steady_tolerance", "chunk_frames",
                 "fpa", "housing", "scene", "shutter", "fpa_sensor", "transient", "ambient",
                 "network", "housing_sensor", "record_every", "description")
SHUTTER_KEYS = ("every", "frames", "at", "start", "temperature")
#: The environment's temperature range (the sensor schema's), K.
ENV_RANGE = (SCHEMA["environment.T_substrate"].lo, SCHEMA["environment.T_substrate"].hi)
MAX_FRAMES = 10_000_000
#: A transient sequence runs warm-up frames until exp(-frames period / tau) < e^-12.
WARMUP_TAU = 12.0


@dataclass(frozen=True)
class Shutter:
    """A shutter closed for ``frames`` frames at each closing: every ``every`` s from
    ``start`` s, and at the times ``at`` (s); while closed the array sees a uniform source
    at ``temperature`` (a profile; None: the housing temperature)."""

    frames: int
    every: float | None = None
    at: tuple[float, ...] = ()
    start: float = 0.0
    temperature: Profile | None = None


@dataclass(frozen=True)
class DriftSequence:
    """A checked drift sequence (see the module docstring); :func:`load_sequence`.

    ``fpa`` and ``housing`` may be None when the ``network`` gives them (driven by the
    ``ambient``); ``record_every`` keeps one frame in so many (the camera still runs at
    ``frame_rate``: the steady thermal model only)."""

    frame_rate: float
    duration: float
    fpa: Profile | None
    housing: Profile | None
    scene: Profile
    shutter: Shutter | None = None
    fpa_sensor: FpaSensor = field(default_factory=FpaSensor)
    thermal: str = "auto"
    steady_tolerance: float = 1e-3
    chunk_frames: int | None = None
    transient: Mapping[str, Any] = field(default_factory=dict)
    source: str = "sequence"
    ambient: Profile | None = None
    network: ThermalNetwork | None = None
    housing_sensor: HousingSensor = field(default_factory=HousingSensor)
    record_every: int = 1

    @property
    def n_frames(self) -> int:
        """Frames of the sequence: round(duration frame_rate / record_every), at least 1."""
        return max(1, round(self.duration * self.frame_rate / self.record_every))

    @property
    def frame_period(self) -> float:
        """The camera's frame period, s (every pixel pulsed once per period)."""
        return 1.0 / self.frame_rate

    @property
    def record_rate(self) -> float:
        """Frames per second kept in the file, Hz."""
        return self.frame_rate / self.record_every

    def schedule(self) -> Schedule:
        """The per-frame temperatures and shutter, every range checked (ConfigError)."""
        n = self.n_frames
        t = np.arange(n) / self.record_rate
        nodes = self._nodes(t)
        housing, fpa = nodes["housing"], nodes["fpa"]
        scene = self.scene.values(t)
        check_range(self.scene.path, self.scene, scene, t, 1e-300, 1e5, "a scene temperature")
        closed = np.zeros(n, bool)
        T_sh = nodes["shutter"]
        if self.shutter is not None:
            closed = shutter_frames(self.shutter, self.record_rate, n)
            if self.shutter.temperature is not None:
                T_sh = self.shutter.temperature.values(t)
                check_range(self.shutter.temperature.path, self.shutter.temperature, T_sh, t,
                            *ENV_RANGE, "the shutter's temperature")
        return Schedule(t, fpa, housing, scene, closed, T_sh, nodes["ambient"], nodes["lens"])

    def _nodes(self, t: np.ndarray) -> dict[str, np.ndarray]:
        """Ambient, housing, FPA, lens and shutter temperature at the frame times (K): the
        explicit profiles, the lags in order, then the network's nodes; ranges checked."""
        vals: dict[str, np.ndarray] = {}
        where = {"ambient": "the ambient temperature", "housing": "environment.T_cam",
                 "fpa": "environment.T_substrate"}
        profiles = {"ambient": self.ambient, "housing": self.housing, "fpa": self.fpa}

        def put(name: str, prof: Profile, v: np.ndarray) -> None:
            check_range(prof.path, prof, v, t, *ENV_RANGE, where[name])
            vals[name] = v

        for name, prof in profiles.items():
            if prof is not None and prof.kind != "lag":
                put(name, prof, prof.values(t))

        def lags() -> None:
            for _ in range(2):
                for name, prof in profiles.items():
                    if prof is None or prof.kind != "lag" or name in vals:
                        continue
                    src = prof.params.get("follows") or LAG_DEFAULT[name]
                    if src in vals:
                        put(name, prof, prof.values(t, follow=vals[src]))

        lags()
        net: dict[str, np.ndarray] = {}
        if self.network is not None:
            net = self.network.solve(t, vals["ambient"], vals.get("housing"))
            for name in ("housing", "fpa"):
                if name not in vals and profiles[name] is None:
                    check_range(self.network.path, Profile("network", {}, self.network.path),
                                net[name], t, *ENV_RANGE, where[name])
                    vals[name] = net[name]
            lags()
        for name in ("housing", "fpa"):
            if name not in vals:
                raise ConfigError(f"sequence.{name}: its temperature is not given (a profile, or "
                                  "[sequence.network] with [sequence.ambient]), or a lag "
                                  "follows a temperature that is not given")
        vals.setdefault("ambient", vals["housing"])
        for k in ("lens", "shutter"):
            vals[k] = net[k] if net else vals["housing"]
            check_range(f"sequence.network.{k}_tau", Profile("network", {}, "sequence.network"),
                        vals[k], t, *ENV_RANGE, f"the {k}'s temperature")
        return vals

    def to_dict(self) -> dict[str, Any]:
        """The sequence as plain data (for a frame file's ``sequence_json``)."""
        def prof(p: Profile | None) -> Any:
            if p is None:
                return None
            return {"profile": p.kind, **{k: (v.tolist() if isinstance(v, np.ndarray) else v)
                                          for k, v in p.params.items()}}

        sh = self.shutter
        return {"frame_rate": self.frame_rate, "duration": self.duration,
                "record_every": self.record_every,
                "frames": self.n_frames, "thermal": self.thermal,
                "steady_tolerance": self.steady_tolerance, "fpa": prof(self.fpa),
                "housing": prof(self.housing), "scene": prof(self.scene),
                "ambient": prof(self.ambient),
                "network": None if self.network is None else self.network.to_dict(),
                "shutter": None if sh is None else {
                    "frames": sh.frames, "every": sh.every, "at": list(sh.at),
                    "start": sh.start, "temperature": prof(sh.temperature)},
                "fpa_sensor": {k: getattr(self.fpa_sensor, k)
                               for k in FpaSensor.__dataclass_fields__},
                "housing_sensor": {k: getattr(self.housing_sensor, k)
                                   for k in HousingSensor.__dataclass_fields__},
                "transient": dict(self.transient), "source": self.source}


#: What a ``lag`` profile follows by default: the FPA the housing, the housing the ambient.
LAG_DEFAULT = {"fpa": "housing", "housing": "ambient", "ambient": ""}


@dataclass
class Schedule:
    """Per-frame time (s), FPA, housing and scene temperature (K), shutter closed (bool),
    the shutter's temperature (K), the ambient's and the lens's (K) of a sequence: arrays of
    one value per frame."""

    time_s: np.ndarray
    fpa_K: np.ndarray
    T_cam_K: np.ndarray
    scene_K: np.ndarray
    shutter: np.ndarray
    T_shutter_K: np.ndarray
    ambient_K: np.ndarray | None = None
    lens_K: np.ndarray | None = None

    def env(self) -> dict[str, np.ndarray]:
        """The pipeline's per-frame environment (:data:`model.pipeline.ENV_FIELDS`)."""
        env = {"T_substrate": self.fpa_K, "T_cam": self.T_cam_K, "shutter": self.shutter,
               "T_shutter": self.T_shutter_K}
        if self.lens_K is not None and np.any(self.lens_K != self.T_cam_K):
            env["T_lens"] = self.lens_K
        return env

    def fields(self, sensor: FpaSensor, seed: int,
               housing_sensor: HousingSensor | None = None) -> dict[str, np.ndarray]:
        """The frame file's per-frame fields (:data:`model.fpa_sensor.FRAME_FIELDS`)."""
        return frame_fields(self.time_s, self.fpa_K, self.T_cam_K, self.scene_K, self.shutter,
                            sensor, seed, ambient_K=self.ambient_K, lens_K=self.lens_K,
                            shutter_K=self.T_shutter_K, housing_sensor=housing_sensor)

    def largest_change(self) -> float:
        """Largest change between two frames of anything a pixel sees, K: the scene (the
        shutter's temperature while closed), the housing, the lens, the FPA."""
        seen = np.where(self.shutter, self.T_shutter_K, self.scene_K)
        series = [seen, self.T_cam_K, self.fpa_K]
        if self.lens_K is not None:
            series.append(self.lens_K)
        steps = [np.abs(np.diff(x)).max(initial=0.0) for x in series]
        return float(max(steps))


def shutter_frames(shutter: Shutter, frame_rate: float, n: int) -> np.ndarray:
    """(n,) bool: True for the frames during which the shutter is closed. A closing at
    time t closes the ``frames`` frames from the first frame at or after t."""
    closed = np.zeros(n, bool)
    times = list(shutter.at)
    if shutter.every is not None:
        k_max = math.floor((n / frame_rate - shutter.start) / shutter.every + 1e-9)
        times += [shutter.start + k * shutter.every for k in range(k_max + 1)]
    for tc in times:
        first = math.ceil(tc * frame_rate - 1e-9)
        if first < n:
            closed[first:first + shutter.frames] = True
    return closed


# ---- reading a sequence ---------------------------------------------------------------------

def _check_keys(table: Mapping[str, Any], path: str, known: Sequence[str]) -> None:
    for key in table:
        if key not in known:
            raise ConfigError(f"{path}.{key} is not a known field{nearest(str(key), known)} "
                              f"(known here: {', '.join(known)})")


def _shutter(table: Any, frame_rate: float, base_dir: Path | None) -> Shutter:
    path = "sequence.shutter"
    if not isinstance(table, Mapping):
        raise ConfigError(f"{path} = {table!r} must be a table")
    _check_keys(table, path, SHUTTER_KEYS)
    if "frames" not in table:
        raise ConfigError(f"{path}.frames is required (frames closed at each closing)")
    frames = check_int(f"{path}.frames", table["frames"], 1, MAX_FRAMES)
    every = None
    if "every" in table:
        every = check_scalar(f"{path}.every", table["every"], 0.0, 1e9, lo_open=True, unit="s")
        closed_s = frames / frame_rate
        if closed_s >= every:
            raise ConfigError(
                f"{path}.frames = {frames} ({closed_s:g} s at {frame_rate:g} Hz) is longer "
                f"than its period {path}.every = {every:g} s; it would never open")
    at = table.get("at", [])
    if not isinstance(at, list):
        raise ConfigError(f"{path}.at = {at!r} must be a list of times (s)")
    at_s = tuple(check_scalar(f"{path}.at[{i}]", v, 0.0, 1e9, unit="s") for i, v in enumerate(at))
    if every is None and not at_s:
        raise ConfigError(f"{path}: give every (s) or at (a list of times, s)")
    start = check_scalar(f"{path}.start", table.get("start", 0.0), 0.0, 1e9, unit="s")
    temp = None
    if "temperature" in table:
        temp = parse_profile(table["temperature"], f"{path}.temperature", base_dir)
    return Shutter(frames, every, at_s, start, temp)


def _shutter_within(shutter: Shutter, frame_rate: float, duration: float) -> None:
    """ConfigError naming the key when a closing would come after the last frame (it
    would never close: the run would hold no shutter frame where one was asked for)."""
    n = max(1, round(duration * frame_rate))

    def first(t: float) -> int:  # as shutter_frames: the first frame at or after t
        return math.ceil(t * frame_rate - 1e-9)

    end = f"the last frame ({n} frames: sequence.duration = {duration:g} s at {frame_rate:g} Hz)"
    for i, t in enumerate(shutter.at):
        if first(t) >= n:
            raise ConfigError(f"sequence.shutter.at[{i}] = {t:g} s is after {end}; the shutter "
                              "would never close there")
    if shutter.every is not None and first(shutter.start) >= n:
        raise ConfigError(f"sequence.shutter.start = {shutter.start:g} s is after {end}; the "
                          "shutter would never close")


def sequence_from_dict(data: Mapping[str, Any], source: str = "sequence",
                       base_dir: Path | None = None) -> DriftSequence:
    """A :class:`DriftSequence` from a parsed TOML document holding a ``[sequence]`` table
    (or from that table itself); every key checked, unknown keys refused."""
    if not isinstance(data, Mapping):
        raise ConfigError(f"{source}: a sequence must be a table")
    table = data.get("sequence", data) if "sequence" in data else data
    extra = [k for k in data if k != "sequence"] if "sequence" in data else []
    if extra:
        raise ConfigError(f"{source}: {extra[0]} is not a known section (a sequence file "
                          "holds [sequence] and its sub-tables)")
    if not isinstance(table, Mapping):
        raise ConfigError(f"{source}: sequence must be a table")
    _check_keys(table, "sequence", SEQUENCE_KEYS)
    for key in ("frame_rate", "duration", "scene"):
        if key not in table:
            raise ConfigError(f"sequence.{key} is required")
    if "network" in table and "ambient" not in table:
        raise ConfigError("sequence.ambient is required with sequence.network (the network's "
                          "housing follows the ambient)")
    for key in ("fpa", "housing"):
        if key not in table and "network" not in table:
            raise ConfigError(f"sequence.{key} is required (or [sequence.network] with "
                              "[sequence.ambient], which gives it)")
    rate = check_scalar("sequence.frame_rate", table["frame_rate"], 0.0, 1e5, lo_open=True,
                        unit="Hz")
    duration = check_scalar("sequence.duration", table["duration"], 0.0, 1e7, lo_open=True,
                            unit="s")
    if duration * rate > MAX_FRAMES:
        raise ConfigError(f"sequence.duration x sequence.frame_rate = {duration * rate:.3g} "
                          f"frames; at most {MAX_FRAMES}")
    every = check_int("sequence.record_every", table.get("record_every", 1), 1, 1_000_000)
    if not isinstance(table.get("description", ""), str):
        raise ConfigError("sequence.description must be a string")
    profiles = {}
    for key in ("ambient", "housing", "fpa"):
        profiles[key] = (parse_profile(table[key], f"sequence.{key}", base_dir,
                                       allow_lag=key != "ambient") if key in table else None)
    _check_lags(profiles)
    network = (ThermalNetwork.from_table(table["network"], "sequence.network")
               if "network" in table else None)
    scene = parse_profile(table["scene"], "sequence.scene", base_dir)
    shutter = _shutter(table["shutter"], rate / every, base_dir) if "shutter" in table else None
    if shutter is not None:
        _shutter_within(shutter, rate / every, duration)
    sensor = FpaSensor.from_dict(dict(table.get("fpa_sensor", {})), "sequence.fpa_sensor")
    hsensor = HousingSensor.from_dict(dict(table.get("housing_sensor", {})),
                                      "sequence.housing_sensor")
    thermal = check_choice("sequence.thermal", table.get("thermal", "auto"), THERMAL_CHOICES)
    tol = check_scalar("sequence.steady_tolerance", table.get("steady_tolerance", 1e-3), 0.0,
                       100.0, unit="K")
    chunk = table.get("chunk_frames")
    if chunk is not None:
        chunk = check_int("sequence.chunk_frames", chunk, 1, 100_000)
    transient = table.get("transient", {})
    if not isinstance(transient, Mapping):
        raise ConfigError("sequence.transient must be a table (model.transient settings)")
    from irnuc.model.transient import TransientSettings

    allowed = [k for k in TransientSettings.__dataclass_fields__
               if k not in ("frame_period", "pulse_start")]
    _check_keys(transient, "sequence.transient", allowed)
    if every > 1 and thermal in ("lagged", "transient"):
        raise ConfigError(f"sequence.record_every = {every} needs the steady thermal model "
                          f"(sequence.thermal = {thermal!r} carries every frame's state)")
    seq = DriftSequence(rate, duration, profiles["fpa"], profiles["housing"], scene, shutter,
                        sensor, thermal, tol, chunk, dict(transient), source,
                        profiles["ambient"], network, hsensor, every)
    seq.schedule()  # every range, before any work
    return seq


def _check_lags(profiles: Mapping[str, Profile | None]) -> None:
    """A lag follows a temperature the sequence has, and no two follow each other."""
    follows = {}
    for name, prof in profiles.items():
        if prof is not None and prof.kind == "lag":
            src = prof.params.get("follows") or LAG_DEFAULT[name]
            allowed = {"fpa": ("housing", "ambient"), "housing": ("ambient", "fpa")}[name]
            if src not in allowed:
                raise ConfigError(f"{prof.path}.follows = {src!r}: a lag of the {name} follows "
                                  f"one of {', '.join(allowed)}")
            follows[name] = src
    if follows.get("fpa") == "housing" and follows.get("housing") == "fpa":
        raise ConfigError("sequence.fpa and sequence.housing follow each other (two lags): "
                          "give one of them a profile")


#: The named scenarios shipped with irnuc (``model/scenarios/NAME.toml``).
SCENARIO_DIR = Path(__file__).with_name("scenarios")


def scenario_names() -> list[str]:
    """Names of the shipped scenarios (``irnuc frames --sequence NAME``)."""
    return sorted(p.stem for p in SCENARIO_DIR.glob("*.toml"))


def load_sequence(path: str | Path, flag: str = "") -> DriftSequence:
    """A drift sequence from a TOML file, or a shipped scenario by its name (a bare name
    that is not a file: one of :func:`scenario_names`); a table CSV is read relative to the
    file."""
    p = Path(path)
    text = str(path)
    if not p.exists() and "/" not in text and "\\" not in text and not text.endswith(".toml"):
        names = scenario_names()
        if text not in names:
            raise ConfigError(f"{flag + ' ' if flag else ''}{text}: no such file, and not a "
                              f"scenario ({', '.join(names)}){nearest(text, names)}")
        p = SCENARIO_DIR / f"{text}.toml"  # a name from the list, never a path
    data = read_toml(p, flag)
    where = f"{flag} {p}" if flag else str(p)
    try:
        return sequence_from_dict(data, where, p.parent)
    except ConfigError as exc:
        raise ConfigError(f"{where}: {exc}") from None


# ---- the thermal model -------------------------------------------------------------------

def choose_thermal(cfg: Mapping[str, Any], seq: DriftSequence, sched: Schedule,
                   tau_max: float) -> tuple[str, str]:
    """(thermal model, why) for a sequence; ``tau_max`` the longest pixel C/g, s."""
    period = seq.frame_period
    memory = math.exp(-period / tau_max) if tau_max > 0 else 0.0
    # per frame of the camera (a file may keep one in record_every)
    change = sched.largest_change() / seq.record_every
    ramp = float(np.abs(np.diff(sched.fpa_K)).max(initial=0.0)) * seq.record_rate
    err = max(memory * change, tau_max * ramp)
    facts = (f"the pixels' thermal time constant (up to {tau_max * 1e3:.3g} ms) leaves "
             f"{memory:.3g} of a change in the next frame ({period * 1e3:.3g} ms later); the "
             f"largest change between frames is {change:.3g} K and the substrate moves at up "
             f"to {ramp:.3g} K/s (a pixel lags it by tau times that), so a frame remembers up "
             f"to {err:.3g} K of the ones before")
    if seq.record_every > 1:
        # one frame kept in record_every: only a frame with no memory of the ones before
        # can be made alone
        if seq.thermal == "auto" and err > seq.steady_tolerance:
            raise ConfigError(
                f"sequence.record_every = {seq.record_every}: the frames between those kept "
                f"carry the pixels' memory ({facts}), more than sequence.steady_tolerance = "
                f"{seq.steady_tolerance:g} K; record every frame")
        return "steady", (f"one frame kept in {seq.record_every}, each in the pulse train's "
                          "periodic state (the camera's own frames remember less than "
                          f"sequence.steady_tolerance = {seq.steady_tolerance:g} K)")
    if seq.thermal == "lagged" and cfg["bolometer"]["variant"] == "paper":
        raise ConfigError("sequence.thermal = 'lagged' needs bolometer.variant = "
                          "'equilibrium': the paper variant switches the scene on with the bias "
                          "pulse, so there is no rise before the pulse to carry over")
    if seq.thermal != "auto":
        return seq.thermal, f"asked for (sequence.thermal); {facts}"
    if cfg["bolometer"]["variant"] == "paper":
        return "steady", ("the paper variant switches the scene on with the bias pulse, so no "
                          "frame remembers the one before")
    if err <= seq.steady_tolerance:
        return "steady", (f"{facts}, within sequence.steady_tolerance = "
                          f"{seq.steady_tolerance:g} K: the steady model gives the same frames")
    return "lagged", (f"{facts}, more than sequence.steady_tolerance = "
                      f"{seq.steady_tolerance:g} K: the pixels' thermal memory is kept")


def transient_settings(cfg: Mapping[str, Any], seq: DriftSequence, tau_max: float) -> Any:
    """Settings of the ``transient`` model: the sequence's frame period, the bias pulse at
    the end of each frame, warm-up frames to the periodic state."""
    from irnuc.model.transient import TransientSettings

    period = seq.frame_period
    t_int = cfg["bolometer"]["t_int"]
    warm = min(1000, math.ceil(WARMUP_TAU * tau_max / period)) if tau_max > 0 else 0
    s = TransientSettings.from_any({"warmup_frames": warm, **seq.transient})
    return replace(s, frame_period=period, pulse_start=max(period - t_int, 0.0)).checked(t_int)


# ---- running a sequence ----------------------------------------------------------------------

@dataclass
class SequenceChunk:
    """Frames ``start`` to ``start + len(codes)`` of a sequence."""

    start: int
    codes: np.ndarray
    blind_codes: np.ndarray
    outputs: dict[str, Any]


@dataclass
class SequenceRun:
    """What a sequence run needs before its first frame (all checked)."""

    def per_chunk_products(self) -> set[str]:
        """The products made frame by frame in this run (the others: once per sensor)."""
        key = self.pipe.graph_key(self.schedule.env(), self.thermal)
        return {o for s in self.pipe.graph(key) if s.per_chunk for o in s.outputs}

    sequence: DriftSequence
    schedule: Schedule
    fields: dict[str, np.ndarray]
    pipe: _pl.Pipeline
    cfg: dict[str, Any]
    scene: Scene
    thermal: str
    thermal_reason: str
    transient: Any
    chunk_frames: int
    static: dict[str, Any]


def prepare(cfg: Mapping[str, Any], seq: DriftSequence, scene: str | Scene = "uniform", *,
            seed: int = 0, scene_params: Mapping[str, Any] | None = None) -> SequenceRun:
    """Check everything and configure the sensor of a sequence run (no frame made yet).

    The sensor's reference environment (the electro-thermal solve's reference, docs/model.md)
    is the middle of the sequence's FPA and housing ranges, so slow drifts stay on the
    solver's fast path.
    """
    cfg = _pl.checked_config(cfg)
    seed = check_int("seed", seed, 0, 2**63 - 1)
    if isinstance(scene, str):
        scene = Scene(scene, dict(scene_params or {}))
    check_frame_period(seq.frame_period, cfg["bolometer"]["t_int"],
                       what=f"{seq.source}: sequence.frame_rate = {seq.frame_rate:g} Hz")
    # the sequence's frame rate is the sensor's (every pixel is pulsed once per frame)
    cfg = _pl.checked_config(apply_overrides(cfg, {"readout.frame_rate": seq.frame_rate}))
    sched = seq.schedule()
    check_temps(sched.scene_K)
    mid = {"environment.T_substrate": float(0.5 * (sched.fpa_K.min() + sched.fpa_K.max())),
           "environment.T_cam": float(0.5 * (sched.T_cam_K.min() + sched.T_cam_K.max()))}
    pipe = _pl.Pipeline(apply_overrides(cfg, mid), seed)
    params = pipe.run(sched.scene_K[:0], ["params"])["params"]
    tau_max = float((params["C"] / params["g"]).max())
    thermal, why = choose_thermal(cfg, seq, sched, tau_max)
    transient = transient_settings(cfg, seq, tau_max) if thermal == "transient" else None
    chunk = seq.chunk_frames or int(cfg["run"]["chunk_frames"])
    return SequenceRun(seq, sched, sched.fields(seq.fpa_sensor, seed, seq.housing_sensor), pipe,
                       cfg, scene,
                       thermal, why, transient, chunk, {"tau_max_s": tau_max})


def iter_sequence(run: SequenceRun, outputs: Sequence[str] = ("codes",),
                  progress: Callable[[int, int], None] | None = None
                  ) -> Iterator[SequenceChunk]:
    """The frames of a prepared sequence (:func:`prepare`), chunk by chunk, in time order.

    ``outputs``: keys of :data:`model.pipeline.OUTPUTS`; ``codes`` and ``blind_codes``
    always come (in :class:`SequenceChunk`), the others in ``SequenceChunk.outputs``.
    """
    unknown = [o for o in outputs if o not in _pl.OUTPUTS]
    if unknown:
        raise ConfigError(f"outputs: unknown name(s) {unknown}; known {sorted(_pl.OUTPUTS)}")
    products = list(dict.fromkeys(["codes", "blind_codes", "status", "dT",
                                   *(_pl.OUTPUTS[o] for o in outputs)]))
    sched = run.schedule
    for start, values in run.pipe.iter_chunks(
            sched.scene_K, products, run.scene, env=sched.env(), thermal=run.thermal,
            frame_period=run.sequence.frame_period, transient=run.transient,
            chunk_frames=run.chunk_frames, progress=progress):
        yield SequenceChunk(start, values["codes"], values["blind_codes"],
                            {o: values[_pl.OUTPUTS[o]] for o in outputs} | {
                                "status": values["status"], "dT": values["dT"]})


class Diagnostics:
    """The diagnostics of :func:`model.pipeline.simulate`, accumulated chunk by chunk."""

    def __init__(self, layout: Any, adc_bits: int) -> None:
        rs, cs = layout.active_slice
        self.window = (rs.start, rs.stop, cs.start, cs.stop)
        self.top = (1 << adc_bits) - 1
        self.lo, self.hi, self.total, self.count = math.inf, -math.inf, 0.0, 0
        self.fail = np.zeros(4, np.int64)
        self.clipped = [0, 0]

    def add(self, codes: np.ndarray, status: np.ndarray, dT: np.ndarray) -> None:
        from irnuc.model.core.stream import frame_statistics

        if np.count_nonzero(status):
            self.fail += np.bincount(status.reshape(-1), minlength=4)[:4]
        lo, hi, total, count, n_low, n_high = frame_statistics(dT, status, *self.window,
                                                               codes, self.top)
        if count:
            self.lo, self.hi = min(self.lo, lo), max(self.hi, hi)
            self.total += total
            self.count += count
        self.clipped[0] += int(n_low)
        self.clipped[1] += int(n_high)

    def result(self) -> dict[str, Any]:
        return {"temperature_rise_K": {"min": self.lo if self.count else math.nan,
                                       "mean": self.total / self.count if self.count else math.nan,
                                       "max": self.hi if self.count else math.nan},
                "solver_failures": {"no_convergence": int(self.fail[_kb.STATUS_NO_CONVERGENCE]),
                                    "runaway": int(self.fail[_kb.STATUS_RUNAWAY]),
                                    "invalid": int(self.fail[_kb.STATUS_INVALID])},
                "clipped_low": self.clipped[0], "clipped_high": self.clipped[1]}


@dataclass
class SequenceFrames(_pl.Frames):
    """:class:`model.pipeline.Frames` of a sequence, with its per-frame ``fields``
    (:data:`model.fpa_sensor.FRAME_FIELDS`), the sequence and the thermal model used."""

    fields: dict[str, np.ndarray] = field(default_factory=dict)
    sequence: DriftSequence | None = None
    thermal: str = "steady"
    thermal_reason: str = ""


def _frames(run: SequenceRun, codes: Any, blind: Any, outputs: dict[str, Any],
            diagnostics: dict[str, Any], counts: dict[str, int]) -> SequenceFrames:
    static = run.pipe.run(run.schedule.scene_K[:0], ["defects", "reference_positions"])
    d = static["defects"]
    diagnostics = {**diagnostics, "thermal": run.thermal, "thermal_reason": run.thermal_reason}
    return SequenceFrames(
        codes=codes, temps=run.schedule.scene_K, defect_kind=d.kind, defect_pattern=d.pattern,
        adc_bits=run.cfg["adc"]["bits"], config=dict(run.cfg), seed=run.pipe.seed,
        scene=run.scene, outputs=outputs, diagnostics=diagnostics, counts=counts,
        blind_codes=blind, blind_positions=static["reference_positions"], fields=run.fields,
        sequence=run.sequence, thermal=run.thermal, thermal_reason=run.thermal_reason)


def simulate_sequence(cfg: Mapping[str, Any], seq: DriftSequence, scene: str | Scene = "uniform",
                      *, seed: int = 0, outputs: Sequence[str] = ("codes",),
                      scene_params: Mapping[str, Any] | None = None,
                      progress: Callable[[int, int], None] | None = None) -> SequenceFrames:
    """The frames of a drift sequence, in memory (:func:`write_sequence` streams to disk).

    Parameters
    ----------
    cfg : dict
        A validated sensor configuration (``environment`` is replaced by the sequence's).
    seq : DriftSequence
        From :func:`load_sequence` or :func:`sequence_from_dict`.
    scene, scene_params : as :func:`model.simulate`; the sequence gives the base temperature.
    seed : int
        Seed of every random draw (spread, defects, noise, the FPA sensor's noise).
    outputs : sequence of str
        Keys of :data:`model.pipeline.OUTPUTS`.
    """
    run = prepare(cfg, seq, scene, seed=seed, scene_params=scene_params)
    _pl.check_simulation_memory(run.cfg, seq.n_frames, outputs,
                                what=f"{seq.source}: {seq.n_frames} frame(s) in memory")
    before = dict(run.pipe.counts)
    parts: dict[str, list] = {}
    static: dict[str, Any] = {}
    per_chunk = run.per_chunk_products()
    diag = Diagnostics(run.pipe.layout, run.cfg["adc"]["bits"])
    for ch in iter_sequence(run, outputs, progress):
        diag.add(ch.codes, ch.outputs["status"], ch.outputs["dT"])
        for key, value in (("codes", ch.codes), ("blind_codes", ch.blind_codes),
                           *((o, ch.outputs[o]) for o in outputs if o != "codes")):
            if key in ("codes", "blind_codes") or _pl.OUTPUTS[key] in per_chunk:
                parts.setdefault(key, []).append(value)
            else:  # a product of the sensor, not of the frames: once (cos4, params, ...)
                static.setdefault(key, value)
    joined = {k: np.concatenate(v) for k, v in parts.items()} | static
    counts = {k: v - before.get(k, 0) for k, v in run.pipe.counts.items()
              if v - before.get(k, 0)}
    return _frames(run, joined["codes"], joined["blind_codes"],
                   {o: joined[o] for o in outputs}, diag.result(), counts)


def file_arrays(fr: _pl.Frames, fields: Mapping[str, np.ndarray], sensor: FpaSensor,
                frame_rate: float, extra: Mapping[str, Any] | None = None,
                housing_sensor: HousingSensor | None = None) -> dict[str, Any]:
    """Every array of a frame file but the codes (docs/sequences.md, "File format");
    ``frame_rate``: the frames per second of the file."""
    from irnuc.common.framefile import FORMAT_VERSION

    f = fr.config["fpa"]
    origin = (f["blind"][0] + f["boundary"][0], f["blind"][2] + f["boundary"][2])
    missing = [k for k in FRAME_FIELDS if k not in fields]
    if missing:
        raise ConfigError(f"frame file: missing field(s) {missing}")
    return {
        "format_version": np.int64(FORMAT_VERSION),
        "temps": np.asarray(fields["scene_K"], dtype=np.float64),
        **{k: fields[k] for k in FRAME_FIELDS},
        **sensor.arrays(),
        **(housing_sensor or HousingSensor()).arrays(),
        "frame_rate": np.float64(frame_rate),
        "blind_codes": fr.blind_codes,
        "blind_positions": fr.blind_positions,
        "active_origin": np.array(origin, dtype=np.int32),
        "defect_kind": fr.defect_kind,
        "defect_pattern": fr.defect_pattern,
        "adc_bits": np.int64(fr.adc_bits),
        "seed": np.int64(fr.seed),
        "config_json": np.array(fr.config_json()),
        "diagnostics_json": np.array(json.dumps(fr.diagnostics)),
        **(extra or {}),
    }


def write_sequence(run: SequenceRun, path: str | Path, *,
                   progress: Callable[[int, int], None] | None = None,
                   extra: Mapping[str, Any] | None = None) -> SequenceFrames:
    """Stream a prepared sequence (:func:`prepare`) into the frame file ``path``, written
    aside and renamed into place. Memory: one chunk of frames, whatever the length.

    Returns the run's :class:`SequenceFrames` without codes (``codes`` None, the reference
    pixels' codes kept: (N, K) is small).
    """
    from irnuc.common.framefile import FrameWriter

    path = Path(path)
    seq = run.sequence
    n = seq.n_frames
    lay = run.pipe.layout
    dtype = np.uint16 if run.cfg["adc"]["bits"] <= 16 else np.uint32
    before = dict(run.pipe.counts)
    diag = Diagnostics(lay, run.cfg["adc"]["bits"])
    blind: list[np.ndarray] = []
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes it private; give the usual permissions
    try:
        with FrameWriter(tmp, n, lay.active_shape, dtype) as fw:
            for ch in iter_sequence(run, (), progress):
                fw.write(ch.codes)
                blind.append(ch.blind_codes)
                diag.add(ch.codes, ch.outputs["status"], ch.outputs["dT"])
            counts = {k: v - before.get(k, 0) for k, v in run.pipe.counts.items()
                      if v - before.get(k, 0)}
            fr = _frames(run, None, np.concatenate(blind), {}, diag.result(), counts)
            meta = {"sequence_json": np.array(json.dumps(seq.to_dict())),
                    "thermal": np.array(run.thermal), **(extra or {})}
            fw.close(file_arrays(fr, run.fields, seq.fpa_sensor, seq.record_rate, meta,
                                 housing_sensor=seq.housing_sensor))
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return fr


def sequence_file_bytes(cfg: Mapping[str, Any], seq: DriftSequence) -> int:
    """Bytes of the frame file of a sequence: its codes and reference pixels' codes (the
    per-frame fields and metadata add about 50 bytes per frame and a few kB)."""
    from irnuc.model.fpa import BLIND, BOUNDARY, ArrayLayout

    f = cfg["fpa"]
    lay = ArrayLayout(f["active_rows"], f["active_cols"], tuple(f["boundary"]), tuple(f["blind"]))
    mode = cfg["readout"]["reference_pixels"]
    k = 0 if mode == "none" else int(np.count_nonzero(
        lay.kind_map() == (BOUNDARY if mode == "boundary" else BLIND)))
    per_code = 2 if cfg["adc"]["bits"] <= 16 else 4
    return seq.n_frames * (per_code * (lay.active_rows * lay.active_cols + k) + 50) + 65536


#: :func:`prepare` under the name :mod:`model` exports it.
prepare_sequence = prepare
