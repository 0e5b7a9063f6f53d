"""Noise in the camera team's units: responsivity, temporal NETD and 3D noise.

* :func:`responsivity`: output codes per kelvin of scene, per pixel, in closed form: the
  small-signal derivative of the model's chain at an operating point,

      dcode/dT_scene = (2^bits / (v_high - v_low)) gain I R B / T^2 / (1 + D)
                       * f_Q / g * k_scene dL/dT(T_scene),     D = b R B / T^2

  (the integrator inverts, a hotter scene lowers R for B > 0; the code rises). dL/dT is the
  in-band derivative of Planck's law by quadrature (scipy), independent of the radiance
  series. :func:`responsivity_frames` gives the array's mean per frame of a sequence.
* :func:`netd`: temporal NETD from the noise model in closed form: the white temporal noise
  of each pixel at the integrator (Johnson sqrt(4 k T R / (2 t_int)) gain, readout, the
  stationary 1/f variance, a NOISY defect's) in codes, plus the ADC's quantization
  LSB^2/12, over the responsivity: NETD = sqrt(<sigma^2>) / <responsivity> over the
  defect-free pixels.
* :func:`measured_netd`: the same from frames: per pixel, the codes fitted against the
  frame's scene, FPA and housing temperatures (linear, quadratic in what varies); the
  residual's variance is the temporal noise, the scene coefficient the responsivity; both
  with their standard errors.
* :func:`noise_3d`: the NVESD 3D-noise decomposition of a (T, V, H) data cube by the
  random-effects analysis of variance (expected mean squares), which removes the bias of the
  plain directional averages; every component with its standard error.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from irnuc.model import pipeline as _pl
from irnuc.model.core import bolometer as _kb
from irnuc.model.core.constants import C2, C_LIGHT, H_PLANCK, K_BOLTZMANN
from irnuc.model.validate import ConfigError, check_scalar

#: The seven NVESD components, in the order they are reported: name -> meaning.
COMPONENTS: dict[str, str] = {
    "tvh": "temporal (random spatio-temporal)",
    "tv": "temporal row",
    "th": "temporal column",
    "t": "frame to frame",
    "vh": "fixed pixel (random spatial)",
    "v": "fixed row",
    "h": "fixed column",
}


def band_radiance_derivative(T: float, band: tuple[float, float]) -> float:
    """dL/dT of the in-band blackbody radiance at T (K), W m^-2 sr^-1 K^-1.

    The integral over the band (m) of dB_lambda/dT = B_lambda x e^x / ((e^x - 1) T),
    x = c2 / (lambda T), by adaptive Gauss-Kronrod quadrature (scipy.integrate.quad).
    """
    from scipy.integrate import quad

    def integrand(lam: float) -> float:
        x = C2 / (lam * T)
        b = 2.0 * H_PLANCK * C_LIGHT**2 / lam**5 / math.expm1(x)
        return b * x / T * (-1.0 / math.expm1(-x))  # x e^x / (e^x - 1) / T

    value, _ = quad(integrand, band[0], band[1], epsabs=0.0, epsrel=1e-12, limit=200)
    return float(value)


@dataclass
class Responsivity:
    """Closed-form responsivity of every active pixel at one operating point.

    Attributes
    ----------
    codes_per_K : ndarray
        (H, W) output codes per kelvin of scene temperature.
    sigma_codes : ndarray
        (H, W) white temporal noise of each pixel in codes, ADC quantization included.
    sigma_analog_codes : ndarray
        (H, W) the same without the quantization (the noise at the ADC input, in codes).
    good : ndarray
        (H, W) bool: defect-free pixels (the ones averaged).
    conditions : dict
        T_scene, T_substrate, T_cam (K).
    """

    codes_per_K: np.ndarray
    sigma_codes: np.ndarray
    sigma_analog_codes: np.ndarray
    good: np.ndarray
    conditions: dict[str, float]

    @property
    def mean(self) -> float:
        """Mean responsivity over the defect-free pixels, codes/K."""
        return float(self.codes_per_K[self.good].mean())


def responsivity(cfg: Mapping[str, Any], T_scene: float = 300.0, *, seed: int = 0,
                 T_substrate: float | None = None, T_cam: float | None = None,
                 pipe: _pl.Pipeline | None = None) -> Responsivity:
    """Small-signal responsivity and white temporal noise of every active pixel, at a
    uniform scene of ``T_scene`` (K) and the substrate and housing temperatures (K; default
    the configuration's). See the module docstring for the formulas.

    ``pipe`` (optional) is a configured sensor of ``cfg`` to reuse (its environment is
    given here per frame).
    """
    T_scene = check_scalar("T_scene", T_scene, 0.0, 1e5, lo_open=True, unit="K")
    env = cfg["environment"]
    Ts = float(env["T_substrate"] if T_substrate is None else T_substrate)
    Tc = float(env["T_cam"] if T_cam is None else T_cam)
    pipe = pipe if pipe is not None else _pl.Pipeline(cfg, seed)
    c = pipe.cfg
    b, r, a = c["bolometer"], c["readout"], c["adc"]
    if not b["bias_current"] > 0:
        raise ConfigError("responsivity: bolometer.bias_current = 0 A reads no signal")
    run_env = {"T_substrate": np.array([Ts]), "T_cam": np.array([Tc])}
    wanted = ["v_bolo", "dT", "status", "params", "k_scene", "defects", "Q"]
    wanted += ["pulse_ref"] if b["pulse"] == "integrated" else ["solve_coef"]
    v = pipe.run(np.array([T_scene]), wanted, env=run_env)
    act = pipe.layout.active_slice
    defects = v["defects"]
    dQ = v["k_scene"][act] * band_radiance_derivative(T_scene, tuple(c["radiometry"]["band"]))
    dQ = dQ * defects.resp
    per_volt = 2.0 ** a["bits"] / (a["v_high"] - a["v_low"])
    point = operating_point(pipe, v, Ts)
    resp = per_volt * r["gain"] * (-point["dv_dQ"][act]) * dQ
    var_v = pixel_noise_variance(pipe, point)  # at the integrator output, V^2
    from irnuc.model.defects import noisy_sigma

    extra = noisy_sigma(defects, r["v_low"], r["v_high"])
    if extra is not None:
        var_v = var_v + extra**2
    analog = np.sqrt(var_v) * per_volt
    good = (defects.kind == 0) & (v["status"][0][act] == _kb.STATUS_OK)
    return Responsivity(resp, np.sqrt(analog**2 + 1.0 / 12.0), analog, good,
                        {"T_scene": T_scene, "T_substrate": Ts, "T_cam": Tc})


def operating_point(pipe: _pl.Pipeline, v: Mapping[str, Any], T_s: float) -> dict[str, np.ndarray]:
    """Per pixel of the full array at one frame's operating point (``v``: the pipeline's
    products of that frame): the mean bolometer voltage (V), temperature (K) and resistance
    (ohm) over the pulse, dv/dQ (V/W, the small-signal derivative of the steady state), and
    for the integrated pulse the voltage's sensitivity to the pre-pulse temperature S (V/K)
    with the RMS of that temperature's thermal fluctuation (K)."""
    c = pipe.cfg
    b = c["bolometer"]
    I = b["bias_current"]
    p = v["params"]
    vb = v["v_bolo"][0]
    T = T_s + v["dT"][0]
    out: dict[str, np.ndarray] = {"v": vb, "T": T, "R": vb / I}
    if b["pulse"] != "integrated":
        B = _kb.activation_temperature(b["tcr"], b["T_ref"])
        R = vb / I
        D = v["solve_coef"]["b"] * R * B / (T * T)
        fq = v["solve_coef"]["fq"] if v["solve_coef"]["variant"] == 1 else 1.0
        out["dv_dQ"] = -I * R * B / (T * T) / (1.0 + D) * fq / p["g"]
        return out
    from irnuc.model import stages as st

    ctx = _graph_ctx(pipe)
    pr = v["pulse_ref"]
    Q = v["Q"]
    Tsa = np.array([T_s])
    # the derivative of the steady state by central differences (of the same solve):
    # +-1 mK of unbiased equilibrium, truncation error ~(alpha dQ/g)^2 ~ 1e-9
    dq = 1e-3 * p["g"]
    hi = st._periodic(ctx, Q + dq, p, pr, Tsa)["v_bolo"][0]
    lo = st._periodic(ctx, Q - dq, p, pr, Tsa)["v_bolo"][0]
    out["dv_dQ"] = (hi - lo) / (2.0 * dq)
    sol = st._periodic(ctx, Q, p, pr, Tsa, keep=4)
    th0, ym1, sens = sol["theta0"][0], sol["ym1"][0], sol["sens"][0]
    # the stationary RMS of the pre-pulse temperature (as model.core.pulse._stationary_sd)
    y = 1.0 + ym1
    one_d2 = pr["omd"] * (2.0 - pr["omd"])
    den = one_d2 + (1.0 - pr["omd"]) ** 2 * (1.0 - y) * (1.0 + y)
    T0 = T_s + th0
    sig_eq = np.sqrt(K_BOLTZMANN / p["C"])
    sd = np.where((den > 0) & (T0 > 0),
                  sig_eq * T0 * np.sqrt(one_d2 / np.where(den > 0, den, 1.0)), 0.0)
    out["sens"] = sens
    out["thermal_sd"] = sd if st.thermal_noise_on(c) else np.zeros(th0.shape)
    return out


