"""Reading the files a user passes on the command line, with one-line errors.

Every check happens before any work: the message names the flag, the file, the key and
what is allowed.
"""

from __future__ import annotations

import zipfile
from pathlib import Path
from typing import Any

from irnuc.common.errors import UserError

FRAMES_KEYS = ("codes", "temps", "adc_bits")


def frames_path(value: str, flag: str = "--frames", name: str = "frames.npz") -> Path:
    """A frames file, or the folder ``irnuc frames --out`` wrote (holding ``frames.npz``)."""
    p = Path(value)
    if p.is_dir():
        p = p / name
    if not p.exists():
        raise UserError(f"{flag} {value}: no such file")
    if not p.is_file():
        raise UserError(f"{flag} {value}: is not a file")
    return p


def load_npz(path: Path, flag: str, required: tuple[str, ...]) -> dict[str, Any]:
    """Every array of an ``.npz`` file (no pickles), checked for the required keys."""
    import numpy as np

    if not zipfile.is_zipfile(path):
        raise UserError(f"{flag} {path}: not an .npz file (a zip archive of .npy arrays, as "
                        "written by numpy.savez or irnuc); a .npy, text or truncated file "
                        "cannot be read")
    try:
        with np.load(path, allow_pickle=False) as z:
            missing = [k for k in required if k not in z.files]
            if missing:
                raise UserError(f"{flag} {path}: missing key(s) {', '.join(missing)}; the file "
                                f"holds {', '.join(z.files) or 'nothing'}")
            return {k: z[k] for k in z.files}
    except UserError:
        raise
    except ValueError as exc:  # object arrays need pickles: refused
        raise UserError(f"{flag} {path}: holds an array that needs pickle ({exc}); only "
                        "numeric arrays are read") from None
    except (OSError, EOFError, zipfile.BadZipFile, KeyError) as exc:
        raise UserError(f"{flag} {path}: damaged or truncated .npz ({exc})") from None


def load_frames(value: str, flag: str = "--frames") -> dict[str, Any]:
    """Frames written by ``irnuc frames``: codes (N, H, W) integers, temps (N,) kelvin,
    adc_bits; every field checked."""
    import numpy as np

    path = frames_path(value, flag)
    data = load_npz(path, flag, FRAMES_KEYS)
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
