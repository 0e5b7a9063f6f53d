"""Scenes: the blackbody temperature seen by every pixel, for a batch of frames.

A scene gives, for frame n of a batch with base temperatures ``temps``:

* ``uniform``: every pixel at temps[n] (a uniform blackbody; radiance evaluated once per frame);
* ``gradient``: a linear ramp from temps[n] to temps[n] + span across the columns
  (or rows with ``axis = 0``);
* ``disk``: a disk at ``disk_temperature`` (K) on a background at temps[n]; radius as a
  fraction of the shorter side, centred unless ``centre`` (row, col) fractions are given;
* ``map``: a temperature map (array in K, or an ``.npy`` file in K, or an image file whose
  grey levels are scaled to [t_min, t_max] K), shifted so its mean is temps[n] when
  ``temps`` is given.

Maps cover the active area; boundary pixels see the nearest active-area value (the image
continues past the active area); blind pixels see no scene.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.model.validate import ConfigError, check_array, check_choice, check_int, check_scalar

SCENE_KINDS = ("uniform", "gradient", "disk", "map")


@dataclass(frozen=True)
class Scene:
    """A scene kind and its parameters (see the module docstring)."""

    kind: str = "uniform"
    params: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        check_choice("scene", self.kind, SCENE_KINDS)
        allowed = {
            "uniform": set(),
            "gradient": {"span", "axis"},
            "disk": {"disk_temperature", "radius", "centre"},
            "map": {"map", "path", "t_min", "t_max"},
        }[self.kind]
        unknown = set(self.params) - allowed
        if unknown:
            raise ConfigError(
                f"scene {self.kind!r}: unknown parameter(s) {sorted(unknown)}; "
                f"allowed {sorted(allowed)}")


def check_temps(temps: Sequence[float] | np.ndarray | None, *, required: bool = True) -> np.ndarray:
    """Scene base temperatures, K: finite, > 0, one per frame."""
    if temps is None:
        if required:
            raise ConfigError("temps is required: give at least one scene temperature in K")
        return np.empty(0)
    t = check_array("temps", temps, 0.0, 1e5, lo_open=True, unit="K")
    if t.ndim != 1 or t.size == 0:
        raise ConfigError(f"temps must be a non-empty 1-D list of temperatures, got shape {t.shape}")
    return t


def _temperature_map(field: str, value: Any) -> np.ndarray:
    """A scene map of temperatures, K: real numbers (booleans or text would be read as
    1 K / 0 K scenes), finite and in (0, 1e5]."""
    dtype = np.asarray(value).dtype
    if dtype.kind not in "iuf":
        raise ConfigError(f"{field} has dtype {dtype}; a map of temperatures in K (integer "
                          "or float numbers) is required")
    return check_array(field, value, 0.0, 1e5, lo_open=True, unit="K")


def _load_npy_map(path: Path) -> np.ndarray:
    """An .npy temperature map, its header checked (dtype, 2-D, size against the memory
    there is) before the data is read."""
    from numpy.lib import format as npformat

    from irnuc.common.memory import check_memory

    name = f"scene.path = {str(path)!r}"
    try:
        with path.open("rb") as fh:
            if fh.read(6) != b"\x93NUMPY":  # the .npy magic: text or garbage is named as such
                raise ConfigError(f"{name} is not a readable .npy array (no .npy header; "
                                  "write it with numpy.save)")
            fh.seek(0)
            version = npformat.read_magic(fh)
            read = (npformat.read_array_header_1_0 if version == (1, 0)
                    else npformat.read_array_header_2_0)
            shape, _, dtype = read(fh)
    except (OSError, ValueError, EOFError) as exc:
        raise ConfigError(f"{name} is not a readable .npy array ({exc})") from None
    if dtype.kind not in "iuf":
        raise ConfigError(f"{name} has dtype {dtype}; a map of temperatures in K (integer or "
                          "float numbers) is required")
    if len(shape) != 2:
        raise ConfigError(f"{name} has shape {tuple(shape)}; a 2-D map (rows, cols) is required")
    # The file's array, its float64 copy and the scene built from it.
    check_memory(float(np.prod(shape, dtype=np.float64)) * (dtype.itemsize + 16), name,
                 "give a map of the active area's size")
    try:
        arr = np.load(path, allow_pickle=False)
    except (OSError, ValueError, EOFError) as exc:
        raise ConfigError(f"{name} is not a readable .npy array ({exc})") from None
    return _temperature_map("scene.path", arr)


def _load_map(params: Mapping[str, Any]) -> np.ndarray:
    if "map" in params:
        return _temperature_map("scene.map", params["map"])
    if "path" not in params:
        raise ConfigError("scene 'map' needs either map (array, K) or path (file)")
    path = Path(params["path"])
    if not path.is_file():
        what = "not a regular file" if path.exists() else "no such file"
        raise ConfigError(f"scene.path = {str(path)!r}: {what} (an .npy map in K or an image)")
    from irnuc.common.io import guard_input

    guard_input(path, "scene.path")  # not inside the output folder being replaced
    if path.suffix == ".npy":
        return _load_npy_map(path)
    import matplotlib.image as mpimg

    try:
        img = np.asarray(mpimg.imread(path), dtype=np.float64)
    except Exception as exc:  # PIL raises its own classes for a file that is not an image
        raise ConfigError(f"scene.path = {str(path)!r} is not a readable image or .npy map "
                          f"({type(exc).__name__}: {exc})") from None
    if img.ndim == 3:
        img = img[..., :3].mean(axis=2)
    t_min = check_scalar("scene.t_min", params.get("t_min", 280.0), 0.0, 1e5, lo_open=True, unit="K")
    t_max = check_scalar("scene.t_max", params.get("t_max", 380.0), t_min, 1e5, unit="K")
    span = img.max() - img.min()
    norm = (img - img.min()) / span if span > 0 else np.zeros_like(img)
    return t_min + norm * (t_max - t_min)


def scene_temperatures(scene: Scene, temps: np.ndarray, active_shape: tuple[int, int]
                       ) -> np.ndarray:
    """Scene temperature per frame, K.

    Returns
    -------
    ndarray
        (N,) for a uniform scene, else (N, H, W) over the active area.
    """
    h, w = active_shape
    p = scene.params
    if scene.kind == "uniform":
        return np.asarray(temps, dtype=np.float64)
    if scene.kind == "gradient":
        span = check_scalar("scene.span", p.get("span", 50.0), -1e4, 1e4, unit="K")
        axis = check_int("scene.axis", p.get("axis", 1), 0, 1)
        n = (w if axis == 1 else h)
        ramp = np.linspace(0.0, 1.0, n) if n > 1 else np.zeros(1)
        ramp = ramp[None, :] if axis == 1 else ramp[:, None]
        out = temps[:, None, None] + span * np.broadcast_to(ramp, (h, w))[None]
    elif scene.kind == "disk":
        t_disk = check_scalar("scene.disk_temperature", p.get("disk_temperature", 350.0), 0.0,
                              1e5, lo_open=True, unit="K")
        radius = check_scalar("scene.radius", p.get("radius", 0.25), 0.0, 10.0)
        cy, cx = p.get("centre", (0.5, 0.5))
        cy = check_scalar("scene.centre[0]", cy, 0.0, 1.0)
        cx = check_scalar("scene.centre[1]", cx, 0.0, 1.0)
        yy, xx = np.mgrid[0:h, 0:w]
        inside = (yy - cy * (h - 1)) ** 2 + (xx - cx * (w - 1)) ** 2 <= (radius * min(h, w)) ** 2
        out = np.where(inside[None], t_disk, temps[:, None, None])
    else:
        tmap = _load_map(p)
        if tmap.shape != (h, w):
            raise ConfigError(f"scene map has shape {tmap.shape}; the active area is {(h, w)}")
        if temps.size:
            out = tmap[None] - tmap.mean() + temps[:, None, None]
        else:
            out = tmap[None].copy()
    if not (out > 0).all():
        raise ConfigError("scene: the scene parameters give temperatures <= 0 K")
    return np.ascontiguousarray(out, dtype=np.float64)