def _graph_ctx(pipe: _pl.Pipeline) -> Any:
    from irnuc.model.graph import RunContext
    from irnuc.model.scenes import Scene

    return RunContext(pipe.cfg, pipe.layout, Scene(), pipe.seed, counts=pipe.counts)


def bolometer_variance(pipe: _pl.Pipeline, point: Mapping[str, np.ndarray]) -> np.ndarray:
    """(rows, cols) variance of each bolometer's own noise in one frame, V^2 (model.noise):
    Johnson 2 k T R / t_int, the 1/f octaves above and below the frame rate k V^2 (ln(P /
    t_int) + FLICKER_OCTAVES ln 2), the thermal fluctuation through the pulse (S sd)^2."""
    from irnuc.model import noise as _noise
    from irnuc.model import stages as st

    c = pipe.cfg
    n, b = c["noise"], c["bolometer"]
    var = np.zeros(point["v"].shape)
    if not n["enabled"]:
        return var
    if n["johnson"]:
        var = var + 2.0 * K_BOLTZMANN * np.maximum(point["T"], 0.0) * point["R"] / b["t_int"]
    white, slow = _noise.flicker_variances(n["flicker_coefficient"], st.frame_period(c),
                                           b["t_int"])
    var = var + (white + slow) * point["v"] ** 2
    if "sens" in point:
        var = var + (point["sens"] * point["thermal_sd"]) ** 2
    return var


