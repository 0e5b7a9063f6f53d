"""Mutants nobody chose (``irnuc mutate --auto``, ``irnuc.verif.automut``): Yosys's draw
with a fixed seed, the netlist behind the top's header, the mutation machinery's verdicts
and the formal decision on a survivor (a miter of the two netlists).

A small campaign runs here, in the ``interp_weight`` suite (builds and runs of seconds),
its verdicts in a cache of its own; the full one is ``irnuc mutate --auto N``
(docs/mutation.md).
"""

from __future__ import annotations

import dataclasses
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from irnuc.cosim import netlist
from irnuc.cosim.sources import HDL_DIR, MODULE_FILES
from irnuc.verif import automut, mutate


def test_targets_and_wrapper() -> None:
    for t in automut.TARGETS.values():
        assert f"{t.module}.sv" in MODULE_FILES[t.top], t
        assert (HDL_DIR / f"{t.module}.sv").is_file()
    with pytest.raises(ValueError, match="--modules nope: no such module"):
        automut.targets("nope")
    text = (HDL_DIR / "irnuc_axis_top.sv").read_text()
    w = netlist.wrapper(text, "irnuc_axis_top", "mut")
    # The top's own parameters and ports, then the netlist by name.
    assert "parameter method_e                  Method" in w and "output logic                  irq_o" in w
    assert w.rstrip().endswith("irnuc_axis_top__mut u_netlist (.*);\nendmodule")
    assert "always_ff" not in w


