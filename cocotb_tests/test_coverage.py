"""Functional coverage (cocotb-coverage) and code coverage (Verilator) of the co-simulation.

* every named configuration (and every mode variant of ``nuc_core``) reaches 100 % of its
  bins over the testbenches run for it; an unreachable bin is removed with its reason;
* the merge, the summary and the ``coverage.dat`` reader on small hand-made data (so the
  100 % check can fail: an unhit bin is reported by name).

``run_suite(coverage=True)`` is tested in ``tests/test_suite.py``.
"""

from __future__ import annotations

import pytest

from irnuc.cocotb_tests import tb_dpc, tb_ffc, tb_method, tb_nuc, tb_top
from irnuc.cocotb_tests.runs import coverage_json, run_module
from irnuc.cocotb_tests.test_method_dpc_top import CONFIGS as METHOD_CONFIGS
from irnuc.cocotb_tests.test_method_ffc_top import CONFIGS as FFC_CONFIGS
from irnuc.cocotb_tests.test_nuc_core import _VARIANTS, _config
from irnuc.cosim import coverage
from irnuc.nuc_fixed import load_pipeline, pipeline_names

TB = {"nuc_dpc_top": tb_top.__name__, "dpc_core": tb_dpc.__name__, "nuc_core": tb_nuc.__name__}


def _labels() -> list[str]:
    return list(_VARIANTS)


@pytest.mark.cosim
@pytest.mark.slow
@pytest.mark.parametrize("variant", _labels())
def test_functional_coverage_complete(variant: str) -> None:
    """Every bin of the configuration's coverpoints is hit by the testbenches run for it
    (named configurations: tb_top, tb_dpc, tb_nuc; mode variants: tb_nuc)."""
    cfg = _config(variant)
    tops = ["nuc_core"] if variant not in pipeline_names() else list(TB)
    files = []
    for top in tops:
        run_module(top, cfg, TB[top])
        files.append(coverage_json(top, cfg, TB[top]))
    _assert_closed(coverage.summarize(coverage.merge(files)), coverage.config_label(cfg))


def _assert_closed(summary: dict, label: str) -> None:
    assert label in summary["configurations"], f"no coverage exported for {label}"
    c = summary["configurations"][label]
    assert c["total"] > 0
    assert c["hit"] == c["total"], f"{label}: {c['hit']}/{c['total']}; uncovered {c['uncovered']}"
    for p in c["coverpoints"].values():
        for b, reason in p["removed"].items():
            assert reason and b not in p["bins"], (b, reason)


@pytest.mark.cosim
@pytest.mark.parametrize("config", [n for n in METHOD_CONFIGS if not set("+_") & set(n)])
def test_method_coverage_complete(config: str) -> None:
    """Every bin of a base method's coverpoints (the method's own and the stream, frame and
    reset points) is hit by tb_method on method_dpc_top: the run test_method_dpc_top makes,
    read again (no simulation of its own)."""
    cfg = METHOD_CONFIGS[config]
    run_module("method_dpc_top", cfg, tb_method.__name__)
    files = [coverage_json("method_dpc_top", cfg, tb_method.__name__)]
    _assert_closed(coverage.summarize(coverage.merge(files)), coverage.config_label(cfg))


@pytest.mark.cosim
@pytest.mark.parametrize("config", list(FFC_CONFIGS))
def test_ffc_coverage_complete(config: str) -> None:
    """Every bin of the FFC sequence (cosim/stage_coverage.py) and the stream points is hit
    by tb_ffc on method_ffc_top: the run test_method_ffc_top makes, read again."""
    cfg = FFC_CONFIGS[config]
    run_module("method_ffc_top", cfg, tb_ffc.__name__)
    files = [coverage_json("method_ffc_top", cfg, tb_ffc.__name__)]
    _assert_closed(coverage.summarize(coverage.merge(files)), coverage.config_label(cfg))


