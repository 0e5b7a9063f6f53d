"""``irnuc noise --frames DIR``: temporal NETD, responsivity and 3D noise of frames.

Writes ``noise.json`` (every figure with its uncertainty) and ``noise.png`` under ``--out``;
prints a summary. The physics is in :mod:`irnuc.model.noise_metrics`; docs/model.md
("Noise metrics") says what each number is.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from irnuc.cli._args import add_out, progress, say

JSON_NAME = "noise.json"
FIGURE_NAME = "noise.png"
#: Memory of the work per pixel of a frame besides the frames (fit normal equations, 3D
#: noise sums and residual chunks), bytes; generous.
NOISE_BYTES_PER_PIXEL = 2000.0


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--frames", required=True, metavar="FILE|DIR",
                   help="a frame file (frames.npz) or the folder of `irnuc frames`")
    p.add_argument("--range", default=None, metavar="START:STOP",
                   help="use frames START..STOP-1 only (Python slice bounds; default: all)")
    p.add_argument("--include-shutter", action="store_true",
                   help="keep the frames whose shutter is closed (left out by default)")
    p.add_argument("--settle", type=int, default=None, metavar="N",
                   help="frames left out after each shutter closing while the pixels forget "
                        "it (default: 7 thermal time constants of the file's sensor, or 3)")
    p.add_argument("--seed", type=int, default=None,
                   help="seed of the closed-form model (default: the file's)")
    add_out(p, "out/noise")


def _frame_range(text: str | None, n: int) -> range:
    from irnuc.common.errors import UserError

    if text is None:
        return range(n)
    parts = text.split(":")
    try:
        if len(parts) != 2:
            raise ValueError
        start = int(parts[0]) if parts[0] else 0
        stop = int(parts[1]) if parts[1] else n
    except ValueError:
        raise UserError(f"--range {text!r}: expected START:STOP (integers, either may be "
                        "empty)") from None
    r = range(n)[start:stop]
    if len(r) < 3:
        raise UserError(f"--range {text!r}: {len(r)} frame(s) of the {n} in the file; at "
                        "least 3 are needed")
    return r


def _settle(value: int | None, cfg: dict[str, Any] | None, frame_rate: float) -> int:
    """Frames to leave out after a shutter closing: ``--settle``, or the frames a pixel of
    the file's sensor needs to forget the shutter to 1e-3 (7 time constants C/g)."""
    import math

    from irnuc.common.errors import UserError

    if value is not None:
        if not 0 <= value <= 100_000:
            raise UserError(f"--settle {value} is outside the allowed range 0..100000")
        return value
    if cfg is None:
        return 3
    b = cfg["bolometer"]
    return math.ceil(7.0 * b["C"] / b["g"] * frame_rate)


def _model_config(data: dict[str, Any], where: str) -> tuple[dict[str, Any] | None, int | None]:
    """The sensor configuration and seed a frame file was made with (None: not irnuc's)."""
    import json

    from irnuc.model.config import validate
    from irnuc.model.validate import ConfigError

    if "config_json" not in data:
        return None, None
    try:
        meta = json.loads(str(data["config_json"]))
        return validate(meta["config"], source=f"{where} config_json"), int(meta["seed"])
    except (ValueError, KeyError, TypeError, ConfigError):
        return None, None


