"""The stages of the sensor pipeline (:mod:`model.pipeline`): functions of a
:class:`model.graph.RunContext` and their declared inputs, returning their outputs.

Static stages run once per configured sensor, per-chunk stages once per chunk of frames
(:func:`model.pipeline.build_stages` decides which is which for a run).
"""


from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from irnuc.model import adc as _adc
from irnuc.model import noise as _noise
from irnuc.model import readout as _readout
from irnuc.model.core import bolometer as _kb
from irnuc.model.core import pulse as _kp
from irnuc.model.core import rng as _rng
from irnuc.model.core import stream as _ks
from irnuc.model.core import warmstart as _kw
from irnuc.model.defects import (
    DefectKind,
    DefectMap,
    DefectSpec,
    apply_voltage_defects_at,
    inject_defects,
    noisy_sigma,
    voltage_defect_index,
)
from irnuc.model.fpa import BLIND, BOUNDARY, ArrayLayout, draw_pixel_parameters
from irnuc.model.graph import RunContext, Stage, threads_for
from irnuc.model.optics import cone_factor, cos4_map, focal_length_from_fov
from irnuc.model.radiometry import band_radiance
from irnuc.model.scenes import scene_temperatures

BOLOMETER_VARIANTS = {"equilibrium": 0, "paper": 1}


# ---- static stages ---------------------------------------------------------------------

def stage_params(ctx: RunContext, _: dict) -> dict:
    b = ctx.cfg["bolometer"]
    f = ctx.cfg["fpa"]
    nominal = {"R_ref": b["R_ref"], "g": b["g"], "C": b["C"]}
    return {"params": draw_pixel_parameters(ctx.layout, nominal, f["tolerance"], ctx.seed,
                                            f["spread"])}


def _defect_spec(cfg: Mapping[str, Any]) -> DefectSpec:
    return DefectSpec.from_dict(cfg["fpa"]["defects"], path="fpa.defects")


def stage_defects(ctx: RunContext, _: dict) -> dict:
    return {"defects": inject_defects(ctx.layout.active_shape, _defect_spec(ctx.cfg), ctx.seed)}


def focal_length(cfg: Mapping[str, Any], layout: ArrayLayout) -> float:
    """Focal length, m: given, or from the FOV across the active width (eq. 7)."""
    o = cfg["optics"]
    if o["focal_length"] is not None:
        return float(o["focal_length"])
    return focal_length_from_fov(o["fov"], layout.active_cols * cfg["fpa"]["pitch"])


def stage_cos4(ctx: RunContext, _: dict) -> dict:
    lay = ctx.layout
    return {"cos4": cos4_map(lay.rows, lay.cols, ctx.cfg["fpa"]["pitch"],
                             focal_length(ctx.cfg, lay), lay.optical_centre)}


def _radiance(ctx: RunContext, temps: np.ndarray) -> np.ndarray:
    r = ctx.cfg["radiometry"]
    ctx.counts["radiance_points"] += int(np.size(temps))
    return band_radiance(temps, tuple(r["band"]), rtol=r["rtol"], method=r["method"])


def stage_env_radiance(ctx: RunContext, _: dict) -> dict:
    env = ctx.cfg["environment"]
    L = _radiance(ctx, np.array([env["T_cam"], env["T_substrate"]]))
    return {"L_env": (float(L[0]), float(L[1]))}


def stage_env_frames(ctx: RunContext, _: dict) -> dict:
    """Housing and substrate radiance of each frame of the chunk (a varying environment),
    each distinct temperature evaluated once."""
    env = ctx.env
    assert env is not None
    n = ctx.frames()
    cfg_env = ctx.cfg["environment"]
    out = []
    for key in ("T_cam", "T_substrate"):
        t = np.asarray(env[key], dtype=np.float64) if key in env else np.full(n, cfg_env[key])
        uniq, inv = np.unique(t, return_inverse=True)
        out.append(_radiance(ctx, uniq)[inv].reshape(n, 1, 1))
    return {"L_env_frames": (out[0], out[1])}


def _base(cfg: Mapping[str, Any]) -> float:
    """eps A pi: absorptance times sensitive area times pi, m^2 sr."""
    f = cfg["fpa"]
    return f["absorptance"] * f["pitch"] ** 2 * f["fill_factor"] * math.pi


def _shielded(ctx: RunContext) -> np.ndarray:
    """(rows, cols) True where a pixel sees no scene: the blind (skimming) pixels, and the
    boundary pixels with ``fpa.boundary_view = 'housing'``."""
    kind = ctx.layout.kind_map()
    mask = kind == BLIND
    if ctx.cfg["fpa"]["boundary_view"] == "housing":
        mask |= kind == BOUNDARY
    return mask


def stage_coupling(ctx: RunContext, inp: dict) -> dict:
    """Per-pixel optical coupling: Q = k_scene * L_scene + q_env (W).

    The pixel (absorptance eps, sensitive area A) sees, over the projected solid angle
    pi sin^2(theta) cos^4(beta), the scene through the optics (transmission tau), and the
    housing and optics at T_cam over the rest of the hemisphere. With ``net_radiation``
    it also emits at the substrate temperature (linearised emission is part of g), so a
    scene, housing and substrate all at one temperature heat the pixel by exactly 0.
    Shielded pixels see no scene: ``seen`` is the fraction of the hemisphere (weighted by
    the projected solid angle) that is the scene.
    """
    o = ctx.cfg["optics"]
    cone = cone_factor(o["cone_method"], f_number=o["f_number"], fov=o["fov"])
    seen = o["transmission"] * cone * inp["cos4"]
    seen[_shielded(ctx)] = 0.0
    return {"k_scene": _base(ctx.cfg) * seen, "seen": seen}


