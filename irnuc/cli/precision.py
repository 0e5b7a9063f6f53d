"""``irnuc precision``: work-precision diagrams (error against run time) as HTML + JSON.

Only the standard library is imported at module level; the measurements
(:mod:`model.precision`), numpy and matplotlib are imported inside the functions.
"""

from __future__ import annotations

import argparse
import base64
import html
import io
import json
from pathlib import Path
from typing import Any

DEFAULT_OUT = Path("out/precision")
JSON_NAME = "precision.json"
HTML_NAME = "precision.html"


def _figure_png(component: dict[str, Any]) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    by_method: dict[str, list[dict[str, Any]]] = {}
    for p in component["points"]:
        by_method.setdefault(p["method"], []).append(p)
    markers = "osD^v<>ph*"
    for k, (method, pts) in enumerate(by_method.items()):
        ok = [p for p in pts if p["error"] is not None]
        if not ok:
            continue
        ax.loglog([p["time_s"] for p in ok], [max(p["error"], 1e-17) for p in ok],
                  marker=markers[k % len(markers)], ms=4, lw=1, label=method)
    d = [p for p in component["points"] if p["default"] and p["error"] is not None]
    if d:
        ax.loglog([d[0]["time_s"]], [max(d[0]["error"], 1e-17)], marker="*", ms=16,
                  mfc="none", mec="k", mew=1.5, ls="none", label="default")
    ax.set_xlabel("run time, s (minimum of several runs, after JIT warm-up)")
    ax.set_ylabel("max relative error")
    ax.set_title(component["title"], fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    plt.close(fig)
    return buf.getvalue()


def _fmt(x: float | None) -> str:
    return "-" if x is None else f"{x:.3g}"


def render_html(result: dict[str, Any]) -> str:
    """The HTML report: one log-log figure and one table per component."""
    esc = html.escape
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>irnuc work-precision</title>",
        "<style>body{font-family:sans-serif;max-width:1000px;margin:auto}"
        "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;"
        "padding:2px 6px}.def{font-weight:bold;background:#ffd}</style></head><body>",
        "<h1>Work-precision diagrams</h1>",
        f"<p>Run time is the minimum of several runs after a JIT warm-up, on one numba "
        f"thread. A point is on the Pareto front unless another is both at least "
        f"{result['time_margin']}&times; faster and {result['error_margin']}&times; more "
        f"accurate (margins against timing noise). {'Quick run.' if result['quick'] else ''}"
        "</p>",
    ]
    for c in result["components"]:
        png = base64.b64encode(_figure_png(c)).decode()
        d = c["default"]
        parts += [
            f"<h2>{esc(c['title'])}</h2>",
            f"<p>Problem: {esc(c['problem'])}.<br>Reference: {esc(c['reference'])}.<br>"
            f"Error: {esc(c['error_metric'])}.<br>Default: {esc(str(d['method']))}, "
            f"{esc(d['setting_name'])} = {d['setting']:g}: error {_fmt(d['error'])}, "
            f"time {_fmt(d['time_s'])} s, <b>{'on' if d['on_pareto_front'] else 'NOT on'} "
            "the Pareto front</b>.</p>",
            f"<img alt='{esc(c['name'])}' src='data:image/png;base64,{png}'>",
            "<table><tr><th>method</th><th>setting</th><th>error</th><th>time (s)</th>"
            "<th>work</th><th>front</th><th>missing: reason</th></tr>",
        ]
        for p in c["points"]:
            cls = " class='def'" if p["default"] else ""
            front = "" if p["on_front"] is None else ("yes" if p["on_front"] else "no")
            parts.append(
                f"<tr{cls}><td>{esc(p['method'])}</td><td>{esc(p['setting_name'])} = "
                f"{p['setting']:g}</td><td>{_fmt(p['error'])}</td><td>{_fmt(p['time_s'])}</td>"
                f"<td>{_fmt(p['work'])}</td><td>{front}</td><td>{esc(p['reason'] or '')}</td></tr>")
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
    p.add_argument("--out", default=str(DEFAULT_OUT),
                   help="output folder (default: %(default)s)")
    p.add_argument("--quick", action="store_true",
                   help="fewer settings and samples (about a minute)")
    p.add_argument("--only", action="append", metavar="COMPONENT",
                   help="measure only this component (band_radiance, electro_thermal, "
                        "transient_nonstiff, transient_stiff); repeatable")
    p.add_argument("--no-progress", action="store_true")


def run(args: argparse.Namespace) -> int:
    from irnuc.common.progress import ProgressBar
    from irnuc.reports.studies.precision import run_precision, summarize

    progress = None if args.no_progress else ProgressBar("precision")
    result = run_precision(quick=args.quick, components=args.only, progress=progress)
    j, h = write_report(result, args.out)
    s = summarize(result)
    for c in s["components"]:
        d = c["default"]
        print(f"{c['name']:20s} default {d['method']} {d['setting_name']}={d['setting']:g}: "
              f"error {_fmt(d['error'])}, {_fmt(d['time_s'])} s, "
              f"{'on' if d['on_pareto_front'] else 'NOT on'} the Pareto front; "
              f"{c['missing']} missing point(s)")
    print(f"wrote {h} and {j}")
    return 0


COMMANDS = {
    "precision": ("Work-precision diagrams of the model's numerical methods", add_arguments,
                  run),
}