def test_ffc_classes_of_a_sequence_by_hand() -> None:
    """The FFC bins of a golden run of ffc14 (N = 8, hold): two shutter frames first
    (passed, a short run), an open frame, a full run of 8 (held; the mean pass on its last
    frame, the refresh on the open frame after it), a short run of 3 (held)."""
    import numpy as np

    from irnuc.cosim.stage_coverage import ffc_classes

    cfg = load_pipeline("ffc14")
    assert cfg.ffc_frames == 8 and cfg.ffc_output == "hold"
    seq = [1, 1, 0] + [1] * 8 + [0] + [1] * 3 + [0]
    run = tb_ffc._run_of(cfg, cfg, np.random.default_rng(3), seq, (2, 3))
    assert [f is not None for f in run.foff_out].index(True) == 11
    got = ffc_classes(run, cfg)
    assert got["ffc.frame"] == {"shutter_passed", "accumulate_first", "accumulate_add",
                                "open", "held", "mean", "refresh"}
    assert got["ffc.run"] == {"short", "full"}
    assert got["ffc.refresh_frame"] == {"open"}
    assert got["ffc.first_frame"] == {"shutter"}
    assert got["ffc.tiny_frame"] == set()  # 6-pixel frames
    assert got["ffc.target"] == {"mean"}
    assert list(run.held) == [False] * 3 + [True] * 8 + [False] + [True] * 3 + [False]
    # Every pixel bad: the refresh has no target and keeps the corrections.
    from irnuc.cosim.stages import ffc_run
    from irnuc.nuc_fixed.method_top import MethodCoefficients

    c = run.frames[0].coeffs
    fields = {m: {**v, "bad": np.ones((2, 3), bool)} for m, v in c.fields.items()}
    kept = ffc_run(MethodCoefficients(cfg, fields, c.registers),
                   [f.raw for f in run.frames], list(run.shutter))
    assert kept.kept == (10,)
    assert ffc_classes(kept, cfg)["ffc.target"] == {"no_good_pixel"}


def _snap(bins: dict[str, int], removed: dict[str, str] | None = None) -> dict:
    return {"version": 1, "configurations": {"x": {"config_digest": "d", "tops": ["t"],
            "coverpoints": {"p": {"kind": "point", "bins": bins, "removed": removed or {}}}}}}


def test_merge_and_summary_report_uncovered_bins() -> None:
    merged = coverage.merge_data([_snap({"a": 1, "b": 0}), _snap({"a": 2, "b": 0, "c": 1})])
    s = coverage.summarize(merged)["configurations"]["x"]
    assert s["coverpoints"]["p"]["bins"] == {"a": 3, "b": 0, "c": 1}
    assert (s["hit"], s["total"], s["uncovered"]) == (2, 3, ["p:b"])
    full = coverage.summarize(coverage.merge_data([merged, _snap({"b": 5})]))
    assert full["percent"] == 100.0 and full["configurations"]["x"]["uncovered"] == []


def test_model_removes_unreachable_cross_bins_with_reasons() -> None:
    cfg = load_pipeline("minimal")
    m = coverage.CoverageModel("nuc_dpc_top", cfg, prefix="unit")
    snap = m.snapshot()["configurations"]["minimal"]["coverpoints"]
    cross = snap["dpc.n_x_position"]
    assert "(4, 'corner')" in cross["removed"] and "(4, 'corner')" not in cross["bins"]
    assert "(3, 'corner')" in cross["bins"] and "(8, 'interior')" in cross["bins"]
    assert "at most 3" in cross["removed"]["(4, 'corner')"]
    assert set(snap["frame.error"]["bins"]) == set(coverage.FRAME_ERRORS)
    assert set(snap["reset.stage"]["bins"]) >= {"top_input", "nuc_round", "dpc_window", "flush"}


def test_code_coverage_from_a_coverage_dat(tmp_path) -> None:
    def point(page: str, line: int, count: int, h: str) -> str:
        kv = {"f": "hdl/nuc_core.sv", "l": str(line), "n": "3", "page": page, "o": "c",
              "h": h}
        return "C '" + "".join(f"\x01{k}\x02{v}" for k, v in kv.items()) + f"' {count}"

    dat = tmp_path / "coverage.dat"
    dat.write_text("# SystemC::Coverage-3\n" + "\n".join([
        point("v_line/nuc_core__pi1", 10, 4, "top.a"), point("v_line/nuc_core__pi1", 10, 0,
                                                             "top.b"),
        point("v_line/nuc_core", 12, 0, "top.a"), point("v_toggle/nuc_core", 14, 1, "top.a"),
        point("v_toggle/nuc_core", 15, 0, "top.a")]) + "\n")
    cc = coverage.code_coverage(coverage.read_coverage_dat(dat))
    assert cc["nuc_core"]["line"] == {"hit": 1, "total": 2, "percent": 50.0}
    assert cc["nuc_core"]["toggle"]["percent"] == 50.0
    assert cc["nuc_core"]["missed_lines"] == ["nuc_core.sv:12"]


# ---- the new stimulus can close its own bins (pure Python, no simulation) --------------------

def _stimulus_configs():
    from irnuc.cosim import configspace

    return (configspace.named() + list(configspace.ci_sample())
            + configspace.campaign_sample(18, seed=3, max_dim=64))


