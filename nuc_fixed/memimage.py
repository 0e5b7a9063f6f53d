"""Per-pixel coefficient words and the memory image files (docs/datapath.md, version 1).

Word layout, WW = GW + OW + 1 bits: gain in [GW-1:0], offset (two's complement) in
[GW+OW-1:GW], bad flag in bit GW+OW. Files: ``$readmemh`` hex, raw little-endian binary and
a JSON manifest carrying every format field and the SHA-256 of the binary.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

import numpy as np

from irnuc.common.digest import file_sha256
from irnuc.common.errors import UserError
from irnuc.common.io import read_json_object, write_bytes_atomic
from irnuc.nuc_fixed.config import ConfigError, PipelineConfig
from irnuc.nuc_fixed.nuc import check_coefficients
from irnuc.nuc_fixed.validate import InputError, as_config, bool_array, int_array

MEMIMAGE_VERSION = 1
HEX_NAME = "coeffs.hex"
BIN_NAME = "coeffs.bin"
MANIFEST_NAME = "manifest.json"

# Format fields recorded in (and checked from) the manifest.
_FORMAT_FIELDS = (
    "adc_bits", "gain_int_bits", "gain_frac_bits", "offset_int_bits", "offset_frac_bits",
    "out_bits", "rounding", "overflow", "max_width", "max_height",
)
#: Every manifest field that shapes the result is under ``format_sha256``: the formats and
#: the frame size (swapped width and height fit the same binary image).
_HASHED_FIELDS = (*_FORMAT_FIELDS, "height", "width")


class MemImageError(UserError):
    """A memory image file is malformed, inconsistent or fails its checksum."""


def _check_word_bits(cfg: PipelineConfig) -> None:
    if cfg.word_bits > 64:
        raise ConfigError(
            f"pipeline {cfg.name!r}: word_bits = {cfg.word_bits} is outside the range 1..64 "
            "that the golden model's uint64 coefficient words hold"
        )


def pack_words(gain: np.ndarray, offset: np.ndarray, bad: np.ndarray,
               cfg: PipelineConfig | str) -> np.ndarray:
    """Pack gain codes (unsigned), offset codes (signed) and bad flags into uint64 words.

    Parameters
    ----------
    gain, offset : integer array_like, same shape
        Codes of the gain (U Gi.Gf) and offset (S Oi.Of) formats.
    bad : bool array_like, same shape
        Defective-pixel flags.
    cfg : PipelineConfig or str

    Returns
    -------
    uint64 ndarray of the same shape.
    """
    cfg = as_config(cfg)
    _check_word_bits(cfg)
    g, o = check_coefficients(gain, offset, cfg)
    b = bool_array("bad", bad)
    if b.shape != g.shape:
        raise InputError(f"bad has shape {b.shape} but gain has shape {g.shape}; they must match")
    f = cfg.word_fields
    o_field = o.astype(np.int64) & np.int64((1 << f["offset"][1]) - 1)  # two's complement
    return ((g.astype(np.uint64) << np.uint64(f["gain"][0]))
            | (o_field.astype(np.uint64) << np.uint64(f["offset"][0]))
            | (b.astype(np.uint64) << np.uint64(f["bad"][0])))


def check_words(words: np.ndarray, cfg: PipelineConfig) -> np.ndarray:
    """Validate coefficient words (integers in [0, 2^WW - 1]); return them as uint64."""
    _check_word_bits(cfg)
    w = np.asarray(words)
    if w.dtype.byteorder not in ("=", "|"):
        w = w.astype(w.dtype.newbyteorder("="))
    if w.dtype == np.uint64:
        hi = (1 << cfg.word_bits) - 1
        if w.size == 0:
            raise InputError(f"words is empty (shape {w.shape}); one word per pixel is required")
        if int(w.max()) > hi:
            idx = tuple(int(i) for i in np.argwhere(w > np.uint64(hi))[0])
            raise InputError(
                f"words[{', '.join(map(str, idx))}] = {int(w[idx])} is outside the allowed "
                f"range [0, {hi}] (word_bits = {cfg.word_bits})"
            )
        return w
    return int_array("words", w, 0, (1 << cfg.word_bits) - 1).astype(np.uint64)


def unpack_words(words: np.ndarray, cfg: PipelineConfig | str
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split coefficient words into (gain int64, offset int64 sign-extended, bad bool)."""
    cfg = as_config(cfg)
    w = check_words(words, cfg)

    def get(name: str) -> np.ndarray:
        lsb, width = cfg.word_fields[name]
        return ((w >> np.uint64(lsb)) & np.uint64((1 << width) - 1)).astype(np.int64)

    sign = np.int64(1 << (cfg.offset_bits - 1))
    return get("gain"), (get("offset") ^ sign) - sign, get("bad").astype(bool)


