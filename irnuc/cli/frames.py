"""``irnuc frames``: raw ADC frames from the physics model, written to ``--out/frames.npz``.

The file is an uncompressed ``.npz`` (:mod:`irnuc.common.framefile`): the codes, the
per-frame fields (:data:`model.fpa_sensor.FRAME_FIELDS`), the reference pixels' codes and
the metadata; docs/sequences.md describes every key.
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path
from typing import Any

from irnuc.cli._args import (
    add_out,
    add_sensor,
    load_sensor_arg,
    parse_assignments,
    parse_floats,
    progress,
    say,
    stderr,
)

FRAMES_NAME = "frames.npz"
#: The shipped scenarios (model/scenarios/, ``model.sequence.scenario_names``; a test
#: keeps this list equal to it without importing the model when the parser is built).
SCENARIOS = ("ambient_ramp", "fpa_ramp", "indoor_to_outdoor", "power_on_warmup")


def add_frames_arguments(p: argparse.ArgumentParser) -> None:
    add_sensor(p)
    p.add_argument("--scene", default="uniform", choices=("uniform", "gradient", "disk", "map"))
    p.add_argument("--scene-param", action="append", default=[], metavar="KEY=VALUE",
                   help="scene parameter, e.g. --scene-param disk_temperature=360")
    p.add_argument("--temps", default=None,
                   help="scene temperatures in K, comma-separated (default: 300)")
    p.add_argument("--repeats", type=int, default=None,
                   help="frames per temperature (1..100000; default: 1)")
    p.add_argument("--sequence", default=None, metavar="FILE.toml|SCENARIO",
                   help="a drift sequence (frame rate, duration, the ambient and the camera's "
                        "thermal network or FPA / housing profiles, scene, shutter, the "
                        "temperature sensors; docs/sequences.md) or a shipped scenario by name "
                        f"({', '.join(SCENARIOS)}), instead of --temps: frames in time "
                        "order, streamed to the file in chunks")
    p.add_argument("--seed", type=int, default=0, help="seed of every random draw (>= 0)")
    p.add_argument("--params", action="store_true", help="also write the per-pixel parameters")
    add_out(p, "out/frames")


def run_frames(args: argparse.Namespace) -> int:
    import numpy as np

    from irnuc import model
    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder
    from irnuc.model.fpa_sensor import FpaSensor, constant_fields
    from irnuc.model.pipeline import check_simulation_memory
    from irnuc.model.scenes import check_temps, scene_temperatures
    from irnuc.model.sequence import file_arrays

    scene_params = parse_assignments(args.scene_param, "--scene-param")
    out = claim_output_folder(args.out, kind="frames", inputs={
        "--sensor": args.sensor if Path(args.sensor).exists() else None,
        "--scene-param path": scene_params.get("path"),
        "--sequence": args.sequence if args.sequence and Path(args.sequence).exists() else None})
    if args.sequence is not None:
        for flag, value in (("--temps", args.temps), ("--repeats", args.repeats)):
            if value is not None:
                raise UserError(f"{flag} and --sequence: the sequence gives every frame's "
                                f"scene temperature; give one of them")
        return _run_sequence(args, out, scene_params)
    args.temps = "300" if args.temps is None else args.temps
    args.repeats = 1 if args.repeats is None else args.repeats
    if not 1 <= args.repeats <= 100_000:
        raise UserError(f"--repeats {args.repeats} is outside the allowed range 1..100000")
    if args.seed < 0 or args.seed > 2**63 - 1:
        raise UserError(f"--seed {args.seed} is outside the allowed range 0..2^63-1")
    cfg = load_sensor_arg(args.sensor, parse_assignments(args.set, "--set"))
    temps = parse_floats(args.temps, "--temps", "K")
    try:
        check_temps(temps)
    except model.ConfigError as exc:
        raise UserError(f"--temps {args.temps}: {exc}") from None
    scene = model.Scene(args.scene, scene_params)
    # status: which pixels' solves failed (told below, one line), not written.
    outputs = ["codes", "status", "params"] if args.params else ["codes", "status"]
    n = len(temps) * args.repeats
    f = cfg["fpa"]
    check_simulation_memory(cfg, n, outputs, what=(
        f"--temps ({len(temps)}) x --repeats ({args.repeats}) = {n} frame(s) of "
        f"fpa.active_rows x fpa.active_cols = {f['active_rows']} x {f['active_cols']} pixels"))
    # The scene's parameters and files are read now, on one frame, not after the others.
    try:
        scene_temperatures(scene, np.asarray(temps[:1]), (f["active_rows"], f["active_cols"]))
    except model.ConfigError as exc:
        raise UserError(f"--scene {args.scene} --scene-param: {exc}") from None
    bar = progress("frames") if n > cfg["run"]["chunk_frames"] else None
    with warnings.catch_warnings():  # solver failures are told below, in one line
        warnings.simplefilter("ignore", RuntimeWarning)
        fr = model.simulate(cfg, temps, scene, seed=args.seed, repeats=args.repeats,
                            outputs=outputs, progress=bar)
    status = fr.outputs.pop("status")  # every pixel of the array, blind ones too
    n_failed = int(np.count_nonzero(status))
    if n_failed:
        failed = fr.diagnostics["solver_failures"]
        kinds = ", ".join(k.replace("_", " ") for k, v in failed.items() if v)
        if n_failed == status.size:  # frames of rail codes only: no result
            given = f"--sensor {args.sensor}" + "".join(f" --set {s}" for s in args.set)
            raise UserError(f"{given}: every pixel's solve failed ({n_failed} of {status.size}: "
                            f"{kinds}); no frame holds a measurement (check "
                            "bolometer.bias_current, .g, .tcr)")
        stderr(f"irnuc frames: warning: {n_failed} of {status.size} pixel solves failed "
               f"({kinds}); those pixels read the high rail")
    env = cfg["environment"]
    rate = float(cfg["readout"]["frame_rate"])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        fields = constant_fields(fr.temps, env["T_substrate"], env["T_cam"], seed=args.seed,
                                 frame_rate=rate)
    for w in caught:
        stderr(f"irnuc frames: warning: {w.message}")
    arrays = file_arrays(fr, fields, FpaSensor(), rate)
    if args.params:
        for key, value in fr.outputs["params"].items():
            arrays[f"param_{key}"] = value
    with output_folder(out, kind="frames") as tmp:
        write_frame_file(tmp / FRAMES_NAME, fr.codes, arrays)
    d = fr.diagnostics
    say(f"wrote {out / FRAMES_NAME}: {fr.codes.shape[0]} frame(s) of {fr.codes.shape[1]}x"
        f"{fr.codes.shape[2]} {fr.codes.dtype} codes, {int((fr.defect_kind > 0).sum())} "
        f"defective pixels, self-heating {d['temperature_rise_K']['mean']:.3g} K mean, "
        f"clipped {d['clipped_low']} low / {d['clipped_high']} high")
    return 0


def _run_sequence(args: argparse.Namespace, out: Path, scene_params: dict[str, Any]) -> int:
    """``irnuc frames --sequence FILE.toml``: the frames streamed to the file chunk by chunk."""
    import shutil

    import numpy as np

    from irnuc import model
    from irnuc.common.errors import UserError
    from irnuc.common.io import output_folder
    from irnuc.common.memory import format_bytes
    from irnuc.model.pipeline import check_simulation_memory
    from irnuc.model.scenes import scene_temperatures
    from irnuc.model.sequence import load_sequence, prepare, sequence_file_bytes, write_sequence

    if args.seed < 0 or args.seed > 2**63 - 1:
        raise UserError(f"--seed {args.seed} is outside the allowed range 0..2^63-1")
    cfg = load_sensor_arg(args.sensor, parse_assignments(args.set, "--set"))
    seq = load_sequence(args.sequence, "--sequence")
    scene = model.Scene(args.scene, scene_params)
    f = cfg["fpa"]
    try:
        scene_temperatures(scene, np.asarray([300.0]), (f["active_rows"], f["active_cols"]))
    except model.ConfigError as exc:
        raise UserError(f"--scene {args.scene} --scene-param: {exc}") from None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        run = prepare(cfg, seq, scene, seed=args.seed)
    for w in caught:  # the temperature sensors' clamped readings
        stderr(f"irnuc frames: warning: {w.message}")
    outputs = ["codes", "params"] if args.params else ["codes"]
    check_simulation_memory(cfg, run.chunk_frames, outputs, what=(
        f"--sequence: chunks of {run.chunk_frames} frame(s) of fpa.active_rows x "
        f"fpa.active_cols = {f['active_rows']} x {f['active_cols']} pixels"))
    need = sequence_file_bytes(cfg, seq)
    parent = out.resolve().parent
    parent.mkdir(parents=True, exist_ok=True)
    free = shutil.disk_usage(parent).free
    if need > free:
        raise UserError(f"--out {out}: the {seq.n_frames} frames need {format_bytes(need)} on "
                        f"disk, {format_bytes(free)} are free there")
    kept = f" (one in {seq.record_every} kept)" if seq.record_every > 1 else ""
    say(f"{seq.n_frames} frames at {seq.frame_rate:g} Hz{kept}; thermal model {run.thermal}: "
        f"{run.thermal_reason}")
    extra: dict[str, Any] = {}
    if args.params:
        params = run.pipe.run(run.schedule.scene_K[:0], ["params"])["params"]
        extra = {f"param_{k}": v for k, v in params.items()}
    bar = progress("frames") if seq.n_frames > run.chunk_frames else None
    with output_folder(out, kind="frames") as tmp:
        fr = write_sequence(run, tmp / FRAMES_NAME, progress=bar, extra=extra)
    d = fr.diagnostics
    n_failed = sum(d["solver_failures"].values())
    if n_failed:
        kinds = ", ".join(k.replace("_", " ") for k, v in d["solver_failures"].items() if v)
        stderr(f"irnuc frames: warning: {n_failed} pixel solve(s) failed over the sequence "
               f"({kinds}); those pixels read the high rail")
    closed = int(run.fields["shutter"].sum())
    say(f"wrote {out / FRAMES_NAME}: {seq.n_frames} frame(s) of {f['active_rows']}x"
        f"{f['active_cols']} codes ({format_bytes(need)}), {closed} with the shutter closed, "
        f"FPA {run.schedule.fpa_K.min():.4g}..{run.schedule.fpa_K.max():.4g} K, housing "
        f"{run.schedule.T_cam_K.min():.4g}..{run.schedule.T_cam_K.max():.4g} K, "
        f"{fr.blind_codes.shape[1]} reference pixels, clipped {d['clipped_low']} low / "
        f"{d['clipped_high']} high")
    return 0


def write_frame_file(path: Path, codes: Any, arrays: dict[str, Any]) -> None:
    """Write a frame file at ``path`` (inside the output's temporary folder): the codes in
    chunks (an array, or an iterable of (n, H, W) chunks with ``arrays`` then complete)."""
    import numpy as np

    from irnuc.common.framefile import FrameWriter

    n, h, w = codes.shape
    with FrameWriter(path, n, (h, w), codes.dtype) as fw:
        for start in range(0, n, 64):
            fw.write(np.asarray(codes[start:start + 64]))
        fw.close(arrays)


COMMANDS = {
    "frames": ("Raw ADC frames from the sensor physics model", add_frames_arguments, run_frames),
}
