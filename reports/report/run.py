"""``irnuc report``: everything checked before the work, the phases, the output folder
written as a unit.

Before any work: the configuration (schema), ``--out`` claimed (kind ``report``: a user's
folder is refused, a second run fails at once), the baseline validated, a ``--junit`` file
parsed, a ``--scheduler`` reached, the sweep's widths checked against its pipeline. The
phases then fill a hidden sibling of ``--out``, which replaces ``--out`` as a whole only
when the report is complete: a kill leaves the previous report, whole. The closing line
names only files that exist.
"""

from __future__ import annotations

import copy
import json
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from irnuc.reports.report.base import Report
from irnuc.reports.report.config import check_runs_something, config_path, load_report_config

OUTPUTS = ("index.html", "summary.json", "junit.xml", "coverage.json", "recommended.toml",
           "recommended_temperature.toml")


def build_report(config: Mapping[str, Any], *, out: Path, junit: dict[str, Any] | None = None,
                 no_cosim: bool = False, scheduler: str | None = None,
                 progress: bool = True) -> Report:
    """Run every phase the configuration asks for, writing logs and results under ``out``."""
    from irnuc.reports.report.phases.calibration import phase_frames_and_calibration
    from irnuc.reports.report.phases.cosim import phase_cosim, prefetch_cosim_builds
    from irnuc.reports.report.phases.paper import phase_paper
    from irnuc.reports.report.phases.precision import phase_precision
    from irnuc.reports.report.phases.sweep import phase_sweep, phase_synth, prefetch_synth
    from irnuc.reports.report.phases.temperature import (
        anchor_configs,
        phase_temperature,
        prefetch_anchors,
        prefetch_signoff,
    )

    rep = Report(config=copy.deepcopy(dict(config)), verbose=progress)
    try:
        # The long syntheses whose inputs the configuration already gives (the sign-off's
        # anchors: each method's shipped configuration) start on one core now, while the
        # single-threaded phases (frames, calibration, the paper) use the other.
        if "temperature" in config and anchor_configs(config["temperature"]):
            rep.start_background("anchors", prefetch_anchors, config["temperature"], scheduler)
        elif "temperature" in config:
            # no anchor to synthesize (--quick): the sign-off's study, then its
            # recommendation's synthesis and axis harness build, take that core instead
            rep.start_background("sign-off", prefetch_signoff, config["temperature"], scheduler)
        if "sensor" in config:
            phase_frames_and_calibration(rep)
        if "sweep" in config:
            phase_sweep(rep, scheduler, progress)
            if "synth" in config:
                # its syntheses beside the single-threaded paper phase, read after it
                rep.start_background("sweep syntheses", prefetch_synth, rep, scheduler)
        if "paper" in config:
            phase_paper(rep, progress)
        if "sweep" in config:
            if "synth" in config:
                phase_synth(rep, scheduler, progress)
            if junit is None and not no_cosim and "cosim" in config:
                # the co-simulation's Verilator builds are known once the sweep recommends
                rep.start_background("cosim builds", prefetch_cosim_builds, rep)
        if "temperature" in config:
            phase_temperature(rep, scheduler, progress)
        phase_cosim(rep, out, junit, no_cosim)
        if "precision" in config:
            phase_precision(rep, progress)
    finally:
        rep.close_background()
    _recommended_metrics(rep)
    return rep


def _recommended_metrics(rep: Report) -> None:
    from irnuc.reports.report.sections import SweepSection

    sweep = rep.sections.get("sweep")
    if not isinstance(sweep, SweepSection):
        return
    r = sweep.recommended
    rep.metric("sweep.recommended.bits_per_pixel", r and r["bits_per_pixel"], "lower", "bit")
    rep.metric("sweep.recommended.err_max_lsb", r and r["err_max_lsb"], "lower", "LSB")
    if r and r.cosim:
        rep.metric("sweep.recommended.cosim.failed", r.cosim.failed, "lower")
        rep.metric("sweep.recommended.cosim.mismatches", r.cosim.mismatches, "lower")
        rep.metric("sweep.recommended.cosim.pixels", r.cosim.pixels, "info")


def write_outputs(rep: Report, summary: dict[str, Any], out: Path) -> None:
    from irnuc.common.io import write_text_atomic
    from irnuc.reports.report.render import render_report
    from irnuc.reports.report.summary import validate_summary
    from irnuc.reports.studies import figures

    rep.figure("times", "Run time per phase", figures.phase_times(summary["phases"]))
    summary["schema_validation"] = validate_summary(summary)
    r = (summary["sections"].get("sweep") or {}).get("recommended")
    if r:
        write_text_atomic(out / "recommended.toml", r["pipeline_toml"])
    t = (summary["sections"].get("temperature") or {}).get("recommended")
    if t:
        write_text_atomic(out / "recommended_temperature.toml", t["pipeline_toml"])
    write_text_atomic(out / "summary.json", json.dumps(summary, indent=1) + "\n")
    signoff_junit(out / "junit.xml", summary["signoff"], "temperature" in rep.sections)
    write_text_atomic(out / "index.html", render_report(rep, summary))


