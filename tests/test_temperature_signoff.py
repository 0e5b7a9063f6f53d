"""The report's Temperature section (issue 22): the sign-off's choosing logic against
hand-computed cases, its schema, its baseline comparison, its configuration errors, and one
method's sweep on a tiny sensor."""

from __future__ import annotations

import copy
import json

import jsonschema
import pytest

from irnuc.cli import main
from irnuc.reports.report.base import Report
from irnuc.reports.report.phases import temperature as tp
from irnuc.reports.report.sections import Section
from irnuc.reports.report.summary import SCHEMA_PATH, compare_baseline
from irnuc.reports.studies import signoff as so
from irnuc.reports.studies.hwcost import coefficient_memory


def _pt(i, config, mem, read, mk, period=None, frac=8, valid=True):
    # dead time as a shutter of 9 frames at 30 Hz every `period` minutes would cost
    dead = 0.0 if period is None else 100.0 * 9 / (period * 60 * 30)
    return {"index": i, "key": f"{config}_{i}", "config": config, "method": config, "frac_bits": frac,
            "valid": valid, "memory_bits": mem, "read_bits_per_frame": read, "worst_fpn_mK": mk,
            "worst_fpn_lsb": mk / 10, "ffc_period_min": period, "calibration_bits": mem,
            "runtime_bits": 0, "dead_time_pct": dead, "ffc_per_hour": 0 if period is None else 60 / period}


# ---- recommendation ---------------------------------------------------------------------------
def test_recommend_cheapest_memory_then_bandwidth_then_datapath_then_period() -> None:
    pts = [_pt(0, "a", 40, 40, 5.0), _pt(1, "b", 30, 30, 12.0),   # 1 misses the tolerance
           _pt(2, "c", 32, 50, 9.0), _pt(3, "d", 32, 40, 9.9),    # same memory: 3 reads less
           _pt(4, "e", 32, 40, 8.0, valid=False)]                 # invalid never chosen
    r = so.recommend(pts, 10.0)
    assert r == {"found": True, "index": 3, "candidates": [3, 2, 0]}
    # datapath breaks a tie in memory and bandwidth
    pts2 = [_pt(0, "a", 32, 40, 9.0), _pt(1, "b", 32, 40, 2.0)]
    assert so.recommend(pts2, 10.0)["index"] == 1  # lower residual without datapath
    assert so.recommend(pts2, 10.0, {0: 100.0, 1: 300.0})["index"] == 0
    # the least dead time among equals (here the longest FFC period); no shutter beats any
    pts3 = [_pt(0, "f", 64, 64, 3.0, 0.5), _pt(1, "f", 64, 64, 6.0, 2.0), _pt(2, "f", 64, 64, 5.0, 1.0)]
    assert so.recommend(pts3, 10.0)["candidates"] == [1, 2, 0]
    assert so.recommend([*pts3, _pt(3, "g", 64, 64, 9.0)], 10.0)["index"] == 3
    # nothing meets
    assert so.recommend(pts, 1.0) == {"found": False, "index": None, "candidates": []}


def test_choose_falls_back_to_lowest_residual_flagged() -> None:
    pts = [_pt(0, "a", 40, 40, 25.0, frac=8), _pt(1, "a", 48, 48, 22.0, frac=12),
           _pt(2, "b", 20, 20, 22.0, frac=8)]
    ch = tp.choose(pts, 10.0, [])
    assert ch["meets"] is False and ch["point"]["index"] == 2  # equal residual: less memory
    assert ch["candidates"] == []
    # the fallback at the widest width warns that more bits may help
    pts[1]["worst_fpn_mK"] = 21.0
    ch = tp.choose(pts, 10.0, [])
    assert ch["point"]["index"] == 1
    assert [(e["axis"], e["edge"]) for e in ch["edges"]] == [("frac_bits", "top")]
    ch = tp.choose(pts, 30.0, [])
    assert ch["meets"] is True and ch["point"]["index"] == 2


