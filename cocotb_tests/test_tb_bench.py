"""The per-cycle drivers of the benchmark on a small frame: the testbenches' engine
(``cocotb_tests/tb_bench.py``, one wake-up per cycle) and the batched one
(``cocotb_tests/tb_batch.py`` in the ``nuc_dpc_batch`` transactor, one wake-up per window).

Both must agree with the golden model bit for bit and report mismatches when the expected
frame comes from a different golden configuration; the engine takes one output per
cycle, the batched one keeps full rate (up to the window granularity) and stays exact with
random per-cycle idle gaps and backpressure.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from irnuc import cosim
from irnuc.nuc_fixed import load_pipeline, nuc_dpc_top, pack_words

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


def _run(tmp_path, expected_cfg_changes: dict[str, str], batched: bool = False,
         pause: str = "0,0,0", h: int = 12, w: int = 17
         ) -> tuple[dict, dict[str, cosim.CaseResult]]:
    cfg = load_pipeline("minimal")
    rng = np.random.default_rng(11)
    raw = rng.integers(0, 1 << cfg.adc_bits, size=(h, w), dtype=np.int64)
    g = rng.integers(0, 1 << cfg.gain_bits, size=(h, w), dtype=np.int64)
    half = 1 << (cfg.offset_bits - 1)
    o = rng.integers(-half, half, size=(h, w), dtype=np.int64)
    words = pack_words(g, o, rng.random((h, w)) < 0.1, cfg)
    gcfg = cfg.replace(**expected_cfg_changes) if expected_cfg_changes else cfg
    expected = nuc_dpc_top(raw, words, gcfg).astype(np.int64)
    inp, outp = tmp_path / "in.npz", tmp_path / "out.json"
    np.savez(inp, raw=raw, words=words, expected=expected)
    top, tb = ("nuc_dpc_batch", "tb_batch") if batched else ("nuc_dpc_top", "tb_bench")
    xml = cosim.run(cosim.build(top, cfg), f"irnuc.cocotb_tests.{tb}",
                  env={"IRNUC_BENCH_IN": str(inp), "IRNUC_BENCH_OUT": str(outp),
                       "IRNUC_BATCH_PAUSE": pause},
                  results_xml=tmp_path / "bench.xml")
    info = json.loads(outp.read_text())
    info["n_diff"] = int((expected != nuc_dpc_top(raw, words, cfg)).sum())
    return info, cosim.read_results(xml)


def test_engine_driver_matches_golden(tmp_path) -> None:
    """The engine (public cocotb API only) is exact and runs at one pixel per clock."""
    info, res = _run(tmp_path, {})
    assert res["vga_frame"].passed, res["vga_frame"].message
    assert info["mismatches"] == 0
    # Full rate: the last output leaves exactly pixels - 1 cycles after the first.
    assert info["cycles"] - info["first_out_cycle"] + 1 == info["pixels"]


@pytest.mark.parametrize("batched", [False, True], ids=["engine", "batched"])
def test_driver_detects_wrong_golden(tmp_path, batched: bool) -> None:
    info, res = _run(tmp_path, {"rounding": "truncate"}, batched=batched)  # minimal: half_even
    assert info["n_diff"] > 0
    assert info["mismatches"] == info["n_diff"]
    assert not res["vga_frame"].passed
    assert "mismatching" in res["vga_frame"].message
    assert "frame 0 x" in res["vga_frame"].message


def test_batched_driver_matches_golden(tmp_path) -> None:
    """Batched (one Python wake-up per window, public API only): exact and at full rate, so
    the frame needs only the pipeline latency's windows beyond pixels / Batch."""
    info, res = _run(tmp_path, {}, batched=True, h=20, w=33)
    assert res["vga_frame"].passed, res["vga_frame"].message
    assert info["mismatches"] == 0 and info["outputs"] == info["pixels"]
    k = info["batch"]
    assert info["windows"] <= -(-info["pixels"] // k) + 4


def test_batched_driver_gaps_and_backpressure(tmp_path) -> None:
    """Per-cycle pause masks on both sources and the sink: still exact, and slower."""
    info, res = _run(tmp_path, {}, batched=True, pause="30,40,50", h=20, w=33)
    assert res["vga_frame"].passed, res["vga_frame"].message
    assert info["mismatches"] == 0 and info["outputs"] == info["pixels"]
    assert info["cycles"] > 1.5 * info["pixels"]  # the pauses really happened


def test_batched_transactor_flags_its_errors(tmp_path) -> None:
    """A late command and a FIFO overflow are flagged by the transactor (the batched
    driver fails on either), so a fast driver cannot lose stimulus silently."""
    cfg = load_pipeline("minimal")
    xml = cosim.run(cosim.build("nuc_dpc_batch", cfg), "irnuc.cocotb_tests.tb_batch",
                    testcase="transactor_flags", results_xml=tmp_path / "flags.xml")
    res = cosim.read_results(xml)
    assert res["transactor_flags"].passed, res["transactor_flags"].message
