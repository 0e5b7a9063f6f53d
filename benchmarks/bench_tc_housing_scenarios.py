"""The housing-aware method on the thermal world's scenarios (issue 36 part 1's goal).

For each scenario of ``--scenarios`` (``model/scenarios``: power_on_warmup, ambient_ramp) the
camera's states along the schedule (FPA and housing temperatures, every ``--states``-th of
the run evenly) are imaged on the model (uniform scenes and their 0.5 K neighbours,
``drift_common.slope_frames``), each frame with the FPA and housing readings the scenario's
sensors give at that frame (``model.fpa_sensor.frame_fields``: lags, the housing sensor's
node), and corrected by the golden model of

* ``tchousing14`` (tc_housing), calibrated on a plan over FPA x housing that covers the
  scenario: FPA at ``--fpa-points`` temperatures across its span, the housing at offsets
  ``-6, -3, 0`` K (the scenarios' housing runs 0..6 K below the FPA); and the same with
  ``tc_gain`` (its gain a polynomial in v too, tcgain14's formats);
* the baseline ``tcoffset14`` (tc_offset), calibrated on the same FPA points at housing =
  FPA (the registry fits it at the reference offset, 0 K).

Both with ``reading_range_bits`` widened to hold the scenario's FPA span (12 for the ramp's
52 K) and no FFC (no dead time). Per scenario and method: the worst residual fixed pattern
between states (mK through the corrected image's local responsivity,
``metrics.residuals_mK``) and the worst level error, against 0.5 x NETD (the model's NETD at
a 300 K scene, FPA and housing 300 K, every noise source). The ratio is tchousing14's worst
over tcoffset14's, per scenario.

Usage: ``python benchmarks/bench_tc_housing_scenarios.py [--scenarios a,b] [--states 16]
[--rows 24 --cols 32] [--seed 3]``. The last line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time

import numpy as np

from irnuc.model.fpa_sensor import frame_fields
from irnuc.model.sequence import load_sequence
from irnuc.nuc_fixed import PipelineConfig, load_pipeline
from irnuc.nuc_fixed.method_top import FrameInputs, method_top
from irnuc.reports.studies import drift_common as dc

SCENES = (290.0, 330.0, 370.0)
OFFSETS = (-6.0, -3.0, 0.0)


def _range_bits(span_codes: float) -> int:
    """Bits that hold +-span_codes around the reference (the clamp at 2^bits - 1)."""
    return max(11, int(np.ceil(np.log2(span_codes + 2))))


def _configs(ts: int, hs: int) -> dict[str, PipelineConfig]:
    """The measured configurations with v (and w') widened to ``ts`` (``hs``) bits and
    their formats as many integer bits wider (a coefficient per 2^Ts codes doubles per
    bit); tchousing14 also with tc_gain (tcgain14's tg formats)."""
    out = {}
    for label, name in (("tchousing14", "tchousing14"), ("tchousing14+tc_gain", "tchousing14"),
                        ("tcoffset14", "tcoffset14")):
        cfg = load_pipeline(name)
        grow = {"tc1": ts - 11, "tc2": 2 * (ts - 11), "th1": hs - 11,
                "thx": ts - 11 + hs - 11, "th2": 2 * (hs - 11)}
        ch: dict = {"reading_range_bits": ts,
                    "formats": {f.name: {"int_bits": f.int_bits + grow[f.name]}
                                for f in cfg.formats if grow.get(f.name)}}
        if "housing" in cfg.base.readings:
            ch["housing_range_bits"] = hs
        if label.endswith("tc_gain"):
            g = load_pipeline("tcgain14").to_dict()["formats"]
            ch["tc_gain"] = True
            ch["formats"] |= {"tg1": g["tg1"], "tg2": g["tg2"]}
        out[label] = cfg.replace(**ch)
    return out


def calibrate(sensor: dc.StudySensor, fpa: tuple[float, ...], ref: float, ts: int, hs: int
              ) -> dict:
    """Every configuration of :func:`_configs` calibrated on one plan over FPA x housing
    (tc_offset on its points at housing = FPA)."""
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan

    p = CalibrationPlan(scene=SCENES, fpa=fpa, frames=2, reference_fpa=ref,
                        housing_offset=OFFSETS)
    pts = run_plan(p, sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    return {label: calibrate_points(pts, cfg) for label, cfg in _configs(ts, hs).items()}


def scenario(name: str, sensor: dc.StudySensor, states: int, fpa_points: int,
             node: str | None = None) -> dict:
    seq = load_sequence(name)
    if node is not None:  # the housing sensor moved to another node (the model's housing)
        seq = dataclasses.replace(seq, housing_sensor=dataclasses.replace(seq.housing_sensor,
                                                                          node=node))
    sched = dataclasses.replace(seq, record_every=1).schedule()
    f = frame_fields(sched.time_s, sched.fpa_K, sched.T_cam_K, sched.scene_K, sched.shutter,
                     seq.fpa_sensor, seed=sensor.seed, ambient_K=sched.ambient_K,
                     lens_K=sched.lens_K, shutter_K=sched.T_shutter_K,
                     housing_sensor=seq.housing_sensor)
    lo, hi = float(sched.fpa_K.min()), float(sched.fpa_K.max())
    fpa = tuple(float(t) for t in np.round(np.linspace(lo, hi, fpa_points), 2))
    ref = fpa[len(fpa) // 2]
    span = max(ref - lo, hi - ref) / seq.fpa_sensor.lsb_K
    hspan = (max(ref - (lo + min(OFFSETS)), hi - ref) + 1.0) / seq.housing_sensor.lsb_K
    ts, hs = _range_bits(span), _range_bits(hspan)
    cals = {"cal": calibrate(sensor, fpa, ref, ts, hs)}
    good = ~np.logical_or.reduce([c.bad for c in cals["cal"].values()])
    idx = np.unique(np.linspace(0, len(sched.fpa_K) - 1, states).astype(int))
    rows: dict[str, list] = {n: [] for n in cals["cal"]}
    for i in idx:
        raw, _ = dc.slope_frames(sensor, float(sched.fpa_K[i]), float(sched.T_cam_K[i]), SCENES)
        n = len(raw)
        for name, c in cals["cal"].items():
            sc = dc.scale(sensor, c.targets, SCENES)
            y = method_top(raw, c.coeffs, FrameInputs(
                reading=np.full(n, int(f["fpa_reading"][i])),
                housing_reading=np.full(n, int(f["housing_reading"][i])))).y
            res = dc.residuals(y, good, SCENES, sc)
            rows[name].append({"time_s": float(sched.time_s[i]), "fpa_K": float(sched.fpa_K[i]),
                               "housing_K": float(sched.T_cam_K[i]),
                               "fpn_mK": max(r["fpn_mK"] for r in res),
                               "level_error_mK": max(abs(r["level_error_mK"]) for r in res)})
    out = {"fpa_span_K": [lo, hi],
           "housing_minus_fpa_K": [float((sched.T_cam_K - sched.fpa_K).min()),
                                   float((sched.T_cam_K - sched.fpa_K).max())],
           "housing_sensor_node": seq.housing_sensor.node, "plan_fpa_K": list(fpa),
           "plan_housing_offset_K": list(OFFSETS), "reading_range_bits": ts,
           "housing_range_bits": hs, "states": len(idx), "methods": {}}
    for name, rs in rows.items():
        worst = max(rs, key=lambda r: r["fpn_mK"])
        out["methods"][name] = {
            "worst_fpn_mK": worst["fpn_mK"], "at": {k: worst[k] for k in
                                                    ("time_s", "fpa_K", "housing_K")},
            "worst_level_error_mK": max(r["level_error_mK"] for r in rs),
            "median_fpn_mK": float(np.median([r["fpn_mK"] for r in rs])), "trace": rs}
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenarios", default="power_on_warmup,ambient_ramp")
    ap.add_argument("--states", type=int, default=16)
    ap.add_argument("--fpa-points", type=int, default=5)
    ap.add_argument("--rows", type=int, default=24)
    ap.add_argument("--cols", type=int, default=32)
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--housing-node", choices=("housing", "lens", "shutter"), default=None,
                    help="the housing sensor on this node (default: the scenario's)")
    a = ap.parse_args()
    t0 = time.perf_counter()
    sensor = dc.StudySensor(rows=a.rows, cols=a.cols, seed=a.seed)
    netd_mK = dc.netd(sensor, 300.0).netd_K * 1e3
    result = {"bench": "tc_housing_scenarios", "sensor": {"rows": a.rows, "cols": a.cols,
                                                          "seed": a.seed},
              "netd_mK": netd_mK, "goal_mK": 0.5 * netd_mK, "scenarios": {}}
    for name in a.scenarios.split(","):
        r = scenario(name, sensor, a.states, a.fpa_points, a.housing_node)
        result["scenarios"][name] = r
        m = r["methods"]
        for k, v in m.items():
            print(f"{name:16s} {k:12s} worst {v['worst_fpn_mK']:8.1f} mK (median "
                  f"{v['median_fpn_mK']:6.1f}) level {v['worst_level_error_mK']:8.1f} mK; goal "
                  f"{0.5 * netd_mK:.1f} mK")
        r["ratio_worst_tchousing14_vs_tcoffset14"] = (m["tchousing14"]["worst_fpn_mK"]
                                                     / m["tcoffset14"]["worst_fpn_mK"])
        r["goal_met"] = {k: v["worst_fpn_mK"] <= 0.5 * netd_mK for k, v in m.items()}
    result["seconds"] = time.perf_counter() - t0
    slim = json.loads(json.dumps(result))
    for r in slim["scenarios"].values():
        for v in r["methods"].values():
            v.pop("trace")
    print(json.dumps(slim))


if __name__ == "__main__":
    main()