def signoff_junit(path: Path, signoff: Mapping[str, Any], ran: bool) -> None:
    """Add the sign-off's own testcase (classname ``signoff``, name ``temperature``) to
    ``junit.xml`` in a testsuite of its own, the regression's testcases unchanged: failed
    (with the reason) when the verdict is not met, skipped when not run. Without a
    ``junit.xml`` (no co-simulation) the file is written with this testcase alone when the
    sign-off ran; a CI that does not gate on the sign-off skips classname ``signoff``."""
    import xml.etree.ElementTree as ET

    from irnuc.common.io import write_text_atomic

    if path.is_file():
        root = ET.parse(path).getroot()  # ours, or an ingested --junit already parsed
        if root.tag == "testsuite":
            wrapper = ET.Element("testsuites")
            wrapper.append(root)
            root = wrapper
    elif ran:
        root = ET.Element("testsuites")
    else:
        return
    v = signoff["verdict"]
    suite = ET.SubElement(root, "testsuite", name="signoff", tests="1",
                          failures=str(int(v == "not met")), errors="0",
                          skipped=str(int(v == "not run")))
    tc = ET.SubElement(suite, "testcase", classname="signoff", name="temperature", time="0.000")
    if v == "not met":
        ET.SubElement(tc, "failure", message=f"sign-off not met: {signoff['reason']}"[:200]).text = \
            signoff["reason"]
    elif v == "not run":
        ET.SubElement(tc, "skipped", message=signoff["reason"][:200])
    else:
        ET.SubElement(tc, "system-out").text = f"sign-off met: {signoff['reason']}"
    ET.indent(root)
    write_text_atomic(path, ET.tostring(root, encoding="unicode") + "\n")


def check_scheduler(scheduler: str | None) -> None:
    """An unreachable ``--scheduler`` is an error before the work."""
    if scheduler:
        from irnuc.common.executor import open_executor

        with open_executor(0, scheduler):
            pass


def run_report(args: Any) -> int:
    """Entry point of ``irnuc report`` (argparse namespace, see :mod:`irnuc.cli.report`)."""
    import sys

    from irnuc.common.io import claim_output_folder, output_folder
    from irnuc.reports.report.phases.cosim import parse_junit
    from irnuc.reports.report.phases.sweep import check_sweep
    from irnuc.reports.report.render import status_line
    from irnuc.reports.report.summary import load_baseline, make_summary

    argv = list(getattr(args, "argv", []) or [])
    cfg_file = config_path(args.config)
    out = claim_output_folder(args.out, kind="report", inputs={
        "--config": cfg_file if cfg_file.is_file() else None})
    config = load_report_config(args.config, quick=args.quick)
    check_runs_something(config, f"--config {args.config}", no_cosim=args.no_cosim,
                         junit=bool(args.junit))
    baseline = load_baseline(args.baseline, config) if args.baseline else None
    junit = parse_junit(args.junit) if args.junit else None
    if junit is not None:
        junit["path"] = str(args.junit)
    if "sweep" in config:
        check_sweep(config["sweep"], f"--config {args.config}")
    check_scheduler(args.scheduler)
    t0 = time.perf_counter()
    with output_folder(out, kind="report") as tmp:
        rep = build_report(config, out=tmp, junit=junit, no_cosim=args.no_cosim,
                           scheduler=args.scheduler, progress=not args.no_progress)
        summary = make_summary(rep, argv, baseline, args.baseline)
        write_outputs(rep, summary, tmp)
    total = time.perf_counter() - t0
    times = ", ".join(f"{k} {v:.1f} s" for k, v in rep.phases.items())
    written = [str(Path(out) / n) for n in OUTPUTS if (Path(out) / n).is_file()]
    if not args.no_progress:  # -q: errors only
        print(f"wrote {', '.join(written)} in {total:.1f} s ({times})")
        print(status_line(summary))
    bs = summary.get("baseline", {}).get("signoff")
    if bs and bs["regressed"]:
        print(f"irnuc report: {bs['text']}", file=sys.stderr)
    if summary["status"] != "pass":
        for r in summary["status_reasons"]:
            print(f"irnuc report: FAIL: {r}", file=sys.stderr)
        for e in summary.get("baseline", {}).get("regressions", [])[:20]:
            print(f"  regression: {e['metric']}: {e['baseline']} -> {e['value']} "
                  f"(better {e['better']})", file=sys.stderr)
        return 1
    return 0
