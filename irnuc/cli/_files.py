"""Reading the files a user passes on the command line, with one-line errors.

Every check happens before any work: the message names the flag, the file, the key and
what is allowed.
"""

from __future__ import annotations

import zipfile
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

from irnuc.common.errors import UserError

FRAMES_KEYS = ("codes", "temps", "adc_bits")


def frames_path(value: str, flag: str = "--frames", name: str = "frames.npz") -> Path:
    """A frames file, or the folder ``irnuc frames --out`` wrote (holding ``frames.npz``)."""
    p = Path(value)
    if p.is_dir():
        if not (p / name).exists():
            raise UserError(f"{flag} {value}: a folder without {name} (give the file, or the "
                            "--out folder of irnuc frames)")
        p = p / name
    if not p.exists():
        raise UserError(f"{flag} {value}: no such file")
    if not p.is_file():
        raise UserError(f"{flag} {value}: is not a file")
    return p


def npz_headers(path: Path, flag: str, damaged: list[str] | None = None
                ) -> dict[str, tuple[tuple[int, ...], Any]]:
    """Shape and dtype of every array of an ``.npz`` file, read from the headers only (no
    data), so that sizes can be checked before anything is loaded.

    A member whose header disagrees with the size the archive stores for it is damaged:
    a one-line error, or, with ``damaged`` given, its description appended there (so that
    the caller can first judge the sizes the headers claim)."""
    import numpy as np
    from numpy.lib import format as npformat

    from irnuc.common.framefile import check_member_size

    if not zipfile.is_zipfile(path):
        raise UserError(f"{flag} {path}: not an .npz file (a zip archive of .npy arrays, as "
                        "written by numpy.savez or irnuc); a .npy, text or truncated file "
                        "cannot be read")
    out: dict[str, tuple[tuple[int, ...], Any]] = {}
    try:
        with zipfile.ZipFile(path) as zf:
            for info in zf.infolist():
                if not info.filename.endswith(".npy"):
                    continue
                with zf.open(info) as fh:
                    version = npformat.read_magic(fh)
                    read = (npformat.read_array_header_1_0 if version == (1, 0)
                            else npformat.read_array_header_2_0)
                    shape, _, dtype = read(fh)
                    header = fh.tell()
                name = info.filename[:-4]
                out[name] = (tuple(shape), np.dtype(dtype))
                try:
                    check_member_size(info, header, tuple(shape), np.dtype(dtype), name)
                except ValueError as exc:
                    if damaged is None:
                        raise
                    damaged.append(str(exc))
    except (OSError, EOFError, ValueError, zipfile.BadZipFile, KeyError, zlib.error) as exc:
        raise UserError(f"{flag} {path}: damaged or truncated .npz ({exc})") from None
    return out


Headers = dict[str, tuple[tuple[int, ...], Any]]


def arrays_bytes(headers: Headers) -> float:
    """Bytes of every array of an ``.npz``, from its headers."""
    import math

    return float(sum(math.prod(shape) * dtype.itemsize for shape, dtype in headers.values()))


def frames_work_bytes(shape: tuple[int, ...], per_code: float, per_pixel: float) -> float:
    """Memory of the work on frames of ``shape`` (N, H, W) besides the frames themselves."""
    import math

    return per_code * math.prod(shape) + per_pixel * math.prod(shape[1:])


