"""Issue 36's goal, measured: on the power-on warm-up and the ambient ramp, which method keeps
the worst residual fixed pattern <= 0.5 x NETD (NETD at a 300 K scene, every noise source)
between FFCs, at what dead time and memory, or why none can.

Three measurements on the model (the study sensor, seeded everywhere):

* :func:`floor_terms`: where the floor of the linear (two-point) core comes from, at the
  calibration state (FPA at the plan's reference, housing at the FPA) on noise-free frames:
  the response's curvature over the scene range (a per-pixel least-squares line through the
  calibration scenes of the *unquantized* ADC input, evaluated between and at them), the ADC's
  14-bit quantization (the same fit on the codes), the fixed-point correction (the golden
  model), and the row skimming (the same with ``readout.skimming = "none"``).
* :func:`averaging`: the same state with the sensor's temporal noise on everywhere (the
  calibration plan's frames, the FFC's shutter frames, the frames measured): the residual
  fixed pattern against the frames averaged at calibration (per point) and at each FFC. The
  fixed pattern of a noisy camera is each pixel's *expected* corrected output; it is
  estimated from ``M`` frames per scene without the temporal noise's bias
  (:func:`fixed_pattern`, the NVESD 3D-noise separation of sigma_vh from sigma_tvh).
* :func:`scenario`: a method and an FFC policy on a scenario, noise on: the schedule at the
  camera's frame rate, its FPA and housing sensors' readings, the FFC closed loop on them
  (``ffc_policy.closed_loop``), every FFC's offsets refreshed from ``N`` noisy shutter frames
  at that moment's FPA, housing and shutter temperatures, the lens at its own temperature
  (its emission in the optics' cone, ``model.stages.stage_lens_view``); the residual read
  at the frame before each FFC (the sawtooth's peaks, those with the largest drift since
  their refresh) and at evenly spaced shown frames.

Beside the configurations, float what-ifs (:class:`CurvatureCore`, :class:`PiecewiseCore`:
a core with a curvature term, tc_gain's gain and tc_housing's offset terms, one polynomial or
piecewise over the FPA; no fixed point, no RTL) say what a method that meets the goal would
need, and ``Setup.housing_lag_s`` replaces the scenario's housing sensor lag (a what-if of a
sensor without lag).

The calibration plan covers the scenario (FPA at ``fpa_points`` temperatures over its span;
the housing at ``OFFSETS`` from the FPA for a method that reads it), as
``benchmarks/bench_tc_housing_scenarios.py`` has it; ``reading_range_bits`` (and
``housing_range_bits``) widened to the span and the polynomial's formats with them
(:func:`configs`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from irnuc.reports.studies import drift_common as dc

#: The goal: the worst residual fixed pattern at most this many NETD.
GOAL_NETD = 0.5
#: The plan's and the measurement's scenes, K.
SCENES = (290.0, 330.0, 370.0)
#: The housing offsets (K, from the FPA) of a plan for a method that reads the housing.
OFFSETS = (-6.0, -3.0, 0.0)
#: Frames lost per FFC besides its N shutter frames (the shutter moving), as ffc_interval.
SETTLE_FRAMES = 1
#: VGA at 60 frames/s, the bandwidth the docs' tables quote.
VGA_PIXELS_PER_S = 640 * 480 * 60


def fixed_pattern(y: np.ndarray, good: np.ndarray) -> tuple[float, float]:
    """The fixed pattern and the temporal noise of ``M`` frames of one uniform scene.

    Parameters
    ----------
    y : (M, H, W) array
        Corrected frames (output codes), the camera in one state, M >= 2.
    good : (H, W) bool
        The pixels measured.

    Returns ``(fixed, temporal)``, output codes: ``fixed`` the spatial standard deviation of
    each pixel's expected value, sqrt(var_space(mean_t y) - mean_space(var_t y) / M) (the
    temporal noise's share of the frame average taken out; 0 when negative), ``temporal``
    the root-mean-square over the pixels of each pixel's temporal standard deviation.
    """
    a = np.asarray(y, dtype=np.float64)[:, good]
    m = a.shape[0]
    if m < 2:
        raise ValueError(f"fixed_pattern: {m} frame(s); at least 2 are needed")
    var_t = a.var(axis=0, ddof=1)
    fixed2 = float(a.mean(axis=0).var() - var_t.mean() / m)
    return math.sqrt(max(fixed2, 0.0)), math.sqrt(float(var_t.mean()))


def range_bits(span_codes: float) -> int:
    """Bits that hold +-span_codes around the reference (the clamp at 2^bits - 1)."""
    return max(11, int(np.ceil(np.log2(span_codes + 2))))


def configs(labels: Sequence[str], ts: int, hs: int, ffc_frames: int = 8) -> dict[str, Any]:
    """The configurations of ``labels`` with v (and w') widened to ``ts`` (``hs``) bits and
    the polynomial's formats as many integer bits wider (a coefficient per 2^Ts codes
    doubles per bit). Labels: a pipelines.toml name; ``tchousing14+tc_gain`` (tcgain14's gain
    formats); ``tchousing14+ffc`` (tc_housing with tc_gain composed with ffc, tcffc14's
    FFC: the golden model only, its RTL not built); an FFC configuration with
    ``ffc_frames`` shutter frames."""
    from irnuc.nuc_fixed import load_pipeline

    out = {}
    for label in labels:
        name = label.split("+")[0]
        cfg = load_pipeline(name)
        grow = {"tc1": ts - 11, "tc2": 2 * (ts - 11), "th1": hs - 11,
                "thx": ts - 11 + hs - 11, "th2": 2 * (hs - 11)}
        ch: dict = {"formats": {f.name: {"int_bits": f.int_bits + grow[f.name]}
                                for f in cfg.formats if grow.get(f.name)}}
        if "fpa" in cfg.base.readings:
            ch["reading_range_bits"] = ts
        if "housing" in cfg.base.readings:
            ch["housing_range_bits"] = hs
        if label.endswith(("+tc_gain", "+ffc")) and name == "tchousing14":
            g = load_pipeline("tcgain14").to_dict()["formats"]
            ch["tc_gain"] = True
            ch["formats"] |= {"tg1": g["tg1"], "tg2": g["tg2"]}
        if label.endswith("+ffc"):
            f = load_pipeline("tcffc14").to_dict()
            ch.update(method=f"{cfg.method}+ffc", ffc_output=f["ffc_output"])
            ch["formats"] |= {"ffc": f["formats"]["ffc"]}
        if label.endswith("+ffc") or cfg.has("ffc"):
            ch["ffc_frames"] = int(ffc_frames)
        out[label] = cfg.replace(**ch)
    return out


def cost(cfg: Any) -> dict[str, float]:
    """Memory (bits per pixel, calibration + runtime), bits read per pixel and frame, and the
    VGA 60 Hz bandwidth (MB/s) of a configuration (:func:`drift_common.memory_bits`)."""
    m = dc.memory_bits(cfg)
    return {"memory_bits": m["calibration_bits"] + m["runtime_bits"],
            "calibration_bits": m["calibration_bits"], "runtime_bits": m["runtime_bits"],
            "read_bits": m["read_bits_per_frame"],
            "vga60_MB_s": m["read_bits_per_frame"] * VGA_PIXELS_PER_S / 8e6}


class Camera:
    """The study sensor with its temporal noise on (or off), each call drawing new noise:
    every call takes the next range of frame indices of the noise streams (the same pixels,
    independent draws; ``Pipeline.run(first_frame=...)``), so the results are a function of
    the sensor's seed and the order of the calls only."""

    def __init__(self, sensor: dc.StudySensor, noise: bool = True) -> None:
        self.sensor = sensor
        self.noise = noise
        self.next_frame = 1 << 30  # clear of the calibration plan's indices

    def frames(self, fpa_K: float, cam_K: float, scenes: Sequence[float], repeats: int = 1,
               lens_K: float | None = None, noise: bool | None = None
               ) -> tuple[np.ndarray, np.ndarray]:
        """Raw codes (len(scenes) * repeats, H, W) and blind codes of uniform scenes (each
        scene ``repeats`` times), the lens at ``lens_K`` (default the housing's)."""
        from irnuc.model.pipeline import Pipeline
        from irnuc.model.scenes import Scene

        noisy = self.noise if noise is None else noise
        t = np.repeat(np.asarray(scenes, np.float64), repeats)
        env = None
        if lens_K is not None and lens_K != cam_K:
            env = {"T_lens": np.full(t.size, float(lens_K)), "T_cam": np.full(t.size, cam_K)}
        pipe = Pipeline(self.sensor.config(fpa_K, cam_K, noisy), self.sensor.seed)
        out = pipe.run(t, ["codes", "blind_codes"], Scene(), env=env, first_frame=self.next_frame)
        self.next_frame += t.size
        return out["codes"], np.asarray(out["blind_codes"])

    def shutter_frames(self, fpa_K: np.ndarray, cam_K: np.ndarray, lens_K: np.ndarray,
                       shutter_K: np.ndarray) -> np.ndarray:
        """Raw codes (N, H, W) of N frames with the shutter closed, each frame at its own
        FPA, housing, lens and shutter temperature (K, arrays of N): an FFC's frames while
        the camera drifts (the model's shutter: it fills each pixel's cone at its own
        temperature, ``model.stages.stage_shutter_view``)."""
        from irnuc.model.pipeline import Pipeline
        from irnuc.model.scenes import Scene

        n = len(fpa_K)
        env = {"T_substrate": np.asarray(fpa_K, np.float64), "T_cam": np.asarray(cam_K, np.float64),
               "T_lens": np.asarray(lens_K, np.float64), "shutter": np.ones(n, bool),
               "T_shutter": np.asarray(shutter_K, np.float64)}
        pipe = Pipeline(self.sensor.config(float(fpa_K[0]), float(cam_K[0]), self.noise),
                        self.sensor.seed)
        out = pipe.run(np.full(n, float(shutter_K[0])), ["codes"], Scene(), env=env,
                       first_frame=self.next_frame)
        self.next_frame += n
        return out["codes"]