def reference_variance(pipe: _pl.Pipeline, bolo_var: np.ndarray) -> np.ndarray:
    """(H, W) variance of each active pixel's skimming reference, V^2: the mean of its row's
    (column's) blind pixels carries their noise over their number squared."""
    from irnuc.model.fpa import BLIND

    mode = pipe.cfg["readout"]["skimming"]
    lay = pipe.layout
    rs, cs = lay.active_slice
    blind = lay.kind_map() == BLIND
    if mode == "none":
        return np.zeros(lay.active_shape)
    axis = 1 if mode == "row" else 0
    count = blind.sum(axis=axis)
    total = np.where(blind, bolo_var, 0.0).sum(axis=axis)
    per_line = total / np.maximum(count, 1) ** 2
    if mode == "row":
        return np.broadcast_to(per_line[rs, None], lay.active_shape).copy()
    return np.broadcast_to(per_line[None, cs], lay.active_shape).copy()


def pixel_noise_variance(pipe: _pl.Pipeline, point: Mapping[str, np.ndarray]) -> np.ndarray:
    """(H, W) white temporal variance of each active pixel at the integrator output, V^2:
    gain^2 (its bolometer's own + its skimming reference's) + the readout's (white and 1/f)
    (not the NOISY defects' or the ADC's)."""
    c = pipe.cfg
    n, r = c["noise"], c["readout"]
    act = pipe.layout.active_slice
    bolo = bolometer_variance(pipe, point)
    var = r["gain"] ** 2 * (bolo[act] + reference_variance(pipe, bolo))
    if n["enabled"]:
        var = var + n["readout_sigma"] ** 2 + n["flicker_sigma"] ** 2
    return var


