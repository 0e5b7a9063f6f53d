"""Fmax against nextpnr's place-and-route settings, the flow settings of ``irnuc synth``.

For each configuration of ``--configs`` the top ``--top`` (default the AXI wrapper,
``irnuc_axis_top``, whose paths are routing-bound) is synthesized for ECP5 once
(``cosim.synth.synth_ecp5``), then placed and routed (LFE5U-85F CABGA381, speed 6,
target 150 MHz) once per setting and placer seed of ``--seeds``. A setting is a heap-placer
timing weight of ``--weights`` without the router's timing-driven rip-up, and the flow's
weight with it (``cosim.synth.PLACER_TIMING_WEIGHT``, ``ROUTER_TIMING_RIPUP``). The
baseline is nextpnr's own defaults (weight 10, no rip-up), measured in the same run on the
same netlists; the ratios are the mean Fmax of the flow's settings, and of the flow's
weight alone, over the baseline's. Also per setting: the lowest Fmax and how many
(configuration, seed) runs reach 150 MHz, and the place-and-route seconds.

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


def fmax_summary(values: list[float], seconds: list[float]) -> dict:
    """One setting's runs: mean and lowest Fmax, runs at :data:`GOAL_MHZ`, mean seconds."""
    return {"mean_mhz": round(statistics.fmean(values), 2), "min_mhz": min(values),
            "runs_at_goal": sum(v >= GOAL_MHZ for v in values), "runs": len(values),
            "place_route_s_mean": round(statistics.fmean(seconds), 1)}


def _label(weight: int, ripup: bool) -> str:
    return f"w{weight}" + ("+ripup" if ripup else "")


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
    base, alone = (BASELINE_WEIGHT, False), (synth.PLACER_TIMING_WEIGHT, False)
    flow = (synth.PLACER_TIMING_WEIGHT, synth.ROUTER_TIMING_RIPUP)
    settings = list(dict.fromkeys([*((w, False) for w in weights), flow]))
    cfgs = {name: load_pipeline(name) for name in configs}  # a bad name fails before work

    runs: dict[str, dict[str, dict[str, float]]] = {}
    seconds: dict[str, list[float]] = {_label(*st): [] for st in settings}
    for name, cfg in cfgs.items():
        work = args.out / args.top / name
        params = top_parameters(args.top, cfg)
        net, _ = synth.synth_ecp5(hdl_sources(args.top), args.top, params, work / "ecp5")
        runs[name] = {}
        for w, ripup in settings:
            key = _label(w, ripup)
            runs[name][key] = {}
            for seed in seeds:
                pnr = synth.place_route_ecp5(net, work / f"pnr_{key}_s{seed}",
                                             freq_mhz=GOAL_MHZ, seed=seed, timing_weight=w,
                                             timing_ripup=ripup)
                runs[name][key][str(seed)] = pnr["fmax_mhz"]
                seconds[key].append(pnr["seconds"])
                print(f"{name} {key} seed {seed}: {pnr['fmax_mhz']:.1f} MHz", flush=True)

    summary = {}
    for st in settings:
        key = _label(*st)
        values = [runs[n][key][str(s)] for n in configs for s in seeds]
        summary[key] = fmax_summary(values, seconds[key])
    b, a, f = (summary[_label(*st)] for st in (base, alone, flow))
    print(json.dumps({
        "benchmark": "place_route_settings", "top": args.top, "configs": configs,
        "seeds": seeds, "goal_mhz": GOAL_MHZ, "baseline": _label(*base),
        "flow": _label(*flow), "fmax_mhz": runs, "by_setting": summary,
        "ratio_mean_fmax_flow_vs_baseline": round(f["mean_mhz"] / b["mean_mhz"], 3),
        "ratio_mean_fmax_flow_weight_alone_vs_baseline": round(a["mean_mhz"] / b["mean_mhz"], 3),
        "ratio_place_route_s_flow_vs_baseline": round(
            f["place_route_s_mean"] / b["place_route_s_mean"], 3),
        "tools": synth.tool_versions(),
    }))


if __name__ == "__main__":
    main()
