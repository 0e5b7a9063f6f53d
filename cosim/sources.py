"""The RTL sources (``hdl/``, installed as ``irnuc.hdl``) and the parameters of each top.

Widths and modes come only from a :class:`~irnuc.nuc_fixed.config.PipelineConfig`
(``rtl_parameters``); this module decides which of them a given top module takes.
"""

from __future__ import annotations

from pathlib import Path

import irnuc.hdl
from irnuc.common.errors import UserError
from irnuc.nuc_fixed.config import PipelineConfig

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
_TC = (*_SPILL, *_ARITH, "tc_reading.sv", "tc_poly.sv")
_TABLE = (*_SPILL, *_ARITH, "table_interp.sv")

#: Module -> the HDL files it needs, in dependency order (one module per file; the
#: packages first). Files are looked up in ``hdl/``, then in ``cosim/hdl/``.
MODULE_FILES: dict[str, tuple[str, ...]] = {
    "nuc_core": (*_PKG, *_NUC),
    "dpc_core": (*_PKG, *_DPC),
    "nuc_dpc_top": tuple(dict.fromkeys((*_PKG, *_NUC, *_DPC, "nuc_dpc_top.sv"))),
    "pwl_core": (*_PKG, *_PWL),
    "quad_core": (*_PKG, *_QUAD),
    "tc_poly": (*_PKG, *_TC),
    "table_interp": (*_PKG, *_TABLE),
    "method_dpc_top": tuple(dict.fromkeys((*_PKG, *_NUC, *_PWL, *_QUAD, *_TC, *_TABLE,
                                           *_DPC, "method_dpc_top.sv"))),
    "dpc_ctrl": (*_PKG, *_ARMED, "dpc_ctrl.sv"),
    "irnuc_spill_register": _SPILL,
    "irnuc_stream_assert": _ASSERT,
    "irnuc_frame_assert": (*_PKG, *_FRAME),
    "irnuc_add_tree": ("irnuc_add_tree.sv",),
    "irnuc_mul_parts": (*_PKG, *_MUL),
    "irnuc_dsp_mul": ("irnuc_dsp_mul.sv",),
    "irnuc_round": (*_PKG, "irnuc_round.sv"),
    "irnuc_clip": (*_PKG, "irnuc_clip.sv"),
    "tc_reading": (*_PKG, *_MUL, "irnuc_add_tree.sv", "tc_reading.sv"),
    "interp_weight": (*_PKG, "interp_weight.sv"),
    "irnuc_line_buffer": (*_PKG, "irnuc_line_buffer.sv"),
    "irnuc_pkg_probe": (*_PKG, "irnuc_pkg_probe.sv"),
}
# The AXI top: the core, the framer, the register file and the AXI protocol checkers.
_AXI_ASSERT = ("irnuc_axis_assert.sv", "irnuc_axil_assert.sv")
_REGS = ("irnuc_axil_regs_check.sv", "irnuc_axil_regs.sv")
MODULE_FILES["irnuc_axil_regs"] = (*_PKG, *_ARMED, *_REGS)
MODULE_FILES["irnuc_axis_framer"] = (*_PKG, *_SPILL, "irnuc_axis_framer.sv")
MODULE_FILES["irnuc_axis_buffer"] = (*_ASSERT, "irnuc_axis_buffer.sv")
MODULE_FILES["irnuc_axis_assert"] = (*_ARMED, "irnuc_axis_assert.sv")
MODULE_FILES["irnuc_axil_assert"] = (*_PKG, *_ARMED, "irnuc_axil_assert.sv")
MODULE_FILES["irnuc_axil_regs_check"] = (*_PKG, *_ARMED, "irnuc_axil_regs_check.sv")
MODULE_FILES["irnuc_axis_top"] = tuple(dict.fromkeys((
    *MODULE_FILES["nuc_dpc_top"], *MODULE_FILES["method_dpc_top"], *_AXI_ASSERT,
    *_REGS, "irnuc_axis_framer.sv", "irnuc_axis_buffer.sv", "interp_weight.sv",
    "irnuc_axis_table.sv", "irnuc_axis_top.sv")))
