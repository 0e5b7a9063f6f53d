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


def npz_headers(path: Path, flag: str) -> dict[str, tuple[tuple[int, ...], Any]]:
    """Shape and dtype of every array of an ``.npz`` file, read from the headers only (no
    data), so that sizes can be checked before anything is loaded."""
    import numpy as np
    from numpy.lib import format as npformat

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
                out[info.filename[:-4]] = (tuple(shape), np.dtype(dtype))
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
             work_bytes: Callable[[Headers], float] | None = None) -> dict[str, Any]:
    """Every array of an ``.npz`` file (no pickles), checked for the required keys.

    ``work_bytes(headers)``: the memory the work that follows needs besides the arrays;
    checked, with every array's size, against the available memory before anything is
    loaded.
    """
    import math

    import numpy as np

    from irnuc.common.memory import check_memory

    headers = npz_headers(path, flag)
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
    try:
        with np.load(path, allow_pickle=False) as z:
            return {k: z[k] for k in z.files}
    except (OSError, EOFError, ValueError, zipfile.BadZipFile, KeyError, zlib.error) as exc:
        raise UserError(f"{flag} {path}: damaged or truncated .npz ({exc})") from None


def load_frames(value: str, flag: str = "--frames", work_per_code: float = 0.0,
                work_per_pixel: float = 0.0) -> dict[str, Any]:
    """Frames written by ``irnuc frames``: codes (N, H, W) integers, temps (N,) kelvin,
    adc_bits; every field checked. The work that follows needs ``work_per_code`` bytes per
    code and ``work_per_pixel`` per pixel of a frame besides the frames (checked against
    the available memory before loading)."""
    import numpy as np

    def work(headers: Headers) -> float:
        return frames_work_bytes(headers["codes"][0], work_per_code, work_per_pixel)

    path = frames_path(value, flag)
    data = load_npz(path, flag, FRAMES_KEYS, work)
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
    return data