def test_grid_edges_hand_cases() -> None:
    pts = [_pt(i, "m", 10 + i, 10, 1.0, frac=f) for i, f in enumerate((6, 8, 10))]
    pts.append(_pt(3, "m", 99, 10, 1.0, frac=12, valid=False))  # invalid widths are not the grid
    edges = {(e["axis"], e["edge"]) for e in so.grid_edges(pts[0], pts, [])}
    assert edges == {("frac_bits", "bottom")}
    assert {(e["axis"], e["edge"]) for e in so.grid_edges(pts[2], pts, [])} == {("frac_bits", "top")}
    assert so.grid_edges(pts[1], pts, []) == []
    f = _pt(4, "n", 50, 50, 1.0, period=2.0, frac=8)
    g = _pt(5, "n", 50, 50, 1.0, period=0.5, frac=8)
    both = [f, g, _pt(6, "n", 60, 60, 1.0, period=2.0, frac=10)]
    assert {(e["axis"], e["edge"]) for e in so.grid_edges(f, both, [0.5, 1.0, 2.0])} == {
        ("frac_bits", "bottom"), ("ffc_periods_min", "top")}
    assert ("ffc_periods_min", "bottom") in {
        (e["axis"], e["edge"]) for e in so.grid_edges(g, both, [0.5, 1.0, 2.0])}
    # not meeting: only the ways that may lower the residual
    assert {(e["axis"], e["edge"]) for e in so.grid_edges(g, both, [0.5, 2.0], meets=False)} == {
        ("ffc_periods_min", "bottom")}


def test_pareto_fronts_hand_computed() -> None:
    # (memory, residual): a0 (10, 5) b1 (12, 3) c2 (12, 4) d3 (15, 3) e4 (20, 1) f5 (11, 9)
    pts = [_pt(0, "x", 10, 0, 5.0), _pt(1, "x", 12, 0, 3.0), _pt(2, "y", 12, 0, 4.0),
           _pt(3, "y", 15, 0, 3.0), _pt(4, "y", 20, 0, 1.0), _pt(5, "x", 11, 0, 9.0),
           _pt(6, "x", 5, 0, 0.5, valid=False)]
    fr = so.fronts(pts)
    assert fr["overall"] == [0, 1, 4]
    assert fr["per_method"] == {"x": [0, 1], "y": [2, 3, 4]}


def test_ffc_events_and_sawtooth_segments() -> None:
    assert so.ffc_events(288.0, 292.0, 1.5) == [288.0, 289.5, 291.0]
    segs = so.sawtooth_segments([288.0, 290.0, 292.0], [288.0, 289.5, 291.0], 292.0)
    # each refresh corrects its event's frame up to the frame on which the shutter closes
    assert segs == [(0, [288.0, 289.5]), (1, [289.5, 290.0, 291.0]), (2, [291.0, 292.0])]
    spec = so.SignoffSpec(fpa_K=(288.0, 290.5), fpa_step_K=1.0)
    assert spec.fpa_grid().tolist() == [288.0, 289.0, 290.0, 290.5]


def test_cost_prediction_moves_the_anchor_along_the_slopes() -> None:
    anchor = {k: 100.0 for k in tp.HW_KEYS} | {"fmax_mhz": 150.0, "xc7.dsp": 3.0}
    slopes = {"xc7.lut": (4.0, 2.0), "xc7.dsp": (0.0, -1.0), "fmax_mhz": (-0.5, 0.0)}
    got = tp.predict(anchor, (16, 18), (18, 15), slopes)
    assert got["xc7.lut"] == 100.0 + 4.0 * 2 + 2.0 * -3
    assert got["xc7.dsp"] == 6.0
    assert got["fmax_mhz"] == 149.0
    assert got["ecp5.lut4"] == 100.0  # no slope: unmoved
    assert tp.predict(anchor, (16, 18), (16, 0), {"xc7.ff": (0.0, 10.0)})["xc7.ff"] == 0.0  # clipped


def test_tolerance_from_netd_or_mK() -> None:
    assert tp.tolerance_mK({}, 20.0)[0] == pytest.approx(10.0)
    assert tp.tolerance_mK({"tolerance_netd": 1.5}, 20.0)[0] == pytest.approx(30.0)
    assert tp.tolerance_mK({"tolerance_mK": 7.0}, 20.0) == (7.0, "7 mK (tolerance_mK)")