# table_interp's weight and table pair per frame from the registers (irnuc_axis_top).
MODULE_FILES["irnuc_axis_table"] = (*_PKG, *_ARMED, "interp_weight.sv", "irnuc_axis_table.sv")
#: The base methods irnuc_axis_top is built around (its parameter Method).
AXIS_METHODS = ("one_point", "two_point", "piecewise", "quadratic", "tc_offset",
                "table_interp")
# Simulation-only transactor around the top (batched cocotb driver, cosim/hdl/).
MODULE_FILES["nuc_dpc_batch"] = (*MODULE_FILES["nuc_dpc_top"], "nuc_dpc_batch.sv")

# ---- the stages (blind_drift, ffc) and their composition tops (docs/rtl.md "Stages") -----
_SPKG = (*_PKG, "irnuc_stage_pkg.sv")
_CORE_SUM = (*_ARITH, "core_sum.sv")
_BLIND = (*_SPILL, "irnuc_round.sv", "irnuc_clip.sv", "blind_drift.sv")
MODULE_FILES |= {
    "core_sum": (*_SPKG, *_CORE_SUM),
    "core_out": (*_PKG, *_CORE_OUT),
    "drift_sub": ("drift_sub.sv",),
    "blind_drift": (*_PKG, *_BLIND),
    "method_drift_top": tuple(dict.fromkeys((*_SPKG, *_BLIND, "drift_sub.sv", *_CORE_SUM,
                                             *_CORE_OUT, *_DPC, "method_drift_top.sv"))),
    "ffc_ctrl": (*_SPKG, "ffc_ctrl.sv"),
    "ffc_mean": (*_ARMED, "ffc_mean.sv"),
    "ffc_refresh": (*_PKG, "irnuc_round.sv", "irnuc_clip.sv", "ffc_refresh.sv"),
    "ffc_sums": (*_SPKG, *_CORE_SUM, "ffc_sums.sv"),
    "frame_coefficients": (*_PKG, *_TC, "frame_coefficients.sv"),
    "method_ffc_top": tuple(dict.fromkeys((*_SPKG, *_SPILL, "irnuc_axis_buffer.sv",
                                           "ffc_ctrl.sv", "ffc_mean.sv", *_TC,
                                           "frame_coefficients.sv", *_CORE_SUM, "ffc_sums.sv",
                                           *_CORE_OUT, "ffc_refresh.sv", *_DPC,
                                           "method_ffc_top.sv"))),
}
# The AXI top builds method_ffc_top for the ffc configurations (its parameter Ffc).
# Its core and FFC side (irnuc_axis_core, irnuc_axis_ffc) are modules of their own.
MODULE_FILES["irnuc_axis_ffc"] = tuple(dict.fromkeys((
    *MODULE_FILES["method_ffc_top"], "irnuc_axis_ffc.sv")))
MODULE_FILES["irnuc_axis_core"] = tuple(dict.fromkeys((
    *MODULE_FILES["nuc_dpc_top"], *MODULE_FILES["method_dpc_top"],
    *MODULE_FILES["irnuc_axis_ffc"], *MODULE_FILES["method_drift_top"],
    "irnuc_axis_assert.sv", "irnuc_axis_core.sv")))
MODULE_FILES["irnuc_axis_top"] = tuple(dict.fromkeys((
    *MODULE_FILES["irnuc_axis_core"], *MODULE_FILES["irnuc_axis_top"][:-1],
    "irnuc_axis_top.sv")))
MODULE_FILES["irnuc_assert_armed"] = _ARMED
# A file needed twice (the arming flop through two checkers) is compiled once.
MODULE_FILES = {k: tuple(dict.fromkeys(v)) for k, v in MODULE_FILES.items()}

#: The design's protocol assertions (SVA in ``hdl/`` under `ifdef IRNUC_ASSERT): every
#: simulation build and the lint define it, synthesis does not.
ASSERT_DEFINE = "+define+IRNUC_ASSERT"

_BASE = ("AdcBits", "GainIntBits", "GainFracBits", "OffsetIntBits", "OffsetFracBits",
         "OutBits", "Rounding", "Overflow")
_COEF = ("GainIntBits", "GainFracBits", "OffsetIntBits", "OffsetFracBits")