def calibrate(sensor: dc.StudySensor, labels: Sequence[str], fpa: Sequence[float], ref: float,
              frames: int, noise: bool, ts: int = 11, hs: int = 11, ffc_frames: int = 8,
              offsets: Sequence[float] = OFFSETS) -> dict[str, Any]:
    """Every configuration of :func:`configs` calibrated on one plan over FPA x housing
    (``frames`` per point, the sensor's noise on or off); one that does not read the housing
    is fitted at housing = FPA (the registry's rule)."""
    from irnuc.nuc_fixed.fit import calibrate_points
    from irnuc.nuc_fixed.plan import CalibrationPlan, run_plan

    p = CalibrationPlan(scene=SCENES, fpa=tuple(fpa), frames=int(frames), reference_fpa=ref,
                        housing_offset=tuple(offsets))
    ov = {**sensor.base_overrides(), "noise.enabled": bool(noise)}
    pts = run_plan(p, sensor.preset, ov, seed=sensor.seed)
    floats = {CURVATURE: (2, False), CURVATURE3: (3, False), CURVATURE_FFC: (2, True)}
    fixed = [x for x in labels if x not in floats and x != CURVATURE_PW]
    cals: dict[str, Any] = {label: calibrate_points(pts, cfg)
                            for label, cfg in configs(fixed, ts, hs, ffc_frames).items()}
    # the float cores' targets and bad pixels: the calibration's (typical14's without one)
    base = list(cals.values()) or [calibrate_points(pts, configs(("typical14",), ts, hs)
                                                    ["typical14"])]
    good = ~np.logical_or.reduce([c.bad for c in base])
    lsb = (p.fpa_sensor.lsb_K, p.housing_sensor.lsb_K)
    for label, (order, ffc) in floats.items():
        if label in labels:
            core = CurvatureCore.fit(pts, base[0].targets, good, *lsb, order)
            cals[label] = dataclasses.replace(core, ffc=ffc)
    if CURVATURE_PW in labels:
        cals[CURVATURE_PW] = PiecewiseCore.fit(pts, base[0].targets, good, *lsb)
    return {"plan": p, "cal": cals, "good": good}


