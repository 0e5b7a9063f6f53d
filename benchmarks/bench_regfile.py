"""Area and Fmax of ``irnuc_axis_top`` with the register file generated from the map
(``hdl/``: peakrdl-regblock's block behind ``irnuc_axil_regs``) against the hand-written
one it replaced (``benchmarks/rtl_baseline/irnuc_axil_regs.sv``, commit 6e42ca5), both
measured in this run on the same flow.

For each configuration of ``--configs`` the wrapper is synthesized for ECP5 twice
(``cosim.synth.synth_ecp5``: the design as it is, and a copy of ``hdl/`` with the baseline
register file), then each netlist placed and routed (LFE5U-85F CABGA381, speed 6, target
150 MHz, the flow's settings) once per placer seed of ``--seeds``. Per configuration: ECP5
LUT4, FF and CCU2C of both, the Fmax of each seed and the best; the ratios are the sums of
LUT4 and the means of the best Fmax, new over baseline. ``irnuc synth --top
irnuc_axis_top`` gives the same netlists for the design as it is (and the xc7 area).

Usage: ``python benchmarks/bench_regfile.py [--configs minimal,typical14,tcffc14,table14,
drift14] [--seeds 1,2] [--out DIR]``. The last line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import tempfile
from pathlib import Path

from bench_placer import GOAL_MHZ, _ints

from irnuc.common.cache import cache_dir
from irnuc.cosim import synth
from irnuc.cosim.sources import HDL_DIR, hdl_sources, top_parameters
from irnuc.nuc_fixed import load_pipeline

TOP = "irnuc_axis_top"
BASELINE = Path(__file__).resolve().parent / "rtl_baseline"
BASELINE_FILES = ("irnuc_axil_regs.sv", "irnuc_axil_regs_check.sv")


def _baseline_hdl(tmp: Path) -> Path:
    """A copy of hdl/ with the hand-written register file."""
    out = tmp / "hdl"
    shutil.copytree(HDL_DIR, out)
    for name in BASELINE_FILES:
        shutil.copy(BASELINE / name, out / name)
    return out


def _sources(hdl_dir: Path | None) -> list[Path]:
    files = hdl_sources(TOP, hdl_dir=hdl_dir)
    if hdl_dir is None:
        return files
    return [p for p in files if not p.name.startswith("irnuc_axil_regblock")]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--configs", default="minimal,typical14,tcffc14,table14,drift14")
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--out", type=Path, default=cache_dir("bench_regfile"))
    args = ap.parse_args()
    seeds = _ints(args.seeds, "--seeds")
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    cfgs = {name: load_pipeline(name) for name in configs}  # a bad name fails before work

    results: dict[str, dict[str, dict]] = {}
    with tempfile.TemporaryDirectory(prefix="bench-regfile-") as tmp:
        variants = {"generated": None, "baseline": _baseline_hdl(Path(tmp))}
        for name, cfg in cfgs.items():
            params = top_parameters(TOP, cfg)
            results[name] = {}
            for variant, hdl_dir in variants.items():
                work = args.out / name / variant
                net, cells = synth.synth_ecp5(_sources(hdl_dir), TOP, params, work / "ecp5")
                fmax = {}
                for seed in seeds:
                    pnr = synth.place_route_ecp5(net, work / f"pnr_s{seed}", freq_mhz=GOAL_MHZ,
                                                 seed=seed)
                    fmax[str(seed)] = pnr["fmax_mhz"]
                    print(f"{name} {variant} seed {seed}: {pnr['fmax_mhz']:.1f} MHz, "
                          f"{cells['lut4']} LUT4", flush=True)
                results[name][variant] = {
                    "lut4": cells["lut4"], "ff": cells["ff"], "ccu2c": cells["ccu2c"],
                    "fmax_mhz": fmax, "best_mhz": max(fmax.values()),
                    "at_goal": max(fmax.values()) >= GOAL_MHZ}

    def total(variant: str, key: str) -> float:
        return sum(results[n][variant][key] for n in configs)

    def mean_best(variant: str) -> float:
        return statistics.fmean(results[n][variant]["best_mhz"] for n in configs)

    print(json.dumps({
        "benchmark": "register_file", "top": TOP, "configs": configs, "seeds": seeds,
        "goal_mhz": GOAL_MHZ, "baseline": "benchmarks/rtl_baseline/irnuc_axil_regs.sv",
        "results": results,
        "all_at_goal": all(results[n]["generated"]["at_goal"] for n in configs),
        "ratio_lut4_generated_vs_baseline": round(total("generated", "lut4")
                                                  / total("baseline", "lut4"), 3),
        "ratio_ff_generated_vs_baseline": round(total("generated", "ff")
                                                / total("baseline", "ff"), 3),
        "ratio_mean_best_fmax_generated_vs_baseline": round(mean_best("generated")
                                                            / mean_best("baseline"), 3),
        "tools": synth.tool_versions(),
    }))


if __name__ == "__main__":
    main()
