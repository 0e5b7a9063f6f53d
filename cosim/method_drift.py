"""Co-simulation of the correction methods on drift sequences of the physics model.

A camera's FPA temperature drifts frame after frame; the methods exist for that. Here
every base method is calibrated on the model (``nuc_fixed.plan.run_plan`` and
``nuc_fixed.fit.calibrate_points``, one plan for all), then a sequence of frames with the
FPA temperature ramping (``environment.T_substrate`` and ``T_cam`` set per frame, the
on-die sensor's reading per frame, a scene moving in temperature) is corrected by the
RTL (the bulk harness of ``method_dpc_top``, :mod:`irnuc.cosim.method_bulk`) and by the
golden model, and every output pixel is compared.

:func:`run_campaign` is the API of ``benchmarks/bench_methods_cosim.py``;
``cocotb_tests/test_method_bulk.py`` runs it on small frames.
"""

from __future__ import annotations

import hashlib
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, method_top

__all__ = ["DriftSequence", "calibrate_methods", "drift_sequence", "pgo_build", "run_campaign"]

#: The calibration plan of the campaign: scenes and FPA points, K (the plan of
#: tests/test_methods_calibrate.py), two frames per point.
PLAN_SCENES = (290.0, 330.0, 370.0)
PLAN_FPA = (288.0, 298.0, 308.0)


@dataclass(frozen=True)
class DriftSequence:
    """Frames of a drifting camera.

    Attributes
    ----------
    codes : (N, H, W) raw codes
    fpa_K : (N,) FPA temperature of each frame, K
    scene_K : (N,) scene base temperature, K
    reading : (N,) the on-die sensor's reading, codes
    blind_codes : (N, K) the reference pixels read beside each frame, codes (None: the
        sensor has none)
    shutter : (N,) bool, the shutter closed (the frame images it at the housing
        temperature), or None: open throughout
    """

    codes: np.ndarray
    fpa_K: np.ndarray
    scene_K: np.ndarray
    reading: np.ndarray
    blind_codes: np.ndarray | None = None
    shutter: np.ndarray | None = None


def _overrides(shape: tuple[int, int], extra: Mapping[str, Any] | None) -> dict[str, Any]:
    return {"fpa.active_rows": int(shape[0]), "fpa.active_cols": int(shape[1]),
            **dict(extra or {})}


def drift_sequence(frames: int, shape: tuple[int, int] = (480, 640), *,
                   fpa_K: tuple[float, float] = (289.0, 307.0),
                   scene_K: tuple[float, float] = (295.0, 360.0), scene: str = "gradient",
                   sensor: str = "default", overrides: Mapping[str, Any] | None = None,
                   seed: int = 0, shutter: Sequence[bool] | None = None) -> DriftSequence:
    """``frames`` frames with the FPA (and housing) temperature ramping linearly over
    ``fpa_K`` and the scene over ``scene_K``; the default on-die sensor reads each frame.

    Every frame is the model at that frame's temperatures (``environment.T_substrate`` =
    ``environment.T_cam`` = the FPA temperature), one seed throughout: the same pixels
    drift. ``shutter`` (one flag per frame): a closed frame images the shutter, a uniform
    blackbody at the housing temperature, instead of the scene. Each frame's reference
    pixels (``blind_codes``) are kept.
    """
    from irnuc import model
    from irnuc.model.fpa_sensor import FpaSensor
    from irnuc.nuc_fixed.plan import sensor_config

    t_fpa = np.linspace(fpa_K[0], fpa_K[1], frames)
    t_scene = np.linspace(scene_K[0], scene_K[1], frames)
    closed = (np.zeros(frames, bool) if shutter is None
              else np.asarray(list(shutter), dtype=bool))
    if closed.shape != (frames,):
        raise ValueError(f"shutter holds {closed.size} flags for {frames} frames")
    codes, blind = [], []
    ov = _overrides(shape, overrides)
    for tf, ts, sh in zip(t_fpa, t_scene, closed, strict=True):
        cfg = sensor_config(sensor, {**ov, "environment.T_substrate": float(tf),
                                     "environment.T_cam": float(tf)})
        fr = (model.simulate(cfg, [float(tf)], "uniform", seed=seed) if sh
              else model.simulate(cfg, [float(ts)], scene, seed=seed))
        codes.append(fr.codes[0])
        b = getattr(fr, "blind_codes", None)
        if b is not None and np.size(b):
            blind.append(np.asarray(b).reshape(-1))
    reading = FpaSensor().read(t_fpa, seed=seed)
    return DriftSequence(codes=np.stack(codes), fpa_K=t_fpa, scene_K=t_scene, reading=reading,
                         blind_codes=np.stack(blind) if len(blind) == frames else None,
                         shutter=None if shutter is None else closed)