@dataclass
class Netd:
    """A temporal NETD with what it is made of (K and codes).

    ``uncertainty_K`` is the spread the inputs give it: one standard deviation of the
    pixels' own NETD (each pixel's R, g, C and operating point its own, fpa.tolerance); for
    a measured NETD, its standard error. ``conditions``: the scene, substrate and housing
    temperatures (K), the F-number and the frame rate it holds for.
    """

    netd_K: float
    uncertainty_K: float
    noise_codes: float
    responsivity_codes_per_K: float
    method: str
    notes: str = ""
    conditions: dict[str, float] = field(default_factory=dict)
    percentiles_K: dict[str, float] = field(default_factory=dict)
    #: RMS analog (pre-ADC) noise, codes: 0 when only the ADC's rounding is left
    analog_codes: float = math.nan

    def __float__(self) -> float:
        """The NETD, K."""
        return self.netd_K

    def as_dict(self) -> dict[str, Any]:
        return {"netd_mK": self.netd_K * 1e3, "uncertainty_mK": self.uncertainty_K * 1e3,
                "temporal_noise_codes": self.noise_codes,
                "responsivity_codes_per_K": self.responsivity_codes_per_K,
                "method": self.method, "notes": self.notes, "conditions": dict(self.conditions),
                "percentiles_mK": {k: v * 1e3 for k, v in self.percentiles_K.items()}}

    def text(self) -> str:
        """``26.2 +- 0.4 mK (scene 300 K, F/1, 30 Hz)``."""
        c = self.conditions
        at = (f" (scene {c['T_scene']:g} K, F/{c['f_number']:g}, {c['frame_rate']:g} Hz)"
              if {"T_scene", "f_number", "frame_rate"} <= set(c) else "")
        return f"{self.netd_K * 1e3:.3g} +- {self.uncertainty_K * 1e3:.2g} mK{at}"


#: The scene temperature NETD is quoted at (datasheets quote it at about 300 K), K.
NETD_SCENE_K = 300.0


def netd(cfg: Mapping[str, Any], T_scene: float = NETD_SCENE_K, *, seed: int = 0,
         T_substrate: float | None = None, T_cam: float | None = None,
         pipe: _pl.Pipeline | None = None) -> Netd:
    """Temporal NETD (K): sqrt(<sigma^2>) / <responsivity> over the defect-free pixels, at
    the configuration's F-number and frame rate and a uniform scene (K, 300 K by default).

    The noise is every white temporal source of :func:`pixel_noise_variance` (the pixel's
    bolometer and its skimming reference: Johnson, 1/f, thermal fluctuation; the readout's)
    plus the ADC's quantization LSB^2/12. The uncertainty is the spread the inputs give:
    one standard deviation of the pixels' own NETD sigma_i / responsivity_i.
    """
    rsp = responsivity(cfg, T_scene, seed=seed, T_substrate=T_substrate, T_cam=T_cam,
                       pipe=pipe)
    good = rsp.good
    var = float((rsp.sigma_codes[good] ** 2).mean())
    s_lsb = float(np.sqrt((rsp.sigma_analog_codes[good] ** 2).mean()))
    mean_resp = rsp.mean
    value = math.sqrt(var) / mean_resp
    own = rsp.sigma_codes[good] / rsp.codes_per_K[good]
    notes = ""
    if s_lsb == 0.0:
        notes = ("no temporal noise configured: the NETD is the ADC's rounding, LSB/sqrt(12), "
                 "which constant frames do not show")
    c = pipe.cfg if pipe is not None else cfg
    conditions = {**rsp.conditions, "f_number": float(c["optics"]["f_number"]),
                  "frame_rate": float(c["readout"]["frame_rate"])}
    pct = {f"p{q}": float(np.percentile(own, q)) for q in (5, 50, 95)}
    return Netd(value, float(own.std()), math.sqrt(var), mean_resp, "closed form", notes,
                conditions, pct, s_lsb)