# ---- summary: schema and baseline -------------------------------------------------------------
def _section() -> dict:
    rec = {"key": "typical14_f8", "config": "typical14", "method": "two_point", "frac_bits": 8,
           "widths": {"gain": "18 bits"}, "ffc_period_min": None, "worst_fpn_mK": 8.0,
           "worst_fpn_lsb": 1.2, "netd_mK": 20.0, "tolerance_mK": 10.0, "meets_tolerance": True,
           "memory_bits": 31, "bandwidth_MBps": 71.4, "edges": [], "pipeline": {},
           "memory": coefficient_memory(31, 480, 640), "synth": None,
           "cosim": {"frames": 20, "shape": [480, 640], "pixels_compared": 6144000, "mismatches": 0,
                     "passed": True, "source": "x", "seconds": 1.0, "ffc_events": 0}}
    pt = {**_pt(0, "typical14", 31, 31, 8.0), "per_fpa": [[288.0, 7.5], [308.0, 8.0]],
          "bandwidth_MBps": 71.4, "meets_tolerance": True, "hw": None, "datapath_cost": None}
    d = {"spec": {}, "points": [pt], "netd_mK": 20.0, "netd": {}, "tolerance_mK": 10.0,
         "tolerance": "0.5 x NETD", "noise_3d": {"components": {}}, "camera_temperature": {},
         "fronts": {"memory_bits": {}, "datapath_cost": None, "bandwidth_MBps": {}},
         "recommended": rec, "cost": None}
    return {**d, "verdict": tp.signoff_verdict(d).to_json()}


def _validator(name: str = "temperature"):
    schema = json.loads(SCHEMA_PATH.read_text())
    sub = {"$ref": f"#/$defs/{name}", "$defs": schema["$defs"]}
    return jsonschema.Draft202012Validator(sub)


def test_temperature_section_schema() -> None:
    v = _validator()
    v.validate(_section())
    bad = _section()
    del bad["recommended"]["cosim"]["mismatches"]
    with pytest.raises(jsonschema.ValidationError):
        v.validate(bad)
    with pytest.raises(jsonschema.ValidationError, match=r"(?s)'mismatches',.*On instance\['cosim'\]"):
        _validator("temperature_recommended").validate(bad["recommended"])
    bad = _section()
    bad["recommended"]["worst_fpn_mK"] = -1.0
    with pytest.raises(jsonschema.ValidationError):
        v.validate(bad)
    none = _section()
    none["recommended"] = None
    v.validate(none)
    assert "temperature" in json.loads(SCHEMA_PATH.read_text())["properties"]["phases"][
        "propertyNames"]["enum"]


def test_baseline_compares_the_temperature_metrics() -> None:
    base, now = Report(config={}, verbose=False), Report(config={}, verbose=False)
    tp.temperature_metrics(base, _section())
    worse = _section()
    worse["recommended"]["worst_fpn_mK"] = 9.0
    worse["recommended"]["cosim"]["mismatches"] = 3
    worse["recommended"]["cosim"]["passed"] = False
    worse["points"][0]["worst_fpn_mK"] = 8.5
    tp.temperature_metrics(now, worse)
    cmp = compare_baseline(now.metrics, base.metrics)
    regressed = {e["metric"] for e in cmp["regressions"]}
    assert regressed == {"temperature.recommended.worst_fpn_mK",
                         "temperature.recommended.cosim.mismatches",
                         "temperature.recommended.cosim.failed",
                         "temperature.point.typical14_0.worst_fpn_mK"}
    assert base.metrics["temperature.recommended.cosim.pixels"]["better"] == "info"
    same = Report(config={}, verbose=False)
    tp.temperature_metrics(same, copy.deepcopy(_section()))
    assert compare_baseline(same.metrics, base.metrics)["regressions"] == []


