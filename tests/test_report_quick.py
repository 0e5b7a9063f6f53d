"""`irnuc report --quick`'s content cuts (issue 37 item 6: <= 3 min cold): each one only in
the quick run, each named "not run in --quick: ..." in the notes (never a check), the
default run's content unchanged; and the sign-off made in the background when no anchor
synthesis runs there."""

from __future__ import annotations

import json
from html import unescape
from pathlib import Path

import jsonschema

from irnuc.reports.report.base import Report
from irnuc.reports.report.config import load_report_config, quick_replaced
from irnuc.reports.report.phases import paper as pp
from irnuc.reports.report.phases import precision as pr
from irnuc.reports.report.phases import sweep as sw
from irnuc.reports.report.phases import temperature as tp
from irnuc.reports.studies.precision.studies import COMPONENTS

#: What the quick run keeps of the precision study (the radiance group and the stiffest
#: transient problem), written here independently of the configuration.
QUICK_PRECISION = {"band_radiance", "band_radiance_narrow", "transient_stiff_1e7"}


def test_the_cuts_are_quick_overrides_and_the_default_keeps_its_content() -> None:
    full = load_report_config("default")
    quick = load_report_config("default", quick=True)
    # the default run: the full paper frame, every precision component, 4 fit points and 3
    # candidates, the recommendation placed at 4 seeds with its anchors
    assert (full["paper"]["rows"], full["paper"]["cols"]) == (480, 640)
    assert "components" not in full["precision"]
    assert (full["synth"]["fit_points"], full["synth"]["candidates"]) == (4, 3)
    t = full["temperature"]
    assert tp.setting(t, "place") is True and tp.setting(t, "anchors") is True
    assert tp.setting(t, "synth_seeds") == 4
    assert "quick_overrides" not in full and not quick_replaced(full, "paper.rows")[0]
    # the quick run: the cuts, each with what it replaced
    assert (quick["paper"]["rows"], quick["paper"]["cols"]) == (120, 160)
    assert quick["synth"]["fit_points"] == 3 and quick["synth"]["candidates"] == 1
    assert quick["temperature"]["place"] is False
    assert quick_replaced(quick, "paper.rows") == (True, 480)
    assert quick_replaced(quick, "synth.candidates") == (True, 3)
    assert quick_replaced(quick, "precision.components") == (True, None)
    assert quick_replaced(quick, "temperature.place") == (True, None)
    assert quick_replaced(quick, "sweep.seed") == (False, None)  # not overridden


def test_each_quick_cut_is_named_in_the_notes_and_the_default_names_none() -> None:
    quick = load_report_config("default", quick=True)
    rep = Report(config=quick, verbose=False)
    pp.quick_notes(rep)
    pr.quick_notes(rep)
    sw._quick_synth_notes(rep)
    d: dict = {}
    tp._synth_left_out(rep, quick["temperature"], d)
    assert all(n.split(": ", 2)[1] == "not run in --quick" for n in rep.notes), rep.notes
    by = {n.split(":", 1)[0]: [] for n in rep.notes}
    for n in rep.notes:
        by[n.split(":", 1)[0]].append(n)
    assert set(by) == {"paper", "precision", "synth", "temperature"}
    assert "at the full run's 480 x 640 frame; run at 120 x 160" in by["paper"][0]
    skipped = [n for n in COMPONENTS if n not in QUICK_PRECISION]
    assert len(skipped) == len(COMPONENTS) - 3
    assert f"{len(skipped)} of the study's components ({', '.join(skipped)})" in by["precision"][0]
    assert "1 of the cost model's 4 fit syntheses: fitted on 3 points" in by["synth"][0]
    assert "past the first 1 (the full run synthesizes 3)" in by["synth"][1]
    assert by["temperature"] == [f"temperature: not run in --quick: {tp.NOT_PLACED}"]
    assert d["left_out"] == [tp.NOT_PLACED]
    # the default run: nothing named (nothing left out)
    full = load_report_config("default")
    rep = Report(config=full, verbose=False)
    pp.quick_notes(rep)
    pr.quick_notes(rep)
    sw._quick_synth_notes(rep)
    tp._synth_left_out(rep, full["temperature"], {})
    assert rep.notes == []


def _area(top: str) -> dict:
    return {"top": top, "xc7": {"lut": 900, "ff": 800, "dsp": 2, "bram18": 0, "bram36": 1,
                                "lutram": 0},
            "ecp5": {"lut4": 1000, "ff": 850, "mult18": 2, "dp16kd": 2, "lutram": 0,
                     "ccu2c": 10}, "device": "LFE5U-85F", "config_digest": "x", "cached": False}


def _synth_schema() -> list:
    """The summary schema's alternatives for the Temperature recommendation's synthesis."""
    from irnuc.reports.report import summary

    schema = json.loads((Path(summary.__file__).with_name("summary.schema.json")).read_text())

    def walk(o):
        if isinstance(o, dict):
            if any(isinstance(v, dict) and "not_placed" in v.get("required", [])
                   for v in o.get("oneOf", [])):
                return o
            for v in o.values():
                if (f := walk(v)) is not None:
                    return f
        elif isinstance(o, list):
            for v in o:
                if (f := walk(v)) is not None:
                    return f
        return None

    found = walk(schema)
    assert found is not None, "no schema for an unplaced synthesis"
    return found


