"""Phase: error against run time of every numerical component of the model (the
work-precision study, :mod:`irnuc.reports.studies.precision`), cached per model code.

The section keeps the study's summary (``components``: per component the default's
error, time, work and front status, the numbers of points and failed points); the
diagrams (error against run time and against work, log-log, failed settings drawn as
crosses, the default a star) go into the report as figures.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from irnuc.reports.report.base import Report, left_out, progress
from irnuc.reports.report.sections import Section


def _flatten(prefix: str, obj: Any, out: dict[str, float | int]) -> None:
    if isinstance(obj, Mapping):
        for k, v in obj.items():
            _flatten(f"{prefix}.{k}", v, out)
    elif isinstance(obj, bool):
        out[prefix] = int(obj)
    elif isinstance(obj, int | float) and math.isfinite(obj):
        out[prefix] = obj


def quick_notes(rep: Report) -> None:
    """Name the study's components ``--quick`` leaves out."""
    from irnuc.reports.report.config import quick_replaced
    from irnuc.reports.studies.precision import component_names

    c = rep.config["precision"]
    cut, full = quick_replaced(rep.config, "precision.components")
    if cut:
        ran = component_names(c.get("components"))
        skipped = [n for n in component_names(full) if n not in ran]
        left_out(rep, "precision", f"{len(skipped)} of the study's components "
                 f"({', '.join(skipped)}); run: {', '.join(ran)}", "precision.components")


def phase_precision(rep: Report, show_progress: bool) -> None:
    from irnuc.reports.studies.precision import failure_label, figures, summarize
    from irnuc.reports.studies.precision_cache import cached_precision

    c = rep.config["precision"]
    quick_notes(rep)
    with rep.phase("precision"):
        result = cached_precision(quick=bool(c.get("quick", True)), components=c.get("components"),
                                  progress=progress("precision", show_progress))
        data = summarize(result)
        data["cached"] = bool(result.get("cached"))
        data["details"] = {
            comp["name"]: {
                "title": comp["title"], "problem": comp["problem"],
                "reference": comp["reference"], "error_metric": comp["error_metric"],
                "default": {k: comp["default"].get(k) for k in (
                    "method", "setting_name", "setting", "error", "time_s", "work",
                    "on_pareto_front", "on_front_work")},
                "failed": [{"method": m["method"], "setting_name": m["setting_name"],
                            "setting": m["setting"], "label": failure_label(m["reason"]),
                            "reason": (m["reason"] or "")[:300]} for m in comp["missing"]],
            } for comp in result["components"]}
        figs = figures(result)
    for caption, png in figs:
        rep.figure("precision", caption, png)
    rep.sections["precision"] = Section.of(data)
    flat: dict[str, float | int] = {}
    _flatten("precision", {k: v for k, v in data.items() if k != "details"}, flat)
    for k, v in flat.items():
        # Direction unknown in general: recorded, not compared, except errors (lower).
        better = "lower" if ("error" in k.lower() and "time" not in k.lower()) else "info"
        rep.metric(k, v, better, rel_tol=1e-3 if better == "lower" else None)
