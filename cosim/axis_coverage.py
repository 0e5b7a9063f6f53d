"""Functional coverage of ``irnuc_axis_top`` (sampled by ``cocotb_tests/tb_axis.py``).

The base model's stream points (idle and backpressure patterns, back-to-back frames) and
the AXI wrapper's own: every kind of register access and its response, the pause pattern of
each AXI4-Stream port, frame-size changes, registers written mid-frame, the four enable
combinations, each framing error cause, the coefficient tlast ignored (``coef_sync`` 0),
each interrupt cause and a reset in the middle of a frame. Every bin is reachable on every
two-point configuration (none removed).

On a configuration with the ``ffc`` stage (the core is ``method_ffc_top``; sampled by
``cocotb_tests/tb_axis_ffc.py``) the model holds the stream points and the FFC sequence as
the host runs it through the registers (:data:`FFC_AXIS_POINTS`), each bin decided by
:func:`ffc_axis_classes` from the wrapper's golden framing of a sequence that was driven
and checked, or by a register read that matched the model:

========================= =========================================================================
``axis.ffc.start``        FFC_CTRL.start written while a frame streams (the write's response
                          came between the frame's first and last video beat)
``axis.ffc.frames``       FFC_CTRL.frames = N (a refresh) and below N (a short run, no refresh)
``axis.ffc.status``       FFC_STATUS read busy (after the start) and done (after the run)
``axis.ffc.irq``          IRQ_STATUS.ffc_done read set with irq_o high (IRQ_ENABLE.ffc_done),
                          and both clear after its W1C
``axis.ffc.acc_stream``   words on m_axis_acc at full rate, and with idle cycles on every input
                          and backpressure on every output
``axis.ffc.foff_stream``  the same for the refreshed offsets on m_axis_foff
``axis.ffc.shutter``      shutter frames at full rate, and under backpressure (a shutter event
                          under backpressure)
``axis.ffc.refresh``      a start written mid-frame whose shutter frames begin at the next frame
                          start and end in a refresh (``next_frame_start``)
``axis.ffc.request``      IRQ_STATUS.ffc_request raised (FFC_PERIOD, FFC_THRESHOLD) by the period
                          alone, the threshold alone, both at once; frames with both 0 and no
                          request; cleared by its W1C (irq_o low); raised again after an FFC
                          that followed a request (``rearmed``)
``axis.ffc.drain``        FRAME_SIZE written after held frames went in: the next frame waits for
                          the framer's drain, whose count of items out of the core includes the
                          held ones (``after_held``); a new size written during a run's
                          shutter frame that writes m_axis_acc, or its refresh frame: the drain
                          also waits for the run's write-back words (``new_size_in_run``,
                          ``new_size_in_refresh``)
========================= =========================================================================

On a configuration with the ``blind_drift`` stage (the core is ``method_drift_top``;
sampled by ``cocotb_tests/tb_axis_method.py``) the model holds the stream points and
:data:`DRIFT_AXIS_POINTS`, each bin decided from a frame that was driven and checked:

========================= =========================================================================
``axis.drift.delta``      the frame's drift code (the golden model's, from the BLIND_SUM,
                          BLIND_REF and DRIFT_GAIN the frame started with): below 0, 0, above
                          0, and at a limit of the drift format (saturated)
``axis.drift.blind_sum``  BLIND_SUM written between frames and in the middle of a frame (the
                          frame after the write takes it)
``axis.drift.nuc_off``    a frame with CTRL.nuc_en 0 (the neutral frame word: drift code 0)
========================= =========================================================================

On a configuration that reads the housing (tc_housing, sampled by
``cocotb_tests/tb_axis_method.py``) the model holds the stream points and
:data:`HOUSING_AXIS_POINTS`: ``axis.housing.reading``, HOUSING_READING written between
frames and in the middle of a frame (the frame after the write takes it).

On a table_interp configuration (sampled by ``cocotb_tests/tb_axis_table.py``) the model
holds the stream points and table_interp's selection (:data:`TABLE_AXIS_POINTS`, the method's
``MethodSpec.axis_points``):

========================= =========================================================================
``axis.table.j``          TABLE_SEL.j read back (and matched) at every value 0 .. K - 2
``axis.table.weight``     the weight read back 0, strictly between, and 2^Wf (1.0)
``axis.table.sel``        TABLE_SEL read while computed (valid 0), valid, and with the error
``axis.table.held``       a frame start held by the computation: READING written just before
                          the frame (``between_frames``) and in the second half of the frame
                          before (``in_frame_before``), a gap seen in the video beats taken
========================= =========================================================================

The general AXI points above are the same register file, framer and stream ports on an
FFC, blind_drift or table_interp configuration; they are closed on the two-point
configurations (``tb_axis``).
"""

from __future__ import annotations

from irnuc.cosim.coverage import BACKPRESSURE_PATTERNS, IDLE_PATTERNS, CoverageModel
from irnuc.nuc_fixed.axis import EVENTS, FfcFraming
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.methods.table_interp import TABLE_AXIS_POINTS
from irnuc.nuc_fixed.regmap import RegisterModel