def test_place_false_synthesizes_the_wrapper_for_area_only_and_fmax_is_not_checked(
        monkeypatch) -> None:
    from irnuc.cosim import synth

    asked = []

    def area(cfg, top):
        asked.append(top)
        return _area(top)

    def no_place(*a, **k):
        raise AssertionError("placed although place = false")

    monkeypatch.setattr(tp, "synth_area", area)
    monkeypatch.setattr(synth, "synth_seeds", no_place)
    monkeypatch.setattr(synth, "prepare_netlists", no_place)
    r = {"config": "tcffc14", "frac_bits": 12, "hw": None}
    tp._synth_recommended({"place": False}, r)
    s = r["synth"]
    assert asked == ["irnuc_axis_top"]            # the wrapper only, no bare core
    assert s["placed"] is False and s["fmax_mhz"] is None and s["xc7"]["lut"] == 900
    jsonschema.validate(s, _synth_schema())
    check = tp._fmax_check(s)
    assert check.status == "not run" and "not placed" in check.detail
    assert tp.fmax_note(s) is None
    # a met residual with an unplaced wrapper: met, the fmax named as not checked
    d = {"tolerance_mK": 20.0, "tolerance": "0.5 x NETD = 20 mK",
         "recommended": {"key": "k", "worst_fpn_mK": 10.0, "meets_tolerance": True,
                         "scenarios": {"a": {}}, "synth": s,
                         "cosim": {"passed": True, "mismatches": 0, "pixels_compared": 10,
                                   "min_pixels": 10, "top": "irnuc_axis_top"}}}
    v = tp.signoff_verdict(d)
    assert v.verdict == "met" and "not checked: fmax" in v.reason
    # place = true (the default): placed, not the area-only path
    placed = []

    def seeds(cfg, *, top=None, **kw):
        placed.append(top)
        return {**_area(top), "fmax_mhz": 160.0, "target_mhz": 150.0}

    monkeypatch.setattr(synth, "synth_seeds", seeds)
    monkeypatch.setattr(synth, "prepare_netlists", lambda designs, **kw: 0)
    monkeypatch.setattr(tp, "synth_area", no_place)
    r = {"config": "tcffc14", "frac_bits": 12, "hw": None}
    tp._synth_recommended({}, r)
    assert sorted(placed) == ["irnuc_axis_top", "method_ffc_top"]
    assert r["synth"]["fmax_mhz"] == 160.0 and "placed" not in r["synth"]
    assert tp._fmax_check(r["synth"]).status == "met"


#: The smallest sign-off (8 x 8 study sensor, two methods, one width, one scenario).
TINY_T = {"rows": 8, "cols": 8, "fpa_step_K": 10.0, "scene_K": [300.0, 360.0],
          "methods": ["typical14", "ffc14"], "frac_bits": [8], "ffc_periods_min": [5.0],
          "ffc_changes_K": [0.5], "ffc_either": [], "scenarios": ["fpa_ramp"],
          "noise_frames": 4, "workers": 0, "anchors": False, "place": False}


def test_the_signoff_is_made_in_the_background_when_no_anchor_runs_there(tmp_path,
                                                                         monkeypatch) -> None:
    """Without anchors the report starts the sign-off's study at once in the background,
    then its recommendation's synthesis and axis build (cached); the phase reads the study
    and says it was made by this run (not cached). With anchors the background holds
    them, not the sign-off."""
    from irnuc.reports.report.run import build_report
    from irnuc.reports.studies import signoff as so

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    made: list = []
    monkeypatch.setattr(tp, "synth_area",
                        lambda cfg, top: made.append(("area", top, cfg.name)) or _area(top))
    monkeypatch.setattr(tp, "_prefetch_axis_build", lambda t, r: made.append(("axis", r["key"])))
    monkeypatch.setattr(tp, "_cosim", lambda t, r, spec: made.append(("cosim", r["key"]))
                        or {"cached": False})
    t = dict(TINY_T)
    assert tp.prefetch_signoff(t, None) == {"study": True, "cosim": True}
    assert so.cache_file(tp.spec_of(t)).is_file()
    keys = [m[1] for m in made if m[0] == "axis"]
    assert len(keys) == 1 and ("area", "irnuc_axis_top", "recommended_temperature") in made
    assert ("cosim", keys[0]) in made                # after its build, the same point
    assert made.index(("cosim", keys[0])) > made.index(("axis", keys[0]))
    assert tp.prefetch_signoff(t, None)["study"] is False    # the study was in the cache

    # the phase reads it; made by this run's background job, it is not "cached"
    for made_here in (True, False):
        rep = Report(config={"temperature": {**t, "cosim": False}}, verbose=False)
        rep.start_background("sign-off", lambda v=made_here: {"study": v, "cosim": False})
        tp.phase_temperature(rep, None, False)
        sec = rep.sections["temperature"]
        assert sec["cached"] is (not made_here)
        assert sec["recommended"]["synth"]["placed"] is False
        assert sec["recommended"]["key"] in keys
    # an unplaced recommendation is a valid summary and renders ("not run" Fmax)
    from irnuc.reports.report.render import render_report
    from irnuc.reports.report.summary import make_summary, validate_summary

    summary = make_summary(rep, [], None, None)
    validate_summary(summary)
    assert {c["name"]: c["status"] for c in summary["signoff"]["checks"]}["fmax"] == "not run"
    html = unescape(render_report(rep, summary))
    assert "synthesized for area, not placed" in html and f"not run: {tp.NOT_PLACED}" in html

    # the report: which job it starts at once (the phases themselves stubbed)
    started = []
    monkeypatch.setattr(Report, "start_background",
                        lambda self, name, fn, *a: started.append(name))
    monkeypatch.setattr(tp, "phase_temperature", lambda rep, s, p: None)
    from irnuc.reports.report.phases import cosim as cp

    monkeypatch.setattr(cp, "phase_cosim", lambda *a: None)
    build_report({"temperature": t}, out=tmp_path / "out", progress=False)
    assert started == ["sign-off"]
    started.clear()
    build_report({"temperature": {**t, "anchors": True, "synth": True}}, out=tmp_path / "o2",
                 progress=False)
    assert started == ["anchors"]
