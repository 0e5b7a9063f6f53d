"""``irnuc calibrate`` and ``irnuc correct`` (the golden model on files)."""

from __future__ import annotations

import argparse
import dataclasses
import io
import json
from pathlib import Path
from typing import Any

from irnuc.cli._args import (
    add_out,
    add_pipeline,
    load_pipeline_arg,
    parse_assignments,
    say,
    stderr,
)
from irnuc.common.errors import UserError

CORRECTED_NAME = "corrected.npz"


def _npz_bytes(**arrays: object) -> bytes:
    import numpy as np

    buf = io.BytesIO()
    np.savez_compressed(buf, **arrays)
    return buf.getvalue()


def _check_adc(data: dict[str, Any], cfg: Any, flag: str) -> None:
    if data["adc_bits"] != cfg.adc_bits:
        raise UserError(f"{flag}: the frames have adc_bits = {data['adc_bits']} but pipeline "
                        f"{cfg.name!r} expects adc_bits = {cfg.adc_bits}")


def _pick(temps: Any, wanted: float | None, default: float, flag: str) -> Any:
    import numpy as np

    t = float(default if wanted is None else wanted)
    sel = np.isclose(temps, t, rtol=0.0, atol=1e-6)
    if not sel.any():
        raise UserError(f"{flag} {t:g} K matches no frame; temperatures in the file: "
                        f"{', '.join(f'{v:g}' for v in sorted(set(np.round(temps, 6).tolist())))} K")
    return sel


# ---- calibrate -------------------------------------------------------------------------

def _add_calibrate(p: argparse.ArgumentParser) -> None:
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--frames", metavar="FILE|DIR",
                     help="frames.npz (codes (N,H,W), temps (N,), adc_bits; a method other "
                          "than two_point groups the frames by scene_K and fpa_K and reads "
                          "fpa_reading / blind_codes), or the folder of `irnuc frames`")
    src.add_argument("--plan", metavar="FILE.toml",
                     help="calibration plan (scene x FPA temperatures x frames, "
                          "docs/methods.md), run on the sensor model")
    add_pipeline(p)
    add_out(p, "out/calibration")
    p.add_argument("--sensor", default="default", metavar="PRESET|FILE.toml",
                   help="with --plan: the sensor model, a preset (default, paper) or a sensor "
                        "TOML file (default: %(default)s)")
    p.add_argument("--seed", type=int, default=0,
                   help="with --plan: seed of every random draw (>= 0, default: %(default)s)")
    p.add_argument("--t-low", type=float, default=None, help="low temperature, K (default: lowest)")
    p.add_argument("--t-high", type=float, default=None,
                   help="high temperature, K (default: highest)")
    p.add_argument("--targets", default=None,
                   help="output levels LOW,HIGH in output codes (default: frame means)")
    p.add_argument("--coeff-rounding", default=None,
                   choices=["truncate", "half_up", "half_even"],
                   help="rounding of the coefficients to codes (default: half_even for gain and "
                        "offset, each format's own for the others)")
    p.add_argument("--max-saturated", type=float, default=0.01, metavar="FRACTION",
                   help="with --plan or a method: the largest fraction of pixels whose "
                        "coefficient may saturate (flagged bad); more is an error naming the "
                        "format to widen (default: %(default)s)")
    p.add_argument("--thresholds", default=None, metavar="FILE.toml",
                   help="detection thresholds TOML (default: nuc_fixed/detection.toml)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a detection threshold (low_response=0.4) or, with --plan, a "
                        "sensor field (dotted: fpa.active_rows=48); repeatable")


def _pipeline_file(value: str | None) -> str | None:
    """The file a ``--pipeline`` value reads, if it names one (``FILE.toml[:NAME]``)."""
    if value is None:
        return None
    file = value.partition(":")[0] if value.count(":") == 1 else value
    return file if Path(file).exists() else None


def _work_bytes(what: str) -> dict[str, float]:
    """Memory of the work after loading (nuc_fixed.calibrate's CALIBRATE_WORK_BYTES and
    CORRECT_WORK_BYTES)."""
    from irnuc.nuc_fixed import calibrate

    return {"calibrate": calibrate.CALIBRATE_WORK_BYTES,
            "correct": calibrate.CORRECT_WORK_BYTES}[what]


