"""What every phase fills: the collected :class:`Report` (sections, metrics, figures,
phase times, notes)."""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

# Default tolerances of the baseline comparison (docs/reports.md): the pipeline is
# deterministic (same config + seed -> same bits), so counts must match exactly and float
# metrics within what a different numpy summation order could change.
FLOAT_REL_TOL = 1e-6
FLOAT_ABS_TOL = 1e-9

@dataclass
class Report:
    """Everything a run collects: sections, metrics, figures and phase times."""

    config: dict[str, Any]
    #: Each phase's result, typed and read-only (:mod:`irnuc.reports.report.sections`); a
    #: later phase adding to one stores a new section
    sections: dict[str, Any] = field(default_factory=dict)
    metrics: dict[str, dict[str, Any]] = field(default_factory=dict)
    figures: dict[str, list[tuple[str, bytes]]] = field(default_factory=dict)
    phases: dict[str, float] = field(default_factory=dict)
    #: CPU seconds (user + system, this process and all it started) per phase
    phases_cpu: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    verbose: bool = True
    #: The typed results of the studies, for the phases after the one that ran them
    #: (``sweep``: :class:`irnuc.reports.studies.sweep.SweepResult`); not serialised.
    studies: dict[str, Any] = field(default_factory=dict)

    def metric(self, name: str, value: float | int | None, better: str, unit: str = "",
               abs_tol: float | None = None, rel_tol: float | None = None) -> None:
        """Record one metric; ``better`` is lower, higher, equal or info (never compared)."""
        if value is not None:
            value = int(value) if isinstance(value, bool | np.bool_) else value
            value = float(value) if isinstance(value, float | np.floating) else int(value)
            if isinstance(value, float) and not math.isfinite(value):
                value = None
        exact = isinstance(value, int)
        self.metrics[name] = {
            "value": value, "better": better, "unit": unit,
            "abs_tol": float(abs_tol if abs_tol is not None else (0.0 if exact else FLOAT_ABS_TOL)),
            "rel_tol": float(rel_tol if rel_tol is not None else (0.0 if exact else FLOAT_REL_TOL)),
        }

    def figure(self, section: str, caption: str, png: bytes) -> None:
        self.figures.setdefault(section, []).append((caption, png))

    def say(self, text: str) -> None:
        if self.verbose:
            print(f"irnuc report: {text}", file=sys.stderr, flush=True)

    @contextmanager
    def phase(self, name: str) -> Iterator[None]:
        from irnuc.common.cputime import tree_cpu_seconds

        t0, c0 = time.perf_counter(), tree_cpu_seconds()
        self.say(f"{name} ...")
        try:
            yield
        finally:
            self.phases[name] = round(self.phases.get(name, 0.0) + time.perf_counter() - t0, 3)
            self.phases_cpu[name] = round(self.phases_cpu.get(name, 0.0) + max(
                0.0, tree_cpu_seconds() - c0), 3)


def progress(label: str, enabled: bool) -> Callable[[int, int], None] | None:
    if not enabled:
        return None
    from irnuc.common.progress import ProgressBar

    return ProgressBar(label)