def responsivity_frames(cfg: Mapping[str, Any], scene_K: np.ndarray, fpa_K: np.ndarray,
                        T_cam_K: np.ndarray, *, seed: int = 0, points: int = 32
                        ) -> np.ndarray:
    """(N,) mean closed-form responsivity (codes/K) of each frame of a sequence: evaluated
    at up to ``points`` frames spread over it (every distinct condition when there are
    fewer) and linear in the frame index between them."""
    n = len(scene_K)
    key = np.stack([scene_K, fpa_K, T_cam_K], axis=1)
    distinct = np.unique(key, axis=0)
    pipe = _pl.Pipeline(cfg, seed)
    if len(distinct) <= points:
        values = {tuple(row): responsivity(cfg, row[0], T_substrate=row[1], T_cam=row[2],
                                           pipe=pipe).mean for row in distinct}
        return np.array([values[tuple(row)] for row in key])
    idx = np.unique(np.linspace(0, n - 1, points).round().astype(int))
    at = np.array([responsivity(cfg, key[i, 0], T_substrate=key[i, 1], T_cam=key[i, 2],
                                pipe=pipe).mean for i in idx])
    return np.interp(np.arange(n), idx, at)


# ---- measured on frames ---------------------------------------------------------------------

def _design(columns: Mapping[str, np.ndarray], time_s: np.ndarray | None = None
            ) -> tuple[np.ndarray, list[str], dict[str, float]]:
    """Design matrix of the per-pixel fit: 1, then for each varying quantity its centred
    and scaled value, and when it takes 3 values or more its square and its rate of change
    (a pixel lags what it sees by its thermal time constant: x(t - tau) = x - tau dx/dt).
    Returns the matrix, the column names and each quantity's scale (K per unit)."""
    cols = [np.ones(len(next(iter(columns.values()))))]
    names = ["1"]
    scales: dict[str, float] = {}
    if time_s is not None and len(time_s) >= 3:
        for name, x in list(columns.items()):
            x = np.asarray(x, dtype=np.float64)
            if len(np.unique(x)) >= 3 and len(np.unique(time_s)) == len(time_s):
                columns = {**columns, f"d{name}/dt": np.gradient(x, time_s)}
    for name, x in columns.items():
        x = np.asarray(x, dtype=np.float64)
        span = float(x.max() - x.min())
        if span <= 1e-9 * max(1.0, abs(float(x.mean()))):
            continue
        u = (x - x.mean()) / span
        scales[name] = span
        cols.append(u)
        names.append(name)
        if len(np.unique(x)) >= 3 and not name.startswith("d"):
            cols.append(u * u - (u * u).mean())
            names.append(name + "^2")
    return np.stack(cols, axis=1), names, scales


@dataclass
class MeasuredNoise:
    """Per-pixel fit of frames: temporal noise and responsivity (codes, codes/K)."""

    sigma2_codes: np.ndarray  # (H, W) residual variance
    dof: int
    responsivity: np.ndarray | None  # (H, W) codes/K at the mean scene, or None
    responsivity_se: np.ndarray | None  # its standard error per pixel
    regressors: list[str]