#: The labels of :class:`CurvatureCore` in :func:`calibrate` and :class:`Setup`: the FPA
#: polynomials of order 2 (tc_housing's) and 3.
CURVATURE = "float: curvature + tc_housing"
CURVATURE3 = "float: curvature + tc_housing, cubic in the FPA"
CURVATURE_FFC = "float: curvature + tc_housing + ffc"
CURVATURE_PW = "float: curvature + tc_housing, piecewise in the FPA"


@dataclasses.dataclass
class CurvatureCore:
    """A what-if, not a configuration: the correction a core with a curvature term would
    make, in float (no fixed point, no RTL), to measure whether such a core could meet the
    goal. Per pixel,

        y = (g0 + g1 v + g2 v^2) x + q x^2 + c0 + c1 v + c2 v^2 + h1 w + hx v w + h2 w^2

    (``order`` 3: g3 v^3 x and c3 v^3 too),
    x the raw code scaled to (-1, 1), v and w the FPA and housing readings from their
    references in units of 10 K: tc_housing's offset, tc_gain's gain, and quadratic's
    curvature, fitted per pixel by least squares on every (FPA, housing, scene) point of the
    plan to the calibration's targets."""

    coef: np.ndarray        # (10, H, W)
    t_ref: float            # codes
    h_ref: float            # codes
    lsb_t: float            # K per code
    lsb_h: float
    targets: np.ndarray
    order: int = 2
    ffc: bool = False
    cfg: Any = None

    def has(self, stage: str) -> bool:
        """Whether the core has the stage (``ffc``: an offset refreshed from the shutter's
        frames, the float twin of the ffc stage: each pixel's mean over the N frames made
        equal to the array's median)."""
        return stage == "ffc" and self.ffc

    def _features(self, x: np.ndarray, v: Any, w: Any) -> list[Any]:
        out = [x, x * v, x * v * v, x * x, 1.0, v, v * v, w, v * w, w * w]
        return out + ([x * v**3, v**3] if self.order == 3 else [])

    @classmethod
    def fit(cls, pts: Any, targets: np.ndarray, good: np.ndarray, lsb_t: float,
            lsb_h: float, order: int = 2) -> CurvatureCore:
        means = pts.codes.mean(axis=2, dtype=np.float64)           # (P, S, H, W)
        t_ref = float(np.rint(pts.reading[pts.reference].mean()))
        h_ref = float(np.rint(pts.housing_reading[pts.reference].mean()))
        n_p, n_s, h, w = means.shape
        shape = cls(np.empty(0), t_ref, h_ref, lsb_t, lsb_h, np.empty(0), order)
        rows, tgt = [], []
        for p in range(n_p):
            v = (pts.reading[p].mean() - t_ref) * lsb_t / 10.0
            u = (pts.housing_reading[p].mean() - h_ref) * lsb_h / 10.0
            for k in range(n_s):
                x = means[p, k] / 8192.0 - 1.0
                rows.append(np.stack(np.broadcast_arrays(*shape._features(x, v, u))))
                tgt.append(np.full((h, w), float(targets[k])))
        a = np.stack(rows)                                        # (PS, 10, H, W)
        b = np.stack(tgt)                                         # (PS, H, W)
        ata = np.einsum("nihw,njhw->hwij", a, a)
        atb = np.einsum("nihw,nhw->hwi", a, b)
        ata += 1e-12 * np.eye(ata.shape[-1])  # the bad pixels' singular systems
        coef = np.linalg.solve(ata, atb[..., None])[..., 0]       # (H, W, 10)
        return cls(np.moveaxis(coef, -1, 0), t_ref, h_ref, lsb_t, lsb_h,
                   np.asarray(targets, np.float64), order)

    def correct(self, raw: np.ndarray, reading: int, housing: int) -> np.ndarray:
        v = (reading - self.t_ref) * self.lsb_t / 10.0
        w = (housing - self.h_ref) * self.lsb_h / 10.0
        x = np.asarray(raw, np.float64) / 8192.0 - 1.0
        return sum(c * f for c, f in zip(self.coef, self._features(x, v, w), strict=True))


