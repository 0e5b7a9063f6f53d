"""Phase: the RTL co-simulation, run as a Python API (``irnuc.verif.run_suite`` with the
testbench module ``irnuc.cocotb_tests.tb_top``; never pytest), or an ingested JUnit XML
(``--junit``).

Every Verilator build is made first (no test timer runs during a build); then every test
runs in its own simulator process with its own time limit, scaled with the size of the
design built (``irnuc.verif.test_timeout``), ``jobs`` tests at a time. A test that runs out
of time is one ``timeout`` outcome; the others are kept, and a suite cut short is reported
as partial. The section holds, per test: status, time, pixels compared, mismatches with
their triage lines (frame, x, y, inputs, expected, got, intermediate values), assertion
failures, the paths of the log and waveform; and throughput, coverage and mutation
results where measured (:func:`measured_coverage`, :func:`measured_mutation`).
"""

from __future__ import annotations

import concurrent.futures as cf
import dataclasses
import time
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from irnuc.reports.report.base import Report
from irnuc.reports.report.config import ReportError, input_file
from irnuc.reports.report.sections import CosimCheck, CosimSection, SweepSection, thaw

#: Tests that compare against a deliberately wrong golden model (their mismatches are the
#: checker working, not the RTL failing).
NEGATIVE_CONTROLS = ("checker_detects_mismatch",)


# ---- JUnit ingest -------------------------------------------------------------------------
def parse_junit(path: str | Path) -> dict[str, Any]:
    """Counts and per-test results of a JUnit XML file (pytest's or any xunit2 writer)."""
    p = input_file(path, "--junit", "a JUnit XML file")
    from irnuc.common.errors import UserError
    from irnuc.common.io import read_bytes_capped

    try:  # read with a size cap before it is parsed (a JUnit file of a suite is megabytes)
        data = read_bytes_capped(p, "--junit", 256 * 2**20)
        root = ET.fromstring(data)
    except UserError as exc:
        raise ReportError(str(exc)) from None
    except (ET.ParseError, UnicodeDecodeError) as exc:
        raise ReportError(f"--junit {path}: not a readable JUnit XML file ({exc})") from None
    if root.tag not in ("testsuite", "testsuites"):
        raise ReportError(f"--junit {path}: root element is <{root.tag}>, "
                          "expected <testsuites> or <testsuite>")
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    cases = []
    for suite in suites:
        for tc in suite.iter("testcase"):
            status, message = "passed", ""
            for tag in ("failure", "error", "skipped"):
                el = tc.find(tag)
                if el is not None:
                    status = {"failure": "failed", "error": "error", "skipped": "skipped"}[tag]
                    message = (el.get("message") or el.text or "").strip()[:500]
                    break
            try:
                seconds = float(tc.get("time", 0) or 0)
            except ValueError:
                raise ReportError(f"--junit {path}: testcase {tc.get('name')!r} has time = "
                                  f"{tc.get('time')!r}, not a number") from None
            cases.append({"name": tc.get("name", ""), "classname": tc.get("classname", ""),
                          "time": seconds, "status": status, "message": message})
    if not cases:  # results that check nothing are not a pass
        raise ReportError(f"--junit {path}: holds no <testcase>; nothing to report")
    counts = {k: sum(c["status"] == k for c in cases) for k in ("passed", "failed", "error", "skipped")}
    return {"tests": len(cases), **counts, "timeout": 0,
            "time": round(sum(c["time"] for c in cases), 3), "cases": cases,
            "data": data}


# ---- coverage and mutation (measured by irnuc.cosim) --------------------------------------
#: Uncovered bins and missed source lines listed per configuration/module (the rest counted).
LIST_LIMIT = 40


def measured_coverage(result: Any) -> dict[str, Any] | None:
    """The coverage a suite run measured (``result.coverage``, see
    :attr:`irnuc.verif.SuiteResult.coverage`), condensed for the report: functional bins
    hit per configuration and coverpoint with the uncovered bins by name, and line and
    toggle coverage per configuration and module with the source lines never reached.
    None when the run did not measure coverage."""
    cov = getattr(result, "coverage", None)
    if not isinstance(cov, Mapping) or not cov:
        return None
    f = cov.get("functional") or {}
    functional = {
        "hit": f.get("hit", 0), "total": f.get("total", 0), "percent": f.get("percent", 0.0),
        "configurations": {
            label: {"hit": c["hit"], "total": c["total"], "percent": c["percent"],
                    "tops": list(c.get("tops", [])),
                    "uncovered": list(c.get("uncovered", []))[:LIST_LIMIT],
                    "uncovered_count": len(c.get("uncovered", [])),
                    "coverpoints": {name: {"kind": p.get("kind", "point"), "hit": p["hit"],
                                           "total": p["total"], "percent": p["percent"],
                                           "removed": dict(p.get("removed", {}))}
                                    for name, p in c.get("coverpoints", {}).items()}}
            for label, c in (f.get("configurations") or {}).items()}}
    code = {label: {mod: {"line": dict(m["line"]), "toggle": dict(m["toggle"]),
                          "missed_lines": list(m.get("missed_lines", []))[:LIST_LIMIT],
                          "missed_count": len(m.get("missed_lines", []))}
                    for mod, m in mods.items()}
            for label, mods in (cov.get("code") or {}).items()}
    return {"functional": functional, "code": code}


