"""``irnuc frames``: raw ADC frames from the physics model, written to an ``.npz`` file.

Only the standard library is imported at module level (the CLI builds every sub-command's
parser at start-up); numpy and the model are imported inside :func:`run_frames`.
"""

from __future__ import annotations

import argparse
import tomllib
from typing import Any


def parse_assignments(items: list[str] | None, what: str) -> dict[str, Any]:
    """``["a.b=1", "c=[1, 2]"]`` -> ``{"a.b": 1, "c": [1, 2]}`` (values parsed as TOML)."""
    out: dict[str, Any] = {}
    for item in items or []:
        key, sep, text = item.partition("=")
        if not sep or not key:
            raise ValueError(f"{what} {item!r} must look like KEY=VALUE")
        try:
            out[key.strip()] = tomllib.loads(f"v = {text}")["v"]
        except tomllib.TOMLDecodeError:
            out[key.strip()] = text  # a bare word: a string
    return out


def parse_temps(text: str) -> list[float]:
    try:
        return [float(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise ValueError(f"--temps {text!r} must be a comma-separated list of kelvin") from None


def add_frames_arguments(p: argparse.ArgumentParser) -> None:
    src = p.add_mutually_exclusive_group()
    src.add_argument("--preset", default="default", help="preset name (default: %(default)s)")
    src.add_argument("--config", metavar="FILE.toml", help="sensor configuration file")
    p.add_argument("--set", action="append", metavar="KEY=VALUE",
                   help="override a configuration field, e.g. --set fpa.active_rows=120")
    p.add_argument("--scene", default="uniform", choices=("uniform", "gradient", "disk", "map"))
    p.add_argument("--scene-param", action="append", metavar="KEY=VALUE",
                   help="scene parameter, e.g. --scene-param disk_temperature=360")
    p.add_argument("--temps", default="300", help="scene temperatures in K, comma-separated")
    p.add_argument("--repeats", type=int, default=1, help="frames per temperature")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--params", action="store_true", help="also write the per-pixel parameters")
    p.add_argument("--no-progress", action="store_true")
    p.add_argument("--out", default="out/frames.npz", help="output file (default: %(default)s)")


def run_frames(args: argparse.Namespace) -> int:
    import json

    import numpy as np

    from irnuc import model
    from irnuc.common.io import write_atomic
    from irnuc.common.progress import ProgressBar

    overrides = parse_assignments(args.set, "--set")
    cfg = (model.load_config(args.config, overrides) if args.config
           else model.load_preset(args.preset, overrides))
    temps = parse_temps(args.temps)
    scene = model.Scene(args.scene, parse_assignments(args.scene_param, "--scene-param"))
    outputs = ["codes", "params"] if args.params else ["codes"]
    n = len(temps) * max(args.repeats, 1)
    progress = None
    if not args.no_progress and n > cfg["run"]["chunk_frames"]:
        progress = ProgressBar("frames")
    fr = model.simulate(cfg, temps, scene, seed=args.seed, repeats=args.repeats,
                        outputs=outputs, progress=progress)
    arrays: dict[str, Any] = {
        "codes": fr.codes,
        "temps": fr.temps,
        "defect_kind": fr.defect_kind,
        "defect_pattern": fr.defect_pattern,
        "adc_bits": np.int64(fr.adc_bits),
        "seed": np.int64(fr.seed),
        "config_json": np.array(fr.config_json()),
        "diagnostics_json": np.array(json.dumps(fr.diagnostics)),
    }
    if args.params:
        for key, value in fr.outputs["params"].items():
            arrays[f"param_{key}"] = value
    path = write_atomic(args.out, lambda fh: np.savez_compressed(fh, **arrays))
    d = fr.diagnostics
    print(f"wrote {path}: {fr.codes.shape[0]} frame(s) of {fr.codes.shape[1]}x{fr.codes.shape[2]}"
          f" {fr.codes.dtype} codes, {int((fr.defect_kind > 0).sum())} defective pixels, "
          f"self-heating {d['temperature_rise_K']['mean']:.3g} K mean, "
          f"clipped {d['clipped_low']} low / {d['clipped_high']} high")
    return 0


COMMANDS = {
    "frames": ("Raw ADC frames from the sensor physics model", add_frames_arguments, run_frames),
}