@dataclasses.dataclass
class PiecewiseCore:
    """:class:`CurvatureCore` piecewise in the FPA (a what-if too): one core per window of
    three consecutive FPA points of the plan (each with all its housing offsets), the frame
    corrected by the core whose middle point's FPA reading is nearest its own (as
    table_interp picks its tables, without the interpolation)."""

    centres: np.ndarray                 # (K,) FPA readings, codes
    cores: list[CurvatureCore]
    targets: np.ndarray
    cfg: Any = None

    @classmethod
    def fit(cls, pts: Any, targets: np.ndarray, good: np.ndarray, lsb_t: float,
            lsb_h: float) -> PiecewiseCore:
        from types import SimpleNamespace

        fpa = np.asarray(pts.fpa_K, np.float64)
        temps = np.unique(fpa)
        if temps.size < 3:
            raise ValueError(f"PiecewiseCore: {temps.size} FPA temperature(s); at least 3")
        centres, cores = [], []
        for k in range(1, temps.size - 1):
            sel = np.flatnonzero(np.isin(fpa, temps[k - 1:k + 2]))
            mid = sel[fpa[sel] == temps[k]]
            ref = int(mid[np.argmin(np.abs(pts.housing_K[mid] - temps[k]))])
            sub = SimpleNamespace(codes=pts.codes[sel], reading=pts.reading[sel],
                                  housing_reading=pts.housing_reading[sel],
                                  reference=int(np.flatnonzero(sel == ref)[0]))
            cores.append(CurvatureCore.fit(sub, targets, good, lsb_t, lsb_h))
            centres.append(float(pts.reading[ref].mean()))
        return cls(np.asarray(centres), cores, np.asarray(targets, np.float64))

    def has(self, stage: str) -> bool:
        return False

    def correct(self, raw: np.ndarray, reading: int, housing: int) -> np.ndarray:
        core = self.cores[int(np.argmin(np.abs(self.centres - reading)))]
        return core.correct(raw, reading, housing)


def _inputs(cfg: Any, n: int, reading: Any, housing: Any, shutter: bool) -> Any:
    from irnuc.nuc_fixed.method_top import FrameInputs

    return FrameInputs(reading=np.broadcast_to(np.asarray(reading, np.int64), (n,)).copy(),
                       housing_reading=np.broadcast_to(np.asarray(housing, np.int64),
                                                       (n,)).copy(),
                       shutter=np.full(n, shutter) if cfg.has("ffc") else None)