def housing_power(ctx: RunContext, view: np.ndarray, L_cam: Any, L_s: Any) -> np.ndarray:
    """Power of everything but the scene (or shutter), W: eps A pi ((1 - view) L_cam -
    net L_s) with ``view`` the fraction of the pixel's hemisphere that the scene fills.

    The blind (skimming) pixels see their shield: at T_cam (``fpa.skim_shield =
    'housing'``, view 0) or at the substrate (``'substrate'``: eps A pi (1 - net) L_s, 0
    with net radiation). ``L_cam`` and ``L_s`` are numbers or (N, 1, 1) per frame.
    """
    net = 1.0 if ctx.cfg["bolometer"]["net_radiation"] else 0.0
    base = _base(ctx.cfg)
    q = base * ((1.0 - view) * L_cam - net * L_s)
    if ctx.cfg["fpa"]["skim_shield"] == "substrate":
        q = np.where(_blind_mask(ctx.layout), base * (L_s - net * L_s), q)
    return q


@dataclass(frozen=True)
class HousingFrames:
    """The housing power of frames whose housing or substrate temperature varies: the
    radiances of each frame, evaluated pixel by pixel inside the power pass
    (:func:`model.core.stream.power`) instead of as an (N, rows, cols) array."""

    seen: np.ndarray
    L_cam: np.ndarray  # (N,) W m^-2 sr^-1
    L_s: np.ndarray  # (N,)


@lru_cache(maxsize=8)
def _blind_mask(layout: ArrayLayout) -> np.ndarray:
    return layout.kind_map() == BLIND


def stage_housing(ctx: RunContext, inp: dict) -> dict:
    L_cam, L_s = inp["L_env"]
    if np.ndim(L_s):
        return {"q_env": HousingFrames(inp["seen"], np.asarray(L_cam, np.float64).reshape(-1),
                                       np.asarray(L_s, np.float64).reshape(-1))}
    return {"q_env": housing_power(ctx, inp["seen"], L_cam, L_s)}


def stage_shutter_view(ctx: RunContext, inp: dict) -> dict:
    """Coupling to a closed shutter between the lens and the array: it fills the pixel's
    cone (pi sin^2(theta) cos^4(beta), no lens transmission) at its own temperature; the
    housing fills the rest. Shielded pixels do not see it."""
    o = ctx.cfg["optics"]
    cone = cone_factor(o["cone_method"], f_number=o["f_number"], fov=o["fov"])
    view = cone * inp["cos4"]
    view[_shielded(ctx)] = 0.0
    return {"shutter_view": view}


def stage_lens_view(ctx: RunContext, inp: dict) -> dict:
    """The lens's share of each pixel's hemisphere: its emission (1 - tau) fills the optical
    cone, pi sin^2(theta) cos^4(beta) (no reflection); shielded pixels do not see it."""
    o = ctx.cfg["optics"]
    cone = cone_factor(o["cone_method"], f_number=o["f_number"], fov=o["fov"])
    view = (1.0 - o["transmission"]) * cone * inp["cos4"]
    view[_shielded(ctx)] = 0.0
    return {"lens_view": view}


def _lens_power(ctx: RunContext, inp: dict, Q: np.ndarray, resp: Any) -> None:
    """Add, in place, what a lens away from the housing temperature changes: eps A pi
    (lens view) (L(T_lens) - L(T_cam)) (the housing term assumed the lens at T_cam)."""
    env = ctx.env
    if env is None or "T_lens" not in env:
        return
    n = Q.shape[0]
    T_lens = np.asarray(env["T_lens"], dtype=np.float64)
    T_cam = (np.asarray(env["T_cam"], dtype=np.float64) if "T_cam" in env
             else np.full(n, float(ctx.cfg["environment"]["T_cam"])))
    uniq, inv = np.unique(np.concatenate([T_lens, T_cam]), return_inverse=True)
    L = _radiance(ctx, uniq)[inv]
    dL = L[:n] - L[n:]
    view = _base(ctx.cfg) * inp["lens_view"]
    act = ctx.layout.active_slice
    for k in range(n):
        if dL[k] == 0.0:
            continue
        add = view * dL[k]
        if resp is not None:
            add[act] *= resp
        Q[k] += add


def _nominal_skim(ctx: RunContext, L_cam: Any, L_s: Any) -> Any:
    """Voltage of a nominal blind pixel, its shield as ``fpa.skim_shield`` says, V: a
    number, or one per frame when ``L_cam``, ``L_s`` are given per frame."""
    b = ctx.cfg["bolometer"]
    net = 1.0 if b["net_radiation"] else 0.0
    shield = L_s if ctx.cfg["fpa"]["skim_shield"] == "substrate" else L_cam
    q = np.asarray(_base(ctx.cfg) * (shield - net * L_s), dtype=np.float64).reshape(-1, 1, 1)
    params = {k: np.full((1, 1), b[k]) for k in ("R_ref", "g", "C")}
    per_frame = np.ndim(L_s) > 0
    if b["pulse"] == "integrated":
        T_s = (ctx.substrate(q.shape[0]) if per_frame
               else np.array([float(ctx.cfg["environment"]["T_substrate"])]))
        v = _nominal_periodic(ctx, q[:, 0, 0], T_s)
        return v if per_frame else float(v[0])
    v = _solve(ctx, q, params, ctx.substrate(q.shape[0]) if per_frame else None)["v_bolo"]
    return v[:, 0, 0] if per_frame else float(v[0, 0, 0])


def stage_v_skim(ctx: RunContext, inp: dict) -> dict:
    """Reference voltage for ``skimming = none`` and the fallback of a failed blind row:
    the configured value, or a nominal blind pixel at the substrate temperature (one per
    frame when the environment varies)."""
    r = ctx.cfg["readout"]
    L_cam, L_s = inp["L_env"]
    if r["v_skim"] is not None:
        v = float(r["v_skim"])
        return {"v_skim": v if np.ndim(L_s) == 0 else np.full(np.shape(L_s)[0], v)}
    return {"v_skim": _nominal_skim(ctx, L_cam, L_s)}


