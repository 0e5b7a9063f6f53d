"""``irnuc traffic``: random AXI4-Lite register traffic through irnuc_axis_top on every
configuration (standard library only at import time; docs/verification.md)."""

from __future__ import annotations

import argparse

from irnuc.cli._args import add_out, progress, say


def add_traffic_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--configs", metavar="LIST",
                   help="named configurations (comma-separated; default: every one)")
    p.add_argument("--no-coverage", action="store_true",
                   help="no coverage (coverage.json holds the traffic's bins otherwise)")
    p.epilog = ("writes junit.xml and coverage.json under --out. Exit status: 0 when every "
                "run passed, 1 otherwise, 2 for bad input, 3 when a tool failed")
    add_out(p, "out/traffic")


def run_traffic(args: argparse.Namespace) -> int:
    import json

    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.verif import traffic

    configs = traffic.configurations(args.configs)  # a bad name is one line, before work
    out = claim_output_folder(args.out, kind="traffic")
    with output_folder(out, kind="traffic") as tmp:
        res = traffic.run_traffic(configs, tmp / "runs", coverage=not args.no_coverage,
                                  progress=progress("traffic"))
        res.write_junit(tmp / "junit.xml")
        if res.coverage is not None:
            write_text_atomic(tmp / "coverage.json", json.dumps(res.coverage, indent=1) + "\n")
        for o in res.outcomes:
            say(f"{o.case.cfg.name:12s} {o.test:24s} {o.status:8s} {o.seconds:6.1f} s"
                + (f": {o.message[:200]}" if o.status != "passed" else ""), level=2)
    bad = [o for o in res.outcomes if o.status != "passed"]
    say(f"{len(res.outcomes) - len(bad)} of {len(res.outcomes)} configurations passed"
        + (f"; not passed: {', '.join(o.case.cfg.name for o in bad)}" if bad else ""))
    say(f"wrote {out}")
    return 1 if bad or not res.outcomes else 0


COMMANDS = {
    "traffic": ("Random AXI4-Lite register traffic through irnuc_axis_top on every named "
                "configuration (random strobes, held readies, accesses while pixels stream, "
                "W1C clears racing events, read-only and unmapped offsets), each read "
                "predicted by the register model", add_traffic_arguments, run_traffic),
}
