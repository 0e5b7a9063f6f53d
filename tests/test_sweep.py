"""Bit-width sweeps (reports/studies/sweep.py, reports/studies/metrics.py): metrics against
plain numpy and brute force, quantization against the golden model's calibration, error
bounds from the datapath's rounding analysis, the paper's halving per bit, and the executors
(processes, in-process, Dask LocalCluster) giving identical results."""

from __future__ import annotations

import itertools
import json
import math
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from irnuc.common.errors import UserError
from irnuc.reports.studies import metrics
from irnuc.reports.studies.sweep import (
    SensorSpec,
    SweepAxes,
    SweepError,
    open_executor,
    parse_int_list,
    prepare,
    quantized_nuc,
    resolve_points,
    run_points,
    run_sweep,
    smallest_meeting,
)

PAPER = SensorSpec(preset="paper", overrides={"fpa.active_rows": 40, "fpa.active_cols": 56}, seed=5,
                   t_eval=(300.0, 350.0, 400.0), repeats=1)
DEFAULT = SensorSpec(preset="default", overrides={"fpa.active_rows": 24, "fpa.active_cols": 32,
                                                  "fpa.defects": {"rates": {"dead": 0.01, "hot": 0.01}}},
                     seed=2, t_eval=(350.0,), repeats=2)


@pytest.fixture(scope="module")
def paper_sets():
    axes = SweepAxes(gain_frac_bits=(3, 4, 5, 6), offset_frac_bits=("same",))
    return axes, prepare(PAPER, axes)


@pytest.fixture(scope="module")
def default_sets():
    axes = SweepAxes(gain_frac_bits=(6, 10, 14), offset_frac_bits=(0, 4))
    return axes, prepare(DEFAULT, axes)


# ---- metrics ------------------------------------------------------------------------------
def test_nonuniformity_is_std_over_mean() -> None:
    rng = np.random.default_rng(0)
    y = rng.normal(1000, 10, (8, 9))
    mask = rng.random((8, 9)) > 0.2
    v = y[mask]
    assert metrics.nonuniformity(y, mask) == pytest.approx(np.std(v) / np.mean(v), rel=1e-12)


def test_radial_artefact_of_a_ring_pattern_and_of_noise() -> None:
    h, w = 41, 60
    yy, xx = np.mgrid[0:h, 0:w]
    r = np.hypot(yy - (h - 1) / 2, xx - (w - 1) / 2)
    rings = np.floor(r + 0.5) % 4.0  # a function of the ring index alone
    mask = np.ones((h, w), bool)
    rms, frac = metrics.radial_artefact(rings, mask)
    assert frac == pytest.approx(1.0, abs=1e-12)
    assert rms == pytest.approx(rings.std(), rel=1e-12)
    noise = np.random.default_rng(1).normal(0, 1, (h, w))
    rms_n, frac_n = metrics.radial_artefact(noise, mask)
    assert frac_n < 0.1 and rms_n < 0.35
    # A constant error has no radial structure.
    assert metrics.radial_artefact(np.full((h, w), 3.0), mask) == (0.0, 0.0)


def test_radial_profile_by_hand() -> None:
    err = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]])
    radius, mean, count = metrics.radial_profile(err, np.ones((3, 3), bool))
    # Centre (1, 1): ring 0 = {5}; ring 1 = the 4 edge neighbours (d = 1); ring 1 also takes
    # the corners (d = 1.414 -> floor(1.914) = 1).
    assert radius.tolist() == [0.0, 1.0]
    assert count.tolist() == [1, 8]
    assert mean.tolist() == [5.0, (45.0 - 5.0) / 8]


def test_psnr() -> None:
    assert metrics.psnr_db(1.0, 8) == pytest.approx(20 * math.log10(255))
    assert metrics.psnr_db(0.0, 8) is None


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.integers(1, 20), st.floats(0, 100)), min_size=1, max_size=25))
def test_pareto_front_against_brute_force(pts: list[tuple[int, float]]) -> None:
    cost = np.array([p[0] for p in pts], float)
    err = np.array([p[1] for p in pts], float)
    front = set(metrics.pareto_front(cost, err).tolist())
    for i in range(len(pts)):
        dominated = any((cost[j] <= cost[i] and err[j] <= err[i]) and (cost[j] < cost[i] or err[j] < err[i])
                        for j in range(len(pts)))
        duplicate_before = any(cost[j] == cost[i] and err[j] == err[i] for j in range(len(pts))
                               if j in front and j != i)
        if dominated:
            assert i not in front
        elif not duplicate_before:
            assert i in front


