"""Area and Fmax of ``irnuc_axis_top`` with the FFC request (issue 36: ``FFC_PERIOD``,
``FFC_THRESHOLD``, ``FFC_TRIGGER``, ``FFC_REF``, ``IRQ_STATUS.ffc_request``;
``hdl/irnuc_ffc_trigger.sv`` in ``irnuc_axil_regs``) against the same wrapper without it
(``hdl/`` at ``--before``, default the issue-40 commit it was built on, read with ``git
archive``), both measured in this run on the same flow.

For each configuration of ``--configs`` the wrapper is synthesized for ECP5 twice
(``cosim.synth.synth_ecp5``), then each netlist placed and routed (LFE5U-85F CABGA381,
speed 6, target 150 MHz, the flow's settings) once per placer seed of ``--seeds``. Per
configuration: ECP5 LUT4, FF and CCU2C of both, the Fmax of each seed and the best; the
ratios are the sums of LUT4 / FF and the means of the best Fmax, new over before.

Usage: ``python benchmarks/bench_ffc_trigger.py [--configs ffc14,tcffc14] [--seeds 1]
[--before REV] [--out DIR]``. The last line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import io
import json
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

from bench_placer import GOAL_MHZ, _ints
from bench_regfile import measure, ratios

from irnuc.common.cache import cache_dir
from irnuc.cosim import synth
from irnuc.cosim.sources import HDL_DIR, hdl_sources
from irnuc.nuc_fixed import load_pipeline

TOP = "irnuc_axis_top"
BEFORE = "d666897"  # issue 40's branch head the FFC request was added to
REPO = Path(__file__).resolve().parent.parent


def _before_hdl(rev: str, tmp: Path) -> Path:
    """``hdl/`` of commit ``rev`` (git archive), or a one-line exit."""
    try:
        tar = subprocess.run(["git", "-C", str(REPO), "archive", rev, "hdl"], check=True,
                             capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError) as exc:
        sys.exit(f"bench_ffc_trigger: --before {rev}: git archive failed "
                 f"({getattr(exc, 'stderr', b'').decode().strip() or exc})")
    with tarfile.open(fileobj=io.BytesIO(tar)) as t:
        t.extractall(tmp, filter="data")
    return tmp / "hdl"


def _sources(hdl_dir: Path | None) -> list[Path]:
    """The wrapper's files in ``hdl_dir`` (the files the current list names that the old
    tree has: the old tree has no irnuc_ffc_trigger.sv)."""
    files = hdl_sources(TOP, hdl_dir=hdl_dir)
    return [p for p in files if p.is_file()]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--configs", default="ffc14,tcffc14")
    ap.add_argument("--seeds", default="1")
    ap.add_argument("--before", default=BEFORE)
    ap.add_argument("--out", type=Path, default=cache_dir("bench_ffc_trigger"))
    args = ap.parse_args()
    seeds = _ints(args.seeds, "--seeds")
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    cfgs = {name: load_pipeline(name) for name in configs}  # a bad name fails before work
    bad = [n for n, c in cfgs.items() if not c.has("ffc")]
    if bad:
        sys.exit(f"bench_ffc_trigger: --configs {bad[0]} has no ffc stage")

    with tempfile.TemporaryDirectory(prefix="bench-ffc-trigger-") as tmp:
        variants = {"trigger": HDL_DIR, "before": _before_hdl(args.before, Path(tmp))}
        results = measure(cfgs, variants, _sources, seeds, args.out)

    print(json.dumps({
        "benchmark": "ffc_trigger", "top": TOP, "configs": configs, "seeds": seeds,
        "goal_mhz": GOAL_MHZ, "before": args.before, "results": results,
        "all_at_goal": all(results[n]["trigger"]["at_goal"] for n in configs),
        **ratios(results, "trigger", "before"),
        "tools": synth.tool_versions(),
    }))


if __name__ == "__main__":
    main()