def load_npz(path: Path, flag: str, required: tuple[str, ...],
             work_bytes: Callable[[Headers], float] | None = None,
             mapped: tuple[str, ...] = ()) -> dict[str, Any]:
    """Every array of an ``.npz`` file (no pickles), checked for the required keys.

    ``work_bytes(headers)``: the memory the work that follows needs besides the arrays;
    checked, with every array's size, against the available memory before anything is
    loaded. The arrays named in ``mapped`` are memory-mapped from the file when it stores
    them uncompressed (:func:`irnuc.common.framefile.open_member`).
    """
    import math

    from irnuc.common.io import guard_input
    from irnuc.common.memory import check_memory

    guard_input(path, flag)
    damaged: list[str] = []
    headers = npz_headers(path, flag, damaged)
    missing = [k for k in required if k not in headers]
    if missing:
        raise UserError(f"{flag} {path}: missing key(s) {', '.join(missing)}; the file "
                        f"holds {', '.join(headers) or 'nothing'}")
    objects = [k for k, (_, dtype) in headers.items() if dtype.hasobject]
    if objects:
        raise UserError(f"{flag} {path}: {objects[0]} is an object array (it would need "
                        "pickle); only numeric and text arrays are read")
    need = arrays_bytes(headers) + (work_bytes(headers) if work_bytes is not None else 0.0)
    big = max(headers, key=lambda k: math.prod(headers[k][0]), default="")
    check_memory(need, f"{flag} {path}" + (f" ({big} {headers[big][0]} {headers[big][1]})"
                                           if big else ""),
                 "give fewer or smaller frames")
    if damaged:  # after the sizes the headers claim: a header bomb is named as such
        raise UserError(f"{flag} {path}: damaged or truncated .npz ({damaged[0]})")
    from irnuc.common.framefile import open_member

    try:
        with zipfile.ZipFile(path) as zf:
            return {k: open_member(path, zf, k, mmap=k in mapped) for k in headers}
    except (OSError, EOFError, ValueError, zipfile.BadZipFile, KeyError, zlib.error) as exc:
        raise UserError(f"{flag} {path}: damaged or truncated .npz ({exc})") from None


def load_frames(value: str, flag: str = "--frames", work_per_code: float = 0.0,
                work_per_pixel: float = 0.0) -> dict[str, Any]:
    """Frames written by ``irnuc frames``, every field checked (one line naming the key).

    Returns the file's arrays, with

    * ``codes`` (N, H, W) integer ADC codes (memory-mapped from an uncompressed file),
      ``temps`` (N,) scene temperature, K (float64), ``adc_bits`` (int);
    * the per-frame fields of :data:`model.fpa_sensor.FRAME_FIELDS` by their names
      (``time_s``, ``fpa_K``, ``fpa_reading``, ``T_cam_K``, ``scene_K``, ``shutter``,
      ``ambient_K``, ``lens_K``, ``shutter_K``, ``housing_reading``), ``fpa_sensor`` and
      ``housing_sensor`` (:class:`model.fpa_sensor.FpaSensor`, ``HousingSensor``: bits, LSB,
      zero, the ground-truth offset, noise and lag, the housing sensor's node),
      ``frame_rate`` (Hz);
    * ``blind_codes`` (N, K) and ``blind_positions`` (K, 2): the reference pixels read out
      beside the image and their full-array (row, col); ``active_origin`` (2,);
    * ``fields_synthesized``: True for a file of an older irnuc without the fields, which
      are then made constant from its configuration (K = 0 reference pixels);
      ``housing_synthesized``: True when the ambient, lens, shutter temperatures and the
      housing reading are made up (a file of format 2: the housing's temperature for each,
      read by the default housing sensor).

    The work that follows needs ``work_per_code`` bytes per code and ``work_per_pixel`` per
    pixel of a frame besides the frames (checked against the available memory before
    loading)."""
    import numpy as np

    def work(headers: Headers) -> float:
        return frames_work_bytes(headers["codes"][0], work_per_code, work_per_pixel)

    path = frames_path(value, flag)
    data = load_npz(path, flag, FRAMES_KEYS, work, mapped=("codes", "blind_codes"))
    codes, temps, adc = data["codes"], data["temps"], data["adc_bits"]
    if not np.issubdtype(codes.dtype, np.integer):
        raise UserError(f"{flag} {path}: codes has dtype {codes.dtype}; integer ADC codes "
                        "are required")
    if codes.ndim != 3 or min(codes.shape, default=0) < 1:
        raise UserError(f"{flag} {path}: codes has shape {codes.shape}; (N, H, W) with "
                        "N, H, W >= 1 is required")
    if adc.shape != () or not np.issubdtype(adc.dtype, np.integer) or not 1 <= int(adc) <= 24:
        raise UserError(f"{flag} {path}: adc_bits = {adc!r} must be one integer in 1..24")
    adc_bits = int(adc)
    if not np.issubdtype(temps.dtype, np.number) or np.issubdtype(temps.dtype, np.complexfloating):
        raise UserError(f"{flag} {path}: temps has dtype {temps.dtype}; numbers (kelvin) "
                        "are required")
    if temps.shape != (codes.shape[0],):
        raise UserError(f"{flag} {path}: temps has shape {temps.shape} but there are "
                        f"{codes.shape[0]} frames; one temperature per frame is required")
    t = temps.astype(np.float64)
    if not np.isfinite(t).all() or (t <= 0).any():
        i = int(np.flatnonzero(~np.isfinite(t) | (t <= 0))[0])
        raise UserError(f"{flag} {path}: temps[{i}] = {temps[i]!r}; every frame temperature "
                        "must be a finite number of kelvin above 0")
    lo, hi = int(codes.min()), int(codes.max())
    if lo < 0 or hi > (1 << adc_bits) - 1:
        raise UserError(f"{flag} {path}: codes span {lo}..{hi}, outside 0..{(1 << adc_bits) - 1}"
                        f" of adc_bits = {adc_bits}")
    data["temps"] = t
    data["adc_bits"] = adc_bits
    _frame_fields(data, f"{flag} {path}", codes.shape[0])
    return data