def refresh(cal: Any, shutter_raw: np.ndarray, readings: Any, housing: Any) -> np.ndarray:
    """The FFC offsets of ``cal``'s configuration from its N shutter frames (golden model)."""
    from irnuc.nuc_fixed.method_top import method_top

    n = shutter_raw.shape[0]
    if isinstance(cal, CurvatureCore):
        y = cal.correct(shutter_raw, int(np.asarray(readings).reshape(-1)[-1]),
                        int(np.asarray(housing).reshape(-1)[-1])).mean(axis=0)
        return np.median(y) - y
    return method_top(shutter_raw, cal.coeffs, _inputs(cal.cfg, n, readings, housing,
                                                       True)).ffc_offset


def measure(cal: Any, good: np.ndarray, sc: Any, raw: np.ndarray, slope_raw: np.ndarray,
            repeats: int, reading: int, housing: int, ffc_offset: np.ndarray | None,
            scenes: Sequence[float] = SCENES) -> list[dict[str, float]]:
    """The residual of one camera state: per scene, the fixed pattern of ``repeats`` frames
    (:func:`fixed_pattern`; one noise-free frame: its spatial std) through the corrected
    image's local responsivity (from the noise-free ``slope_raw``, :func:`metrics.residuals_mK`'s
    order), the temporal noise beside it, and the level error of the frames' mean."""
    from irnuc.nuc_fixed.method_top import method_top

    if isinstance(cal, (CurvatureCore, PiecewiseCore)):
        add = 0.0 if ffc_offset is None else ffc_offset
        y = cal.correct(raw, reading, housing) + add
        ys = cal.correct(slope_raw, reading, housing) + add
    else:
        kw = {"ffc_offset": ffc_offset} if ffc_offset is not None else {}
        y = method_top(raw, cal.coeffs, _inputs(cal.cfg, raw.shape[0], reading, housing, False),
                       **kw).y.astype(np.float64)
        ys = method_top(slope_raw, cal.coeffs, _inputs(cal.cfg, slope_raw.shape[0], reading,
                                                       housing, False), **kw).y
    ref = dc.residuals(ys, good, scenes, sc)
    out = []
    for k, r in enumerate(ref):
        yk = y[k * repeats:(k + 1) * repeats]
        fixed, temporal = (fixed_pattern(yk, good) if repeats > 1
                           else (float(yk[0][good].std()), 0.0))
        resp = r["responsivity_codes_per_K"]
        mean = float(yk.mean(axis=0)[good].mean())
        out.append({"scene_K": r["scene_K"], "fpn_lsb": fixed, "temporal_lsb": temporal,
                    "fpn_mK": 1e3 * fixed / resp if resp > 0 else math.inf,
                    "temporal_mK": 1e3 * temporal / resp if resp > 0 else math.inf,
                    "level_error_mK": 1e3 * (sc.temperature(mean) - r["scene_K"])})
    return out


def floor_terms(sensor: dc.StudySensor, eval_scenes: Sequence[float] = (290.0, 310.0, 330.0,
                                                                       350.0, 370.0),
                fpa_K: float = 298.0) -> dict[str, Any]:
    """The noise-free floor of the linear core at the calibration state, term by term (see
    the module docstring); mK through the local responsivity at each of ``eval_scenes``."""
    from irnuc import model
    from irnuc.nuc_fixed.method_top import method_top
    from irnuc.reports.studies.metrics import slope_scenes

    sl = slope_scenes(eval_scenes)
    plan = {**dc.PLAN, "fpa": (fpa_K - 10.0, fpa_K, fpa_K + 10.0)}
    names = ("typical14", "quadratic14", "tcoffset14", "tcffc14", "quadffc14")
    cal = dc.calibrate_methods(sensor, names, plan)
    good = ~np.logical_or.reduce([c.bad for c in cal["cal"].values()])

    def fit_line(skim: str) -> dict[str, list[float]]:
        ov = {**sensor.overrides, "readout.skimming": skim}
        s2 = dataclasses.replace(sensor, overrides=ov)
        lsb = None
        res = {}
        cal_fr = model.simulate(s2.config(fpa_K, fpa_K), list(SCENES), seed=sensor.seed,
                                outputs=["codes", "voltage"])
        ev_fr = model.simulate(s2.config(fpa_K, fpa_K), sl, seed=sensor.seed,
                               outputs=["codes", "voltage"])
        adc = s2.config(fpa_K, fpa_K)["adc"]
        lsb = (adc["v_high"] - adc["v_low"]) / 2 ** adc["bits"]
        for what, xc, xe in (
                ("curvature", (cal_fr.outputs["voltage"] - adc["v_low"]) / lsb,
                 (ev_fr.outputs["voltage"] - adc["v_low"]) / lsb),
                ("curvature+adc", cal_fr.codes.astype(np.float64), ev_fr.codes.astype(np.float64))):
            x = xc[:, good]
            t = x.mean(axis=1)  # the targets: each scene's mean
            xm, tm = x.mean(axis=0), t.mean()
            g = ((x - xm) * (t - tm)[:, None]).sum(0) / ((x - xm) ** 2).sum(0)
            y = g * xe[:, good] + (tm - g * xm)
            row = []
            for k in range(len(eval_scenes)):
                f, lo, hi = y[3 * k], y[3 * k + 1], y[3 * k + 2]
                row.append(1e3 * float(f.std()) / float(hi.mean() - lo.mean()))
            res[what] = row
        return res

    terms = {f"float line, {k}": v for k, v in fit_line("row").items()}
    terms["float line, curvature+adc, skimming none"] = fit_line("none")["curvature+adc"]
    raw, _ = dc.frames_at(sensor, fpa_K, fpa_K, sl)
    sh, _ = dc.frames_at(sensor, fpa_K, fpa_K, [fpa_K], repeats=8)
    rd = int(cal["plan"].fpa_sensor.read(fpa_K)[0])
    for n, c in cal["cal"].items():
        sc = dc.scale(sensor, c.targets, SCENES)
        kw = {}
        if c.cfg.has("ffc"):
            kw["ffc_offset"] = refresh(c, sh, rd, 0)
        y = method_top(raw, c.coeffs, _inputs(c.cfg, raw.shape[0], rd, 0, False), **kw).y
        label = f"golden {n}" + (" (after an FFC at the FPA temperature)" if kw else "")
        terms[label] = [r["fpn_mK"] for r in dc.residuals(y, good, eval_scenes, sc)]
    return {"fpa_K": fpa_K, "calibration_scenes_K": list(SCENES),
            "scenes_K": list(eval_scenes), "fpn_mK": terms}