# ---- configuration ----------------------------------------------------------------------------
@pytest.mark.parametrize(("text", "match"), [
    ("[temperature]\nfpa_K = [308.0, 288.0]\n", "temperature.fpa_K = [308, 288]"),
    ('[temperature]\nmethods = ["typical41"]\n', "temperature.methods"),
    ("[temperature]\ntolerance_mK = 5.0\ntolerance_netd = 0.5\n", "set the tolerance one way"),
    ("[temperature]\nfrac_bit = [8]\n", "did you mean 'frac_bits'"),
    ('[temperature]\noverrides = { "environment.T_cam" = 300.0 }\n', "set by the sign-off"),
    ("[temperature]\nffc_periods_min = [0.0]\n", "temperature.ffc_periods_min[0]"),
])
def test_bad_temperature_config_is_a_clear_error(tmp_path, capsys, text, match) -> None:
    cfg = tmp_path / "bad.toml"
    cfg.write_text(text)
    assert main(["report", "--config", str(cfg), "--out", str(tmp_path / "o")]) == 2
    assert match in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_default_and_quick_temperature_sections() -> None:
    from irnuc.reports.report.config import load_report_config

    full = load_report_config("default")["temperature"]
    quick = load_report_config("default", quick=True)["temperature"]
    assert full["fpa_K"] == [288.0, 308.0] and full["ramp_K_per_min"] == 2.0
    assert (full["cosim_frames"], full["cosim_rows"], full["cosim_cols"]) == (20, 480, 640)
    assert len(quick["frac_bits"]) < len(full["frac_bits"])
    assert quick["cosim_frames"] >= 20


# ---- co-simulation of the recommendation -----------------------------------------------------
def _spec():
    return so.SignoffSpec(rows=6, cols=8, scenarios=("fpa_ramp",), methods=("typical14",))


def test_cosim_result_and_a_mismatch_fails_the_report(monkeypatch, tmp_path) -> None:
    from irnuc.reports.report.summary import make_summary

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path))
    seen = {}

    def fake(t, r, spec, cfg, shape, seed, scenario):
        seen.update(name=cfg.name, w=cfg.max_width, h=cfg.max_height, f=cfg.gain_frac_bits,
                    shape=shape, scenario=scenario)
        return {"frames": 20, "pixels_compared": 20 * shape[0] * shape[1], "mismatches": 2,
                "passed": False, "ffc_events": 0, "lines": ["m_axis_video: 2 of ... differ"]}

    monkeypatch.setattr(tp, "_cosim_run", fake)
    t = {"cosim_frames": 20, "cosim_rows": 12, "cosim_cols": 16, "cosim_seed": 3}
    c = tp._cosim(t, {"config": "typical14", "frac_bits": 9}, _spec())
    assert seen == {"name": "recommended_temperature", "w": 16, "h": 12, "f": 9,
                    "shape": (12, 16), "scenario": "power_on_warmup"}
    assert (c["pixels_compared"], c["mismatches"], c["passed"]) == (20 * 12 * 16, 2, False)
    assert c["top"] == "irnuc_axis_top" and not c["cached"]
    # the same run again comes from the cache (keyed by digest), not from the harness
    seen.clear()
    again = tp._cosim(t, {"config": "typical14", "frac_bits": 9}, _spec())
    assert again["cached"] and again["mismatches"] == 2 and seen == {}
    sec = _section()
    sec["recommended"]["cosim"] = c
    rep = Report(config={"name": "x"}, verbose=False)
    rep.sections["temperature"] = Section.of(sec)
    tp.temperature_metrics(rep, sec)
    s = make_summary(rep, [], None, None)
    assert s["status"] == "fail"
    assert any("temperature co-simulation: 2 pixel mismatch" in r for r in s["status_reasons"])


def test_method_the_axis_harness_cannot_drive_is_not_a_pass(monkeypatch, tmp_path) -> None:
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path))

    def never(*a, **kw):
        raise AssertionError("the harness must not run")

    monkeypatch.setattr(tp, "_cosim_run", never)
    t = {"cosim_frames": 2, "cosim_rows": 4, "cosim_cols": 4}
    c = tp._cosim(t, {"config": "drift14", "frac_bits": 8}, _spec())
    assert c["passed"] is None and c["mismatches"] is None and c["pixels_compared"] == 0
    assert "blind_drift" in c["not_run"]
    assert tp._cosim_check(c).status == "not run"
    rep = Report(config={}, verbose=False)
    sec = _section()
    sec["recommended"]["cosim"] = c
    _validator().validate(sec)
    tp.temperature_metrics(rep, sec)
    assert "temperature.recommended.cosim.mismatches" not in rep.metrics


