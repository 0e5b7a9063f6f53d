"""``irnuc synth``: area and Fmax of the RTL for pipeline configurations (standard library
only at import time)."""

from __future__ import annotations

import argparse

from irnuc.cli._args import add_executor, add_out, load_pipeline_arg, progress, say

#: What irnuc_axis_top wraps (the help's words; tests/test_cli.py checks them against the
#: method registry, nuc_fixed.methods: BASES and each StageSpec's rtl_bases, not imported
#: here so that ``irnuc --help`` stays fast): every base method, and per stage the bases
#: its top composes.
AXIS_WRAPS = ("one_point", "two_point", "piecewise", "quadratic", "tc_offset", "table_interp",
              "tc_housing")
AXIS_STAGES = {"blind_drift": ("one_point", "two_point"),
               "ffc": ("one_point", "two_point", "quadratic", "tc_offset")}


def _words(items: tuple[str, ...], last: str = "and") -> str:
    return ", ".join(items[:-1]) + f" {last} {items[-1]}" if len(items) > 1 else items[0]


def top_help() -> str:
    """The help of ``--top``: every top, and every method irnuc_axis_top wraps."""
    stages = "; ".join(f"{stage} with {_words(bases, 'or')}" for stage, bases in AXIS_STAGES.items())
    return ("the module to synthesize: nuc_dpc_top, method_dpc_top, method_drift_top, "
            "method_ffc_top or irnuc_axis_top (the AXI4-Stream/AXI4-Lite wrapper of the core "
            f"of {_words(AXIS_WRAPS)}, and of the compositions {stages}); default: the "
            "pipeline's bare core (nuc_dpc_top for two_point, method_dpc_top for the other "
            "base methods, the stage's top for a method with a stage)")


def add_synth_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--pipeline", action="append", required=True, metavar="NAME|FILE.toml",
                   help="NUC + DPC configuration: a name in nuc_fixed/pipelines.toml or a "
                        "pipeline TOML file; repeat it to synthesize several (in parallel)")
    p.add_argument("--top", default=None, metavar="MODULE", help=top_help())
    p.add_argument("--max-width", type=int, default=None,
                   help="line-buffer length to synthesize (default: the pipeline's max_width)")
    p.add_argument("--max-height", type=int, default=None,
                   help="largest frame height (default: the pipeline's max_height)")
    p.add_argument("--speed", type=int, default=6, choices=(6, 7, 8),
                   help="ECP5 speed grade for place and route (default: %(default)s, the "
                        "slowest)")
    p.add_argument("--freq", type=float, default=150.0, metavar="MHZ",
                   help="clock nextpnr aims at (default: %(default)s MHz)")
    p.add_argument("--seed", type=int, default=1,
                   help="placer seed; with --seeds the first of them (default: %(default)s)")
    p.add_argument("--seeds", type=int, default=1, metavar="N",
                   help="place each configuration at N placer seeds (--seed, --seed + 1, "
                        "...; in parallel on --workers, each placement cached) and report the "
                        "best, the worst and the spread; synth.json keeps the best "
                        "placement's figures (default: %(default)s)")
    p.add_argument("--out-of-context", action="store_true",
                   help="place and route as a block inside a larger design: ports not on "
                        "package pins, no I/O buffers (nextpnr --out-of-context)")
    add_executor(p, "synthesize", workers_help="worker processes for several "
                 "configurations; 0 = in-process", cache="this result")
    add_out(p, "out/synth")


