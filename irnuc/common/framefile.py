"""The frame file: an uncompressed ``.npz``, written frame chunk by frame chunk and read
memory-mapped.

A frame file is an ordinary ``.npz`` (a ZIP archive of ``.npy`` arrays, as
``numpy.savez`` writes and ``numpy.load`` reads), with every member *stored* (ZIP_STORED,
no compression; ZIP64 for members past 4 GiB). So

* :class:`FrameWriter` streams the frames into the ``codes`` member chunk by chunk: the
  writer never holds more than one chunk, whatever the number of frames;
* :func:`open_member` maps a stored member straight from the file (``numpy.memmap`` at the
  member's data offset), so a reader touches only the frames it uses;
* ``numpy.load`` reads it like any other ``.npz``; a compressed ``.npz`` (older irnuc, or
  ``numpy.savez_compressed``) still reads, by loading instead of mapping.

The cost is disk: 2 bytes per code (16-bit codes), 614 kB per VGA frame (docs/sequences.md).
"""

from __future__ import annotations

import struct
import zipfile
from collections.abc import Mapping
from pathlib import Path
from typing import IO, Any

import numpy as np
from numpy.lib import format as npformat

#: Version of the frame file's layout of keys (docs/sequences.md, "File format").
FORMAT_VERSION = 3

_LOCAL_HEADER = struct.Struct("<4s2B4HL2L2H")  # the ZIP local file header, 30 bytes
_LOCAL_MAGIC = b"PK\x03\x04"


def _npy_header(shape: tuple[int, ...], dtype: np.dtype) -> bytes:
    """The ``.npy`` header of a C-ordered array of ``shape`` and ``dtype``."""
    import io

    buf = io.BytesIO()
    header = {"descr": npformat.dtype_to_descr(np.dtype(dtype)), "fortran_order": False,
              "shape": tuple(int(s) for s in shape)}
    npformat.write_array_header_2_0(buf, header)
    return buf.getvalue()


class FrameWriter:
    """Write a frame file: ``codes`` (N, H, W) streamed in chunks, the rest at the end.

    Parameters
    ----------
    path : path
        The file to write (the caller writes it aside and renames it into place).
    n_frames : int
        Frames the file will hold; :meth:`close` refuses fewer.
    frame_shape : (int, int)
        (H, W) of a frame.
    dtype : numpy dtype
        Dtype of the codes (uint16 up to 16-bit codes).

    Use as a context manager; :meth:`write` takes (n, H, W) chunks in order and
    :meth:`close` adds the other arrays (small: per-frame fields, maps, metadata).
    """

    def __init__(self, path: str | Path, n_frames: int, frame_shape: tuple[int, int],
                 dtype: Any) -> None:
        self.path = Path(path)
        self.n_frames = int(n_frames)
        self.frame_shape = (int(frame_shape[0]), int(frame_shape[1]))
        self.dtype = np.dtype(dtype)
        self.written = 0
        self._zip = zipfile.ZipFile(self.path, "w", zipfile.ZIP_STORED, allowZip64=True)
        self._member: IO[bytes] | None = self._zip.open("codes.npy", "w", force_zip64=True)
        self._member.write(_npy_header((self.n_frames, *self.frame_shape), self.dtype))

    def write(self, chunk: np.ndarray) -> None:
        """Append frames (n, H, W) to ``codes``."""
        if self._member is None:
            raise ValueError("frame file: codes already closed")
        if chunk.shape[1:] != self.frame_shape or chunk.dtype != self.dtype:
            raise ValueError(f"frame file: chunk {chunk.shape} {chunk.dtype}, expected "
                             f"(n, {self.frame_shape[0]}, {self.frame_shape[1]}) {self.dtype}")
        if self.written + chunk.shape[0] > self.n_frames:
            raise ValueError(f"frame file: more than the {self.n_frames} frames declared")
        self._member.write(memoryview(np.ascontiguousarray(chunk)).cast("B"))
        self.written += chunk.shape[0]

    def close(self, arrays: Mapping[str, Any] | None = None) -> None:
        """Finish ``codes`` and write the other arrays (each stored as ``NAME.npy``)."""
        if self._member is not None:
            if self.written != self.n_frames:
                self.abort()
                raise ValueError(f"frame file: {self.written} of {self.n_frames} frames written")
            self._member.close()
            self._member = None
        for name, value in (arrays or {}).items():
            arr = np.asanyarray(value)
            if arr.dtype.hasobject:
                raise ValueError(f"frame file: {name} is an object array")
            with self._zip.open(f"{name}.npy", "w", force_zip64=arr.nbytes > 2**31) as fh:
                npformat.write_array(fh, arr, allow_pickle=False)
        self._zip.close()

    def abort(self) -> None:
        """Close without finishing (the caller removes the file)."""
        try:
            if self._member is not None:
                self._member.close()
                self._member = None
            self._zip.close()
        except (OSError, ValueError):
            pass

    def __enter__(self) -> FrameWriter:
        return self

    def __exit__(self, exc_type: Any, *_: Any) -> None:
        if exc_type is not None:
            self.abort()


def member_data_offset(path: str | Path, info: zipfile.ZipInfo) -> int:
    """Byte offset, in the file, of a stored member's data (past its local header)."""
    with open(path, "rb") as fh:
        fh.seek(info.header_offset)
        raw = fh.read(_LOCAL_HEADER.size)
    fields = _LOCAL_HEADER.unpack(raw)
    if fields[0] != _LOCAL_MAGIC:
        raise ValueError(f"{info.filename}: no local header at {info.header_offset}")
    name_len, extra_len = fields[-2], fields[-1]
    return info.header_offset + _LOCAL_HEADER.size + name_len + extra_len


def check_member_size(info: zipfile.ZipInfo, header_len: int, shape: tuple[int, ...],
                      dtype: np.dtype, where: str) -> None:
    """ValueError unless a ``.npy`` member stores exactly the bytes its header declares
    (``header_len`` bytes of header, then the array): a header that disagrees with the
    stored size would map other members' bytes as codes, or too few."""
    import math

    want = math.prod(shape) * dtype.itemsize
    have = info.file_size - header_len
    if have != want:
        raise ValueError(f"{where}: its header declares shape {shape} {dtype} ({want} bytes) "
                         f"but {have} bytes are stored; the file is damaged")


def open_member(path: str | Path, zf: zipfile.ZipFile, name: str,
                mmap: bool = True) -> np.ndarray:
    """The array ``NAME.npy`` of an open ``.npz``: mapped from the file when it is stored
    uncompressed (and ``mmap``), else read (a compressed member). No pickles; a member
    whose header disagrees with its stored size is a ValueError."""
    info = zf.getinfo(f"{name}.npy")
    if mmap and info.compress_type == zipfile.ZIP_STORED:
        with zf.open(info) as fh:
            version = npformat.read_magic(fh)
            read = (npformat.read_array_header_1_0 if version == (1, 0)
                    else npformat.read_array_header_2_0)
            shape, fortran, dtype = read(fh)
            header_len = fh.tell()
        check_member_size(info, header_len, tuple(shape), dtype, name)
        if not dtype.hasobject and int(np.prod(shape)) * dtype.itemsize > 0:
            offset = member_data_offset(path, info) + header_len
            return np.memmap(path, dtype=dtype, mode="r", offset=offset, shape=shape,
                             order="F" if fortran else "C")
    with zf.open(info) as fh:
        return npformat.read_array(fh, allow_pickle=False)