def fit_frames(frames: Iterable[np.ndarray] | np.ndarray, scene_K: np.ndarray,
               fpa_K: np.ndarray, T_cam_K: np.ndarray, chunk: int = 64,
               time_s: np.ndarray | None = None) -> MeasuredNoise:
    """Fit every pixel's codes against the frame's scene, FPA and housing temperatures
    (:func:`_design`) by least squares, accumulating the normal equations chunk by chunk
    (a memory-mapped file is read once, a chunk at a time).

    ``frames``: an (N, H, W) array (or memmap); ``time_s`` (N,): the frames' times, for
    the rate-of-change regressors (none without).
    """
    X, names, scales = _design({"scene": scene_K, "fpa": fpa_K, "T_cam": T_cam_K}, time_s)
    n, p = X.shape
    if n <= p:
        raise ConfigError(f"noise: {n} frame(s) cannot separate temporal noise from "
                          f"{p} regressors ({', '.join(names)}); give more frames")
    codes = np.asarray(frames) if not hasattr(frames, "shape") else frames
    h, w = codes.shape[1:]
    xtx = X.T @ X
    xty = np.zeros((p, h * w))
    yy = np.zeros(h * w)
    shift = np.asarray(codes[0], dtype=np.float64).reshape(-1)  # against cancellation
    for start in range(0, n, chunk):
        y = np.asarray(codes[start:start + chunk], dtype=np.float64).reshape(-1, h * w) - shift
        xty += X[start:start + chunk].T @ y
        yy += (y * y).sum(axis=0)
    inv = np.linalg.inv(xtx)
    beta = inv @ xty
    rss = yy - (beta * xty).sum(axis=0)
    dof = n - p
    sigma2 = np.maximum(rss, 0.0) / dof
    resp = resp_se = None
    if "scene" in names:
        k = names.index("scene")
        resp = (beta[k] / scales["scene"]).reshape(h, w)
        resp_se = np.sqrt(sigma2 * inv[k, k]).reshape(h, w) / scales["scene"]
    return MeasuredNoise(sigma2.reshape(h, w), dof, resp, resp_se, names)


def measured_netd(fit: MeasuredNoise, good: np.ndarray,
                  responsivity_codes_per_K: float | None = None) -> Netd:
    """Temporal NETD (K) of a fit (:func:`fit_frames`) over the ``good`` pixels:
    sqrt(<sigma^2>) / <responsivity>, the responsivity measured (the scene varied) or the
    one given (closed form). Uncertainty: one standard error, from the chi-square spread of
    the residual variance (2 sigma^4 / dof per pixel) and the responsivity's fit error."""
    s2 = fit.sigma2_codes[good]
    if s2.size == 0:
        raise ConfigError("noise: no defect-free pixel to measure the NETD on")
    m = float(s2.mean())
    # Var of the mean of P variance estimates, each 2 sigma^4 / dof.
    rel_noise = math.sqrt(2.0 * float((s2**2).mean()) / fit.dof / s2.size) / (2.0 * m) if m else 0.0
    if fit.responsivity is not None and responsivity_codes_per_K is None:
        r = fit.responsivity[good]
        mean_r = float(r.mean())
        if not (math.isfinite(mean_r) and mean_r != 0.0):
            # Codes that do not follow the scene (a stuck, saturated or 1-bit sensor).
            raise ConfigError(f"noise: the measured responsivity is {mean_r:g} codes/K (the "
                              "codes do not follow the scene: stuck, saturated or too "
                              "coarse); the NETD is not defined")
        rel_resp = math.sqrt(float((fit.responsivity_se[good] ** 2).mean()) / r.size) / abs(mean_r)
        method = "measured (noise and responsivity from the frames)"
    else:
        if responsivity_codes_per_K is None:
            raise ConfigError("noise: the scene does not vary in these frames, so the "
                              "responsivity cannot be measured; give it (closed form)")
        mean_r, rel_resp = float(responsivity_codes_per_K), 0.0
        if not (math.isfinite(mean_r) and mean_r != 0.0):
            raise ConfigError(f"noise: the closed-form responsivity is {mean_r:g} codes/K; the "
                              "NETD is not defined")
        method = "measured noise, closed-form responsivity"
    value = math.sqrt(m) / mean_r
    return Netd(value, value * math.hypot(rel_noise, rel_resp), math.sqrt(m), mean_r, method)


