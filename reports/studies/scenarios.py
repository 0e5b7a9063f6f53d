"""The sign-off's thermal scenarios: every sweep point judged on the camera's real thermal
world (issue 37), the shipped scenarios of ``model/scenarios`` (power-on warm-up, ambient
ramp, indoors to outdoors, the FPA ramp with the housing following).

A scenario runs at its camera's frame rate for minutes to an hour; correcting every frame of
every point would cost hours. What is computed instead, and why it holds:

* **Nodes.** The scenario's schedule (its thermal network at the full frame rate) is walked
  and a *node* is kept each time the FPA, the housing or the shutter has moved by
  ``node_K`` since the last node (or ``node_max_s`` has passed), the first and last frames
  included. At each node the study sensor's raw frames are made by the physics model in its
  steady state (:func:`drift_common.frames_at`): the uniform scenes each with their
  neighbours 0.5 K either side (the local responsivity, :func:`metrics.residuals_mK`) and
  one frame of the shutter at its temperature then.
* **Between nodes** a frame is the linear interpolation (in time) of its two nodes' raw
  frames, rounded to codes. The nodes are at most ``node_K`` apart in every temperature, so
  the interpolation error is the raw signal's curvature over ``node_K`` (stated in the
  result: ``interpolation``).
* **Readings.** The FPA and housing sensors' readings are the scenario's own at the full
  frame rate (their lag, LSB and noise; ``Schedule.fields``): the trigger of a
  temperature-triggered FFC policy sees what the register file would see.
* **FFC.** A policy (:class:`irnuc.nuc_fixed.ffc_policy.FfcPolicy`) runs closed loop on the
  readings (:func:`irnuc.nuc_fixed.ffc_policy.closed_loop`, power-on FFC at frame 0); each FFC
  takes ``ffc_frames`` frames of the shutter at the FFC's start (their readings the frames'
  own) and refreshes the offsets from the refresh frame on; the frames lost are the
  shutter frames and :data:`SETTLE_FRAMES` (dead time, %), the events per hour counted.
* **Where the residual is read.** At every node the camera shows (not dead), and at the
  frame just before each FFC (the sawtooth's peaks; when there are more than
  ``max_peaks``, those with the largest temperature change since their refresh).

Per point and scenario: the worst residual fixed pattern over the scenes (mK, the corrected
image's local responsivity, and LSB), the worst level error (mK), when the worst happened,
the FFC events per hour and the dead time, and a trace (time, pattern, level) for the
figures.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from irnuc.reports.studies import drift_common as dc

#: Frames lost per FFC besides its shutter frames (the shutter moving): as ffc_interval.
SETTLE_FRAMES = 1


@dataclass(frozen=True)
class Policy:
    """An FFC trigger policy in physical units (None: that trigger off)."""

    period_min: float | None = None
    change_K: float | None = None

    @property
    def tag(self) -> str:
        """The policy's part of a point key: ``p0.5`` / ``t0.1`` / ``p3t1.5``."""
        out = ""
        if self.period_min is not None:
            out += f"p{self.period_min:g}"
        if self.change_K is not None:
            out += f"t{self.change_K:g}"
        return out

    def describe(self) -> str:
        parts = []
        if self.period_min is not None:
            parts.append(f"every {self.period_min:g} min")
        if self.change_K is not None:
            parts.append(f"on a {self.change_K:g} K FPA change")
        return " or ".join(parts)

    def registers(self, frame_rate: float, lsb_K: float) -> Any:
        from irnuc.nuc_fixed.ffc_policy import FfcPolicy

        return FfcPolicy.from_physical(None if self.period_min is None else 60.0 * self.period_min,
                                       self.change_K, frame_rate, lsb_K)


def policies(periods_min: Sequence[float], changes_K: Sequence[float],
             either: Sequence[Sequence[float]]) -> list[Policy]:
    """Period-only, change-only and period-or-change policies, in that order."""
    out = [Policy(period_min=float(p)) for p in periods_min]
    out += [Policy(change_K=float(c)) for c in changes_K]
    out += [Policy(period_min=float(p), change_K=float(c)) for p, c in either]
    return out


