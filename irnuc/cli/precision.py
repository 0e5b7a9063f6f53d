"""``irnuc precision``: work-precision diagrams (error against run time) as HTML + JSON.

Only the standard library is imported at module level; the measurements and figures
(:mod:`irnuc.reports.studies.precision`), the page's template
(:func:`irnuc.reports.report.render.render_precision_page`, the report's stylesheet) and the
cache (:mod:`irnuc.reports.studies.precision_cache`, shared with ``irnuc report``) are
imported inside the functions.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from irnuc.cli._args import add_out, progress, say

DEFAULT_OUT = Path("out/precision")
JSON_NAME = "precision.json"
HTML_NAME = "precision.html"


def _fmt(x: float | None) -> str:
    return "-" if x is None else f"{x:.3g}"


def write_report(result: dict[str, Any], out_dir: str | Path = DEFAULT_OUT) -> tuple[Path, Path]:
    """Write ``precision.json`` and ``precision.html`` (the report's templates and
    stylesheet) atomically into ``out_dir``."""
    from irnuc.common.io import write_text_atomic
    from irnuc.reports.report.render import render_precision_page
    from irnuc.reports.studies.precision_cache import code_digest

    out = Path(out_dir)
    result = {**result, "code_digest": code_digest()}
    j = write_text_atomic(out / JSON_NAME, json.dumps(result, indent=1, sort_keys=True))
    h = write_text_atomic(out / HTML_NAME, render_precision_page(result))
    return j, h


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
    from irnuc.reports.studies.precision_cache import store_precision

    store_precision(result, args.only)  # the report reuses it
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