# ---- 3D noise ------------------------------------------------------------------------------

@dataclass
class Noise3D:
    """The NVESD 3D-noise components of a data cube (codes).

    Attributes
    ----------
    sigma : dict
        Component -> standard deviation (sqrt of the variance estimate, 0 if negative).
    variance, variance_se : dict
        Component -> unbiased variance estimate and its standard error (codes^2).
    naive : dict
        Component -> the plain directional-average estimate (biased by the components
        below it; for comparison with tools that report it).
    mean : float
        Grand mean S (codes).
    shape : (T, V, H)
    """

    sigma: dict[str, float]
    variance: dict[str, float]
    variance_se: dict[str, float]
    naive: dict[str, float]
    mean: float
    shape: tuple[int, int, int]

    def as_dict(self, scale: float = 1.0, unit: str = "codes") -> dict[str, Any]:
        """The components (scaled by ``scale``: e.g. 1/responsivity for kelvin)."""
        return {name: {"meaning": COMPONENTS[name], f"sigma_{unit}": self.sigma[name] * scale,
                       f"sigma_se_{unit}": _sigma_se(self.variance[name],
                                                    self.variance_se[name]) * scale,
                       f"naive_{unit}": self.naive[name] * scale}
                for name in COMPONENTS}


def _sigma_se(var: float, se: float) -> float:
    """Standard error of sqrt(var) from that of var (delta method; se itself near 0)."""
    return se / (2.0 * math.sqrt(var)) if var > 0 else math.sqrt(max(se, 0.0))