def _frame_fields(data: dict[str, Any], where: str, n: int) -> None:
    """Check (or, for an older file, make up) the per-frame fields, the FPA sensor and the
    reference pixels of a frame file, in place."""
    import json

    import numpy as np

    from irnuc.model.fpa_sensor import (
        FRAME_FIELDS,
        PLAIN_FRAME_RATE,
        SENSOR_NODES,
        FpaSensor,
        HousingSensor,
        constant_fields,
    )
    from irnuc.model.validate import ConfigError

    def sensor_of(cls: Any, what: str) -> Any:
        prefix = cls.PREFIX + "_"
        keys = [k for k in data if k.startswith(prefix)]
        try:
            return cls(**{k[len(prefix):]: (str(v) if (v := data.pop(k)).dtype.kind == "U"
                                            else v.item()) for k in keys})
        except (ConfigError, TypeError, ValueError) as exc:
            raise UserError(f"{where}: bad {what} sensor settings ({exc})") from None

    sensor = sensor_of(FpaSensor, "FPA")
    data["fpa_sensor"] = sensor
    housing_sensor = sensor_of(HousingSensor, "housing")
    data["housing_sensor"] = housing_sensor
    present = [k for k in FRAME_FIELDS if k in data]
    data["fields_synthesized"] = not present
    if not present:  # an older file: the fields its configuration implies
        env = _file_environment(data, json)
        data.update(constant_fields(data["temps"], env["T_substrate"], env["T_cam"], sensor))
        data["frame_rate"] = np.float64(PLAIN_FRAME_RATE)
    # a file of format 2: no ambient, lens, shutter temperature nor housing reading; the
    # camera in equilibrium with its surroundings, the housing read by the default sensor
    housing_keys = ("ambient_K", "lens_K", "shutter_K", "housing_reading")
    data["housing_synthesized"] = bool(present) and not any(k in data for k in housing_keys)
    if data["housing_synthesized"] and "T_cam_K" in data:
        cam = np.asarray(data["T_cam_K"], dtype=np.float64)
        for k in ("ambient_K", "lens_K", "shutter_K"):
            data[k] = cam.copy()
        if cam.size and np.isfinite(cam).all() and (cam > 0).all():
            data["housing_reading"] = housing_sensor.read(cam)
    elif data["fields_synthesized"]:
        data["housing_synthesized"] = True
    missing = [k for k in FRAME_FIELDS if k not in data]
    if missing:
        raise UserError(f"{where}: missing per-frame field(s) {', '.join(missing)}")
    for key, (dtype, unit, _) in FRAME_FIELDS.items():
        arr = np.asarray(data[key])
        if arr.shape != (n,):
            raise UserError(f"{where}: {key} has shape {arr.shape}; one value per frame ({n}) "
                            "is required")
        if dtype == "bool":
            if arr.dtype != np.bool_:
                raise UserError(f"{where}: {key} has dtype {arr.dtype}; bool is required")
        elif dtype == "int64":
            if not np.issubdtype(arr.dtype, np.integer):
                raise UserError(f"{where}: {key} has dtype {arr.dtype}; integers are required")
            sn = housing_sensor if key == "housing_reading" else sensor
            if arr.size and (arr.min() < 0 or arr.max() > sn.max_code):
                raise UserError(f"{where}: {key} spans {arr.min()}..{arr.max()}, outside "
                                f"0..{sn.max_code} of {sn.PREFIX}_bits = {sn.bits}")
        else:
            if not np.issubdtype(arr.dtype, np.floating) or not np.isfinite(arr).all():
                raise UserError(f"{where}: {key} must hold finite numbers ({unit})")
        data[key] = arr.astype(dtype)
    for key in ("fpa_K", "T_cam_K", "ambient_K", "lens_K", "shutter_K"):
        if (data[key] <= 0).any():
            raise UserError(f"{where}: {key} must be above 0 K")
    if housing_sensor.node not in SENSOR_NODES:  # checked by the sensor; kept for clarity
        raise UserError(f"{where}: housing_sensor_node = {housing_sensor.node!r}")
    rate = np.asarray(data.get("frame_rate", PLAIN_FRAME_RATE))
    if rate.shape != () or not np.isfinite(rate) or not rate > 0:
        raise UserError(f"{where}: frame_rate = {rate!r} must be one number above 0 Hz")
    data["frame_rate"] = float(rate)
    _reference_pixels(data, where, n)