# ---- per-chunk stages ------------------------------------------------------------------

def stage_scene(ctx: RunContext, _: dict) -> dict:
    return {"T_scene": scene_temperatures(ctx.scene, ctx.temps, ctx.layout.active_shape)}


def stage_scene_radiance(ctx: RunContext, inp: dict) -> dict:
    t = inp["T_scene"]
    if t.ndim == 1:  # uniform: once per frame
        return {"L_scene": _radiance(ctx, t)}
    # Per-pixel scenes: evaluate each distinct temperature once.
    uniq, inv = np.unique(t, return_inverse=True)
    L_act = _radiance(ctx, uniq)[inv.reshape(t.shape)]
    lay = ctx.layout
    rs, cs = lay.active_slice
    # Boundary pixels see the nearest active value: pad by edge replication.
    pad = ((0, 0), (rs.start, lay.rows - rs.stop), (cs.start, lay.cols - cs.stop))
    return {"L_scene": np.pad(L_act, pad, mode="edge")}


def stage_power(ctx: RunContext, inp: dict) -> dict:
    L = inp["L_scene"]
    if L.ndim == 1:
        L = L[:, None, None]
    q_env = inp["q_env"]
    resp = inp["defect_resp"]
    # The sum and the responsivity in one pass: (k L + q) resp, as numpy would round it.
    Q = np.empty((L.shape[0], *ctx.layout.shape))
    rs, cs = ctx.layout.active_slice
    none = np.empty((0, 0))
    if isinstance(q_env, HousingFrames):  # per frame: (q_env, seen, blind, L_cam, L_s)
        housing = (none, True, q_env.seen, _blind_mask(ctx.layout), q_env.L_cam, q_env.L_s)
    else:
        housing = (q_env, False, none, np.empty((0, 0), bool), np.empty(0), np.empty(0))
    q, per_frame, seen, blind, L_cam, L_s = housing
    net = 1.0 if ctx.cfg["bolometer"]["net_radiation"] else 0.0
    with threads_for(Q.size):
        _ks.power(inp["k_scene"], L, L.shape[1] == 1, q, per_frame, seen, blind,
                  _base(ctx.cfg), net, ctx.cfg["fpa"]["skim_shield"] == "substrate", L_cam,
                  L_s, resp if resp is not None else none, rs.start, cs.start, Q)
    if "lens_view" in inp:
        _lens_power(ctx, inp, Q, resp)
    if "shutter_view" in inp:
        # the frames it overwrites need the defects' responsivity too (and hide the lens)
        _shutter_power(ctx, inp, Q, resp)
    return {"Q": Q}


def _shutter_power(ctx: RunContext, inp: dict, Q: np.ndarray, resp: Any) -> None:
    """Replace, in the frames whose shutter is closed, the scene by the shutter (in place);
    ``resp``: the defects' responsivity factor (H, W) to apply to those frames (None:
    none)."""
    env = ctx.env
    if env is None or "shutter" not in env:
        return
    closed = np.flatnonzero(env["shutter"])
    if closed.size == 0:
        return
    ctx.counts["shutter_frames"] += int(closed.size)
    view = inp["shutter_view"]
    T_sh = np.asarray(env["T_shutter"], dtype=np.float64)[closed]
    uniq, inv = np.unique(T_sh, return_inverse=True)
    L_sh = _radiance(ctx, uniq)[inv]
    L_cam, L_s = inp["L_env"]
    L_cam = np.asarray(L_cam, dtype=np.float64).reshape(-1)
    L_s = np.asarray(L_s, dtype=np.float64).reshape(-1)
    for k, n in enumerate(closed):
        lc = L_cam[n] if L_cam.size > 1 else L_cam[0]
        ls = L_s[n] if L_s.size > 1 else L_s[0]
        Q[n] = _base(ctx.cfg) * view * L_sh[k] + housing_power(ctx, view, lc, ls)
        if resp is not None:
            Q[(n, *ctx.layout.active_slice)] *= resp


def _solve(ctx: RunContext, Q: np.ndarray, params: Mapping[str, np.ndarray],
           T_s: np.ndarray | None = None) -> dict:
    """The cold solve (:func:`model.core.bolometer.solve_frames`), frame by frame when the
    substrate temperature ``T_s`` (N,) varies."""
    b = ctx.cfg["bolometer"]
    B = _kb.activation_temperature(b["tcr"], b["T_ref"])
    shape = Q.shape
    dT = np.empty(shape)
    v = np.empty(shape)
    status = np.empty(shape, np.uint8)
    iters = np.empty(shape, np.int32)
    Q = np.ascontiguousarray(Q)
    temps = [float(ctx.cfg["environment"]["T_substrate"])] if T_s is None else list(T_s)
    parts = [slice(None)] if T_s is None else [slice(n, n + 1) for n in range(shape[0])]
    with threads_for(Q.size):
        for sl, Ts in zip(parts, temps, strict=True):
            _kb.solve_frames(Q[sl], params["R_ref"], params["g"], params["C"], B, b["T_ref"],
                             Ts, b["bias_current"], b["t_int"], BOLOMETER_VARIANTS[b["variant"]],
                             b["rtol"], b["max_iter"], b["runaway_temperature"], dT[sl], v[sl],
                             status[sl], iters[sl])
    return {"v_bolo": v, "dT": dT, "status": status, "iters": iters}