def test_a_sweep_without_a_valid_point_fails_the_report() -> None:
    from irnuc.reports.report.summary import make_summary

    sec = _section()
    sec["points"] = [_pt(0, "piecewise14", 1, 1, 0.0, valid=False)]
    sec["recommended"] = None
    rep = Report(config={"name": "x"}, verbose=False)
    rep.sections["temperature"] = Section.of(sec)
    tp.temperature_metrics(rep, sec)
    s = make_summary(rep, [], None, None)
    assert s["status"] == "fail"
    assert any("no valid point" in r for r in s["status_reasons"])


def test_recommendation_synthesis_judges_the_model_on_the_bare_core(monkeypatch) -> None:
    """Wrapped in irnuc_axis_top, the recommendation's cost-model error is taken against the
    bare core at the same widths (what the model predicts), and the wrapper's share is
    stated on its own."""
    from irnuc.cosim import synth

    def figs(lut, ff, dsp, fmax):
        return {"xc7": {"lut": lut, "ff": ff, "dsp": dsp, "bram36": 1, "bram18": 0},
                "ecp5": {"lut4": lut + 10, "ff": ff + 20, "mult18": dsp, "dp16kd": 2},
                "fmax_mhz": fmax, "device": "LFE5U-85F", "speed": 6, "target_mhz": 150.0}

    tops, asked = [], []

    def fake(cfg, *, top=None, **kw):
        tops.append(top)
        asked.append(kw)
        return figs(2000, 3000, 8, 140.0) if top == "irnuc_axis_top" else figs(900, 1700, 8, 160.0)

    monkeypatch.setattr(synth, "synth_seeds", fake)
    prepared = []
    monkeypatch.setattr(synth, "prepare_netlists",
                        lambda designs, **kw: prepared.append([t for _, t in designs]) or 0)
    pred = {"source": "model", "xc7.lut": 950.0, "xc7.ff": 1650.0, "xc7.dsp": 8.0,
            "xc7.bram36": 1.0, "ecp5.lut4": 960.0, "ecp5.ff": 1720.0, "ecp5.mult18": 8.0,
            "ecp5.dp16kd": 2.0, "fmax_mhz": 150.0}
    r = {"config": "tcgain14", "frac_bits": 12, "hw": pred}
    tp._synth_recommended({}, r)
    sy = r["synth"]
    assert tops == ["irnuc_axis_top", "method_dpc_top"]
    # both netlists made side by side before the placements
    assert prepared[0] == ["irnuc_axis_top", "method_dpc_top"]
    # Both placed at the default seeds on the default workers; {"synth_seeds": 2} asks 2.
    assert asked == [{"seeds": 4, "workers": 2}] * 2
    tp._synth_recommended({"synth_seeds": 2, "workers": 1}, {**r})
    assert asked[2:] == [{"seeds": 2, "workers": 1}] * 2
    assert sy["top"] == "irnuc_axis_top" and sy["core"]["top"] == "method_dpc_top"
    assert sy["prediction_error"]["xc7.lut"] == 50.0 and sy["prediction_error"]["xc7.ff"] == -50.0
    assert sy["prediction_error"]["fmax_mhz"] == -10.0
    assert sy["wrapper_overhead"]["xc7.lut"] == 1100.0 and sy["wrapper_overhead"]["fmax_mhz"] == -20.0


