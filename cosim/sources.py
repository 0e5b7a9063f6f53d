"""The RTL sources (``hdl/``, installed as ``irnuc.hdl``) and the parameters of each top.

Widths and modes come only from a :class:`~irnuc.nuc_fixed.config.PipelineConfig`
(``rtl_parameters``); this module decides which of them a given top module takes.
"""

from __future__ import annotations

import importlib
from pathlib import Path

from irnuc.common.errors import UserError
from irnuc.nuc_fixed.config import PipelineConfig

#: Folder of the SystemVerilog sources.
HDL_DIR = Path(importlib.import_module("irnuc.hdl").__file__).resolve().parent

#: Module -> the HDL files it needs, in dependency order (one module per file).
MODULE_FILES: dict[str, tuple[str, ...]] = {
    "nuc_core": ("nuc_core.sv",),
    "dpc_core": ("dpc_core.sv",),
    "nuc_dpc_top": ("nuc_core.sv", "dpc_core.sv", "nuc_dpc_top.sv"),
}

#: The parameters each sub-module takes (``nuc_dpc_top`` takes all of them).
_MODULE_PARAMETERS: dict[str, tuple[str, ...]] = {
    "nuc_core": ("AdcBits", "GainIntBits", "GainFracBits", "OffsetIntBits", "OffsetFracBits",
                 "OutBits", "Rounding", "Overflow"),
    "dpc_core": ("OutBits", "MaxWidth", "MaxHeight"),
}


def hdl_sources(top: str) -> list[Path]:
    """HDL files needed to elaborate module ``top``."""
    if top not in MODULE_FILES:
        raise UserError(f"unknown HDL top {top!r}; known: {', '.join(sorted(MODULE_FILES))}")
    return [HDL_DIR / name for name in MODULE_FILES[top]]


def top_parameters(top: str, cfg: PipelineConfig) -> dict[str, int]:
    """The SV parameters of ``top`` for configuration ``cfg`` (a subset of the top's)."""
    hdl_sources(top)
    params = cfg.rtl_parameters()
    keep = _MODULE_PARAMETERS.get(top)
    return params if keep is None else {k: params[k] for k in keep}
