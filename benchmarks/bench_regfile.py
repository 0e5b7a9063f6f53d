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


def measure(cfgs: dict, variants: dict[str, Path | None], sources, seeds: list[int],
            out: Path) -> dict[str, dict[str, dict]]:
    """Each configuration's ``TOP`` synthesized for ECP5 once per variant (an hdl folder;
    ``sources(folder)`` its files), placed and routed once per seed: configuration ->
    variant -> LUT4, FF, CCU2C, the Fmax of each seed, the best, whether it met the goal."""
    results: dict[str, dict[str, dict]] = {}
    for name, cfg in cfgs.items():
        params = top_parameters(TOP, cfg)
        results[name] = {}
        for variant, hdl_dir in variants.items():
            work = out / name / variant
            net, cells = synth.synth_ecp5(sources(hdl_dir), TOP, params, work / "ecp5")
            fmax = {}
            for seed in seeds:
                pnr = synth.place_route_ecp5(net, work / f"pnr_s{seed}", freq_mhz=GOAL_MHZ,
                                             seed=seed)
                fmax[str(seed)] = pnr["fmax_mhz"]
                print(f"{name} {variant} seed {seed}: {pnr['fmax_mhz']:.1f} MHz, "
                      f"{cells['lut4']} LUT4, {cells['ff']} FF", flush=True)
            results[name][variant] = {
                "lut4": cells["lut4"], "ff": cells["ff"], "ccu2c": cells["ccu2c"],
                "fmax_mhz": fmax, "best_mhz": max(fmax.values()),
                "at_goal": max(fmax.values()) >= GOAL_MHZ}
    return results


def ratios(results: dict[str, dict[str, dict]], new: str, old: str) -> dict[str, float]:
    """Variant ``new`` over ``old`` over every configuration: the sums of LUT4 and FF, the
    means of the best Fmax."""
    def total(variant: str, key: str) -> float:
        return sum(r[variant][key] for r in results.values())

    def mean_best(variant: str) -> float:
        return statistics.fmean(r[variant]["best_mhz"] for r in results.values())

    return {f"ratio_lut4_{new}_vs_{old}": round(total(new, "lut4") / total(old, "lut4"), 3),
            f"ratio_ff_{new}_vs_{old}": round(total(new, "ff") / total(old, "ff"), 3),
            f"ratio_mean_best_fmax_{new}_vs_{old}": round(mean_best(new) / mean_best(old), 3)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--configs", default="minimal,typical14,tcffc14,table14,drift14")
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--out", type=Path, default=cache_dir("bench_regfile"))
    args = ap.parse_args()
    seeds = _ints(args.seeds, "--seeds")
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    cfgs = {name: load_pipeline(name) for name in configs}  # a bad name fails before work

    with tempfile.TemporaryDirectory(prefix="bench-regfile-") as tmp:
        variants = {"generated": None, "baseline": _baseline_hdl(Path(tmp))}
        results = measure(cfgs, variants, _sources, seeds, args.out)

    print(json.dumps({
        "benchmark": "register_file", "top": TOP, "configs": configs, "seeds": seeds,
        "goal_mhz": GOAL_MHZ, "baseline": "benchmarks/rtl_baseline/irnuc_axil_regs.sv",
        "results": results,
        "all_at_goal": all(results[n]["generated"]["at_goal"] for n in configs),
        **ratios(results, "generated", "baseline"),
        "tools": synth.tool_versions(),
    }))


if __name__ == "__main__":
    main()