def test_fmax_note_only_below_the_target() -> None:
    """A recommendation synthesized below its target frequency gets a note naming the top,
    the figure and the target; at or above it, or without a target, none. Over a seed
    sweep: a note when the best seed misses, or when some seeds do."""
    from irnuc.cosim.synth import best_of_seeds
    from irnuc.reports.report.phases.temperature import fmax_note

    below = {"top": "irnuc_axis_top", "fmax_mhz": 148.04, "target_mhz": 150.0}
    assert fmax_note(below) == (
        "temperature: the recommendation's irnuc_axis_top reaches 148.0 MHz, below the 150 MHz "
        "target, at this placer seed (irnuc synth --seeds N tries others)")
    assert fmax_note({**below, "fmax_mhz": 150.0}) is None
    assert fmax_note({**below, "target_mhz": None}) is None
    assert fmax_note({}) is None

    def sweep(*fmax):
        runs = [{"seed": i + 1, "fmax_mhz": f, "top": "irnuc_axis_top", "xc7": {}, "ecp5": {},
                 "config_digest": "d", "target_mhz": 150.0} for i, f in enumerate(fmax)]
        return best_of_seeds(runs)

    assert fmax_note(sweep(151.0, 160.2, 150.0, 155.5)) is None
    assert fmax_note(sweep(145.0, 148.7, 138.2, 141.0)) == (
        "temperature: the recommendation's irnuc_axis_top reaches 148.7 MHz at the best of 4 "
        "placer seeds (seed 2; worst 138.2), below the 150 MHz target")
    assert fmax_note(sweep(151.0, 160.2, 142.84, 155.5)) == (
        "temperature: the recommendation's irnuc_axis_top reaches 160.2 MHz at the best of 4 "
        "placer seeds (seed 2) but 142.8 at seed 3: 3 of 4 placements meet the 150 MHz target")


def test_too_few_cosimulated_pixels_do_not_meet_the_sign_off() -> None:
    c = {"passed": True, "mismatches": 0, "pixels_compared": 999_999, "min_pixels": 1_000_000,
         "top": "irnuc_axis_top"}
    chk = tp._cosim_check(c)
    assert chk.status == "not met" and "fewer than the 1000000" in chk.detail
    assert tp._cosim_check({**c, "pixels_compared": 1_000_000}).status == "met"


def test_a_wrapper_that_does_not_fit_the_pins_is_not_tried_on_them_again(tmp_path,
                                                                          monkeypatch) -> None:
    """nextpnr's "no BELs remaining ... TRELLIS_IO" for the wrapper on the package's pins:
    placed out of context (the bare core too), and remembered for that design, so that a
    second (warm) report goes out of context at once; another design is tried on pins."""
    from irnuc.cosim import synth

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    calls = []

    def fake(cfg, *, top=None, **kw):
        calls.append((top, bool(kw.get("out_of_context"))))
        if top == "irnuc_axis_top" and not kw.get("out_of_context"):
            raise synth.SynthError("nextpnr-ecp5 failed (exit 255)\nERROR: Unable to place cell "
                                   "'x$tr_io', no BELs remaining to implement cell type "
                                   "'TRELLIS_IO'")
        return {"xc7": {"lut": 1, "ff": 1, "dsp": 0, "bram36": 0, "bram18": 0},
                "ecp5": {"lut4": 1, "ff": 1, "mult18": 0, "dp16kd": 0}, "fmax_mhz": 160.0,
                "target_mhz": 150.0}

    monkeypatch.setattr(synth, "synth_seeds", fake)
    monkeypatch.setattr(synth, "prepare_netlists", lambda designs, **kw: 0)
    r = {"config": "tcffc14", "frac_bits": 16, "hw": None}
    tp._synth_recommended({}, r)
    # the wrapper on pins first; then the wrapper and the core out of context, side by side
    assert calls[0] == ("irnuc_axis_top", False)
    assert sorted(calls[1:]) == [("irnuc_axis_top", True), ("method_ffc_top", True)]
    assert r["synth"]["out_of_context"] and "out of context" in r["synth"]["why"]
    first = dict(r["synth"])
    calls.clear()
    tp._synth_recommended({}, r)  # warm: straight out of context, the same result
    assert sorted(calls) == [("irnuc_axis_top", True), ("method_ffc_top", True)]
    assert r["synth"] == first
    calls.clear()
    tp._synth_recommended({}, {"config": "tcffc14", "frac_bits": 12, "hw": None})
    assert calls[0] == ("irnuc_axis_top", False)  # another design: tried on pins


