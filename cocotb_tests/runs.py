"""Glue between pytest and the cocotb runs: one simulation per (top, configuration,
testbench module) and pytest session, one pytest test per cocotb test.

Under pytest the results go to one folder of the session (:func:`set_results_root`, set
by ``cocotb_tests/conftest.py`` to ``<pytest basetemp>/cocotb_results``, shared by the
pytest-xdist workers): the first worker that needs a simulation runs it under a file lock
and marks it done; any other test of any worker that needs it reads its results. Outside
pytest every call runs its simulation (into the irnuc cache's ``cocotb_results``)."""

from __future__ import annotations

import functools
import os
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType

from irnuc import cosim
from irnuc.common.io import file_lock
from irnuc.cosim import cocotb_test_names, metrics
from irnuc.cosim.coverage import COVERAGE_ENV
from irnuc.nuc_fixed import PipelineConfig

#: The session's results folder (None: outside a pytest session).
_SESSION_ROOT: Path | None = None


def set_results_root(path: Path | None) -> None:
    """Make ``path`` the folder of this pytest session's simulation results."""
    global _SESSION_ROOT
    _SESSION_ROOT = None if path is None else Path(path)


def results_root() -> Path:
    """Where :func:`run_module` writes (the session's folder, else the irnuc cache's)."""
    return _SESSION_ROOT if _SESSION_ROOT is not None else cosim.results_dir()

__all__ = ["case_params", "check_case", "cocotb_test_names", "coverage_json", "module_metrics",
           "run_case", "run_module", "waves_requested"]


def waves_requested() -> bool:
    """FST waveforms on request: ``pytest --waves`` or ``IRNUC_WAVES=1``."""
    return os.environ.get("IRNUC_WAVES", "0") not in ("", "0")


@functools.cache
def run_module(top: str, cfg: PipelineConfig, module: str, seed: int = 1
               ) -> dict[str, cosim.CaseResult]:
    """Build (cached) and run every cocotb test of ``module`` on ``top``; parse the XML.

    A failed RTL assertion stops the simulation: the cocotb test running then fails (and
    those after it); its assertion lines from the simulator log are added to the message.
    """
    waves = waves_requested()
    cov = coverage_json(top, cfg, module)
    xml = cov.with_suffix(".xml")
    done = cov.with_suffix(f".s{seed}.done")
    with file_lock(cov.with_suffix(".lock")):
        if _SESSION_ROOT is None or not done.is_file():
            bld = cosim.build(top, cfg, waves=waves)
            for stale in (cov, cov.with_suffix(".metrics.jsonl"), done):
                stale.unlink(missing_ok=True)
            cosim.run(bld, module, env={"IRNUC_SEED": str(seed), COVERAGE_ENV: str(cov),
                                        metrics.METRICS_ENV: str(cov.with_suffix(".metrics.jsonl"))},
                      seed=seed, waves=waves, results_xml=xml)
            done.touch()
        results = cosim.read_results(xml)
    fired = cosim.assertion_failures(xml)
    if fired:
        note = "\nRTL assertions failed (simulation stopped):\n" + "\n".join(fired[:10])
        results = {k: v if v.passed else cosim.CaseResult(v.name, False, v.message + note)
                   for k, v in results.items()}
    return results


def module_metrics(top: str, cfg: PipelineConfig, module: str) -> list[dict]:
    """The metric lines the testbench recorded in its :func:`run_module` run."""
    run_module(top, cfg, module)
    return metrics.read(coverage_json(top, cfg, module).with_suffix(".metrics.jsonl"))


def coverage_json(top: str, cfg: PipelineConfig, module: str) -> Path:
    """The functional-coverage file a :func:`run_module` run exports."""
    tag = f"{cfg.name}-{cfg.digest()[:8]}-{top}-{module.rsplit('.', 1)[-1]}"
    return results_root() / f"{tag}.coverage.json"


def case_params(tb: ModuleType, configs: Sequence[str]) -> list[tuple[str, str]]:
    """(configuration, cocotb test) of every test of testbench ``tb`` on every
    configuration: the parameters of a pytest wrapper (one pytest test per cocotb test)."""
    return [(c, t) for c in configs for t in cocotb_test_names(tb)]


def run_case(top: str, cfg: PipelineConfig, tb: ModuleType, case: str) -> None:
    """Fail unless cocotb test ``case`` of ``tb`` passed on ``top`` (one simulation of the
    whole testbench per (top, configuration), run once)."""
    check_case(run_module(top, cfg, tb.__name__), case)


def check_case(results: dict[str, cosim.CaseResult], case: str) -> None:
    if case not in results:
        raise AssertionError(f"cocotb test {case!r} did not run; results: {sorted(results)}")
    res = results[case]
    assert res.passed, f"cocotb test {case} failed:\n{res.message}\n(results in {results_root()})"