def run(args: argparse.Namespace) -> int:
    import json

    import numpy as np

    from irnuc.cli._files import load_frames
    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.model import noise_metrics as nm

    out = claim_output_folder(args.out, kind="noise", inputs={"--frames": args.frames})
    if args.seed is not None and not 0 <= args.seed <= 2**63 - 1:
        raise UserError(f"--seed {args.seed} is outside the allowed range 0..2^63-1")
    data = load_frames(args.frames, work_per_pixel=NOISE_BYTES_PER_PIXEL)
    codes = data["codes"]
    n = codes.shape[0]
    frames = _frame_range(args.range, n)
    cfg, seed = _model_config(data, f"--frames {args.frames}")
    seed = seed if args.seed is None else args.seed
    settle = _settle(args.settle, cfg, data["frame_rate"])
    sel = np.zeros(n, bool)
    sel[frames.start:frames.stop:frames.step] = True
    if not args.include_shutter:
        closed = data["shutter"]
        sel &= ~closed
        for k in np.flatnonzero(closed[:-1] & ~closed[1:]):  # the shutter opens after k
            sel[k + 1:k + 1 + settle] = False
    idx = np.flatnonzero(sel)
    if idx.size < 3:
        raise UserError(f"--frames {args.frames}: {idx.size} frame(s) with the shutter open in "
                        "the range; at least 3 are needed (--include-shutter keeps the others)")
    contiguous = idx.size == idx[-1] - idx[0] + 1
    cube = codes[idx[0]:idx[-1] + 1] if contiguous else codes[idx]
    fields = {k: data[k][idx] for k in ("scene_K", "fpa_K", "T_cam_K", "time_s")}
    good = (data["defect_kind"] == 0) if "defect_kind" in data else np.ones(codes.shape[1:], bool)
    if good.shape != codes.shape[1:]:
        good = np.ones(codes.shape[1:], bool)
    try:
        fit = nm.fit_frames(cube, fields["scene_K"], fields["fpa_K"], fields["T_cam_K"],
                            time_s=fields["time_s"])
    except nm.ConfigError as exc:
        raise UserError(f"--frames {args.frames}: {exc}") from None
    closed = None
    resp_frames = None
    if cfg is not None:
        closed = nm.netd(cfg, float(fields["scene_K"].mean()), seed=seed or 0,
                         T_substrate=float(fields["fpa_K"].mean()),
                         T_cam=float(fields["T_cam_K"].mean()))
        resp_frames = nm.responsivity_frames(cfg, fields["scene_K"], fields["fpa_K"],
                                             fields["T_cam_K"], seed=seed or 0)
    if fit.responsivity is None and closed is None:
        raise UserError(f"--frames {args.frames}: the scene does not vary and the file holds no "
                        "sensor configuration: no responsivity to turn codes into kelvin")
    try:
        measured = nm.measured_netd(fit, good, None if fit.responsivity is not None
                                    else closed.responsivity_codes_per_K)
    except nm.ConfigError as exc:
        raise UserError(f"--frames {args.frames}: {exc}") from None
    resp = measured.responsivity_codes_per_K
    bar = progress("3D noise") if cube.shape[0] > 64 else None
    n3 = nm.noise_3d(cube, progress=bar)

    result: dict[str, Any] = {
        "frames": str(args.frames), "frames_used": int(idx.size), "frame_shape": list(codes.shape[1:]),
        "frames_left_out": int(len(frames) - idx.size),
        "settle_frames": settle,
        "conditions_K": {k: {"min": float(v.min()), "max": float(v.max())}
                         for k, v in fields.items() if k != "time_s"},
        "netd_measured": measured.as_dict(),
        "regressors": fit.regressors,
        "defect_free_pixels": int(good.sum()),
        "noise_3d": {"codes": n3.as_dict(), "mK": n3.as_dict(1e3 / resp, "mK"),
                     "mean_code": n3.mean, "shape_tvh": list(n3.shape),
                     "method": "random-effects ANOVA (expected mean squares), NVESD components",
                     "note": "every pixel of the frames, defective ones included"},
    }
    if closed is not None:
        # The closed form is the same functional of the same pixels: what separates the two
        # is the measurement's standard error (the closed form's uncertainty is the pixels'
        # spread, which both share).
        both = float(measured.uncertainty_K)
        diff = measured.netd_K - closed.netd_K
        result["netd_closed_form"] = closed.as_dict()
        # Without analog noise the ADC's rounding of noiseless frames is deterministic, not
        # the uniform noise of the closed form, and neither side has an uncertainty for
        # that: the comparison is reported, not judged.
        judged = closed.analog_codes > 0.0
        result["agreement"] = {"difference_mK": diff * 1e3, "combined_uncertainty_mK": both * 1e3,
                               "judged": judged,
                               "within_3_sigma": bool(abs(diff) <= 3.0 * both) if judged else None}
        result["responsivity_per_frame_codes_per_K"] = {
            "frame": idx.tolist(), "closed_form": resp_frames.tolist()}
    with output_folder(out, kind="noise") as tmp:
        write_text_atomic(tmp / JSON_NAME, json.dumps(result, indent=1))
        _figure(tmp / FIGURE_NAME, n3, fit, good, idx, fields, resp_frames, measured, closed)
    _summary(result, measured, closed, n3, resp)
    say(f"wrote {out / JSON_NAME} and {out / FIGURE_NAME}")
    return 0