__all__ = ["AXIS_POINTS", "AXIS_TOPS", "DRIFT_AXIS_POINTS", "FFC_AXIS_POINTS",
           "HOUSING_AXIS_POINTS",
           "REGISTER_ACCESS", "RESET_SIZE_PIXELS", "TABLE_AXIS_POINTS", "TRAFFIC_POINTS",
           "TRAFFIC_TOP", "AxisCoverageModel", "TrafficCoverageModel", "drift_delta_class",
           "ffc_axis_classes"]

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

#: The random register traffic of cocotb_tests/axil_traffic.py has a model of its own (the
#: "top" key of its samples; every testbench that runs the traffic closes it).
TRAFFIC_TOP = "irnuc_axil_traffic"
#: A frame at the reset size (MaxWidth x MaxHeight) is simulated when it has at most this
#: many pixels.
RESET_SIZE_PIXELS = 4096
#: Coverpoint -> bins of the random register traffic: every byte-strobe class, every kind
#: of address written and read (a read-only one written and a write-only one read: SLVERR;
#: a reserved read-only one written: SLVERR on every build), BREADY and RREADY held low
#: under a waiting response, a write and a read issued at once (the slave takes one
#: transaction at a time), reads, writes and W1C clears while pixels stream, a frame at the
#: reset size, and FRAME_SIZE's byte lanes (each unwritten lane carrying another byte than
#: the register holds, the write taken; a written lane putting a field out of range,
#: refused).
TRAFFIC_POINTS: dict[str, tuple[str, ...]] = {
    "axil.traffic.strobe": ("full", "partial", "noncontiguous", "none"),
    "axil.traffic.address": ("write", "read", "ro_write", "wo_read", "reserved_write",
                             "reserved_ro_write", "reserved_read", "unmapped_write",
                             "unmapped_read"),
    "axil.traffic.overlap": ("write_and_read",),
    "axil.traffic.ready_held": ("bready", "rready"),
    "axil.traffic.streaming": ("read", "write", "w1c_clear"),
    "axil.traffic.reset_size": ("frame",),
    "axil.traffic.size_strobe": ("ignored_lane0", "ignored_lane1", "ignored_lane2",
                                 "ignored_lane3", "refused"),
}

#: Coverpoint -> bins of the FFC sequence through the registers (a configuration with ffc).
FFC_AXIS_POINTS: dict[str, tuple[str, ...]] = {
    "axis.ffc.start": ("mid_frame",),
    "axis.ffc.frames": ("n", "short"),
    "axis.ffc.status": ("busy", "done"),
    "axis.ffc.irq": ("ffc_done", "cleared"),
    "axis.ffc.acc_stream": ("full_rate", "idle_backpressure"),
    "axis.ffc.foff_stream": ("full_rate", "idle_backpressure"),
    "axis.ffc.shutter": ("full_rate", "backpressure"),
    "axis.ffc.refresh": ("next_frame_start",),
    "axis.ffc.drain": ("after_held", "new_size_in_run", "new_size_in_refresh"),
    "axis.ffc.request": ("period", "threshold", "both", "disabled", "cleared", "rearmed"),
    "axis.ffc.runs": ("second",),
}


#: Coverpoint -> bins of blind_drift through the registers (a configuration with it).
DRIFT_AXIS_POINTS: dict[str, tuple[str, ...]] = {
    "axis.drift.delta": ("negative", "zero", "positive", "saturated"),
    "axis.drift.blind_sum": ("between_frames", "mid_frame"),
    "axis.drift.nuc_off": ("neutral",),
}


#: Coverpoint -> bins of the housing reading through the registers (a method that reads it,
#: tc_housing, without a stage): HOUSING_READING written between frames (the host's write
#: of each frame, docs/integration.md) and in the middle of a frame (the next frame takes
#: it, the running one keeps its own).
HOUSING_AXIS_POINTS: dict[str, tuple[str, ...]] = {
    "axis.housing.reading": ("between_frames", "mid_frame"),
}


def drift_delta_class(delta: int, lo: int, hi: int) -> str:
    """The ``axis.drift.delta`` bin of a frame's drift code in a format of codes lo..hi."""
    if delta in (lo, hi):
        return "saturated"
    return "negative" if delta < 0 else "positive" if delta > 0 else "zero"


