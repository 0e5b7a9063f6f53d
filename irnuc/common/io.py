"""Outputs that are never half-written or mixed.

* :func:`write_atomic` writes one file beside its target and renames it into place.
* :func:`output_folder` builds a multi-file result in a hidden sibling folder and swaps it
  into place as a unit (``renameat2(RENAME_EXCHANGE)`` on Linux), under a lock so that two
  runs on one folder cannot interleave; the previous result stays whole until the swap.
  Hidden leftovers of killed runs (``.NAME.tmp-*``) are removed by the next run that holds
  the lock. It replaces only what irnuc wrote: an existing folder must be empty or carry
  the marker file (``.irnuc-output``) of the same command, so a careless ``--out ~`` never
  deletes a user's files.
* :func:`claim_output_folder` takes that lock before the work, so a second run on one
  folder fails at once instead of after its work.
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


#: Errors of the writing itself, not of the path: a full disk, a file-size limit
#: (``ulimit -f``), a quota.
WRITE_ERRNOS = frozenset({errno.ENOSPC, errno.EFBIG, errno.EDQUOT})


class WriteError(OutputError):
    """An output could not be written (disk full, file too large); what was there before
    is left whole. ``path`` is the file, ``errno`` the operating system's error."""

    def __init__(self, message: str, path: Path, errno_: int) -> None:
        super().__init__(message)
        self.path = path
        self.errno = errno_


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
    except OSError as exc:
        Path(tmp).unlink(missing_ok=True)
        if exc.errno not in WRITE_ERRNOS:
            raise
        kept = "the previous file is left whole" if path.exists() else "nothing was written"
        raise WriteError(f"{path}: cannot be written ({os.strerror(exc.errno)}); {kept}",
                         path, exc.errno) from None
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


#: What a name that becomes a file or folder name may hold: letters, digits, ``_ . -``,
#: starting with a letter or digit (no separator, no ``..``, nothing hidden), at most 64.
PLAIN_NAME = r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,63}$"


def plain_name(name: str, what: str) -> str:
    """``name`` if it can be one file or folder name inside an output folder; a one-line
    :class:`UserError` naming ``what`` otherwise (a name never becomes a path)."""
    import re

    if not isinstance(name, str) or not re.fullmatch(PLAIN_NAME, name):
        raise UserError(f"{what} = {name!r} cannot name a file or folder: use letters, "
                        "digits, '_', '.' and '-' (at most 64, starting with a letter or digit)")
    return name


#: The most irnuc reads of a configuration, manifest, baseline or report file (they are
#: kilobytes): a device, a pipe or a wrong file is refused before it fills the memory.
MAX_TEXT_BYTES = 16 * 2**20


def read_bytes_capped(path: str | Path, what: str = "", limit: int = MAX_TEXT_BYTES) -> bytes:
    """The bytes of a file the user named, reading at most ``limit`` (one-line
    :class:`UserError` naming ``what`` (e.g. the flag) and the path otherwise).

    Any kind of file is read (``/dev/stdin``, a pipe) but never more than ``limit`` + 1
    bytes, so ``/dev/zero`` or a multi-gigabyte file is an error at once.
    """
    path = Path(path)
    name = f"{what} {path}" if what else str(path)
    guard_input(path, what)
    try:
        with path.open("rb") as fh:
            data = fh.read(limit + 1)
    except FileNotFoundError:
        raise UserError(f"{name}: no such file") from None
    except IsADirectoryError:
        raise UserError(f"{name}: is a folder, not a file") from None
    except OSError as exc:
        raise UserError(f"{name}: cannot be read ({exc.strerror or exc})") from None
    if len(data) > limit:
        raise UserError(f"{name}: larger than {_size_text(limit)}, the most irnuc reads of such "
                        "a file; is it the right file?")
    return data


