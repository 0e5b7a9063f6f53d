"""Fmax against nextpnr's heap-placer timing weight, the flow setting of ``irnuc synth``.

For each configuration of ``--configs`` the top ``--top`` (default the AXI wrapper,
``irnuc_axis_top``, whose paths are routing-bound) is synthesized for ECP5 once
(``cosim.synth.synth_ecp5``), then placed and routed (LFE5U-85F CABGA381, speed 6,
target 150 MHz) once per timing weight of ``--weights`` and placer seed of ``--seeds``.
The baseline is nextpnr's own default weight (10), measured in the same run on the same
netlists; the ratio is the mean Fmax at the flow's weight
(``cosim.synth.PLACER_TIMING_WEIGHT``) over the mean at the baseline weight. Also per
weight: the lowest Fmax and how many (configuration, seed) runs reach 150 MHz, and the
place-and-route seconds (a higher weight may cost placer time).

Usage: ``python benchmarks/bench_placer.py [--top irnuc_axis_top]
[--configs tcgain14,ffc14,quadffc14,tcffc14] [--weights 10,30] [--seeds 1,2]
[--out DIR]``. The last line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import statistics
from pathlib import Path

from irnuc.common.cache import cache_dir
from irnuc.cosim import synth
from irnuc.cosim.sources import hdl_sources, top_parameters
from irnuc.nuc_fixed import load_pipeline

BASELINE_WEIGHT = 10  # nextpnr's default --placer-heap-timingweight
GOAL_MHZ = 150.0


def _ints(text: str, flag: str) -> list[int]:
    try:
        out = [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise SystemExit(f"bench_placer: {flag} {text!r} is not a comma-separated list of "
                         "integers") from None
    if not out:
        raise SystemExit(f"bench_placer: {flag} is empty")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--top", default="irnuc_axis_top")
    ap.add_argument("--configs", default="tcgain14,ffc14,quadffc14,tcffc14")
    ap.add_argument("--weights", default=f"{BASELINE_WEIGHT},{synth.PLACER_TIMING_WEIGHT}")
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--out", type=Path, default=cache_dir("bench_placer"))
    args = ap.parse_args()
    weights = _ints(args.weights, "--weights")
    seeds = _ints(args.seeds, "--seeds")
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    for w in (BASELINE_WEIGHT, synth.PLACER_TIMING_WEIGHT):
        if w not in weights:
            weights.append(w)
    cfgs = {name: load_pipeline(name) for name in configs}  # a bad name fails before work

    runs: dict[str, dict[str, dict[str, float]]] = {}
    seconds: dict[int, list[float]] = {w: [] for w in weights}
    for name, cfg in cfgs.items():
        work = args.out / args.top / name
        params = top_parameters(args.top, cfg)
        net, _ = synth.synth_ecp5(hdl_sources(args.top), args.top, params, work / "ecp5")
        runs[name] = {}
        for w in weights:
            runs[name][str(w)] = {}
            for seed in seeds:
                pnr = synth.place_route_ecp5(net, work / f"pnr_w{w}_s{seed}", freq_mhz=GOAL_MHZ,
                                             seed=seed, timing_weight=w)
                runs[name][str(w)][str(seed)] = pnr["fmax_mhz"]
                seconds[w].append(pnr["seconds"])
                print(f"{name} weight {w} seed {seed}: {pnr['fmax_mhz']:.1f} MHz", flush=True)

    summary = {}
    for w in weights:
        values = [runs[n][str(w)][str(s)] for n in configs for s in seeds]
        summary[str(w)] = {"mean_mhz": round(statistics.fmean(values), 2),
                           "min_mhz": min(values),
                           "runs_at_goal": sum(v >= GOAL_MHZ for v in values),
                           "runs": len(values),
                           "place_route_s_mean": round(statistics.fmean(seconds[w]), 1)}
    base, flow = summary[str(BASELINE_WEIGHT)], summary[str(synth.PLACER_TIMING_WEIGHT)]
    print(json.dumps({
        "benchmark": "placer_timing_weight", "top": args.top, "configs": configs,
        "seeds": seeds, "goal_mhz": GOAL_MHZ, "baseline_weight": BASELINE_WEIGHT,
        "flow_weight": synth.PLACER_TIMING_WEIGHT, "fmax_mhz": runs, "by_weight": summary,
        "ratio_mean_fmax_flow_vs_baseline": round(flow["mean_mhz"] / base["mean_mhz"], 3),
        "ratio_place_route_s_flow_vs_baseline": round(
            flow["place_route_s_mean"] / base["place_route_s_mean"], 3),
        "tools": synth.tool_versions(),
    }))


if __name__ == "__main__":
    main()
