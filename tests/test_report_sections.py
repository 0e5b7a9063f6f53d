"""The report's typed results (reports/report/sections.py): read-only, replaced and never
changed in place, their JSON the mapping they were made from, read by the page's templates
and code by name."""

from __future__ import annotations

import dataclasses
import json

import pytest

from irnuc.reports.report.sections import (
    CosimCheck,
    CosimSection,
    Recommendation,
    Section,
    SweepSection,
    SynthCheck,
    thaw,
)

_REC = {"index": 3, "label": "g14 o4", "bits_per_pixel": 33, "err_max_lsb": 0.4,
        "edges": [{"axis": "gain_frac_bits", "edge": "top", "widen": "add"}],
        "pipeline": {"name": "recommended", "formats": {}}, "cosim": None, "synth": None}
_SWEEP = {"frame": [12, 16], "points": [{"index": 0, "hw": None}, {"index": 3, "hw": None}],
          "tolerance": {"metric": "err_max_lsb", "max_error": 0.5}, "axes": {"a": [1, 2]}}


def _sweep() -> SweepSection:
    return SweepSection.of(_SWEEP, recommended=Recommendation.of(_REC))


def test_the_json_is_the_mapping_the_section_was_made_of() -> None:
    s = _sweep()
    got = json.loads(json.dumps(s.to_json()))
    assert got == {**_SWEEP, "recommended": _REC}
    # The fields a later phase sets appear once set, and only then.
    assert "synth" not in got and "datapath_cost" not in got["recommended"]


def test_nothing_is_changed_in_place() -> None:
    s = _sweep()
    with pytest.raises(TypeError):
        s["tolerance"]["metric"] = "x"  # type: ignore[index]
    with pytest.raises(TypeError):
        s.points[0]["hw"] = {}  # type: ignore[index]
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.recommended = None  # type: ignore[misc]
    assert isinstance(s["points"], tuple) and isinstance(s.recommended["edges"], tuple)


def test_a_later_phase_makes_a_new_section() -> None:
    s = _sweep()
    check = CosimCheck(passed=2, failed=0, pixels=960, mismatches=0, tests=("a", "b"))
    synth = SynthCheck(fmax_mhz=150.5, xc7={"lut": 600}, ecp5={"lut4": 700}, device="85k",
                       speed=6, target_mhz=150.0, critical_path=())
    rec = dataclasses.replace(s.recommended, cosim=check, synth=synth, datapath_cost=812.0)
    s2 = dataclasses.replace(s, recommended=rec, synth={"fit_indices": [0]},
                             pareto_memory=(0, 3))
    assert s.recommended.cosim is None and "synth" not in s  # the old one is unchanged
    j = s2.to_json()
    assert j["recommended"]["cosim"] == {"passed": 2, "failed": 0, "pixels": 960,
                                         "mismatches": 0, "tests": ["a", "b"]}
    assert j["recommended"]["synth"]["xc7"] == {"lut": 600}
    assert j["recommended"]["datapath_cost"] == 812.0 and j["pareto_memory"] == [0, 3]
    assert j["synth"] == {"fit_indices": [0]}
    # Read by name as the page reads it, typed or not.
    assert s2["recommended"]["cosim"]["passed"] == 2 and s2["frame"][1] == 16
    assert s2.get("nothing", 7) == 7 and "axes" in s2 and "pareto_datapath" not in s2


def test_the_templates_read_fields_and_data_with_dots() -> None:
    from irnuc.reports.report.render import environment

    check = CosimCheck(passed=1, failed=1, pixels=10, mismatches=3, tests=("t",))
    s = dataclasses.replace(_sweep(), recommended=dataclasses.replace(
        Recommendation.of(_REC), cosim=check))
    c = CosimSection.of({"tests": 2, "passed": 1, "failed": 1, "error": 0, "cases": []})
    tpl = environment().from_string(
        "{{ s.sweep.recommended.cosim.mismatches }} {{ s.sweep.frame[0] }} "
        "{{ s.sweep.recommended.bits_per_pixel }} {{ s.cosim.failed }} {{ s.cosim.cases|length }}")
    assert tpl.render(s={"sweep": s, "cosim": c}) == "3 12 33 1 0"


def test_a_section_of_plain_data() -> None:
    sec = Section.of({"a": [1, {"b": 2}]})
    assert thaw(sec) == {"a": [1, {"b": 2}]} and sec["a"][1]["b"] == 2