def guard_input(path: str | Path, what: str = "") -> None:
    """Refuse to read ``path`` when it lies inside an output folder this process has
    claimed (:func:`claim_output_folder`): replacing that folder would delete it.

    Every reader of a user's file calls it (:func:`read_bytes_capped` does), so an input
    named inside another input (a sequence's table CSV, a manifest's files) is refused
    like one named on the command line, before its content is used.
    """
    if not _CLAIMS:
        return
    q = Path(os.path.realpath(os.path.abspath(path)))
    for p, name in _CLAIM_NAMES.items():
        if p in _CLAIMS and (q == p or q.is_relative_to(p)):
            shown = f"{what} {path}" if what else str(path)
            raise OutputError(f"{name}: holds {shown}, which this command reads and would "
                              "replace; give another output folder")


def _size_text(n: int) -> str:
    return f"{n / 2**20:g} MiB" if n >= 2**20 else f"{n} bytes"


def parse_json(data: bytes, name: str) -> Any:
    """A JSON document (UTF-8); one-line :class:`UserError` naming ``name`` for anything
    that is not one: bad syntax or encoding, nesting too deep for the parser, an integer
    too long to convert."""
    import json

    try:
        return json.loads(data.decode("utf-8"))
    except RecursionError:
        raise UserError(f"{name}: not a readable JSON file (nested too deeply)") from None
    except (UnicodeDecodeError, ValueError) as exc:  # JSONDecodeError, int digit limit
        raise UserError(f"{name}: not a readable JSON file ({exc})") from None


def read_json_object(path: str | Path, what: str = "", limit: int = MAX_TEXT_BYTES
                     ) -> dict[str, Any]:
    """A JSON file whose top level is an object; one-line :class:`UserError` otherwise.

    ``what`` (e.g. the flag that named the file) is put before the path in messages; at
    most ``limit`` bytes are read (:func:`read_bytes_capped`).
    """
    path = Path(path)
    name = f"{what} {path}" if what else str(path)
    data = parse_json(read_bytes_capped(path, what, limit), name)
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


#: Name of the marker file every output folder holds: "irnuc <command>". An existing
#: folder without it (and not empty) is not irnuc's to replace.
MARKER_NAME = ".irnuc-output"

#: Output folders this process has claimed (path -> open lock file), see
#: :func:`claim_output_folder`.
_CLAIMS: dict[Path, IO[str]] = {}
#: How each claimed folder was given (``--out out/cal``), for messages.
_CLAIM_NAMES: dict[Path, str] = {}


def _absolute(path: Path) -> Path:
    """``path`` made absolute with ``.``/``..`` removed and the parent's links resolved
    (the last component is kept, so a link there is seen as a link)."""
    a = Path(os.path.abspath(path))
    return Path(os.path.realpath(a.parent)) / a.name if a.name else a


def _marker_text(kind: str | None) -> str:
    return f"irnuc {kind or 'output'}\n"


def _read_marker(folder: Path) -> str | None:
    try:
        return (folder / MARKER_NAME).read_text(errors="replace").strip()
    except OSError:
        return None


def _nested_output(folder: Path) -> Path | None:
    """The first folder below ``folder`` that is another irnuc output (its marker file)."""
    for root, dirs, files in os.walk(folder):
        if MARKER_NAME in files and Path(root) != folder:
            return Path(root)
        dirs.sort()
    return None


