"""Fmax over placer seeds: ``irnuc synth --seeds N`` against the single-seed flow.

For each configuration of ``--configs`` (default: every 14-bit configuration, the
``*14`` names of ``nuc_fixed/pipelines.toml``) and each top of ``--tops`` (``bare``: the
configuration's own core, ``cosim.synth.default_top``; ``irnuc_axis_top``: the AXI
wrapper), ``cosim.synth.synth_seeds`` places the design at placer seeds 1..``--seeds``
(LFE5U-85F CABGA381, speed 6, target 150 MHz, the flow's settings; in parallel on
``--workers``, every placement cached by design and seed, so a second run reads the cache).
The baseline is the single-seed flow, ``irnuc synth`` at its default seed 1: the first of
the same placements, measured in the same run on the same netlists. Per design: seed 1's
Fmax, the best and the worst over the seeds and their seeds, the spread, the ratios best /
seed 1 and worst / seed 1; and whether it meets the goal of issue 41 (best >= 150 MHz,
worst >= 140 MHz). Overall: the means, the lowest, the designs meeting the goal under
each rule (seed 1 at 150 against best of N at 150 and worst at 140), the place-and-route
seconds of the placements.

Usage: ``python benchmarks/bench_seeds.py [--configs typical14,ffc14] [--tops
bare,irnuc_axis_top] [--seeds 4] [--workers 2]``. Run it under the heavy-job lock. The last
line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from irnuc.common.cache import cache_dir
from irnuc.cosim import synth
from irnuc.nuc_fixed import load_pipeline, pipeline_names

BEST_GOAL_MHZ, WORST_GOAL_MHZ = 150.0, 140.0


def default_configs() -> list[str]:
    """typical14 and every ``*14`` configuration of every method (``pipeline_names()``
    alone lists only the two-point ones)."""
    names = [n for n in pipeline_names(method=None) if n.endswith("14")]
    return ["typical14", *[n for n in names if n != "typical14"]]


def design_row(r: dict) -> dict:
    """One design's figures from a seed sweep's result (``synth.best_of_seeds``)."""
    sd = r["seeds"]
    s1 = sd["fmax_mhz"][str(sd["seeds"][0])]
    return {"top": r["top"], "seed1_mhz": s1, "best_mhz": sd["best_mhz"],
            "best_seed": sd["best_seed"], "worst_mhz": sd["worst_mhz"],
            "worst_seed": sd["worst_seed"], "spread_mhz": sd["spread_mhz"],
            "fmax_mhz": sd["fmax_mhz"],
            "ratio_best_vs_seed1": round(sd["best_mhz"] / s1, 3),
            "ratio_worst_vs_seed1": round(sd["worst_mhz"] / s1, 3),
            "meets_goal": sd["best_mhz"] >= BEST_GOAL_MHZ and sd["worst_mhz"] >= WORST_GOAL_MHZ,
            "ecp5_lut4": r["ecp5"]["lut4"], "ecp5_ff": r["ecp5"]["ff"]}


def summary(rows: list[dict]) -> dict:
    s1 = [r["seed1_mhz"] for r in rows]
    best = [r["best_mhz"] for r in rows]
    worst = [r["worst_mhz"] for r in rows]
    return {
        "designs": len(rows),
        "mean_seed1_mhz": round(statistics.fmean(s1), 2),
        "mean_best_mhz": round(statistics.fmean(best), 2),
        "mean_worst_mhz": round(statistics.fmean(worst), 2),
        "min_seed1_mhz": min(s1), "min_best_mhz": min(best), "min_worst_mhz": min(worst),
        "seed1_at_150": sum(v >= BEST_GOAL_MHZ for v in s1),
        "best_at_150": sum(v >= BEST_GOAL_MHZ for v in best),
        "worst_at_140": sum(v >= WORST_GOAL_MHZ for v in worst),
        "meeting_goal": sum(r["meets_goal"] for r in rows),
        "ratio_mean_best_vs_seed1": round(statistics.fmean(best) / statistics.fmean(s1), 3),
        "ratio_min_best_vs_min_seed1": round(min(best) / min(s1), 3),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--configs", default=",".join(default_configs()))
    ap.add_argument("--tops", default="bare,irnuc_axis_top")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    tops = [t.strip() for t in args.tops.split(",") if t.strip()]
    cfgs = {name: load_pipeline(name) for name in configs}  # a bad name fails before work
    for t in tops:
        if t != "bare" and t not in synth.SYNTH_TOPS:
            raise SystemExit(f"bench_seeds: --tops {t!r}: expected bare or one of "
                             f"{', '.join(synth.SYNTH_TOPS)}")
    if not 2 <= args.seeds <= synth.MAX_SEEDS:
        raise SystemExit(f"bench_seeds: --seeds {args.seeds}: expected 2..{synth.MAX_SEEDS}")

    t0 = time.perf_counter()
    rows: dict[str, dict[str, dict]] = {}
    pnr_s: list[float] = []
    cached = 0
    for name, cfg in cfgs.items():
        rows[name] = {}
        for t in tops:
            top = synth.default_top(cfg) if t == "bare" else t
            if top not in synth.tops_for(cfg):
                continue
            # Counted before the sweep: afterwards every placement is in the cache.
            cached += sum((cache_dir("synth") / synth.synth_key(cfg, top=top, seed=s)
                           / "synth.json").is_file() for s in synth.seed_list(args.seeds))
            r = synth.synth_seeds(cfg, top=top, seeds=args.seeds, workers=args.workers)
            row = design_row(r)
            rows[name][t] = row
            for s in r["seeds"]["seeds"]:
                one = synth.synth_config(cfg, top=top, seed=s)  # cached: its seconds
                pnr_s.append(one["seconds"]["place_route"])
            print(f"{name} {top}: seed 1 {row['seed1_mhz']:.1f}, best {row['best_mhz']:.1f} "
                  f"(seed {row['best_seed']}), worst {row['worst_mhz']:.1f} (seed "
                  f"{row['worst_seed']}) MHz{'' if row['meets_goal'] else '  MISSES THE GOAL'}",
                  flush=True)
    by_top = {t: summary([rows[n][t] for n in configs if t in rows[n]]) for t in tops}
    every = summary([row for n in configs for row in rows[n].values()])
    print(json.dumps({
        "benchmark": "seeds", "configs": configs, "tops": tops,
        "seeds": synth.seed_list(args.seeds), "baseline": "seed 1 (the single-seed flow)",
        "goal": {"best_mhz": BEST_GOAL_MHZ, "worst_mhz": WORST_GOAL_MHZ},
        "device": f"LFE5U-{synth.ECP5_DEVICE.removesuffix('k')}F {synth.ECP5_PACKAGE} speed "
                  f"{synth.ECP5_SPEED_DEFAULT}",
        "designs": rows, "by_top": by_top, "all": every,
        "ratio_mean_best_vs_seed1": every["ratio_mean_best_vs_seed1"],
        "place_route_s": {"placements": len(pnr_s), "total": round(sum(pnr_s), 1),
                          "mean": round(statistics.fmean(pnr_s), 1) if pnr_s else None,
                          "cached_before_this_run": cached},
        "seconds": round(time.perf_counter() - t0, 1),
        "tools": synth.tool_versions(),
    }))


if __name__ == "__main__":
    main()
