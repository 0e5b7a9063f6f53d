"""The report's phases, one module each (run in order by
:func:`irnuc.reports.report.run.build_report`)."""