def test_precision_recall_counts() -> None:
    found = np.array([1, 1, 0, 0, 1], bool)
    truth = np.array([1, 0, 1, 0, 1], bool)
    pr = metrics.precision_recall(found, truth)
    assert (pr["true_positives"], pr["false_positives"], pr["false_negatives"]) == (2, 1, 1)
    assert pr["precision"] == pytest.approx(2 / 3) and pr["recall"] == pytest.approx(2 / 3)


# ---- selection ----------------------------------------------------------------------------
@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.integers(10, 40), st.floats(0.01, 10)), min_size=1, max_size=30),
       st.floats(0.05, 5))
def test_smallest_meeting_is_exhaustive(pts: list[tuple[int, float]], bound: float) -> None:
    points = [{"index": i, "bits_per_pixel": b, "err_max_lsb": e} for i, (b, e) in enumerate(pts)]
    res = smallest_meeting(points, bound)
    ok = [p for p in points if p["err_max_lsb"] <= bound]
    assert res["found"] == bool(ok)
    if ok:
        least = min(p["bits_per_pixel"] for p in ok)
        assert res["bits_per_pixel"] == least
        assert sorted(res["points"]) == sorted(p["index"] for p in ok if p["bits_per_pixel"] == least)
        assert points[res["best"]]["err_max_lsb"] == min(points[i]["err_max_lsb"] for i in res["points"])


@pytest.mark.parametrize(("text", "expected"), [
    ("3:6", (3, 4, 5, 6)), ("0:8:4", (0, 4, 8)), ("3,5,auto", (3, 5, "auto")), ("7", (7,)),
])
def test_parse_int_list(text: str, expected: tuple) -> None:
    assert parse_int_list(text, "--x", ("auto",)) == expected


@pytest.mark.parametrize("text", ["", "a", "3:", "1:5:0", "auto"])
def test_parse_int_list_rejects(text: str) -> None:
    with pytest.raises(SweepError, match="--x"):
        parse_int_list(text, "--x")


@pytest.mark.parametrize(("field", "value", "match"), [
    ("gain_frac_bits", (33,), "axes.gain_frac_bits holds 33"),
    ("gain_frac_bits", (), "axes.gain_frac_bits is empty"),
    ("offset_int_bits", (0,), "axes.offset_int_bits holds 0"),
    ("coeff_rounding", ("nearest",), "axes.coeff_rounding holds 'nearest'"),
    ("pipeline", "nope", "axes.pipeline"),
])
def test_axes_validation_names_the_field(field: str, value: object, match: str) -> None:
    with pytest.raises(SweepError, match=match):
        SweepAxes(**{field: value}).check()


@pytest.mark.parametrize(("field", "value", "match"), [
    ("t_low", -1.0, "sensor.t_low"), ("repeats", 0, "sensor.repeats"), ("t_eval", (), "sensor.t_eval"),
])
def test_sensor_validation_names_the_field(field: str, value: object, match: str) -> None:
    with pytest.raises(SweepError, match=match):
        SensorSpec(**{field: value}).check()


def test_too_wide_point_is_refused_before_evaluation(default_sets) -> None:
    _, sets = default_sets
    axes = SweepAxes(gain_frac_bits=(32,), offset_frac_bits=(32,), gain_int_bits=(16,), offset_int_bits=(32,))
    with pytest.raises(SweepError, match="sum needs"):
        resolve_points(axes, sets)