def stage_coefficients(ctx: RunContext, inp: dict) -> dict:
    """Per-pixel b = I^2 f / g (and f_Q for the ``paper`` variant) of the solve (static)."""
    b = ctx.cfg["bolometer"]
    p = inp["params"]
    variant = BOLOMETER_VARIANTS[b["variant"]]
    shape = p["g"].shape
    fq = np.empty(shape) if variant == 1 else np.ones((1, 1))
    bb = np.empty(shape)
    _kw.coefficients(p["g"], p["C"], b["bias_current"], b["t_int"], variant, fq, bb)
    return {"solve_coef": {"fq": fq, "b": bb, "variant": variant}}


def stage_reference_solution(ctx: RunContext, inp: dict) -> dict:
    """The solve's reference: every pixel solved once, looking at a uniform scene at the
    housing temperature with the configuration's environment (docs/model.md). The nominal
    pixel is solved first (neighbour-started, :func:`model.core.bolometer.solve_frames`)
    and every pixel is then solved from it, as a frame from its reference: the spread of
    the pixels is small, so this takes two Newton steps where the cold solve takes three."""
    b = ctx.cfg["bolometer"]
    L_cam, L_s = inp["L_env"]
    Q = inp["k_scene"] * L_cam
    Q += housing_power(ctx, inp["seen"], L_cam, L_s)
    defects: DefectMap = inp["defects"]
    if (defects.resp != 1.0).any():
        Q[ctx.layout.active_slice] *= defects.resp
    p, coef = inp["params"], inp["solve_coef"]
    # The nominal pixel at the typical power of the array.
    q_nom = float(np.median(Q[::7, ::7]))
    nominal = {k: np.full((1, 1), float(b[k])) for k in ("R_ref", "g", "C")}
    one = _solve(ctx, np.full((1, 1, 1), q_nom), nominal)
    coef_nom = stage_coefficients(ctx, {"params": nominal})["solve_coef"]
    start = _reference_state(ctx, np.full((1, 1), q_nom), nominal, coef_nom, one)
    full = {k: np.ascontiguousarray(np.broadcast_to(v, Q.shape)) if isinstance(v, np.ndarray)
            else v for k, v in start.items()}
    sol = _solve_predicted(ctx, {"solve_reference": full, "solve_coef": coef, "params": p},
                           Q[None], None, T_s=np.array([float(ctx.cfg["environment"]
                                                                 ["T_substrate"])]))
    return {"solve_reference": _reference_state(ctx, Q, p, coef, sol)}


def _reference_state(ctx: RunContext, Q: np.ndarray, p: Mapping[str, np.ndarray],
                     coef: Mapping[str, Any], sol: Mapping[str, np.ndarray]) -> dict[str, Any]:
    """Predictor maps (:func:`model.core.warmstart.reference_state`) of a solved frame."""
    b = ctx.cfg["bolometer"]
    B = _kb.activation_temperature(b["tcr"], b["T_ref"])
    T_s = float(ctx.cfg["environment"]["T_substrate"])
    shape = Q.shape
    c, s, ds = (np.empty(shape, np.float32) for _ in range(3))
    e = np.empty(shape)
    inv_T = np.empty(shape)
    _kw.reference_state(Q, coef["fq"], p["g"], coef["variant"], coef["b"], p["R_ref"], B, T_s,
                        sol["dT"][0], sol["v_bolo"][0], sol["status"][0], b["bias_current"],
                        c, s, ds, e, inv_T)
    return {"inv_T": inv_T, "e": e, "c": c, "s": s, "ds": ds}


def _solve_predicted(ctx: RunContext, inp: dict, Q: np.ndarray | None,
                     A: np.ndarray | None, T_s: np.ndarray | None = None) -> dict:
    b = ctx.cfg["bolometer"]
    ref, coef, p = inp["solve_reference"], inp["solve_coef"], inp["params"]
    B = _kb.activation_temperature(b["tcr"], b["T_ref"])
    src = A if A is not None else Q
    assert src is not None
    src = np.ascontiguousarray(src)
    n = src.shape[0]
    dT, v, status, iters = _kw.empty_solution(src.shape)
    with threads_for(src.size):
        _kw.solve_frames_predicted(src, src, A is not None, p["R_ref"], p["g"], coef["fq"],
                                   coef["variant"], coef["b"], B, b["T_ref"],
                                   ctx.substrate(n) if T_s is None else T_s,
                                   b["bias_current"], b["rtol"], b["max_iter"],
                                   b["runaway_temperature"], ref["inv_T"], ref["e"], ref["c"],
                                   ref["s"], ref["ds"], dT, v, status, iters)
    return {"v_bolo": v, "dT": dT, "status": status, "iters": iters}


def stage_bolometer(ctx: RunContext, inp: dict) -> dict:
    return _solve_predicted(ctx, inp, inp["Q"], None)


# ---- the integrated pulse train (bolometer.pulse = "integrated", docs/model.md 5) ---------

#: Relative error of a pulse's mean voltage that the step count is chosen for, and the
#: largest step count (beyond it every pixel takes the adaptive integrator).
PULSE_RTOL = 1e-5
PULSE_MAX_STEPS = 64


def frame_period(cfg: Mapping[str, Any]) -> float:
    """Time between two bias pulses of a pixel, s (1 / readout.frame_rate)."""
    return 1.0 / float(cfg["readout"]["frame_rate"])


def choose_steps(cfg: Mapping[str, Any], q: float, T_s: float) -> int:
    """Runge-Kutta steps per pulse: the fewest (1, 2, 4, ...) whose error on the nominal
    pixel's mean voltage in the periodic state (16/15 of its difference from twice as many
    steps, RK4 being of order 4) is at most PULSE_RTOL; 0 (the adaptive integrator for every
    pixel) when PULSE_MAX_STEPS are not enough."""
    b = cfg["bolometer"]
    B = _kb.activation_temperature(b["tcr"], b["T_ref"])
    g, C = float(b["g"]), float(b["C"])
    x = (frame_period(cfg) - b["t_int"]) * g / C
    n = 1
    while n <= PULSE_MAX_STEPS:
        err = _kp.nominal_steps_error(n, -math.expm1(-x), T_s, q,
                                      float(b["R_ref"]), g, C, B, b["T_ref"], b["bias_current"],
                                      b["t_int"], b["runaway_temperature"])
        if err * 16.0 / 15.0 <= PULSE_RTOL:
            return n
        n *= 2
    return 0