def test_a_netlist_that_fails_is_said_by_its_top_not_raised(monkeypatch) -> None:
    """Yosys failing on the wrapper while both netlists are prepared: the recommendation's
    synthesis is "not placed" with the top's own error (the fmax check not met), as when each
    top made its netlist itself; the report goes on."""
    from irnuc.cosim import synth

    def prepare(designs, **kw):
        raise synth.SynthError("yosys failed on irnuc_axis_top")

    def seeds(cfg, *, top=None, **kw):
        raise synth.SynthError(f"yosys failed on {top}\nlog ...")

    monkeypatch.setattr(synth, "prepare_netlists", prepare)
    monkeypatch.setattr(synth, "synth_seeds", seeds)
    r = {"config": "tcgain14", "frac_bits": 12, "hw": None}
    tp._synth_recommended({}, r)
    assert r["synth"]["error"] == "yosys failed on irnuc_axis_top"
    assert tp._fmax_check(r["synth"]).status == "not met"


# ---- time: what --quick leaves out, work started beside the phases (issue 37 item 6) --------
def test_quick_leaves_out_the_anchors_and_seeds_and_says_so(monkeypatch) -> None:
    """--quick synthesizes no anchor and places the recommendation at one seed; the default
    keeps both (anchors on, 4 seeds). Left out is named "not run in --quick" in the notes,
    and no anchor synthesis is asked for."""
    from irnuc.cosim import synth
    from irnuc.reports.report.config import load_report_config

    full = load_report_config("default")["temperature"]
    quick = load_report_config("default", quick=True)["temperature"]
    assert tp.setting(full, "anchors") is True and tp.setting(full, "synth_seeds") == 4
    assert quick["anchors"] is False and quick["synth_seeds"] == 1
    assert tp.anchor_configs(quick) == []
    assert [c.name for c in tp.anchor_configs(full)] == list(tp.spec_of(full).methods)

    def no_synth(*a, **k):
        raise AssertionError("an anchor was synthesized in --quick")

    monkeypatch.setattr(synth, "synth_configs", no_synth)
    rep = Report(config={"quick": True, "temperature": quick})
    d = {"points": [_pt(0, "typical14", 10, 10, 5.0)]}
    tp._cost_points(rep, quick, d, None, False)
    assert d["cost"] is None
    assert rep.notes and rep.notes[0].startswith("temperature: not run in --quick: the methods' "
                                                  "anchor syntheses")
    # the same key outside --quick names the key instead
    rep2 = Report(config={"temperature": {"anchors": False}})
    tp._cost_points(rep2, {"anchors": False}, {"points": []}, None, False)
    assert "not run (temperature.anchors = false)" in rep2.notes[0]


def test_background_job_runs_beside_and_is_joined_before_use() -> None:
    """start_background runs the work in a thread (the caller goes on), join waits for it
    and records when it ran; a failure is recorded, not raised (the phase redoes the work
    and reports its own error); close waits for every job."""
    import threading

    rep = Report(config={}, verbose=False)
    gate, done = threading.Event(), []
    rep.start_background("a", lambda: (gate.wait(10), done.append(1)))
    assert done == []                     # the caller was not held
    gate.set()
    rec = rep.join_background("a")
    assert done == [1] and rec["end_s"] >= rec["start_s"] and "error" not in rec
    assert rep.join_background("a") is None and rep.join_background("never") is None

    def boom() -> None:
        raise RuntimeError("no yosys\nmore")

    rep.start_background("b", boom)
    rep.start_background("c", lambda: done.append(2))
    rep.close_background()
    assert rep.background["b"]["error"] == "RuntimeError: no yosys"
    assert done == [1, 2] and rep._jobs == {}


def test_anchors_prefetched_in_the_background_then_read_by_the_phase(monkeypatch) -> None:
    """The report starts the anchors' syntheses (one worker) before its first phase; the
    Temperature phase asks for the same configurations on its own workers (the designs
    the background has not made yet are shared out: each cache entry is locked while
    made) and joins the job before it goes on."""
    from irnuc.cosim import synth

    calls = []

    def fake(cfgs, *, workers=2, scheduler=None, progress=None):
        calls.append(([c.name for c in cfgs], workers))
        return [{"xc7": {"lut": 1, "ff": 1, "dsp": 0, "bram36": 0, "bram18": 0},
                 "ecp5": {"lut4": 1, "ff": 1, "mult18": 0, "dp16kd": 0}, "fmax_mhz": 200.0,
                 "cached": len(calls) > 1} for _ in cfgs]

    monkeypatch.setattr(synth, "synth_configs", fake)
    t = {"methods": ["typical14", "ffc14"]}
    rep = Report(config={"temperature": t}, verbose=False)
    rep.start_background("anchors", tp.prefetch_anchors, t, None)
    d = {"points": [_pt(0, "typical14", 10, 10, 5.0), _pt(1, "ffc14", 12, 10, 4.0)]}
    for p in d["points"]:
        p.update(gain_bits=16, offset_bits=16)
    tp._cost_points(rep, t, d, None, False)
    assert sorted(calls, key=lambda c: c[1]) == [(["typical14", "ffc14"], 1),
                                                 (["typical14", "ffc14"], 2)]
    assert "end_s" in rep.background["anchors"] and "anchors" not in rep._jobs
    assert set(d["cost"]["anchors"]) == {"typical14", "ffc14"}


