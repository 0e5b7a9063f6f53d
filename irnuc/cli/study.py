"""``irnuc study NAME``: one correction-method study, its figure and its JSON.

The studies live in ``reports/studies`` (``docs/methods.md``, "Studies"); each is a
``run(quick, sensor) -> dict`` and a ``figure(result) -> PNG bytes``. Only the standard
library is imported here at module level.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from irnuc.cli._args import add_out, parse_assignments, progress, say

#: Study name -> (module under irnuc.reports.studies, one line).
STUDIES: dict[str, tuple[str, str]] = {
    "camera_temperature": ("camera_temperature", "housing temperature rising, falling and "
                           "constant: two_point with and without blind_drift, per frame"),
    "ffc_interval": ("ffc_interval", "residual against time since the last FFC under FPA "
                     "ramps of 0.5 and 2 K/min; the longest FFC period below the NETD; "
                     "the shutter's cost of FFC trigger policies (period, temperature "
                     "change) on the warm-up and ambient-ramp scenarios"),
    "methods_range": ("methods_range", "every method over FPA 288-308 K and scenes 280-380 K "
                      "against coefficient memory and bandwidth"),
    "method_bits": ("method_bits", "residual against fraction bits 3..16 for every method "
                    "(the paper's Table 2)"),
    "housing": ("housing", "residual and level error against the housing-FPA difference "
                "(-5..+5 K) for every temperature method, calibrated at housing = FPA and "
                "over FPA x housing; the blind pixels' coupling to the housing"),
}


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("name", metavar="NAME", help="the study: " + "; ".join(
        f"{k} ({v[1]})" for k, v in STUDIES.items()))
    p.add_argument("--quick", action="store_true",
                   help="a smaller array and fewer points (seconds)")
    p.add_argument("--sensor", default="default", metavar="PRESET|FILE.toml",
                   help="sensor model: a preset or a sensor TOML file (default: %(default)s)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a sensor field, e.g. --set fpa.active_rows=48 (repeatable; "
                        "the study sets the FPA and housing temperatures itself)")
    p.add_argument("--seed", type=int, default=3, help="seed of every draw (default: %(default)s)")
    add_out(p, "out/study")


def _study_module(name: str) -> Any:
    """The module of study ``name`` (imported here, not by string, so that the layer
    contract sees the command line's use of the reports)."""
    from irnuc.reports.studies import (
        camera_temperature,
        ffc_interval,
        housing,
        method_bits,
        methods_range,
    )

    modules = {m.__name__.rsplit(".", 1)[-1]: m
               for m in (camera_temperature, ffc_interval, housing, method_bits, methods_range)}
    return modules[STUDIES[name][0]]


def run(args: argparse.Namespace) -> int:
    from irnuc.cli._args import load_sensor_arg
    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_bytes_atomic
    from irnuc.common.schema import nearest

    if args.name not in STUDIES:
        raise UserError(f"study {args.name!r} is not one of {', '.join(STUDIES)}"
                        f"{nearest(args.name, list(STUDIES))}")
    out = claim_output_folder(args.out, kind="study", inputs={
        "--sensor": args.sensor if Path(args.sensor).exists() else None})
    if args.seed < 0 or args.seed > 2**63 - 1:
        raise UserError(f"--seed {args.seed} is outside the allowed range 0..2^63-1")
    ov = parse_assignments(args.set, "--set")
    for k in ("environment.T_substrate", "environment.T_cam"):
        if k in ov:
            raise UserError(f"--set {k}: the study sets it")
    cfg = load_sensor_arg(args.sensor, ov)  # every field checked before any work
    if int(cfg["adc"]["bits"]) != 14:
        raise UserError(f"--sensor {args.sensor}: the studies compare the 14-bit method "
                        f"configurations; the sensor has a {cfg['adc']['bits']}-bit ADC")
    from irnuc.reports.studies.drift_common import StudySensor

    quick_size = {"rows": 24, "cols": 32} if args.quick else {"rows": 48, "cols": 64}
    size = {"rows": int(ov.pop("fpa.active_rows", quick_size["rows"])),
            "cols": int(ov.pop("fpa.active_cols", quick_size["cols"]))}
    sensor = StudySensor(preset=args.sensor if args.sensor in ("default", "paper")
                         else cfg, seed=args.seed, overrides=ov, **size)
    module = _study_module(args.name)
    result: dict[str, Any] = module.run(quick=args.quick, sensor=sensor,
                                        progress=progress(args.name))
    fig = module.figure(result)
    # a study with a text table (``table(result) -> str``) writes it beside the JSON
    text = module.table(result) if hasattr(module, "table") else None
    with output_folder(out, kind="study") as tmp:
        write_bytes_atomic(tmp / f"{args.name}.json",
                           (json.dumps(result, indent=1) + "\n").encode())
        write_bytes_atomic(tmp / f"{args.name}.png", fig)
        if text is not None:
            write_bytes_atomic(tmp / f"{args.name}.txt", text.encode())
    files = [f"{args.name}.json", f"{args.name}.png"] + ([f"{args.name}.txt"] if text else [])
    say(f"{args.name}: {result['title']} ({result['seconds']:.1f} s); wrote "
        + ", ".join(str(out / f) for f in files))
    return 0


COMMANDS = {
    "study": ("Correction-method studies: camera temperature, FFC interval, methods over an "
              "FPA range, fraction bits per method, the housing away from the FPA", add_arguments, run),
}
