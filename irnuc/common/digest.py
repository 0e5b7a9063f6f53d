"""One digest for configurations, caches and provenance: SHA-256 of canonical JSON."""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterable
from pathlib import Path
from typing import Any

#: Hex digits kept: 64 bits, plenty to tell configurations and sources apart.
DIGEST_CHARS = 16


def digest(obj: Any) -> str:
    """Short SHA-256 of ``obj`` as canonical JSON (sorted keys; non-JSON values as str)."""
    text = json.dumps(obj, sort_keys=True, default=str, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:DIGEST_CHARS]


def file_sha256(path: str | Path) -> str:
    """Full SHA-256 of a file's bytes (hex)."""
    h = hashlib.sha256()
    with Path(path).open("rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def files_digest(paths: Iterable[str | Path], extra: Any = None) -> str:
    """Short digest of several files (names and bytes) and an optional JSON-able extra."""
    h = hashlib.sha256()
    for p in paths:
        p = Path(p)
        h.update(p.name.encode())
        h.update(p.read_bytes())
    h.update(json.dumps(extra, sort_keys=True, default=str).encode())
    return h.hexdigest()[:DIGEST_CHARS]


def package_files(module: Any, tag: str = "", patterns: tuple[str, ...] = ("*.py",),
                  recursive: bool = True) -> list[tuple[str, Path]]:
    """The source files of the package holding ``module`` (its folder; sub-folders too when
    ``recursive``) matching ``patterns``, sorted, each named by its path under the folder
    (``<tag>/<path>`` with a ``tag``): the inputs of :func:`named_files_digest`."""
    root = Path(module.__file__).parent
    find = root.rglob if recursive else root.glob
    paths = sorted({p for pat in patterns for p in find(pat)})
    return [(f"{tag}/{p.relative_to(root).as_posix()}" if tag else p.relative_to(root).as_posix(),
             p) for p in paths]


def named_files_digest(files: Iterable[tuple[str, str | Path]]) -> str:
    """Short digest of (name, file) pairs, names and bytes in order: what a stored result of
    a study measured (the code it ran)."""
    h = hashlib.sha256()
    for name, path in files:
        h.update(name.encode())
        h.update(Path(path).read_bytes())
    return h.hexdigest()[:DIGEST_CHARS]