def noise_3d(frames: np.ndarray, chunk: int = 64,
             progress: Callable[[int, int], None] | None = None) -> Noise3D:
    """3D-noise decomposition of a (T, V, H) cube of codes (frames, rows, columns).

    Mean squares of the three-way layout without replication, computed in two passes over
    the frames (a memory-mapped cube is read a chunk at a time); the variance components
    follow from their expectations,

        E[MS_tvh] = s_tvh^2,              E[MS_tv] = s_tvh^2 + H s_tv^2,
        E[MS_th]  = s_tvh^2 + V s_th^2,   E[MS_vh] = s_tvh^2 + T s_vh^2,
        E[MS_t]   = s_tvh^2 + H s_tv^2 + V s_th^2 + V H s_t^2, and likewise for v and h,

    each with the standard error of the linear combination (Var MS = 2 E[MS]^2 / df).
    """
    T, V, H = frames.shape
    if min(T, V, H) < 2:
        raise ConfigError(f"3D noise needs at least 2 frames, rows and columns; got {T, V, H}")
    s_t = np.zeros(T)
    s_tv = np.zeros((T, V))
    s_th = np.zeros((T, H))
    s_vh = np.zeros((V, H))
    shift = float(np.asarray(frames[0], dtype=np.float64).mean())
    for start in range(0, T, chunk):
        x = np.asarray(frames[start:start + chunk], dtype=np.float64) - shift
        s_tv[start:start + len(x)] = x.sum(axis=2)
        s_th[start:start + len(x)] = x.sum(axis=1)
        s_vh += x.sum(axis=0)
        if progress is not None:
            progress(min(start + chunk, T), 2 * T)
    s_t = s_tv.sum(axis=1)
    m = s_t.sum() / (T * V * H)
    m_t = s_t / (V * H) - m
    m_v = s_tv.sum(axis=0) / (T * H) - m
    m_h = s_th.sum(axis=0) / (T * V) - m
    m_tv = s_tv / H - m - m_t[:, None] - m_v[None, :]
    m_th = s_th / V - m - m_t[:, None] - m_h[None, :]
    m_vh = s_vh / T - m - m_v[:, None] - m_h[None, :]
    ss_tvh = 0.0
    for start in range(0, T, chunk):
        x = np.asarray(frames[start:start + chunk], dtype=np.float64) - shift
        sl = slice(start, start + len(x))
        r = (x - m - m_t[sl, None, None] - m_v[None, :, None] - m_h[None, None, :]
             - m_tv[sl, :, None] - m_th[sl, None, :] - m_vh[None, :, :])
        ss_tvh += float((r * r).sum())
        if progress is not None:
            progress(T + min(start + chunk, T), 2 * T)
    ss = {"t": V * H * float((m_t**2).sum()), "v": T * H * float((m_v**2).sum()),
          "h": T * V * float((m_h**2).sum()), "tv": H * float((m_tv**2).sum()),
          "th": V * float((m_th**2).sum()), "vh": T * float((m_vh**2).sum()), "tvh": ss_tvh}
    df = {"t": T - 1, "v": V - 1, "h": H - 1, "tv": (T - 1) * (V - 1), "th": (T - 1) * (H - 1),
          "vh": (V - 1) * (H - 1), "tvh": (T - 1) * (V - 1) * (H - 1)}
    ms = {k: ss[k] / df[k] for k in ss}
    # Each variance component as a linear combination of mean squares.
    combos: dict[str, dict[str, float]] = {
        "tvh": {"tvh": 1.0},
        "tv": {"tv": 1.0 / H, "tvh": -1.0 / H},
        "th": {"th": 1.0 / V, "tvh": -1.0 / V},
        "vh": {"vh": 1.0 / T, "tvh": -1.0 / T},
        "t": {"t": 1.0 / (V * H), "tv": -1.0 / (V * H), "th": -1.0 / (V * H),
              "tvh": 1.0 / (V * H)},
        "v": {"v": 1.0 / (T * H), "tv": -1.0 / (T * H), "vh": -1.0 / (T * H),
              "tvh": 1.0 / (T * H)},
        "h": {"h": 1.0 / (T * V), "th": -1.0 / (T * V), "vh": -1.0 / (T * V),
              "tvh": 1.0 / (T * V)},
    }
    var = {k: sum(c * ms[j] for j, c in combo.items()) for k, combo in combos.items()}
    se = {k: math.sqrt(sum(c * c * 2.0 * ms[j] ** 2 / df[j] for j, c in combo.items()))
          for k, combo in combos.items()}
    naive = {"t": float(m_t.std()), "v": float(m_v.std()), "h": float(m_h.std()),
             "tv": float(m_tv.std()), "th": float(m_th.std()), "vh": float(m_vh.std()),
             "tvh": math.sqrt(ss_tvh / (T * V * H))}
    sigma = {k: math.sqrt(v) if v > 0 else 0.0 for k, v in var.items()}
    return Noise3D(sigma, var, se, naive, float(m + shift), (T, V, H))


def synthetic_cube(shape: tuple[int, int, int], sigma: Mapping[str, float], seed: int,
                   mean: float = 1000.0) -> np.ndarray:
    """A (T, V, H) cube with independent Gaussian components of the given standard
    deviations (keys of :data:`COMPONENTS`), each drawn over the axes it names."""
    T, V, H = shape
    rng = np.random.default_rng(seed)
    shapes = {"t": (T, 1, 1), "v": (1, V, 1), "h": (1, 1, H), "tv": (T, V, 1),
              "th": (T, 1, H), "vh": (1, V, H), "tvh": (T, V, H)}
    cube = np.full(shape, float(mean))
    for name in COMPONENTS:
        s = float(sigma.get(name, 0.0))
        if s:
            cube = cube + s * rng.standard_normal(shapes[name])
    return cube
