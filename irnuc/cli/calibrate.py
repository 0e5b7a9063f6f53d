"""``irnuc calibrate`` and ``irnuc correct`` (registered in ``reports.cli``).

Only the standard library is imported at module level; numpy and the golden model are
imported inside ``run`` so that ``irnuc --help`` stays fast.
"""

from __future__ import annotations

import argparse
import io
import json
from pathlib import Path

from irnuc.common.io import write_bytes_atomic


def _save_npz(path: Path, **arrays: object) -> None:
    import numpy as np

    buf = io.BytesIO()
    np.savez_compressed(buf, **arrays)
    write_bytes_atomic(path, buf.getvalue())


def _load_frames(path: str) -> dict[str, object]:
    import numpy as np

    from irnuc.cli import UsageError

    p = Path(path)
    if not p.is_file():
        raise FileNotFoundError(f"--frames {path}: no such file")
    with np.load(p, allow_pickle=False) as z:
        missing = [k for k in ("codes", "temps", "adc_bits") if k not in z.files]
        if missing:
            raise UsageError(f"--frames {path}: missing key(s) {missing}; found {z.files}")
        data = {k: z[k] for k in z.files}
    codes, temps = data["codes"], data["temps"]
    if codes.ndim != 3 or temps.shape != (codes.shape[0],):
        raise UsageError(f"--frames {path}: codes has shape {codes.shape} and temps "
                         f"{temps.shape}; (N, H, W) and (N,) are required")
    return data


def _check_adc(data: dict[str, object], cfg: object, path: str) -> None:
    from irnuc.cli import UsageError

    adc = int(data["adc_bits"])  # type: ignore[call-overload]
    if adc != cfg.adc_bits:  # type: ignore[attr-defined]
        raise UsageError(f"--frames {path}: adc_bits = {adc} but pipeline "
                         f"{cfg.name!r} expects adc_bits = {cfg.adc_bits}")  # type: ignore[attr-defined]


def _pick(temps: object, wanted: float | None, default: float, flag: str) -> object:
    import numpy as np

    from irnuc.cli import UsageError

    t = float(default if wanted is None else wanted)
    sel = np.isclose(temps, t, rtol=0.0, atol=1e-6)  # type: ignore[arg-type]
    if not sel.any():
        raise UsageError(f"{flag} = {t:g} K matches no frame; temperatures in the file: "
                         f"{sorted(set(np.round(temps, 6).tolist()))} K")  # type: ignore[arg-type]
    return sel


# ---- calibrate -------------------------------------------------------------------------

def _add_calibrate(p: argparse.ArgumentParser) -> None:
    p.add_argument("--frames", required=True, help="npz with codes (N,H,W), temps (N,), adc_bits")
    p.add_argument("--config", required=True, help="pipeline name in nuc_fixed/pipelines.toml")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--t-low", type=float, default=None, help="low temperature, K (default: lowest)")
    p.add_argument("--t-high", type=float, default=None,
                   help="high temperature, K (default: highest)")
    p.add_argument("--targets", default=None,
                   help="output levels LOW,HIGH in output codes (default: frame means)")
    p.add_argument("--rounding", default="half_even", choices=["truncate", "half_up", "half_even"],
                   help="rounding of the coefficients to codes")
    p.add_argument("--thresholds", default=None, help="detection TOML (default: built-in)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override one detection threshold (repeatable)")