def test_the_recommendation_keeps_the_reading_range_the_plan_needed() -> None:
    """A point calibrated with a widened reading range (the plan covering the scenarios) is
    synthesized and co-simulated with that range: the recommendation record keeps
    ``range_bits`` and point_config rebuilds the same configuration (the report stopped at
    the axis co-simulation's calibration when it did not)."""
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.reports.studies.method_bits import with_frac_bits, with_range_bits

    p = {**_pt(0, "tcffc14", 500, 100, 30.0, frac=12), "range_bits": {"reading_range_bits": 12},
         "formats": {}, "gain_bits": 16, "offset_bits": 16}
    r = tp._recommended({"point": p, "meets": False, "candidates": [], "edges": []}, 15.0, 31.0,
                        so.SignoffSpec(rows=6, cols=8, scenarios=("fpa_ramp",)))
    cfg = tp.point_config(r, 12, 16)
    want = with_range_bits(with_frac_bits(load_pipeline("tcffc14"), 12), reading_range_bits=12)
    assert cfg.reading_range_bits == 12
    assert {f.name: (f.int_bits, f.frac_bits) for f in cfg.formats} == \
        {f.name: (f.int_bits, f.frac_bits) for f in want.formats}
    assert r["pipeline"]["reading_range_bits"] == 12
    # a point that needed none keeps the shipped range
    q = {k: v for k, v in p.items() if k != "range_bits"}
    assert tp.point_config(q).reading_range_bits == 11


def test_the_core_is_placed_beside_the_wrapper_once_its_pins_are_known(tmp_path,
                                                                      monkeypatch) -> None:
    """At one seed (--quick) a wrapper placement alone leaves a core idle: the bare core's
    placement starts as soon as the wrapper's pin question is answered (here: it does not
    fit, found at its first placement on pins), while the wrapper is still being placed
    out of context. Sequential placements would deadlock below (the wrapper's placement
    waits for the core's to start) and fail on the timeout."""
    import threading

    from irnuc.cosim import synth

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    core_started = threading.Event()
    order = []

    def fake(cfg, *, top=None, **kw):
        ooc = bool(kw.get("out_of_context"))
        if top == "irnuc_axis_top" and not ooc:
            raise synth.SynthError("ERROR: no BELs remaining to implement cell type 'TRELLIS_IO'")
        if top == "irnuc_axis_top":
            assert core_started.wait(20), "the core was not placed beside the wrapper"
        else:
            core_started.set()
        order.append((top, ooc))
        return {"xc7": {"lut": 1, "ff": 1, "dsp": 0, "bram36": 0, "bram18": 0},
                "ecp5": {"lut4": 1, "ff": 1, "mult18": 0, "dp16kd": 0},
                "fmax_mhz": 150.0 if top == "irnuc_axis_top" else 170.0, "target_mhz": 150.0}

    monkeypatch.setattr(synth, "synth_seeds", fake)
    monkeypatch.setattr(synth, "prepare_netlists", lambda designs, **kw: 0)
    r = {"config": "tcffc14", "frac_bits": 16, "hw": None}
    tp._synth_recommended({"synth_seeds": 1}, r)
    assert order == [("method_ffc_top", True), ("irnuc_axis_top", True)]
    assert r["synth"]["fmax_mhz"] == 150.0 and r["synth"]["core"]["fmax_mhz"] == 170.0
    assert r["synth"]["out_of_context"]
