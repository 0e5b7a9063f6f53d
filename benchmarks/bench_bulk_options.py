"""Verilator-level options (and modified designs) of the bulk co-simulation, per method.

The bulk harness of ``method_dpc_top`` (``irnuc.cosim.build_bulk``) is built once per
variant: the plain build (``FAST_ARGS``: ``-O3``, ``--x-assign fast``, ``--x-initial
fast``, one C++ file, assertions on; what every test and ``bench_methods_cosim.py`` use)
and the same with more Verilator options (``--variant NAME=OPT[,OPT...]``; by default
Verilator's own passes switched off or on one at a time, C function inlining, module
inlining, ``--no-timing``) or with a modified copy of the design (``--hdl-dir DIR``, run as
the variant ``hdl``: an RTL change measured before it is made). Each variant streams the
same ``--frames`` VGA frames of the drift sequence of ``bench_methods_cosim.py`` (FPA
289 -> 307 K, calibrated on the model) through one harness process, ``--repeat`` times;
the figure is the least CPU time (user + system) of the harness process, which other work
on a shared machine moves least. Every run's outputs are compared bit for bit with the
golden model (``method_top``) and byte for byte with the plain build's.

Printed per method and variant: CPU seconds, pixels per CPU-second, the ratio to the plain
build measured in the same run (``cpu_ratio``: plain CPU / variant CPU, above 1 is
faster), whether the outputs are identical, and whether Verilator generated the same C++
as for the plain build (``same_code``: the option changed nothing). The last line is one
JSON object.

Usage: ``python benchmarks/bench_bulk_options.py [--only tcgain14] [--frames 6]
[--variant name=--inline-cfuncs,1000] [--hdl-dir /tmp/hdl_copy]``
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import time
from pathlib import Path

import numpy as np

from irnuc.cosim.bulk import build_bulk
from irnuc.cosim.method_bulk import check_method_bulk, run_method_bulk
from irnuc.cosim.method_drift import calibrate_methods, drift_sequence
from irnuc.nuc_fixed import load_pipeline
from irnuc.nuc_fixed.method_top import FrameInputs, method_top

METHODS = ("tcgain14", "table14", "typical14")
#: The base methods' configurations (those of bench_methods_cosim.py): method_dpc_top.
CHOICES = ("onepoint14", "typical14", "piecewise14", "quadratic14", "tcoffset14", "tcgain14",
           "table14")
#: Verilator options tried by default (name -> options): passes off, or more inlining.
VARIANTS = {
    "inline-cfuncs": ("--inline-cfuncs", "1000"),
    "inline-mult-all": ("--inline-mult", "0"),
    "no-timing": ("--no-timing",),
    "no-dfg": ("-fno-dfg",),
    "dfg-synthesize-all": ("-fdfg-synthesize-all",),
    "no-table": ("-fno-table",),
    "no-gate": ("-fno-gate",),
    "no-merge-cond": ("-fno-merge-cond",),
    "no-split": ("-fno-split",),
    "no-inline-funcs": ("-fno-inline-funcs",),
}


def _code(build_dir: Path) -> str:
    """The generated model (its root class), source paths removed."""
    text = "".join(p.read_text() for p in sorted(build_dir.glob("V*___024root*.cpp"))
                   + sorted(build_dir.glob("V*___024root.h")))
    return re.sub(r'"[^"\n]*/([^/"\n]+\.sv)"', r'"\1"', text)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", action="append", default=[], choices=CHOICES,
                    help="method configuration (repeatable; default: "
                         + ", ".join(METHODS) + ")")
    ap.add_argument("--frames", type=int, default=6)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--variant", action="append", default=[], metavar="NAME=OPT[,OPT...]",
                    help="Verilator options to measure (repeatable; replaces the defaults)")
    ap.add_argument("--hdl-dir", type=Path, default=None,
                    help="a modified copy of hdl/ measured as the variant 'hdl'")
    args = ap.parse_args()
    if args.frames < 1 or args.repeat < 1:
        sys.exit("bench_bulk_options: --frames and --repeat must be at least 1")
    variants: dict[str, tuple[str, ...]] = {}
    for v in args.variant:
        name, eq, opts = v.partition("=")
        if not eq or not name or not opts:
            sys.exit(f"bench_bulk_options: --variant {v!r}: expected NAME=OPT[,OPT...]")
        variants[name] = tuple(opts.split(","))
    variants = variants or dict(VARIANTS)
    if args.hdl_dir is not None:
        if not (args.hdl_dir / "method_dpc_top.sv").is_file():
            sys.exit(f"bench_bulk_options: --hdl-dir {args.hdl_dir}: no method_dpc_top.sv")
        variants["hdl"] = ()
    names = args.only or list(METHODS)
    cfgs = [load_pipeline(n) for n in names]
    shape = (480, 640)
    seq = drift_sequence(args.frames, shape, seed=args.seed)
    cals = calibrate_methods(cfgs, shape, seed=args.seed)
    out: dict = {"frames": args.frames, "frame": list(shape), "repeat": args.repeat,
                 "baseline": "the plain bulk build (FAST_ARGS) in the same run",
                 "variants": {k: list(v) for k, v in variants.items()},
                 "hdl_dir": None if args.hdl_dir is None else str(args.hdl_dir),
                 "methods": {}}
    for cfg in cfgs:
        c = cals[cfg.name]
        rd = seq.reading if "fpa" in cfg.base.readings else None
        expected = method_top(seq.codes, c, FrameInputs(reading=rd)).y
        builds = {"plain": build_bulk(cfg, top="method_dpc_top")}
        for name, opts in variants.items():
            builds[name] = build_bulk(cfg, top="method_dpc_top", verilator_args=opts,
                                      hdl_dir=args.hdl_dir if name == "hdl" else None)
        plain_code = _code(builds["plain"].build_dir)
        rows: dict = {}
        ref: tuple[np.ndarray, int] | None = None
        for name, bld in builds.items():
            cpu, wall = [], []
            for _ in range(args.repeat):
                r = run_method_bulk(bld, c, seq.codes, rd, seed=args.seed + 1)
                cpu.append(r.cpu_seconds)
                wall.append(r.sim_seconds)
            k = check_method_bulk(r, c, seq.codes, rd, expected=expected)
            words = np.stack([r.data, r.sof, r.eol])
            ref = (words, r.cycles) if ref is None else ref
            rows[name] = {"cpu_seconds": round(min(cpu), 4),
                          "cpu_all": [round(x, 4) for x in sorted(cpu)],
                          "wall_seconds": round(min(wall), 4),
                          "pixels_per_cpu_s": round(seq.codes.size / max(min(cpu), 1e-9)),
                          "mismatches": k.mismatches + k.missing + k.extra + int(r.frame_err),
                          "identical_outputs": bool(np.array_equal(words, ref[0])
                                                    and r.cycles == ref[1]),
                          "cycles": r.cycles,
                          "same_code": _code(bld.build_dir) == plain_code}
        base = rows["plain"]["cpu_seconds"]
        for name, row in rows.items():
            row["cpu_ratio"] = round(base / max(row["cpu_seconds"], 1e-9), 3)
            print(f"{cfg.name:10s} {name:20s} {row['cpu_seconds']:7.3f} CPU-s "
                  f"{row['pixels_per_cpu_s'] / 1e6:6.2f} Mpx/CPU-s  x{row['cpu_ratio']:.3f}  "
                  f"{'same code' if row['same_code'] and name != 'plain' else ''}"
                  f"{'' if row['identical_outputs'] else '  OUTPUTS DIFFER'}"
                  f"{'' if row['mismatches'] == 0 else '  MISMATCHES'}", flush=True)
        out["methods"][cfg.name] = rows
    out["mismatches"] = sum(r["mismatches"] for m in out["methods"].values()
                            for r in m.values())
    out["passed"] = out["mismatches"] == 0 and all(
        r["identical_outputs"] for m in out["methods"].values() for r in m.values())
    out["best"] = {m: max(rows, key=lambda n: rows[n]["cpu_ratio"])
                   for m, rows in out["methods"].items()}
    out["finished"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    print(json.dumps(out))


if __name__ == "__main__":
    main()
