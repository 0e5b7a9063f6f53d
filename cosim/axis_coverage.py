"""Functional coverage of ``irnuc_axis_top`` (sampled by ``cocotb_tests/tb_axis.py``).

The base model's stream points (idle and backpressure patterns, back-to-back frames) and
the AXI wrapper's own: every kind of register access and its response, the pause pattern of
each AXI4-Stream port, frame-size changes, registers written mid-frame, the four enable
combinations, each framing error cause, the coefficient tlast ignored (``coef_sync`` 0),
each interrupt cause and a reset in the middle of a frame. Every bin is reachable on every
two-point configuration (none removed).
"""

from __future__ import annotations

from irnuc.cosim.coverage import BACKPRESSURE_PATTERNS, IDLE_PATTERNS, CoverageModel
from irnuc.nuc_fixed.axis import EVENTS
from irnuc.nuc_fixed.config import PipelineConfig

__all__ = ["AXIS_POINTS", "AXIS_TOPS", "REGISTER_ACCESS", "AxisCoverageModel"]

#: The tops whose coverage model is :class:`AxisCoverageModel`.
AXIS_TOPS = ("irnuc_axis_top",)

#: AXI4-Lite accesses by what the register file answers: OKAY on a register (whole word or
#: some byte lanes), OKAY on a reserved register (a method's register the core does not
#: have), SLVERR for an offset outside the map or a read-only register, SLVERR for an
#: illegal value (a frame size of 0 or above FRAME_MAX).
REGISTER_ACCESS = ("read_okay", "read_reserved", "read_slverr", "write_okay",
                   "write_partial", "write_reserved", "write_slverr", "write_slverr_value")

#: Coverpoint -> bins of the AXI wrapper.
AXIS_POINTS: dict[str, tuple[str, ...]] = {
    "axis.register_access": REGISTER_ACCESS,
    "axis.video_idle": IDLE_PATTERNS,
    "axis.coef_idle": IDLE_PATTERNS,
    "axis.backpressure": BACKPRESSURE_PATTERNS,
    "axis.frame_transition": ("same_size", "size_change"),
    "axis.mid_frame_write": ("ctrl", "frame_size"),
    "axis.enables": ("nuc0_dpc0", "nuc0_dpc1", "nuc1_dpc0", "nuc1_dpc1"),
    "axis.marker": EVENTS,
    "axis.coef_sync": ("off",),
    "axis.irq": ("error", "frame_done"),
    "axis.reset": ("mid_frame",),
}


class AxisCoverageModel(CoverageModel):
    """The coverpoints of ``irnuc_axis_top`` on one configuration (:data:`AXIS_POINTS`
    and the base model's stream points)."""

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        super().__init__(top, cfg, prefix)
        point = self.add_point
        for name, bins in AXIS_POINTS.items():
            point(name, bins)
