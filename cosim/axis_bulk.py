"""Bulk co-simulation through ``irnuc_axis_top``: AXI4-Stream video and coefficients in,
corrected video out, the registers written over AXI4-Lite, the FFC streams (the harness
plays the external memory's reads and takes its writes), bit for bit against the golden
model (issue 37: the sign-off's recommendation through the top it is synthesized with).

The harness (``harness/axis_main.cpp``, Verilator ``--cc --exe``, no cocotb) is dumb on
purpose: it replays streams and register writes this module derives from the golden model
and records every output word; the comparison is here, in numpy.

* :func:`axis_stimulus` makes a run from a calibration, raw frames, each frame's sensor
  readings (frame-file field names: ``fpa_reading``, ``housing_reading``, ...) and the frames
  FFCs start at. The register writes come from the register map and the configuration's
  registers (``PipelineConfig.registers``), not from a list: the calibration registers
  (``source = "calibration"``: T_REF, ...) once, FRAME_SIZE and CTRL, then before each frame
  every runtime register that a per-frame reading feeds (the READINGS registry's
  ``inputs_field`` names the register: ``reading`` -> READING; a method that reads the
  housing gets its register the same way) and ``FFC_CTRL`` (start, N frames) before each
  FFC's first shutter frame.
* The golden side: a configuration with the ``ffc`` stage through
  :func:`irnuc.cosim.stages.ffc_run` (pixels, accumulator and offset words) with the
  wrapper's framing (:func:`irnuc.nuc_fixed.axis.ffc_framing`: which frames carry words,
  which are shown); any other through :func:`irnuc.nuc_fixed.method_top.method_top` with
  the frames' readings. Methods whose frame word needs more than registers fed per frame
  (``table_interp``: TABLE_SEL; ``blind_drift``: BLIND_SUM from the blind pixels) are
  refused with the reason (never a pass).
"""

from __future__ import annotations

import json
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.common.errors import UserError
from irnuc.cosim.builds import Build
from irnuc.cosim.bulk import harness_build
from irnuc.cosim.verilator import verilator_env
from irnuc.nuc_fixed import MethodCoefficients, PipelineConfig

TOP = "irnuc_axis_top"
AXIS_HARNESS = Path(__file__).resolve().with_name("harness") / "axis_main.cpp"
AXIS_EXE = "axis_bulk"
_SOF, _EOL = 1 << 16, 1 << 17
_LAST = np.uint64(1 << 63)


def unsupported(cfg: PipelineConfig) -> str | None:
    """Why the harness cannot drive ``cfg`` through irnuc_axis_top (None: it can)."""
    from irnuc.cosim.synth import tops_for

    if TOP not in tops_for(cfg):
        return f"irnuc_axis_top does not implement {cfg.method}"
    if cfg.base_method == "table_interp":
        return ("table_interp's table pair and weight come from TABLE_SEL and TABLE_READING, "
                "which this harness does not drive yet")
    if cfg.has("blind_drift"):
        return "blind_drift's BLIND_SUM per frame is not driven by this harness yet"
    return None


def build_axis(cfg: PipelineConfig) -> Build:
    """Build (cached) the axis harness of ``irnuc_axis_top`` for ``cfg``."""
    return harness_build(cfg, TOP, AXIS_HARNESS, AXIS_EXE,
                         header=f'#include "V{TOP}.h"\nusing AxisTop = V{TOP};\n',
                         header_name="axis_top.h", name=f"{cfg.name}-axisbulk")


@dataclass
class AxisStimulus:
    """One run of the harness and what the golden model expects of it."""

    video: np.ndarray       # uint32 beats (data | sof << 16 | eol << 17)
    coef: np.ndarray        # (words, limbs) uint64
    coef_last: np.ndarray   # uint8
    foff: np.ndarray        # uint64
    foff_last: np.ndarray
    acc: np.ndarray
    acc_last: np.ndarray
    writes: list[tuple[int, int, int]]  # (beat, address, data)
    want_video: np.ndarray  # uint32
    want_acc: np.ndarray    # uint64, bit 63 tlast
    want_foff: np.ndarray
    frames: int
    shown: int
    ffc_events: int


def _beats(frames: list[np.ndarray]) -> np.ndarray:
    out = []
    for f in frames:
        h, w = f.shape
        pos = np.arange(h * w)
        out.append(np.asarray(f, np.int64).ravel().astype(np.uint32)
                   | np.where(pos == 0, _SOF, 0).astype(np.uint32)
                   | np.where(pos % w == w - 1, _EOL, 0).astype(np.uint32))
    return np.concatenate(out) if out else np.zeros(0, np.uint32)