def stage_pulse_reference(ctx: RunContext, inp: dict) -> dict:
    """What the pulse train needs once per sensor: the step count, every pixel's 1 - d, d =
    exp(-(P - t_int) g / C) its decay between pulses, and the first guess of every periodic
    solve: its periodic excess theta_0 - Q/g at the sensor's environment looking at a
    uniform scene at the housing temperature, with its slope (single precision)."""
    b = ctx.cfg["bolometer"]
    p = inp["params"]
    L_cam, L_s = inp["L_env"]
    Q = inp["k_scene"] * L_cam + housing_power(ctx, inp["seen"], L_cam, L_s)
    defects: DefectMap = inp["defects"]
    if (defects.resp != 1.0).any():
        Q[ctx.layout.active_slice] *= defects.resp
    T_s = float(ctx.cfg["environment"]["T_substrate"])
    period = frame_period(ctx.cfg)
    n = choose_steps(ctx.cfg, float(np.median(Q[::7, ::7])), T_s)
    x = (period - b["t_int"]) * p["g"] / p["C"]
    # the nominal pixel's excess first: every pixel then starts a Newton step or two away
    q_nom = float(np.median(Q[::7, ::7]))
    nominal = {k: np.full((1, 1), float(b[k])) for k in ("R_ref", "g", "C")}
    xn = (period - b["t_int"]) * nominal["g"] / nominal["C"]
    z1 = np.zeros((1, 1), np.float32)
    nom = _periodic(ctx, np.full((1, 1, 1), q_nom), nominal,
                    {"n": n, "omd": -np.expm1(-xn), "excess": z1, "slope": z1, "teq": z1},
                    np.array([T_s]), keep=1)
    ex_nom = float(nom["theta0"][0, 0, 0] - q_nom / b["g"]) if nom["status"][0, 0, 0] == 0 else 0.0
    zero = np.zeros(Q.shape, np.float32)
    pr = {"n": n, "omd": -np.expm1(-x), "excess": np.full(Q.shape, ex_nom, np.float32),
          "slope": zero, "teq": zero}
    sol = _periodic(ctx, Q[None], p, pr, np.array([T_s]), keep=2)
    excess, slope, teq = (np.empty(Q.shape, np.float32) for _ in range(3))
    _kp.reference_maps(Q, p["g"], sol["theta0"][0], sol["ym1"][0], pr["omd"],
                       sol["status"][0], T_s, excess, slope, teq)
    return {"pulse_ref": {**pr, "excess": excess, "slope": slope, "teq": teq,
                          "period": period}}


def _periodic(ctx: RunContext, Q: np.ndarray, p: Mapping[str, np.ndarray], pr: Mapping[str, Any],
              T_s: np.ndarray, keep: int = 0) -> dict:
    """The periodic state of the pulse train of (N, rows, cols) frames (no memory); with
    ``keep`` 1 also theta_0, 2 theta_0 and y - 1, 4 also the pulse's rise and the voltage's
    sensitivity S."""
    b = ctx.cfg["bolometer"]
    B = _kb.activation_temperature(b["tcr"], b["T_ref"])
    Q = np.ascontiguousarray(Q)
    shape = Q.shape
    v, m = np.empty(shape), np.empty(shape)
    status = np.empty(shape, np.uint8)
    iters = np.empty(shape, np.int32)
    aux = np.empty((keep, *shape)) if keep else np.empty((0, 1, 1, 1))
    with threads_for(Q.size):
        _kp.periodic_frames(Q, np.ascontiguousarray(T_s, dtype=np.float64), p["R_ref"], p["g"],
                            p["C"], pr["omd"], pr["excess"], pr["slope"], pr["teq"],
                            B, b["T_ref"], b["bias_current"], b["t_int"], pr["n"],
                            b["runaway_temperature"], v, m, status, iters, aux)
    out = {"v_bolo": v, "dT": m, "status": status, "iters": iters}
    if keep:
        out |= {"theta0": aux[0]}
    if keep == 2:
        out |= {"ym1": aux[1]}
    if keep >= 4:
        out |= {"rise": aux[1], "ym1": aux[2], "sens": aux[3]}
    return out


def thermal_noise_on(cfg: Mapping[str, Any]) -> bool:
    """True if the pixels' thermal fluctuation is drawn (integrated pulse, noise on)."""
    n = cfg["noise"]
    return bool(n["enabled"] and n["thermal_fluctuation"]
                and cfg["bolometer"]["pulse"] == "integrated")


def _thermal_keys(ctx: RunContext, n: int) -> np.ndarray:
    """(n,) uint64 keys of the thermal fluctuation's draws of this chunk's frames (empty when
    it is off)."""
    if not thermal_noise_on(ctx.cfg):
        return np.empty(0, np.uint64)
    ctx.counts["thermal_noise_frames"] += n
    return _noise.keys(ctx.seed, ctx.first_frame, n, _noise.THERMAL_STREAM)


def stage_bolometer_periodic(ctx: RunContext, inp: dict) -> dict:
    """Every frame in the periodic state of its own pulse train (no memory of the frames
    before), plus the thermal fluctuation before the pulse when noise is on."""
    Q = inp["Q"]
    n = Q.shape[0]
    pr = inp["pulse_ref"]
    T_s = ctx.substrate(n)
    keys = _thermal_keys(ctx, n)
    sol = _periodic(ctx, Q, inp["params"], pr, T_s, keep=4 if keys.size else 0)
    if keys.size:
        with threads_for(Q.size):
            _kp.thermal_noise_steady(sol["v_bolo"], sol["dT"], sol["theta0"], sol["ym1"],
                                     sol["sens"], inp["params"]["C"], pr["omd"], T_s, keys,
                                     _rng.ZIG_X, _rng.ZIG_F)
    return {k: sol[k] for k in ("v_bolo", "dT", "status", "iters")}