def ffc_axis_classes(framing: FfcFraming, n: int, count: int, start_frame: int,
                     write_beat: int, frame_pixels: int, idle: str, bp: str,
                     resize_beat: int | None = None, resized: bool = False
                     ) -> dict[str, set[str]]:
    """The bins of :data:`FFC_AXIS_POINTS` (but status, irq, request and runs, read on the
    DUT) one sequence hits: ``framing`` is the wrapper's golden framing of its shutter flags
    (:func:`irnuc.nuc_fixed.axis.ffc_framing`), ``count`` FFC_CTRL.frames of a start that
    the framing applies from frame ``start_frame`` on, ``n`` the configured N;
    ``write_beat`` the video beats taken (frames of ``frame_pixels`` beats, back to back)
    when the start's write response came; ``idle`` / ``bp`` the pause patterns of every
    input / output (``none``: full rate); ``resize_beat`` the video beats taken when a
    FRAME_SIZE write's response came (None: no such write), ``resized`` whether it wrote
    another size."""
    out: dict[str, set[str]] = {k: set() for k in FFC_AXIS_POINTS
                                if k not in ("axis.ffc.status", "axis.ffc.irq",
                                             "axis.ffc.request", "axis.ffc.runs")}
    frame_of_write, into = divmod(int(write_beat), int(frame_pixels))
    mid = into > 0 and frame_of_write + 1 == start_frame
    if mid:
        out["axis.ffc.start"].add("mid_frame")
    refresh = any(framing.foff_out)
    if 0 < count <= n:
        out["axis.ffc.frames"].add("n" if count == n else "short")
    way = ("full_rate" if idle == bp == "none" else
           "idle_backpressure" if "none" not in (idle, bp) else None)
    if way is not None:
        if any(framing.acc_out):
            out["axis.ffc.acc_stream"].add(way)
        if refresh:
            out["axis.ffc.foff_stream"].add(way)
    if any(framing.shutter):
        if idle == bp == "none":
            out["axis.ffc.shutter"].add("full_rate")
        elif bp != "none":
            out["axis.ffc.shutter"].add("backpressure")
    first = framing.shutter.index(True) if any(framing.shutter) else None
    if mid and refresh and first == start_frame:
        out["axis.ffc.refresh"].add("next_frame_start")
    if resize_beat is not None:
        frame_of_resize = int(resize_beat) // int(frame_pixels)
        if not all(framing.shown[:frame_of_resize]):
            out["axis.ffc.drain"].add("after_held")
        if resized and framing.acc_out[frame_of_resize]:
            out["axis.ffc.drain"].add("new_size_in_run")
        if resized and framing.foff_out[frame_of_resize]:
            out["axis.ffc.drain"].add("new_size_in_refresh")
    return out


class AxisCoverageModel(CoverageModel):
    """The coverpoints of ``irnuc_axis_top`` on one configuration (:data:`AXIS_POINTS`, or
    :data:`FFC_AXIS_POINTS` with the ffc stage, :data:`DRIFT_AXIS_POINTS` with
    blind_drift, :data:`TABLE_AXIS_POINTS` with table_interp, and the base model's stream
    points)."""

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        super().__init__(top, cfg, prefix)
        point = self.add_point
        points = dict(FFC_AXIS_POINTS if cfg.has("ffc") else
                      DRIFT_AXIS_POINTS if cfg.has("blind_drift") else
                      HOUSING_AXIS_POINTS if "housing" in cfg.base.readings else AXIS_POINTS)
        own = cfg.base.axis_points(cfg)  # a method's own part of the wrapper
        if own and not cfg.stages:
            points = dict(own)
        if cfg.has("ffc") and cfg.ffc_output != "hold":
            points["axis.ffc.drain"] = tuple(b for b in points["axis.ffc.drain"]
                                             if b != "after_held")
            self.removed["axis.ffc.drain"] = {
                "after_held": f"ffc_output = {cfg.ffc_output!r}: shutter frames are passed, "
                              "never held"}
        if cfg.has("ffc") and "fpa" not in cfg.base.readings:
            gone = ("threshold", "both")
            points["axis.ffc.request"] = tuple(b for b in points["axis.ffc.request"]
                                               if b not in gone)
            self.removed["axis.ffc.request"] = dict.fromkeys(
                gone, f"{cfg.base_method} takes no FPA reading: READING is reserved, the "
                      "reading 0, the threshold never reached")
        for name, bins in points.items():
            point(name, bins)

    def sample_classes(self, classes: dict[str, set[str]]) -> None:
        for name, labels in classes.items():
            for b in sorted(labels):
                self.sample(name, b)


class TrafficCoverageModel(CoverageModel):
    """The coverpoints of the random register traffic (:data:`TRAFFIC_POINTS`) on one
    configuration; the reset-size frame removed where it is too large to simulate, the
    write of a reserved read-only register where the configuration has them all."""

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        # Not the base model's points (streams, frames): only the traffic's.
        self.top, self.cfg, self.prefix = top, cfg, prefix
        self.removed: dict[str, dict[str, str]] = {}
        self._samplers = {}
        points = dict(TRAFFIC_POINTS)
        pixels = cfg.max_width * cfg.max_height
        if pixels > RESET_SIZE_PIXELS:
            del points["axil.traffic.reset_size"]
            self.removed["axil.traffic.reset_size"] = {
                "frame": f"the reset size {cfg.max_width} x {cfg.max_height} ({pixels} pixels) "
                         f"is too long a frame to simulate here (at most {RESET_SIZE_PIXELS}); "
                         "irnuc formal's framer proof starts frames at the reset size"}
        m = RegisterModel(cfg)
        if not any(not m.present(r) and not r.writable for r in m.map.registers):
            points["axil.traffic.address"] = tuple(
                b for b in points["axil.traffic.address"] if b != "reserved_ro_write")
            self.removed["axil.traffic.address"] = {
                "reserved_ro_write": f"{cfg.name} has every read-only register of the map"}
        for name, bins in points.items():
            self.add_point(name, bins)
