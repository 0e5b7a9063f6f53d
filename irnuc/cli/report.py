"""``irnuc report``: the hardware team's regression report (standard library only at import)."""

from __future__ import annotations

import argparse

from irnuc.cli._args import add_out


def add_report_arguments(p: argparse.ArgumentParser) -> None:
    add_out(p, "out/report")
    p.add_argument("--config", default="default", metavar="NAME|FILE.toml",
                   help="embedded configuration (default, small) or a TOML file (default: %(default)s)")
    p.add_argument("--baseline", metavar="FILE.json",
                   help="compare every metric with an earlier summary.json; exit 1 on a regression")
    p.add_argument("--junit", metavar="FILE.xml",
                   help="ingest co-simulation results instead of running them")
    p.add_argument("--no-cosim", action="store_true", help="skip the co-simulation phase")
    p.add_argument("--quick", action="store_true",
                   help="apply the configuration's [quick] overrides (smaller frames, fewer points)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the sweep points on a Dask distributed cluster")


def run_report_command(args: argparse.Namespace) -> int:
    from irnuc.cli._args import verbosity
    from irnuc.reports.report import run_report

    args.no_progress = verbosity() < 1
    # The options as given (for the provenance), whether called from the console or from main([...]).
    args.argv = [f"--{k.replace('_', '-')}" + ("" if v is True else f" {v}")
                 for k, v in vars(args).items()
                 if k not in ("command", "no_progress", "verbosity") and v not in (None, False)]
    return run_report(args)


COMMANDS = {
    "report": ("The hardware team's regression report: calibration, sweep, paper tables, "
               "co-simulation, numerical fidelity (HTML + summary.json)",
               add_report_arguments, run_report_command),
}
