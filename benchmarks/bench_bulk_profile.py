"""Per-RTL-module profile of the bulk co-simulation's Verilated model (issue 41 item 3).

For each method (default tcgain14, table14, typical14) ``--frames`` VGA frames of the drift
sequence of ``bench_methods_cosim.py`` run through the bulk harness of ``method_dpc_top``
under valgrind's callgrind (``irnuc.cosim.bulk_profile``: the plain build's code with line
tables; every output still checked bit for bit). Printed: the instructions per clock
cycle, the share of each RTL module (its instances' generated statements), of the harness,
the scheduler and Verilator's inlined helpers, the costliest instances, and the costliest
generated statements of the top modules. ``--hdl-dir``: the same for a modified copy of the
design (an RTL change measured before it is made); ``--baseline-hdl``: with ``--hdl-dir``,
the plain design profiled in the same run and the ratio of instructions per cycle.
Needs valgrind. The last line is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from irnuc.cosim.bulk_profile import callgrind_tools, profile_method
from irnuc.cosim.method_drift import calibrate_methods, drift_sequence
from irnuc.nuc_fixed import load_pipeline

METHODS = ("tcgain14", "table14", "typical14")
#: The base methods' configurations (those of bench_methods_cosim.py): method_dpc_top.
CHOICES = ("onepoint14", "typical14", "piecewise14", "quadratic14", "tcoffset14", "tcgain14",
           "table14")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", action="append", default=[], choices=CHOICES,
                    help="method configuration (repeatable; default: " + ", ".join(METHODS)
                    + ")")
    ap.add_argument("--frames", type=int, default=1)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--hdl-dir", type=Path, default=None,
                    help="profile a modified copy of hdl/ instead")
    ap.add_argument("--baseline-hdl", action="store_true",
                    help="with --hdl-dir: also profile hdl/ and report the ratio")
    ap.add_argument("--top", type=int, default=12, help="rows per table")
    args = ap.parse_args()
    if args.frames < 1:
        sys.exit("bench_bulk_profile: --frames must be at least 1")
    if args.hdl_dir is not None and not (args.hdl_dir / "method_dpc_top.sv").is_file():
        sys.exit(f"bench_bulk_profile: --hdl-dir {args.hdl_dir}: no method_dpc_top.sv")
    try:
        callgrind_tools()
    except FileNotFoundError as e:
        sys.exit(f"bench_bulk_profile: {e}")
    cfgs = [load_pipeline(n) for n in (args.only or METHODS)]
    shape = (480, 640)
    seq = drift_sequence(args.frames, shape, seed=args.seed)
    cals = calibrate_methods(cfgs, shape, seed=args.seed)
    out: dict = {"frames": args.frames, "frame": list(shape),
                 "hdl_dir": None if args.hdl_dir is None else str(args.hdl_dir),
                 "unit": "instructions (callgrind), percent of the harness process's",
                 "methods": {}}
    designs = [("design", args.hdl_dir)]
    if args.hdl_dir is not None and args.baseline_hdl:
        designs.insert(0, ("baseline", None))
    for cfg in cfgs:
        c = cals[cfg.name]
        rd = seq.reading if "fpa" in cfg.base.readings else None
        entry: dict = {}
        for label, hdl in designs:
            prof, bad = profile_method(cfg, c, seq.codes, rd, hdl_dir=hdl)
            per_cycle = prof.total / max(prof.cycles, 1)
            print(f"\n== {cfg.name} ({label}{'' if hdl is None else ' ' + str(hdl)}): "
                  f"{prof.total:,} instructions, {prof.cycles:,} cycles, "
                  f"{per_cycle:.0f} per cycle, {bad} mismatches")
            for title, rows in (("module", prof.shares(prof.modules, args.top)),
                                ("outside the model", prof.shares(prof.outside, args.top)),
                                ("instance", prof.shares(prof.instances, args.top))):
                print(f"-- per {title}")
                for r in (r for r in rows if r["percent"] >= 0.1):
                    print(f"{r['percent']:6.2f} %  {r['per_cycle']:7.1f}/cycle  {r['name']}")
            entry[label] = {
                "instructions": prof.total, "cycles": prof.cycles,
                "per_cycle": round(per_cycle, 1), "mismatches": bad,
                "modules": prof.shares(prof.modules),
                "outside": prof.shares(prof.outside),
                "instances": prof.shares(prof.instances, 40),
                "lines": {m: [[n, code[:160]] for n, code in v]
                          for m, v in prof.lines.items()
                          if m in {r["name"] for r in prof.shares(prof.modules, 8)}}}
        if "baseline" in entry:
            entry["ratio_to_baseline"] = round(entry["baseline"]["per_cycle"]
                                               / max(entry["design"]["per_cycle"], 1e-9), 4)
            print(f"-- {cfg.name}: instructions per cycle, baseline / design = "
                  f"{entry['ratio_to_baseline']}")
        out["methods"][cfg.name] = entry
    out["mismatches"] = sum(d["mismatches"] for m in out["methods"].values()
                            for k, d in m.items() if isinstance(d, dict))
    print(json.dumps(out))


if __name__ == "__main__":
    main()
