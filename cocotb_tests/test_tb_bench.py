"""The lean per-cycle driver of the benchmark (``cocotb_tests/tb_bench.py``) on a small frame.

It must agree with the golden model bit for bit, take one output per cycle, and report
mismatches when the expected frame comes from a different golden configuration.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from irnuc import cosim
from irnuc.nuc_fixed import load_pipeline, nuc_dpc_top, pack_words

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


def _run(tmp_path, expected_cfg_changes: dict[str, str]
         ) -> tuple[dict, dict[str, cosim.CaseResult]]:
    cfg = load_pipeline("minimal")
    rng = np.random.default_rng(11)
    h, w = 12, 17
    raw = rng.integers(0, 1 << cfg.adc_bits, size=(h, w), dtype=np.int64)
    g = rng.integers(0, 1 << cfg.gain_bits, size=(h, w), dtype=np.int64)
    half = 1 << (cfg.offset_bits - 1)
    o = rng.integers(-half, half, size=(h, w), dtype=np.int64)
    words = pack_words(g, o, rng.random((h, w)) < 0.1, cfg)
    gcfg = cfg.replace(**expected_cfg_changes) if expected_cfg_changes else cfg
    expected = nuc_dpc_top(raw, words, gcfg).astype(np.int64)
    inp, outp = tmp_path / "in.npz", tmp_path / "out.json"
    np.savez(inp, raw=raw, words=words, expected=expected)
    xml = cosim.run(cosim.build("nuc_dpc_top", cfg), "irnuc.cocotb_tests.tb_bench",
                  env={"IRNUC_BENCH_IN": str(inp), "IRNUC_BENCH_OUT": str(outp)},
                  results_xml=tmp_path / "bench.xml")
    info = json.loads(outp.read_text())
    info["n_diff"] = int((expected != nuc_dpc_top(raw, words, cfg)).sum())
    return info, cosim.read_results(xml)


def test_lean_driver_matches_golden(tmp_path) -> None:
    """The lean driver (public cocotb API only) is exact and runs at one pixel per clock."""
    info, res = _run(tmp_path, {})
    assert res["vga_frame"].passed, res["vga_frame"].message
    assert info["mismatches"] == 0
    # Full rate: the last output leaves exactly pixels - 1 cycles after the first.
    assert info["cycles"] - info["first_out_cycle"] + 1 == info["pixels"]


def test_lean_driver_detects_wrong_golden(tmp_path) -> None:
    info, res = _run(tmp_path, {"rounding": "truncate"})  # minimal rounds half_even
    assert info["n_diff"] > 0
    assert info["mismatches"] == info["n_diff"]
    assert not res["vga_frame"].passed
    assert "mismatching" in res["vga_frame"].message
    assert "frame 0 x" in res["vga_frame"].message
