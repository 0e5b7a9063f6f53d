"""``irnuc calibrate`` and ``irnuc correct`` (the golden model on files)."""

from __future__ import annotations

import argparse
import io
from pathlib import Path
from typing import Any

from irnuc.cli._args import add_out, add_pipeline, load_pipeline_arg, parse_assignments, say
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
    p.add_argument("--frames", required=True, metavar="FILE|DIR",
                   help="frames.npz (codes (N,H,W), temps (N,), adc_bits), or the folder of "
                        "`irnuc frames`")
    add_pipeline(p)
    add_out(p, "out/calibration")
    p.add_argument("--t-low", type=float, default=None, help="low temperature, K (default: lowest)")
    p.add_argument("--t-high", type=float, default=None,
                   help="high temperature, K (default: highest)")
    p.add_argument("--targets", default=None,
                   help="output levels LOW,HIGH in output codes (default: frame means)")
    p.add_argument("--coeff-rounding", default="half_even",
                   choices=["truncate", "half_up", "half_even"],
                   help="rounding of the coefficients to codes (default: %(default)s)")
    p.add_argument("--thresholds", default=None, metavar="FILE.toml",
                   help="detection thresholds TOML (default: nuc_fixed/detection.toml)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override one detection threshold (repeatable)")


def _pipeline_file(value: str | None) -> str | None:
    """The file a ``--pipeline`` value reads, if it names one (``FILE.toml[:NAME]``)."""
    if value is None:
        return None
    file = value.partition(":")[0] if value.count(":") == 1 else value
    return file if Path(file).exists() else None


#: Memory of the work after loading, per ADC code and per pixel of a frame, above measured
#: peaks (docs/robustness.md): calibrate selects the two stacks and takes float64
#: statistics (per code), then some twenty float64 maps (per pixel); correct makes the
#: output codes and their compressed file.
CALIBRATE_BYTES = {"per_code": 12.0, "per_pixel": 1500.0}
CORRECT_BYTES = {"per_code": 8.0, "per_pixel": 128.0}


def _run_calibrate(args: argparse.Namespace) -> int:
    import json

    import numpy as np

    from irnuc.cli._args import flagged, parse_floats
    from irnuc.cli._files import load_frames
    from irnuc.common.io import claim_output_folder, output_folder, write_bytes_atomic
    from irnuc.nuc_fixed.badpix import load_thresholds, reason_names
    from irnuc.nuc_fixed.calibrate import calibrate, summary_text
    from irnuc.nuc_fixed.memimage import write_memimage

    out = claim_output_folder(args.out, kind="calibrate", inputs={
        "--frames": args.frames, "--pipeline": _pipeline_file(args.pipeline),
        "--thresholds": args.thresholds})
    cfg = load_pipeline_arg(args.pipeline)
    overrides = parse_assignments(args.set, "--set")
    if args.thresholds is not None:
        if Path(args.thresholds).is_dir():
            raise UserError(f"--thresholds {args.thresholds}: is a folder, not a TOML file")
        if not Path(args.thresholds).is_file():
            raise UserError(f"--thresholds {args.thresholds}: "
                            + ("not a regular file" if Path(args.thresholds).exists()
                               else "no such file"))
    try:
        th = load_thresholds(args.thresholds, overrides=overrides)
    except UserError as exc:
        if args.thresholds is None or str(exc).startswith("--set"):
            raise  # the message names --set or the shipped file
        raise flagged("--thresholds", args.thresholds, exc) from None
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
    data = load_frames(args.frames, work_per_code=CALIBRATE_BYTES["per_code"],
                       work_per_pixel=CALIBRATE_BYTES["per_pixel"])
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
                        rounding=args.coeff_rounding)
    except UserError as exc:  # frames the calibration cannot use (too large, no good pixel)
        raise flagged("--frames", args.frames, exc) from None

    words = cal.words()
    rows = ["row,col,reason_code,reasons"]
    for r, c in np.argwhere(cal.bad).tolist():
        code = int(cal.reasons[r, c])
        rows.append(f"{r},{c},{code},{'|'.join(reason_names(code))}")
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
                                                     "summary.json", "summary.txt"))
    say(text.rstrip("\n"))
    say(f"wrote {out}/: coeffs.npz, badpix.csv, coeffs.hex, coeffs.bin, manifest.json, "
        "summary.json, summary.txt")
    return 0


# ---- correct ---------------------------------------------------------------------------

def _add_correct(p: argparse.ArgumentParser) -> None:
    p.add_argument("--frames", required=True, metavar="FILE|DIR",
                   help="frames.npz (codes (N,H,W), temps (N,), adc_bits), or its folder")
    p.add_argument("--coeffs", required=True, metavar="DIR",
                   help="folder written by irnuc calibrate")
    p.add_argument("--pipeline", default=None, metavar="NAME|FILE.toml",
                   help="check that the coefficients were made for this pipeline "
                        "(default: the one their manifest names)")
    add_out(p, "out/corrected")
    p.add_argument("--source", default="bin", choices=["bin", "hex"],
                   help="memory image file to read the coefficient words from (both are "
                        "checked against the manifest)")


def _run_correct(args: argparse.Namespace) -> int:
    import numpy as np

    from irnuc.cli._args import flagged
    from irnuc.cli._files import load_frames
    from irnuc.common.io import claim_output_folder, output_folder, write_bytes_atomic
    from irnuc.nuc_fixed.memimage import read_memimage
    from irnuc.nuc_fixed.top import nuc_dpc_top

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
        words, cfg = read_memimage(coeffs, want, source=args.source)
    except UserError as exc:
        raise flagged("--coeffs", args.coeffs, exc) from None
    data = load_frames(args.frames, work_per_code=CORRECT_BYTES["per_code"],
                       work_per_pixel=CORRECT_BYTES["per_pixel"])
    _check_adc(data, cfg, f"--frames {args.frames}")
    codes = data["codes"]
    if codes.shape[1:] != words.shape:
        raise UserError(f"--frames {args.frames}: frames are {codes.shape[1]} x {codes.shape[2]}"
                        f" (H x W) but the coefficients in {args.coeffs} are "
                        f"{words.shape[0]} x {words.shape[1]}")
    corrected = nuc_dpc_top(codes, words, cfg)
    extra = {"defect_kind": data["defect_kind"]} if "defect_kind" in data else {}
    with output_folder(out, kind="correct") as tmp:
        write_bytes_atomic(tmp / CORRECTED_NAME, _npz_bytes(
            corrected=corrected, temps=data["temps"], out_bits=np.int64(cfg.out_bits),
            config=np.str_(cfg.name), **extra))
    say(f"wrote {out / CORRECTED_NAME}: corrected {corrected.shape} {corrected.dtype} "
        f"(pipeline {cfg.name})")
    return 0


COMMANDS = {
    "calibrate": ("two-point NUC coefficients, bad-pixel map and memory image from frames",
                  _add_calibrate, _run_calibrate),
    "correct": ("apply calibrated coefficients (NUC + DPC golden model) to frames",
                _add_correct, _run_correct),
}
