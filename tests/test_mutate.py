"""``irnuc mutate`` and ``irnuc.verif.mutate``: the catalogue, a small campaign (killed,
equivalent), the cache and ``cached_summary``, the command line.

The full campaign is not run here (see docs/mutation.md for its figures): one catalogue
mutant on the ``minimal`` pipeline and two hand-made ones in the small ``interp_weight``
suite, in a cache of their own.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from irnuc.cosim.sources import HDL_DIR, MODULE_FILES
from irnuc.verif import mutate

#: Every design module of the two-point top, the methods' top, the per-frame weight, the
#: stage tops and the AXI wrapper (assertion checkers and packages have nothing to mutate).
DESIGN = {f.removesuffix(".sv") for top in ("nuc_dpc_top", "method_dpc_top", "interp_weight",
                                            "method_drift_top", "method_ffc_top",
                                            "irnuc_axis_top")
          for f in MODULE_FILES[top]} - {"irnuc_stream_assert", "irnuc_frame_assert",
                                          "irnuc_method_pkg", "irnuc_stage_pkg",
                                          "irnuc_axis_assert", "irnuc_axil_assert",
                                          "irnuc_axil_regs_check", "irnuc_assert_armed",
                                          "irnuc_axil_regblock_pkg"}


def test_catalogue_covers_every_design_module() -> None:
    assert len(mutate.CATALOGUE) >= 30
    assert len({m.id for m in mutate.CATALOGUE}) == len(mutate.CATALOGUE)
    assert {m.file.removesuffix(".sv") for m in mutate.CATALOGUE} == DESIGN
    for m in mutate.CATALOGUE:
        text = (HDL_DIR / m.file).read_text()
        assert text.count(m.find) == 1, m.id
        assert m.apply(text) != text
        assert m.pipeline() is not None


def test_a_stale_mutant_is_a_clear_error() -> None:
    m = mutate.Mutant("x", "nuc_core.sv", "no such text", "y", "test")
    with pytest.raises(ValueError, match="occurs 0 times"):
        m.apply((HDL_DIR / "nuc_core.sv").read_text())
    with pytest.raises(ValueError, match="--only nope: no such mutant"):
        mutate.catalogue(["nope"])
    with pytest.raises(ValueError, match="did you mean 'dpc_no_rounding'"):
        mutate.catalogue(["dpc_no_roundin"])


@pytest.mark.cosim
@pytest.mark.slow
def test_small_campaign_cache_and_cli(tmp_path, own_cache) -> None:
    # The verdicts in a cache of their own; the Verilator builds (the baseline's, the
    # runtime objects) shared with the session (own_cache).
    assert mutate.cached_summary() is None
    # All three in the small interp_weight suite, whose builds and runs take seconds where
    # the two-point suite takes tens (its mutants share the code path: the suite is a
    # field of the mutant). Killed: the weight's quotient bits one place too high.
    # Survived and equivalent: a comment changed (one without an argument, one with).
    picked = mutate.catalogue(["iw_bit_position"])
    iw = {k: getattr(picked[0], k) for k in ("top", "suite", "config")}
    first_line = (HDL_DIR / "interp_weight.sv").read_text().splitlines()[0]
    blind = mutate.Mutant("comment_only", "interp_weight.sv", first_line,
                          first_line + " (changed)", "a comment changed", **iw)
    argued = mutate.Mutant("comment_argued", "interp_weight.sv", first_line,
                           first_line + " (argued)", "a comment changed",
                           equivalent="a comment: the design is the same", **iw)
    s = mutate.run_mutants([*picked, blind, argued], workers=0)
    by_id = {r["id"]: r for r in s["mutants"]}
    # A change no test can see, without an argument: must be reported as survived (the
    # classification can fail), and is not cached as a complete campaign.
    assert by_id["comment_only"]["status"] == "survived" and s["survivors"] == ["comment_only"]
    assert not s["complete"]
    s = mutate.summarize([r for r in s["mutants"] if r["id"] != "comment_only"], 2)
    assert by_id["iw_bit_position"]["status"] == "killed"
    assert by_id["iw_bit_position"]["killed_by"]
    assert by_id["comment_argued"]["status"] == "equivalent"
    assert by_id["comment_argued"]["equivalent"] == "a comment: the design is the same"
    assert (s["killed"], s["survived"], s["equivalent"], s["total"]) == (1, 0, 1, 2)
    assert s["score"] == 1.0
    cached = mutate.cached_summary()
    assert cached is not None and cached["rtl_digest"] == mutate.rtl_digest()
    assert cached["killing_tests"] == {"iw_bit_position":
                                       by_id["iw_bit_position"]["killed_by"]}
    # A second run comes from the cache (the baseline's pass too: its run would leave a
    # fresh results file).
    baseline_xml = next((tmp_path / "cache" / "mutate" / "baseline").glob("*.xml"))
    stamp = baseline_xml.stat().st_mtime_ns
    again = mutate.run_mutants(picked, workers=0)
    assert all(r["cached"] for r in again["mutants"])
    assert baseline_xml.stat().st_mtime_ns == stamp
    # The command line exactly as documented, coverage on (its own process: the test layer
    # does not import irnuc.cli; the coverage run once ended the whole campaign in a
    # ValueError, a testbench named by string and never imported): --out claimed,
    # mutate.json written from the cache, coverage.json from the unmutated design's suite
    # with coverage; a bad id is one line, exit 2.
    irnuc = Path(sys.executable).with_name("irnuc")
    env = {**os.environ, "IRNUC_CACHE_DIR": str(tmp_path / "cache")}
    out = tmp_path / "out"
    proc = subprocess.run([str(irnuc), "mutate", "--only", "iw_bit_position", "--out",
                           str(out), "-q"], env=env, capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr
    data = json.loads((out / "mutate.json").read_text())
    assert data["killed"] == 1 and data["total"] == 1
    assert all(r["cached"] for r in data["mutants"])
    cov = json.loads((out / "coverage.json").read_text())
    assert set(cov) == {"functional", "code"}
    code = next(iter(cov["code"].values()))
    assert "interp_weight" in code and code["interp_weight"]["line"]["hit"] > 0
    bad = subprocess.run([str(irnuc), "mutate", "--only", "nope", "--out",
                          str(tmp_path / "o2")], env=env, capture_output=True, text=True)
    err = bad.stderr.strip().splitlines()
    assert bad.returncode == 2 and len(err) == 1 and "--only nope: no such mutant" in err[0]
    assert not (tmp_path / "o2").exists()


def test_every_suite_a_mutant_names_is_imported() -> None:
    # The coverage run of `irnuc mutate` (and every campaign) reads each mutant's suite
    # from an imported module: in a fresh interpreter, importing the campaign must be
    # enough for every suite of the catalogue, the package check's too.
    code = ("import sys; from irnuc.verif import mutate; from irnuc.cosim import "
            "cocotb_test_names; mods = {m.suite for m in mutate.CATALOGUE} | "
            "{mutate.PKG_SUITE}; print(len(mods)); "
            "print(min(len(cocotb_test_names(m)) for m in mods))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    n_modules, fewest_tests = (int(v) for v in proc.stdout.split())
    assert n_modules >= 10 and fewest_tests >= 1


def test_configs_of_the_per_configuration_run() -> None:
    from irnuc.cosim import configspace

    sample = [c.name for c in configspace.ci_sample()]
    got = [c.name for c in mutate.configurations("sample, minimal")]
    assert got == [*sample, "minimal"] and len(set(got)) == len(got)
    assert [c.name for c in mutate.configurations("minimal")] == ["minimal"]
    for spec, msg in (("minimall", "did you mean 'minimal'"), ("sample,sample", "more than once"),
                      ("", "empty name"), ("minimal,", "empty name"),
                      (sample[0], "no such configuration")):
        with pytest.raises(ValueError, match=msg):
            mutate.configurations(spec)


def test_equivalence_on_some_configurations_only() -> None:
    from irnuc.cosim import configspace

    by_id = {m.id: m for m in mutate.CATALOGUE}
    narrow = {c.name: c for c in configspace.ci_sample()}["ci20-004"]
    assert narrow.max_width == 3
    for mid in ("ctrl_ahead_start", "ctrl_write_current_col"):
        m = by_id[mid]
        assert m.equivalence() is None  # not equivalent everywhere: counted on its own config
        assert m.equivalence(m.pipeline()) is None and m.pipeline().max_width > 3
        assert m.equivalence(narrow).startswith("max_width <= 3: ")
    # The argument rests on dpc_core taking the column word from the window for W <= 3.
    core = (HDL_DIR / "dpc_core.sv").read_text()
    assert "if (lb_w1) begin" in core and "end else if (lb_w3) begin" in core
    # A mutant equivalent everywhere stays so on every configuration.
    m = by_id["ctrl_idle_read_col"]
    assert m.equivalence(narrow) == m.equivalence() == m.equivalent
    # The frame-size mutants on one-pixel-wide, -high and 1 x 1 frames (the sample's
    # ci20-179 is 1 x 263, ci20-072 1 x 1): equivalent exactly where the size they test
    # cannot change; on the 3 x 15 configuration every one counts.
    sample = {c.name: c for c in configspace.ci_sample()}
    wide1, pixel1 = sample["ci20-179"], sample["ci20-072"]
    assert (wide1.max_width, pixel1.max_width, pixel1.max_height) == (1, 1, 1)
    assert wide1.max_height > 1
    on_wide1 = {"ctrl_same_no_width", "ctrl_col_next_last", "ctrl_flush_short"}
    on_high1 = {"ctrl_same_no_height", "ctrl_row_last_width", "ctrl_top_is_bottom"}
    for mid in on_wide1 | on_high1 | {"ctrl_tail_no_flush"}:
        m = by_id[mid]
        assert m.equivalence() is None and m.equivalence(narrow) is None, mid
        assert (m.equivalence(wide1) is not None) == (mid in on_wide1), mid
        assert m.equivalence(pixel1) is not None, mid
    assert pixel1.max_frame_pixels == 1 and wide1.max_frame_pixels == wide1.max_height


def test_suite_closure_follows_imports_only() -> None:
    # A mutant's cached verdict is keyed by the files its suite runs: the wrapper's FFC suite
    # runs its own testbench, the shared bench and the build layer, not the other suites.
    def names(suite: str) -> set[str]:
        return {p.relative_to(mutate.IRNUC_DIR).as_posix()
                for p in mutate.suite_closure(f"irnuc.cocotb_tests.{suite}")}

    ffc, top = names("tb_axis_ffc"), names("tb_top")
    assert {"cocotb_tests/tb_axis_ffc.py", "cocotb_tests/axis_bench.py",
            "cocotb_tests/axil_traffic.py", "cosim/builds.py", "cosim/_cocotb_adapter.py",
            "nuc_fixed/axis.py", "cocotb_tests/__init__.py", "__init__.py"} <= ffc
    assert "cocotb_tests/tb_axis_method.py" not in ffc
    assert "cocotb_tests/tb_top.py" in top and "cocotb_tests/tb_axis_ffc.py" not in top
    assert not any(n.startswith(("verif/", "reports/", "cli")) or n.startswith("test_")
                   or "/test_" in n for n in ffc | top)


def test_imported_names_reads_what_runs(tmp_path: Path) -> None:
    src = tmp_path / "m.py"
    src.write_text(
        "from typing import TYPE_CHECKING\n"
        "import irnuc.a\n"
        "from . import sib\n"
        "from .pkg import thing\n"
        "if TYPE_CHECKING:\n"
        "    import irnuc.only_for_types\n"
        "else:\n"
        "    import irnuc.at_run_time\n"
        "def f():\n"
        "    try:\n"
        "        from irnuc.lazy import x\n"
        "    except ImportError:\n"
        "        import irnuc.fallback\n"
        "    return [1 for _ in ()]\n")
    got = mutate._imported_names(src, "irnuc.cosim")
    assert {"irnuc.a", "irnuc.cosim", "irnuc.cosim.sib", "irnuc.cosim.pkg",
            "irnuc.cosim.pkg.thing", "irnuc.at_run_time", "irnuc.lazy", "irnuc.lazy.x",
            "irnuc.fallback"} <= got
    assert "irnuc.only_for_types" not in got
