"""``irnuc sweep`` and ``irnuc report`` (standard library only at import time)."""

from __future__ import annotations

import argparse
import sys


def add_sweep_arguments(p: argparse.ArgumentParser) -> None:
    src = p.add_argument_group("sensor frames (model)")
    src.add_argument("--preset", default="default", help="model preset (default: %(default)s)")
    src.add_argument("--set", action="append", metavar="KEY=VALUE",
                     help="override a model field, e.g. --set fpa.tolerance.R_ref=1e-4")
    src.add_argument("--rows", type=int, default=120, help="active rows (default: %(default)s)")
    src.add_argument("--cols", type=int, default=160, help="active columns (default: %(default)s)")
    src.add_argument("--seed", type=int, default=0)
    src.add_argument("--repeats", type=int, default=4, help="frames per calibration temperature")
    src.add_argument("--t-low", type=float, default=300.0, help="low calibration temperature, K")
    src.add_argument("--t-high", type=float, default=400.0, help="high calibration temperature, K")
    src.add_argument("--t-eval", default="350", help="evaluation temperatures, K, comma-separated")
    ax = p.add_argument_group("swept widths (lists: 3,4,5 or LO:HI or LO:HI:STEP)")
    ax.add_argument("--pipeline", default="typical14", help="base golden-model configuration")
    ax.add_argument("--gain-frac", default="4:14", help="gain fraction bits (default: %(default)s)")
    ax.add_argument("--offset-frac", default="0:4",
                    help="offset fraction bits, or 'same' as the gain (default: %(default)s)")
    ax.add_argument("--gain-int", default="auto", help="gain integer bits, or 'auto' (no good "
                    "coefficient saturates)")
    ax.add_argument("--offset-int", default="auto", help="offset integer bits incl. sign, or 'auto'")
    ax.add_argument("--adc-bits", default=None, help="ADC bits (default: the preset's)")
    ax.add_argument("--out-bits", default=None, help="output bits (default: = ADC bits)")
    ax.add_argument("--rounding", default=None,
                    help="datapath rounding(s): truncate, half_up, half_even (default: the pipeline's)")
    ax.add_argument("--coeff-rounding", default="half_even", help="coefficient quantization rounding(s)")
    sel = p.add_argument_group("selection")
    sel.add_argument("--max-error", type=float, default=1.0,
                     help="error bound for the smallest widths (default: %(default)s)")
    sel.add_argument("--error-metric", default="err_max_lsb",
                     help="err_max_lsb (default), err_rms_lsb, residual_nu, residual_nu_adc_lsb, "
                     "radial_rms_lsb")
    run = p.add_argument_group("execution and output")
    run.add_argument("--workers", type=int, default=2, help="worker processes; 0 = in-process")
    run.add_argument("--scheduler", metavar="ADDRESS",
                     help="run the points on a Dask distributed cluster (needs dask[distributed])")
    run.add_argument("--out", default="out/sweep", help="output folder (default: %(default)s)")
    run.add_argument("--no-figures", action="store_true")
    run.add_argument("--no-progress", action="store_true")


