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
from typing import Any

import numpy as np

from irnuc.common.digest import file_sha256
from irnuc.common.errors import UserError
from irnuc.common.io import read_json_object, write_bytes_atomic
from irnuc.nuc_fixed.config import ConfigError, PipelineConfig
from irnuc.nuc_fixed.nuc import check_coefficients
from irnuc.nuc_fixed.validate import InputError, as_config, bool_array, check_frame_shape, int_array

MEMIMAGE_VERSION = 1
METHOD_IMAGE_VERSION = 2
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


def _format_digest_fields(manifest: dict[str, object]) -> dict[str, object]:
    """The fields the format SHA-256 covers: the base formats, the frame size (and,
    version 2, the method)."""
    fmt = {k: manifest.get(k) for k in _HASHED_FIELDS}
    if manifest.get("version") == METHOD_IMAGE_VERSION:
        fmt["method_fields"] = manifest.get("method_fields")
    return fmt


def _format_sha256(fields: dict[str, object]) -> str:
    return hashlib.sha256(json.dumps(fields, sort_keys=True).encode()).hexdigest()


#: The manifest's own integrity field: the SHA-256 of every other field.
MANIFEST_HASH = "manifest_sha256"


def _manifest_sha256(manifest: dict[str, object]) -> str:
    """SHA-256 of every field of a manifest but :data:`MANIFEST_HASH` (canonical JSON)."""
    return _format_sha256({k: v for k, v in manifest.items() if k != MANIFEST_HASH})


def seal_manifest(manifest: dict[str, object]) -> dict[str, object]:
    """Set the manifest's two hashes from its fields, in place (and return it): the
    formats' (``format_sha256``) and every field's (``manifest_sha256``: the registers,
    the FPA sensor, the file hashes ... any edit of any field is caught)."""
    manifest["format_sha256"] = _format_sha256(_format_digest_fields(manifest))
    manifest.pop(MANIFEST_HASH, None)
    manifest[MANIFEST_HASH] = _manifest_sha256(manifest)
    return manifest


#: The FPA sensor's settings that decide which code a temperature reads (its noise does
#: not): recorded in the manifest and compared with the frames' by ``irnuc correct`` for
#: the methods that read the FPA sensor.
SENSOR_CODE_FIELDS = ("bits", "lsb_K", "zero_K", "offset_K")

#: The housing sensor's: the FPA sensor's and the node it sits on (a sensor on the lens
#: reads another temperature than one on the housing wall).
HOUSING_SENSOR_CODE_FIELDS = (*SENSOR_CODE_FIELDS, "node")

#: Per sensor kind (the manifest's key is ``<kind>_sensor``): the per-frame field the
#: method reads, the fields compared and the sensor's name in messages.
_SENSOR_KINDS = {
    "fpa": ("fpa_reading", SENSOR_CODE_FIELDS, "FPA sensor"),
    "housing": ("housing_reading", HOUSING_SENSOR_CODE_FIELDS, "housing sensor"),
}


def sensor_record(sensor: Any) -> dict[str, object] | None:
    """The manifest's ``fpa_sensor`` / ``housing_sensor``: every setting of a
    :class:`~irnuc.model.fpa_sensor.FpaSensor` or ``HousingSensor`` (None: not known)."""
    if sensor is None:
        return None
    from dataclasses import asdict

    def value(k: str, v: object) -> object:
        if k == "bits":
            return int(v)  # type: ignore[call-overload]
        return v if isinstance(v, str) else float(v)  # type: ignore[arg-type]

    return {k: value(k, v) for k, v in asdict(sensor).items()}


