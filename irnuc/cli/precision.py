"""``irnuc precision``: work-precision diagrams (error against run time) as HTML + JSON.

Only the standard library is imported at module level; the measurements and figures
(:mod:`irnuc.reports.studies.precision`), numpy and matplotlib are imported inside the
functions.
"""

from __future__ import annotations

import argparse
import base64
import html
import json
from pathlib import Path
from typing import Any

from irnuc.cli._args import add_out, progress, say

DEFAULT_OUT = Path("out/precision")
JSON_NAME = "precision.json"
HTML_NAME = "precision.html"


def _fmt(x: float | None) -> str:
    return "-" if x is None else f"{x:.3g}"


def render_html(result: dict[str, Any]) -> str:
    """The HTML report: per component two log-log figures (error against time and against
    work), the table of points and the table of omitted (failed) settings."""
    from irnuc.reports.studies.precision import failure_label, figures

    esc = html.escape
    figs = figures(result)
    secs = result.get("seconds")
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>irnuc work-precision</title>",
        "<style>body{font-family:sans-serif;max-width:1150px;margin:auto}"
        "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;"
        "padding:2px 6px}.def{font-weight:bold;background:#ffd}.bad{color:#a00}</style>"
        "</head><body>",
        "<h1>Work-precision diagrams</h1>",
        f"<p>Run time is the minimum of a few runs after a JIT warm-up, on one numba "
        f"thread; the work axis (series terms, Newton iterations, substeps) is free of timing "
        f"noise. A point is on the Pareto front unless another is both at least "
        f"{result['time_margin']}&times; faster (cheaper) and {result['error_margin']}&times; "
        f"more accurate. Failed settings are red crosses above the data, at the time and "
        f"work they took to fail, and listed under each figure. "
        f"{'Quick run. ' if result['quick'] else ''}"
        f"{'Study time ' + format(secs, '.0f') + ' s.' if secs is not None else ''}</p>",
    ]
    for c, (caption, png) in zip(result["components"], figs, strict=True):
        d = c["default"]
        b64 = base64.b64encode(png).decode()
        parts += [
            f"<h2>{esc(c['title'])}</h2>",
            f"<p>Problem: {esc(c['problem'])}.<br>Reference: {esc(c['reference'])}; its own "
            f"error estimate {_fmt(c['reference_error'])}.<br>Error: "
            f"{esc(c['error_metric'])}.<br>Default: {esc(str(d['method']))}, "
            f"{esc(d['setting_name'])} = {d['setting']:g}: error {_fmt(d['error'])}, "
            f"time {_fmt(d['time_s'])} s, work {_fmt(d['work'])}, "
            f"<b>{'on' if d['on_pareto_front'] else 'NOT on'} the Pareto front</b> "
            f"(by work: {'on' if d['on_front_work'] else 'not on'}).</p>",
            f"<figure><img alt='{esc(c['name'])}' src='data:image/png;base64,{b64}'>"
            f"<figcaption>{esc(caption)}</figcaption></figure>",
            "<table><tr><th>method</th><th>setting</th><th>error</th><th>time (s)</th>"
            "<th>work</th><th>front (time)</th><th>front (work)</th></tr>",
        ]
        for p in c["points"]:
            if p["failed"]:
                continue
            cls = " class='def'" if p["default"] else ""
            yn = {None: "", True: "yes", False: "no"}
            parts.append(
                f"<tr{cls}><td>{esc(p['method'])}</td><td>{esc(p['setting_name'])} = "
                f"{p['setting']:g}</td><td>{_fmt(p['error'])}</td><td>{_fmt(p['time_s'])}</td>"
                f"<td>{_fmt(p['work'])}</td><td>{yn[p['on_front']]}</td>"
                f"<td>{yn[p['on_front_work']]}</td></tr>")
        parts.append("</table>")
        if c["missing"]:
            parts.append("<h3>Omitted (failed) settings</h3><table><tr><th>method</th>"
                         "<th>setting</th><th>label</th><th>reason</th></tr>")
            for m in c["missing"]:
                parts.append(f"<tr class='bad'><td>{esc(m['method'])}</td><td>"
                             f"{esc(m['setting_name'])} = {m['setting']:g}</td><td>"
                             f"{esc(failure_label(m['reason']))}</td><td>"
                             f"{esc(m['reason'] or '')}</td></tr>")
            parts.append("</table>")
    parts.append("</body></html>")
    return "\n".join(parts)