def check_output_folder(path: str | Path, flag: str = "--out", *, kind: str | None = None,
                        inputs: dict[str, str | Path | None] | None = None) -> Path:
    """Check, before any work, that ``path`` can become an output folder.

    It may be missing, an empty folder, or a folder irnuc wrote before for the same
    ``kind`` (command), as its marker file says: that one is replaced as a whole. Anything
    else is refused, so that irnuc never deletes a user's own files: a file, a link, a
    folder with other content, a folder holding the current folder or one of the
    ``inputs`` (``{flag: path}`` of what the command reads). Its parent must be writable.
    """
    given = Path(path)
    name = f"{flag} {given}"
    if not str(path).strip():
        raise OutputError(f"{flag} is empty; give a folder path")
    p = _absolute(given)
    if not p.name or p == Path(p.anchor):
        raise OutputError(f"{name}: is the root folder; give a folder of its own")
    if p.is_symlink():
        raise OutputError(f"{name}: is a symbolic link; give the folder it points to "
                          f"({os.path.realpath(p)}) or a new folder")
    if p.exists() and not p.is_dir():
        raise OutputError(f"{name}: exists and is not a folder; give a folder path")
    cwd = Path(os.path.realpath(os.getcwd()))
    if cwd == p or cwd.is_relative_to(p):
        raise OutputError(f"{name}: holds the current folder, which irnuc would replace as a "
                          "whole; give another folder")
    for in_flag, value in (inputs or {}).items():
        if value is None or not str(value):
            continue
        q = Path(os.path.realpath(os.path.abspath(value)))
        if q == p or q.is_relative_to(p):
            raise OutputError(f"{name}: holds {in_flag} {value}, which this command reads and "
                              "would replace; give another output folder")
    for outer in p.parents:  # inside another output, the next run of that one deletes it
        marker = _read_marker(outer)
        if marker is not None:
            raise OutputError(f"{name}: is inside {outer}, the output of `{marker}`, which its "
                              f"next run replaces as a whole ({flag} with it); give a folder "
                              "outside it")
    if p.is_dir():
        try:
            entries = [e.name for e in os.scandir(p)]
        except OSError as exc:
            raise OutputError(f"{name}: cannot be read ({exc.strerror})") from None
        if entries:
            marker = _read_marker(p)
            if marker is None:
                raise OutputError(
                    f"{name}: is a folder with other content (no {MARKER_NAME} marker of an "
                    "irnuc output); irnuc replaces --out as a whole, so give a new or empty "
                    "folder")
            if kind is not None and marker not in (_marker_text(kind).strip(), "irnuc output"):
                raise OutputError(f"{name}: holds the output of `{marker}`, not of `irnuc "
                                  f"{kind}`; give another folder")
            nested = _nested_output(p)
            if nested is not None:
                raise OutputError(f"{name}: holds {nested.relative_to(p)}, the output of "
                                  f"`{_read_marker(nested)}`, which replacing {flag} as a whole "
                                  "would delete; move it out or give another folder")
    parent = p.parent
    probe = parent
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir():
        raise OutputError(f"{name}: {probe} is not a folder")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise OutputError(f"{name}: no permission to write in {probe}")
    return given


def claim_output_folder(path: str | Path, flag: str = "--out", *, kind: str | None = None,
                        inputs: dict[str, str | Path | None] | None = None) -> Path:
    """:func:`check_output_folder`, then take the folder's lock before the work starts.

    A second run on the same folder then fails at once (not after its work). The lock is
    held until :func:`output_folder` on the same path finishes, :func:`release_claims` is
    called, or the process ends.
    """
    given = check_output_folder(path, flag, kind=kind, inputs=inputs)
    p = _absolute(given)
    if p in _CLAIMS:
        return given
    p.parent.mkdir(parents=True, exist_ok=True)
    fh = _lock_output(p, f"{flag} {given}")
    _CLAIMS[p] = fh
    _CLAIM_NAMES[p] = f"{flag} {given}"
    _remove_stale(p)
    return given


def _lock_path(p: Path) -> Path:
    return p.parent / f".{p.name}.lock"


def _lock_output(p: Path, what: str) -> IO[str]:
    """Take the lock ``.NAME.lock`` of output folder ``p`` without waiting (an open file
    holding the flock); :class:`OutputError` naming ``what`` when another run holds it.

    The lock file is removed when the lock is released (:func:`_unlock_output`), so a run
    leaves nothing beside ``--out``. A run that opened the file just before another
    removed it holds a lock on a name that is gone: it sees that the path is no longer its
    file and tries again on the new one.
    """
    path = _lock_path(p)
    for _ in range(100):
        fh = path.open("a")
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            fh.close()
            raise OutputError(f"{what}: another irnuc run is writing it; wait for it to "
                              "finish or choose another output folder") from None
        try:
            same = os.stat(path).st_ino == os.fstat(fh.fileno()).st_ino
        except FileNotFoundError:
            same = False
        if same:
            return fh
        fh.close()  # removed (or replaced) by the run that held it: take the new one
    raise OutputError(f"{what}: its lock file {path} keeps changing; is another program "
                      "removing it?")


