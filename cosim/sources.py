"""The RTL sources (``hdl/``, installed as ``irnuc.hdl``) and the parameters of each top.

Widths and modes come only from a :class:`~irnuc.nuc_fixed.config.PipelineConfig`
(``rtl_parameters``); this module decides which of them a given top module takes.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import irnuc.hdl
from irnuc.common.errors import UserError
from irnuc.nuc_fixed import methods
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.methods import rtl as methods_rtl

#: Folder of the SystemVerilog sources (the design).
HDL_DIR = Path(irnuc.hdl.__file__).resolve().parent
#: Simulation-only HDL of the co-simulation (the package probe, the batched transactor),
#: not the design.
SIM_HDL_DIR = Path(__file__).resolve().parent / "hdl"

_PKG = ("irnuc_pkg.sv", "irnuc_method_pkg.sv")
#: The arming flop of every simulation check (irnuc_assert_armed), then the stream checker.
_ARMED = ("irnuc_assert_armed.sv",)
_ASSERT = (*_ARMED, "irnuc_stream_assert.sv")
_FRAME = (*_ARMED, "irnuc_frame_assert.sv")
_SPILL = (*_ASSERT, "irnuc_spill_register.sv")
_MUL = ("irnuc_dsp_mul.sv", "irnuc_mul_parts.sv")
_ARITH = (*_MUL, "irnuc_add_tree.sv", "irnuc_round.sv", "irnuc_clip.sv")
_NUC = (*_SPILL, *_MUL, "irnuc_add_tree.sv", "nuc_core.sv")
_DPC = (*_SPILL, *_FRAME, *_MUL, "irnuc_add_tree.sv", "irnuc_line_buffer.sv",
        "dpc_ctrl.sv", "dpc_core.sv")
# The end of a core (round, OUT, output register), shared by the cores that sum parts.
_CORE_OUT = (*_ASSERT, "irnuc_axis_buffer.sv", "irnuc_round.sv", "irnuc_clip.sv", "core_out.sv")
_PWL = tuple(dict.fromkeys((*_SPILL, *_ARITH, *_CORE_OUT, "pwl_core.sv")))
_QUAD = tuple(dict.fromkeys((*_SPILL, *_ARITH, *_CORE_OUT, "quad_core.sv")))

def _module_files() -> dict[str, tuple[str, ...]]:
    """Module -> the HDL files it needs, in dependency order (one module per file; the
    packages first), the methods' from the registry (:func:`module_files`)."""
    # The methods' fronts (hdl/<MethodSpec.rtl_module>.sv and what it instantiates), every one
    # behind the same ports, and frame_coefficients, which picks the configured method's; the
    # core of each kind (method_core) and the DPC tail of every top.
    fronts = {m.rtl_module: tuple(dict.fromkeys((*_SPILL, *_ARITH, *_ARMED, *m.rtl_files,
                                                   f"{m.rtl_module}.sv")))
               for m in methods.BASES.values()}
    frame_coef = (*dict.fromkeys(f for files in fronts.values() for f in files),
                   "frame_coefficients.sv")
    method_core = tuple(dict.fromkeys((*_NUC, *_PWL, *_QUAD, "method_core.sv")))
    tail = (*_DPC, "dpc_tail.sv")

    files: dict[str, tuple[str, ...]] = {
        "nuc_core": (*_PKG, *_NUC),
        "dpc_core": (*_PKG, *_DPC),
        "nuc_dpc_top": tuple(dict.fromkeys((*_PKG, *_NUC, *tail, "nuc_dpc_top.sv"))),
        "pwl_core": (*_PKG, *_PWL),
        "quad_core": (*_PKG, *_QUAD),
        "method_dpc_top": tuple(dict.fromkeys((*_PKG, *frame_coef, *method_core, *tail,
                                               "method_dpc_top.sv"))),
        **{name: (*_PKG, *files) for name, files in fronts.items()},
        "frame_coefficients": (*_PKG, *frame_coef),
        "method_core": (*_PKG, *method_core),
        "dpc_tail": (*_PKG, *tail),
        "dpc_ctrl": (*_PKG, *_ARMED, "dpc_ctrl.sv"),
        "irnuc_spill_register": _SPILL,
        "irnuc_stream_assert": _ASSERT,
        "irnuc_frame_assert": (*_PKG, *_FRAME),
        "irnuc_add_tree": ("irnuc_add_tree.sv",),
        "irnuc_mul_parts": (*_PKG, *_MUL),
        "irnuc_dsp_mul": ("irnuc_dsp_mul.sv",),
        "irnuc_round": (*_PKG, "irnuc_round.sv"),
        "irnuc_clip": (*_PKG, "irnuc_clip.sv"),
        "interp_weight": (*_PKG, "interp_weight.sv"),
        "irnuc_line_buffer": (*_PKG, "irnuc_line_buffer.sv"),
        "irnuc_pkg_probe": (*_PKG, "irnuc_pkg_probe.sv"),
    }
    # Each file of a method's front on its own (tc_poly, table_interp, ...).
    for m in methods.BASES.values():
        for i, f in enumerate(m.rtl_files):
            files[f.removesuffix(".sv")] = (*_PKG, *_SPILL, *_ARITH, *m.rtl_files[:i + 1])
    # The AXI top: the core, the framer, the register file and the AXI protocol checkers.
    axi_assert = ("irnuc_axis_assert.sv", "irnuc_axil_assert.sv")
    # The register block generated from nuc_fixed/registers.rdl (its package first) and the
    # hand-written register file around it (cosim/regfiles.py, docs/regmap.md).
    regblock = ("irnuc_axil_regblock_pkg.sv", "irnuc_axil_regblock.sv")
    regs = (*regblock, "irnuc_axil_regs_check.sv", "irnuc_ffc_trigger.sv", "irnuc_axil_regs.sv")
    files["irnuc_axil_regblock"] = regblock
    files["irnuc_axil_regs"] = (*_PKG, *_ARMED, *regs)
    files["irnuc_axis_framer"] = (*_PKG, *_SPILL, "irnuc_axis_framer.sv")
    files["irnuc_axis_buffer"] = (*_ASSERT, "irnuc_axis_buffer.sv")
    files["irnuc_axis_assert"] = (*_ARMED, "irnuc_axis_assert.sv")
    files["irnuc_axil_assert"] = (*_PKG, *_ARMED, "irnuc_axil_assert.sv")
    files["irnuc_axil_regs_check"] = (*_PKG, *_ARMED, "irnuc_axil_regs_check.sv")
    files["irnuc_ffc_trigger"] = (*_ARMED, "irnuc_ffc_trigger.sv")
    files["irnuc_axis_top"] = tuple(dict.fromkeys((
        *files["nuc_dpc_top"], *files["method_dpc_top"], *axi_assert,
        *regs, "irnuc_axis_framer.sv", "irnuc_axis_buffer.sv", "interp_weight.sv",
        "irnuc_axis_table.sv", "irnuc_axis_top.sv")))
    # table_interp's weight and table pair per frame from the registers (irnuc_axis_top).
    files["irnuc_axis_table"] = (*_PKG, *_ARMED, "interp_weight.sv", "irnuc_axis_table.sv")
    # Simulation-only transactor around the top (batched cocotb driver, cosim/hdl/).
    files["nuc_dpc_batch"] = (*files["nuc_dpc_top"], "nuc_dpc_batch.sv")

    # ---- the stages (blind_drift, ffc) and their composition tops (docs/rtl.md "Stages") -----
    spkg = (*_PKG, "irnuc_stage_pkg.sv")
    core_sum = (*_ARITH, "core_sum.sv")
    blind = (*_SPILL, "irnuc_round.sv", "irnuc_clip.sv", "blind_drift.sv")
    files |= {
        "core_sum": (*spkg, *core_sum),
        "core_out": (*_PKG, *_CORE_OUT),
        "drift_sub": ("drift_sub.sv",),
        "blind_drift": (*_PKG, *blind),
        "method_drift_top": tuple(dict.fromkeys((*spkg, *blind, "drift_sub.sv", *frame_coef,
                                                 *core_sum, *_CORE_OUT, *tail,
                                                 "method_drift_top.sv"))),
        "ffc_ctrl": (*spkg, "ffc_ctrl.sv"),
        "ffc_mean": (*_ARMED, "ffc_mean.sv"),
        "ffc_refresh": (*_PKG, "irnuc_round.sv", "irnuc_clip.sv", "ffc_refresh.sv"),
        "ffc_sums": (*spkg, *core_sum, "ffc_sums.sv"),
        "method_ffc_top": tuple(dict.fromkeys((*spkg, *_SPILL, "irnuc_axis_buffer.sv",
                                               "ffc_ctrl.sv", "ffc_mean.sv", *frame_coef,
                                               *core_sum, "ffc_sums.sv", *_CORE_OUT,
                                               "ffc_refresh.sv", *tail, "method_ffc_top.sv"))),
    }
    # The AXI top builds method_ffc_top for the ffc configurations (its parameter Ffc).
    # Its core and FFC side (irnuc_axis_core, irnuc_axis_ffc) are modules of their own.
    files["irnuc_axis_ffc"] = tuple(dict.fromkeys((
        *files["method_ffc_top"], "irnuc_axis_ffc.sv")))
    files["irnuc_axis_core"] = tuple(dict.fromkeys((
        *files["nuc_dpc_top"], *files["method_dpc_top"],
        *files["irnuc_axis_ffc"], *files["method_drift_top"],
        "irnuc_axis_assert.sv", "irnuc_axis_core.sv")))
    files["irnuc_axis_top"] = tuple(dict.fromkeys((
        *files["irnuc_axis_core"], *files["irnuc_axis_top"][:-1],
        "irnuc_axis_top.sv")))
    files["irnuc_assert_armed"] = _ARMED
    # The smoke testbench of the FuseSoC core's sim target (hdl/tb/: beside the core file,
    # not the design).
    files["irnuc_axis_top_tb"] = (*files["irnuc_axis_top"], "tb/irnuc_axis_top_tb.sv")
    # A file needed twice (the arming flop through two checkers) is compiled once.
    files = {k: tuple(dict.fromkeys(v)) for k, v in files.items()}
    return files