def measured_mutation() -> dict[str, Any] | None:
    """The ``irnuc mutate`` catalogue as the cache holds it for the current RTL and suite
    sources (:func:`irnuc.verif.mutate.current_results`: every mutant's result however
    many runs produced it, the ones without a result named), condensed for the report:
    counts, score, survivors, the equivalent mutants with their arguments, and per mutant
    its status and killing test. None when no mutant has a result on these sources."""
    from irnuc.verif import mutate

    s = mutate.current_results()
    if not s.get("total"):
        return None
    keys = ("rtl_digest", "total", "catalogue_size", "killed", "survived", "equivalent",
            "score", "complete", "survivors", "equivalents", "missing")
    out = {k: s[k] for k in keys if k in s}
    out["invalid"] = len(s.get("invalid") or [])
    out["mutants"] = [{k: m.get(k) for k in ("id", "file", "what", "config", "status",
                                             "killed_by", "seconds")}
                      for m in s.get("mutants", [])]
    return out


def measured_auto_mutation() -> dict[str, Any] | None:
    """The ``irnuc mutate --auto 8`` campaign as the cache holds it for the current sources
    (:func:`irnuc.verif.automut.current_results`: the modules drawn, each mutant's result,
    the ones without a result and the modules not drawn named), condensed: counts, score,
    per module, and per mutant its status, killing test or formal verdict. None when no
    automatic mutant has a result on these sources."""
    from irnuc.verif import automut

    s = automut.current_results()
    if not s.get("total"):
        return None
    keys = ("rtl_digest", "total", "killed", "survived", "equivalent", "score", "complete",
            "survivors", "n", "seed", "modules", "per_module", "decided", "missing",
            "not_drawn")
    out = {k: s[k] for k in keys if k in s}
    out["mutants"] = [{"id": m.get("id"), "file": m.get("file"), "what": m.get("what"),
                       "config": m.get("config"), "status": m.get("status"),
                       "killed_by": m.get("killed_by"),
                       "verdict": (m.get("decided") or {}).get("verdict"),
                       "note": m.get("equivalent") or (m.get("message") or "")[:200]}
                      for m in s.get("mutants", [])]
    return out


def measured_formal() -> dict[str, Any] | None:
    """The ``irnuc formal`` campaign as the cache holds it for the current RTL and formal
    sources (:func:`irnuc.verif.formal.current_results`: every proof's and planted
    fault's result however many runs produced it; the ones without a result are listed
    as ``missing``, status ``not run``, never counted as holding), condensed: proofs
    (engine, depth, status, time, cover), planted faults (the property each must fail and
    whether it did). None when no proof or fault has a result on these sources."""
    from irnuc.verif import formal

    s = formal.current_results()
    if len(s.get("missing", [])) == len(s["proofs"]) + len(s["faults"]):
        return None
    out = {k: s[k] for k in ("digest", "proved", "bounded", "not_ok", "detected", "missed",
                             "unplanted", "ok", "complete", "seconds", "missing") if k in s}
    out["proofs"] = [{"id": r["id"], "what": r.get("what", ""), "engine": r["engine"],
                      "depth": r.get("depth"), "wanted": r.get("wanted"),
                      "status": r["status"],
                      "seconds": r.get("seconds", 0.0), "asserts": r.get("asserts"),
                      "cover": _cover_note(r.get("cover")),
                      "message": r.get("message", "")}
                     for r in s.get("proofs", [])]
    out["faults"] = [{"id": r["id"], "property": r.get("property"), "what": r.get("what", ""),
                      "detected": r.get("detected"), "step": r.get("step")}
                     for r in s.get("faults", [])]
    return out


