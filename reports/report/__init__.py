"""``irnuc report``: the hardware team's regression report (``docs/reports.md``).

Modules:

* :mod:`~irnuc.reports.report.config`   the report TOML, validated (schema, nearest names)
* :mod:`~irnuc.reports.report.phases`   one module per phase: ``calibration`` (frames,
  calibration, bad-pixel detection), ``sweep`` (bit-width sweep, hardware cost, cost model,
  fronts, recommendation), ``paper``, ``cosim`` (``irnuc.verif.run_suite`` or ``--junit``),
  ``precision`` (work-precision diagrams)
* :mod:`~irnuc.reports.report.summary`  provenance, baseline (validated), ``summary.json``
* :mod:`~irnuc.reports.report.render`   Jinja2 templates and one stylesheet
* :mod:`~irnuc.reports.report.run`      checks before the work, the phases, the output
  folder written as a unit
"""

from __future__ import annotations

from irnuc.reports.report.base import Report
from irnuc.reports.report.config import ReportError, config_hash, load_report_config
from irnuc.reports.report.phases.cosim import parse_junit
from irnuc.reports.report.run import build_report, run_report
from irnuc.reports.report.summary import (
    SCHEMA_PATH,
    compare_baseline,
    load_baseline,
    validate_summary,
)

__all__ = [
    "SCHEMA_PATH",
    "Report",
    "ReportError",
    "build_report",
    "compare_baseline",
    "config_hash",
    "load_baseline",
    "load_report_config",
    "parse_junit",
    "run_report",
    "validate_summary",
]