@dataclass
class Trajectory:
    """A scenario's nodes and their raw frames, and its full-rate readings (see the module
    docstring). ``raw``: (nodes, 3 S, H, W) scene frames; ``shutter_raw``: (nodes, H, W);
    ``blind`` / ``shutter_blind`` the blind codes beside them."""

    name: str
    description: str
    frame_rate: float
    time_s: np.ndarray          # full rate
    fpa_K: np.ndarray           # full rate
    housing_K: np.ndarray       # full rate
    fpa_reading: np.ndarray     # full rate
    housing_reading: np.ndarray  # full rate
    lsb_K: float
    nodes: np.ndarray           # frame indices
    raw: np.ndarray
    blind: np.ndarray
    shutter_raw: np.ndarray
    shutter_blind: np.ndarray

    @property
    def n(self) -> int:
        return int(self.time_s.size)

    def frames(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """Raw scene frames and blind codes at full-rate frame ``i`` (interpolated)."""
        return self._interp(i, self.raw, self.blind)

    def shutter(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        return self._interp(i, self.shutter_raw, self.shutter_blind)

    def _interp(self, i: int, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        k = int(np.searchsorted(self.nodes, i, side="right") - 1)
        k = min(max(k, 0), self.nodes.size - 1)
        if self.nodes[k] == i or k == self.nodes.size - 1:
            return a[k], b[k]
        w = (i - self.nodes[k]) / (self.nodes[k + 1] - self.nodes[k])
        return (np.rint((1 - w) * a[k] + w * a[k + 1]).astype(a.dtype),
                np.rint((1 - w) * b[k] + w * b[k + 1]).astype(b.dtype))


def pick_nodes(fpa: np.ndarray, housing: np.ndarray, shutter_K: np.ndarray, frame_rate: float,
               node_K: float, node_max_s: float) -> np.ndarray:
    """Frame indices of the nodes: the first frame, then each frame where the FPA, the
    housing or the shutter has moved ``node_K`` or more since the last node or
    ``node_max_s`` seconds have passed, and the last frame."""
    gap = max(1, round(node_max_s * frame_rate))
    out = [0]
    last = 0
    n = fpa.size
    series = np.stack([fpa, housing, shutter_K])
    i = 1
    while i < n:
        # the next frame where any series leaves the band around the last node
        j = min(n, last + gap)
        seg = np.abs(series[:, i:j] - series[:, last:last + 1]).max(axis=0)
        hit = np.flatnonzero(seg >= node_K)
        nxt = i + int(hit[0]) if hit.size else j
        if nxt >= n:
            break
        out.append(nxt)
        last, i = nxt, nxt + 1
    if out[-1] != n - 1:
        out.append(n - 1)
    return np.asarray(out, np.int64)


def trajectory(name: str, sensor: dc.StudySensor, scenes: Sequence[float], node_K: float,
               node_max_s: float) -> Trajectory:
    """Load the named scenario and make its nodes' frames."""
    from irnuc.model.sequence import load_sequence
    from irnuc.reports.studies.metrics import slope_scenes

    seq = load_sequence(name)
    sched = dataclasses.replace(seq, record_every=1).schedule()
    fields = sched.fields(seq.fpa_sensor, sensor.seed, seq.housing_sensor)
    nodes = pick_nodes(sched.fpa_K, sched.T_cam_K, sched.T_shutter_K, seq.frame_rate, node_K,
                       node_max_s)
    sl = slope_scenes(scenes)
    raw, blind, sraw, sblind = [], [], [], []
    for i in nodes:
        r, b = dc.frames_at(sensor, float(sched.fpa_K[i]), float(sched.T_cam_K[i]),
                            [*sl, float(sched.T_shutter_K[i])])
        raw.append(r[:-1])
        blind.append(b[:-1])
        sraw.append(r[-1])
        sblind.append(b[-1])
    return Trajectory(
        name=name, description=_description(name),
        frame_rate=float(seq.frame_rate), time_s=np.asarray(sched.time_s, np.float64),
        fpa_K=np.asarray(sched.fpa_K, np.float64), housing_K=np.asarray(sched.T_cam_K, np.float64),
        fpa_reading=np.asarray(fields["fpa_reading"], np.int64),
        housing_reading=np.asarray(fields["housing_reading"], np.int64),
        lsb_K=float(seq.fpa_sensor.lsb_K), nodes=nodes, raw=np.stack(raw), blind=np.stack(blind),
        shutter_raw=np.stack(sraw), shutter_blind=np.stack(sblind))


def _description(name: str) -> str:
    """The scenario file's ``description`` (the name when it has none)."""
    from irnuc.common.schema import read_toml
    from irnuc.model.sequence import SCENARIO_DIR, scenario_names

    if name not in scenario_names():  # a name from the list, never a path
        return name
    return str((read_toml(SCENARIO_DIR / f"{name}.toml").get("sequence") or {}).get(
        "description") or name)


def ffc_starts(traj: Trajectory, pol: Policy, ffc_frames: int) -> list[int]:
    """The FFC start frames of ``pol`` on the scenario, closed loop (frame 0: power-on)."""
    from irnuc.nuc_fixed.ffc_policy import closed_loop

    return closed_loop(traj.fpa_reading, pol.registers(traj.frame_rate, traj.lsb_K), ffc_frames)


def _inputs(cfg: Any, traj: Trajectory, idx: Sequence[int], blind: np.ndarray,
            shutter: bool) -> Any:
    from irnuc.nuc_fixed.method_top import FrameInputs

    idx = np.asarray(idx, np.int64)
    return FrameInputs(reading=traj.fpa_reading[idx], housing_reading=traj.housing_reading[idx],
                       blind_codes=blind,
                       shutter=np.full(idx.size, shutter) if cfg.has("ffc") else None)


def _sig(x: float) -> float:
    return float(f"{x:.4g}")


def evaluate(cal: Any, traj: Trajectory, scenes: Sequence[float], sc: Any, good: np.ndarray,
             pol: Policy | None, starts: Sequence[int] | None, max_peaks: int,
             settle_frames: int = SETTLE_FRAMES, memo: dict[str, Any] | None = None
             ) -> dict[str, Any]:
    """One calibrated point on one scenario (see the module docstring): worst residual
    (mK, LSB), worst level error (mK), when, FFC events per hour, dead time, the trace.

    ``memo``: a dict shared by the calls of one calibration on one scenario (its FFC
    policies): a frame corrected with a given refresh, and a refresh, are computed once
    (the golden model corrects each frame on its own: the same bits either way)."""
    from irnuc.nuc_fixed.method_top import method_top

    cfg = cal.cfg
    n = traj.n
    s3 = 3 * len(scenes)
    hours = n / traj.frame_rate / 3600.0

    memo = {} if memo is None else memo
    done_rows: dict[tuple[int | None, int], tuple[float, float, float]] = memo.setdefault(
        "rows", {})

    def residuals(s: int | None, idx: Sequence[int], ffc_offset: np.ndarray | None
                  ) -> list[tuple[float, float, float]]:
        """(LSB, mK, level mK) at each frame of ``idx`` shown with refresh ``s``, one
        golden-model call for the frames not yet corrected with it."""
        todo = [i for i in idx if (s, i) not in done_rows]
        if todo:
            for i, r in zip(todo, _residuals(todo, ffc_offset), strict=True):
                done_rows[s, i] = r
        return [done_rows[s, i] for i in idx]

    def _residuals(idx: Sequence[int], ffc_offset: np.ndarray | None
                   ) -> list[tuple[float, float, float]]:
        fr = [traj.frames(i) for i in idx]
        raw = np.concatenate([f[0] for f in fr])
        blind = np.concatenate([f[1] for f in fr])
        rep = [i for i in idx for _ in range(s3)]
        y = method_top(raw, cal.coeffs, _inputs(cfg, traj, rep, blind, False),
                       ffc_offset=ffc_offset).y
        out = []
        for k in range(len(idx)):
            res = dc.residuals(y[k * s3:(k + 1) * s3], good, scenes, sc)
            # a NaN (a level off the temperature scale) counts as infinite: never hidden by max
            mk = [r["fpn_mK"] if math.isfinite(r["fpn_mK"]) else math.inf for r in res]
            lv = [r["level_error_mK"] if math.isfinite(r["level_error_mK"]) else math.inf
                  for r in res]
            out.append((max(r["fpn_lsb"] for r in res), max(mk), max(lv, key=abs)))
        return out

    out: dict[str, Any] = {}
    if pol is None:
        at = [int(i) for i in traj.nodes]
        refresh_of: dict[int, int | None] = {i: None for i in at}
        out.update(ffc_per_hour=0.0, dead_time_pct=0.0, ffc_starts=0)
        ffc_s: list[float] = []
    else:
        nf = int(cfg.ffc_frames or 1)
        st = np.asarray(starts, np.int64)
        dead = np.zeros(n, bool)
        for s in st:
            dead[s:s + nf + settle_frames] = True
        # the refresh each frame shows: the last FFC whose refresh frame is at or before it
        done = st + nf
        nodes = [int(i) for i in traj.nodes if not dead[i]]
        peaks = [int(s) - 1 for s in st[1:] if not dead[int(s) - 1]]
        if len(peaks) > max_peaks:
            def change(i: int) -> float:
                j = int(st[np.searchsorted(done, i, side="right") - 1])
                return max(abs(traj.fpa_K[i] - traj.fpa_K[j]),
                           abs(traj.housing_K[i] - traj.housing_K[j]))
            peaks = sorted(peaks, key=change, reverse=True)[:max_peaks]
        at = sorted(set(nodes) | set(peaks))
        refresh_of = {}
        for i in at:
            k = int(np.searchsorted(done, i, side="right") - 1)
            refresh_of[i] = int(st[k]) if k >= 0 else None
        out.update(ffc_per_hour=_sig(len(st) / hours), dead_time_pct=_sig(100.0 * dead.mean()),
                   ffc_starts=len(st))
        ffc_s = [float(traj.time_s[s]) for s in st[:2000]]
    refs: dict[int, np.ndarray] = memo.setdefault("refs", {})

    def refresh(s: int) -> np.ndarray:
        if s not in refs:
            nf = int(cfg.ffc_frames or 1)
            raw, blind = traj.shutter(s)
            idx = [min(s + k, n - 1) for k in range(nf)]
            refs[s] = method_top(np.repeat(raw[None], nf, axis=0), cal.coeffs, _inputs(
                cfg, traj, idx, np.repeat(blind[None], nf, axis=0), True)).ffc_offset
        return refs[s]

    rows = []  # (frame, LSB, mK, level mK)
    groups: dict[int | None, list[int]] = {}
    for i in at:
        s = refresh_of[i]
        if pol is not None and s is None:
            continue  # before the power-on FFC's refresh: dead anyway
        groups.setdefault(s, []).append(i)
    for s, idx in groups.items():
        rows += [(i, *r) for i, r in zip(
            idx, residuals(s, idx, None if s is None else refresh(s)), strict=True)]
    rows.sort()
    wi, _, wm, _ = max(rows, key=lambda r: r[2])
    out.update(worst_fpn_mK=_sig(wm), worst_fpn_lsb=_sig(max(r[1] for r in rows)),
               worst_level_error_mK=_sig(max(abs(r[3]) for r in rows)),
               worst_at_s=_sig(float(traj.time_s[wi])), worst_frame=int(wi),
               worst_refresh_frame=refresh_of[wi], evaluated=len(rows), ffc_s=ffc_s,
               trace=[[_sig(float(traj.time_s[i])), _sig(mk), _sig(lv)] for i, _, mk, lv in rows])
    return out


def summary(traj: Trajectory) -> dict[str, Any]:
    """What the report shows of a scenario: its span, nodes, the housing-FPA difference."""
    step = max(1, traj.n // 600)
    return {"name": traj.name, "description": traj.description, "frame_rate": traj.frame_rate,
            "duration_s": _sig(float(traj.time_s[-1] + 1.0 / traj.frame_rate)),
            "frames": traj.n, "nodes": int(traj.nodes.size),
            "fpa_span_K": [_sig(float(traj.fpa_K.min())), _sig(float(traj.fpa_K.max()))],
            "housing_span_K": [_sig(float(traj.housing_K.min())),
                               _sig(float(traj.housing_K.max()))],
            "housing_minus_fpa_K": [_sig(float((traj.housing_K - traj.fpa_K).min())),
                                    _sig(float((traj.housing_K - traj.fpa_K).max()))],
            "curve": {"t_s": [_sig(float(v)) for v in traj.time_s[::step]],
                      "fpa_K": [_sig(float(v)) for v in traj.fpa_K[::step]],
                      "housing_K": [_sig(float(v)) for v in traj.housing_K[::step]]}}


def worst_over(per: Mapping[str, Mapping[str, Any]]) -> dict[str, Any]:
    """A point's figures worst over its scenarios (and which scenario)."""
    name = max(per, key=lambda k: per[k]["worst_fpn_mK"])
    return {"worst_fpn_mK": per[name]["worst_fpn_mK"],
            "worst_fpn_lsb": max(p["worst_fpn_lsb"] for p in per.values()),
            "worst_level_error_mK": max(p["worst_level_error_mK"] for p in per.values()),
            "worst_scenario": name,
            "ffc_per_hour": max(p["ffc_per_hour"] for p in per.values()),
            "dead_time_pct": max(p["dead_time_pct"] for p in per.values())}


def breaking(p: Mapping[str, Any], tol: float) -> list[str]:
    """The scenarios on which point ``p`` misses ``tol`` (mK), worst first, each said as
    ``name (x mK at t s)``."""
    per = p.get("scenarios") or {}
    bad = sorted((k for k, v in per.items() if v["worst_fpn_mK"] > tol),
                 key=lambda k: -per[k]["worst_fpn_mK"])
    return [f"{k} ({per[k]['worst_fpn_mK']:.3g} mK at {per[k]['worst_at_s']:.0f} s)" for k in bad]