_FILES_OF: dict[tuple[str, ...], dict[str, tuple[str, ...]]] = {}


def module_files() -> dict[str, tuple[str, ...]]:
    """Module -> the HDL files it needs, for the methods registered now (a test may
    register one; :data:`MODULE_FILES` is the shipped registry's)."""
    key = tuple(methods.BASES)
    if key not in _FILES_OF:
        _FILES_OF[key] = _module_files()
    return _FILES_OF[key]


#: Module -> the HDL files it needs (the shipped methods'; :func:`module_files`). Files are
#: looked up in ``hdl/``, then in ``cosim/hdl/``.
MODULE_FILES: dict[str, tuple[str, ...]] = module_files()


#: The design's protocol assertions (SVA in ``hdl/`` under `ifdef IRNUC_ASSERT): every
#: simulation build and the lint define it, synthesis does not.
ASSERT_DEFINE = "+define+IRNUC_ASSERT"

def method_cores() -> dict[str, tuple[str, ...]]:
    """The modules each base method's datapath is checked in on its own
    (``MethodSpec.rtl_checked``; method_dpc_top holds every method)."""
    return {m.name: m.rtl_checked for m in methods.BASES.values()}


def method_parameters(cfg: PipelineConfig) -> dict[str, int]:
    """The SV parameters of ``method_dpc_top`` (and its cores) beyond
    :meth:`~PipelineConfig.rtl_parameters`: ``Method`` (the base method's code, its index
    in the registry, ``irnuc_pkg::method_e``), every format's ``<Name>IntBits`` /
    ``<Name>FracBits`` (and a computed format's modes: ``WeightRounding``) and every
    parameter of the base method (``SquareBits``, ``TcOrder``, ``TcGain``,
    ``ReadingBits``, ...), from the registry (``nuc_fixed.methods.rtl_parameters``).

    Raises :class:`UserError` for a method with stages (``blind_drift``, ``ffc``): the RTL
    has the base methods.
    """
    if cfg.stages:
        raise UserError(f"pipeline {cfg.name!r}: method {cfg.method!r} has stages "
                        f"({', '.join(cfg.stages)}); method_dpc_top implements the "
                        f"base methods {', '.join(methods.BASES)} (the stages: "
                        f"{', '.join(STAGE_TOPS.values())})")
    return _base_parameters(cfg)


