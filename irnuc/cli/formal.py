"""``irnuc formal``: the proofs of the integration layer and their planted faults
(standard library only at import time; docs/formal.md)."""

from __future__ import annotations

import argparse

from irnuc.cli._args import add_executor, add_out, progress, say


def add_formal_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--only", action="append", default=[], metavar="ID",
                   help="run only this proof or planted fault (repeatable; see --list)")
    p.add_argument("--list", action="store_true",
                   help="list the proofs and planted faults and exit")
    p.add_argument("--quick", action="store_true",
                   help="only the proofs and faults of the test suite (seconds)")
    p.add_argument("--configs", metavar="LIST",
                   help="the configuration proofs (register file, irnuc_axis_top) of these "
                        "named configurations only (comma-separated; default: all)")
    p.add_argument("--no-faults", action="store_true",
                   help="run the proofs only, not the planted faults")
    p.epilog = ("writes formal.json (every result), junit.xml and traces/*.vcd (each "
                "counterexample) under --out. Exit status: 0 when every proof holds and "
                "every planted fault is detected, 1 otherwise, 2 for bad input, 3 when a "
                "tool failed")
    add_executor(p, "run the proofs", workers=2, cache="a proof's result")
    add_out(p, "out/formal")


def run_formal(args: argparse.Namespace) -> int:
    import json
    import shutil
    from pathlib import Path

    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.verif import formal

    if args.list:
        for p in formal.PROOFS:
            depth = ("unbounded" if p.engine == "pdr" else
                     f"covers<={p.depth}" if formal.measured_bound(p) else f"depth {p.depth}")
            say(f"{p.id:24s} {p.engine:4s} {depth:10s} {p.what}", level=0)
        for f in formal.FAULTS:
            say(f"{f.id:24s} fault of {f.proof}: {f.property} must fail ({f.what})", level=0)
        return 0
    if not 0 <= args.workers <= 256:
        raise UserError(f"--workers {args.workers} is outside the allowed range 0..256")
    configs = None
    if args.configs is not None:
        from irnuc.common.schema import nearest
        from irnuc.nuc_fixed import pipeline_names

        names = list(pipeline_names(method=None))
        configs = [w.strip() for w in args.configs.split(",")]
        for w in configs:
            if w not in names:
                raise UserError(f"--configs {w or repr(args.configs)}: no such configuration"
                                f"{nearest(w, names)} (allowed: {', '.join(names)})")
    proofs, faults = formal.select(args.only, quick=args.quick, faults=not args.no_faults,
                                   configs=configs)
    out = claim_output_folder(args.out, kind="formal")
    summary = formal.run_campaign(proofs, faults, workers=args.workers,
                                  scheduler=args.scheduler, use_cache=not args.no_cache,
                                  progress=progress("formal"))
    with output_folder(out, kind="formal") as tmp:
        (tmp / "traces").mkdir()
        for r in [*summary["proofs"], *summary["faults"]]:
            if r.get("vcd") and Path(r["vcd"]).is_file():
                dest = tmp / "traces" / f"{r['id']}.vcd"
                shutil.copyfile(r["vcd"], dest)
                r["vcd"] = f"traces/{r['id']}.vcd"
        write_text_atomic(tmp / "formal.json", json.dumps(summary, indent=1) + "\n")
        write_text_atomic(tmp / "junit.xml", formal.junit(summary))
    for r in summary["proofs"]:
        cover = r.get("cover") or {}
        say(f"{r['id']:24s} {r['status']:8s} {r['engine']:4s}"
            + (f" depth {r['depth']}" if r["depth"] else "")
            + (f", cover {cover['status']}" if cover else "") + f" ({r['seconds']:.1f} s)"
            + (f": {r['message']}" if r["message"] else ""), level=2)
    for r in summary["faults"]:
        say(f"{r['id']:24s} {'detected' if r['detected'] else 'MISSED':8s} {r['property']}"
            + (f" (step {r['step']})" if r.get("step") is not None else ""), level=2)
    say(f"{summary['proved']} proved, {summary['bounded']} bounded passes, "
        f"{len(summary['not_ok'])} not holding of {len(summary['proofs'])} proofs; "
        f"{summary['detected']} of {len(summary['faults'])} planted faults detected"
        + (f"; not holding: {', '.join(summary['not_ok'])}" if summary["not_ok"] else "")
        + (f"; missed: {', '.join(summary['missed'])}" if summary["missed"] else ""))
    say(f"wrote {out / 'formal.json'}, {out / 'junit.xml'}")
    return 0 if summary["ok"] else 1


COMMANDS = {
    "formal": ("Formal proofs of the integration layer (AXI4-Stream, video framing, "
               "AXI4-Lite, the framer, buffers, FFC control; irnuc_axis_top bounded per "
               "configuration) and the faults planted to show each property can fail; "
               "cached by content", add_formal_arguments, run_formal),
}
