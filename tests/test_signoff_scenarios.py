"""The sign-off over thermal scenarios (issue 37): nodes, interpolation, policies, the
registry's methods, the worst over scenarios and the per-scenario reasons; a tiny sweep of
one method on the shortest scenario checked against a hand computation with the golden
model. Fast: tiny sensors, no RTL (the axis harness is in cocotb_tests/test_axis_bulk.py).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from irnuc.reports.studies import scenarios as scn
from irnuc.reports.studies import signoff as so


def test_nodes_every_half_kelvin_of_any_temperature_and_the_ends() -> None:
    fpa = 0.1 * np.arange(21)          # 0 .. 2 K in 0.1 K steps
    housing = np.zeros(21)
    shutter = np.zeros(21)
    got = scn.pick_nodes(fpa, housing, shutter, frame_rate=1.0, node_K=0.5, node_max_s=1e6)
    assert got.tolist() == [0, 5, 10, 15, 20]
    # the housing alone moving makes nodes too; a time gap makes one without a change
    got = scn.pick_nodes(np.zeros(21), fpa, shutter, frame_rate=1.0, node_K=0.5, node_max_s=1e6)
    assert got.tolist() == [0, 5, 10, 15, 20]
    got = scn.pick_nodes(np.zeros(10), np.zeros(10), np.zeros(10), frame_rate=2.0, node_K=0.5,
                         node_max_s=2.0)
    assert got.tolist() == [0, 4, 8, 9]


def test_frames_between_nodes_are_interpolated_in_time() -> None:
    a = np.full((3, 2, 2), 100, np.int64)
    b = np.full((3, 2, 2), 111, np.int64)
    tr = scn.Trajectory(
        name="x", description="", frame_rate=1.0, time_s=np.arange(11.0), fpa_K=np.zeros(11),
        housing_K=np.zeros(11), fpa_reading=np.zeros(11, np.int64),
        housing_reading=np.zeros(11, np.int64), lsb_K=0.01, nodes=np.array([0, 10]),
        raw=np.stack([a, b]), blind=np.zeros((2, 3, 4), np.int64),
        shutter_raw=np.stack([a[0], b[0]]), shutter_blind=np.zeros((2, 4), np.int64))
    raw, _ = tr.frames(0)
    assert (raw == 100).all()
    raw, _ = tr.frames(5)
    assert (raw == 106).all()          # 100 + 11 / 2 = 105.5 rounds to even: 106
    raw, _ = tr.frames(3)
    assert (raw == 103).all()          # 100 + 3.3
    raw, _ = tr.frames(10)
    assert (raw == 111).all()


def test_policy_tags_text_and_registers() -> None:
    ps = scn.policies([0.5], [0.1], [[3.0, 1.5]])
    assert [p.tag for p in ps] == ["p0.5", "t0.1", "p3t1.5"]
    assert ps[2].describe() == "every 3 min or on a 1.5 K FPA change"
    # the Lepton's at 30 Hz with a 0.01 K reading: 3 min = 5400 frames, 1.5 K = 150 codes
    r = ps[2].registers(30.0, 0.01)
    assert (r.period, r.threshold) == (5400, 150)
    r = ps[1].registers(8.7, 0.01)
    assert (r.period, r.threshold) == (0, 10)


def test_registry_methods_are_the_14_bit_configurations() -> None:
    from irnuc.nuc_fixed.config import PIPELINES_TOML

    tables = tomllib.loads(Path(PIPELINES_TOML).read_text())
    want = [n for n, t in tables.items() if isinstance(t, dict) and t.get("adc_bits") == 14]
    got = so.registry_methods()
    assert list(got) == want
    assert {"tcffc14", "tcgain14", "ffc14"} <= set(got)
    assert not {"wide16", "minimal"} & set(got)


def test_worst_over_scenarios_and_the_scenarios_that_break_a_point() -> None:
    per = {"a": {"worst_fpn_mK": 10.0, "worst_fpn_lsb": 1.0, "worst_level_error_mK": 50.0,
                 "ffc_per_hour": 30.0, "dead_time_pct": 0.3, "worst_at_s": 12.0},
           "b": {"worst_fpn_mK": 40.0, "worst_fpn_lsb": 0.5, "worst_level_error_mK": 5.0,
                 "ffc_per_hour": 10.0, "dead_time_pct": 0.1, "worst_at_s": 600.4},
           "c": {"worst_fpn_mK": 20.0, "worst_fpn_lsb": 0.7, "worst_level_error_mK": 7.0,
                 "ffc_per_hour": 60.0, "dead_time_pct": 0.5, "worst_at_s": 1.0}}
    w = scn.worst_over(per)
    assert w == {"worst_fpn_mK": 40.0, "worst_fpn_lsb": 1.0, "worst_level_error_mK": 50.0,
                 "worst_scenario": "b", "ffc_per_hour": 60.0, "dead_time_pct": 0.5}
    assert scn.breaking({"scenarios": per}, 15.0) == ["b (40 mK at 600 s)", "c (20 mK at 1 s)"]
    assert scn.breaking({"scenarios": per}, 40.0) == []


def test_recommend_charges_dead_time_then_ffc_rate() -> None:
    base = {"valid": True, "memory_bits": 40, "read_bits_per_frame": 30, "worst_fpn_mK": 5.0}
    pts = [{**base, "index": 0, "dead_time_pct": 2.0, "ffc_per_hour": 200.0},
           {**base, "index": 1, "dead_time_pct": 0.5, "ffc_per_hour": 60.0},
           {**base, "index": 2, "dead_time_pct": 0.5, "ffc_per_hour": 30.0},
           {**base, "index": 3, "dead_time_pct": 0.1, "ffc_per_hour": 10.0, "worst_fpn_mK": 50.0}]
    r = so.recommend(pts, 10.0)
    assert r["index"] == 2 and r["candidates"] == [2, 1, 0]


@pytest.fixture(scope="module")
def tiny_sweep():
    spec = so.SignoffSpec(rows=6, cols=8, frac_bits=(12,), methods=("tcoffset14", "tcffc14"),
                          scene_K=(300.0, 340.0), ffc_periods_min=(0.25,), ffc_changes_K=(0.2,),
                          ffc_either=(), scenarios=("fpa_ramp",), noise_frames=2,
                          housing_offset_K=(0.0,))
    return spec, so.run(spec, workers=0)


def test_tiny_sweep_points_policies_and_costs(tiny_sweep) -> None:
    _spec, res = tiny_sweep
    keys = [p["key"] for p in res["points"]]
    assert keys == ["tcoffset14_f12", "tcffc14_f12_p0.25", "tcffc14_f12_t0.2"]
    seq = res["scenarios"]["fpa_ramp"]
    # fpa_ramp: 60 s at 30 Hz, the FPA 293 -> 295 K at 2 K/min, the housing 2 K below
    assert seq["frames"] == 1800 and seq["fpa_span_K"][0] == 293.0
    assert seq["fpa_span_K"][1] == pytest.approx(295.0, abs=0.01)
    p = res["points"][1]
    s = p["scenarios"]["fpa_ramp"]
    # every 15 s in 60 s: FFCs at 0, 15, 30, 45 s (closed loop: +1 frame each for the
    # request), 4 in 1/60 h; dead: 8 shutter + 1 settling frame each
    assert s["ffc_starts"] == 4 and s["ffc_per_hour"] == pytest.approx(240.0)
    assert s["dead_time_pct"] == pytest.approx(100.0 * 4 * 9 / 1800, rel=1e-3)
    q = res["points"][0]
    assert q["ffc_per_hour"] == 0 and q["dead_time_pct"] == 0
    for pt in res["points"]:
        assert pt["worst_fpn_mK"] == max(v["worst_fpn_mK"] for v in pt["scenarios"].values())


def test_tiny_sweep_residual_against_the_golden_model_by_hand(tiny_sweep) -> None:
    """tcoffset14 at the scenario's last frame, recomputed here: the model's frames at that
    frame's FPA and housing, the golden model with that frame's reading, the spatial std
    over the good pixels, through the local responsivity (a central difference of the
    corrected means, written out here)."""
    import dataclasses

    from irnuc.model.sequence import load_sequence
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top
    from irnuc.nuc_fixed.plan import run_plan
    from irnuc.reports.studies import drift_common as dc

    spec, res = tiny_sweep
    sensor = spec.sensor()
    pts = run_plan(spec.plan(), sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    cal = calibrate_points(pts, load_pipeline("tcoffset14"))
    seq = load_sequence("fpa_ramp")
    sched = dataclasses.replace(seq, record_every=1).schedule()
    fields = sched.fields(seq.fpa_sensor, sensor.seed, seq.housing_sensor)
    i = sched.fpa_K.size - 1  # the last frame is a node
    good = ~cal.bad
    worst = 0.0
    for scene in spec.scene_K:
        raw, _ = dc.frames_at(sensor, float(sched.fpa_K[i]), float(sched.T_cam_K[i]),
                              [scene, scene - 0.5, scene + 0.5])
        y = method_top(raw, cal.coeffs, FrameInputs(
            reading=np.full(3, int(fields["fpa_reading"][i])))).y.astype(float)
        slope = (y[2][good].mean() - y[1][good].mean()) / 1.0
        worst = max(worst, 1e3 * y[0][good].std() / slope)
    trace = res["points"][0]["traces"]["fpa_ramp"]["trace"]
    last = trace[-1]
    assert last[0] == pytest.approx(float(sched.time_s[i]), abs=0.01)  # 4 digits kept
    assert last[1] == pytest.approx(worst, rel=1e-3)


def test_lepton_shaped_preset_and_its_report_configuration() -> None:
    """The outside check's camera: the Lepton's published figures (80 x 60, 17 um, f/1.1,
    27 Hz inside the core), its NETD under the datasheet's 50 mK, and the report
    configuration that compares policies around the Lepton's own (3 min or 1.5 C)."""
    from irnuc import model
    from irnuc.reports.report.config import load_report_config
    from irnuc.reports.studies import drift_common as dc

    c = model.load_preset("lepton")
    assert (c["fpa"]["active_cols"], c["fpa"]["active_rows"]) == (80, 60)
    assert c["fpa"]["pitch"] == 17e-6 and c["optics"]["f_number"] == 1.1
    assert c["readout"]["frame_rate"] == 27.0
    netd = dc.netd(dc.StudySensor(preset="lepton", rows=12, cols=16, seed=4), 298.0)
    assert 20.0 < netd.netd_K * 1e3 < 50.0
    t = load_report_config("lepton")["temperature"]
    assert t["preset"] == "lepton" and (t["rows"], t["cols"]) == (60, 80)
    assert [3.0, 1.5] in t["ffc_either"] and 1.5 in t["ffc_changes_K"]