def _split_set(items: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """``--set`` values: dotted keys are sensor fields, plain keys detection thresholds."""
    sensor = {k: v for k, v in items.items() if "." in k}
    return sensor, {k: v for k, v in items.items() if "." not in k}


def _load_thresholds(args: argparse.Namespace, overrides: dict[str, Any]) -> Any:
    from irnuc.cli._args import flagged
    from irnuc.nuc_fixed.badpix import load_thresholds

    if args.thresholds is not None:
        if Path(args.thresholds).is_dir():
            raise UserError(f"--thresholds {args.thresholds}: is a folder, not a TOML file")
        if not Path(args.thresholds).is_file():
            raise UserError(f"--thresholds {args.thresholds}: "
                            + ("not a regular file" if Path(args.thresholds).exists()
                               else "no such file"))
    try:
        return load_thresholds(args.thresholds, overrides=overrides)
    except UserError as exc:
        if args.thresholds is None or str(exc).startswith("--set"):
            raise  # the message names --set or the shipped file
        raise flagged("--thresholds", args.thresholds, exc) from None


def _run_calibrate(args: argparse.Namespace) -> int:
    import numpy as np

    from irnuc.cli._args import flagged, parse_floats
    from irnuc.cli._files import load_frames
    from irnuc.common.io import claim_output_folder, output_folder, write_bytes_atomic
    from irnuc.nuc_fixed.badpix import reason_names
    from irnuc.nuc_fixed.calibrate import calibrate, summary_text
    from irnuc.nuc_fixed.memimage import write_memimage

    out = claim_output_folder(args.out, kind="calibrate", inputs={
        "--frames": args.frames, "--plan": args.plan, "--pipeline": _pipeline_file(args.pipeline),
        "--thresholds": args.thresholds,
        "--sensor": args.sensor if args.plan and Path(args.sensor).exists() else None})
    cfg = load_pipeline_arg(args.pipeline)
    sensor_set, th_set = _split_set(parse_assignments(args.set, "--set"))
    if sensor_set and args.plan is None:
        raise UserError(f"--set {next(iter(sensor_set))}: a sensor field is set only with "
                        "--plan (the frames are already simulated)")
    for flag, given in (("--sensor", args.sensor != "default"), ("--seed", args.seed != 0)):
        if given and args.plan is None:
            raise UserError(f"{flag}: only with --plan (the frames are already simulated)")
    if not 0.0 <= args.max_saturated <= 1.0:
        raise UserError(f"--max-saturated {args.max_saturated}: must lie in 0..1")
    th = _load_thresholds(args, th_set)
    if args.plan is not None or not cfg.plain:
        for flag in ("--t-low", "--t-high", "--targets"):
            if getattr(args, flag[2:].replace("-", "_")) is not None:
                raise UserError(f"{flag}: not with --plan or a method other than two_point "
                                "(every scene of the plan is used; the targets are the scene "
                                "means at the reference FPA temperature)")
        return _calibrate_method(args, cfg, th, sensor_set, out)
    targets = None
    if args.targets is not None:
        targets = tuple(parse_floats(args.targets, "--targets", "output codes"))
        if len(targets) != 2:
            raise UserError(f"--targets {args.targets!r}: expected two numbers LOW,HIGH")
        top = (1 << cfg.out_bits) - 1
        if not all(0 <= t <= top for t in targets):
            raise UserError(f"--targets {args.targets!r}: each level must lie in 0..{top} (the "
                            f"output codes of out_bits = {cfg.out_bits})")
        if not targets[0] < targets[1]:  # the gain is unsigned: the scene must brighten
            raise UserError(f"--targets {args.targets!r}: LOW (the output at --t-low) must be "
                            "below HIGH (the output at --t-high)")
    for flag, v in (("--t-low", args.t_low), ("--t-high", args.t_high)):
        if v is not None and not (np.isfinite(v) and v > 0):
            raise UserError(f"{flag} {v}: must be a finite temperature above 0 K")
    work = _work_bytes("calibrate")
    data = load_frames(args.frames, work_per_code=work["per_code"],
                       work_per_pixel=work["per_pixel"])
    _check_adc(data, cfg, f"--frames {args.frames}")
    temps = data["temps"]
    sel_lo = _pick(temps, args.t_low, float(np.min(temps)), "--t-low")
    sel_hi = _pick(temps, args.t_high, float(np.max(temps)), "--t-high")
    t_lo = float(np.mean(temps[sel_lo]))
    t_hi = float(np.mean(temps[sel_hi]))
    if not t_lo < t_hi:
        raise UserError(f"--t-low {t_lo:g} K must be below --t-high {t_hi:g} K (the frames "
                        "need two temperatures)")
    codes = data["codes"]
    try:
        cal = calibrate(codes[sel_lo], codes[sel_hi], cfg, thresholds=th, targets=targets,
                        rounding=args.coeff_rounding or "half_even")
    except UserError as exc:  # frames the calibration cannot use (too large, no good pixel)
        raise flagged("--frames", args.frames, exc) from None

    words = cal.words()
    rows = _badpix_rows(cal.bad, cal.reasons, reason_names)
    summary = dict(cal.summary) | {"frames_file": str(args.frames), "t_low": t_lo,
                                   "t_high": t_hi}
    text = summary_text(cal)
    with output_folder(out, kind="calibrate") as tmp:
        write_bytes_atomic(tmp / "coeffs.npz", _npz_bytes(
            gain_code=cal.gain_code, offset_code=cal.offset_code, bad=cal.bad,
            reasons=cal.reasons, gain=cal.gain, offset=cal.offset, words=words,
            config=np.str_(cfg.name)))
        write_bytes_atomic(tmp / "badpix.csv", ("\n".join(rows) + "\n").encode())
        write_bytes_atomic(tmp / "summary.json", (json.dumps(summary, indent=2) + "\n").encode())
        write_bytes_atomic(tmp / "summary.txt", text.encode())
        # Last: the manifest names and hashes every file above.
        write_memimage(tmp, words, cfg, extra_files=("coeffs.npz", "badpix.csv",
                                                     "summary.json", "summary.txt"),
                       fpa_sensor=data["fpa_sensor"], housing_sensor=data["housing_sensor"])
    say(text.rstrip("\n"))
    say(f"wrote {out}/: coeffs.npz, badpix.csv, coeffs.hex, coeffs.bin, manifest.json, "
        "summary.json, summary.txt")
    return 0


def _badpix_rows(bad: Any, reasons: Any, names: Any) -> list[str]:
    import numpy as np

    rows = ["row,col,reason_code,reasons"]
    for r, c in np.argwhere(bad).tolist():
        code = int(reasons[r, c])
        rows.append(f"{r},{c},{code},{'|'.join(names(code))}")
    return rows


def _calibrate_method(args: argparse.Namespace, cfg: Any, th: Any, sensor_set: dict[str, Any],
                      out: Path) -> int:
    """``irnuc calibrate --plan`` (or frames of several points) for any method."""
    import numpy as np

    from irnuc.cli._args import flagged, load_sensor_arg
    from irnuc.cli._files import load_frames
    from irnuc.common.io import output_folder, write_bytes_atomic
    from irnuc.nuc_fixed.badpix import reason_names
    from irnuc.nuc_fixed.fit import calibrate_points, summary_text
    from irnuc.nuc_fixed.memimage import write_method_image
    from irnuc.nuc_fixed.plan import load_plan, points_from_frames, run_plan

    if args.plan is not None:
        if args.seed < 0 or args.seed > 2**63 - 1:
            raise UserError(f"--seed {args.seed} is outside the allowed range 0..2^63-1")
        plan = load_plan(args.plan)
        for k in ("environment.T_substrate", "environment.T_cam"):
            if k in sensor_set:
                raise UserError(f"--set {k}: the plan sets it at every point (plan.fpa, "
                                "plan.cam, plan.housing_offset)")
        scfg = load_sensor_arg(args.sensor, sensor_set)
        if int(scfg["adc"]["bits"]) != cfg.adc_bits:
            raise UserError(f"--sensor {args.sensor}: a {scfg['adc']['bits']}-bit ADC but "
                            f"pipeline {cfg.name!r} has adc_bits = {cfg.adc_bits} (use --set "
                            f"adc.bits={cfg.adc_bits} or another pipeline)")
        from irnuc.model.pipeline import check_simulation_memory
        from irnuc.nuc_fixed.fit import check_readings

        # What the plan's FPA sensor reads at its points (without noise): a sensor the
        # method cannot use is refused before the simulation.
        quiet = dataclasses.replace(plan.fpa_sensor, noise_K=0.0)
        check_readings(cfg, quiet.read(np.asarray(plan.fpa)).tolist(), plan.reference_index,
                       f"--plan {args.plan}", "its fpa_sensor")
        cfg.base.check_plan(cfg, plan, f"--plan {args.plan}")
        n_pts = len(plan.points())
        n = n_pts * len(plan.scene) * plan.frames
        where = (f"{len(plan.fpa)} FPA x {len(plan.housing_offset)} housing offsets"
                 if plan.housing_offset else f"{n_pts} FPA")
        check_simulation_memory(scfg, n, ["codes"], what=(
            f"--plan {args.plan}: {where} x {len(plan.scene)} scene temperatures x "
            f"{plan.frames} frames = {n} frame(s)"))
        say(f"simulating {n} frame(s): {where} x {len(plan.scene)} scene temperatures x "
            f"{plan.frames} frames", 2)
        points = run_plan(plan, scfg, seed=args.seed)
        source = {"plan": str(args.plan), "sensor": args.sensor, "seed": args.seed,
                  "set": sensor_set}
        fpa_sensor, housing_sensor = plan.fpa_sensor, plan.housing_sensor
    else:
        work = _work_bytes("calibrate")
        data = load_frames(args.frames, work_per_code=work["per_code"],
                           work_per_pixel=work["per_pixel"])
        _check_adc(data, cfg, f"--frames {args.frames}")
        _check_fields(data, cfg, f"--frames {args.frames}")
        points = points_from_frames(data, f"--frames {args.frames}")
        source = {"frames_file": str(args.frames)}
        fpa_sensor, housing_sensor = data["fpa_sensor"], data["housing_sensor"]
    try:
        cal = calibrate_points(points, cfg, thresholds=th, rounding=args.coeff_rounding,
                               max_saturated=args.max_saturated)
    except UserError as exc:
        flag, value = ("--plan", args.plan) if args.plan else ("--frames", args.frames)
        msg = str(exc)
        if msg.startswith(("pipeline ", "--")):
            raise UserError(msg if msg.startswith("--") else f"--pipeline {args.pipeline}: {msg}") from None
        raise flagged(flag, value, exc) from None
    c = cal.coeffs
    arrays: dict[str, Any] = {f"{m}.{f}": v for m, fs in c.fields.items() for f, v in fs.items()}
    arrays |= {f"float.{k}": np.asarray(v) for k, v in cal.floats.items()}
    arrays |= {"bad": cal.bad, "reasons": cal.reasons, "targets": cal.targets,
               "config": np.str_(cfg.name), "method": np.str_(cfg.method)}
    rows = _badpix_rows(cal.bad, cal.reasons, reason_names)
    summary = dict(cal.summary) | source
    text = summary_text(cal)
    with output_folder(out, kind="calibrate") as tmp:
        write_bytes_atomic(tmp / "coeffs.npz", _npz_bytes(**arrays))
        write_bytes_atomic(tmp / "badpix.csv", ("\n".join(rows) + "\n").encode())
        write_bytes_atomic(tmp / "summary.json", (json.dumps(summary, indent=2) + "\n").encode())
        write_bytes_atomic(tmp / "summary.txt", text.encode())
        # Images a DMA streams into irnuc_axis_top beyond the memories (table_interp: tables
        # j and j + 1 in one word, TABLE_SEL.j picks one; docs/integration.md).
        pairs = _dma_images(tmp, c)
        manifest = write_method_image(tmp, c, extra_files=("coeffs.npz", "badpix.csv",
                                                           "summary.json", "summary.txt",
                                                           *pairs), fpa_sensor=fpa_sensor,
                                       housing_sensor=housing_sensor)
    say(text.rstrip("\n"))
    images = [n for n in manifest["files"] if n.endswith((".hex", ".bin"))]  # type: ignore[union-attr]
    say(f"wrote {out}/: coeffs.npz, badpix.csv, {', '.join(images)}, manifest.json, "
        "summary.json, summary.txt")
    return 0


def _dma_images(directory: Path, coeffs: Any) -> tuple[str, ...]:
    """Write the method's DMA images (``MethodSpec.dma_images``: table_interp's
    ``table_pair{j}.bin``)."""
    from irnuc.common.io import write_bytes_atomic

    images = coeffs.cfg.base.dma_images(coeffs)
    for name, data in images.items():
        write_bytes_atomic(directory / name, data)
    return tuple(images)


# ---- correct ---------------------------------------------------------------------------

def _add_correct(p: argparse.ArgumentParser) -> None:
    p.add_argument("--frames", required=True, metavar="FILE|DIR",
                   help="frames.npz (codes (N,H,W), temps (N,), adc_bits, and the per-frame "
                        "fields the method needs: fpa_reading, blind_codes, shutter), or its "
                        "folder")
    p.add_argument("--coeffs", required=True, metavar="DIR",
                   help="folder written by irnuc calibrate")
    p.add_argument("--pipeline", default=None, metavar="NAME|FILE.toml",
                   help="check that the coefficients were made for this pipeline "
                        "(default: the one their manifest names)")
    add_out(p, "out/corrected")
    p.add_argument("--source", default="bin", choices=["bin", "hex"],
                   help="memory image file to read the coefficient words from (both are "
                        "checked against the manifest)")
    p.add_argument("--ffc-target", type=float, default=None, metavar="CODES",
                   help="ffc: the level the shutter image is flattened to, output codes "
                        "(default: the shutter image's own mean level)")


#: Per-frame fields of a frames file a method reads (model.fpa_sensor.FRAME_FIELDS and the
#: model's blind pixel codes), by the name method_top.needs gives.
_FRAME_FIELD_KEYS = {"fpa_reading": "fpa_reading", "blind_codes": "blind_codes",
                     "shutter": "shutter", "housing_reading": "housing_reading"}


def _check_fields(data: dict[str, Any], cfg: Any, where: str) -> None:
    """One line when the frames lack a per-frame field the method reads.

    A frame file of an older irnuc has its fields made up from its configuration
    (``fields_synthesized``): its FPA reading is not a measurement, so a method that reads
    it refuses the file; one without reference pixels has no blind codes.
    """
    from irnuc.nuc_fixed.method_top import needs

    for name in needs(cfg):
        key = _FRAME_FIELD_KEYS[name]
        absent = key not in data
        if name == "fpa_reading" and data.get("fields_synthesized", False):
            absent = True
        if name == "housing_reading" and data.get("housing_synthesized", False):
            absent = True
        if name == "blind_codes" and not absent and data[key].shape[-1] == 0:
            absent = True
        if absent:
            raise UserError(f"{where}: method {cfg.method!r} needs the per-frame field {key}; "
                            "the file lacks it (make the frames with irnuc frames or a drift "
                            "sequence of this version)")


def _run_correct(args: argparse.Namespace) -> int:
    import numpy as np

    from irnuc.cli._args import flagged
    from irnuc.cli._files import load_frames
    from irnuc.common.io import claim_output_folder, output_folder, write_bytes_atomic
    from irnuc.nuc_fixed.memimage import check_sensor, read_calibration
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top, needs

    out = claim_output_folder(args.out, kind="correct", inputs={
        "--frames": args.frames, "--coeffs": args.coeffs,
        "--pipeline": _pipeline_file(args.pipeline)})
    coeffs = Path(args.coeffs)
    if not coeffs.is_dir():
        raise UserError(f"--coeffs {args.coeffs}: not a folder (give the --out folder of "
                        "irnuc calibrate)")
    if not (coeffs / "manifest.json").is_file():
        raise UserError(f"--coeffs {args.coeffs}: no manifest.json (run irnuc calibrate)")
    want = load_pipeline_arg(args.pipeline) if args.pipeline else None
    try:
        mc, manifest = read_calibration(coeffs, want, source=args.source)
    except UserError as exc:
        raise flagged("--coeffs", args.coeffs, exc) from None
    cfg = mc.cfg
    if args.ffc_target is not None:
        if not cfg.has("ffc"):
            raise UserError(f"--ffc-target: method {cfg.method!r} has no ffc stage")
        top = (1 << cfg.out_bits) - 1
        if not 0.0 <= args.ffc_target <= top:
            raise UserError(f"--ffc-target {args.ffc_target:g}: must lie in 0..{top} output codes")
    work = _work_bytes("correct")
    data = load_frames(args.frames, work_per_code=work["per_code"],
                       work_per_pixel=work["per_pixel"])
    _check_adc(data, cfg, f"--frames {args.frames}")
    codes = data["codes"]
    if codes.shape[1:] != mc.shape:
        raise UserError(f"--frames {args.frames}: frames are {codes.shape[1]} x {codes.shape[2]}"
                        f" (H x W) but the coefficients in {args.coeffs} are "
                        f"{mc.shape[0]} x {mc.shape[1]}")
    _check_fields(data, cfg, f"--frames {args.frames}")
    for kind in ("fpa", "housing"):
        check_sensor(manifest.get(f"{kind}_sensor"), data[f"{kind}_sensor"], cfg,
                     f"--frames {args.frames}", f"--coeffs {args.coeffs}", kind=kind)
    fields = {name: np.asarray(data[_FRAME_FIELD_KEYS[name]]) for name in needs(cfg)}
    # the housing reading goes to the golden model the way the FPA's does (tc_housing reads
    # it: _check_fields refused a file without one); a file of format 2 has none of its own
    # (housing_synthesized)
    housing = (None if data.get("housing_synthesized") or "housing_reading" not in data
               else np.asarray(data["housing_reading"]))
    inputs = dataclasses.replace(FrameInputs.from_fields(cfg, fields), housing_reading=housing)
    target = None
    if args.ffc_target is not None:
        target = int(np.floor(args.ffc_target * 2 ** cfg.format("ffc").frac_bits + 0.5))
    try:
        res = method_top(codes, mc, inputs, ffc_target=target)
    except UserError as exc:
        raise flagged("--frames", args.frames, exc) from None
    corrected = res.y
    extra: dict[str, Any] = {"defect_kind": data["defect_kind"]} if "defect_kind" in data else {}
    if res.delta is not None:
        extra["drift_delta"] = res.delta
    if cfg.has("ffc"):
        extra |= {"ffc_refreshes": np.asarray(res.refreshes, dtype=np.int64),
                  "ffc_kept": np.asarray(res.kept, dtype=np.int64),
                  "held": res.held, "ffc_offset": res.ffc_offset}
        if res.kept:
            stderr(f"irnuc correct: warning: {len(res.kept)} FFC refresh(es) kept the previous "
                   f"offsets (after frame(s) {', '.join(map(str, res.kept[:5]))}"
                   f"{', ...' if len(res.kept) > 5 else ''}): every pixel of their mean frame "
                   "is bad, so there is no target (ffc_kept in the output)")
    with output_folder(out, kind="correct") as tmp:
        write_bytes_atomic(tmp / CORRECTED_NAME, _npz_bytes(
            corrected=corrected, temps=data["temps"], out_bits=np.int64(cfg.out_bits),
            config=np.str_(cfg.name), method=np.str_(cfg.method), **extra))
    say(f"wrote {out / CORRECTED_NAME}: corrected {corrected.shape} {corrected.dtype} "
        f"(pipeline {cfg.name}, method {cfg.method})")
    return 0


COMMANDS = {
    "calibrate": ("NUC coefficients of any method, bad-pixel map and memory images from "
                  "frames or a calibration plan over scene and FPA temperature",
                  _add_calibrate, _run_calibrate),
    "correct": ("apply calibrated coefficients (NUC + DPC golden model) to frames",
                _add_correct, _run_correct),
}
