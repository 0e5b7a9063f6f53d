"""Bulk co-simulation (C++ harness) of ``method_dpc_top`` against ``nuc_fixed.method_top``.

Every base method's configuration: random calibrations over every code range with the
FPA reading changing every frame (table_interp: the tables switch), full rate without a
bubble, idle gaps with backpressure, and a drift sequence of the physics model (the FPA
ramping over the calibrated range, every method calibrated on the model); a wrong golden
configuration must be caught, wrong stimulus is refused before any work.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from irnuc import cosim
from irnuc.cocotb_tests.method_stim import random_coefficients, random_raw, random_reading
from irnuc.common.errors import UserError
from irnuc.cosim.method_bulk import check_method_bulk, run_method_bulk
from irnuc.cosim.method_drift import calibrate_methods, drift_sequence, pgo_build
from irnuc.nuc_fixed import InputError, load_pipeline
from irnuc.nuc_fixed.method_top import FrameInputs, method_top

pytestmark = [pytest.mark.cosim, pytest.mark.slow]

METHOD_CONFIGS = ("onepoint14", "typical14", "piecewise14", "quadratic14", "tcoffset14",
                  "tcgain14", "table14")
SHAPE = (24, 40)


@functools.cache
def _build(config: str, assertions: bool = True) -> cosim.Build:
    return cosim.build_bulk(load_pipeline(config), top="method_dpc_top", assertions=assertions)


def _stimulus(config: str, frames: int, seed: int):
    cfg = load_pipeline(config)
    rng = np.random.default_rng(seed)
    c = random_coefficients(cfg, *SHAPE, rng)
    raw = np.stack([random_raw(cfg, *SHAPE, rng) for _ in range(frames)])
    rd = [random_reading(cfg, c, rng) for _ in range(frames)]
    return c, raw, (None if rd[0] is None else rd)


@pytest.mark.parametrize("config", METHOD_CONFIGS)
def test_method_bulk_full_rate(config: str) -> None:
    """Bit exact at valid = 1 / ready = 1, one output per cycle without a bubble, the frame
    word and (table_interp) the tables changing from frame to frame."""
    c, raw, rd = _stimulus(config, 5, seed=11)
    res = run_method_bulk(_build(config), c, raw, rd)
    chk = check_method_bulk(res, c, raw, rd)
    assert chk.passed, chk.report()
    assert res.inputs_taken == (raw.size, raw.size)
    assert res.last_out_cycle - res.first_out_cycle + 1 == raw.size, "bubble in the output"


@pytest.mark.parametrize("config", METHOD_CONFIGS)
def test_method_bulk_gaps_and_backpressure(config: str) -> None:
    """Idle gaps on both inputs and backpressure, frames over two harness processes."""
    c, raw, rd = _stimulus(config, 4, seed=12)
    res = run_method_bulk(_build(config), c, raw, rd, idle_percent=25, stall_percent=35,
                          seed=5, shards=2)
    chk = check_method_bulk(res, c, raw, rd)
    assert chk.passed, chk.report()
    assert res.cycles > 1.4 * raw.size


@pytest.mark.parametrize("config", ["typical14", "table14"])
def test_method_bulk_direct_eval_equals_public_eval(config: str) -> None:
    """The harness's direct scheduler calls (the default) and the model's public eval()
    every cycle (``public_eval``, the previous path) give the same outputs, markers and
    cycle counts under gaps and backpressure, frames over three shards read from one file
    (skip=), the public eval still at cycle 0 and every 4096th; both bit exact."""
    c, raw, rd = _stimulus(config, 7, seed=13)
    runs = [run_method_bulk(_build(config), c, raw, rd, idle_percent=20, stall_percent=30,
                            seed=9, shards=3, public_eval=p) for p in (False, True)]
    for res in runs:
        chk = check_method_bulk(res, c, raw, rd)
        assert chk.passed, chk.report()
    fast, old = runs
    assert np.array_equal(fast.data, old.data)
    assert np.array_equal(fast.sof, old.sof) and np.array_equal(fast.eol, old.eol)
    assert (fast.cycles, fast.stall_cycles, fast.inputs_taken) == (
        old.cycles, old.stall_cycles, old.inputs_taken)
    assert fast.cycles > 2 * 4096  # most cycles go through the scheduler call alone


@pytest.mark.parametrize("assertions", [True, False], ids=["assertions", "noassert"])
def test_method_bulk_fast_path_catches_a_planted_mismatch(assertions: bool) -> None:
    """One raw code changed in what the DUT streams, the golden model given the original
    frames: the fast path (one scheduler call per cycle; on the assertion build and on the
    build without assertions, the benchmark's throughput run) reports exactly the outputs
    the change moves (the golden model on both stimuli says which: the pixel, and the
    neighbours whose defect replacement reads it), under gaps and backpressure, 2 shards."""
    cfg = load_pipeline("typical14")
    c, raw, rd = _stimulus("typical14", 3, seed=16)
    want = method_top(raw, c, FrameInputs()).y.ravel()
    # The first pixel of frame 1's middle row whose changed code moves the golden model's
    # output (random coefficients clip many outputs at either end, which no code moves).
    f, r = 1, SHAPE[0] // 2
    for col in range(SHAPE[1]):
        planted = raw.copy()
        planted[f, r, col] = ((1 << cfg.adc_bits) - 1) - raw[f, r, col]  # far from it
        moved = np.flatnonzero(want != method_top(planted, c, FrameInputs()).y.ravel())
        if moved.size:
            break
    assert moved.size >= 1, "no code of the row moves an output of the golden model"
    res = run_method_bulk(_build("typical14", assertions), c, planted, rd, idle_percent=10,
                          stall_percent=20, seed=3, shards=2)
    chk = check_method_bulk(res, c, raw, rd)
    assert not chk.passed
    assert (chk.mismatches, chk.missing, chk.extra) == (moved.size, 0, 0), chk.report()
    assert chk.first_index == moved[0]
    assert moved[0] // (SHAPE[0] * SHAPE[1]) == f
    # and the run on the right frames passes (the same build and path)
    ok = run_method_bulk(_build("typical14", assertions), c, raw, rd, idle_percent=10,
                         stall_percent=20, seed=3, shards=2)
    assert check_method_bulk(ok, c, raw, rd).passed


@functools.cache
def _drift():
    cfgs = [load_pipeline(n) for n in METHOD_CONFIGS]
    return drift_sequence(6, SHAPE, seed=2), calibrate_methods(cfgs, SHAPE, seed=2)


@pytest.mark.parametrize("config", METHOD_CONFIGS)
def test_method_bulk_model_drift(config: str) -> None:
    """A drift sequence of the model (FPA 289 -> 307 K, the sensor's readings), the method
    calibrated on the model: exact, and the readings span the calibrated FPA range."""
    seq, cals = _drift()
    cfg = load_pipeline(config)
    rd = seq.reading if "fpa" in cfg.base.readings else None
    res = run_method_bulk(_build(config), cals[config], seq.codes, rd, shards=2)
    chk = check_method_bulk(res, cals[config], seq.codes, rd)
    assert chk.passed, chk.report()
    assert chk.compared == seq.codes.size
    assert seq.fpa_K[0] < 290.0 and seq.fpa_K[-1] > 306.0


def test_method_bulk_pgo_build_equals_plain_build() -> None:
    """The profile-guided build (gcc PGO, the benchmark's ``pgo_*`` run) is trained (a
    profile of the model and of the harness beside their objects, the final compile from
    it), cached apart from the plain build, and streams the same outputs, markers and
    cycles as the plain build under gaps and backpressure over two shards, bit exact."""
    seq, cals = _drift()
    cfg, c = load_pipeline("tcoffset14"), cals["tcoffset14"]
    pgo = pgo_build(cfg, c, seq, seq.reading)
    plain = _build("tcoffset14")
    assert pgo.build_dir != plain.build_dir and "-pgo-" in pgo.build_dir.name
    profiles = {p.stem for p in pgo.build_dir.glob("*.gcda")}
    assert {"bulk_main", "Vmethod_dpc_top__ALL"} <= profiles, profiles
    assert "-fprofile-use" in (pgo.build_dir / "make.log").read_text()
    runs = [run_method_bulk(b, c, seq.codes, seq.reading, idle_percent=15, stall_percent=25,
                            seed=4, shards=2) for b in (pgo, plain)]
    for res in runs:
        chk = check_method_bulk(res, c, seq.codes, seq.reading)
        assert chk.passed, chk.report()
    a, b = runs
    assert np.array_equal(a.data, b.data) and np.array_equal(a.sof, b.sof)
    assert np.array_equal(a.eol, b.eol)
    assert (a.cycles, a.stall_cycles, a.inputs_taken) == (b.cycles, b.stall_cycles,
                                                         b.inputs_taken)


def test_method_bulk_detects_wrong_golden() -> None:
    """The check fails against the golden model of another rounding mode, with triage."""
    c, raw, rd = _stimulus("tcgain14", 3, seed=13)
    res = run_method_bulk(_build("tcgain14"), c, raw, rd)
    other = load_pipeline("tcgain14").replace(rounding="truncate")
    chk = check_method_bulk(res, c, raw, rd, golden=other)
    assert not chk.passed and chk.mismatches > 0
    assert "golden s" in chk.lines[0] and "reading" in chk.lines[0]


def test_method_bulk_refuses_bad_stimulus() -> None:
    """Wrong coefficients, frame size, readings or top: one clear error before any run."""
    c, raw, rd = _stimulus("tcoffset14", 2, seed=14)
    bld = _build("tcoffset14")
    with pytest.raises(InputError, match="reading"):
        run_method_bulk(bld, c, raw, None)
    with pytest.raises(InputError, match="readings holds"):
        run_method_bulk(bld, c, raw, rd[:1])
    with pytest.raises(InputError, match="coefficients are"):
        run_method_bulk(bld, c, raw[:, :-1, :], rd)
    other, _, _ = _stimulus("table14", 1, seed=15)
    with pytest.raises(InputError, match="coefficients are of"):
        run_method_bulk(bld, other, raw, rd)
    with pytest.raises(UserError, match="method_bulk"):
        cosim.run_bulk(bld, raw, np.zeros(SHAPE, np.uint64))
