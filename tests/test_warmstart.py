"""The predicted (warm-started) electro-thermal solve: same tolerance as the cold solve,
against mpmath, whatever was solved before, with every fallback path exercised."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from irnuc import model
from irnuc.model.core import bolometer as kb
from irnuc.model.pipeline import Pipeline


def _cfg(**over):
    # The predicted (warm-started) solve is the self-heating-factor pulse model's
    # (bolometer.pulse = "self_heating"); the integrated pulse train has its own tests
    # (tests/test_pulse.py).
    base = {"fpa.active_rows": 16, "fpa.active_cols": 20, "fpa.defects": {},
            "fpa.tolerance": {"R_ref": 3e-3, "g": 5e-3, "C": 5e-3},
            "bolometer.pulse": "self_heating"}
    return model.load_preset("default", {**base, **over})


def _mp_root(Q, R_ref, g, C, cfg, T_s):
    """dT of dT = a + b R(T_s + dT) at 40 digits (paper eq. 16-19), from the parameters."""
    mpmath.mp.dps = 40
    b = cfg["bolometer"]
    u = mpmath.mpf(b["t_int"]) * g / C
    f = 1 - (1 - mpmath.exp(-u)) / u
    fq = f if b["variant"] == "paper" else 1
    a = mpmath.mpf(Q) * fq / g
    bb = mpmath.mpf(b["bias_current"]) ** 2 * f / g
    B = -mpmath.mpf(b["tcr"]) * b["T_ref"] ** 2

    def h(x):
        return x - a - bb * R_ref * mpmath.exp(B * (1 / (T_s + x) - 1 / mpmath.mpf(b["T_ref"])))

    return mpmath.findroot(h, a + bb * R_ref)


def _check_against_mpmath(pipe, temps, T_s, rtol):
    v = pipe.run(np.asarray(temps), ["Q", "params", "dT", "status", "iters"],
                 env={"T_substrate": np.full(len(temps), T_s)} if T_s is not None else None)
    Ts = T_s if T_s is not None else pipe.cfg["environment"]["T_substrate"]
    rng = np.random.default_rng(0)
    p = v["params"]
    for n in range(len(temps)):
        for i, j in zip(rng.integers(0, p["g"].shape[0], 6), rng.integers(0, p["g"].shape[1], 6),
                        strict=True):
            ref = _mp_root(v["Q"][n, i, j], p["R_ref"][i, j], p["g"][i, j], p["C"][i, j],
                           pipe.cfg, Ts)
            got = v["dT"][n, i, j]
            assert v["status"][n, i, j] == kb.STATUS_OK
            assert abs(got - float(ref)) <= rtol * abs(float(ref)), (n, i, j)
    return v


@pytest.mark.parametrize("temps", [[300.0], [250.0, 400.0, 1000.0]])
def test_predicted_solve_meets_the_tolerance_against_mpmath(temps):
    pipe = Pipeline(_cfg(), seed=1)
    v = _check_against_mpmath(pipe, temps, None, 3e-12)
    if temps == [300.0]:  # the reference scene (at T_cam): one Newton step per pixel
        assert (v["iters"] == 1).all()


def test_a_substrate_far_from_the_reference_takes_the_safeguarded_path():
    pipe = Pipeline(_cfg(), seed=1)
    # 20 K below the reference substrate: exponents past the polynomial's range
    v = _check_against_mpmath(pipe, [300.0], 280.0, 3e-12)
    assert v["iters"].max() > 2


def test_paper_variant_and_positive_tcr_against_the_cold_solver():
    for over in ({"bolometer.variant": "paper"}, {"bolometer.tcr": 0.004}):
        cfg = _cfg(**over)
        pipe = Pipeline(cfg, seed=2)
        v = pipe.run(np.array([300.0, 350.0]), ["Q", "params", "dT", "v_bolo"])
        b = cfg["bolometer"]
        p = v["params"]
        shape = v["Q"].shape
        out = (np.empty(shape), np.empty(shape), np.empty(shape, np.uint8),
               np.empty(shape, np.int32))
        kb.solve_frames(v["Q"], p["R_ref"], p["g"], p["C"],
                        kb.activation_temperature(b["tcr"], b["T_ref"]), b["T_ref"],
                        cfg["environment"]["T_substrate"], b["bias_current"], b["t_int"],
                        1 if b["variant"] == "paper" else 0, b["rtol"], b["max_iter"],
                        b["runaway_temperature"], *out)
        np.testing.assert_allclose(v["dT"], out[0], rtol=5e-12)
        np.testing.assert_allclose(v["v_bolo"], out[1], rtol=5e-12)


def test_results_do_not_depend_on_what_the_sensor_solved_before():
    cfg = _cfg(**{"run.chunk_frames": 2})
    fresh = Pipeline(cfg, seed=4).simulate([310.0, 290.0, 500.0], outputs=["voltage", "codes"])
    busy = Pipeline(cfg, seed=4)
    busy.simulate([1000.0, 200.0])
    again = busy.simulate([310.0, 290.0, 500.0], outputs=["voltage", "codes"])
    np.testing.assert_array_equal(fresh.outputs["voltage"], again.outputs["voltage"])
    np.testing.assert_array_equal(fresh.codes, again.codes)
    one_chunk = Pipeline(_cfg(**{"run.chunk_frames": 16}), seed=4).simulate(
        [310.0, 290.0, 500.0], outputs=["voltage"])
    np.testing.assert_array_equal(fresh.outputs["voltage"], one_chunk.outputs["voltage"])


def test_the_reference_is_solved_once_per_sensor():
    pipe = Pipeline(_cfg(), seed=1)
    pipe.simulate([300.0])
    pipe.simulate([320.0, 330.0])
    assert pipe.counts["solve_reference"] == 1 and pipe.counts["bolometer"] == 2