# ---- files ---------------------------------------------------------------------------

def word_bytes(cfg: PipelineConfig) -> int:
    """Bytes per word in the raw binary, ceil(WW / 8)."""
    return (cfg.word_bits + 7) // 8


def hex_digits(cfg: PipelineConfig) -> int:
    """Hex digits per line of the ``$readmemh`` file, ceil(WW / 4)."""
    return (cfg.word_bits + 3) // 4


def to_hex(words: np.ndarray, cfg: PipelineConfig) -> str:
    """``$readmemh`` text: one zero-padded lower-case word per line, raster order."""
    nd = hex_digits(cfg)
    return "".join(f"{int(v):0{nd}x}\n" for v in np.asarray(words).reshape(-1))


def to_bin(words: np.ndarray, cfg: PipelineConfig) -> bytes:
    """Raw binary: each word little-endian in ceil(WW/8) bytes, raster order, no header."""
    nb = word_bytes(cfg)
    le = np.ascontiguousarray(np.asarray(words, dtype=np.uint64).reshape(-1)).astype("<u8")
    return le.view(np.uint8).reshape(-1, 8)[:, :nb].tobytes()


def format_fields(cfg: PipelineConfig) -> dict[str, object]:
    """The fields that give the words their meaning (recorded and hashed in the manifest)."""
    return {k: getattr(cfg, k) for k in _FORMAT_FIELDS}


def _format_sha256(fields: dict[str, object]) -> str:
    return hashlib.sha256(json.dumps(fields, sort_keys=True).encode()).hexdigest()


def write_memimage(directory: str | os.PathLike, words: np.ndarray,
                   cfg: PipelineConfig | str, extra_files: tuple[str, ...] = ()
                   ) -> dict[str, object]:
    """Write ``coeffs.hex``, ``coeffs.bin`` and ``manifest.json`` into ``directory``.

    The manifest records every format field (and their SHA-256) and the SHA-256 of every
    file it names: the two memory images and ``extra_files`` (names of files already in
    ``directory``, e.g. the calibration's ``coeffs.npz``). Returns the manifest.
    """
    cfg = as_config(cfg)
    w = check_words(words, cfg)
    if w.ndim != 2:
        raise InputError(f"words has shape {w.shape}; (H, W) is required")
    h, wd = w.shape
    if not (1 <= h <= cfg.max_height and 1 <= wd <= cfg.max_width):
        raise InputError(
            f"words frame size is {h} x {wd}; pipeline {cfg.name!r} allows up to "
            f"{cfg.max_height} x {cfg.max_width}"
        )
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    raw = to_bin(w, cfg)
    write_bytes_atomic(d / BIN_NAME, raw)
    write_bytes_atomic(d / HEX_NAME, to_hex(w, cfg).encode("ascii"))
    fmt = format_fields(cfg)
    files = {name: file_sha256(d / name) for name in (BIN_NAME, HEX_NAME, *extra_files)}
    manifest: dict[str, object] = {
        "version": MEMIMAGE_VERSION,
        "config": cfg.name,
        "description": cfg.description,
        **fmt,
        "format_sha256": _format_sha256({**fmt, "height": h, "width": wd}),
        "word_bits": cfg.word_bits,
        "word_layout": {k: [lsb + width - 1, lsb] for k, (lsb, width) in cfg.word_fields.items()},
        "width": wd,
        "height": h,
        "hex_file": HEX_NAME,
        "bin_file": BIN_NAME,
        "bin_bytes_per_word": word_bytes(cfg),
        "sha256": files[BIN_NAME],
        "files": files,
    }
    write_bytes_atomic(d / MANIFEST_NAME, (json.dumps(manifest, indent=2) + "\n").encode())
    return manifest


