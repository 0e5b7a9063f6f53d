"""Verification campaigns that run the testbenches: the co-simulation suite as a Python API
(:mod:`~irnuc.verif.suite`: builds first, one timer per test, results, coverage, JUnit) and
mutation testing of the RTL (:mod:`~irnuc.verif.mutate`).

This layer sits above the testbenches (``irnuc.cocotb_tests``) because it runs them; the
report and the command line call it (docs/architecture.md, "Layers").
"""

from irnuc.verif.suite import (
    SuiteCase,
    SuiteResult,
    TestOutcome,
    merge_results,
    run_suite,
    test_timeout,
)

__all__ = ["SuiteCase", "SuiteResult", "TestOutcome", "merge_results", "run_suite",
           "test_timeout"]
