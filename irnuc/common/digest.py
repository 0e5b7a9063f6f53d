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