def stage_bolometer_train_lagged(ctx: RunContext, inp: dict) -> dict:
    """The pulse train with thermal memory: each pixel's temperature carried from pulse to
    pulse (the first frame of a run in its periodic state), the substrate linear through
    every frame; the thermal fluctuation drawn between pulses when noise is on."""
    b = ctx.cfg["bolometer"]
    p, pr = inp["params"], inp["pulse_ref"]
    Q = np.ascontiguousarray(inp["Q"])
    n = Q.shape[0]
    T_s = ctx.substrate(n)
    st = ctx.state.get("train")
    if st is None:
        st = {"theta": np.zeros(p["g"].shape), "T_prev": float(T_s[0]), "has": False}
        ctx.state["train"] = st
    B = _kb.activation_temperature(b["tcr"], b["T_ref"])
    v, m = np.empty(Q.shape), np.empty(Q.shape)
    status = np.empty(Q.shape, np.uint8)
    iters = np.empty(Q.shape, np.int32)
    keys = _thermal_keys(ctx, n)
    with threads_for(Q.size):
        _kp.lagged_frames(Q, T_s, st["T_prev"], p["R_ref"], p["g"], p["C"], pr["omd"],
                          pr["excess"], pr["slope"], pr["teq"], st["theta"], st["has"],
                          pr["period"], b["t_int"], B, b["T_ref"], b["bias_current"], pr["n"],
                          b["runaway_temperature"], keys, v, m, status, iters,
                          _rng.ZIG_X, _rng.ZIG_F)
    st.update(T_prev=float(T_s[-1]), has=True)
    return {"v_bolo": v, "dT": m, "status": status, "iters": iters}


def _nominal_periodic(ctx: RunContext, q: np.ndarray, T_s: np.ndarray) -> np.ndarray:
    """Voltage of a nominal pixel in the periodic state, for the powers q (N,) W at the
    substrate temperatures T_s (N,) K."""
    b = ctx.cfg["bolometer"]
    nominal = {k: np.full((1, 1), float(b[k])) for k in ("R_ref", "g", "C")}
    period = frame_period(ctx.cfg)
    x = (period - b["t_int"]) * nominal["g"] / nominal["C"]
    zero = np.zeros((1, 1), np.float32)
    pr = {"n": choose_steps(ctx.cfg, float(np.median(q)), float(np.median(T_s))),
          "omd": -np.expm1(-x), "excess": zero, "slope": zero, "teq": zero}
    return _periodic(ctx, q.reshape(-1, 1, 1), nominal, pr, T_s)["v_bolo"][:, 0, 0]


def stage_bolometer_lagged(ctx: RunContext, inp: dict) -> dict:
    """The steady pulse with thermal memory between frames: the rise before the pulse
    follows its equilibrium Q/g through exp(-period g/C) per frame (equilibrium variant)."""
    Q = np.ascontiguousarray(inp["Q"])
    n = Q.shape[0]
    p = inp["params"]
    st = ctx.state.get("lagged")
    if st is None:
        assert ctx.frame_period is not None
        decay = np.exp(-ctx.frame_period * p["g"] / p["C"])
        st = {"decay": decay, "theta": np.zeros(p["g"].shape), "T_prev": 0.0, "has": False}
        ctx.state["lagged"] = st
    T_s = ctx.substrate(n)
    theta = np.empty(Q.shape)
    with threads_for(Q.size):
        _kw.lagged_rise(Q, p["g"], st["decay"], T_s, st["T_prev"], st["theta"], st["has"],
                        theta)
    st.update(theta=theta[-1].copy(), T_prev=float(T_s[-1]), has=True)
    return _solve_predicted(ctx, inp, None, theta)


def stage_bolometer_transient(ctx: RunContext, inp: dict) -> dict:
    """The time-domain model (:func:`model.transient.integrate_pixels`), its state carried
    from chunk to chunk: the same bits as one run over the whole sequence."""
    from irnuc.model import transient as _tr

    b = ctx.cfg["bolometer"]
    p = inp["params"]
    Q = np.ascontiguousarray(inp["Q"])
    n = Q.shape[0]
    T_s = ctx.substrate(n)
    st = ctx.state.get("transient")
    settings = ctx.transient
    theta0 = before = None
    if st is not None:
        settings = _replace_warmup(settings)
        theta0, before = st["theta"], st["T_prev"]
    res = _tr.integrate_pixels(Q, T_s, p["R_ref"], p["g"], p["C"], tcr=b["tcr"],
                               T_ref=b["T_ref"], bias_current=b["bias_current"],
                               t_int=b["t_int"], runaway_temperature=b["runaway_temperature"],
                               settings=settings, theta0=theta0, T_s_before=before)
    status = res.status
    if st is not None and st["failed"].any():
        status[:, st["failed"]] = st["status"][st["failed"]]
    s = _tr.TransientSettings.from_any(settings)
    after = s.frame_period - s.pulse_start - b["t_int"]
    prev = T_s[-2] if n > 1 else (T_s[0] if before is None else before)
    rate = float(T_s[-1] - prev) / s.frame_period
    last = status[-1] != _kb.STATUS_OK
    relaxed = np.empty(p["g"].size)
    end = np.ascontiguousarray(res.dT_end[-1]).ravel() - 0.5 * rate * b["t_int"]
    with threads_for(relaxed.size):
        _kw.relax_after_pulse(end, Q[-1].ravel(), p["g"].ravel(), p["C"].ravel(), after, rate,
                              last.ravel(), relaxed)
    ctx.state["transient"] = {"theta": relaxed.reshape(p["g"].shape), "T_prev": float(T_s[-1]),
                              "failed": last, "status": status[-1].copy()}
    ctx.counts["transient_pulses"] += int(status.size)
    return {"v_bolo": res.v_bolo, "dT": res.dT_mean, "status": status, "iters": res.substeps}