def read_manifest(directory: str | os.PathLike) -> dict[str, object]:
    """The manifest of a memory image folder, its structure checked."""
    path = Path(directory) / MANIFEST_NAME
    try:
        manifest = read_json_object(path)
    except UserError as exc:
        raise MemImageError(f"{exc} (a manifest written by irnuc calibrate is needed)") from None
    if manifest.get("version") != MEMIMAGE_VERSION:
        raise MemImageError(
            f"{path}: version = {manifest.get('version')!r}; this reader supports "
            f"{MEMIMAGE_VERSION}"
        )
    words = {dict: "a JSON object", int: "an integer", str: "a string"}
    for key, kind in (("files", dict), ("height", int), ("width", int), ("sha256", str),
                      ("format_sha256", str)):
        if not isinstance(manifest.get(key), kind) or isinstance(manifest.get(key), bool):
            raise MemImageError(f"{path}: field {key!r} is missing or not {words[kind]}")
    unhashed = [n for n in (BIN_NAME, HEX_NAME) if n not in manifest["files"]]  # type: ignore[operator]
    if unhashed:
        raise MemImageError(f"{path}: files names no SHA-256 of {', '.join(unhashed)}; every "
                            "memory image file must be hashed")
    fmt = {k: manifest.get(k) for k in _HASHED_FIELDS}
    if _format_sha256(fmt) != manifest["format_sha256"]:
        raise MemImageError(f"{path}: the format fields ({', '.join(_HASHED_FIELDS)}) do not "
                            "match their recorded SHA-256; the manifest was edited")
    return manifest


def check_files(directory: str | os.PathLike, manifest: dict[str, object]) -> dict[str, bytes]:
    """Every file the manifest names exists and has its recorded SHA-256.

    Returns the bytes that were checked, by name: a caller parses exactly those, so a folder
    replaced while it is being read cannot mix two runs.
    """
    d = Path(directory)
    contents: dict[str, bytes] = {}
    for name, want in manifest["files"].items():  # type: ignore[union-attr]
        f = d / str(name)
        if Path(str(name)).name != str(name):
            raise MemImageError(f"{d / MANIFEST_NAME}: file name {name!r} is not a plain name")
        if not f.is_file():
            raise MemImageError(f"{f}: named by the manifest but missing")
        data = f.read_bytes()
        got = hashlib.sha256(data).hexdigest()
        if got != want:
            raise MemImageError(f"{f}: SHA-256 {got} does not match the manifest ({want}); "
                                "the file is corrupt or from another run")
        contents[str(name)] = data
    return contents


def manifest_config(manifest: dict[str, object]) -> PipelineConfig:
    """The pipeline configuration recorded in a manifest."""
    missing = [k for k in ("config", *_FORMAT_FIELDS) if k not in manifest]
    if missing:
        raise MemImageError(f"{MANIFEST_NAME} is missing field(s) {missing}")
    return PipelineConfig(name=str(manifest["config"]),
                          description=str(manifest.get("description", "")),
                          **{k: manifest[k] for k in _FORMAT_FIELDS})  # type: ignore[arg-type]