# ---- the quantized NUC against the golden model --------------------------------------------
def test_quantization_matches_golden_calibration(default_sets) -> None:
    """Per-point codes equal nuc_fixed.calibrate's at the same widths (good pixels)."""
    from irnuc.nuc_fixed.calibrate import calibrate

    axes, sets = default_sets
    cs = sets[(None, None)]
    from irnuc import model
    cfgm = DEFAULT.model_config()
    pipe = model.Pipeline(cfgm, seed=DEFAULT.seed)
    fr = pipe.simulate([DEFAULT.t_low, DEFAULT.t_high], repeats=DEFAULT.repeats)
    m = DEFAULT.repeats
    for point, _ in resolve_points(axes, sets):
        cfg = point.config(*cs.gain.shape)
        cal = calibrate(fr.codes[:m], fr.codes[m:], cfg, rounding=point.coeff_rounding)
        y, info = quantized_nuc(cs, point)
        both = cs.good & ~cal.bad  # calibrate may flag more (range) at narrow widths
        from irnuc.nuc_fixed import nuc_core

        y_gold = nuc_core(cs.raw_eval, cal.gain_code, cal.offset_code, cfg)
        assert np.array_equal(y[:, both], y_gold[:, both]), point
        assert info["gain_saturated"] == 0 and info["offset_saturated"] == 0  # auto integer bits


def test_error_within_the_rounding_bound(default_sets) -> None:
    """|y_q - y_float| <= output rounding + max(x)*LSB_g/2 + LSB_o/2 (no saturation)."""
    axes, sets = default_sets
    cs = sets[(None, None)]
    with open_executor(0) as h:
        pts = run_points(h, resolve_points(axes, sets), sets)
    xmax = float(cs.raw_eval[:, cs.good].max())
    for p in pts:
        out_round = 0.5 if p["rounding"] != "truncate" else 1.0
        bound = out_round + xmax * 2.0 ** -(p["gain_frac_bits"] + 1) + 2.0 ** -(p["offset_frac_bits"] + 1)
        assert 0 < p["err_max_lsb"] <= bound + 1e-9, p
        assert p["err_rms_lsb"] <= p["err_max_lsb"]
        assert p["bits_per_pixel"] == p["gain_int_bits"] + p["gain_frac_bits"] + p["offset_int_bits"] \
            + p["offset_frac_bits"] + 1
        assert p["bits_per_frame"] == p["bits_per_pixel"] * cs.gain.size
    # More gain fraction bits never make the worst error worse by more than the output rounding.
    by = {(p["offset_frac_bits"], p["gain_frac_bits"]): p["err_max_lsb"] for p in pts}
    for of, gf in by:
        if (of, gf + 4) in by:
            assert by[(of, gf + 4)] <= by[(of, gf)] + 1.0


def test_paper_residual_nonuniformity_halves_per_bit(paper_sets) -> None:
    """The paper's observation, and the uniform-rounding model 2^-f/sqrt(12)."""
    axes, sets = paper_sets
    with open_executor(0) as h:
        pts = run_points(h, resolve_points(axes, sets), sets)
    nu = [p["residual_nu"] for p in pts]
    for a, b in itertools.pairwise(nu):
        assert 1.6 < a / b < 2.5, nu
    for f, v in zip((3, 4, 5, 6), nu, strict=True):
        assert v == pytest.approx(2.0**-f / math.sqrt(12.0), rel=0.3)
    # Headline metrics come from 350 K only (300 and 400 K are calibration points).
    for p in pts:
        mid = [r for r in p["per_temp"] if not r["calibration_point"]]
        assert [r["t_eval"] for r in mid] == [350.0]
        assert p["residual_nu"] == mid[0]["residual_nu"]
        # The float NUC is exact at its own calibration points.
        cal = [r for r in p["per_temp"] if r["calibration_point"]]
        assert all(r["float_nu"] < 1e-12 for r in cal)
    # The error at 3 bits is mostly radial (the cos^4 rings).
    assert pts[0]["radial_fraction"] > 0.5


def test_truncated_coefficients_bias_the_error(paper_sets) -> None:
    _, sets = paper_sets
    tr = SweepAxes(gain_frac_bits=(6,), offset_frac_bits=("same",), coeff_rounding=("truncate",))
    he = SweepAxes(gain_frac_bits=(6,), offset_frac_bits=("same",), coeff_rounding=("half_even",))
    with open_executor(0) as h:
        p_tr = run_points(h, resolve_points(tr, sets), sets)[0]
        p_he = run_points(h, resolve_points(he, sets), sets)[0]
    mid_tr = next(r for r in p_tr["per_temp"] if not r["calibration_point"])
    mid_he = next(r for r in p_he["per_temp"] if not r["calibration_point"])
    # Floor rounding of gain and offset lowers every output: a clearly negative mean error.
    assert mid_tr["err_mean_lsb"] < -abs(mid_he["err_mean_lsb"])