#: The parameters each sub-module takes (``nuc_dpc_top`` and ``method_dpc_top`` take all
#: of theirs).
_MODULE_PARAMETERS: dict[str, tuple[str, ...]] = {
    "nuc_core": _BASE,
    "dpc_core": ("OutBits", "MaxWidth", "MaxHeight"),
    "dpc_ctrl": ("MaxWidth", "MaxHeight"),
    "irnuc_axis_framer": (*_COEF, "AdcBits", "MaxWidth", "MaxHeight"),
    "nuc_dpc_top": (*_BASE, "MaxWidth", "MaxHeight"),
    "irnuc_pkg_probe": ("GainIntBits", "GainFracBits", "OffsetIntBits", "OffsetFracBits",
                        "OutBits"),
    "pwl_core": ("AdcBits", "GainIntBits", "GainFracBits", "KneeIntBits", "KneeFracBits",
                 "LevelIntBits", "LevelFracBits", "OutBits", "Rounding", "Overflow"),
    "quad_core": (*_BASE, "QuadIntBits", "QuadFracBits", "SquareBits"),
    "tc_poly": (*_COEF, "Tc1IntBits", "Tc1FracBits", "Tc2IntBits", "Tc2FracBits",
                "Tg1IntBits", "Tg1FracBits", "Tg2IntBits", "Tg2FracBits", "TcOrder", "TcGain",
                "ReadingBits", "ReadingRangeBits", "Rounding"),
    "tc_reading": ("ReadingBits", "ReadingRangeBits"),
    "table_interp": (*_COEF, "WeightFracBits", "WeightRounding"),
    "interp_weight": ("ReadingBits", "Tables", "WeightFracBits", "WeightRounding"),
    "irnuc_axis_table": ("ReadingBits", "Tables", "WeightFracBits", "WeightRounding"),
}

#: The module each base method's datapath is checked in on its own (method_dpc_top holds
#: every method; these are the method's own cores).
METHOD_CORES: dict[str, tuple[str, ...]] = {
    "one_point": ("nuc_core",),
    "two_point": ("nuc_core",),
    "piecewise": ("pwl_core",),
    "quadratic": ("quad_core",),
    "tc_offset": ("tc_poly", "tc_reading", "nuc_core"),
    "table_interp": ("table_interp", "interp_weight", "nuc_core"),
}

#: The method formats method_dpc_top takes (``<Name>IntBits``, ``<Name>FracBits``).
_METHOD_FORMATS = ("knee", "level", "quad", "tc1", "tc2", "tg1", "tg2", "weight")
#: Method parameters as SystemVerilog parameters (the names of nuc_fixed.layout.rtl_package).
_METHOD_FIELDS = {"square_bits": "SquareBits", "tc_order": "TcOrder",
                  "reading_bits": "ReadingBits", "reading_range_bits": "ReadingRangeBits",
                  "tables": "Tables"}


def _sv_name(text: str) -> str:
    return "".join(p[:1].upper() + p[1:] for p in text.split("_") if p)


def method_parameters(cfg: PipelineConfig) -> dict[str, int]:
    """The SV parameters of ``method_dpc_top`` (and its cores) beyond
    :meth:`~PipelineConfig.rtl_parameters`: ``Method`` (the index in
    :data:`~irnuc.nuc_fixed.config.BASE_METHODS`, ``irnuc_method_pkg::method_e``), every
    method format's ``<Name>IntBits``/``<Name>FracBits`` (``WeightRounding`` too), and the
    method fields (``SquareBits``, ``TcOrder``, ``TcGain``, ``ReadingBits``, ...).

    Raises :class:`UserError` for a method with stages (``blind_drift``, ``ffc``): the RTL
    has the base methods.
    """
    from irnuc.nuc_fixed.config import BASE_METHODS

    if cfg.stages:
        raise UserError(f"pipeline {cfg.name!r}: method {cfg.method!r} has stages "
                        f"({', '.join(cfg.stages)}); method_dpc_top implements the "
                        f"base methods {', '.join(BASE_METHODS)} (the stages: "
                        f"{', '.join(STAGE_TOPS.values())})")
    return _base_parameters(cfg)


