"""The timing and bookkeeping of the work-precision study: points, the Pareto front,
timed calls after a warm-up, failed settings, and double-double errors."""

from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

#: A point dominates another only if it is faster (or cheaper) by this factor and more
#: accurate by ERROR_MARGIN: run-time noise on a shared machine must not decide the front.
TIME_MARGIN = 1.5
ERROR_MARGIN = 4.0
#: Errors below this are "exact to double precision" and compare equal.
ERROR_FLOOR = 1e-15
#: A timed call (after its untimed warm-up) is repeated only while the repeats together
#: stay below this, s.
TIME_BUDGET = 0.6
#: Substep budget per pulse and pixel of the transient studies: beyond, a failed point.
TRANSIENT_BUDGET = 10_000


@dataclass
class Point:
    """One measurement.

    ``error`` is None for a failed point (``failed`` set, ``reason`` the message);
    ``time_s`` is then the time the failing call took and ``work`` the work done until it
    failed, when known (None for a refusal before any step).
    """

    method: str
    setting_name: str
    setting: float
    error: float | None
    time_s: float | None
    work: float | None = None
    reason: str | None = None
    default: bool = False
    on_front: bool | None = None
    on_front_work: bool | None = None
    failed: bool = False


def single_thread() -> contextlib.AbstractContextManager[None]:
    """Time on one numba thread: on a shared machine, waiting for a second busy core
    would dominate the small problems and make the timings noise."""
    from irnuc.model.graph import threads_for

    return threads_for(0)


def best_time(fn: Callable[[], Any], repeats: int) -> float:
    """Minimum wall time of up to ``repeats`` calls of ``fn`` (at least one), s; call it
    after a warm-up call. Slow calls are not repeated past TIME_BUDGET."""
    best = math.inf
    spent = 0.0
    for _ in range(max(1, repeats)):
        if spent > TIME_BUDGET:
            break
        t0 = time.perf_counter()
        fn()
        dt = time.perf_counter() - t0
        best = min(best, dt)
        spent += dt
    return best


def _dominates(p: Point, q: Point, axis: str) -> bool:
    if p.error is None or q.error is None:
        return False
    cp, cq = (p.time_s, q.time_s) if axis == "time" else (p.work, q.work)
    if cp is None or cq is None:
        return False
    ep = max(p.error, ERROR_FLOOR)
    eq = max(q.error, ERROR_FLOOR)
    return cp * TIME_MARGIN <= cq and ep * ERROR_MARGIN <= eq


def dominates(p: Point, q: Point) -> bool:
    """True if ``p`` is clearly both faster and more accurate than ``q``."""
    return _dominates(p, q, "time")


def mark_front(points: list[Point]) -> None:
    """Set ``on_front`` (by run time) and ``on_front_work`` (by work, among the points of
    the same work unit: the whole component) of every measured point; None if failed."""
    for q in points:
        ok = q.error is not None
        q.on_front = not any(_dominates(p, q, "time") for p in points) if ok else None
        q.on_front_work = (not any(_dominates(p, q, "work") for p in points)
                           if ok and q.work is not None else None)


Runner = tuple[Callable[[], Any], Callable[[Any], tuple[float, float]]]


class SettingFailed(RuntimeError):
    """A method did not deliver a result at this setting (the reason is the message).

    ``work`` is the work done before it failed, when known.
    """

    def __init__(self, message: str, work: float | None = None) -> None:
        super().__init__(message)
        self.work = work


def _failed(points: list[Point], method: str, name: str, setting: float, exc: Exception,
            seconds: float, default: bool) -> None:
    points.append(Point(method, name, setting, None, seconds, getattr(exc, "work", None),
                        f"{type(exc).__name__}: {exc}"[:300], default, failed=True))


def _time_failure(call: Callable[[], Any]) -> float:
    """Wall time of one more call of a setting that failed, s (it is compiled by now)."""
    t0 = time.perf_counter()
    with contextlib.suppress(Exception):
        call()
    return time.perf_counter() - t0


def measure(points: list[Point], method: str, name: str, setting: float, runner: Runner,
            repeats: int, default: bool = False) -> None:
    """``runner = (call, evaluate)``: ``evaluate(call())`` gives (error, work) or raises
    :class:`SettingFailed`; only ``call`` is timed.

    The first call is the warm-up and is never timed: it compiles every kernel and
    signature this setting reaches (numba's JIT, seconds), which would otherwise be drawn
    as the setting's run time. The point's time is the best of up to ``repeats`` calls
    after it; a failed setting's time is that of one more, compiled, call.
    """
    call, evaluate = runner
    try:
        out = call()
    except Exception as exc:  # a failing setting is a failed point, with its reason
        _failed(points, method, name, setting, exc, _time_failure(call), default)
        return
    try:
        err, work = evaluate(out)
        if not math.isfinite(err):
            raise SettingFailed("non-finite result")
    except Exception as exc:
        _failed(points, method, name, setting, exc, _time_failure(call), default)
        return
    points.append(Point(method, name, setting, float(err), best_time(call, repeats), work,
                        None, default))


def component(name: str, title: str, problem: str, reference: str, reference_error: float,
               metric: str, work_name: str, points: list[Point], default: dict[str, Any],
               seconds: float, **extra: Any) -> dict[str, Any]:
    mark_front(points)
    d = [p for p in points if p.default]
    dp = d[0] if d else None
    return {
        "name": name,
        "title": title,
        "problem": problem,
        "reference": reference,
        "reference_error": reference_error,
        "error_metric": metric,
        "work_name": work_name,
        "points": [asdict(p) for p in points],
        "missing": [{"method": p.method, "setting_name": p.setting_name, "setting": p.setting,
                     "reason": p.reason} for p in points if p.failed],
        "default": {**default,
                    "error": dp.error if dp else None,
                    "time_s": dp.time_s if dp else None,
                    "work": dp.work if dp else None,
                    "failed": bool(dp is None or dp.failed),
                    "reason": dp.reason if dp else "default not measured",
                    "on_pareto_front": bool(dp and dp.on_front),
                    "on_front_work": bool(dp and dp.on_front_work)},
        "seconds": seconds,
        **extra,
    }


def dd(x: Any) -> tuple[float, float]:
    """An mpf as a double-double pair (hi, lo), hi = float(x), lo = float(x - hi)."""
    hi = float(x)
    return hi, float(x - hi)


def rel_error_dd(got: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """|got - ref| / |ref| for a (2, ...) double-double reference: got - hi is exact when
    the two agree to a factor of 2 (Sterbenz), so errors below 1e-16 stay resolved."""
    hi, lo = ref[0], ref[1]
    return np.abs((got - hi) - lo) / np.abs(hi)