def test_policies_sharing_corrected_frames_give_the_same_figures() -> None:
    """The sweep corrects a frame with a given FFC refresh once for all the policies of a
    calibration (``evaluate``'s ``memo``): each policy's figures equal those it gets alone,
    and the second policy reuses the first one's frames (the power-on FFC's at least)."""
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.plan import run_plan
    from irnuc.reports.studies import drift_common as dc

    spec = so.SignoffSpec(rows=6, cols=8, frac_bits=(12,), methods=("tcffc14",),
                          scene_K=(300.0, 340.0), housing_offset_K=(0.0,),
                          scenarios=("fpa_ramp",))
    sensor = spec.sensor()
    pts = run_plan(spec.plan(), sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    cal = calibrate_points(pts, load_pipeline("tcffc14"))
    tr = scn.trajectory("fpa_ramp", sensor, spec.scene_K, 0.5, 120.0)
    sc = dc.scale(sensor, cal.targets, sorted(set(pts.scene_K.tolist())))
    nf = int(cal.cfg.ffc_frames or 1)
    pols = [scn.Policy(period_min=0.25), scn.Policy(period_min=0.5), scn.Policy(change_K=0.2)]
    memo: dict = {}
    sizes = []
    for pol in pols:
        st = scn.ffc_starts(tr, pol, nf)
        alone = scn.evaluate(cal, tr, spec.scene_K, sc, ~cal.bad, pol, st, 24)
        before = len(memo.get("rows", {}))
        shared = scn.evaluate(cal, tr, spec.scene_K, sc, ~cal.bad, pol, st, 24, memo=memo)
        assert shared == alone
        sizes.append((before, len(memo["rows"]), alone["evaluated"]))
    # p0.5's FFCs are a subset of p0.25's: fewer new frames than it evaluates
    assert sizes[1][1] - sizes[1][0] < sizes[1][2]


# ---- the calibration plan covers the scenarios it judges -----------------------------------
def _span_by_hand(name: str) -> tuple[float, float, float, float, np.ndarray, np.ndarray]:
    """A scenario's FPA and housing - FPA extremes and its sensors' readings at the full
    frame rate, from its schedule (not through the sign-off)."""
    import dataclasses

    from irnuc.model.sequence import load_sequence

    seq = load_sequence(name)
    sched = dataclasses.replace(seq, record_every=1).schedule()
    fields = sched.fields(seq.fpa_sensor, 4, seq.housing_sensor)
    fpa, cam = np.asarray(sched.fpa_K), np.asarray(sched.T_cam_K)
    return (float(fpa.min()), float(fpa.max()), float((cam - fpa).min()),
            float((cam - fpa).max()), np.asarray(fields["fpa_reading"]),
            np.asarray(fields["housing_reading"]))


@pytest.mark.parametrize("quick", [False, True])
def test_the_signoff_plan_covers_every_scenarios_fpa_and_housing(quick) -> None:
    """A camera is calibrated over its operating range: the report's sign-off plan holds
    every shipped scenario's FPA and housing - FPA span (the ambient ramp's FPA at 263 K
    left the old fixed 288-308 K plan), and the reading ranges the sweep gives the methods
    hold every plan point's and every scenario frame's reading around the reference
    reading (none clamped). Fails if a scenario's FPA leaves the plan."""
    from irnuc.model.sequence import scenario_names
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.reports.report.config import load_report_config
    from irnuc.reports.report.phases.temperature import spec_of
    from irnuc.reports.studies.method_bits import with_range_bits

    spec = spec_of(load_report_config("default", quick=quick)["temperature"])
    assert set(spec.scenarios) == set(scenario_names())
    plan = spec.plan()
    ref = len(plan.fpa) // 2
    ranges = spec.range_bits()
    t_ref = int(plan.fpa_sensor.read(plan.fpa[ref])[0])
    h_ref = int(plan.housing_sensor.read(plan.fpa[ref])[0])
    for name in spec.scenarios:
        lo, hi, dlo, dhi, rd, hrd = _span_by_hand(name)
        assert plan.fpa[0] <= lo and hi <= plan.fpa[-1], (name, lo, hi, plan.fpa)
        assert plan.housing_offset[0] <= dlo and dhi <= plan.housing_offset[-1], name
        for cname in ("tcffc14", "tcgain14", "tchousing14"):
            cfg = with_range_bits(load_pipeline(cname), **ranges)
            lim = (1 << cfg.reading_range_bits) - 1
            assert np.abs(rd - t_ref).max() <= lim, (name, cname)
            if cfg.housing_range_bits:
                assert np.abs(hrd - h_ref).max() <= (1 << cfg.housing_range_bits) - 1
    # and the plan's own points (every FPA at every housing offset) within the ranges
    reads = plan.fpa_sensor.read(np.asarray(plan.fpa))
    assert np.abs(reads - t_ref).max() <= (1 << ranges["reading_range_bits"]) - 1
    # the middle point is the plan's reference and the points are evenly spaced
    assert plan.fpa[ref] == pytest.approx(0.5 * (plan.fpa[0] + plan.fpa[-1]))
    assert np.allclose(np.diff(plan.fpa), np.diff(plan.fpa)[0])


def test_a_plan_inside_its_fpa_k_when_the_scenarios_are() -> None:
    """fpa_ramp (293-295 K) lies inside 288-308 K: the plan is today's three points; the
    housing offsets widened to its housing - FPA (-3.8 .. -2 K) only where needed."""
    spec = so.SignoffSpec(rows=6, cols=8, scenarios=("fpa_ramp",), housing_offset_K=(-2.0, 0.0))
    plan = spec.plan()
    assert plan.fpa == (288.0, 298.0, 308.0)
    assert plan.housing_offset == (-4.0, 0.0)
    # +-10 K at 0.01 K (1000 codes) needs 10 bits: the shipped 11-bit ranges are kept
    assert spec.range_bits()["reading_range_bits"] == 10
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.reports.studies.method_bits import with_range_bits

    cfg = load_pipeline("tcffc14")
    assert with_range_bits(cfg, **spec.range_bits()) is cfg


def test_widening_a_reading_range_grows_the_polynomial_and_never_narrows() -> None:
    """One bit more of range halves v = u / 2^Ts: the linear coefficients gain one integer
    bit, the squared ones two; a narrower request or a method without the reading is left
    as shipped."""
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.reports.studies.method_bits import with_range_bits

    base = load_pipeline("tcgain14")
    wide = with_range_bits(base, reading_range_bits=13)
    ib = {f.name: f.int_bits for f in base.formats}
    iw = {f.name: f.int_bits for f in wide.formats}
    assert wide.reading_range_bits == 13 and base.reading_range_bits == 11
    assert (iw["tc1"] - ib["tc1"], iw["tc2"] - ib["tc2"]) == (2, 4)
    assert (iw["tg1"] - ib["tg1"], iw["tg2"] - ib["tg2"]) == (2, 4)
    assert {k: v for k, v in iw.items() if k not in ("tc1", "tc2", "tg1", "tg2")} == \
        {k: v for k, v in ib.items() if k not in ("tc1", "tc2", "tg1", "tg2")}
    assert with_range_bits(base, reading_range_bits=10) is base
    typ = load_pipeline("typical14")
    assert with_range_bits(typ, reading_range_bits=13, housing_range_bits=13) is typ
    h = with_range_bits(load_pipeline("tchousing14"), housing_range_bits=12)
    hb = {f.name: f.int_bits for f in load_pipeline("tchousing14").formats}
    hw = {f.name: f.int_bits for f in h.formats}
    assert (hw["th1"] - hb["th1"], hw["thx"] - hb["thx"], hw["th2"] - hb["th2"],
            hw["tc1"] - hb["tc1"]) == (1, 1, 2, 0)


def test_a_ramp_point_calibrated_on_the_covering_plan_is_read_inside_it() -> None:
    """tcffc14 on the ambient ramp (FPA from 263 K) with the sign-off's plan and ranges:
    a valid point whose record names the widened reading range; its ambient_ramp residual
    stays within a few NETD (1.13 K on the old 288-308 K plan, the reading clamped)."""
    from irnuc.nuc_fixed.plan import run_plan

    spec = so.SignoffSpec(rows=6, cols=8, methods=("tcffc14",), frac_bits=(14,),
                          ffc_periods_min=(), ffc_changes_K=(0.1,), ffc_either=(),
                          scenarios=("ambient_ramp",), node_K=1.0)
    sensor = spec.sensor()
    pts = run_plan(spec.plan(), sensor.preset, sensor.base_overrides(), seed=sensor.seed)
    tr = {"ambient_ramp": scn.trajectory("ambient_ramp", sensor, spec.scene_K, 1.0, 120.0)}
    starts = {("ambient_ramp", "t0.1", 8): scn.ffc_starts(tr["ambient_ramp"], spec.policies()[0],
                                                          8)}
    (p,) = so.method_points(spec.to_dict(), "tcffc14", pts, tr, starts, spec.range_bits())
    assert p["valid"] and p["range_bits"] == {"reading_range_bits": 12}
    assert p["worst_fpn_mK"] < 200.0