def averaging(sensor: dc.StudySensor, cal_frames: Sequence[int] = (2, 8, 32),
              ffc_frames: Sequence[int] = (8, 16, 32, 64), repeats: int = 48,
              fpa_K: float = 298.0,
              labels: Sequence[str] = ("tcgain14", "tcffc14", "quadratic14", "quadffc14")
              ) -> dict[str, Any]:
    """The residual against the frames averaged, noise on, at the calibration state: every
    label calibrated with each ``cal_frames`` per point; an FFC method refreshed from each
    ``ffc_frames`` shutter frames there; ``repeats`` frames per scene measured."""
    from irnuc.reports.studies.metrics import slope_scenes

    cam = Camera(sensor)
    fpa = (fpa_K - 10.0, fpa_K, fpa_K + 10.0)
    raw, _ = cam.frames(fpa_K, fpa_K, SCENES, repeats)
    slope_raw, _ = cam.frames(fpa_K, fpa_K, slope_scenes(SCENES), noise=False)
    sh_all, _ = cam.frames(fpa_K, fpa_K, [fpa_K], max(ffc_frames))
    rows = []
    for nc in cal_frames:
        cals = calibrate(sensor, labels, fpa, fpa_K, nc, True, offsets=(0.0,))
        good = cals["good"]
        rd = int(cals["plan"].fpa_sensor.read(fpa_K)[0])
        for label, c0 in cals["cal"].items():
            sc = dc.scale(sensor, c0.targets, SCENES)
            for nf in (ffc_frames if c0.cfg.has("ffc") else (0,)):
                c = c0
                off = None
                if nf:
                    # the accumulator's width follows N: the same coefficients, N frames
                    c = with_ffc_frames(c0, nf)
                    off = refresh(c, sh_all[:nf], rd, 0)
                res = measure(c, good, sc, raw, slope_raw, repeats, rd, 0, off)
                rows.append({"method": label, "cal_frames": nc, "ffc_frames": nf,
                             "fpn_mK": [r["fpn_mK"] for r in res],
                             "worst_fpn_mK": max(r["fpn_mK"] for r in res),
                             "temporal_mK": [r["temporal_mK"] for r in res]})
    netd = dc.netd(sensor, fpa_K).netd_K * 1e3
    return {"fpa_K": fpa_K, "scenes_K": list(SCENES), "repeats": repeats, "netd_mK": netd,
            "rows": rows}


def with_ffc_frames(cal: Any, n: int) -> Any:
    """``cal`` with its FFC refreshed from ``n`` shutter frames: the same coefficient codes
    (N sets only the FFC's accumulator and mean, not the calibration)."""
    if isinstance(cal, CurvatureCore):
        return cal
    cfg = cal.cfg.replace(ffc_frames=int(n))
    return dataclasses.replace(cal, coeffs=dataclasses.replace(cal.coeffs, cfg=cfg))