def calibrate_methods(cfgs: Sequence[PipelineConfig], shape: tuple[int, int], *,
                      frames: int = 2, sensor: str = "default",
                      overrides: Mapping[str, Any] | None = None, seed: int = 0
                      ) -> dict[str, MethodCoefficients]:
    """Every configuration calibrated on one plan run on the model (name -> codes)."""
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan

    plan = CalibrationPlan(scene=PLAN_SCENES, fpa=PLAN_FPA, frames=frames)
    pts = run_plan(plan, sensor, _overrides(shape, overrides), seed=seed)
    return {c.name: calibrate_points(pts, c).coeffs for c in cfgs}


#: The PGO training workload of :func:`pgo_build`: this many rows of the first and the last
#: frame of the sequence (with the calibration cut alike), once at full rate and once with
#: idle gaps and backpressure of this many percent.
PGO_TRAIN_ROWS = 32
PGO_TRAIN_GAPS = 10


def pgo_build(cfg: PipelineConfig, coeffs: MethodCoefficients, seq: DriftSequence,
              readings: np.ndarray | None, *, assertions: bool = True):
    """The bulk harness of ``method_dpc_top`` for ``cfg`` built with gcc's profile-guided
    optimisation (:func:`irnuc.cosim.bulk.harness_build`), trained on a strip of the
    sequence: the first :data:`PGO_TRAIN_ROWS` rows of its first and last frame with their
    readings, at full rate and with idle gaps and backpressure. Cached under a digest of
    that workload; the same RTL, options and outputs as the plain build."""
    from irnuc.common.digest import digest
    from irnuc.cosim.bulk import build_bulk
    from irnuc.cosim.method_bulk import run_method_bulk

    rows = min(PGO_TRAIN_ROWS, seq.codes.shape[1])
    pick = sorted({0, seq.codes.shape[0] - 1})
    raw = np.ascontiguousarray(seq.codes[pick, :rows])
    strip = MethodCoefficients(cfg=coeffs.cfg, registers=dict(coeffs.registers),
                               fields={m: {k: np.ascontiguousarray(v[:rows])
                                           for k, v in f.items()}
                                       for m, f in coeffs.fields.items()})
    rd = None if readings is None else np.asarray(readings)[pick]

    def train(bld) -> None:
        for gaps in (0, PGO_TRAIN_GAPS):
            run_method_bulk(bld, strip, raw, rd, idle_percent=gaps, stall_percent=gaps)

    def sha(a: np.ndarray) -> str:
        return hashlib.sha256(np.ascontiguousarray(a).tobytes()).hexdigest()

    key = digest({"raw": sha(raw), "words": {k: sha(v) for k, v in strip.words().items()},
                  "registers": repr(sorted(strip.registers.items())),
                  "readings": None if rd is None else np.asarray(rd).tolist(),
                  "gaps": PGO_TRAIN_GAPS})
    return build_bulk(cfg, top="method_dpc_top", assertions=assertions, train=train,
                      train_key=key)


