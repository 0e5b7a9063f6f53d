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
    #: Work started beside the phases (:meth:`start_background`): name -> its start and end
    #: (s since the report started) and its error, if any.
    background: dict[str, dict[str, Any]] = field(default_factory=dict)
    _jobs: dict[str, Any] = field(default_factory=dict, repr=False)
    #: What each background job returned (:meth:`background_value`)
    _values: dict[str, Any] = field(default_factory=dict, repr=False)
    _pool: Any = field(default=None, repr=False)
    _t0: float = field(default_factory=time.perf_counter, repr=False)

    def start_background(self, name: str, fn: Callable[..., Any], *args: Any) -> None:
        """Run ``fn(*args)`` in a thread beside the phases: work whose inputs are known
        early and whose results land in the cache (syntheses, Verilator builds), started
        while a single-threaded phase leaves a core idle. The phase that needs it calls
        :meth:`join_background` first; a failure there is only recorded (the phase does
        the work again and reports its own error). It runs niced
        (:func:`irnuc.common.executor.background_priority`: its tools and pool workers
        too), so it takes the cores the phases leave idle rather than slowing them. A
        phase's CPU (``phases_cpu``) counts the whole process tree, so it includes the
        background work running beside it."""
        import concurrent.futures as cf

        from irnuc.common.executor import start_forkserver

        if self._pool is None:
            self._pool = cf.ThreadPoolExecutor(max_workers=3, thread_name_prefix="irnuc-bg")
        start_forkserver()  # from this thread, at its priority (the background's are lower)
        rec: dict[str, Any] = {"start_s": round(time.perf_counter() - self._t0, 3)}
        self.background[name] = rec

        def run() -> None:
            from irnuc.common.executor import background_priority

            try:
                # at a lower priority: it takes the cores the phases leave idle
                with background_priority():
                    self._values[name] = fn(*args)
            except Exception as exc:  # the phase that needs it does it again
                rec["error"] = f"{type(exc).__name__}: {str(exc).splitlines()[0][:300]}" \
                    if str(exc) else type(exc).__name__
            finally:
                rec["end_s"] = round(time.perf_counter() - self._t0, 3)
                self.say(f"{name} finished in the background")

        self._jobs[name] = self._pool.submit(run)
        self.say(f"{name} started in the background")

    def join_background(self, name: str) -> dict[str, Any] | None:
        """Wait for the background job ``name`` (none started: None); its record."""
        job = self._jobs.pop(name, None)
        if job is None:
            return None
        t0 = time.perf_counter()
        job.result()
        rec = self.background[name]
        rec["waited_s"] = round(time.perf_counter() - t0, 3)
        return rec

    def background_value(self, name: str) -> Any:
        """What the background job ``name`` returned (None: not run, not finished or
        failed)."""
        return self._values.get(name)

    def close_background(self) -> None:
        """Wait for every background job (the report ends with none running)."""
        for name in list(self._jobs):
            self.join_background(name)
        if self._pool is not None:
            self._pool.shutdown(wait=True)
            self._pool = None

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


def left_out(rep: Report, section: str, what: str, key: str) -> str:
    """Name in the report's notes what this run left out, and return the note:
    ``<section>: not run in --quick: <what>`` (``--quick``'s ``[quick]`` table), else
    ``<section>: not run (<key>)`` (the configuration's ``key``). A cut is named, never
    counted as a check."""
    how = "not run in --quick" if rep.config.get("quick") else f"not run ({key})"
    note = f"{section}: {how}: {what}"
    rep.notes.append(note)
    return note


def progress(label: str, enabled: bool) -> Callable[[int, int], None] | None:
    if not enabled:
        return None
    from irnuc.common.progress import ProgressBar

    return ProgressBar(label)

