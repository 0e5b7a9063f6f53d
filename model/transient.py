"""Transient (time-domain) bolometer model: the heat balance of paper eq. 14 in time.

Per pixel, over the whole array (active, boundary and blind pixels),

    C dT/dt = I(t)^2 R(T) + Q - g (T - T_s)

where I(t) is the bias current during the pulse (the integration window) and 0 otherwise,
Q = eps (P_scene + P_housing) (- the linearised emission with ``net_radiation``) is the
absorbed power of the frame from the steady pipeline's own stages, and the substrate
temperature T_s may change from frame to frame. Each frame: the scene (and T_s) steps at
the frame start, the bias pulse runs from ``pulse_start`` for ``t_int``, the pixel relaxes
until the next frame. The output of a frame is the bolometer voltage averaged over the
pulse (what the integrator integrates), then the steady pipeline's skimming, integrator,
noise and ADC stages make the codes. This is the temporal simulation the paper lists as
future work; the steady model's self-heating factor is its constant-R approximation.

Integrators are chosen by name from :data:`INTEGRATORS`; see :mod:`model.core.transient`
and ``docs/transient.md``.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np

from irnuc.model import graph as _graph
from irnuc.model import pipeline as _pl
from irnuc.model.config import apply_overrides
from irnuc.model.core import bolometer as _kb
from irnuc.model.core import transient as _kt
from irnuc.model.scenes import Scene, check_temps
from irnuc.model.validate import (
    ConfigError,
    check_array,
    check_choice,
    check_frame_period,
    check_int,
    check_scalar,
)

#: Integrators by name (codes of :mod:`model.core.transient`).
INTEGRATORS: dict[str, int] = {
    "rk4": _kt.M_RK4,
    "backward_euler": _kt.M_BACKWARD_EULER,
    "trapezoidal": _kt.M_TRAPEZOIDAL,
    "exponential": _kt.M_EXPONENTIAL,
    "auto": _kt.M_AUTO,
}
#: Integrator names by code (``auto`` reports the one that finished each pulse;
#: ``quasi_static``: ``auto`` or ``exponential`` took the pulse in the tau -> 0 limit).
INTEGRATOR_NAMES: dict[int, str] = {**{v: k for k, v in INTEGRATORS.items()},
                                    _kt.M_QUASI_STATIC: "quasi_static"}
#: Order of accuracy of each integrator (for documentation and convergence tests).
INTEGRATOR_ORDER: dict[str, int] = {"rk4": 4, "backward_euler": 1, "trapezoidal": 2,
                                    "exponential": 3}
#: Defaults, chosen from the work-precision study (``irnuc precision``, docs/transient.md):
#: ``auto`` is adaptive RK4 on non-stiff pixels (the cheapest at 1e-10-level accuracy) and
#: the exponential integrator on stiff ones (exact on the linear part, no stability limit).
DEFAULT_INTEGRATOR = "auto"
DEFAULT_STEPS = 4
DEFAULT_RTOL = 1e-9
#: Initial state of the first frame: in equilibrium with its scene without bias, or at the
#: substrate temperature.
INITIAL_STATES = ("equilibrium", "substrate")
EXPLICIT_POLICIES = ("limit", "refuse")

STATUS_STEP_LIMIT = _kt.STATUS_STEP_LIMIT

#: Extra outputs of :func:`simulate_transient` besides :data:`model.pipeline.OUTPUTS`.
TRANSIENT_OUTPUTS: dict[str, str] = {
    **_pl.OUTPUTS,
    "pulse_end_rise": "dT_end",   # (N, rows, cols) T - T_s at the end of the pulse, K
    "substeps": "substeps",       # (N, rows, cols) integrator substeps per pulse
}


class StiffnessError(ConfigError):
    """The explicit integrator would need more steps than allowed: it refuses to run."""


@dataclass(frozen=True)
class TransientSettings:
    """Time-domain settings of :func:`simulate_transient`.

    Attributes
    ----------
    integrator : str
        Key of :data:`INTEGRATORS`; ``auto`` (default) picks RK4 or the exponential method
        per pixel and pulse from the local stiffness.
    steps : int
        Steps per bias pulse, 1..1e6 (substeps are added where stability or Newton needs them).
    frame_period : float
        Time from one frame start to the next, s, >= pulse_start + t_int.
    pulse_start : float
        Start of the bias pulse after the frame start (and the scene step), s, >= 0.
    initial : str
        ``equilibrium``: the first frame starts in equilibrium with its scene, no bias;
        ``substrate``: it starts at the substrate temperature.
    warmup_frames : int
        Copies of the first frame run before the recorded ones (to reach the periodic state).
    rtol : float or None
        None: fixed steps. A number in [1e-14, 0.1]: adaptive steps by step doubling, the
        local error held below rtol (``steps`` then sets only the first step).
    max_substeps : int
        Substep budget per pulse and pixel (every attempted step counts).
    explicit_policy : str
        ``limit``: RK4 splits steps to stay stable (refusing past ``max_substeps``);
        ``refuse``: RK4 refuses any step beyond its stability limit.
    """

    integrator: str = DEFAULT_INTEGRATOR
    steps: int = DEFAULT_STEPS
    frame_period: float = 1.0 / 30.0
    pulse_start: float = 0.0
    initial: str = "equilibrium"
    warmup_frames: int = 0
    rtol: float | None = DEFAULT_RTOL
    max_substeps: int = 200_000
    explicit_policy: str = "limit"

    def checked(self, t_int: float) -> TransientSettings:
        """Validated copy; ``t_int`` (s) is the pulse length it must fit around."""
        p = "transient."
        check_choice(p + "integrator", self.integrator, INTEGRATORS)
        check_int(p + "steps", self.steps, 1, 1_000_000)
        fp = check_scalar(p + "frame_period", self.frame_period, 0.0, 1e3, lo_open=True,
                          unit="s")
        ps = check_scalar(p + "pulse_start", self.pulse_start, 0.0, 1e3, unit="s")
        check_frame_period(fp, t_int, ps, what=f"transient.frame_period = {fp:g} s")
        check_choice(p + "initial", self.initial, INITIAL_STATES)
        check_int(p + "warmup_frames", self.warmup_frames, 0, 100_000)
        if self.rtol is not None:
            check_scalar(p + "rtol", self.rtol, 1e-14, 0.1)
        check_int(p + "max_substeps", self.max_substeps, 1, 100_000_000)
        check_choice(p + "explicit_policy", self.explicit_policy, EXPLICIT_POLICIES)
        return replace(self, frame_period=min(fp, 1e3), pulse_start=ps)

    @classmethod
    def from_any(cls, value: TransientSettings | Mapping[str, Any] | None) -> TransientSettings:
        if value is None:
            return cls()
        if isinstance(value, TransientSettings):
            return value
        if not isinstance(value, Mapping):
            raise ConfigError(f"transient settings = {value!r} must be a table")
        known = set(cls.__dataclass_fields__)
        unknown = set(value) - known
        if unknown:
            raise ConfigError(f"transient: unknown field(s) {sorted(unknown)}; known {sorted(known)}")
        return cls(**value)


@dataclass
class TransientResult:
    """Per frame and pixel results of :func:`integrate_pixels` (all shaped (N, *shape)).

    Attributes
    ----------
    v_bolo : ndarray
        Bolometer voltage I R(T) averaged over the pulse, V.
    dT_mean : ndarray
        T - T_s averaged over the pulse, K.
    dT_end : ndarray
        T - T_s at the end of the pulse, K.
    status : ndarray
        uint8 codes of :mod:`model.core.bolometer` (0 ok, 1 no convergence, 2 runaway,
        3 invalid); failed pixels hold their last finite values.
    substeps : ndarray
        Integrator substeps used in the pulse.
    method : ndarray or None
        uint8 code (:data:`INTEGRATORS`) of the integrator that finished each pulse.
    """

    v_bolo: np.ndarray
    dT_mean: np.ndarray
    dT_end: np.ndarray
    status: np.ndarray
    substeps: np.ndarray
    method: np.ndarray | None = None

    def integrators_used(self) -> dict[str, int]:
        """Pixel pulses finished by each integrator (``auto`` splits into two)."""
        if self.method is None:
            return {}
        codes, counts = np.unique(self.method, return_counts=True)
        return {INTEGRATOR_NAMES[int(c)]: int(k) for c, k in zip(codes, counts, strict=True)}


def _as_pixels(name: str, value: Any, shape: tuple[int, ...], unit: str) -> np.ndarray:
    arr = check_array(name, value, 0.0, None, lo_open=True, unit=unit)
    try:
        return np.ascontiguousarray(np.broadcast_to(arr, shape), dtype=np.float64).ravel()
    except ValueError:
        raise ConfigError(f"{name} has shape {arr.shape}; the pixel array is {shape}") from None


def integrate_pixels(
    Q: np.ndarray,
    T_s: float | np.ndarray,
    R_ref: float | np.ndarray,
    g: float | np.ndarray,
    C: float | np.ndarray,
    *,
    tcr: float,
    T_ref: float,
    bias_current: float,
    t_int: float,
    runaway_temperature: float = 1000.0,
    settings: TransientSettings | Mapping[str, Any] | None = None,
    theta0: float | np.ndarray | None = None,
    T_s_before: float | None = None,
) -> TransientResult:
    """Integrate the heat balance of every pixel through a sequence of frames.

    Parameters
    ----------
    Q : array_like, (N, *shape)
        Absorbed power of each frame and pixel, W, finite.
    T_s : float or array_like (N,)
        Substrate temperature of each frame, K, > 0.
    R_ref, g, C : float or array_like broadcastable to shape
        Resistance at T_ref (ohm), thermal conductance (W/K), heat capacity (J/K), > 0.
    tcr : float
        Temperature coefficient of resistance at T_ref, 1/K, in [-1, 1].
    T_ref : float
        Reference temperature of R_ref, K, > 0.
    bias_current : float
        Current during the pulse, A, in [0, 1].
    t_int : float
        Pulse (integration) length, s, in (0, 10].
    runaway_temperature : float
        A pixel hotter than this (K) is a thermal runaway.
    settings : TransientSettings or dict, optional
    theta0 : float or array_like, optional
        T - T_s at the start of the first frame, K; default from ``settings.initial``.
    T_s_before : float, optional
        Substrate temperature at the start of the first frame, K (default T_s[0]): frame n's
        substrate goes linearly from the previous frame's value to its own (a continued
        run gives the last frame's).

    Returns
    -------
    TransientResult

    Raises
    ------
    ConfigError
        On a bad argument, before any work.
    StiffnessError
        If the explicit integrator would need more steps than allowed.
    """
    Qa = np.asarray(Q, dtype=np.float64)
    if Qa.ndim < 1 or Qa.shape[0] < 1:
        raise ConfigError(f"Q must have shape (N, ...) with N >= 1 frames, got {Qa.shape}")
    if not np.isfinite(Qa).all():
        raise ConfigError("Q (absorbed power, W) holds non-finite values; allowed: finite")
    n = Qa.shape[0]
    shape = Qa.shape[1:]
    npix = int(np.prod(shape)) if shape else 1
    tcr = check_scalar("bolometer.tcr", tcr, -1.0, 1.0, unit="1/K")
    T_ref = check_scalar("bolometer.T_ref", T_ref, 0.0, None, lo_open=True, unit="K")
    I = check_scalar("bolometer.bias_current", bias_current, 0.0, 1.0, unit="A")
    t_int = check_scalar("bolometer.t_int", t_int, 0.0, 10.0, lo_open=True, unit="s")
    T_max = check_scalar("bolometer.runaway_temperature", runaway_temperature, 0.0, None,
                         lo_open=True, unit="K")
    s = TransientSettings.from_any(settings).checked(t_int)
    Ts = check_array("environment.T_substrate", T_s, 0.0, None, lo_open=True, unit="K")
    Ts = np.ascontiguousarray(np.broadcast_to(Ts, (n,)) if Ts.ndim == 0 else Ts,
                              dtype=np.float64)
    if Ts.shape != (n,):
        raise ConfigError(f"environment.T_substrate has shape {Ts.shape}; expected ({n},)")
    Rr = _as_pixels("bolometer.R_ref", R_ref, shape, "ohm")
    gg = _as_pixels("bolometer.g", g, shape, "W/K")
    CC = _as_pixels("bolometer.C", C, shape, "J/K")
    Qf = np.ascontiguousarray(Qa.reshape(n, npix))
    if theta0 is None:
        th0 = Qf[0] / gg if s.initial == "equilibrium" else np.zeros(npix)
    else:
        th0 = np.ascontiguousarray(np.broadcast_to(
            check_array("theta0", theta0, unit="K"), shape), dtype=np.float64).ravel()
    before = float(Ts[0]) if T_s_before is None else check_scalar(
        "T_s_before", T_s_before, 0.0, None, lo_open=True, unit="K")
    cold = ~(before + th0 > 0.0)
    if cold.any():
        if theta0 is not None:
            raise ConfigError("theta0: the initial pixel temperature T_s + theta0 must be > 0 K")
        k = int(np.argmax(cold))
        raise ConfigError(
            f"transient.initial = 'equilibrium': the unbiased equilibrium T_s + Q/g of "
            f"{int(cold.sum())} pixel(s) is at or below 0 K (first: Q = {Qf[0, k]:.3g} W, "
            f"bolometer.g = {gg[k]:.3g} W/K: the pixel emits more than it absorbs and g "
            "cannot hold it); use transient.initial = 'substrate' or a larger bolometer.g")
    B = _kb.activation_temperature(tcr, T_ref)
    method = INTEGRATORS[s.integrator]
    refuse = s.explicit_policy == "refuse"
    if method == _kt.M_RK4:
        _precheck_rk4(th0, Ts[0], Qf[0], I, Rr, B, T_ref, gg, CC, t_int, s)
    v, dm, de, st, sub, used = _kt.empty_outputs((n, npix))
    _kt.integrate_frames(Qf, Ts, Rr, gg, CC, np.ascontiguousarray(th0), B, T_ref, I, t_int,
                         s.frame_period, s.pulse_start, s.warmup_frames, method, s.steps,
                         s.max_substeps, T_max, refuse,
                         float(s.rtol) if s.rtol is not None else 0.0, v, dm, de, st, sub,
                         used, before)
    bad = st == STATUS_STEP_LIMIT
    if bad.any():
        f, p = (int(i) for i in np.argwhere(bad)[0])
        lam = (gg[p] + I * I * abs(B) * Rr[p] / Ts[f] ** 2) / CC[p]
        raise StiffnessError(_stiff_message(s, t_int, lam, int(bad.sum()),
                                            (f, *np.unravel_index(p, shape))))
    full = (n, *shape)
    return TransientResult(v.reshape(full), dm.reshape(full), de.reshape(full),
                           st.reshape(full), sub.reshape(full), used.reshape(full))


def _stiff_message(s: TransientSettings, t_int: float, lam: float, count: int,
                   where: tuple[int, ...]) -> str:
    need = t_int * lam / _kt.RK4_STABILITY
    if s.explicit_policy == "refuse":
        limit = f"transient.steps = {s.steps} (explicit_policy = 'refuse')"
    else:
        limit = f"transient.max_substeps = {s.max_substeps}"
    return (f"transient.integrator = 'rk4' refuses: {count} pixel pulse(s) would need about "
            f"{need:.3g} steps (t_int |lambda| / {_kt.RK4_STABILITY}, |lambda| = {lam:.3g} 1/s, "
            f"tau = {1 / lam:.3g} s, first at frame/pixel {where}) to stay stable, more than "
            f"{limit}; use transient.integrator = 'auto' (the default: RK4 where it is cheapest, "
            "the exponential integrator on stiff pixels) or 'exponential'")


def _precheck_rk4(th0, Ts0, Q0, I, R, B, T_ref, g, C, t_int, s) -> None:
    """Refuse before any work when RK4 clearly needs too many steps at the initial state."""
    T = Ts0 + th0
    dR = -B * R * np.exp(B * (1.0 / T - 1.0 / T_ref)) / (T * T)
    lam = np.abs((I * I * dR - g) / C)
    need = t_int * lam / _kt.RK4_STABILITY
    limit = s.steps if s.explicit_policy == "refuse" else s.max_substeps
    worst = int(np.argmax(need))
    if need[worst] > limit:
        raise StiffnessError(_stiff_message(s, t_int, float(lam[worst]),
                                            int((need > limit).sum()), (0, worst)))


# ---- frames ----------------------------------------------------------------------------

def absorbed_power(cfg: Mapping[str, Any], temps: np.ndarray, scene: Scene, seed: int,
                   substrate: np.ndarray, pipes: dict[float, _pl.Pipeline] | None = None
                   ) -> tuple[np.ndarray, dict[str, Any]]:
    """Absorbed power Q (N, rows, cols) W by the steady pipeline's stages, per substrate
    temperature (the emission and blind-pixel terms depend on it).

    ``pipes`` (optional) collects the configured sensor of each substrate temperature (K),
    so a caller can reuse their static products and stage counts.
    Returns Q and the static products (params, defects) of the first T_s.
    """
    n = temps.shape[0]
    Q: np.ndarray | None = None
    static: dict[str, Any] = {}
    pipes = {} if pipes is None else pipes
    for value in np.unique(substrate):
        idx = np.flatnonzero(substrate == value)
        pipe = pipes.get(float(value))
        if pipe is None:  # the Pipeline validates the configuration
            c = apply_overrides(cfg, {"environment.T_substrate": float(value)})
            pipe = pipes[float(value)] = _pl.Pipeline(c, seed)
        got = pipe.run(temps[idx], ["Q"] if static else ["Q", "params", "defects"], scene)
        if Q is None:
            Q = np.empty((n, *got["Q"].shape[1:]))
        Q[idx] = got["Q"]
        if not static:
            static = {"params": got["params"], "defects": got["defects"]}
    assert Q is not None
    return Q, static


def simulate_transient(
    cfg: Mapping[str, Any],
    temps: Sequence[float] | np.ndarray,
    scene: str | Scene = "uniform",
    *,
    seed: int = 0,
    substrate: float | Sequence[float] | np.ndarray | None = None,
    settings: TransientSettings | Mapping[str, Any] | None = None,
    outputs: Sequence[str] = ("codes",),
    scene_params: Mapping[str, Any] | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> _pl.Frames:
    """A sequence of sensor frames from the time-domain model.

    Parameters
    ----------
    cfg : dict
        A validated configuration; ``bolometer.variant`` (a steady-model option) is not used.
    temps : sequence of float
        Scene base temperature of each frame in time order, K (> 0).
    scene : str or Scene
        As :func:`model.simulate`.
    seed : int
        Seed of every random draw; same inputs and seed give the same bits.
    substrate : float or sequence of float, optional
        Substrate temperature of each frame, K (> 0); default ``environment.T_substrate``.
    settings : TransientSettings or dict, optional
        Integrator and timing (:class:`TransientSettings`).
    outputs : sequence of str
        Keys of :data:`TRANSIENT_OUTPUTS`.
    scene_params : dict, optional
    progress : callable, optional
        ``progress(done, total)`` after the integration and after the readout.

    Returns
    -------
    model.pipeline.Frames
        Like the steady model's; ``diagnostics["transient"]`` adds the settings, the pixel
        pulses finished by each integrator (``integrators_used``), the substeps used and the
        stiffness (t_int / tau) range, and the solver-failure counts include the runaway
        pixels. ``counts`` holds the stage executions of every configured sensor used
        (one per substrate temperature) plus ``transient`` (integration runs) and
        ``transient_pulses`` (pixel pulses integrated).
    """
    if isinstance(scene, str):
        scene = Scene(scene, dict(scene_params or {}))
    t = check_temps(temps)
    seed = check_int("seed", seed, 0, 2**63 - 1)
    unknown = [o for o in outputs if o not in TRANSIENT_OUTPUTS]
    if unknown:
        raise ConfigError(f"outputs: unknown name(s) {unknown}; known {sorted(TRANSIENT_OUTPUTS)}")
    b = cfg["bolometer"]
    s = TransientSettings.from_any(settings).checked(b["t_int"])
    if substrate is None:
        Ts = np.full(t.shape, float(cfg["environment"]["T_substrate"]))
    else:
        Ts = check_array("substrate", substrate, 0.0, 1e5, lo_open=True, unit="K")
        Ts = np.broadcast_to(Ts, t.shape).copy() if Ts.ndim == 0 else Ts
        if Ts.shape != t.shape:
            raise ConfigError(f"substrate has {Ts.size} value(s); give one per frame ({t.size})")
    # One configured sensor per substrate temperature; the one at the configured T_s also
    # does the readout, so its static products (housing radiance, skim voltage) are shared.
    T_cfg = float(cfg["environment"]["T_substrate"])
    pipes: dict[float, _pl.Pipeline] = {T_cfg: _pl.Pipeline(cfg, seed)}
    Q, static = absorbed_power(cfg, t, scene, seed, Ts, pipes)
    p = static["params"]
    res = integrate_pixels(Q, Ts, p["R_ref"], p["g"], p["C"], tcr=b["tcr"], T_ref=b["T_ref"],
                           bias_current=b["bias_current"], t_int=b["t_int"],
                           runaway_temperature=b["runaway_temperature"], settings=s)
    if progress is not None:
        progress(1, 2)
    pipe = pipes[T_cfg]
    pipe.counts["transient"] += 1
    pipe.counts["transient_pulses"] += int(res.status.size)
    ctx = _graph.RunContext(cfg, pipe.layout, scene, seed, temps=t, first_frame=0,
                         counts=pipe.counts)
    values: dict[str, Any] = {**pipe._static, **static, "Q": Q, "v_bolo": res.v_bolo,
                              "dT": res.dT_mean, "status": res.status, "iters": res.substeps,
                              "dT_end": res.dT_end, "substeps": res.substeps}
    products = [TRANSIENT_OUTPUTS[o] for o in outputs]
    _graph.run_planned(pipe.stages, ctx, values, products)
    if progress is not None:
        progress(2, 2)
    diagnostics = _pl._diagnostics(pipe, values)
    tau = p["C"] / p["g"]
    diagnostics["transient"] = {
        **{k: v for k, v in asdict(s).items()},
        "integrators_used": res.integrators_used(),
        "substeps": {"min": int(res.substeps.min()), "max": int(res.substeps.max()),
                     "mean": float(res.substeps.mean())},
        "pulse_over_tau": {"min": float(b["t_int"] / tau.max()),
                           "max": float(b["t_int"] / tau.min())},
        "runaway_pixels": int((res.status == _kb.STATUS_RUNAWAY).any(axis=0).sum()),
    }
    counts: Counter = Counter()
    for q in pipes.values():
        counts.update(q.counts)
    defects = static["defects"]
    return _pl.Frames(
        codes=values.get("codes"),
        temps=t,
        defect_kind=defects.kind,
        defect_pattern=defects.pattern,
        adc_bits=cfg["adc"]["bits"],
        config=dict(cfg),
        seed=seed,
        scene=scene,
        outputs={o: values[TRANSIENT_OUTPUTS[o]] for o in outputs},
        diagnostics=diagnostics,
        counts=dict(counts),
    )