@dataclasses.dataclass(frozen=True)
class Setup:
    """What a scenario run measures: the methods (labels of :func:`configs`), the FFC
    policies (name -> (period s, FPA change K), None off) of the FFC methods, the frames
    averaged per calibration point and per FFC, the frames measured per scene and state,
    how many sawtooth peaks and evenly spaced states are read."""

    labels: tuple[str, ...] = ("tchousing14+tc_gain", "tcffc14", "tchousing14+ffc",
                               "quadffc14", CURVATURE, CURVATURE_FFC, CURVATURE_PW)
    policies: tuple[tuple[str, float | None, float | None], ...] = (
        ("Lepton: 3 min or 1.5 K", 180.0, 1.5), ("0.1 K", None, 0.1))
    cal_frames: int = 32
    ffc_frames: tuple[int, ...] = (8, 32)
    repeats: int = 24
    peaks: int = 6
    states: int = 8
    fpa_points: int = 5
    noise: bool = True
    #: FPA points of the plan of the piecewise core (:data:`CURVATURE_PW`)
    piecewise_fpa_points: int = 9
    #: the housing sensor's lag, s, instead of the scenario's (None: as shipped): a what-if
    housing_lag_s: float | None = None


def scenario(name: str, sensor: dc.StudySensor, setup: Setup = Setup()) -> dict[str, Any]:
    """Every method of ``setup`` on the named scenario (see the module docstring)."""
    from irnuc.model.sequence import load_sequence
    from irnuc.nuc_fixed.ffc_policy import FfcPolicy, closed_loop
    from irnuc.reports.studies.metrics import slope_scenes

    seq = load_sequence(name)
    if setup.housing_lag_s is not None:
        seq = dataclasses.replace(seq, housing_sensor=dataclasses.replace(
            seq.housing_sensor, lag_s=float(setup.housing_lag_s)))
    sched = dataclasses.replace(seq, record_every=1).schedule()
    f = sched.fields(seq.fpa_sensor, sensor.seed, seq.housing_sensor)
    fpa_K, cam_K = np.asarray(sched.fpa_K), np.asarray(sched.T_cam_K)
    lens_K = np.asarray(sched.lens_K if sched.lens_K is not None else sched.T_cam_K)
    shut_K = np.asarray(sched.T_shutter_K)
    rd, hrd = np.asarray(f["fpa_reading"]), np.asarray(f["housing_reading"])
    n = fpa_K.size
    lo, hi = float(fpa_K.min()), float(fpa_K.max())
    fpa = tuple(float(t) for t in np.round(np.linspace(lo, hi, setup.fpa_points), 2))
    ref = fpa[len(fpa) // 2]
    ts = range_bits(max(ref - lo, hi - ref) / seq.fpa_sensor.lsb_K)
    hs = range_bits((max(ref - (lo + min(OFFSETS)), hi - ref) + 1.0)
                     / seq.housing_sensor.lsb_K)
    plain = tuple(x for x in setup.labels if x != CURVATURE_PW)
    cals = calibrate(sensor, plain, fpa, ref, setup.cal_frames, setup.noise, ts, hs) if plain \
        else {"cal": {}, "good": None}
    if CURVATURE_PW in setup.labels:
        fpa_pw = tuple(float(t) for t in np.round(np.linspace(lo, hi,
                                                              setup.piecewise_fpa_points), 2))
        pw = calibrate(sensor, (CURVATURE_PW,), fpa_pw, fpa_pw[len(fpa_pw) // 2],
                       setup.cal_frames, setup.noise, ts, hs)
        cals["cal"][CURVATURE_PW] = pw["cal"][CURVATURE_PW]
        cals["good"] = pw["good"] if cals["good"] is None else cals["good"] & pw["good"]
    good = cals["good"]
    cam = Camera(sensor, setup.noise)
    frames_cache: dict[int, tuple[np.ndarray, np.ndarray]] = {}

    def frames(i: int) -> tuple[np.ndarray, np.ndarray]:
        if i not in frames_cache:
            args = (float(fpa_K[i]), float(cam_K[i]))
            raw, _ = cam.frames(*args, SCENES, setup.repeats, lens_K=float(lens_K[i]))
            sl, _ = cam.frames(*args, slope_scenes(SCENES), lens_K=float(lens_K[i]),
                               noise=False)
            frames_cache[i] = (raw, sl)
        return frames_cache[i]

    def shutter(s: int, nf: int) -> np.ndarray:
        idx = np.minimum(np.arange(s, s + nf), n - 1)
        return cam.shutter_frames(fpa_K[idx], cam_K[idx], lens_K[idx], shut_K[idx])

    def read(c: Any, i: int, off: np.ndarray | None) -> dict[str, Any]:
        raw, sl = frames(i)
        sc = dc.scale(sensor, c.targets, SCENES)
        res = measure(c, good, sc, raw, sl, setup.repeats, int(rd[i]), int(hrd[i]), off)
        return {"frame": int(i), "time_s": float(sched.time_s[i]), "fpa_K": float(fpa_K[i]),
                "housing_K": float(cam_K[i]),
                "fpn_mK": max(r["fpn_mK"] for r in res),
                "level_error_mK": max((r["level_error_mK"] for r in res), key=abs),
                "per_scene_mK": [r["fpn_mK"] for r in res]}

    out: dict[str, Any] = {
        "fpa_span_K": [lo, hi], "plan_fpa_K": list(fpa), "reading_range_bits": ts,
        "housing_range_bits": hs, "housing_sensor_node": seq.housing_sensor.node,
        "housing_sensor_lag_s": seq.housing_sensor.lag_s,
        "housing_minus_fpa_K": [float((cam_K - fpa_K).min()), float((cam_K - fpa_K).max())],
        "lens_minus_housing_K": [float((lens_K - cam_K).min()), float((lens_K - cam_K).max())],
        "cal_frames": setup.cal_frames, "repeats": setup.repeats, "runs": []}
    even = np.unique(np.linspace(0, n - 1, setup.states).astype(int))
    for label, c0 in cals["cal"].items():
        if not _has_ffc(c0):
            rows = [read(c0, int(i), None) for i in even]
            out["runs"].append(_summary(label, c0.cfg, None, 0, rows, 0, 0.0, n, seq))
            continue
        for pname, period_s, change_K in setup.policies:
            pol = FfcPolicy.from_physical(period_s, change_K, seq.frame_rate,
                                          seq.fpa_sensor.lsb_K)
            for nf in setup.ffc_frames:
                c = with_ffc_frames(c0, nf)
                starts = np.asarray(closed_loop(rd, pol, nf), np.int64)
                dead = np.zeros(n, bool)
                for s in starts:
                    dead[s:s + nf + SETTLE_FRAMES] = True
                done = starts + nf

                def last_ffc(i: int, starts: np.ndarray = starts, done: np.ndarray = done
                             ) -> int:
                    return int(starts[np.searchsorted(done, i, side="right") - 1])

                def drift(i: int) -> float:
                    j = last_ffc(i)
                    return max(abs(fpa_K[i] - fpa_K[j]),
                               abs((cam_K[i] - fpa_K[i]) - (cam_K[j] - fpa_K[j])))

                cand = [int(s) - 1 for s in starts[1:] if not dead[int(s) - 1]]
                if not dead[n - 1]:
                    cand.append(n - 1)
                peaks = sorted(cand, key=drift, reverse=True)[:setup.peaks]
                shown = [int(i) for i in even if not dead[i] and i >= done[0]]
                rows = []
                offs: dict[int, np.ndarray] = {}
                for i in sorted(set(peaks) | set(shown)):
                    s = last_ffc(i)
                    if s not in offs:
                        idx = np.minimum(np.arange(s, s + nf), n - 1)
                        offs[s] = refresh(c, shutter(s, nf), rd[idx], hrd[idx])
                    rows.append(read(c, i, offs[s]) | {"drift_K": drift(i)})
                out["runs"].append(_summary(label, c.cfg, pname, nf, rows, len(starts),
                                            100.0 * float(dead.mean()), n, seq))
    return out


def _has_ffc(cal: Any) -> bool:
    if isinstance(cal, (CurvatureCore, PiecewiseCore)):
        return cal.has("ffc")
    return cal.cfg.has("ffc")


def kind(label: str) -> str:
    """What a label of :func:`configs` is: ``configuration`` (pipelines.toml, golden model
    and RTL), ``golden composition`` (the registry composes it; no RTL), ``float what-if``
    (:class:`CurvatureCore`: neither)."""
    if label.startswith("float:"):
        return "float what-if"
    return "golden composition" if label == "tchousing14+ffc" else "configuration"


def _summary(label: str, cfg: Any, policy: str | None, nf: int, rows: list[dict[str, Any]],
             ffcs: int, dead_pct: float, n: int, seq: Any) -> dict[str, Any]:
    worst = max(rows, key=lambda r: r["fpn_mK"])
    hours = n / seq.frame_rate / 3600.0
    return {"method": label, "kind": kind(label), "policy": policy, "ffc_frames": nf,
            "worst_fpn_mK": worst["fpn_mK"],
            "at": {k: worst[k] for k in ("time_s", "fpa_K", "housing_K")},
            "median_fpn_mK": float(np.median([r["fpn_mK"] for r in rows])),
            "worst_level_error_mK": max(abs(r["level_error_mK"]) for r in rows),
            "ffc_per_hour": ffcs / hours, "dead_time_pct": dead_pct,
            **(cost(cfg) if cfg is not None else {"memory_bits": None, "runtime_bits": None,
                                                   "calibration_bits": None, "read_bits": None,
                                                   "vga60_MB_s": None}), "trace": rows}