def write_report(result: dict[str, Any], out_dir: str | Path = DEFAULT_OUT) -> tuple[Path, Path]:
    """Write ``precision.json`` and ``precision.html`` atomically into ``out_dir``."""
    from irnuc.common.io import write_text_atomic

    out = Path(out_dir)
    result = {**result, "code_digest": code_digest()}
    j = write_text_atomic(out / JSON_NAME, json.dumps(result, indent=1, sort_keys=True))
    h = write_text_atomic(out / HTML_NAME, render_html(result))
    return j, h


def precision_summary(out_dir: str | Path = DEFAULT_OUT, *, run_if_missing: bool = True,
                      quick: bool = True) -> dict[str, Any]:
    """The summary for ``irnuc report``: from ``out_dir/precision.json`` if that file holds a
    run of the current model code at the same depth (``quick``), else from a fresh run,
    which is also written there."""
    from irnuc.reports.studies.precision import run_precision, summarize

    path = Path(out_dir) / JSON_NAME
    if path.is_file():
        cached = json.loads(path.read_text())
        # Reuse a stored run only if it measured this very code at the same depth.
        if cached.get("code_digest") == code_digest() and cached.get("quick") == quick:
            return summarize(cached)
    if not run_if_missing:
        raise FileNotFoundError(f"{path} holds no run of the current code; run `irnuc precision`")
    result = run_precision(quick=quick)
    write_report(result, out_dir)
    return summarize(result)


def code_digest() -> str:
    """Hash of the model's source files: a stored precision run is valid for this code only."""
    import hashlib

    from irnuc import model
    root = Path(model.__file__).parent
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(path.relative_to(root).as_posix().encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


def add_arguments(p: argparse.ArgumentParser) -> None:
    add_out(p, str(DEFAULT_OUT))
    p.add_argument("--quick", action="store_true",
                   help="fewer settings and samples (well under a minute)")
    p.add_argument("--only", action="append", metavar="COMPONENT",
                   help="measure only this component (band_radiance, band_radiance_narrow, "
                        "electro_thermal, transient_nonstiff, transient_stiff_1e3, ...) or "
                        "group (radiance, transient, transient_stiff); repeatable")


def run(args: argparse.Namespace) -> int:
    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder
    from irnuc.reports.studies.precision import component_names, run_precision

    out = claim_output_folder(args.out, kind="precision")
    try:
        component_names(args.only)
    except UserError as exc:
        raise UserError(f"--only: {exc}") from None
    result = run_precision(quick=args.quick, components=args.only, progress=progress("precision"))
    with output_folder(out, kind="precision") as tmp:
        write_report(result, tmp)
    for c in result["components"]:
        d = c["default"]
        say(f"{c['name']:22s} default {d['method']} {d['setting_name']}={d['setting']:g}: "
            f"error {_fmt(d['error'])}, {_fmt(d['time_s'])} s, work {_fmt(d['work'])}, "
            f"{'on' if d['on_pareto_front'] else 'NOT on'} the Pareto front; "
            f"{len(c['missing'])} failed setting(s)")
    say(f"study time {result['seconds']:.0f} s; wrote {out / HTML_NAME} and {out / JSON_NAME}")
    return 0


COMMANDS = {
    "precision": ("Work-precision diagrams of the model's numerical methods", add_arguments,
                  run),
}
