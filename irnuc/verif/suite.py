"""A co-simulation suite as a Python API: builds first, then every test on its own timer.

The report, the mutation runner and anyone else who wants co-simulation results without
pytest call :func:`run_suite`:

1. every distinct build the cases need is made first (cached; no test timer runs);
2. every cocotb test then runs in its own simulator process (a child process group),
   with a wall-time limit that scales with the size of the design built
   (:func:`test_timeout`), so one slow or hung test costs only itself;
3. each outcome is kept as it comes (passed, failed, error, timeout), with its log, its
   waveform (if asked for), the metrics the testbench recorded (pixels compared,
   mismatches, triage lines, cycles) and the assertion failures found in the log;
4. :meth:`SuiteResult.write_junit` writes one JUnit XML of everything that ran.

The testbench side of the metrics: a testbench appends JSON lines to the file named by
``$IRNUC_TB_METRICS`` (:mod:`irnuc.cosim.metrics`).

This module runs testbenches, so it sits above them (the ``irnuc.verif`` layer); a case
names a testbench module its caller has imported.
"""

from __future__ import annotations

import json
import re
import time
import xml.etree.ElementTree as ET
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from irnuc.common.io import write_text_atomic
from irnuc.cosim import metrics as tb_metrics
from irnuc.cosim.builds import (
    Build,
    SimulationTimeout,
    assertion_failures,
    build,
    cocotb_test_names,
    coverage_file,
    read_results,
    run,
)
from irnuc.cosim.coverage import COVERAGE_ENV
from irnuc.cosim.verilator import RtlError, waves_suffix
from irnuc.nuc_fixed import PipelineConfig


@dataclass(frozen=True)
class SuiteCase:
    """One testbench module on one top module and configuration."""

    top: str
    cfg: PipelineConfig
    module: str
    tests: tuple[str, ...] | None = None  # None: every cocotb test of the module
    seed: int = 1
    env: tuple[tuple[str, str], ...] = ()

    @property
    def label(self) -> str:
        return f"{self.cfg.name}/{self.top}/{self.module.rsplit('.', 1)[-1]}"


@dataclass
class TestOutcome:
    """What one cocotb test did."""

    case: SuiteCase
    test: str
    status: str  # passed, failed, error, timeout
    seconds: float
    message: str = ""
    log: Path | None = None
    waves: Path | None = None
    metrics: list[dict[str, Any]] = field(default_factory=list)
    assertion_failures: list[str] = field(default_factory=list)

    @property
    def name(self) -> str:
        return f"{self.case.label}::{self.test}"


@dataclass
class SuiteResult:
    """Every outcome of a suite run, and the time spent building and running."""

    outcomes: list[TestOutcome]
    build_seconds: float
    run_seconds: float
    builds: list[str]
    #: Functional coverage (``functional``: :func:`irnuc.cosim.coverage.summarize` of the
    #: bins merged over the tests run, per configuration) and code coverage (``code``:
    #: configuration -> module -> line and toggle hit/total/percent); None when the suite
    #: ran without ``coverage=True``.
    coverage: dict[str, Any] | None = None
    #: (case, functional coverage file, coverage.dat) of every test run with coverage, so
    #: that results of separate runs merge (:func:`merge_results`).
    coverage_sources: list[tuple[SuiteCase, Path, Path]] = field(default_factory=list,
                                                                 repr=False)

    def count(self, status: str) -> int:
        return sum(o.status == status for o in self.outcomes)

    @property
    def passed(self) -> bool:
        return bool(self.outcomes) and all(o.status == "passed" for o in self.outcomes)

    def totals(self) -> dict[str, Any]:
        pixels = sum(int(m.get("compared", 0)) for o in self.outcomes for m in o.metrics)
        errors = sum(int(m.get("errors", 0)) for o in self.outcomes for m in o.metrics)
        return {"tests": len(self.outcomes), "passed": self.count("passed"),
                "failed": self.count("failed"), "error": self.count("error"),
                "timeout": self.count("timeout"), "pixels": pixels, "mismatches": errors,
                "assertion_failures": sum(len(o.assertion_failures) for o in self.outcomes),
                "build_seconds": round(self.build_seconds, 3),
                "run_seconds": round(self.run_seconds, 3)}

    def write_junit(self, path: Path) -> Path:
        """One JUnit XML file (a ``testsuite`` per case) of every outcome."""
        root = ET.Element("testsuites")
        by_case: dict[str, list[TestOutcome]] = {}
        for o in self.outcomes:
            by_case.setdefault(o.case.label, []).append(o)
        for label, outs in by_case.items():
            suite = ET.SubElement(root, "testsuite", name=label, tests=str(len(outs)),
                                  failures=str(sum(o.status == "failed" for o in outs)),
                                  errors=str(sum(o.status in ("error", "timeout") for o in outs)))
            for o in outs:
                tc = ET.SubElement(suite, "testcase", classname=label, name=o.test,
                                   time=f"{o.seconds:.3f}")
                if o.status == "failed":
                    ET.SubElement(tc, "failure", message=o.message[:200]).text = o.message
                elif o.status in ("error", "timeout"):
                    ET.SubElement(tc, "error", message=f"{o.status}: {o.message[:200]}").text = \
                        o.message
        ET.indent(root)
        write_text_atomic(path, ET.tostring(root, encoding="unicode") + "\n")
        return path