def _base_parameters(cfg: PipelineConfig) -> dict[str, int]:
    """:func:`method_parameters` of the base method of any configuration."""
    return {"Method": list(methods.BASES).index(cfg.base_method),
            **methods.rtl_parameters(cfg, (cfg.base,))}


#: Parameters of the generic building blocks for a configuration: the sizes they get
#: inside nuc_dpc_top (for the lint of every module).
_BLOCK_PARAMETERS = {
    "irnuc_spill_register": lambda p: {"DataBits": p["OutBits"] + 2},
    "irnuc_stream_assert": lambda p: {"DataBits": p["OutBits"] + 2},
    "irnuc_frame_assert": lambda p: {"MaxWidth": p["MaxWidth"], "MaxHeight": p["MaxHeight"]},
    "irnuc_add_tree": lambda p: {"Leaves": 9, "Width": p["OutBits"] + 3, "SideBits": 4},
    "irnuc_mul_parts": lambda p: {"ABits": p["AdcBits"],
                                  "BBits": p["GainIntBits"] + p["GainFracBits"]},
    "irnuc_line_buffer": lambda p: {"Depth": p["MaxWidth"], "DataBits": 2 * p["OutBits"] + 2},
    "irnuc_axis_assert": lambda p: {"DataBits": 8 * ((p["AdcBits"] + 7) // 8), "UserBits": 1},
    "irnuc_axis_buffer": lambda p: {"DataBits": p["AdcBits"] + 2},
    "irnuc_axil_assert": lambda p: {},
    "irnuc_assert_armed": lambda p: {},
    "irnuc_axil_regs_check": lambda p: {"MaxWidth": p["MaxWidth"], "MaxHeight": p["MaxHeight"]},
    "irnuc_ffc_trigger": lambda p: {},
    "irnuc_axil_regblock": lambda p: {},  # generated: no parameter
    "irnuc_axis_top_tb": lambda p: {},  # irnuc_axis_top at its defaults
    "irnuc_round": lambda p: {"InBits": p["AdcBits"] + 20, "FracBits": 14,
                              "Rounding": p["Rounding"]},
    "irnuc_clip": lambda p: {"InBits": p["OutBits"] + 4, "OutBits": p["OutBits"],
                             "Overflow": p["Overflow"]},
    "irnuc_dsp_mul": lambda p: {},
}

def register_file_parameters(cfg: PipelineConfig) -> dict[str, int]:
    """The parameters of ``irnuc_axil_regs`` for ``cfg``: the widths and modes, the method
    (code, stages) and the width of every method register slot (``RegisterSlot`` of the
    registry: 0 where the method has none)."""
    from irnuc.nuc_fixed.regmap import config_params

    p = cfg.rtl_parameters()
    c = config_params(cfg)
    return {**p, "MethodCode": c["MethodCode"], "HasBlindDrift": c["HasBlindDrift"],
            "HasFfc": c["HasFfc"], "FfcFrames": c["FfcFrames"],
            "CoefLayoutVersion": c["CoefLayoutVersion"],
            # CONFIG.word_bits: the method's coefficient word (irnuc_axis_top passes its
            # WordBits; the module's default is two_point's).
            "CoefWordBits": c["WordBits"], **methods.slot_parameters(cfg)}


def tool_parameters(params: Mapping[str, int], tool: str) -> dict[str, str]:
    """The ``-G`` values of ``params`` in a tool's syntax (``verilator`` or ``slang``).

    A typed enum parameter (a top's ``Method``, ``irnuc_pkg::method_e``) is given as a
    sized constant to Verilator (``3'd4``: a 32-bit integer is truncated with a warning)
    and as its literal to slang (``irnuc_pkg::MethodTcOffset``: slang converts no integer
    to an enum); the others as integers.
    """
    from irnuc.nuc_fixed.rtl_spec import METHOD

    # name -> (bits, package, literals by code): method_e, and method_core's core_kind_e.
    enums = {"Method": (METHOD.bits, "irnuc_pkg", [lit.name for lit in METHOD.literals]),
             "Kind": (2, "irnuc_method_pkg", list(methods_rtl.CORE_KINDS.values()))}
    out = {}
    for k, v in params.items():
        e = enums.get(k)
        if e is None:
            out[k] = str(int(v))
        elif tool == "verilator":
            out[k] = f"{e[0]}'d{int(v)}"
        else:
            out[k] = f"{e[1]}::{e[2][int(v)]}"
    return out


def verilator_g(params: Mapping[str, int]) -> list[str]:
    """Verilator's ``-G`` options of ``params`` (:func:`tool_parameters`)."""
    return [f"-G{k}={v}" for k, v in tool_parameters(params, "verilator").items()]


def hdl_sources(top: str, hdl_dir: Path | None = None) -> list[Path]:
    """HDL files needed to elaborate module ``top``.

    ``hdl_dir`` replaces ``hdl/`` (a modified copy of the design, e.g. a mutant); files it
    lacks are taken from ``cosim/hdl/``.
    """
    files = module_files()
    if top not in files:
        raise UserError(f"unknown HDL top {top!r}; known: {', '.join(sorted(files))}")
    base = Path(hdl_dir) if hdl_dir is not None else HDL_DIR
    return [base / name if (base / name).is_file() else SIM_HDL_DIR / name
            for name in files[top]]


def _values(cfg: PipelineConfig) -> dict[str, int]:
    """Every RTL parameter ``cfg`` decides: the base ones, ``Method``, the formats and
    parameters of its base method and stages, the flags of its stages (irnuc_axis_top's
    ``Ffc``, ``Drift``: only those set)."""
    return {**cfg.rtl_parameters(), "Method": list(methods.BASES).index(cfg.base_method),
            **methods.rtl_parameters(cfg),
            **{s.rtl_flag: 1 for s in cfg.parts[1:] if s.rtl_flag}}


def _check_stage_top(top: str, cfg: PipelineConfig) -> None:
    """A stage's top (or its part of irnuc_axis_top's core) is built only for a
    configuration of that stage and a base method it composes with."""
    for s in methods.STAGES.values():
        if top in (s.rtl_top, s.rtl_wrapper):
            stage_parameters(s.rtl_top, cfg)


def top_parameters(top: str, cfg: PipelineConfig) -> dict[str, int]:
    """The SV parameters of ``top`` for configuration ``cfg`` (a subset of the top's): for a
    top with a generated header (``nuc_fixed.methods.rtl``), a method front and
    frame_coefficients, those of its parameters ``cfg`` decides."""
    hdl_sources(top)
    params = cfg.rtl_parameters()
    if top == "irnuc_axil_regs":
        return register_file_parameters(cfg)
    generated = methods_rtl.modules()
    fronts = {m.rtl_module for m in methods.BASES.values()}
    if top in generated or top in fronts or top == "frame_coefficients":
        if top == "method_dpc_top":
            method_parameters(cfg)  # a method with a stage is refused
        _check_stage_top(top, cfg)
        spec = generated.get(top)
        if spec is not None and spec.flags and cfg.stages:
            stage_parameters(stage_top(cfg) or "method_dpc_top", cfg)
        names = methods_rtl.parameters_of(top)
        if spec is not None and spec.flags and cfg.plain:
            return {k: v for k, v in params.items() if k in names}  # nuc_dpc_top inside
        vals = _values(cfg)
        if top == cfg.base.rtl_module:  # a front shared by methods: the one cfg has
            vals |= dict.fromkeys(cfg.base.rtl_front_flags, 1)
        return {k: vals[k] for k in names if k in vals}
    if top == "method_core":
        vals = {**_values(cfg), "Kind": list(methods_rtl.CORE_KINDS).index(cfg.base.core)}
        return {k: vals[k] for k in methods_rtl.module_parameters(top, HDL_DIR) if k in vals}
    if top == "dpc_tail":
        return {k: params[k] for k in ("OutBits", "MaxWidth", "MaxHeight")}
    if top in _STAGE_BLOCKS:
        want = stage_top(cfg)
        if want is None:
            raise UserError(f"pipeline {cfg.name!r}: {top} is a block of the stage tops; "
                            f"method {cfg.method!r} has no stage")
        p = stage_parameters(want, cfg)
        declared = methods_rtl.module_parameters(top, hdl_sources(top)[-1].parent)
        return {k: p[k] for k in declared if k in p}
    if top in _BLOCK_PARAMETERS:
        return _BLOCK_PARAMETERS[top](params)
    # Any other module: the parameters its file declares that cfg decides.
    vals = _values(cfg)
    declared = methods_rtl.module_parameters(top, hdl_sources(top)[-1].parent)
    return {k: vals[k] for k in declared if k in vals}


# ---- the stages -------------------------------------------------------------------------

#: The composition top of each stage (a configuration has at most one stage).
STAGE_TOPS: dict[str, str] = {s.name: s.rtl_top for s in methods.STAGES.values()}
#: The base methods each stage top composes with (its parameter ``Method``).
STAGE_BASES: dict[str, tuple[str, ...]] = {s.rtl_top: s.rtl_bases
                                           for s in methods.STAGES.values()}


#: The blocks of the stage tops (the lint of every module, at the sizes it gets in its top:
#: the parameters its file declares, of its top's).
_STAGE_BLOCKS = ("blind_drift", "drift_sub", "core_sum", "core_out", "ffc_ctrl", "ffc_mean",
                 "ffc_refresh", "ffc_sums")


def stage_top(cfg: PipelineConfig) -> str | None:
    """The composition top of a configuration with a stage (None without one)."""
    for stage in cfg.stages:
        if stage in STAGE_TOPS:
            return STAGE_TOPS[stage]
    return None


def stage_parameters(top: str, cfg: PipelineConfig) -> dict[str, int]:
    """The SV parameters of a stage top: those of ``method_dpc_top`` for the base method
    and the stage's (blind_drift: ``BlindMax``, ``Drift*``, ``DriftGain*``; ffc:
    ``FfcFrames``, ``FfcHold``, ``Ffc*``). Raises :class:`UserError` for a base method the
    stage top does not compose with (:data:`STAGE_BASES`)."""
    want = stage_top(cfg)
    if want != top:
        raise UserError(f"pipeline {cfg.name!r}: method {cfg.method!r} has no {top} "
                        f"(its top: {want or 'method_dpc_top'})")
    if cfg.base_method not in STAGE_BASES[top]:
        raise UserError(f"pipeline {cfg.name!r}: {top} composes {cfg.stages[0]} with "
                        f"{', '.join(STAGE_BASES[top])}, not {cfg.base_method!r} (not in "
                        f"RTL yet)")
    params = {**cfg.rtl_parameters(), **_base_parameters(cfg)}
    params.pop("Tables", None)
    return params | methods.rtl_parameters(cfg, cfg.parts[1:])
