"""The axis bulk harness (``cosim/harness/axis_main.cpp``, :mod:`irnuc.cosim.axis_bulk`):
``irnuc_axis_top`` with tc_offset + ffc (tcffc14) on a few tiny frames of the physics
model, the registers (FRAME_SIZE, CTRL, T_REF, READING per frame, FFC_CTRL) written over
AXI4-Lite, an FFC run through the FFC streams, idle inputs and back-pressure: bit-exact
against the golden model. Then the same RTL run against a golden model given other
readings than the registers carry, and a golden model without the FFC run: both must be
caught (the RTL is the independent reference of the golden model here).
"""

from __future__ import annotations

import dataclasses
import functools
from types import SimpleNamespace

import numpy as np
import pytest

from irnuc.cosim import axis_bulk as ab
from irnuc.nuc_fixed import load_pipeline

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


@functools.cache
def _setup():
    from irnuc import model
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan, sensor_config

    size = {"fpa.active_rows": 6, "fpa.active_cols": 8}
    pts = run_plan(CalibrationPlan(scene=(290.0, 330.0, 370.0), fpa=(288.0, 298.0, 308.0),
                                   frames=2), "default", size, seed=4)
    cfg = load_pipeline("tcffc14").replace(max_width=64, max_height=64)
    cal = calibrate_points(pts, cfg).coeffs

    def frame(k: int) -> np.ndarray:
        c = sensor_config("default", {**size, "environment.T_substrate": 295.0 + 0.5 * k,
                                      "environment.T_cam": 293.0, "noise.enabled": True})
        return model.simulate(c, [300.0 + 7 * k], seed=4, outputs=["codes"]).codes[0]

    raws = [frame(k) for k in range(14)]
    fields = {"fpa_reading": 6500 + 40 * np.arange(14), "housing_reading": np.full(14, 5000)}
    return cfg, cal, raws, fields, ab.build_axis(cfg)


def test_axis_harness_bit_exact_with_an_ffc_run_and_readings() -> None:
    _cfg, cal, raws, fields, bld = _setup()
    st = ab.axis_stimulus(cal, raws, fields, [2])
    # FFC_CTRL before frame 2: frames 2..9 shutter (held), 10 the refresh
    assert st.ffc_events == 1 and st.shown == 14 - 8
    kinds = {a for _, a, _ in st.writes}
    from irnuc.nuc_fixed.regmap import register_map

    m = register_map()
    assert {m["READING.LO"].offset, m["T_REF.LO"].offset, m["FFC_CTRL"].offset,
            m["FRAME_SIZE"].offset} <= kinds
    res = ab.run_axis(bld, st, seed=3, stall_percent=20, idle_percent=10)
    assert res["passed"], res["lines"]
    assert res["mismatches"] == 0 and res["pixels_compared"] == 6 * 6 * 8
    assert res["words_compared"] > 0 and res["register_writes"] == len(st.writes)


def test_axis_harness_catches_a_wrong_golden_model() -> None:
    _cfg, cal, raws, fields, bld = _setup()
    good = ab.axis_stimulus(cal, raws, fields, [2])
    # The golden model told other readings than the registers carry.
    other = ab.axis_stimulus(cal, raws, {**fields, "fpa_reading": fields["fpa_reading"] + 300},
                             [2])
    wrong = dataclasses.replace(good, want_video=other.want_video)
    res = ab.run_axis(bld, wrong, seed=3)
    assert not res["passed"] and res["mismatches"] > 0
    assert any("m_axis_video" in ln for ln in res["lines"])
    # The golden model without the FFC run expects frames the RTL holds: they never come
    # (the harness times out and every expected word counts as missing).
    no_ffc = ab.axis_stimulus(cal, raws, fields, [])
    wrong = dataclasses.replace(good, want_video=no_ffc.want_video)
    res = ab.run_axis(bld, wrong, seed=3)
    assert not res["passed"] and res["mismatches"] > 0 and "timeout" in res["lines"][0]


def test_axis_harness_refuses_what_it_cannot_drive() -> None:
    from irnuc.common.errors import UserError

    _cfg, _cal, raws, fields, _ = _setup()
    drift = load_pipeline("drift14")
    assert "blind_drift" in (ab.unsupported(drift) or "")
    assert ab.unsupported(load_pipeline("tcgain14")) is None
    assert "table_interp" in (ab.unsupported(load_pipeline("table14")) or "")
    with pytest.raises(UserError, match="drift14"):
        ab.axis_stimulus(SimpleNamespace(cfg=drift), raws, fields, [])