def run_synth(args: argparse.Namespace) -> int:
    import json

    from irnuc.common.errors import UserError
    from irnuc.common.io import (
        claim_output_folder,
        output_folder,
        plain_name,
        write_text_atomic,
    )
    from irnuc.cosim.synth import MAX_SEEDS, SYNTH_TOPS, synth_configs, tops_for
    from irnuc.nuc_fixed.rtl_spec import PIPELINE_RANGES

    out = claim_output_folder(args.out, kind="synth")
    cfgs = [load_pipeline_arg(p) for p in args.pipeline]
    names = [plain_name(c.name, f"--pipeline {p}: the configuration's name")
             for c, p in zip(cfgs, args.pipeline, strict=True)]
    if len(set(names)) != len(names):
        raise UserError(f"--pipeline names {', '.join(names)}: each configuration once")
    for flag, v, field in (("--max-width", args.max_width, "max_width"),
                           ("--max-height", args.max_height, "max_height")):
        lo, hi = PIPELINE_RANGES[field]
        if v is not None and not lo <= v <= hi:
            raise UserError(f"{flag} {v} is outside the allowed range {lo}..{hi}")
    if args.top is not None and args.top not in SYNTH_TOPS:
        raise UserError(f"--top {args.top!r}: expected one of {', '.join(SYNTH_TOPS)}")
    if args.top is not None:
        for c, p in zip(cfgs, args.pipeline, strict=True):
            fits = tops_for(c)
            if args.top not in fits:
                raise UserError(f"--top {args.top} --pipeline {p}: method {c.method!r} is built "
                                f"by {', '.join(fits) or 'no top'}")
    if not 1.0 <= args.freq <= 1000.0:
        raise UserError(f"--freq {args.freq:g} is outside the allowed range 1..1000 MHz")
    if not 0 <= args.seed < 2**31:
        raise UserError(f"--seed {args.seed} is outside the allowed range 0..2^31-1")
    if not 1 <= args.seeds <= MAX_SEEDS:
        raise UserError(f"--seeds {args.seeds} is outside the allowed range 1..{MAX_SEEDS}")
    if args.seed + args.seeds - 1 >= 2**31:
        raise UserError(f"--seed {args.seed} --seeds {args.seeds}: the last seed is past "
                        "2^31-1")
    if not 0 <= args.workers <= 256:
        raise UserError(f"--workers {args.workers} is outside the allowed range 0..256")
    for c in cfgs:  # the changed frame limits must still be a legal configuration
        c.replace(**{k: v for k, v in (("max_width", args.max_width),
                                       ("max_height", args.max_height)) if v is not None})
    parallel = len(cfgs) > 1 or args.seeds > 1
    results = synth_configs(cfgs, workers=args.workers if parallel else 0, seeds=args.seeds,
                            scheduler=args.scheduler, progress=progress("synth"),
                            top=args.top, max_width=args.max_width, max_height=args.max_height,
                            speed=args.speed, freq_mhz=args.freq, seed=args.seed,
                            out_of_context=args.out_of_context, use_cache=not args.no_cache)
    with output_folder(out, kind="synth") as tmp:
        if len(results) == 1:
            write_text_atomic(tmp / "synth.json", json.dumps(results[0], indent=1) + "\n")
        else:
            for r in results:  # the names were checked plain: each is one folder
                write_text_atomic(tmp / plain_name(r["config"]["name"], "--pipeline name")
                                  / "synth.json", json.dumps(r, indent=1) + "\n")
            index = {"configurations": [
                {"name": r["config"]["name"], "fmax_mhz": r["fmax_mhz"], "xc7": r["xc7"],
                 "ecp5": r["ecp5"], "config_digest": r["config_digest"],
                 **({"seeds": r["seeds"]} if "seeds" in r else {})} for r in results]}
            write_text_atomic(tmp / "synth.json", json.dumps(index, indent=1) + "\n")
    for r in results:
        x, e = r["xc7"], r["ecp5"]
        say(f"{r['config']['name']} {r['top']} ({r['config']['max_width']} x {r['config']['max_height']}): "
            f"Fmax {fmax_text(r)} (ECP5-85k speed {r['speed']}"
            f"{', out of context' if r.get('out_of_context') else ''}); xc7 {x['lut']} LUT, "
            f"{x['ff']} FF, {x['dsp']} DSP48, {x['bram18']} RAMB18, {x['bram36']} RAMB36, "
            f"{x['lutram']} LUTRAM; ECP5 {e['lut4']} LUT4, {e['ff']} FF, {e['mult18']} MULT18, "
            f"{e['dp16kd']} DP16KD" + (" (cached)" if r["cached"] else ""))
    say(f"wrote {out / 'synth.json'}")
    return 0


def fmax_text(r: dict) -> str:
    """A result's Fmax in words: one placement's, or the best, worst and spread of a seed
    sweep (with the seed of each and how many placements reach the target)."""
    sd = r.get("seeds")
    if not sd:
        return f"{r['fmax_mhz']:.1f} MHz"
    seeds = sd["seeds"]
    span = (f"seeds {seeds[0]}-{seeds[-1]}" if seeds == list(range(seeds[0], seeds[-1] + 1))
            else "seeds " + ", ".join(map(str, seeds)))
    return (f"best {sd['best_mhz']:.1f} MHz (seed {sd['best_seed']}), worst "
            f"{sd['worst_mhz']:.1f} (seed {sd['worst_seed']}), spread {sd['spread_mhz']:.1f}, "
            f"{sd['at_target']} of {sd['runs']} at {sd['target_mhz']:g} MHz over {span}")


COMMANDS = {
    "synth": ("Synthesize the RTL (xc7 and ECP5 with pyosys), place and route it on ECP5 "
              "(nextpnr): area and Fmax per pipeline configuration", add_synth_arguments,
              run_synth),
}
