"""The work-precision study's results, cached (``irnuc precision`` and ``irnuc report``).

A stored run is valid for the model code it measured (:func:`code_digest`, a hash of the
model's sources), at its depth (``quick``) and for its components; it lives in the irnuc
cache (``precision/<digest>-<quick|full>-<components>.json``). ``irnuc precision`` stores
every run there; the report reuses it, or runs the study and stores it.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any


def code_digest() -> str:
    """Hash of the model's source files: a stored precision run is valid for this code only."""
    from irnuc import model

    root = Path(model.__file__).parent
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(path.relative_to(root).as_posix().encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


def _key(quick: bool, components: Sequence[str] | None) -> str:
    from irnuc.reports.studies.precision import component_names

    names = component_names(components)
    tag = "all" if not components else hashlib.sha256(",".join(names).encode()).hexdigest()[:8]
    return f"{code_digest()}-{'quick' if quick else 'full'}-{tag}"


def cache_file(quick: bool, components: Sequence[str] | None = None) -> Path:
    from irnuc.common.cache import cache_dir

    return cache_dir("precision") / f"{_key(quick, components)}.json"


def store_precision(result: dict[str, Any], components: Sequence[str] | None = None) -> Path:
    """Keep a study result in the cache (atomically), tagged with the code it measured."""
    from irnuc.common.io import write_text_atomic

    path = cache_file(bool(result["quick"]), components)
    return write_text_atomic(path, json.dumps({**result, "code_digest": code_digest()}) + "\n")


def cached_precision(quick: bool = True, components: Sequence[str] | None = None, *,
                     run_if_missing: bool = True,
                     progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The full study result of the current model code: from the cache, else run (and
    stored). ``FileNotFoundError`` when absent and ``run_if_missing`` is false."""
    path = cache_file(quick, components)
    if path.is_file():
        try:
            data = json.loads(path.read_text())
            if data.get("code_digest") == code_digest() and data.get("quick") == quick:
                return {**data, "cached": True}
        except (OSError, json.JSONDecodeError):
            pass  # a damaged entry is measured again
    if not run_if_missing:
        raise FileNotFoundError(f"{path}: no stored precision run of the current code; run "
                                "`irnuc precision`")
    from irnuc.reports.studies.precision import run_precision

    result = run_precision(quick=quick, components=components, progress=progress)
    store_precision(result, components)
    return {**result, "code_digest": code_digest(), "cached": False}
