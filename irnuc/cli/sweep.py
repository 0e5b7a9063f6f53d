"""``irnuc sweep``: the coefficient bit-width sweep (standard library only at import time)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from irnuc.cli._args import (
    add_executor,
    add_out,
    add_pipeline,
    add_sensor,
    load_pipeline_arg,
    load_sensor_arg,
    parse_assignments,
    parse_floats,
    progress,
    say,
)


def add_sweep_arguments(p: argparse.ArgumentParser) -> None:
    src = p.add_argument_group("sensor frames (model)")
    add_sensor(src)
    src.add_argument("--rows", type=int, default=120, help="active rows (default: %(default)s)")
    src.add_argument("--cols", type=int, default=160, help="active columns (default: %(default)s)")
    src.add_argument("--seed", type=int, default=0)
    src.add_argument("--repeats", type=int, default=4, help="frames per calibration temperature")
    src.add_argument("--t-low", type=float, default=300.0, help="low calibration temperature, K")
    src.add_argument("--t-high", type=float, default=400.0, help="high calibration temperature, K")
    src.add_argument("--t-eval", default="350", help="evaluation temperatures, K, comma-separated")
    ax = p.add_argument_group("swept widths (lists: 3,4,5 or LO:HI or LO:HI:STEP)")
    add_pipeline(ax, help_extra="; the base of every swept point")
    ax.add_argument("--gain-frac", default="4:14", help="gain fraction bits (default: %(default)s)")
    ax.add_argument("--offset-frac", default="0:4",
                    help="offset fraction bits, or 'same' as the gain (default: %(default)s)")
    ax.add_argument("--gain-int", default="auto", help="gain integer bits, or 'auto' (no good "
                    "coefficient saturates)")
    ax.add_argument("--offset-int", default="auto", help="offset integer bits incl. sign, or 'auto'")
    ax.add_argument("--adc-bits", default=None,
                    help="ADC bits to sweep, re-simulating the sensor at each (default: the "
                    "pipeline's adc_bits; the sensor's ADC must then match it)")
    ax.add_argument("--out-bits", default=None, help="output bits (default: the pipeline's out_bits)")
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
    add_executor(run, "run the points")
    add_out(run, "out/sweep")
    run.add_argument("--no-figures", action="store_true")


def run_sweep_command(args: argparse.Namespace) -> int:
    import csv
    import io
    import json
    import math

    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_bytes_atomic
    from irnuc.reports.studies.sweep import (
        SensorSpec,
        SweepAxes,
        check_metric,
        check_widths,
        parse_int_list,
        run_sweep,
    )

    out = claim_output_folder(args.out, kind="sweep", inputs={
        "--sensor": args.sensor if Path(args.sensor).exists() else None,
        "--pipeline": args.pipeline if Path(args.pipeline).exists() else None})
    check_metric(args.error_metric)
    if not (math.isfinite(args.max_error) and args.max_error > 0):
        raise UserError(f"--max-error {args.max_error}: must be a finite number above 0")
    words = ("truncate", "half_up", "half_even")

    def roundings(text: str | None, name: str) -> tuple:
        if text is None:
            return (None,)
        vals = tuple(v.strip() for v in text.split(",") if v.strip())
        bad = [v for v in vals if v not in words]
        if bad or not vals:
            raise UserError(f"{name} {text!r}: each value must be one of {', '.join(words)}")
        return vals

    for flag, v in (("--rows", args.rows), ("--cols", args.cols)):
        if not 1 <= v <= 16384:
            raise UserError(f"{flag} {v} is outside the allowed range 1..16384")
    load_pipeline_arg(args.pipeline)
    overrides = {"fpa.active_rows": args.rows, "fpa.active_cols": args.cols,
                 **parse_assignments(args.set, "--set")}
    load_sensor_arg(args.sensor, overrides)  # the sensor's own errors, named by --sensor
    sensor = SensorSpec(preset=args.sensor, overrides=overrides, seed=args.seed,
                        t_low=args.t_low, t_high=args.t_high,
                        t_eval=tuple(parse_floats(args.t_eval, "--t-eval", "K")),
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
    check_widths(sensor, axes, sensor_name="--sensor", pipeline_name="--pipeline")
    if not 0 <= args.workers <= 256:
        raise UserError(f"--workers {args.workers} is outside the allowed range 0..256")
    _check_sweep_memory(args, sensor, axes)
    res = run_sweep(sensor, axes, workers=args.workers, scheduler=args.scheduler,
                    progress=progress("sweep"))
    d = res.to_dict(max_error=args.max_error, metric=args.error_metric)
    from irnuc.reports.studies.hwcost import coefficient_memory

    rows, cols = res.frame_shape()
    for pt in d["points"]:  # the coefficient store of the swept frame (irnuc report adds synthesis)
        pt["memory"] = coefficient_memory(pt["bits_per_pixel"], rows, cols)
    cols = ["index", "adc_bits", "out_bits", "gain_int_bits", "gain_frac_bits", "offset_int_bits",
            "offset_frac_bits", "rounding", "coeff_rounding", "bits_per_pixel", "bits_per_frame",
            "residual_nu", "residual_nu_adc_lsb", "err_max_lsb", "err_rms_lsb", "psnr_db",
            "radial_rms_lsb", "radial_fraction", "gain_saturated_fraction",
            "offset_saturated_fraction"]
    buf = io.StringIO()
    wr = csv.writer(buf)
    wr.writerow([*cols, "xc7_bram36", "ecp5_dp16kd", "external_bytes_per_frame"])
    for pt in d["points"]:
        m = pt["memory"]
        wr.writerow([pt[c] for c in cols] + [m["xc7_bram36"], m["ecp5_dp16kd"],
                                             m["external_bytes_per_frame"]])
    files = {"sweep.json": (json.dumps(d, indent=1) + "\n").encode(),
             "sweep.csv": buf.getvalue().encode()}
    if not args.no_figures:
        from irnuc.reports.studies import figures

        front = res.pareto(args.error_metric)
        files["error_vs_bits.png"] = figures.error_vs_bits(res.points, args.error_metric,
                                                           args.max_error)
        files["pareto.png"] = figures.pareto(res.points, front, args.error_metric, d["smallest"])
    with output_folder(out, kind="sweep") as tmp:
        for name, data in files.items():
            write_bytes_atomic(tmp / name, data)
    sm = d["smallest"]
    say(f"{len(res.points)} point(s) on {res.executor} in {sum(res.seconds.values()):.1f} s; "
        f"wrote {out}/: {', '.join(files)}")
    if sm["found"]:
        best = res.points[sm["best"]]
        say(f"smallest widths with {args.error_metric} <= {args.max_error:g}: "
            f"{sm['bits_per_pixel']} bit/pixel, "
            f"gain {best['gain_format']}, offset {best['offset_format']} "
            f"({best[args.error_metric]:.4g}; {len(sm['points'])} combination(s) at that cost)")
    else:
        print(f"no swept width meets {args.error_metric} <= {args.max_error:g}", file=sys.stderr)
    return 0


def _check_sweep_memory(args: argparse.Namespace, sensor, axes) -> None:
    """Check, before any work, that the frames of the sweep and its workers fit in memory
    (estimate in the message)."""
    from irnuc.reports.studies.sweep import check_sweep_memory

    n_eval = len(sensor.t_eval)
    sets = len(dict.fromkeys(axes.out_bits)) * len(dict.fromkeys(axes.adc_bits))
    check_sweep_memory(sensor, axes, args.workers, (
        f"--rows x --cols = {args.rows} x {args.cols} with --repeats {args.repeats}, "
        f"{n_eval} --t-eval value(s), {sets} (ADC, output) width pair(s) and --workers "
        f"{args.workers}"), "use a smaller frame, fewer frames or fewer workers")


COMMANDS = {
    "sweep": ("Coefficient bit-width sweep of the two-point NUC (error, memory, Pareto front)",
              add_sweep_arguments, run_sweep_command),
}