# ---- executors ----------------------------------------------------------------------------
def _strip(points):
    return [{k: v for k, v in p.items() if k != "seconds"} for p in points]


def test_processes_and_inline_agree(default_sets) -> None:
    axes, sets = default_sets
    a = run_sweep(DEFAULT, axes, workers=0, sets=sets)
    b = run_sweep(DEFAULT, axes, workers=2, sets=sets)
    assert _strip(a.points) == _strip(b.points)
    assert "process" in b.executor
    json.dumps(a.to_dict(max_error=1.0))  # JSON-ready


def test_dask_local_cluster_same_results(default_sets) -> None:
    distributed = pytest.importorskip("distributed")
    axes, sets = default_sets
    ref = run_sweep(DEFAULT, axes, workers=0, sets=sets)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        done = []
        res = run_sweep(DEFAULT, axes, scheduler=cluster.scheduler_address, sets=sets,
                        progress=lambda d, n: done.append((d, n)))
    assert res.executor.startswith("dask")
    assert _strip(res.points) == _strip(ref.points)
    assert done[-1] == (len(ref.points), len(ref.points))


def test_scheduler_without_dask_is_a_clear_error(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "distributed", None)
    with pytest.raises(UserError, match=r"needs Dask distributed.*pip install"), open_executor(
            scheduler="tcp://127.0.0.1:1"):
        pass


def test_same_seed_same_bits() -> None:
    axes = SweepAxes(gain_frac_bits=(8,), offset_frac_bits=(2,))
    a = run_sweep(DEFAULT, axes, workers=0)
    b = run_sweep(DEFAULT, axes, workers=0)
    assert _strip(a.points) == _strip(b.points)


def test_sweep_cli(tmp_path, capsys) -> None:
    from irnuc.cli import main

    out = tmp_path / "sw"
    rc = main(["sweep", "--sensor", "paper", "--rows", "24", "--cols", "32", "--t-eval", "350",
               "--repeats", "1", "--gain-frac", "10:14:2", "--offset-frac", "same", "--workers", "0",
               "--max-error", "2", "--out", str(out)])
    assert rc == 0
    d = json.loads((out / "sweep.json").read_text())
    assert d["n_points"] == 3 and len((out / "sweep.csv").read_text().splitlines()) == 4
    assert (out / "pareto.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "smallest widths" in capsys.readouterr().out
    rc = main(["sweep", "--gain-frac", "40", "--out", str(out)])
    assert rc == 2
    assert "axes.gain_frac_bits holds 40" in capsys.readouterr().err


def test_widths_come_from_the_pipeline_and_a_mismatch_is_refused() -> None:
    from irnuc.reports.studies.sweep import SensorSpec, SweepAxes, SweepError, run_sweep

    small = {"fpa.active_rows": 8, "fpa.active_cols": 10}
    axes = SweepAxes(gain_frac_bits=(5,), offset_frac_bits=(1,), pipeline="minimal")
    with pytest.raises(SweepError, match=r"14-bit ADC .* adc_bits = 8"):
        run_sweep(SensorSpec(overrides=small, repeats=1), axes, workers=0)
    res = run_sweep(SensorSpec(overrides={**small, "adc.bits": 8}, repeats=1), axes, workers=0)
    p = res.points[0]
    assert (p["adc_bits"], p["out_bits"]) == (8, 6)  # minimal: 8-bit ADC, 6-bit output
    # Explicit ADC widths are swept as asked (the sensor re-simulated at each).
    res = run_sweep(SensorSpec(overrides=small, repeats=1),
                    SweepAxes(gain_frac_bits=(5,), offset_frac_bits=(1,), adc_bits=(8,),
                              pipeline="minimal"), workers=0)
    assert (res.points[0]["adc_bits"], res.points[0]["out_bits"]) == (8, 6)