def _words(images: list[np.ndarray], bits: int) -> tuple[np.ndarray, np.ndarray]:
    """Words (uint64, two's complement in ``bits``) and tlast flags of per-frame images."""
    if not images:
        return np.zeros(0, np.uint64), np.zeros(0, np.uint8)
    mask = (1 << bits) - 1
    w = np.concatenate([(np.asarray(a, np.int64).ravel() & mask).astype(np.uint64)
                        for a in images])
    last = np.concatenate([np.arange(np.size(a)) == np.size(a) - 1 for a in images])
    return w, last.astype(np.uint8)


def _reg_writes(cfg: PipelineConfig, name: str, value: int) -> list[tuple[int, int]]:
    """(address, data) of a method register's LO (and HI) word, or an array's entries."""
    from irnuc.nuc_fixed.regmap import register_map

    reg = cfg.registers[name]
    m = register_map()
    v = int(value) & ((1 << reg.width) - 1)
    words = {r.word: r.offset for r in m.registers
             if r.config_register == name and r.word is not None}
    out = [(words["lo"], v & 0xFFFF_FFFF)]
    if reg.width > 32:
        out.append((words["hi"], v >> 32))
    return out


def axis_stimulus(cal: MethodCoefficients, raws: list[np.ndarray],
                  fields: dict[str, np.ndarray], ffc_starts: list[int]) -> AxisStimulus:
    """The harness's streams and register writes and the golden model's outputs for
    ``raws`` (each (H, W)) corrected with ``cal``, each frame's readings ``fields`` (frame
    file names) and FFCs starting at ``ffc_starts`` (frames; FFC builds only)."""
    from irnuc.cosim.stages import ffc_run
    from irnuc.cosim.stream import stream_limbs
    from irnuc.nuc_fixed.axis import ffc_framing, ffc_shutter_flags
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top
    from irnuc.nuc_fixed.methods import READINGS
    from irnuc.nuc_fixed.regmap import register_map

    cfg = cal.cfg
    why = unsupported(cfg)
    if why:
        raise UserError(f"pipeline {cfg.name!r}: {why}")
    n = len(raws)
    h, w = raws[0].shape
    m = register_map()
    # The per-frame readings the method takes, by the register each one feeds.
    feeds = {r.inputs_field: np.asarray(fields[r.frame_field], np.int64)
             for r in READINGS.values()
             if r.name in cfg.base.readings and r.inputs_field in cfg.registers}
    for reg, v in feeds.items():
        if v.size != n:
            raise UserError(f"{reg}: {v.size} readings for {n} frames")
    writes: list[tuple[int, int, int]] = []

    def at(beat: int, pairs: list[tuple[int, int]]) -> None:
        writes.extend((beat, a, d) for a, d in pairs)

    ctrl = m["CTRL"]
    at(0, [(m["FRAME_SIZE"].offset, w | (h << 16)),
           (ctrl.offset, ctrl.field("nuc_en").mask | ctrl.field("dpc_en").mask
            | ctrl.field("coef_sync").mask)])
    for name, value in cal.registers.items():
        if name in cfg.registers:
            at(0, _reg_writes(cfg, name, int(value)))
    ffc = cfg.has("ffc")
    nf = int(cfg.ffc_frames or 1)
    starts = sorted({int(s) for s in ffc_starts if 0 <= int(s) < n}) if ffc else []
    fctl = m["FFC_CTRL"] if ffc else None
    for k in range(n):
        for reg, v in feeds.items():
            at(k * h * w, _reg_writes(cfg, reg, int(v[k])))
        if fctl is not None and k in starts:
            at(k * h * w, [(fctl.offset, fctl.field("start").mask
                            | (nf << fctl.field("frames").lsb))])
    limbs = stream_limbs(cal, None if "reading" not in feeds else int(feeds["reading"][0]))
    L = limbs.shape[-1]
    coef = np.tile(limbs.reshape(-1, L), (n, 1))
    coef_last = np.tile((np.arange(h * w) == h * w - 1).astype(np.uint8), n)
    video = _beats(raws)
    if ffc:
        shutter = ffc_shutter_flags(n, {s: nf for s in starts})
        rd = [int(v) for v in feeds["reading"]] if "reading" in feeds else None
        run = ffc_run(cal, raws, shutter, readings=rd)
        framing = ffc_framing(cfg, shutter)
        cbits = cfg.memories["ffc_offset"].word_bits
        abits = cfg.memories["ffc_acc"].word_bits
        foff, foff_last = _words(list(run.foff_in), cbits)
        acc, acc_last = _words([a for a in run.acc_in if a is not None], abits)
        wa, la = _words([a for a in run.acc_out if a is not None], abits)
        wf, lf = _words([a for a in run.foff_out if a is not None], cbits)
        shown = [f.expected for f, s in zip(run.frames, framing.shown, strict=True) if s]
        want_acc = wa | (la.astype(np.uint64) << np.uint64(63))
        want_foff = wf | (lf.astype(np.uint64) << np.uint64(63))
        events = sum(f is not None for f in run.foff_out)
    else:
        x = np.stack([np.asarray(r, np.int64) for r in raws])
        y = method_top(x, cal, FrameInputs(**{k: v for k, v in feeds.items()})).y
        shown = list(y)
        foff = acc = want_acc = want_foff = np.zeros(0, np.uint64)
        foff_last = acc_last = np.zeros(0, np.uint8)
        events = 0
    return AxisStimulus(video=video, coef=coef.astype(np.uint64), coef_last=coef_last,
                        foff=foff, foff_last=foff_last, acc=acc, acc_last=acc_last,
                        writes=writes, want_video=_beats([np.asarray(f) for f in shown]),
                        want_acc=want_acc, want_foff=want_foff, frames=n, shown=len(shown),
                        ffc_events=int(events))


