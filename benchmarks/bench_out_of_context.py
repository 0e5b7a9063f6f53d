"""Fmax of a top placed and routed on the package's pins against out of context.

``irnuc synth`` places a top with its ports bound to package pins (LFE5U-85F CABGA381): a
wide AXI wrapper then fills most of the I/O ring (the FFC compositions of
``irnuc_axis_top``: 290-354 of the 365 I/O), which could pull its logic towards every side
of the die. Inside an SoC those ports meet on-chip logic. ``--out-of-context`` (nextpnr's option of the
same name) places the design as such a block: no I/O buffers, no pins.

For each configuration of ``--configs`` the top ``--top`` is synthesized for ECP5 once
(``cosim.synth.synth_ecp5``), then placed and routed with the flow's settings
(``PLACER_TIMING_WEIGHT``, ``ROUTER_TIMING_RIPUP``; speed 6, target 150 MHz) once per
placer seed of ``--seeds``, on pins (the baseline, the flow's default) and out of context,
in the same run on the same netlists. Reported per setting: mean and lowest Fmax, the runs
at 150 MHz, the place-and-route seconds; the ratio is the mean Fmax out of context over the
baseline's.

Usage: ``python benchmarks/bench_out_of_context.py [--top irnuc_axis_top]
[--configs ffc14,quadffc14,tcffc14] [--seeds 1,2,3,4] [--workers 2] [--out DIR]``. The
last line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import json
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from bench_placer import GOAL_MHZ, _ints, fmax_summary

from irnuc.common.cache import cache_dir
from irnuc.cosim import synth
from irnuc.cosim.sources import hdl_sources, top_parameters
from irnuc.nuc_fixed import load_pipeline

SETTINGS = {"pins": False, "out_of_context": True}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--top", default="irnuc_axis_top")
    ap.add_argument("--configs", default="ffc14,quadffc14,tcffc14")
    ap.add_argument("--seeds", default="1,2,3,4")
    ap.add_argument("--workers", type=int, default=2,
                    help="place-and-route runs at once (each is one nextpnr process)")
    ap.add_argument("--out", type=Path, default=cache_dir("bench_out_of_context"))
    args = ap.parse_args()
    seeds = _ints(args.seeds, "--seeds")
    if not 1 <= args.workers <= 64:
        raise SystemExit(f"bench_out_of_context: --workers {args.workers} is outside 1..64")
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    cfgs = {name: load_pipeline(name) for name in configs}  # a bad name fails before work

    nets = {}
    for name, cfg in cfgs.items():
        work = args.out / args.top / name
        nets[name], _ = synth.synth_ecp5(hdl_sources(args.top), args.top,
                                         top_parameters(args.top, cfg), work / "ecp5")

    def run(job: tuple[str, str, int]) -> tuple[str, str, int, dict]:
        name, key, seed = job
        pnr = synth.place_route_ecp5(nets[name], args.out / args.top / name / f"pnr_{key}_s{seed}",
                                     freq_mhz=GOAL_MHZ, seed=seed,
                                     out_of_context=SETTINGS[key])
        return name, key, seed, pnr

    jobs = [(n, k, s) for n in configs for k in SETTINGS for s in seeds]
    runs: dict[str, dict[str, dict[str, float]]] = {n: {k: {} for k in SETTINGS} for n in configs}
    seconds: dict[str, list[float]] = {k: [] for k in SETTINGS}
    io_used: dict[str, set[int]] = {k: set() for k in SETTINGS}
    with ThreadPoolExecutor(args.workers) as pool:
        for name, key, seed, pnr in pool.map(run, jobs):
            runs[name][key][str(seed)] = pnr["fmax_mhz"]
            seconds[key].append(pnr["seconds"])
            io_used[key].add(pnr["utilization"].get("TRELLIS_IO", {}).get("used", 0))
            print(f"{name} {key} seed {seed}: {pnr['fmax_mhz']:.1f} MHz", flush=True)

    summary = {}
    for key in SETTINGS:
        values = [runs[n][key][str(s)] for n in configs for s in seeds]
        summary[key] = {**fmax_summary(values, seconds[key]),
                        "io_buffers_used": sorted(io_used[key])}
    b, o = summary["pins"], summary["out_of_context"]
    print(json.dumps({
        "benchmark": "out_of_context", "top": args.top, "configs": configs, "seeds": seeds,
        "goal_mhz": GOAL_MHZ, "baseline": "pins",
        "placer_timing_weight": synth.PLACER_TIMING_WEIGHT,
        "router_timing_ripup": synth.ROUTER_TIMING_RIPUP,
        "fmax_mhz": runs, "by_setting": summary,
        "ratio_mean_fmax_out_of_context_vs_pins": round(o["mean_mhz"] / b["mean_mhz"], 3),
        "ratio_place_route_s_out_of_context_vs_pins": round(
            o["place_route_s_mean"] / b["place_route_s_mean"], 3),
        "tools": synth.tool_versions(),
    }))


if __name__ == "__main__":
    main()