@dataclass
class MethodRun:
    """One method's campaign result."""

    name: str
    method: str
    frames: int
    pixels: int
    compared: int
    mismatches: int
    missing: int
    extra: int
    frame_err: bool
    cycles: int
    sim_seconds: float
    golden_seconds: float
    readings: tuple[int, int]
    lines: list[str] = field(default_factory=list)
    #: The co-simulation end to end, golden model excepted: stimulus written, harness run,
    #: outputs read and compared, s.
    bulk_seconds: float = 0.0
    #: ``baseline=True``: the harness's time on the previous path (every eval through the
    #: model's public ``eval()``), s, and that run's mismatches (missing and extra counted).
    baseline_seconds: float | None = None
    baseline_mismatches: int | None = None
    #: CPU time of the harness processes, s (this path and the baseline's).
    sim_cpu_seconds: float = 0.0
    baseline_cpu_seconds: float | None = None
    #: ``noassert=True``: the same fast path on a build without the protocol assertions
    #: (throughput only; every output still compared): its wall and CPU time, s, and its
    #: mismatches (missing and extra counted).
    noassert_seconds: float | None = None
    noassert_cpu_seconds: float | None = None
    noassert_mismatches: int | None = None
    #: ``pgo=True``: the fast path on the profile-guided build of the same RTL with the
    #: assertions (:func:`pgo_build`), every output compared: wall and CPU time, s,
    #: mismatches (missing and extra counted).
    pgo_seconds: float | None = None
    pgo_cpu_seconds: float | None = None
    pgo_mismatches: int | None = None
    #: ``single=True``: the plain assertion build in one harness process (no shards):
    #: wall and CPU time, s, mismatches.
    single_seconds: float | None = None
    single_cpu_seconds: float | None = None
    single_mismatches: int | None = None
    #: Harness processes of the main, baseline, no-assertion and PGO runs.
    shards: int = 1

    @property
    def passed(self) -> bool:
        return (self.mismatches == 0 and self.missing == 0 and self.extra == 0
                and not self.frame_err and self.compared == self.pixels)

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "method": self.method, "frames": self.frames,
                "pixels": self.pixels, "compared": self.compared,
                "mismatches": self.mismatches, "missing": self.missing, "extra": self.extra,
                "frame_err": self.frame_err, "cycles": self.cycles, "passed": self.passed,
                "sim_seconds": round(self.sim_seconds, 3),
                "golden_seconds": round(self.golden_seconds, 3),
                "sim_pixels_per_s": round(self.pixels / max(self.sim_seconds, 1e-9)),
                "sim_cpu_seconds": round(self.sim_cpu_seconds, 3),
                "pixels_per_cpu_s": round(self.pixels / max(self.sim_cpu_seconds, 1e-9)),
                "bulk_seconds": round(self.bulk_seconds, 3),
                "end_to_end_pixels_per_s": round(
                    self.pixels / max(self.bulk_seconds + self.golden_seconds, 1e-9)),
                **({} if self.baseline_seconds is None else {
                    "baseline_sim_seconds": round(self.baseline_seconds, 3),
                    "baseline_pixels_per_s": round(self.pixels / max(self.baseline_seconds,
                                                                     1e-9)),
                    "baseline_mismatches": self.baseline_mismatches,
                    "baseline_cpu_seconds": round(self.baseline_cpu_seconds or 0.0, 3),
                    "cpu_ratio_to_baseline": round((self.baseline_cpu_seconds or 0.0)
                                                   / max(self.sim_cpu_seconds, 1e-9), 3),
                    "ratio_to_baseline": round(self.baseline_seconds
                                               / max(self.sim_seconds, 1e-9), 3)}),
                "shards": self.shards,
                **self._variant("noassert", self.noassert_seconds, self.noassert_cpu_seconds,
                                self.noassert_mismatches),
                **self._variant("pgo", self.pgo_seconds, self.pgo_cpu_seconds,
                                self.pgo_mismatches),
                **self._variant("single", self.single_seconds, self.single_cpu_seconds,
                                self.single_mismatches),
                "reading_range": list(self.readings), "lines": self.lines[:10]}

    def _variant(self, name: str, secs: float | None, cpu: float | None,
                 bad: int | None) -> dict[str, Any]:
        """``<name>_*`` figures of one more run of the same frames (none if not run)."""
        if secs is None:
            return {}
        cpu = cpu or 0.0
        d: dict[str, Any] = {
            f"{name}_sim_seconds": round(secs, 3),
            f"{name}_pixels_per_s": round(self.pixels / max(secs, 1e-9)),
            f"{name}_cpu_seconds": round(cpu, 3),
            f"{name}_pixels_per_cpu_s": round(self.pixels / max(cpu, 1e-9)),
            f"{name}_mismatches": bad}
        if self.baseline_seconds is not None:
            d[f"{name}_ratio_to_baseline"] = round(self.baseline_seconds / max(secs, 1e-9), 3)
            d[f"{name}_cpu_ratio_to_baseline"] = round(
                (self.baseline_cpu_seconds or 0.0) / max(cpu, 1e-9), 3)
        return d


