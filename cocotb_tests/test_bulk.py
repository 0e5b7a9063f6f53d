"""Bulk co-simulation (C++ harness, raw binary files) of ``nuc_dpc_top`` against the golden model.

The harness (``cosim/harness/bulk_main.cpp``) streams whole frames through the
Verilated RTL; ``irnuc.cosim.check_bulk`` compares every output code and marker with
``nuc_fixed.nuc_dpc_top`` in numpy. Every named configuration, several frame shapes
(back-to-back frames, the widest line buffer, 1 x 1 frames), full rate (no bubble) and
random idle gaps with backpressure, frames sharded over parallel harness processes, and a
deliberately wrong golden configuration that must be caught.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from irnuc import cosim
from irnuc.common.errors import UserError
from irnuc.nuc_fixed import InputError, load_pipeline, nuc_dpc_top, pack_words, pipeline_names

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


@functools.cache
def _build(config: str) -> cosim.Build:
    return cosim.build_bulk(load_pipeline(config))


def _shapes(config: str) -> dict[str, tuple[int, int, int]]:
    """name -> (frames, H, W)."""
    cfg = load_pipeline(config)
    return {
        "3x_small": (3, min(cfg.max_height, 9), min(cfg.max_width, 14)),
        "max_width": (1, 3, cfg.max_width),
        "column": (2, min(cfg.max_height, 40), 1),
        "1x1": (3, 1, 1),
    }


def _stimulus(config: str, frames: int, h: int, w: int, seed: int):
    """Random raw codes over the full range, random words, 5 % bad pixels."""
    cfg = load_pipeline(config)
    rng = np.random.default_rng(seed)
    raw = rng.integers(0, 1 << cfg.adc_bits, size=(frames, h, w), dtype=np.int64)
    g = rng.integers(0, 1 << cfg.gain_bits, size=(h, w), dtype=np.int64)
    half = 1 << (cfg.offset_bits - 1)
    o = rng.integers(-half, half, size=(h, w), dtype=np.int64)
    bad = rng.random((h, w)) < 0.05
    return raw, pack_words(g, o, bad, cfg)


@pytest.mark.parametrize("shape", ["3x_small", "max_width", "column", "1x1"])
@pytest.mark.parametrize("config", pipeline_names())
def test_bulk_full_rate_matches_golden(config: str, shape: str) -> None:
    """Bit exact at valid = 1 / ready = 1, and one output per cycle without a bubble."""
    cfg = load_pipeline(config)
    frames, h, w = _shapes(config)[shape]
    raw, words = _stimulus(config, frames, h, w, seed=3)
    res = cosim.run_bulk(_build(config), raw, words)
    chk = cosim.check_bulk(res, raw, words, cfg)
    assert chk.passed, chk.report()
    assert res.data.size == raw.size
    assert res.inputs_taken == (raw.size, raw.size)
    assert res.last_out_cycle - res.first_out_cycle + 1 == raw.size, "bubble in the output"


@pytest.mark.parametrize("config", pipeline_names())
def test_bulk_gaps_and_backpressure(config: str) -> None:
    """Random idle gaps on both inputs and output backpressure: still exact, and slower."""
    cfg = load_pipeline(config)
    frames, h, w = _shapes(config)["3x_small"]
    raw, words = _stimulus(config, frames, h, w, seed=4)
    res = cosim.run_bulk(_build(config), raw, words, idle_percent=30, stall_percent=40, seed=9)
    chk = cosim.check_bulk(res, raw, words, cfg)
    assert chk.passed, chk.report()
    assert res.cycles > 1.5 * raw.size  # the gaps really happened
    again = cosim.run_bulk(_build(config), raw, words, idle_percent=30, stall_percent=40, seed=9)
    assert again.cycles == res.cycles  # same seed, same schedule
    np.testing.assert_array_equal(again.data, res.data)


@pytest.mark.parametrize("stall", [10, 50, 90])
@pytest.mark.parametrize("config", pipeline_names())
def test_bulk_throughput_under_backpressure(config: str, stall: int) -> None:
    """Full-rate inputs, a back-pressured output: exact, and no cycle lost inside the core
    (output cycles = outputs + stalled cycles), across back-to-back frames."""
    cfg = load_pipeline(config)
    frames, h, w = _shapes(config)["3x_small"]
    raw, words = _stimulus(config, frames, h, w, seed=8)
    res = cosim.run_bulk(_build(config), raw, words, stall_percent=stall, seed=stall)
    assert cosim.check_bulk(res, raw, words, cfg).passed
    assert res.stall_cycles > 0
    assert res.last_out_cycle - res.first_out_cycle + 1 == raw.size + res.stall_cycles


@pytest.mark.parametrize("config", pipeline_names())
def test_bulk_checker_detects_wrong_golden(config: str) -> None:
    """Against another rounding mode the comparison must report mismatches with positions."""
    cfg = load_pipeline(config)
    other = cfg.replace(rounding="truncate" if cfg.rounding != "truncate" else "half_up")
    raw, words = _stimulus(config, 2, min(cfg.max_height, 16), min(cfg.max_width, 16), seed=5)
    res = cosim.run_bulk(_build(config), raw, words)
    assert cosim.check_bulk(res, raw, words, cfg).passed
    wrong = nuc_dpc_top(raw, words, other).astype(np.int64).ravel()
    n_diff = int((wrong != nuc_dpc_top(raw, words, cfg).astype(np.int64).ravel()).sum())
    assert n_diff > 0, "the two golden configurations must differ on this stimulus"
    chk = cosim.check_bulk(res, raw, words, other)
    assert chk.mismatches == n_diff
    assert not chk.passed
    assert chk.lines and chk.lines[0].startswith("frame ")
    assert "expected" in chk.lines[0] and "golden p" in chk.lines[0]


def test_bulk_checker_detects_markers_and_missing_outputs() -> None:
    """A wrong marker, a missing output and an extra output are each reported."""
    cfg = load_pipeline("minimal")
    raw, words = _stimulus("minimal", 1, 4, 5, seed=6)
    res = cosim.run_bulk(_build("minimal"), raw, words)
    assert cosim.check_bulk(res, raw, words, cfg).passed
    eol = res.eol.copy()
    eol[4] = ~eol[4]  # last column of row 0
    chk = cosim.check_bulk(dataclasses.replace(res, eol=eol), raw, words, cfg)
    assert chk.mismatches == 1
    assert "frame 0 x 4 y 0" in chk.lines[0] and "eol 0 (expected 1)" in chk.lines[0]
    short = dataclasses.replace(res, data=res.data[:-1], sof=res.sof[:-1], eol=res.eol[:-1])
    chk = cosim.check_bulk(short, raw, words, cfg)
    assert chk.missing == 1 and chk.errors == 1 and "1 output(s) missing" in chk.lines[0]
    chk = cosim.check_bulk(dataclasses.replace(res, extra=2), raw, words, cfg)
    assert chk.extra == 2 and chk.errors == 2 and "2 extra output(s)" in chk.lines[0]


@pytest.mark.parametrize("stall", [0, 40])
def test_bulk_sharded_matches_single_process(stall: int) -> None:
    """Frames split over parallel harness processes (each with its own reset): the same
    outputs as one process at full rate, every frame checked, the cycle accounting summed;
    more shards than frames start one process per frame."""
    cfg = load_pipeline("minimal")
    raw, words = _stimulus("minimal", 5, 9, 14, seed=12)
    one = cosim.run_bulk(_build("minimal"), raw, words, stall_percent=stall, seed=3)
    for shards, started in ((2, 2), (8, 5)):
        res = cosim.run_bulk(_build("minimal"), raw, words, stall_percent=stall, seed=3,
                             shards=shards)
        assert res.shards == started
        assert cosim.check_bulk(res, raw, words, cfg).passed
        np.testing.assert_array_equal(res.data, one.data)
        assert res.inputs_taken == (raw.size, raw.size)
        assert res.last_out_cycle - res.first_out_cycle + 1 == raw.size + res.stall_cycles
        assert (res.stall_cycles > 0) == (stall > 0)


def test_bulk_sharded_detects_wrong_golden() -> None:
    """Every shard's outputs are compared: a wrong golden configuration is caught in all."""
    cfg = load_pipeline("minimal")
    other = cfg.replace(rounding="truncate")
    raw, words = _stimulus("minimal", 4, 8, 8, seed=13)
    res = cosim.run_bulk(_build("minimal"), raw, words, shards=2)
    n_diff = nuc_dpc_top(raw, words, other) != nuc_dpc_top(raw, words, cfg)
    assert n_diff[:2].any() and n_diff[2:].any(), "both shards must have differing pixels"
    chk = cosim.check_bulk(res, raw, words, other)
    assert chk.mismatches == int(n_diff.sum()) and not chk.passed


