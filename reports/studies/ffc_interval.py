"""Study: how long a shutter refresh (FFC) holds while the FPA temperature ramps.

At FPA temperature ``ffc_fpa`` the shutter closes (a uniform source at the housing
temperature, the housing at the FPA temperature) and the FFC refreshes the offsets from
``ffc_frames`` shutter frames. The FPA then ramps at 0.5 and 2 K/min; the residual fixed
pattern of a uniform scene is measured against the time since that FFC, in mK beside the
NETD, and the longest FFC period that keeps it below the NETD is read off. The frames are
the model's steady state at each FPA temperature, so both ramps share one curve of residual
against FPA change; the rate sets the time axis. Methods: ``two_point + ffc`` (``ffc14``)
and ``tc_offset + ffc`` (``tcffc14``), and, for comparison, ``two_point`` without FFC.

The shutter's cost (issue 36): each FFC trigger policy of :data:`POLICIES` (a period, an FPA
temperature change, or either: :class:`irnuc.nuc_fixed.ffc_policy.FfcPolicy`, the register
file's ``FFC_PERIOD`` / ``FFC_THRESHOLD``) runs closed loop (the host starts an FFC at each
request, :func:`irnuc.nuc_fixed.ffc_policy.closed_loop`) on the FPA readings of the thermal
world's scenarios (:data:`SCENARIOS`, ``model/scenarios``, at the camera's frame rate);
:func:`shutter_cost` gives the FFC events per hour, the frames lost to the shutter (dead
time, %) and the residual's sawtooth: each shown frame's residual fixed pattern is the
curve above (mK through the local responsivity, ``metrics.residuals_mK``) at that frame's
FPA change since the last FFC. Approximations, stated in the result: the curve is measured
at the FFC's FPA temperature ``ffc_fpa`` with the housing at the FPA and is applied at every
FPA temperature of the scenario (the housing's own drift is issue 36's housing study).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from irnuc.reports.studies import drift_common as dc

NAME = "ffc_interval"
TITLE = "Residual fixed pattern against time since the last FFC, FPA ramping"
METHODS = ("ffc14", "tcffc14")
RATES_K_PER_MIN = (0.5, 2.0)
#: The trigger policies of the shutter's cost: name -> (period s, FPA change K), None off.
POLICIES: dict[str, tuple[float | None, float | None]] = {
    "Lepton: 3 min or 1.5 K": (180.0, 1.5),
    "3 min": (180.0, None),
    "1 min": (60.0, None),
    "1.5 K": (None, 1.5),
    "0.5 K": (None, 0.5),
    "0.1 K": (None, 0.1),
    "3 min or 0.1 K": (180.0, 0.1),
}
QUICK_POLICIES = ("Lepton: 3 min or 1.5 K", "0.1 K")
#: The policies whose sawtooth the figure draws (a trace of 10 s maxima in the JSON).
TRACE_POLICIES = ("Lepton: 3 min or 1.5 K", "0.1 K")
TRACE_S = 10.0
#: The thermal world's scenarios the policies run on (model/scenarios/<name>.toml).
SCENARIOS = ("power_on_warmup", "ambient_ramp")
#: Frames lost per FFC besides its shutter frames: the shutter's movement.
SETTLE_FRAMES = 1


def longest_period(t_min: np.ndarray, fpn_mK: np.ndarray, netd: float) -> float | None:
    """Minutes from the FFC until the residual first exceeds the NETD (linear between
    samples); None when it stays below over the whole span, 0 when it starts above."""
    above = np.flatnonzero(np.asarray(fpn_mK) > netd)
    if above.size == 0:
        return None
    i = int(above[0])
    if i == 0:
        return 0.0
    t0, t1, f0, f1 = t_min[i - 1], t_min[i], fpn_mK[i - 1], fpn_mK[i]
    return float(t0 + (netd - f0) / (f1 - f0) * (t1 - t0))


def residual_at(change_K: np.ndarray, curve_K: np.ndarray, curve_mK: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """The residual (mK) at FPA changes ``change_K`` (K, >= 0) on a measured curve (changes
    ``curve_K`` increasing from 0, residuals ``curve_mK``): linear between its points,
    linear from its last two beyond it; and which were beyond it."""
    x, y = np.asarray(curve_K, np.float64), np.asarray(curve_mK, np.float64)
    d = np.abs(np.asarray(change_K, np.float64))
    out = np.interp(d, x, y)
    beyond = d > x[-1]
    if beyond.any() and x.size > 1:
        slope = (y[-1] - y[-2]) / (x[-1] - x[-2])
        out[beyond] = y[-1] + slope * (d[beyond] - x[-1])
    return out, beyond


def shutter_cost(fpa_K: np.ndarray, readings: np.ndarray, frame_rate: float, policy: Any,
                 ffc_frames: int, curves: dict[str, tuple[np.ndarray, np.ndarray]],
                 settle_frames: int = SETTLE_FRAMES, trace_s: float | None = None
                 ) -> dict[str, Any]:
    """The cost of an FFC trigger policy on a sequence, closed loop.

    Parameters
    ----------
    fpa_K : (n,) array
        The FPA temperature of each frame, K.
    readings : (n,) int array
        The FPA sensor's reading of each frame (codes): what the trigger compares.
    frame_rate : float
        Frames per second, Hz.
    policy : FfcPolicy
        The trigger (period frames, threshold codes).
    ffc_frames : int
        N, shutter frames of an FFC (the refresh frame follows them).
    curves : dict
        Method -> (FPA change since the FFC, K; residual fixed pattern, mK): each shown
        frame's residual is its method's curve at its change (:func:`residual_at`).
    settle_frames : int
        Frames lost per FFC besides its N shutter frames (the shutter moving).
    trace_s : float or None
        With a value, ``trace``: the largest residual of the shown frames in each span of
        that many seconds (mK, NaN where none is shown), the sawtooth to draw.

    Returns the FFC starts (frames), events per hour (the power-on FFC at frame 0
    included), the frames lost (each FFC's N shutter frames and ``settle_frames``) and
    the dead time (% of frames), and per method the worst and mean residual over the shown
    frames after the first refresh (mK), the residual just before each FFC (the sawtooth's
    peaks) and the frames whose change lay beyond the curve.
    """
    from irnuc.nuc_fixed.ffc_policy import closed_loop

    fpa = np.asarray(fpa_K, np.float64)
    n = fpa.size
    starts = closed_loop(readings, policy, ffc_frames)
    dead = np.zeros(n, bool)
    # The FPA temperature each FFC's offsets hold (the mean over its shutter frames), from
    # its refresh frame on.
    at = np.full(n, np.nan)
    for s in starts:
        dead[s:s + ffc_frames + settle_frames] = True
        if s + ffc_frames < n:
            at[s + ffc_frames:] = fpa[s:s + ffc_frames].mean()
    shown = ~dead & ~np.isnan(at)
    change = np.abs(fpa - np.where(np.isnan(at), fpa, at))
    hours = n / frame_rate / 3600.0
    out: dict[str, Any] = {
        "policy": policy.describe(frame_rate), "period_frames": policy.period,
        "threshold_codes": policy.threshold, "ffc_starts": len(starts),
        "events_per_hour": len(starts) / hours, "dead_frames": int(dead.sum()),
        "dead_time_pct": 100.0 * float(dead.mean()),
        "worst_change_K": float(change[shown].max(initial=0.0)), "residual": {}}
    for name, (cx, cy) in curves.items():
        r, beyond = residual_at(change, cx, cy)
        peaks = [float(r[s - 1]) for s in starts[1:] if shown[s - 1]]
        out["residual"][name] = {
            "worst_mK": float(r[shown].max(initial=0.0)),
            "mean_mK": float(r[shown].mean()) if shown.any() else 0.0,
            "peaks_mK": peaks, "beyond_curve_frames": int((beyond & shown).sum())}
        if trace_s:
            step = max(1, round(trace_s * frame_rate))
            shown_r = np.where(shown, r, -np.inf)
            pad = -(-n // step) * step - n
            m = np.pad(shown_r, (0, pad), constant_values=-np.inf).reshape(-1, step).max(1)
            out.setdefault("trace", {"t_s": (np.arange(m.size) * step / frame_rate).tolist()})
            out["trace"][name] = np.where(np.isfinite(m), m, np.nan).tolist()
    return out


def policy_costs(curves: dict[str, tuple[np.ndarray, np.ndarray]], ffc_frames: int,
                 seed: int, policies: tuple[str, ...], scenarios: tuple[str, ...]
                 ) -> dict[str, dict[str, Any]]:
    """:func:`shutter_cost` of each named policy on each scenario (its schedule at the
    camera's frame rate, its FPA sensor's readings)."""
    import dataclasses

    from irnuc.model.sequence import load_sequence
    from irnuc.nuc_fixed.ffc_policy import FfcPolicy

    out: dict[str, dict[str, Any]] = {}
    for sc_name in scenarios:
        seq = load_sequence(sc_name)
        sched = dataclasses.replace(seq, record_every=1).schedule()
        readings = seq.fpa_sensor.read(sched.fpa_K, seed=seed)
        lsb = seq.fpa_sensor.lsb_K
        out[sc_name] = {"frame_rate": seq.frame_rate, "duration_s": seq.duration,
                        "fpa_span_K": [float(sched.fpa_K.min()), float(sched.fpa_K.max())],
                        "policies": {}}
        for pname in policies:
            period_s, change_K = POLICIES[pname]
            pol = FfcPolicy.from_physical(period_s, change_K, seq.frame_rate, lsb)
            cost = shutter_cost(sched.fpa_K, readings, seq.frame_rate, pol, ffc_frames, curves,
                                trace_s=TRACE_S if pname in TRACE_POLICIES else None)
            cost["policy"] = pol.describe(seq.frame_rate, lsb)
            out[sc_name]["policies"][pname] = cost
    return out


def run(quick: bool = False, sensor: dc.StudySensor | None = None, scene_K: float = 330.0,
        ffc_fpa: float = 300.0, max_change_K: float = 6.0,
        progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """Residual against FPA change after one FFC, for each method and ramp (JSON-ready)."""
    import time

    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    t0 = time.perf_counter()
    sensor = sensor or dc.StudySensor(rows=24 if quick else 48, cols=32 if quick else 64)
    # Dense near the FFC, where a method without temperature compensation crosses the NETD.
    grid = (0.0, 0.1, 0.3, 1.0, 3.0, 6.0) if quick else (
        0.0, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0)
    changes = np.asarray([d for d in grid if d <= max_change_K])
    cal = dc.calibrate_methods(sensor, (*METHODS, "typical14"), dc.PLAN)
    base = cal["cal"]["ffc14"]
    sc = dc.scale(sensor, base.targets, dc.PLAN["scene"])
    good = ~np.logical_or.reduce([c.bad for c in cal["cal"].values()])
    n_ffc = int(base.cfg.ffc_frames or 1)
    shutter_raw, _ = dc.frames_at(sensor, ffc_fpa, ffc_fpa, [ffc_fpa], repeats=n_ffc)
    reading0 = int(cal["plan"].fpa_sensor.read(ffc_fpa)[0])
    scene_raw = []
    readings = []
    for i, d in enumerate(changes):
        raw, _ = dc.slope_frames(sensor, ffc_fpa + d, ffc_fpa + d, [scene_K])
        scene_raw.append(raw)
        readings += [int(cal["plan"].fpa_sensor.read(ffc_fpa + d)[0])] * 3
        if progress:
            progress(i + 1, len(changes))
    scene_raw = np.concatenate(scene_raw)
    n3 = len(readings)
    curves: dict[str, Any] = {}
    levels: dict[str, Any] = {}

    def per_change(y: np.ndarray) -> list[dict[str, float]]:
        return [dc.residuals(y[3 * k:3 * k + 3], good, [scene_K], sc)[0]
                for k in range(len(changes))]

    for name in METHODS:
        c = cal["cal"][name]
        ref = method_top(shutter_raw, c.coeffs, FrameInputs(
            reading=np.full(n_ffc, reading0), shutter=np.ones(n_ffc, bool)))
        y = method_top(scene_raw, c.coeffs, FrameInputs(
            reading=np.asarray(readings), shutter=np.zeros(n3, bool)),
            ffc_offset=ref.ffc_offset).y
        res = per_change(y)
        curves[c.cfg.method] = [r["fpn_mK"] for r in res]
        levels[c.cfg.method] = [r["level_error_mK"] for r in res]
    res = per_change(method_top(scene_raw, cal["cal"]["typical14"].coeffs).y)
    curves["two_point (no FFC)"] = [r["fpn_mK"] for r in res]
    levels["two_point (no FFC)"] = [r["level_error_mK"] for r in res]
    nd = dc.netd(sensor, ffc_fpa)
    netd = nd.netd_K * 1e3
    ramps = {}
    for rate in RATES_K_PER_MIN:
        t_min = changes / rate
        ramps[f"{rate:g} K/min"] = {
            "rate_K_per_min": rate, "t_min": t_min.tolist(),
            "longest_period_min": {m: longest_period(t_min, np.asarray(v), netd)
                                   for m, v in curves.items()},
            "span_min": float(t_min[-1])}
    with_ffc = {m: (changes, np.asarray(curves[m])) for m in curves if "no FFC" not in m}
    costs = policy_costs(with_ffc, n_ffc, sensor.seed,
                         QUICK_POLICIES if quick else tuple(POLICIES),
                         SCENARIOS[:1] if quick else SCENARIOS)
    return {
        "study": NAME, "title": TITLE, "quick": quick,
        "policies": costs, "settle_frames": SETTLE_FRAMES,
        "policy_note": ("residual of each shown frame: the curve above at its FPA change "
                        f"since the last FFC (measured at FPA {ffc_fpa:g} K, housing at the "
                        "FPA), applied at every FPA temperature of the scenario"),
        "sensor": {"preset": str(sensor.preset), "rows": sensor.rows, "cols": sensor.cols,
                   "seed": sensor.seed, "overrides": dict(sensor.overrides)},
        "scene_K": scene_K, "ffc_fpa_K": ffc_fpa, "ffc_frames": n_ffc,
        "fpa_change_K": changes.tolist(), "fpn_mK": curves, "level_error_mK": levels,
        "ramps": ramps, "netd_mK": netd, "netd": nd.as_dict(),
        "seconds": time.perf_counter() - t0,
    }


def figure(result: dict[str, Any]) -> bytes:
    """Residual against time since the FFC, one panel per ramp, the NETD; below, the
    sawtooth of the traced policies on each scenario."""
    from irnuc.reports.studies.figures import png

    plt = dc.pyplot()
    ramps = result["ramps"]
    scen = result.get("policies", {})
    cols = max(len(ramps), len(scen))
    rows = 2 if scen else 1
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.8 * rows), squeeze=False)
    for ax in axes[0][len(ramps):]:
        ax.set_visible(False)
    for ax, (sname, sc) in zip(axes[-1] if scen else [], scen.items(), strict=False):
        k = 0
        for pname, c in sc["policies"].items():
            tr = c.get("trace")
            if not tr:
                continue
            for m in (x for x in tr if x != "t_s"):
                ax.plot(np.asarray(tr["t_s"]) / 60.0, tr[m], lw=0.8, color=f"C{k}",
                        label=f"{m}, {pname}: {c['dead_time_pct']:.2g} % dead")
                k += 1
        ax.axhline(result["netd_mK"], color="k", ls=":", lw=1, label="NETD")
        ax.axhline(0.5 * result["netd_mK"], color="k", ls="--", lw=0.8, label="0.5 NETD")
        ax.set_yscale("log")
        ax.set_xlabel("time, min")
        ax.set_ylabel("residual fixed pattern, mK (10 s max)")
        ax.set_title(f"{sname}: FFC on request (closed loop)", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    for ax in (axes[-1][len(scen):] if scen else []):
        ax.set_visible(False)
    for ax, (rname, ramp) in zip(axes[0], ramps.items(), strict=False):
        for i, (m, v) in enumerate(result["fpn_mK"].items()):
            lp = ramp["longest_period_min"][m]
            tag = "stays below" if lp is None else f"{lp:.2g} min"
            ax.plot(ramp["t_min"], v, "o-", ms=3, color=f"C{i}", label=f"{m}: {tag}")
        ax.axhline(result["netd_mK"], color="k", ls=":", lw=1,
                   label=f"NETD {result['netd_mK']:.0f} mK (300 K scene)")
        ax.set_yscale("log")
        ax.set_xscale("symlog", linthresh=0.1)
        ax.set_xlim(0.0, ramp["span_min"])
        ax.set_xlabel("time since the FFC, min")
        ax.set_ylabel("residual fixed pattern, mK")
        ax.set_title(f"FPA ramp {rname}", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.9 if rows == 2 else 0.8))
    fig.suptitle(f"{TITLE}\nFFC at FPA {result['ffc_fpa_K']:g} K ({result['ffc_frames']} "
                 f"frames), scene {result['scene_K']:g} K", fontsize=9)
    return png(fig)