def run_sweep_command(args: argparse.Namespace) -> int:
    import csv
    import io
    import json
    from pathlib import Path

    from irnuc.cli.frames import parse_assignments, parse_temps
    from irnuc.common.io import write_atomic, write_text_atomic
    from irnuc.common.progress import ProgressBar
    from irnuc.reports.studies.sweep import SensorSpec, SweepAxes, check_metric, parse_int_list, run_sweep

    check_metric(args.error_metric)
    words = ("truncate", "half_up", "half_even")

    def roundings(text: str | None, name: str) -> tuple:
        if text is None:
            return (None,)
        vals = tuple(v.strip() for v in text.split(",") if v.strip())
        bad = [v for v in vals if v not in words]
        if bad or not vals:
            raise ValueError(f"{name} = {text!r}: each value must be one of {', '.join(words)}")
        return vals

    overrides = {"fpa.active_rows": args.rows, "fpa.active_cols": args.cols,
                 **parse_assignments(args.set, "--set")}
    sensor = SensorSpec(preset=args.preset, overrides=overrides, seed=args.seed,
                        t_low=args.t_low, t_high=args.t_high, t_eval=tuple(parse_temps(args.t_eval)),
                        repeats=args.repeats)
    axes = SweepAxes(
        gain_frac_bits=parse_int_list(args.gain_frac, "--gain-frac"),
        offset_frac_bits=parse_int_list(args.offset_frac, "--offset-frac", ("same",)),
        gain_int_bits=parse_int_list(args.gain_int, "--gain-int", ("auto",)),
        offset_int_bits=parse_int_list(args.offset_int, "--offset-int", ("auto",)),
        adc_bits=parse_int_list(args.adc_bits, "--adc-bits") if args.adc_bits else (None,),
        out_bits=parse_int_list(args.out_bits, "--out-bits") if args.out_bits else (None,),
        rounding=roundings(args.rounding, "--rounding"),
        coeff_rounding=roundings(args.coeff_rounding, "--coeff-rounding"),
        pipeline=args.pipeline)
    sensor.check()
    axes.check()
    progress = None if args.no_progress else ProgressBar("sweep")
    res = run_sweep(sensor, axes, workers=args.workers, scheduler=args.scheduler, progress=progress)
    out = Path(args.out)
    d = res.to_dict(max_error=args.max_error, metric=args.error_metric)
    write_text_atomic(out / "sweep.json", json.dumps(d, indent=1) + "\n")
    cols = ["index", "adc_bits", "out_bits", "gain_int_bits", "gain_frac_bits", "offset_int_bits",
            "offset_frac_bits", "rounding", "coeff_rounding", "bits_per_pixel", "bits_per_frame",
            "residual_nu", "residual_nu_adc_lsb", "err_max_lsb", "err_rms_lsb", "psnr_db",
            "radial_rms_lsb", "radial_fraction", "gain_saturated_fraction", "offset_saturated_fraction"]
    buf = io.StringIO()
    wr = csv.writer(buf)
    wr.writerow(cols)
    for p in res.points:
        wr.writerow([p[c] for c in cols])
    write_text_atomic(out / "sweep.csv", buf.getvalue())
    if not args.no_figures:
        from irnuc.reports.studies import figures

        front = res.pareto(args.error_metric)
        for name, data in (("error_vs_bits.png", figures.error_vs_bits(res.points, args.error_metric,
                                                                        args.max_error)),
                           ("pareto.png", figures.pareto(res.points, front, args.error_metric,
                                                         d["smallest"]))):
            write_atomic(out / name, lambda fh, data=data: fh.write(data))
    sm = d["smallest"]
    print(f"{len(res.points)} point(s) on {res.executor} in {sum(res.seconds.values()):.1f} s; "
          f"wrote {out}/sweep.json, sweep.csv"
          + ("" if args.no_figures else ", error_vs_bits.png, pareto.png"))
    if sm["found"]:
        best = res.points[sm["best"]]
        print(f"smallest widths with {args.error_metric} <= {args.max_error:g}: "
              f"{sm['bits_per_pixel']} bit/pixel, "
              f"gain U{best['gain_int_bits']}.{best['gain_frac_bits']}, offset "
              f"S{best['offset_int_bits']}.{best['offset_frac_bits']} "
              f"({best[args.error_metric]:.4g}; {len(sm['points'])} combination(s) at that cost)")
    else:
        print(f"no swept width meets {args.error_metric} <= {args.max_error:g}", file=sys.stderr)
    return 0


def add_report_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", default="out/report", help="output folder (default: %(default)s)")
    p.add_argument("--config", default="default",
                   help="embedded configuration (default, small) or a TOML file (default: %(default)s)")
    p.add_argument("--baseline", metavar="SUMMARY.json",
                   help="compare every metric with an earlier summary.json; exit 1 on a regression")
    p.add_argument("--junit", metavar="FILE.xml",
                   help="ingest co-simulation results instead of running them")
    p.add_argument("--no-cosim", action="store_true", help="skip the co-simulation phase")
    p.add_argument("--quick", action="store_true",
                   help="apply the configuration's [quick] overrides (smaller frames, fewer points)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the sweep points on a Dask distributed cluster")
    p.add_argument("--no-progress", action="store_true")


def run_report_command(args: argparse.Namespace) -> int:
    from irnuc.reports.report import run_report

    # The options as given (for the provenance), whether called from the console or from main([...]).
    args.argv = [f"--{k.replace('_', '-')}" + ("" if v is True else f" {v}")
                 for k, v in vars(args).items() if k != "command" and v not in (None, False)]
    return run_report(args)


COMMANDS = {
    "sweep": ("Coefficient bit-width sweep of the two-point NUC (error, memory, Pareto front)",
              add_sweep_arguments, run_sweep_command),
    "report": ("The hardware team's regression report: calibration, sweep, paper tables, "
               "co-simulation, numerical fidelity (HTML + summary.json)",
               add_report_arguments, run_report_command),
}