def _again(bld, c: MethodCoefficients, codes: np.ndarray, rd: np.ndarray | None,
           expected: np.ndarray, kw: dict[str, Any]) -> tuple[float, float, int]:
    """One more checked run of the campaign's frames: wall, CPU seconds, mismatches
    (missing, extra and a framing error counted)."""
    from irnuc.cosim.method_bulk import check_method_bulk, run_method_bulk

    r = run_method_bulk(bld, c, codes, rd, **kw)
    k = check_method_bulk(r, c, codes, rd, expected=expected)
    return r.sim_seconds, r.cpu_seconds, k.mismatches + k.missing + k.extra + int(r.frame_err)


def run_campaign(cfgs: Sequence[PipelineConfig], frames: int = 20,
                 shape: tuple[int, int] = (480, 640), *, shards: int = 2,
                 idle_percent: int = 0, stall_percent: int = 0, seed: int = 0,
                 sequence: DriftSequence | None = None,
                 coeffs: Mapping[str, MethodCoefficients] | None = None,
                 baseline: bool = False, noassert: bool = False, pgo: bool = False,
                 single: bool = False) -> list[MethodRun]:
    """Calibrate every configuration on the model, make a drift sequence, and co-simulate
    each method on it (bulk harness in ``shards`` processes, bit for bit against
    ``method_top``). More runs of the same frames, each checked as well: ``baseline``,
    the harness's previous path (``public_eval``), for the benchmark's ratio;
    ``noassert``, a build without the protocol assertions (throughput); ``pgo``, the
    profile-guided build with the assertions (:func:`pgo_build`); ``single``, the plain
    build in one process."""
    from irnuc.cosim.bulk import build_bulk
    from irnuc.cosim.method_bulk import check_method_bulk, run_method_bulk

    seq = sequence or drift_sequence(frames, shape, seed=seed)
    cals = coeffs or calibrate_methods(cfgs, shape, seed=seed)
    out = []
    for cfg in cfgs:
        c = cals[cfg.name]
        rd = seq.reading if "fpa" in cfg.base.readings else None
        t0 = time.perf_counter()
        expected = method_top(seq.codes, c, FrameInputs(reading=rd)).y
        t_golden = time.perf_counter() - t0
        bld = build_bulk(cfg, top="method_dpc_top")
        kw = {"shards": shards, "seed": seed + 1, "idle_percent": idle_percent,
              "stall_percent": stall_percent}
        t0 = time.perf_counter()
        res = run_method_bulk(bld, c, seq.codes, rd, **kw)
        chk = check_method_bulk(res, c, seq.codes, rd, expected=expected)
        t_bulk = time.perf_counter() - t0

        run = (c, seq.codes, rd, expected)
        none = (None, None, None)
        base = _again(bld, *run, {**kw, "public_eval": True}) if baseline else none
        na = (_again(build_bulk(cfg, top="method_dpc_top", assertions=False), *run, kw)
              if noassert else none)
        pg = _again(pgo_build(cfg, c, seq, rd), *run, kw) if pgo else none
        one = _again(bld, *run, {**kw, "shards": 1}) if single else none
        out.append(MethodRun(name=cfg.name, method=cfg.method, frames=seq.codes.shape[0],
                             pixels=int(seq.codes.size), compared=chk.compared,
                             mismatches=chk.mismatches, missing=chk.missing, extra=chk.extra,
                             frame_err=res.frame_err, cycles=res.cycles,
                             sim_seconds=res.sim_seconds, golden_seconds=t_golden,
                             readings=(int(seq.reading.min()), int(seq.reading.max())),
                             lines=list(chk.lines), bulk_seconds=t_bulk,
                             baseline_seconds=base[0], baseline_cpu_seconds=base[1],
                             baseline_mismatches=base[2], sim_cpu_seconds=res.cpu_seconds,
                             noassert_seconds=na[0], noassert_cpu_seconds=na[1],
                             noassert_mismatches=na[2], pgo_seconds=pg[0],
                             pgo_cpu_seconds=pg[1], pgo_mismatches=pg[2],
                             single_seconds=one[0], single_cpu_seconds=one[1],
                             single_mismatches=one[2], shards=res.shards))
    return out
