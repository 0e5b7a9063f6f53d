"""The one documented cache directory of irnuc (builds, synthesis results, studies).

``$IRNUC_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/irnuc``, else ``~/.cache/irnuc``.
Everything in it is keyed by a digest of its inputs, so it is safe to share between
checkouts and runs and to delete at any time (docs/architecture.md).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any


def cache_dir(*parts: str) -> Path:
    """The cache root, or a folder under it (created)."""
    root = os.environ.get("IRNUC_CACHE_DIR")
    if root:
        base = Path(root)
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        base = Path(xdg) / "irnuc" if xdg else Path.home() / ".cache" / "irnuc"
    path = base.joinpath(*parts)
    path.mkdir(parents=True, exist_ok=True)
    return path


def read_cached_json(path: Path) -> Any:
    """A JSON file of the cache, or None when it is missing or unreadable (a result that is
    not there is to be made again, not an error)."""
    if not path.is_file():
        return None
    try:
        return json.loads(path.read_text())
    except (OSError, json.JSONDecodeError):
        return None