def test_timeout(cfg: PipelineConfig, base: float = 120.0) -> float:
    """Wall-time limit of one test: ``base`` seconds for a design of up to 1024 pixels per
    line, growing with the line-buffer length (a longer line means longer frames and a
    slower model)."""
    return base * max(1.0, cfg.max_width / 1024)


def run_suite(cases: Sequence[SuiteCase], out_dir: Path, *, waves: bool = False,
              timeout_base: float = 120.0, build_args: Sequence[str] = (),
              progress: Callable[[int, int], None] | None = None,
              coverage: bool = False, hdl_dir: Path | None = None,
              stop_on_failure: bool = False) -> SuiteResult:
    """Build everything, then run every test of every case on its own timer.

    Parameters
    ----------
    cases : sequence of SuiteCase
    out_dir : Path
        Folder for result files, simulator logs, metrics and waveforms (one sub-folder
        per test).
    waves : bool
        Record a waveform of every test.
    timeout_base : float
        Seconds per test for a design of up to 1024 pixels per line (see
        :func:`test_timeout`).
    build_args : sequence of str
        Extra Verilator options for every build.
    progress : callable, optional
        ``progress(done, total)`` after every test.
    coverage : bool
        Collect functional coverage (every testbench exports its bins) and code coverage
        (builds with Verilator line and toggle coverage); merged into
        :attr:`SuiteResult.coverage` and written to ``out_dir/coverage.json``.
    hdl_dir : Path, optional
        Build a modified copy of ``hdl/`` (a mutant) instead of the design.
    stop_on_failure : bool
        Stop after the first test that does not pass (mutation runs).
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    builds: dict[tuple[str, str], Build] = {}
    for c in cases:
        key = (c.top, c.cfg.digest())
        if key not in builds:
            builds[key] = build(c.top, c.cfg, waves=waves, extra_args=build_args,
                                coverage=coverage, hdl_dir=hdl_dir)
    build_seconds = time.perf_counter() - t0
    plan = [(c, t) for c in cases for t in (c.tests or tuple(cocotb_test_names(c.module)))]
    outcomes: list[TestOutcome] = []
    cov_files: list[tuple[SuiteCase, Path, Path]] = []
    t1 = time.perf_counter()
    for i, (c, test) in enumerate(plan):
        bld = builds[(c.top, c.cfg.digest())]
        tag = re.sub(r"[^A-Za-z0-9_.-]", "_", f"{c.cfg.name}-{c.cfg.digest()[:8]}-{c.top}-"
                                               f"{c.module.rsplit('.', 1)[-1]}-{test}")
        xml = out_dir / f"{tag}.xml"
        run_dir = out_dir / f"{tag}.run"
        metrics_file = run_dir / "metrics.jsonl"
        run_dir.mkdir(parents=True, exist_ok=True)
        metrics_file.unlink(missing_ok=True)
        cov_file = run_dir / "coverage.json"
        cov_file.unlink(missing_ok=True)
        env = {"IRNUC_SEED": str(c.seed), tb_metrics.METRICS_ENV: str(metrics_file), **dict(c.env)}
        if coverage:
            env[COVERAGE_ENV] = str(cov_file)
        start = time.perf_counter()
        status, message = "error", ""
        try:
            res = read_results(run(bld, c.module, env=env, testcase=test, seed=c.seed,
                                   results_xml=xml, waves=waves,
                                   timeout=test_timeout(c.cfg, timeout_base)))
            r = res.get(test)
            if r is None:
                status, message = "error", f"cocotb test {test!r} did not run"
            else:
                status, message = ("passed" if r.passed else "failed"), r.message
        except SimulationTimeout as exc:
            status, message = "timeout", str(exc)
        except RtlError as exc:
            status, message = "error", str(exc)
        log = run_dir / "sim.log"
        wave = xml.with_suffix(waves_suffix())
        outcomes.append(TestOutcome(
            case=c, test=test, status=status, seconds=time.perf_counter() - start,
            message=message, log=log if log.is_file() else None,
            waves=wave if waves and wave.is_file() else None,
            metrics=tb_metrics.read(metrics_file), assertion_failures=assertion_failures(xml)))
        if coverage:
            cov_files.append((c, cov_file, coverage_file(xml)))
        if progress is not None:
            progress(i + 1, len(plan))
        if stop_on_failure and status != "passed":
            break
    result = SuiteResult(outcomes=outcomes, build_seconds=build_seconds,
                         run_seconds=time.perf_counter() - t1,
                         builds=[str(b.build_dir) for b in builds.values()])
    if coverage:
        result.coverage_sources = cov_files
        _write_coverage(result, out_dir)
    return result


def _write_coverage(result: SuiteResult, out_dir: Path) -> None:
    result.coverage = suite_coverage(result.coverage_sources)
    write_text_atomic(Path(out_dir) / "coverage.json",
                      json.dumps(result.coverage, indent=1, sort_keys=True) + "\n")


def merge_results(parts: Sequence[SuiteResult], out_dir: Path, *,
                  run_seconds: float | None = None) -> SuiteResult:
    """One result of several suite runs (for example one test per run, run in parallel):
    outcomes in order, build time and builds of all of them, coverage merged over every
    test that collected it (and written to ``out_dir/coverage.json``).

    Parameters
    ----------
    parts : sequence of SuiteResult
    out_dir : Path
        Folder of the merged ``coverage.json``.
    run_seconds : float, optional
        Wall time of the runs (default: the sum of theirs, as when run one after another).
    """
    merged = SuiteResult(
        outcomes=[o for p in parts for o in p.outcomes],
        build_seconds=sum(p.build_seconds for p in parts),
        run_seconds=sum(p.run_seconds for p in parts) if run_seconds is None else run_seconds,
        builds=sorted({b for p in parts for b in p.builds}),
        coverage_sources=[s for p in parts for s in p.coverage_sources])
    if merged.coverage_sources:
        _write_coverage(merged, out_dir)
    return merged


def suite_coverage(files: Sequence[tuple[SuiteCase, Path, Path]]) -> dict[str, Any]:
    """Functional coverage merged over the exported files, code coverage per configuration
    and module merged over the ``coverage.dat`` files (see :attr:`SuiteResult.coverage`)."""
    from irnuc.cosim import coverage as cov

    functional = cov.summarize(cov.merge(f for _, f, _ in files))
    points: dict[str, list] = {}
    for case, _, dat in files:
        if dat.is_file():
            points.setdefault(cov.config_label(case.cfg), []).append(cov.read_coverage_dat(dat))
    code = {label: cov.code_coverage(cov.merge_points(p)) for label, p in sorted(points.items())}
    return {"functional": functional, "code": code}