@pytest.mark.cosim
@pytest.mark.slow
def test_small_automatic_campaign(tmp_path, own_cache) -> None:
    from irnuc.cosim import formal

    t = automut.TARGETS["interp_weight"]
    drawn = automut.draw(t, 3)
    # A fixed seed draws the same mutations; another seed others.
    assert [m.yosys for m in drawn] == [m.yosys for m in automut.draw(t, 3)]
    assert [m.yosys for m in drawn] != [m.yosys for m in automut.draw(t, 3, seed=2)]
    assert all(m.yosys.startswith("mutate -mode ") and "-src" not in m.yosys for m in drawn)
    assert all("interp_weight.sv:" in m.what for m in drawn)
    s = automut.run_auto([t], 2, workers=0)
    assert s["total"] == 2 and s["n"] == 2 and not s["complete"]
    for r in s["mutants"]:
        assert r["status"] in ("killed", "survived", "equivalent"), r
        if r["status"] != "killed":  # a survivor is decided, not argued
            assert r["decided"]["verdict"] in ("equivalent", "different", "undecided"), r
    assert s["per_module"]["interp_weight"]["killed"] == s["killed"] >= 1
    # The decision: the unmutated netlist is proved equivalent to itself; a killed mutant's
    # netlist differs, with a trace from reset.
    cfg = drawn[0].pipeline()
    killed = next(m for m in drawn if m.id in s["killing_tests"])
    gold, mut, ports = mutate._netlists(killed, cfg, tmp_path / "k")
    unmutated = dataclasses.replace(killed, yosys="")
    _, copy, _ = mutate._netlists(unmutated, cfg, tmp_path / "u")
    same = formal.equivalence(gold, copy, "interp_weight", ports, tmp_path / "same")
    assert same["verdict"] == "equivalent" and same["engine"] == "equiv_induct"
    diff = formal.equivalence(gold, mut, "interp_weight", ports, tmp_path / "diff")
    assert diff["verdict"] == "different" and Path(diff["vcd"]).is_file()
    assert diff["step"] is not None and diff["step"] > 0
    # The command line from the cache: mutate.json, per module.
    irnuc = Path(sys.executable).with_name("irnuc")
    env = {**os.environ, "IRNUC_CACHE_DIR": str(tmp_path / "cache")}
    proc = subprocess.run([str(irnuc), "mutate", "--auto", "2", "--modules", "interp_weight",
                           "--workers", "0", "--out", str(tmp_path / "out"), "-q"], env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode in (0, 1), proc.stderr
    data = json.loads((tmp_path / "out" / "mutate.json").read_text())
    assert all(r["cached"] for r in data["mutants"]) and data["killed"] == s["killed"]
    bad = subprocess.run([str(irnuc), "mutate", "--auto", "2", "--only", "x", "--out",
                          str(tmp_path / "o2")], env=env, capture_output=True, text=True)
    assert bad.returncode == 2 and "--auto draws its own mutants" in bad.stderr


def test_draw_reads_a_typed_enum_parameter_as_its_literal() -> None:
    # slang refuses `-G Method=5` (no implicit int -> method_e): every configuration but the
    # two-point ones failed to draw. The literal named by the package, the rest as integers.
    from irnuc.cosim import netlist
    from irnuc.cosim.sources import top_parameters
    from irnuc.nuc_fixed import load_pipeline

    params = top_parameters("irnuc_axis_top", load_pipeline("table14"))
    read = netlist._read([], "irnuc_axis_top", params)[0]
    assert "-G Method=irnuc_pkg::Method" in read and f"-G Method={params['Method']} " not in read
    assert f"-G AdcBits={params['AdcBits']} " in read


def test_miter_decision_cached_apart_from_the_suite(tmp_path, monkeypatch) -> None:
    # A survivor's miter (up to 20 minutes) depends on the netlists only: a testbench change
    # re-keys the mutant's verdict but must not run the same miter again; --no-cache does.
    from irnuc.cosim import formal
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.verif import mutate
    from irnuc.verif.mutant import Mutant

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    calls = []
    monkeypatch.setattr(mutate, "_netlists", lambda m, cfg, work: ("g", "m", {}))
    monkeypatch.setattr(formal, "equivalence",
                        lambda *a: calls.append(a) or {"verdict": "undecided", "n": len(calls)})
    m = Mutant("auto_interp_weight_s9_0", "interp_weight.sv", "", "", "x", config="table14",
               top="interp_weight", suite="irnuc.cocotb_tests.tb_interp_weight",
               yosys="mutate -mode inv -cell $1")
    cfg = load_pipeline("table14")
    first = mutate._decide(m, cfg, tmp_path)
    assert mutate._decide(m, cfg, tmp_path) == first and len(calls) == 1
    other = Mutant(**{**m.__dict__, "yosys": "mutate -mode inv -cell $2"})
    mutate._decide(other, cfg, tmp_path)
    mutate._decide(m, cfg, tmp_path, use_cache=False)
    assert len(calls) == 3


_ONE_WORD = """module one_word (
  input  logic       clk_i,
  input  logic       rst_ni,
  input  logic [3:0] d_i,
  output logic       v_o,
  output logic [3:0] q_o
);
  logic [3:0] node_q [1];
  always_ff @(posedge clk_i or negedge rst_ni) if (!rst_ni) v_o <= 1'b0; else v_o <= 1'b1;
  always_ff @(posedge clk_i) node_q[0] <= d_i;
  assign q_o = node_q[0]{tail};
endmodule
"""


def test_miter_of_netlists_with_a_one_word_array(tmp_path) -> None:
    """An unreset unpacked array of one element (an adder tree's level of one node) is a
    one-word memory in a Yosys-written netlist; the miter's model still builds (Yosys's
    write_smt2 asserted on the zero-width address decode of memory_map;
    formal.write_models folds it) and the decision finds the changed output, one cycle
    after reset."""
    from irnuc.cosim import formal

    nets = {}
    for tag, tail in (("gold", ""), ("mut", " ^ 4'd1")):
        (tmp_path / tag).mkdir()
        src = tmp_path / tag / "one_word.sv"
        src.write_text(_ONE_WORD.replace("{tail}", tail))
        nets[tag] = netlist.write_netlist([src], "one_word", {}, tmp_path / f"n_{tag}" / "n.v",
                                          tag)
    assert "node_q [0:0]" in nets["gold"].read_text()  # the netlist keeps the one-word memory
    ports = netlist.ports(nets["gold"])
    res = formal.equivalence(nets["gold"], nets["mut"], "one_word", ports, tmp_path / "eq",
                             timeout=60)
    assert res["verdict"] == "different" and res["step"] == 1, res