def check_sensor(manifest_sensor: object, sensor: Any, cfg: PipelineConfig, where: str,
                 coeffs: str, kind: str = "fpa") -> None:
    """:class:`MemImageError` when frames read by ``sensor`` would give another reading
    than the calibration's sensor for the same temperature (``cfg``'s method reads it).

    ``kind``: ``"fpa"`` (the on-die sensor, ``fpa_reading``) or ``"housing"`` (the
    housing sensor, ``housing_reading``; its node is compared too).
    """
    from irnuc.nuc_fixed.method_top import needs

    field_name, code_fields, label = _SENSOR_KINDS[kind]
    if field_name not in needs(cfg):
        return
    if not isinstance(manifest_sensor, dict):
        raise MemImageError(f"{coeffs}: the manifest does not record the {label} of the "
                            f"calibration, which method {cfg.method!r} reads; calibrate again "
                            "with this irnuc")
    now = sensor_record(sensor) or {}
    diff = [k for k in code_fields if manifest_sensor.get(k) != now.get(k)]
    if diff:
        def show(d: dict) -> str:
            return ", ".join(f"{k} = {d.get(k)!r}" for k in diff)

        raise MemImageError(
            f"{where}: the frames' {label} ({show(now)}) is not the calibration's in "
            f"{coeffs} ({show(manifest_sensor)}): the same temperature reads another code, "
            f"and method {cfg.method!r} would apply the wrong temperature terms; calibrate "
            "with this sensor")


def write_memimage(directory: str | os.PathLike, words: np.ndarray,
                   cfg: PipelineConfig | str, extra_files: tuple[str, ...] = (),
                   fpa_sensor: Any = None, housing_sensor: Any = None) -> dict[str, object]:
    """Write ``coeffs.hex``, ``coeffs.bin`` and ``manifest.json`` into ``directory``.

    The manifest records every format field (and their SHA-256), the FPA and housing
    sensors of the calibration (``fpa_sensor``, a :class:`~irnuc.model.fpa_sensor.FpaSensor`;
    ``housing_sensor``, a ``HousingSensor``), the
    SHA-256 of every file it names (the two memory images and ``extra_files``, names of
    files already in ``directory``, e.g. the calibration's ``coeffs.npz``) and the SHA-256
    of all its other fields (:func:`seal_manifest`). Returns the manifest.
    """
    cfg = as_config(cfg)
    w = check_words(words, cfg)
    if w.ndim != 2:
        raise InputError(f"words has shape {w.shape}; (H, W) is required")
    h, wd = check_frame_shape("words", w.shape, cfg)
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
        "fpa_sensor": sensor_record(fpa_sensor),
        "housing_sensor": sensor_record(housing_sensor),
    }
    seal_manifest(manifest)
    write_bytes_atomic(d / MANIFEST_NAME, (json.dumps(manifest, indent=2) + "\n").encode())
    return manifest


def read_manifest(directory: str | os.PathLike,
                  versions: tuple[int, ...] = (MEMIMAGE_VERSION,)) -> dict[str, object]:
    """The manifest of a memory image folder, its structure checked.

    ``versions``: the manifest versions the caller reads (1: two-point, one memory;
    2: every method, :func:`read_method_image`).
    """
    path = Path(directory) / MANIFEST_NAME
    try:
        manifest = read_json_object(path)
    except UserError as exc:
        raise MemImageError(f"{exc} (a manifest written by irnuc calibrate is needed)") from None
    version = manifest.get("version")
    if version not in versions or isinstance(version, bool):
        raise MemImageError(
            f"{path}: version = {version!r}; this reader supports "
            f"{' and '.join(map(str, versions))}"
        )
    words = {dict: "a JSON object", int: "an integer", str: "a string"}
    required = [("files", dict), ("height", int), ("width", int), ("sha256", str),
                ("format_sha256", str)]
    if version == METHOD_IMAGE_VERSION:
        required += [("memories", dict), ("registers", dict), ("method_fields", dict)]
    for i, (key, kind) in enumerate(required):
        if not isinstance(manifest.get(key), kind) or isinstance(manifest.get(key), bool):
            ver = f"version = {version} but " if i >= 5 else ""
            raise MemImageError(f"{path}: {ver}field {key!r} is missing or not {words[kind]}")
    from irnuc.nuc_fixed.rtl_spec import FRAME_DIM_MAX

    for key in ("height", "width"):
        if not 1 <= manifest[key] <= FRAME_DIM_MAX:  # type: ignore[operator]
            raise MemImageError(f"{path}: {key} = {manifest[key]} is outside 1..{FRAME_DIM_MAX}")
    images = (BIN_NAME, HEX_NAME) if version == MEMIMAGE_VERSION else tuple(
        n for m in manifest["memories"].values() if isinstance(m, dict)  # type: ignore[union-attr]
        for n in (m.get("bin_file"), m.get("hex_file")))
    unhashed = [str(n) for n in images if n not in manifest["files"]]  # type: ignore[operator]
    if unhashed or not images:
        raise MemImageError(f"{path}: files names no SHA-256 of {', '.join(unhashed) or 'any image'}"
                            "; every memory image file must be hashed")
    fmt = _format_digest_fields(manifest)
    if _format_sha256(fmt) != manifest["format_sha256"]:
        raise MemImageError(f"{path}: the format fields ({', '.join(fmt)}) do not "
                            "match their recorded SHA-256; the manifest was edited")
    if not isinstance(manifest.get(MANIFEST_HASH), str):
        raise MemImageError(f"{path}: no {MANIFEST_HASH} (the SHA-256 of every field); it was "
                            "written by an older irnuc or edited: run irnuc calibrate again")
    if _manifest_sha256(manifest) != manifest[MANIFEST_HASH]:
        raise MemImageError(f"{path}: its fields (registers, FPA sensor, file hashes ...) do "
                            f"not match their recorded SHA-256 ({MANIFEST_HASH}); the manifest "
                            "was edited")
    return manifest