def _cover_note(cover: Mapping[str, Any] | None) -> str | None:
    """A proof's covers in the report: status, and reached / total when not all were."""
    if not cover:
        return None
    steps = cover.get("steps") or {}
    total = cover.get("total") or len(steps)
    if cover.get("status") == "covered" or not total:
        return cover.get("status")
    return f"{cover.get('status')} ({len(steps)} / {total})"


# ---- running the suite --------------------------------------------------------------------
def _relative(path: Path | None, root: Path) -> str | None:
    if path is None:
        return None
    try:
        return str(Path(path).relative_to(root))
    except ValueError:
        return str(path)


def _case_entry(o: Any, root: Path) -> dict[str, Any]:
    pixels = sum(int(m.get("compared", 0)) for m in o.metrics)
    errors = sum(int(m.get("errors", 0)) for m in o.metrics)
    lines = [ln for m in o.metrics if int(m.get("errors", 0)) for ln in m.get("lines", [])][:10]
    negative = o.test in NEGATIVE_CONTROLS
    return {
        "name": o.test, "classname": o.case.label, "configuration": o.case.cfg.name,
        "status": o.status, "time": round(o.seconds, 3), "message": o.message[:2000],
        "pixels": pixels, "mismatches": 0 if negative else errors,
        "negative_control": negative, "detected": errors if negative else None,
        "triage": lines, "assertion_failures": list(o.assertion_failures)[:20],
        "log": _relative(o.log, root), "waves": _relative(o.waves, root),
    }


def run_cosim(rep: Report, configs: list[Any], c: Mapping[str, Any], out: Path) -> dict[str, Any]:
    """Build every configuration, then run the tests ``jobs`` at a time; the section."""
    from irnuc import cosim
    from irnuc.cocotb_tests import tb_top  # imported here: the report's import stays light
    from irnuc.nuc_fixed import gain_format, offset_format
    from irnuc.verif import SuiteCase, merge_results, run_suite, test_timeout

    tests = tuple(c["tests"])
    waves = bool(c.get("waves", False))
    jobs = int(c.get("jobs", 2))
    base = float(c.get("timeout_base", 120.0))
    seed = int(c.get("seed", 1))
    coverage = bool(c.get("coverage", True))
    work = out / "cosim"
    t0 = time.perf_counter()
    for cfg in configs:  # builds before any test timer starts
        cosim.build("nuc_dpc_top", cfg, waves=waves, coverage=coverage)
    build_seconds = time.perf_counter() - t0
    plan = [(cfg, t) for cfg in configs for t in tests]

    def run_one(item: tuple[Any, str]) -> Any:
        cfg, t = item
        case = SuiteCase("nuc_dpc_top", cfg, tb_top.__name__, tests=(t,), seed=seed)
        # A folder per test: its files (and its own coverage.json) apart from the others.
        return run_suite([case], work / f"{cfg.name}-{cfg.digest()[:8]}" / t,
                               waves=waves, timeout_base=base, coverage=coverage)

    t1 = time.perf_counter()
    # Each test is one task: the ``jobs`` simulators take the next test as they finish.
    with cf.ThreadPoolExecutor(max_workers=max(1, min(jobs, len(plan)))) as pool:
        parts = list(pool.map(run_one, plan))
    merged = merge_results(parts, out, run_seconds=time.perf_counter() - t1)
    merged.build_seconds = build_seconds
    outcomes = merged.outcomes
    merged.write_junit(out / "junit.xml")
    cases = [_case_entry(o, out) for o in outcomes]
    pixels = sum(x["pixels"] for x in cases)
    sim_seconds = sum(x["time"] for x in cases)
    section: dict[str, Any] = {
        "source": "irnuc.verif.run_suite", "testbench": tb_top.__name__,
        "tests": len(cases), "passed": sum(x["status"] == "passed" for x in cases),
        "failed": sum(x["status"] == "failed" for x in cases),
        "error": sum(x["status"] == "error" for x in cases),
        "timeout": sum(x["status"] == "timeout" for x in cases), "skipped": 0,
        "planned": len(plan), "partial": len(cases) < len(plan) or any(
            x["status"] == "timeout" for x in cases),
        "time": round(sim_seconds, 3), "build_seconds": round(build_seconds, 3),
        "run_seconds": round(merged.run_seconds, 3), "jobs": jobs,
        "pixels": pixels, "mismatches": sum(x["mismatches"] for x in cases),
        "assertion_failures": sum(len(x["assertion_failures"]) for x in cases),
        "throughput_pixels_per_s": round(pixels / sim_seconds, 3) if sim_seconds else None,
        "timeouts_s": {cfg.name: test_timeout(cfg, base) for cfg in configs},
        "configurations": [{"name": cfg.name, "digest": cfg.digest(), "adc_bits": cfg.adc_bits,
                            "out_bits": cfg.out_bits,
                            "gain": str(gain_format(cfg)), "offset": str(offset_format(cfg)),
                            "rounding": cfg.rounding, "max_width": cfg.max_width,
                            "max_height": cfg.max_height, "word_bits": cfg.word_bits,
                            "tests": [x["name"] for x in cases if x["configuration"] == cfg.name]}
                           for cfg in configs],
        "cases": cases, "junit": "junit.xml", "work": _relative(work, out),
        "coverage": measured_coverage(merged),
        "coverage_file": "coverage.json" if merged.coverage is not None else None,
        "mutation": measured_mutation(),
        "mutation_auto": measured_auto_mutation(),
        "formal": measured_formal(),
    }
    return section