def _base_parameters(cfg: PipelineConfig) -> dict[str, int]:
    """:func:`method_parameters` of the base method of any configuration."""
    from irnuc.nuc_fixed.config import BASE_METHODS, ROUNDING_MODES

    out = {"Method": BASE_METHODS.index(cfg.base_method)}
    for f in cfg.formats:
        if f.name in _METHOD_FORMATS:
            out[f"{_sv_name(f.name)}IntBits"] = f.int_bits
            out[f"{_sv_name(f.name)}FracBits"] = f.frac_bits
        if f.name == "weight":
            out["WeightRounding"] = ROUNDING_MODES[f.rounding]
    for field, name in _METHOD_FIELDS.items():
        value = getattr(cfg, field)
        if value is not None:
            out[name] = int(value)
    if cfg.tc_gain is not None:
        out["TcGain"] = int(cfg.tc_gain)
    return out


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
    "irnuc_round": lambda p: {"InBits": p["AdcBits"] + 20, "FracBits": 14,
                              "Rounding": p["Rounding"]},
    "irnuc_clip": lambda p: {"InBits": p["OutBits"] + 4, "OutBits": p["OutBits"],
                             "Overflow": p["Overflow"]},
    "irnuc_dsp_mul": lambda p: {},
}

#: The method register slots of irnuc_axil_regs (parameter <Name>RegBits) and the
#: PipelineConfig.registers each holds.
_REG_SLOTS = {"GainRegBits": "gain", "LevelRegBits": "level", "ReadingRegBits": "reading",
              "TRefRegBits": "t_ref", "BlindSumRegBits": "blind_sum",
              "BlindRefRegBits": "blind_ref", "DriftGainRegBits": "drift_gain",
              "FfcTargetRegBits": "ffc_target"}


def register_file_parameters(cfg: PipelineConfig) -> dict[str, int]:
    """The parameters of ``irnuc_axil_regs`` for ``cfg``: the widths and modes, the method
    (code, stages) and the width of every method register (0 where the method has none)."""
    from irnuc.nuc_fixed.regmap import config_params

    p = cfg.rtl_parameters()
    c = config_params(cfg)
    regs = cfg.registers
    table = regs.get("table_readings")
    return {**p, "MethodCode": c["MethodCode"], "HasBlindDrift": c["HasBlindDrift"],
            "HasFfc": c["HasFfc"], "FfcFrames": c["FfcFrames"],
            "CoefLayoutVersion": c["CoefLayoutVersion"],
            # CONFIG.word_bits: the method's coefficient word (irnuc_axis_top passes its
            # WordBits; the module's default is two_point's).
            "CoefWordBits": c["WordBits"],
            **{k: (regs[n].width if n in regs else 0) for k, n in _REG_SLOTS.items()},
            "TableReadings": table.count if table else 0,
            "TableReadingBits": table.width if table else 1}


#: Modules whose parameters include the method's (method_parameters).
_METHOD_MODULES = ("method_dpc_top", "pwl_core", "quad_core", "tc_poly", "tc_reading",
                   "table_interp", "interp_weight", "irnuc_axis_table")

def hdl_sources(top: str, hdl_dir: Path | None = None) -> list[Path]:
    """HDL files needed to elaborate module ``top``.

    ``hdl_dir`` replaces ``hdl/`` (a modified copy of the design, e.g. a mutant); files it
    lacks are taken from ``cosim/hdl/``.
    """
    if top not in MODULE_FILES:
        raise UserError(f"unknown HDL top {top!r}; known: {', '.join(sorted(MODULE_FILES))}")
    base = Path(hdl_dir) if hdl_dir is not None else HDL_DIR
    return [base / name if (base / name).is_file() else SIM_HDL_DIR / name
            for name in MODULE_FILES[top]]


def top_parameters(top: str, cfg: PipelineConfig) -> dict[str, int]:
    """The SV parameters of ``top`` for configuration ``cfg`` (a subset of the top's)."""
    hdl_sources(top)
    params = cfg.rtl_parameters()
    if top == "irnuc_axil_regs":
        return register_file_parameters(cfg)
    if top == "irnuc_axis_ffc":
        return stage_parameters("method_ffc_top", cfg)
    axis = top in ("irnuc_axis_top", "irnuc_axis_core")  # the same parameters
    if axis and stage_top(cfg) == "method_ffc_top":
        return {**stage_parameters("method_ffc_top", cfg), "Ffc": 1}
    if axis and stage_top(cfg) == "method_drift_top":
        return {**stage_parameters("method_drift_top", cfg), "Drift": 1}
    if axis and cfg.method in AXIS_METHODS and cfg.method != "two_point":
        p = {**params, **method_parameters(cfg)}
        # Tables: irnuc_axis_table's, in the top (the core takes the weight only).
        return {k: v for k, v in p.items() if k != "Tables" or top == "irnuc_axis_top"}
    if top in STAGE_TOPS.values():
        return stage_parameters(top, cfg)
    if top in _STAGE_BLOCKS:
        want = stage_top(cfg)
        if want is None:
            raise UserError(f"pipeline {cfg.name!r}: {top} is a block of the stage tops; "
                            f"method {cfg.method!r} has no stage")
        p = stage_parameters(want, cfg)
        return {k: p[k] for k in _STAGE_BLOCKS[top] if k in p}
    if top in _BLOCK_PARAMETERS:
        return _BLOCK_PARAMETERS[top](params)
    if top in _METHOD_MODULES:
        params = {**params, **method_parameters(cfg)}
        if top == "method_dpc_top":
            return {k: v for k, v in params.items() if k != "Tables"}
    keep = _MODULE_PARAMETERS.get(top)
    return params if keep is None else {k: params[k] for k in keep if k in params}