def _summary(result: dict[str, Any], measured: Any, closed: Any, n3: Any, resp: float) -> None:
    from irnuc.model.noise_metrics import COMPONENTS

    say(f"{result['frames_used']} frames of {result['frame_shape'][0]}x"
        f"{result['frame_shape'][1]}; responsivity {resp:.4g} codes/K")
    m = measured.as_dict()
    say(f"NETD measured    {m['netd_mK']:.4g} +/- {m['uncertainty_mK']:.2g} mK  ({m['method']})")
    if closed is not None:
        c = closed.as_dict()
        a = result["agreement"]
        say(f"NETD closed form {c['netd_mK']:.4g} +/- {c['uncertainty_mK']:.2g} mK  "
            f"(+/- the pixels' spread; difference {a['difference_mK']:.3g} mK, "
            + ("not judged" if not a["judged"] else
               f"{'within' if a['within_3_sigma'] else 'OUTSIDE'} 3 standard errors of the "
               "measurement")
            + ")"
            + (f"; {c['notes']}" if c["notes"] else ""))
    say("3D noise        codes        mK")
    for name, meaning in COMPONENTS.items():
        s = n3.sigma[name]
        say(f"  sigma_{name:<4} {s:10.4g} {s * 1e3 / resp:10.4g}   {meaning}")


def _figure(path: Path, n3: Any, fit: Any, good: Any, idx: Any, fields: dict[str, Any],
            resp_frames: Any, measured: Any, closed: Any) -> None:
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt
    import numpy as np

    from irnuc.common.io import write_atomic
    from irnuc.model.noise_metrics import COMPONENTS

    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
    names = list(COMPONENTS)
    ax[0].bar([f"σ_{k}" for k in names], [n3.sigma[k] for k in names], color="tab:blue")
    ax[0].set_yscale("symlog", linthresh=0.1)
    ax[0].set_ylabel("codes")
    ax[0].set_title("3D noise (NVESD)")
    ax[0].tick_params(axis="x", rotation=45)
    sigma = np.sqrt(fit.sigma2_codes[good])
    ax[1].hist(sigma, bins=60, color="tab:gray")
    ax[1].axvline(measured.noise_codes, color="tab:red", label="measured (RMS)")
    if closed is not None:
        ax[1].axvline(closed.noise_codes, color="tab:green", ls="--", label="closed form")
    ax[1].set_xlabel("temporal noise per pixel, codes")
    ax[1].set_title(f"NETD {measured.netd_K * 1e3:.3g} mK measured"
                    + (f", {closed.netd_K * 1e3:.3g} mK closed form" if closed else ""))
    ax[1].legend(fontsize=8)
    t = fields["time_s"]
    if resp_frames is not None:
        ax[2].plot(t, resp_frames, color="tab:green", label="closed form")
    if fit.responsivity is not None:
        ax[2].axhline(float(fit.responsivity[good].mean()), color="tab:red", ls=":",
                      label="measured (all frames)")
    ax[2].set_xlabel("time, s")
    ax[2].set_ylabel("codes per K of scene")
    ax[2].set_title("responsivity per frame")
    ax[2].legend(fontsize=8)
    fig.tight_layout()
    write_atomic(path, lambda fh: fig.savefig(fh, format="png", dpi=110))
    plt.close(fig)


COMMANDS = {
    "noise": ("Temporal NETD, responsivity and 3D noise of frames (JSON + figure)",
              add_arguments, run),
}