def _unlock_output(p: Path, fh: IO[str]) -> None:
    """Remove the lock file while holding it, then release it (closing the file)."""
    with contextlib.suppress(OSError):
        if os.stat(_lock_path(p)).st_ino == os.fstat(fh.fileno()).st_ino:
            os.unlink(_lock_path(p))
    fh.close()


def release_claims() -> None:
    """Release every output folder lock this process holds (the command line calls it
    when a command ends, however it ends)."""
    for p in list(_CLAIMS):
        _release(p)


def _release(p: Path) -> None:
    fh = _CLAIMS.pop(p, None)
    _CLAIM_NAMES.pop(p, None)
    if fh is not None:
        _unlock_output(p, fh)  # closing the file releases the flock


def _remove_stale(p: Path) -> None:
    """Under the lock of ``p`` every temporary folder of its name is a killed run's."""
    for stale in p.parent.glob(f".{p.name}.tmp-*"):
        _remove_tree(stale)


def _remove_tree(path: Path) -> None:
    """Remove a folder, or a link or file left where a temporary folder was."""
    if path.is_symlink() or not path.is_dir():
        path.unlink(missing_ok=True)
    else:
        shutil.rmtree(path, ignore_errors=True)


@contextlib.contextmanager
def output_folder(path: str | Path, flag: str = "--out", *, kind: str | None = None
                  ) -> Iterator[Path]:
    """Yield an empty hidden sibling folder to fill; on success swap it in as ``path``.

    On an exception (or a kill) ``path`` keeps its previous content, whole. Two runs on
    one ``path`` do not interleave: the second fails at once with a clear message. The
    folder gets the marker file of ``kind`` (see :func:`check_output_folder`).
    """
    given = check_output_folder(path, flag, kind=kind)
    p = _absolute(given)
    parent = p.parent
    parent.mkdir(parents=True, exist_ok=True)
    held = p in _CLAIMS
    if not held:
        _CLAIMS[p] = _lock_output(p, f"{flag} {given}")
        _CLAIM_NAMES[p] = f"{flag} {given}"
    try:
        _remove_stale(p)
        tmp = Path(tempfile.mkdtemp(prefix=f".{p.name}.tmp-", dir=parent))
        os.chmod(tmp, 0o777 & ~_umask())
        try:
            try:
                yield tmp
                (tmp / MARKER_NAME).write_text(_marker_text(kind))
            except (OSError, WriteError) as exc:  # named by --out, not the hidden folder
                if exc.errno not in WRITE_ERRNOS:
                    raise
                raise _folder_write_error(exc, tmp, p, f"{flag} {given}") from None
            if p.is_dir():
                if _exchange(tmp, p):
                    shutil.rmtree(tmp, ignore_errors=True)  # now the previous result
                else:
                    old = Path(tempfile.mkdtemp(prefix=f".{p.name}.tmp-", dir=parent))
                    os.rename(p, old / "previous")
                    os.rename(tmp, p)
                    shutil.rmtree(old, ignore_errors=True)
            else:
                os.rename(tmp, p)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
    finally:
        _release(p)


def _folder_write_error(exc: OSError | WriteError, tmp: Path, p: Path, name: str) -> WriteError:
    """A write error while an output folder was being filled, told by the folder's name and
    the file's name inside it (not the hidden temporary folder's)."""
    f = getattr(exc, "path", None) or exc.filename
    inner = ""
    if f is not None:
        with contextlib.suppress(ValueError):
            inner = f"{Path(os.path.abspath(f)).relative_to(tmp)}: "
    kept = ("its previous content is left whole" if p.exists() else "nothing was written")
    return WriteError(f"{name}: {inner}cannot be written ({os.strerror(exc.errno or 0)}); {kept}",
                      p, exc.errno or 0)
