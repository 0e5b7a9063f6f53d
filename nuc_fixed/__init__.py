"""Bit-accurate fixed-point golden model of the irnuc NUC + DPC pipeline.

One function per RTL module (``nuc_core``, ``dpc_core``, ``nuc_dpc_top``); the bit-exact
contract is ``docs/datapath.md`` and the user guide ``docs/golden_model.md``.
"""

from irnuc.nuc_fixed.config import ConfigError, PipelineConfig, load_pipeline, pipeline_names
from irnuc.nuc_fixed.dpc import dpc_core
from irnuc.nuc_fixed.fixed import FixedFormat, apply_overflow, gain_format, offset_format, round_shift
from irnuc.nuc_fixed.memimage import (
    MemImageError,
    pack_words,
    read_memimage,
    unpack_words,
    write_memimage,
)
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, MethodOutput, method_top
from irnuc.nuc_fixed.nuc import NucIntermediates, nuc_core
from irnuc.nuc_fixed.top import nuc_dpc_top
from irnuc.nuc_fixed.validate import InputError

__all__ = [
    "ConfigError",
    "FixedFormat",
    "FrameInputs",
    "InputError",
    "MemImageError",
    "MethodCoefficients",
    "MethodOutput",
    "NucIntermediates",
    "PipelineConfig",
    "apply_overflow",
    "dpc_core",
    "gain_format",
    "load_pipeline",
    "method_top",
    "nuc_core",
    "nuc_dpc_top",
    "offset_format",
    "pack_words",
    "pipeline_names",
    "read_memimage",
    "round_shift",
    "unpack_words",
    "write_memimage",
]