# ---- the stages -------------------------------------------------------------------------

#: The composition top of each stage (a configuration has at most one stage).
STAGE_TOPS: dict[str, str] = {"blind_drift": "method_drift_top", "ffc": "method_ffc_top"}
#: The base methods each stage top composes with (its parameter ``Method``).
STAGE_BASES: dict[str, tuple[str, ...]] = {
    "method_drift_top": ("one_point", "two_point"),
    "method_ffc_top": ("one_point", "two_point", "quadratic", "tc_offset"),
}


#: The blocks of the stage tops and the parameters of their top each takes (the lint of
#: every module, at the sizes it gets in its top).
_STAGE_BLOCKS: dict[str, tuple[str, ...]] = {
    "blind_drift": ("AdcBits", "BlindMax", "DriftIntBits", "DriftFracBits", "DriftRounding",
                    "DriftOverflow", "DriftGainIntBits", "DriftGainFracBits"),
    "drift_sub": ("AdcBits", "DriftIntBits", "DriftFracBits"),
    "core_sum": ("AdcBits", *_COEF, "QuadIntBits", "QuadFracBits", "SquareBits"),
    "core_out": ("OutBits", "Rounding", "Overflow"),
    "ffc_ctrl": ("FfcFrames",),
    "ffc_mean": (),
    "ffc_refresh": ("OutBits", "FfcIntBits", "FfcFracBits", "FfcRounding", "FfcOverflow"),
    "ffc_sums": ("AdcBits", *_COEF, "QuadIntBits", "QuadFracBits", "SquareBits",
                 "FfcFracBits"),
    "frame_coefficients": ("Method", *_COEF, "QuadIntBits", "QuadFracBits", "Tc1IntBits",
                           "Tc1FracBits", "Tc2IntBits", "Tc2FracBits", "Tg1IntBits",
                           "Tg1FracBits", "Tg2IntBits", "Tg2FracBits", "TcOrder", "TcGain",
                           "ReadingBits", "ReadingRangeBits", "Rounding"),
}


def stage_top(cfg: PipelineConfig) -> str | None:
    """The composition top of a configuration with a stage (None without one)."""
    for stage in cfg.stages:
        if stage in STAGE_TOPS:
            return STAGE_TOPS[stage]
    return None


def _format_parameters(cfg: PipelineConfig, name: str, prefix: str) -> dict[str, int]:
    from irnuc.nuc_fixed.config import OVERFLOW_MODES, ROUNDING_MODES

    f = cfg.format(name)
    return {f"{prefix}IntBits": f.int_bits, f"{prefix}FracBits": f.frac_bits,
            f"{prefix}Rounding": ROUNDING_MODES[f.rounding],
            f"{prefix}Overflow": OVERFLOW_MODES[f.overflow]}


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
    if cfg.has("blind_drift"):
        params |= {"BlindMax": int(cfg.blind_max or 1),
                   **_format_parameters(cfg, "drift", "Drift")}
        g = cfg.format("drift_gain")
        params |= {"DriftGainIntBits": g.int_bits, "DriftGainFracBits": g.frac_bits}
    if cfg.has("ffc"):
        params |= {"FfcFrames": int(cfg.ffc_frames or 1),
                   "FfcHold": int(cfg.ffc_output == "hold"),
                   **_format_parameters(cfg, "ffc", "Ffc")}
    return params