def test_size_walk_hits_every_size_bin_the_model_keeps() -> None:
    """For named, CI-sample and random configurations (maxima from 1 x 1 up), the size walk
    of tb_top.size_class_changes hits every bin of frame.size_class and of the size
    changes that the coverage model keeps, and the model removes only what no size walk
    can reach (every removed bin has a reason)."""
    import numpy as np

    from irnuc.cocotb_tests import stimulus

    for i, cfg in enumerate(_stimulus_configs()):
        m = coverage.CoverageModel("nuc_dpc_top", cfg, prefix=f"walk{i}")
        sizes = stimulus.size_walk(cfg, np.random.default_rng(i))
        assert all(1 <= h <= cfg.max_height and 1 <= w <= cfg.max_width for h, w in sizes)
        m.sample_size_changes(sizes, [True] * len(sizes))
        snap = m.snapshot()["configurations"][coverage.config_label(cfg)]["coverpoints"]
        for point in ("frame.size_class", "frame.change_width", "frame.change_height"):
            p = snap.get(point, {"bins": {}, "removed": {}})
            missing = [b for b, n in p["bins"].items() if n == 0]
            assert not missing, f"{cfg.name} {point}: the walk misses {missing}"
            assert all(p["removed"].values())


def test_dpc_neighbourhoods_hit_their_bins_on_the_named_configurations() -> None:
    """The DPC neighbourhoods of tb_top.dpc_arithmetic hit every kept dpc.arith bin of the
    named configurations: sampled from the frames they make, through the golden NUC of
    the inputs found for them (not from the generator's own bookkeeping)."""
    import numpy as np

    from irnuc.cocotb_tests import stimulus
    from irnuc.cosim import configspace
    from irnuc.nuc_fixed import nuc_core, unpack_words

    for i, cfg in enumerate(configspace.named()):
        bins = coverage.dpc_arith_bins(cfg, "nuc_dpc_top")[0]
        nb = stimulus.dpc_neighbourhoods(cfg, np.random.default_rng(i), bins,
                                         coverage.nuc_output_intervals(cfg),
                                         preimage=lambda v, c=cfg: stimulus.nuc_preimage(c, v))
        assert not nb.missing, (cfg.name, nb.missing[:5])
        m = coverage.CoverageModel("nuc_dpc_top", cfg, prefix=f"arith{i}")
        for raw, words in zip(nb.raw, nb.words, strict=True):
            g, o, bad = unpack_words(words, cfg)
            m.sample_dpc_arith(nuc_core(raw, g, o, cfg), bad)
        hits = m.snapshot()["configurations"][cfg.name]["coverpoints"]["dpc.arith"]["bins"]
        assert len(hits) == len(bins) and all(hits.values()), cfg.name


def test_sample_dpc_arith_by_hand() -> None:
    """One bad pixel in the middle of a 3 x 3 frame with two bad neighbours: n = 6 good
    neighbours; their sum and its residue and range, counted by hand."""
    import numpy as np

    from irnuc.nuc_fixed import load_pipeline

    cfg = load_pipeline("minimal")  # 6-bit output: full scale 63
    y = np.array([[60, 61, 62], [63, 0, 60], [5, 7, 63]])
    bad = np.zeros((3, 3), bool)
    bad[1, 1] = bad[2, 0] = bad[2, 1] = True
    m = coverage.CoverageModel("nuc_dpc_top", cfg, prefix="byhand")
    m.sample_dpc_arith(y, bad)
    hits = m.snapshot()["configurations"]["minimal"]["coverpoints"]["dpc.arith"]["bins"]
    # Pixel (1, 1): good 60, 61, 62, 63, 60, 63 -> n = 6, S = 369, 369 % 6 = 3, mean 61.5
    # >= 7/8 * 63: high. Pixel (2, 0): good (1, 0) = 63 only -> n = 1, residue 0, high.
    # Pixel (2, 1): good 63, 60, 63 -> n = 3, S = 186, residue 0, mean 62: high.
    assert {k for k, v in hits.items() if v} == {"(6, 3, 'high')", "(1, 0, 'high')",
                                                  "(3, 0, 'high')"}
    y2 = np.array([[4, 5, 9], [1, 2, 3]])
    bad2 = np.array([[False, True, False], [False, False, False]])
    m2 = coverage.CoverageModel("nuc_dpc_top", cfg, prefix="byhand2")
    m2.sample_dpc_arith(y2, bad2)
    # (0, 1): good 4, 9, 1, 2, 3 -> n = 5, S = 19, residue 4, mean 3.8 <= 63 / 4: low.
    hits2 = m2.snapshot()["configurations"]["minimal"]["coverpoints"]["dpc.arith"]["bins"]
    assert {k for k, v in hits2.items() if v} == {"(5, 4, 'low')"}