def _run_calibrate(args: argparse.Namespace) -> int:
    import numpy as np

    from irnuc.cli import UsageError
    from irnuc.nuc_fixed.badpix import load_thresholds, reason_names
    from irnuc.nuc_fixed.calibrate import calibrate, summary_text
    from irnuc.nuc_fixed.config import load_pipeline
    from irnuc.nuc_fixed.memimage import write_memimage

    cfg = load_pipeline(args.config)
    overrides: dict[str, float] = {}
    for item in args.set:
        key, sep, value = item.partition("=")
        try:
            overrides[key.strip()] = float(value) if "." in value or "e" in value else int(value)
        except ValueError:
            raise UsageError(f"--set {item!r}: expected KEY=NUMBER") from None
        if not sep:
            raise UsageError(f"--set {item!r}: expected KEY=NUMBER")
    th = load_thresholds(args.thresholds, overrides=overrides)
    targets = None
    if args.targets is not None:
        try:
            targets = tuple(float(v) for v in args.targets.split(","))
        except ValueError:
            raise UsageError(f"--targets {args.targets!r}: expected LOW,HIGH numbers") from None
        if len(targets) != 2:
            raise UsageError(f"--targets {args.targets!r}: expected two numbers LOW,HIGH")
    data = _load_frames(args.frames)
    _check_adc(data, cfg, args.frames)
    temps = data["temps"]
    sel_lo = _pick(temps, args.t_low, float(np.min(temps)), "--t-low")
    sel_hi = _pick(temps, args.t_high, float(np.max(temps)), "--t-high")
    t_lo = float(np.mean(temps[sel_lo]))
    t_hi = float(np.mean(temps[sel_hi]))
    if not t_lo < t_hi:
        raise UsageError(f"--t-low = {t_lo:g} K must be below --t-high = {t_hi:g} K")
    codes = data["codes"]
    cal = calibrate(codes[sel_lo], codes[sel_hi], cfg, thresholds=th, targets=targets,
                    rounding=args.rounding)

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    words = cal.words()
    write_memimage(out, words, cfg)
    _save_npz(out / "coeffs.npz", gain_code=cal.gain_code, offset_code=cal.offset_code,
              bad=cal.bad, reasons=cal.reasons, gain=cal.gain, offset=cal.offset, words=words,
              config=np.str_(cfg.name))
    rows = ["row,col,reason_code,reasons"]
    for r, c in np.argwhere(cal.bad).tolist():
        code = int(cal.reasons[r, c])
        rows.append(f"{r},{c},{code},{'|'.join(reason_names(code))}")
    write_bytes_atomic(out / "badpix.csv", ("\n".join(rows) + "\n").encode())
    summary = dict(cal.summary) | {"frames_file": str(args.frames), "t_low": t_lo,
                                   "t_high": t_hi}
    write_bytes_atomic(out / "summary.json", (json.dumps(summary, indent=2) + "\n").encode())
    text = summary_text(cal)
    write_bytes_atomic(out / "summary.txt", text.encode())
    print(text, end="")
    print(f"wrote {out}/: coeffs.npz, badpix.csv, coeffs.hex, coeffs.bin, manifest.json, "
          "summary.json, summary.txt")
    return 0


# ---- correct ---------------------------------------------------------------------------

def _add_correct(p: argparse.ArgumentParser) -> None:
    p.add_argument("--frames", required=True, help="npz with codes (N,H,W), temps (N,), adc_bits")
    p.add_argument("--coeffs", required=True, help="folder written by irnuc calibrate")
    p.add_argument("--out", required=True, help="output npz")
    p.add_argument("--source", default="bin", choices=["bin", "hex"],
                   help="memory image file to read the coefficient words from")


def _run_correct(args: argparse.Namespace) -> int:
    import numpy as np

    from irnuc.nuc_fixed.memimage import read_memimage
    from irnuc.nuc_fixed.top import nuc_dpc_top

    if not (Path(args.coeffs) / "manifest.json").is_file():
        raise FileNotFoundError(f"--coeffs {args.coeffs}: no manifest.json (run irnuc calibrate)")
    words, cfg = read_memimage(args.coeffs, source=args.source)
    data = _load_frames(args.frames)
    _check_adc(data, cfg, args.frames)
    codes = data["codes"]
    if codes.shape[1:] != words.shape:
        from irnuc.cli import UsageError

        raise UsageError(f"--frames frames are {codes.shape[1:]} (H, W) but the coefficients "
                         f"in {args.coeffs} are {words.shape}")
    corrected = nuc_dpc_top(codes, words, cfg)
    extra = {"defect_kind": data["defect_kind"]} if "defect_kind" in data else {}
    _save_npz(Path(args.out), corrected=corrected, temps=data["temps"],
              out_bits=np.int64(cfg.out_bits), config=np.str_(cfg.name), **extra)
    print(f"wrote {args.out}: corrected {corrected.shape} {corrected.dtype} "
          f"(pipeline {cfg.name})")
    return 0


COMMANDS = {
    "calibrate": ("two-point NUC coefficients, bad-pixel map and memory image from frames",
                  _add_calibrate, _run_calibrate),
    "correct": ("apply calibrated coefficients (NUC + DPC golden model) to frames",
                _add_correct, _run_correct),
}
