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

_PKG = ("irnuc_pkg.sv",)
_ASSERT = ("irnuc_stream_assert.sv",)
_FRAME = ("irnuc_frame_assert.sv",)
_SPILL = (*_ASSERT, "irnuc_spill_register.sv")
_NUC = (*_SPILL, "irnuc_mul_parts.sv", "irnuc_add_tree.sv", "nuc_core.sv")
_DPC = (*_SPILL, *_FRAME, "irnuc_mul_parts.sv", "irnuc_add_tree.sv", "irnuc_line_buffer.sv",
        "dpc_ctrl.sv", "dpc_core.sv")

#: Module -> the HDL files it needs, in dependency order (one module per file; the
#: package first). Files are looked up in ``hdl/``, then in ``cosim/hdl/``.
MODULE_FILES: dict[str, tuple[str, ...]] = {
    "nuc_core": (*_PKG, *_NUC),
    "dpc_core": (*_PKG, *_DPC),
    "nuc_dpc_top": tuple(dict.fromkeys((*_PKG, *_NUC, *_DPC, "nuc_dpc_top.sv"))),
    "dpc_ctrl": (*_PKG, "dpc_ctrl.sv"),
    "irnuc_spill_register": _SPILL,
    "irnuc_stream_assert": _ASSERT,
    "irnuc_frame_assert": (*_PKG, *_FRAME),
    "irnuc_add_tree": ("irnuc_add_tree.sv",),
    "irnuc_mul_parts": (*_PKG, "irnuc_mul_parts.sv"),
    "irnuc_line_buffer": (*_PKG, "irnuc_line_buffer.sv"),
    "irnuc_pkg_probe": (*_PKG, "irnuc_pkg_probe.sv"),
}
# The AXI top: the core, the framer, the register file and the AXI protocol checkers.
_AXI_ASSERT = ("irnuc_axis_assert.sv", "irnuc_axil_assert.sv")
MODULE_FILES["irnuc_axil_regs"] = (*_PKG, "irnuc_axil_regs.sv")
MODULE_FILES["irnuc_axis_framer"] = (*_PKG, *_SPILL, "irnuc_axis_framer.sv")
MODULE_FILES["irnuc_axis_assert"] = ("irnuc_axis_assert.sv",)
MODULE_FILES["irnuc_axil_assert"] = (*_PKG, "irnuc_axil_assert.sv")
MODULE_FILES["irnuc_axis_top"] = tuple(dict.fromkeys((
    *MODULE_FILES["nuc_dpc_top"], *_AXI_ASSERT, "irnuc_axil_regs.sv", "irnuc_axis_framer.sv",
    "irnuc_axis_top.sv")))
# Simulation-only transactor around the top (batched cocotb driver, cosim/hdl/).
MODULE_FILES["nuc_dpc_batch"] = (*MODULE_FILES["nuc_dpc_top"], "nuc_dpc_batch.sv")

#: The design's protocol assertions (SVA in ``hdl/`` under `ifdef IRNUC_ASSERT): every
#: simulation build and the lint define it, synthesis does not.
ASSERT_DEFINE = "+define+IRNUC_ASSERT"

#: The parameters each sub-module takes (``nuc_dpc_top`` takes all of them).
_MODULE_PARAMETERS: dict[str, tuple[str, ...]] = {
    "nuc_core": ("AdcBits", "GainIntBits", "GainFracBits", "OffsetIntBits", "OffsetFracBits",
                 "OutBits", "Rounding", "Overflow"),
    "dpc_core": ("OutBits", "MaxWidth", "MaxHeight"),
    "dpc_ctrl": ("MaxWidth", "MaxHeight"),
    "irnuc_axis_framer": ("AdcBits", "GainIntBits", "GainFracBits", "OffsetIntBits",
                          "OffsetFracBits", "MaxWidth", "MaxHeight"),
    "irnuc_pkg_probe": ("GainIntBits", "GainFracBits", "OffsetIntBits", "OffsetFracBits",
                        "OutBits"),
}

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
    "irnuc_axil_assert": lambda p: {},
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
            **{k: (regs[n].width if n in regs else 0) for k, n in _REG_SLOTS.items()},
            "TableReadings": table.count if table else 0,
            "TableReadingBits": table.width if table else 1}


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
    if top in _BLOCK_PARAMETERS:
        return _BLOCK_PARAMETERS[top](params)
    keep = _MODULE_PARAMETERS.get(top)
    return params if keep is None else {k: params[k] for k in keep}