def _file_environment(data: dict[str, Any], json: Any) -> dict[str, float]:
    """The substrate and housing temperatures (K) of an older file's configuration."""
    default = {"T_substrate": 300.0, "T_cam": 300.0}
    if "config_json" not in data:
        return default
    try:
        env = json.loads(str(data["config_json"]))["config"]["environment"]
        return {k: float(env[k]) for k in default}
    except (ValueError, KeyError, TypeError):
        return default


def _reference_pixels(data: dict[str, Any], where: str, n: int) -> None:
    import numpy as np

    if "blind_codes" not in data:
        data["blind_codes"] = np.empty((n, 0), data["codes"].dtype)
        data["blind_positions"] = np.empty((0, 2), np.int32)
    codes, pos = data["blind_codes"], np.asarray(data.get("blind_positions", np.empty((0, 2))))
    if codes.ndim != 2 or codes.shape[0] != n or not np.issubdtype(codes.dtype, np.integer):
        raise UserError(f"{where}: blind_codes has shape {codes.shape} {codes.dtype}; (N, K) "
                        f"integer codes with N = {n} frames are required")
    if pos.shape != (codes.shape[1], 2) or not np.issubdtype(pos.dtype, np.integer):
        raise UserError(f"{where}: blind_positions has shape {pos.shape}; (K, 2) integer "
                        f"(row, col) with K = {codes.shape[1]} is required")
    top = (1 << data["adc_bits"]) - 1
    if codes.size and (int(codes.min()) < 0 or int(codes.max()) > top):
        raise UserError(f"{where}: blind_codes span {int(codes.min())}..{int(codes.max())}, "
                        f"outside 0..{top} of adc_bits = {data['adc_bits']}")
    data["blind_positions"] = pos.astype(np.int32)