def _replace_warmup(settings: Any) -> Any:
    """Settings of the chunks after the first: no warm-up frames (the state is carried)."""
    from dataclasses import replace

    return replace(settings, warmup_frames=0)


def make_skim_stage(mode: str) -> Stage:
    fn = _readout.SKIMMING_MODES[mode]
    if mode == "none":
        def run_fixed(ctx: RunContext, inp: dict) -> dict:
            return {"v_ref": fn(inp["v_sense"], inp["status"], ctx.layout, inp["v_skim"])}

        return Stage("skimming_none", ("v_sense", "status", "v_skim"), ("v_ref",), True,
                     run_fixed)

    # Row/column skimming needs the nominal reference voltage (a solve) only as the
    # fallback of a row or column whose blind pixels all failed: asked for on demand.
    def run(ctx: RunContext, inp: dict) -> dict:
        assert ctx.demand is not None
        demand = ctx.demand
        return {"v_ref": fn(inp["v_sense"], inp["status"], ctx.layout,
                            lambda: demand("v_skim"))}

    return Stage(f"skimming_{mode}", ("v_sense", "status"), ("v_ref",), True, run)


def stage_integrator(ctx: RunContext, inp: dict) -> dict:
    r = ctx.cfg["readout"]
    act = (slice(None), *ctx.layout.active_slice)
    v_bolo = inp["v_sense"]
    v = np.empty((v_bolo.shape[0], *ctx.layout.active_shape))
    rs, cs = ctx.layout.active_slice
    with threads_for(v.size):
        _ks.integrate_frames(v_bolo, rs.start, cs.start, inp["v_ref"], r["gain"], r["v_reset"], v)
    apply_voltage_defects_at(v, inp["defect_index"], r["v_low"], r["v_high"], r["v_reset"])
    failed = (inp["status"][act] != _kb.STATUS_OK) if np.count_nonzero(inp["status"]) else None
    if failed is not None and failed.any():
        # A runaway or unsolved pixel drives its integrator into the high rail; it is
        # counted in Frames.diagnostics, never passed on as NaN.
        v[failed] = r["v_high"]
    return {"v_int": v}


def stage_defect_index(ctx: RunContext, inp: dict) -> dict:
    """What the per-frame stages need of the defects, found once per sensor: the output
    defects' pixels (:func:`model.defects.voltage_defect_index`) and the responsivity
    factor over the active area (None when no pixel has one)."""
    d: DefectMap = inp["defects"]
    return {"defect_index": voltage_defect_index(d),
            "defect_resp": d.resp if (d.resp != 1.0).any() else None}


def stage_noisy_pixels(ctx: RunContext, inp: dict) -> dict:
    """Extra noise of NOISY defect pixels, V (None without any): fixed per sensor."""
    r = ctx.cfg["readout"]
    sigma = noisy_sigma(inp["defects"], r["v_low"], r["v_high"])
    if sigma is None:
        return {"noisy_sigma": None}
    idx = np.flatnonzero(sigma)
    return {"noisy_sigma": (sigma, idx, sigma.reshape(-1)[idx])}


def bolometer_noise_on(cfg: Mapping[str, Any]) -> bool:
    """True if the bolometers' own noise (Johnson, 1/f) is drawn."""
    n = cfg["noise"]
    return bool(n["enabled"] and (n["johnson"] or n["flicker_coefficient"] > 0.0))


def stage_bolometer_noise(ctx: RunContext, inp: dict) -> dict:
    """The bolometers' own noise on the voltage of every pixel of the array (the skimming
    references included, so a row or column shares its reference's noise): Johnson and
    the 1/f octaves above the frame rate white, the octaves below from a Voss generator
    (:mod:`model.noise`)."""
    cfg = ctx.cfg
    nz, b = cfg["noise"], cfg["bolometer"]
    v = np.ascontiguousarray(inp["v_bolo"])
    n = v.shape[0]
    shape = ctx.layout.shape
    white, slow = _noise.flicker_variances(nz["flicker_coefficient"], frame_period(cfg),
                                           b["t_int"])
    if slow > 0.0:
        st = ctx.state.get("bolometer_flicker")
        if st is None:
            st = ctx.state["bolometer_flicker"] = _noise.VossState(shape, _noise.FLICKER_STREAM)
        octave, kf = st.plan(ctx.seed, ctx.first_frame, n)
        vals, total = st.arrays()
    else:
        octave, kf = np.full(n, -1, np.int64), np.zeros(n, np.uint64)
        vals, total = np.empty((0, 1, 1)), np.empty((1, 1))
    out = np.empty(v.shape)
    ctx.counts["bolometer_noise_frames"] += n
    with threads_for(v.size):
        _ks.bolometer_noise(v, inp["dT"], inp["status"], ctx.substrate(n), b["bias_current"],
                            b["t_int"], bool(nz["johnson"]), white, math.sqrt(slow),
                            _noise.keys(ctx.seed, ctx.first_frame, n, _noise.BOLOMETER_STREAM),
                            kf, octave, vals, total, _rng.ZIG_X, _rng.ZIG_F, out)
    return {"v_sense": out}