#: Bytes per pixel a file named by a manifest may hold besides the memory images (the
#: calibration's arrays, its bad-pixel list, the table pair images), on top of
#: :data:`~irnuc.common.io.MAX_TEXT_BYTES`: generous (the largest is some 100), and a
#: bound, so that a damaged or foreign file is refused before it is read.
EXTRA_BYTES_PER_PIXEL = 512


def check_files(directory: str | os.PathLike, manifest: dict[str, object],
                limits: dict[str, int] | None = None) -> dict[str, bytes]:
    """Every file the manifest names exists, is no larger than its limit and has its
    recorded SHA-256.

    ``limits``: the most bytes of the files to read (the memory images: their size from
    the frame size and word width); those are returned, by name, so that a caller parses
    exactly the bytes that were checked (a folder replaced while it is being read cannot
    mix two runs). Every other file is hashed as it is read, up to
    ``MAX_TEXT_BYTES + EXTRA_BYTES_PER_PIXEL`` per pixel of the manifest's frame size.
    """
    import hashlib as _hl

    from irnuc.common.io import MAX_TEXT_BYTES, guard_input, read_bytes_capped

    d = Path(directory)
    pixels = int(manifest["height"]) * int(manifest["width"])  # type: ignore[call-overload]
    limits = dict(limits or {})
    contents: dict[str, bytes] = {}
    for name, want in manifest["files"].items():  # type: ignore[union-attr]
        f = d / str(name)
        if Path(str(name)).name != str(name) or str(name) in ("", ".", ".."):
            raise MemImageError(f"{d / MANIFEST_NAME}: file name {name!r} is not a plain name")
        if not f.is_file():
            raise MemImageError(f"{f}: named by the manifest but missing (or not a regular "
                                "file)")
        guard_input(f, "--coeffs")
        limit = limits.get(str(name), MAX_TEXT_BYTES + EXTRA_BYTES_PER_PIXEL * pixels)
        size = f.stat().st_size
        if size > limit:
            raise MemImageError(f"{f}: {size} bytes, more than the {limit} a {manifest['height']}"
                                f" x {manifest['width']} calibration's file holds; it is not "
                                "this calibration's")
        if str(name) in limits:
            data = read_bytes_capped(f, "", limit)
            got = _hl.sha256(data).hexdigest()
            contents[str(name)] = data
        else:
            h = _hl.sha256()
            read = 0
            with f.open("rb") as fh:
                while chunk := fh.read(1 << 20):
                    read += len(chunk)
                    if read > limit:  # grew while it was read
                        raise MemImageError(f"{f}: more than {limit} bytes; it is not this "
                                            "calibration's")
                    h.update(chunk)
            got = h.hexdigest()
        if got != want:
            raise MemImageError(f"{f}: SHA-256 {got} does not match the manifest ({want}); "
                                "the file is corrupt or from another run")
    return contents