def read_memimage(directory: str | os.PathLike, cfg: PipelineConfig | str | None = None,
                  source: str = "bin") -> tuple[np.ndarray, PipelineConfig]:
    """Read a memory image back as (H, W) uint64 words and its configuration.

    Parameters
    ----------
    directory : path
        Folder written by :func:`write_memimage`.
    cfg : PipelineConfig, str or None
        If given, every format field of the manifest must match it.
    source : {"bin", "hex"}
        Which file the words are taken from. Either way every file the manifest names is
        checked against its SHA-256, the format fields against theirs, and the hex words
        against the binary ones.
    """
    if source not in ("bin", "hex"):
        raise ConfigError(f"source = {source!r} is not one of ['bin', 'hex']")
    d = Path(directory)
    manifest = read_manifest(d)
    try:
        mcfg = manifest_config(manifest)
    except ConfigError as exc:
        raise MemImageError(f"{d / MANIFEST_NAME}: {exc}") from None
    if cfg is not None:
        cfg = as_config(cfg)
        diff = {k: (manifest[k], getattr(cfg, k)) for k in _FORMAT_FIELDS
                if manifest[k] != getattr(cfg, k)}
        if diff:
            raise MemImageError(
                f"{d / MANIFEST_NAME}: format fields differ from pipeline {cfg.name!r} "
                f"(manifest, expected): {diff}"
            )
    if manifest.get("word_bits") != mcfg.word_bits:
        raise MemImageError(
            f"{d / MANIFEST_NAME}: word_bits = {manifest.get('word_bits')!r} but the formats "
            f"give {mcfg.word_bits}"
        )
    contents = check_files(d, manifest)
    h, w = int(manifest["height"]), int(manifest["width"])  # type: ignore[arg-type]
    n = h * w
    raw = contents[BIN_NAME]
    if manifest["sha256"] != manifest["files"].get(BIN_NAME):  # type: ignore[union-attr]
        raise MemImageError(f"{d / MANIFEST_NAME}: sha256 and files[{BIN_NAME!r}] disagree")
    nb = word_bytes(mcfg)
    if len(raw) != n * nb:
        raise MemImageError(
            f"{d / BIN_NAME}: {len(raw)} bytes, expected {n} words x {nb} bytes = {n * nb}"
        )
    buf = np.zeros((n, 8), dtype=np.uint8)
    buf[:, :nb] = np.frombuffer(raw, dtype=np.uint8).reshape(n, nb)
    words = buf.view("<u8").reshape(h, w).astype(np.uint64)
    # The hex image is read and compared in both modes: it is what $readmemh loads.
    hex_words = _parse_hex(d / HEX_NAME, contents[HEX_NAME], mcfg, n).reshape(h, w)
    if not np.array_equal(hex_words, words):
        idx = tuple(int(i) for i in np.argwhere(hex_words != words)[0])
        raise MemImageError(
            f"{d / HEX_NAME}: word at (row, col) {idx} = {int(hex_words[idx]):x} differs "
            f"from the binary ({int(words[idx]):x})"
        )
    try:
        check_words(words, mcfg)
    except InputError as exc:
        raise MemImageError(f"{d}: {exc}") from None
    return words, mcfg


def _parse_hex(path: Path, data: bytes, cfg: PipelineConfig, n: int) -> np.ndarray:
    nd = hex_digits(cfg)
    try:
        lines = data.decode("ascii").splitlines()
    except UnicodeDecodeError as exc:
        raise MemImageError(f"{path}: not ASCII text ({exc}); one hex word per line is "
                            "required") from None
    if len(lines) != n:
        raise MemImageError(f"{path}: {len(lines)} lines, expected {n} words")
    out = np.empty(n, dtype=np.uint64)
    for i, line in enumerate(lines):
        if len(line) != nd:
            raise MemImageError(f"{path}: line {i + 1} = {line!r} is not {nd} hex digits")
        # Digits only: int() would also take a sign, "0x" or "_" separators.
        if line.strip(_HEX_DIGITS):
            raise MemImageError(f"{path}: line {i + 1} = {line!r} is not hexadecimal")
        out[i] = int(line, 16)
    return out


_HEX_DIGITS = "0123456789abcdefABCDEF"
