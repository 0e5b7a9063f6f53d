"""The work-precision study's results, cached (``irnuc precision`` and ``irnuc report``).

A stored run is valid for the code it measured (:func:`code_digest`, a hash of the
model's sources and of the study's own code), at its depth (``quick``) and for its
components; it lives in the irnuc cache
(``precision/<digest>-<quick|full>-<components>.json``). ``irnuc precision`` stores every
run there; the report reuses it, or runs the study and stores it.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any


def code_digest() -> str:
    """Hash of what a stored precision run measured: the model's sources and the study's own
    code (its problems, references, sample sizes and budgets); valid for this code only."""
    from irnuc import model
    from irnuc.common.digest import named_files_digest, package_files
    from irnuc.reports.studies import precision

    return named_files_digest([*package_files(model),
                               *package_files(precision, "study", recursive=False)])


def _key(quick: bool, components: Sequence[str] | None, digest: str) -> str:
    from irnuc.reports.studies.precision import component_names

    names = component_names(components)
    tag = "all" if not components else hashlib.sha256(",".join(names).encode()).hexdigest()[:8]
    return f"{digest}-{'quick' if quick else 'full'}-{tag}"


def cache_file(quick: bool, components: Sequence[str] | None = None,
               digest: str | None = None) -> Path:
    from irnuc.common.cache import cache_dir

    key = _key(quick, components, digest or code_digest())
    return cache_dir("precision") / f"{key}.json"


def store_precision(result: dict[str, Any], components: Sequence[str] | None = None) -> Path:
    """Keep a study result in the cache (atomically), tagged with the code it measured."""
    from irnuc.common.io import write_text_atomic

    d = code_digest()
    path = cache_file(bool(result["quick"]), components, d)
    return write_text_atomic(path, json.dumps({**result, "code_digest": d}) + "\n")


def cached_precision(quick: bool = True, components: Sequence[str] | None = None, *,
                     run_if_missing: bool = True,
                     progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The full study result of the current model code: from the cache, else run (and
    stored). ``FileNotFoundError`` when absent and ``run_if_missing`` is false."""
    d = code_digest()
    path = cache_file(quick, components, d)
    if path.is_file():
        try:
            data = json.loads(path.read_text())
            if data.get("code_digest") == d and data.get("quick") == quick:
                return {**data, "cached": True}
        except (OSError, json.JSONDecodeError):
            pass  # a damaged entry is measured again
    if not run_if_missing:
        raise FileNotFoundError(f"{path}: no stored precision run of the current code; run "
                                "`irnuc precision`")
    from irnuc.reports.studies.precision import run_precision

    result = run_precision(quick=quick, components=components, progress=progress)
    store_precision(result, components)
    return {**result, "code_digest": d, "cached": False}