def run_axis(bld: Build, st: AxisStimulus, *, seed: int = 1, stall_percent: int = 0,
             idle_percent: int = 0) -> dict[str, Any]:
    """Run the harness on ``st``; compare every output word with the golden model's."""
    with tempfile.TemporaryDirectory(prefix="irnuc-axis-") as tmp:
        d = Path(tmp)
        files = {"video.bin": st.video.astype("<u4"), "coef.bin": st.coef.astype("<u8"),
                 "coef_last.bin": st.coef_last.astype(np.uint8),
                 "foff.bin": st.foff.astype("<u8"), "foff_last.bin": st.foff_last.astype(np.uint8),
                 "acc.bin": st.acc.astype("<u8"), "acc_last.bin": st.acc_last.astype(np.uint8),
                 "writes.bin": np.asarray([[b, a | (dd << 32)] for b, a, dd in st.writes],
                                          np.uint64).reshape(-1, 2).astype("<u8")}
        for name, arr in files.items():
            arr.tofile(d / name)
        (d / "meta.txt").write_text(" ".join(str(int(v)) for v in (
            st.video.size, st.coef.shape[0], st.coef.shape[1], st.foff.size, st.acc.size,
            len(st.writes), st.want_video.size, st.want_acc.size, st.want_foff.size, seed,
            stall_percent, idle_percent)) + "\n")
        t0 = time.perf_counter()
        proc = subprocess.run([str(bld.build_dir / AXIS_EXE), str(d)], capture_output=True,
                              text=True, env=verilator_env())
        sim_s = time.perf_counter() - t0
        lines = proc.stdout.strip().splitlines()
        try:
            info = json.loads(lines[-1]) if lines else {"error": proc.stderr[-400:]}
        except json.JSONDecodeError:  # the model stopped ($stop of an assertion): its text
            info = {"error": " ".join(lines[-3:])[-400:]}
        if proc.returncode != 0 or "error" in info:
            # A run that stops (a timeout: outputs the golden model expects never came)
            # counts every expected word as missing.
            err = str(info.get("error", proc.stderr[-400:]))
            return {"passed": False, "pixels_compared": 0, "error": err,
                    "mismatches": int(st.want_video.size + st.want_acc.size + st.want_foff.size),
                    "lines": [f"the harness stopped: {err} ({info})"],
                    "harness_seconds": round(sim_s, 3), "stderr": proc.stderr[-2000:]}
        got_v = np.fromfile(d / "out_video.bin", "<u4")
        got_a = np.fromfile(d / "out_acc.bin", "<u8")
        got_f = np.fromfile(d / "out_foff.bin", "<u8")
    out: dict[str, Any] = {"harness_seconds": round(sim_s, 3), "cycles": info["cycles"],
                           "register_writes": info["writes"],
                           "bad_responses": info["bad_responses"], "extra": info["extra"]}
    lines_out: list[str] = []
    bad = 0
    for name, got, want in (("m_axis_video", got_v, st.want_video),
                            ("m_axis_acc", got_a, st.want_acc),
                            ("m_axis_foff", got_f, st.want_foff)):
        k = min(got.size, want.size)
        diff = np.flatnonzero(got[:k] != want[:k])
        miss = abs(int(got.size) - int(want.size))
        bad += int(diff.size) + miss
        if diff.size:
            i = int(diff[0])
            lines_out.append(f"{name}: {diff.size} of {k} words differ; first at word {i}: got "
                             f"0x{int(got[i]):x}, the golden model 0x{int(want[i]):x}")
        if miss:
            lines_out.append(f"{name}: {got.size} words, the golden model {want.size}")
    bad += int(info["bad_responses"]) + int(info["extra"])
    if info["bad_responses"]:
        lines_out.append(f"{info['bad_responses']} AXI4-Lite write(s) not answered OKAY")
    if info["extra"]:
        lines_out.append(f"{info['extra']} output words after the expected ones")
    out.update(pixels_compared=int(min(got_v.size, st.want_video.size)),
               words_compared=int(min(got_a.size, st.want_acc.size)
                                  + min(got_f.size, st.want_foff.size)),
               mismatches=bad, passed=bad == 0 and st.want_video.size > 0, lines=lines_out[:10])
    return out