def prefetch_cosim_builds(rep: Report) -> None:
    """Make the co-simulation phase's Verilator builds (cached) in the background, as soon
    as the sweep has recommended (:meth:`Report.start_background`); the phase joins it
    before its own builds, which then come from the cache."""
    from irnuc import cosim

    c = rep.config["cosim"]
    for cfg in _configs(rep, list(c["pipelines"]), say=False):
        cosim.build("nuc_dpc_top", cfg, waves=bool(c.get("waves", False)),
                    coverage=bool(c.get("coverage", True)))


def _configs(rep: Report, names: list[str], say: bool = True) -> list[Any]:
    from irnuc.nuc_fixed import load_pipeline

    out = []
    for name in names:
        if name == "recommended":
            r = (rep.sections.get("sweep") or {}).get("recommended")
            if r is None:
                if say:
                    rep.notes.append("co-simulation of the recommended widths skipped: the "
                                     "sweep recommends none")
                continue
            from irnuc.nuc_fixed import PipelineConfig

            out.append(PipelineConfig(**thaw(r["pipeline"])))
        else:
            out.append(load_pipeline(name))
    return out


def phase_cosim(rep: Report, out: Path, junit: dict[str, Any] | None, no_cosim: bool) -> None:
    from irnuc.common.errors import ToolError
    from irnuc.common.io import write_bytes_atomic

    section = None
    if junit is not None:
        with rep.phase("cosim"):
            section = {k: v for k, v in junit.items() if k != "data"}
            section["source"] = str(junit.get("path", "--junit"))
            write_bytes_atomic(out / "junit.xml", junit["data"])
            section["junit"] = "junit.xml"
            section["partial"] = False
    elif not no_cosim and "cosim" in rep.config:
        c = rep.config["cosim"]
        with rep.phase("cosim"):
            rep.join_background("cosim builds")
            configs = _configs(rep, list(c["pipelines"]))
            if configs:
                try:
                    section = run_cosim(rep, configs, c, out)
                except ToolError as exc:  # a build that failed: the report says so, whole
                    section = {"source": "irnuc.verif.run_suite", "tests": 0, "passed": 0,
                               "failed": 0, "error": 1, "timeout": 0, "skipped": 0, "time": 0.0,
                               "cases": [], "partial": True, "note": str(exc)[:4000]}
    if section is None:
        return
    rep.sections["cosim"] = CosimSection.of(section)
    rep.metric("cosim.tests", section["tests"], "info")
    rep.metric("cosim.passed", section["passed"], "info")
    rep.metric("cosim.failed", section["failed"], "lower")
    rep.metric("cosim.errors", section["error"] + section.get("timeout", 0), "lower")
    if "pixels" in section:
        rep.metric("cosim.pixels", section["pixels"], "info")
        rep.metric("cosim.mismatches", section["mismatches"], "lower")
        rep.metric("cosim.assertion_failures", section["assertion_failures"], "lower")
    sweep = rep.sections.get("sweep")
    rec = sweep.recommended if isinstance(sweep, SweepSection) else None
    if rec is not None and section.get("cases"):
        mine = [x for x in section["cases"] if x.get("configuration") == "recommended"]
        if mine:
            check = CosimCheck(passed=sum(x["status"] == "passed" for x in mine),
                               failed=sum(x["status"] != "passed" for x in mine),
                               pixels=sum(x["pixels"] for x in mine),
                               mismatches=sum(x["mismatches"] for x in mine),
                               tests=tuple(x["name"] for x in mine))
            rep.sections["sweep"] = dataclasses.replace(
                sweep, recommended=dataclasses.replace(rec, cosim=check))