def _image_limits(names: dict[str, int], pixels: int) -> dict[str, int]:
    """The most bytes of each memory image (``{bin or hex file: word bits}``): the binary
    image's exact size, the hex image's with a two-byte line end."""
    out = {}
    for name, bits in names.items():
        out[name] = (pixels * ((bits + 7) // 8) if name.endswith(".bin")
                     else pixels * ((bits + 3) // 4 + 2))
    return out


def manifest_config(manifest: dict[str, object]) -> PipelineConfig:
    """The pipeline configuration recorded in a manifest (version 2: with its method)."""
    missing = [k for k in ("config", *_FORMAT_FIELDS) if k not in manifest]
    if missing:
        raise MemImageError(f"{MANIFEST_NAME} is missing field(s) {missing}")
    method = manifest["method_fields"] if manifest.get("version") == METHOD_IMAGE_VERSION else {}
    return PipelineConfig(name=str(manifest["config"]),
                          description=str(manifest.get("description", "")),
                          **{k: manifest[k] for k in _FORMAT_FIELDS},  # type: ignore[arg-type]
                          **method)  # type: ignore[arg-type]


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
    h, w = int(manifest["height"]), int(manifest["width"])  # type: ignore[arg-type]
    n = h * w
    contents = check_files(d, manifest, _image_limits(
        {BIN_NAME: mcfg.word_bits, HEX_NAME: mcfg.word_bits}, n))
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


def _parse_hex(path: Path, data: bytes, cfg: PipelineConfig | int, n: int) -> np.ndarray:
    """The words of a ``$readmemh`` file of ``cfg``'s words (or of words of ``cfg`` bits)."""
    nd = hex_digits(cfg) if isinstance(cfg, PipelineConfig) else (cfg + 3) // 4
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


# ---- version 2: every method, several memories --------------------------------------------

def words_to_hex(words: np.ndarray, word_bits: int) -> bytes:
    """``$readmemh`` text of words of ``word_bits`` bits (as :func:`to_hex`)."""
    nd = (word_bits + 3) // 4
    return "".join(f"{int(v):0{nd}x}\n" for v in np.asarray(words).reshape(-1)).encode("ascii")


def words_to_bin(words: np.ndarray, word_bits: int) -> bytes:
    """Raw little-endian binary of words of ``word_bits`` bits (as :func:`to_bin`)."""
    nb = (word_bits + 7) // 8
    le = np.ascontiguousarray(np.asarray(words, dtype=np.uint64).reshape(-1)).astype("<u8")
    return le.view(np.uint8).reshape(-1, 8)[:, :nb].tobytes()


def _method_fields(cfg: PipelineConfig) -> dict[str, object]:
    d = cfg.to_dict()
    return {k: v for k, v in d.items() if k not in (*_FORMAT_FIELDS, "name", "description")}


def write_method_image(directory: str | os.PathLike, coeffs: Any,
                       extra_files: tuple[str, ...] = (), fpa_sensor: Any = None,
                       housing_sensor: Any = None) -> dict[str, object]:
    """Write the memory images of a method's coefficients and their manifest.

    ``coeffs`` is a :class:`~irnuc.nuc_fixed.method_top.MethodCoefficients`. Plain
    two-point configurations write version 1 (:func:`write_memimage`); every other method
    version 2: ``NAME.hex`` and ``NAME.bin`` per calibration memory and a manifest with
    the method, its formats, every memory's layout and file hashes, the registers' values,
    width, height, the FPA and housing sensors of the calibration (``fpa_sensor``,
    ``housing_sensor``), the SHA-256 of
    every file (the images and ``extra_files``) and of every other field
    (:func:`seal_manifest`).
    """
    from irnuc.nuc_fixed.layout import layouts_dict

    cfg = coeffs.cfg
    coeffs.check()
    words = coeffs.words()
    if cfg.plain:
        return write_memimage(directory, words["coeffs"], cfg, extra_files, fpa_sensor,
                              housing_sensor)
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    h, w = coeffs.shape
    desc = layouts_dict(cfg)
    memories: dict[str, object] = {}
    for name, wd in words.items():
        layout = cfg.memories[name]
        write_bytes_atomic(d / f"{name}.bin", words_to_bin(wd, layout.word_bits))
        write_bytes_atomic(d / f"{name}.hex", words_to_hex(wd, layout.word_bits))
        memories[name] = {**desc["memories"][name],  # type: ignore[index]
                          "hex_file": f"{name}.hex", "bin_file": f"{name}.bin",
                          "bin_bytes_per_word": (layout.word_bits + 7) // 8}
    names = [n for m in memories.values() for n in (m["bin_file"], m["hex_file"])]  # type: ignore[index]
    files = {n: file_sha256(d / n) for n in (*names, *extra_files)}
    for m in memories.values():
        m["sha256"] = files[m["bin_file"]]  # type: ignore[index]
    fmt = format_fields(cfg)
    mfields = _method_fields(cfg)
    first = next(iter(memories))
    manifest: dict[str, object] = {
        "version": METHOD_IMAGE_VERSION,
        "config": cfg.name,
        "description": cfg.description,
        "method": cfg.method,
        **fmt,
        "method_fields": mfields,
        "format_sha256": _format_sha256({**fmt, "height": h, "width": w,
                                         "method_fields": mfields}),
        "word_bits": cfg.memories[first].word_bits,
        "memories": memories,
        "registers": {k: (list(v) if isinstance(v, tuple) else v)
                      for k, v in coeffs.registers.items()},
        "register_layout": desc["registers"],
        "runtime_memories": {k: v for k, v in desc["memories"].items()  # type: ignore[union-attr]
                             if v["source"] == "runtime"},
        "width": w,
        "height": h,
        "sha256": files[f"{first}.bin"],
        "files": files,
        "fpa_sensor": sensor_record(fpa_sensor),
        "housing_sensor": sensor_record(housing_sensor),
    }
    seal_manifest(manifest)
    write_bytes_atomic(d / MANIFEST_NAME, (json.dumps(manifest, indent=2) + "\n").encode())
    return manifest


def _same_config(mcfg: PipelineConfig, cfg: PipelineConfig | str | None, path: Path) -> None:
    """:class:`MemImageError` unless ``cfg`` (if given) is the configuration the
    coefficients were made for: every field (formats, method and stages, their
    parameters), whatever the names."""
    if cfg is None:
        return
    cfg = as_config(cfg)
    mine, theirs = mcfg.to_dict(), cfg.to_dict()
    diff = [k for k in dict.fromkeys([*mine, *theirs])
            if k not in ("name", "description") and mine.get(k) != theirs.get(k)]
    if diff:
        shown = "; ".join(f"{k} = {mine.get(k)!r} here, {theirs.get(k)!r} there"
                          for k in diff[:3]) + ("; ..." if len(diff) > 3 else "")
        raise MemImageError(f"{path}: the coefficients were made for pipeline {mcfg.name!r} "
                            f"(method {mcfg.method!r}), whose fields differ from pipeline "
                            f"{cfg.name!r} (method {cfg.method!r}): {shown}")


def read_method_image(directory: str | os.PathLike, cfg: PipelineConfig | str | None = None,
                      source: str = "bin") -> Any:
    """Read a memory image folder of any method back as ``MethodCoefficients``
    (:func:`read_calibration` without the manifest)."""
    return read_calibration(directory, cfg, source)[0]


def read_calibration(directory: str | os.PathLike, cfg: PipelineConfig | str | None = None,
                     source: str = "bin") -> tuple[Any, dict[str, object]]:
    """Read a memory image folder of any method back: ``(MethodCoefficients, manifest)``.

    Both versions get every check: the version; the format fields and every other field
    against their hashes; the whole configuration (formats, method and stages) against
    ``cfg`` if given; every file against its size limit and SHA-256; the sizes; and that
    every hex word equals the binary one. Version 1 folders (two-point) are read by
    :func:`read_memimage`.
    """
    from irnuc.nuc_fixed.method_top import MethodCoefficients

    if source not in ("bin", "hex"):
        raise ConfigError(f"source = {source!r} is not one of ['bin', 'hex']")
    d = Path(directory)
    manifest = read_manifest(d, versions=(MEMIMAGE_VERSION, METHOD_IMAGE_VERSION))
    try:
        mcfg = manifest_config(manifest)
    except (ConfigError, TypeError) as exc:
        raise MemImageError(f"{d / MANIFEST_NAME}: {exc}") from None
    _same_config(mcfg, cfg, d / MANIFEST_NAME)
    if manifest["version"] == MEMIMAGE_VERSION:
        words, mcfg = read_memimage(d, None, source)
        g, o, bad = unpack_words(words, mcfg)
        return (MethodCoefficients(mcfg, {"coeffs": {"gain": g, "offset": o, "bad": bad}}),
                manifest)
    h, w = int(manifest["height"]), int(manifest["width"])  # type: ignore[arg-type]
    mems = manifest["memories"]
    want = [m.name for m in mcfg.memories.values() if m.source == "calibration"]
    if sorted(mems) != sorted(want):  # type: ignore[arg-type]
        raise MemImageError(f"{d / MANIFEST_NAME}: memories {sorted(mems)} but method "  # type: ignore[arg-type]
                            f"{mcfg.method!r} has {want}")
    names: dict[str, int] = {}
    for name in want:
        m = mems[name]  # type: ignore[index]
        wb = mcfg.memories[name].word_bits
        if not isinstance(m, dict) or m.get("word_bits") != wb:
            raise MemImageError(f"{d / MANIFEST_NAME}: memory {name} has word_bits = "
                                f"{m.get('word_bits') if isinstance(m, dict) else m!r} but the "
                                f"formats give {wb}")
        for key in ("bin_file", "hex_file"):
            if not isinstance(m.get(key), str):
                raise MemImageError(f"{d / MANIFEST_NAME}: memory {name} has {key} = "
                                    f"{m.get(key)!r}; a file name is required")
            names[m[key]] = wb
    contents = check_files(d, manifest, _image_limits(names, h * w))
    words_by: dict[str, np.ndarray] = {}
    for name in want:
        m = mems[name]  # type: ignore[index]
        wb = mcfg.memories[name].word_bits
        nb = (wb + 7) // 8
        raw = contents[m["bin_file"]]
        if len(raw) != h * w * nb:
            raise MemImageError(f"{d / m['bin_file']}: {len(raw)} bytes, expected {h * w} "
                                f"words x {nb} bytes = {h * w * nb}")
        buf = np.zeros((h * w, 8), dtype=np.uint8)
        buf[:, :nb] = np.frombuffer(raw, dtype=np.uint8).reshape(h * w, nb)
        bw = buf.view("<u8").reshape(h, w).astype(np.uint64)
        hw = _parse_hex(d / m["hex_file"], contents[m["hex_file"]], wb, h * w).reshape(h, w)
        if not np.array_equal(hw, bw):
            idx = tuple(int(i) for i in np.argwhere(hw != bw)[0])
            raise MemImageError(f"{d / m['hex_file']}: word at (row, col) {idx} = "
                                f"{int(hw[idx]):x} differs from the binary ({int(bw[idx]):x})")
        words_by[name] = bw if source == "bin" else hw
    regs = manifest["registers"]
    try:
        return MethodCoefficients.from_words(mcfg, words_by, {
            k: (tuple(v) if isinstance(v, list) else v)
            for k, v in regs.items()}), manifest  # type: ignore[union-attr]
    except (UserError, TypeError) as exc:
        raise MemImageError(f"{d}: {exc}") from None