def test_bulk_rejects_bad_arguments() -> None:
    bld = _build("minimal")
    raw, words = _stimulus("minimal", 1, 4, 5, seed=7)
    with pytest.raises(ValueError, match=r"idle_percent = 100 .*0\.\.99"):
        cosim.run_bulk(bld, raw, words, idle_percent=100)
    with pytest.raises(ValueError, match=r"stall_percent = -1 .*0\.\.99"):
        cosim.run_bulk(bld, raw, words, stall_percent=-1)
    with pytest.raises(ValueError, match=r"seed = -3"):
        cosim.run_bulk(bld, raw, words, seed=-3)
    with pytest.raises(ValueError, match=r"shards = 0 .*1\.\.16"):
        cosim.run_bulk(bld, raw, words, shards=0)
    with pytest.raises(InputError, match="raw"):
        cosim.run_bulk(bld, raw + 256, words)  # minimal: 8-bit codes
    with pytest.raises(InputError, match="frame size"):
        cosim.run_bulk(bld, np.zeros((65, 2), dtype=np.int64), np.zeros((65, 2), np.uint64))
    with pytest.raises(InputError, match="words has shape"):
        cosim.run_bulk(bld, raw, words[:, :3])
    with pytest.raises(UserError, match="not a bulk build"):
        cosim.run_bulk(cosim.Build("nuc_dpc_top", bld.cfg, bld.build_dir.parent, {}, False),
                     raw, words)
