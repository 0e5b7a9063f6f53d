"""Outputs that are never half-written or mixed.

* :func:`write_atomic` writes one file beside its target and renames it into place.
* :func:`output_folder` builds a multi-file result in a hidden sibling folder and swaps it
  into place as a unit (``renameat2(RENAME_EXCHANGE)`` on Linux), under a lock so that two
  runs on one folder cannot interleave; the previous result stays whole until the swap.
  Hidden leftovers of killed runs (``.NAME.tmp-*``) are removed by the next run that holds
  the lock.
* :func:`file_lock` is the advisory lock both use (``fcntl.flock``).
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import errno
import fcntl
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO, Any

from irnuc.common.errors import UserError


class OutputError(UserError):
    """An output path cannot be written (wrong kind of file, permission, busy)."""


def _umask() -> int:
    umask = os.umask(0)
    os.umask(umask)
    return umask


def write_atomic(path: str | Path, write: Callable[[IO[bytes]], Any]) -> Path:
    """Call ``write(fh)`` on a temporary file in the target folder, then rename it into place.

    A crash or an exception leaves no half-written file at ``path``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        # mkstemp creates the file private (0600); give it the usual permissions.
        os.chmod(tmp, 0o666 & ~_umask())
        with os.fdopen(fd, "wb") as fh:
            write(fh)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def write_bytes_atomic(path: str | Path, data: bytes) -> Path:
    """Write a bytes file atomically."""
    return write_atomic(path, lambda fh: fh.write(data))


def write_text_atomic(path: str | Path, text: str) -> Path:
    """Write a text file atomically (UTF-8)."""
    return write_atomic(path, lambda fh: fh.write(text.encode()))


def read_json_object(path: str | Path, what: str = "") -> dict[str, Any]:
    """A JSON file whose top level is an object; one-line :class:`UserError` otherwise.

    ``what`` (e.g. the flag that named the file) is put before the path in messages.
    """
    import json

    path = Path(path)
    name = f"{what} {path}" if what else str(path)
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        raise UserError(f"{name}: no such file") from None
    except IsADirectoryError:
        raise UserError(f"{name}: is a folder, not a JSON file") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise UserError(f"{name}: not a readable JSON file ({exc})") from None
    if not isinstance(data, dict):
        raise UserError(f"{name}: the top level is a {type(data).__name__}; a JSON object is "
                        "required")
    return data


@contextlib.contextmanager
def file_lock(path: str | Path, *, wait: bool = True, what: str = "") -> Iterator[None]:
    """Hold an exclusive advisory lock on ``path`` (created if missing).

    With ``wait=False`` a lock held by another process raises :class:`OutputError` naming
    ``what`` instead of waiting.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("a") as fh:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            raise OutputError(f"{what or path}: another irnuc run is writing it; wait for "
                              "it to finish or choose another output folder") from None
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


_RENAME_EXCHANGE = 2
_AT_FDCWD = -100


def _exchange(a: Path, b: Path) -> bool:
    """Atomically swap two paths (Linux ``renameat2``); False where unsupported."""
    libc_name = ctypes.util.find_library("c")
    if not libc_name:
        return False
    libc = ctypes.CDLL(libc_name, use_errno=True)
    fn = getattr(libc, "renameat2", None)
    if fn is None:
        return False
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


def check_output_folder(path: str | Path, flag: str = "--out") -> Path:
    """Check, before any work, that ``path`` can become an output folder.

    It may be missing or an existing folder (replaced as a whole); it may not be a file,
    and its parent must be writable.
    """
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise OutputError(f"{flag} {path}: exists and is not a folder; give a folder path")
    parent = path.absolute().parent
    probe = parent
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir():
        raise OutputError(f"{flag} {path}: {probe} is not a folder")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise OutputError(f"{flag} {path}: no permission to write in {probe}")
    return path


@contextlib.contextmanager
def output_folder(path: str | Path, flag: str = "--out") -> Iterator[Path]:
    """Yield an empty hidden sibling folder to fill; on success swap it in as ``path``.

    On an exception (or a kill) ``path`` keeps its previous content, whole. Two runs on
    one ``path`` do not interleave: the second fails at once with a clear message.
    """
    path = check_output_folder(path, flag)
    parent = path.absolute().parent
    parent.mkdir(parents=True, exist_ok=True)
    with file_lock(parent / f".{path.name}.lock", wait=False, what=f"{flag} {path}"):
        for stale in parent.glob(f".{path.name}.tmp-*"):
            shutil.rmtree(stale, ignore_errors=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.tmp-", dir=parent))
        os.chmod(tmp, 0o777 & ~_umask())
        try:
            yield tmp
            if path.is_dir():
                if _exchange(tmp, path):
                    shutil.rmtree(tmp, ignore_errors=True)  # now the previous result
                else:
                    old = Path(tempfile.mkdtemp(prefix=f".{path.name}.tmp-", dir=parent))
                    os.rename(path, old / "previous")
                    os.rename(tmp, path)
                    shutil.rmtree(old, ignore_errors=True)
            else:
                os.rename(tmp, path)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