def stage_noise(ctx: RunContext, inp: dict) -> dict:
    """Noise at the integrator output of the active pixels: the readout's (white and its
    1/f, ``noise.readout_sigma``, ``noise.flicker_sigma``) and NOISY defect pixels'."""
    cfg = ctx.cfg
    n = cfg["noise"]
    noisy = inp["noisy_sigma"]
    extra = noisy[0] if noisy is not None else None
    if not n["enabled"] or (n["readout_sigma"] == 0.0 and n["flicker_sigma"] == 0.0):
        if noisy is None:
            return {"v_out": inp["v_int"]}
        ctx.counts["noise_frames"] += inp["v_int"].shape[0]
        # v_int is this chunk's own array, used by nothing else: add in place.
        return {"v_out": _noise.add_noise_at(inp["v_int"], noisy[1], noisy[2], ctx.seed,
                                             ctx.first_frame, copy=False)}
    sigma2: np.ndarray | float = n["readout_sigma"] ** 2
    if extra is not None:
        sigma2 = sigma2 + extra**2
    flicker = n["flicker_sigma"]
    if flicker > 0.0 and ctx.flicker is None:
        ctx.flicker = _noise.VossState(ctx.layout.active_shape, _noise.READOUT_FLICKER_STREAM)
    ctx.counts["noise_frames"] += inp["v_int"].shape[0]
    return {"v_out": _noise.add_noise(inp["v_int"], np.sqrt(sigma2), ctx.seed, ctx.first_frame,
                                      flicker, ctx.flicker)}


def stage_adc(ctx: RunContext, inp: dict) -> dict:
    r, a = ctx.cfg["readout"], ctx.cfg["adc"]
    return {"codes": _adc.adc_convert(inp["v_out"], a["bits"], a["v_low"], a["v_high"],
                                      a["rounding"], rails=(r["v_low"], r["v_high"]))}


def noise_configured(cfg: Mapping[str, Any]) -> bool:
    """True if some noise source at the integrator output is non-zero (the readout's, or a
    NOISY defect's): noise enabled with every sigma 0 adds exactly nothing there, so it gets
    no stage and draws nothing."""
    n = cfg["noise"]
    if n["enabled"] and (n["readout_sigma"] > 0 or n["flicker_sigma"] > 0):
        return True
    spec = _defect_spec(cfg)
    kinds = set(spec.cluster_kinds) | {spec.line_kind} if (spec.clusters or spec.rows or spec.cols) else set()
    kinds |= {k for k, rate in spec.rates.items() if rate > 0}
    kinds |= {str(p.get("kind")) for p in spec.listed}
    return DefectKind.NOISY.name.lower() in {str(k).lower() for k in kinds}


def _temporal_noise(cfg: Mapping[str, Any]) -> bool:
    """True if the array's own temporal noise (not a NOISY defect's) is non-zero."""
    n = cfg["noise"]
    return bool(n["enabled"] and (n["johnson"] or n["readout_sigma"] > 0
                                  or n["flicker_sigma"] > 0 or n["flicker_coefficient"] > 0
                                  or thermal_noise_on(cfg)))


# ---- reference (shielded) pixels read out beside the image ------------------------------

def stage_reference_layout(ctx: RunContext, _: dict) -> dict:
    """Full-array (row, col) of the pixels ``readout.reference_pixels`` names, row-major."""
    mode = ctx.cfg["readout"]["reference_pixels"]
    kind = ctx.layout.kind_map()
    if mode == "none":
        mask = np.zeros(kind.shape, bool)
    else:
        mask = kind == (BOUNDARY if mode == "boundary" else BLIND)
    return {"reference_positions": np.argwhere(mask).astype(np.int32).reshape(-1, 2)}


def stage_reference_pixels(ctx: RunContext, inp: dict) -> dict:
    """ADC codes of the reference pixels, (N, K): each read like an active pixel through
    the integrator against its own row's (column's) skimming reference, with its own
    bolometer noise (in ``v_sense``), the readout's white noise (drawn from a stream of its
    own, so the image's bits do not depend on it) and the ADC. Pixels whose solve failed
    read the high rail."""
    cfg = ctx.cfg
    r, a, nz = cfg["readout"], cfg["adc"], cfg["noise"]
    pos = inp["reference_positions"]
    v_bolo, status = inp["v_sense"], inp["status"]
    n = v_bolo.shape[0]
    if pos.shape[0] == 0:
        return {"blind_codes": np.empty((n, 0), _adc.adc_dtype(a["bits"]))}
    rows, cols = pos[:, 0], pos[:, 1]
    mode = r["skimming"]
    lines = rows if mode == "row" else cols
    uniq, where = np.unique(lines, return_inverse=True)

    def fallback() -> Any:
        assert ctx.demand is not None
        return ctx.demand("v_skim")

    ref = _readout.line_reference(v_bolo, status, ctx.layout, mode, uniq,
                                  fallback)[:, where.reshape(-1)]
    vp = v_bolo[:, rows, cols]
    v = _readout.integrate(vp, ref, r["gain"], r["v_reset"])
    failed = status[:, rows, cols] != _kb.STATUS_OK
    if failed.any():
        v[failed] = r["v_high"]
    if nz["enabled"] and nz["readout_sigma"] > 0:
        for k in range(n):
            v[k] += nz["readout_sigma"] * _noise.normals(ctx.seed, ctx.first_frame + k,
                                                         _noise.REFERENCE_STREAM, v.shape[1:])
    codes = _adc.adc_convert(v, a["bits"], a["v_low"], a["v_high"], a["rounding"],
                             rails=(r["v_low"], r["v_high"]))
    return {"blind_codes": codes}


def env_input(fn: Callable[[RunContext, dict], dict], key: str
               ) -> Callable[[RunContext, dict], dict]:
    """``fn`` reading the housing and substrate radiance from ``key`` as ``L_env``."""
    if key == "L_env":
        return fn
    return lambda ctx, inp: fn(ctx, {**inp, "L_env": inp[key]} if key in inp else inp)
