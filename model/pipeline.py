"""The sensor pipeline: a small graph of stages with declared inputs and outputs.

A request for some outputs runs only the stages those outputs need, each once: the stages
that do not depend on the scene (per-pixel parameters, defects, cos^4, housing radiance,
optical coupling) once per run, the others once per chunk of frames. The graph itself is
built from the configuration, so only the configured skimming mode is computed and the
noise stage exists only when noise is configured. :attr:`Pipeline.counts` records how often
each stage ran and how many temperatures the radiance series was evaluated at; the tests
check "computes only what it needs" with these counts.
"""

from __future__ import annotations

import json
import math
import warnings
from collections import Counter
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from irnuc.model import adc as _adc
from irnuc.model import noise as _noise
from irnuc.model import readout as _readout
from irnuc.model.config import config_digest
from irnuc.model.core import bolometer as _kb
from irnuc.model.defects import (
    DefectKind,
    DefectMap,
    DefectSpec,
    apply_voltage_defects,
    inject_defects,
    noisy_sigma,
)
from irnuc.model.fpa import ArrayLayout, draw_pixel_parameters
from irnuc.model.optics import cone_factor, cos4_map, focal_length_from_fov
from irnuc.model.radiometry import band_radiance
from irnuc.model.scenes import Scene, check_temps, scene_temperatures
from irnuc.model.validate import ConfigError, check_int

BOLOMETER_VARIANTS = {"equilibrium": 0, "paper": 1}

#: Names a caller can request from :func:`simulate`, and the product each one is.
OUTPUTS: dict[str, str] = {
    "codes": "codes",                 # (N, H, W) ADC codes
    "voltage": "v_out",               # (N, H, W) integrator output at the ADC input, V
    "bolometer_voltage": "v_bolo",    # (N, rows, cols) I R(T), V, full array
    "temperature_rise": "dT",         # (N, rows, cols) T - T_substrate, K
    "status": "status",               # (N, rows, cols) solver status codes
    "power": "Q",                     # (N, rows, cols) absorbed power, W
    "scene_radiance": "L_scene",      # (N,) or (N, rows, cols) W m^-2 sr^-1
    "scene_temperature": "T_scene",   # (N,) or (N, H, W) K
    "params": "params",               # per-pixel R_ref, g, C over the full array
    "defects": "defects",             # DefectMap (ground truth)
    "cos4": "cos4",                   # (rows, cols)
}


@dataclass(frozen=True)
class Stage:
    """One node of the graph: ``fn(ctx, inputs) -> outputs`` (dicts keyed by product)."""

    name: str
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    per_chunk: bool
    fn: Callable[[RunContext, dict[str, Any]], dict[str, Any]]


@dataclass
class RunContext:
    """What a stage may read besides its inputs."""

    cfg: Mapping[str, Any]
    layout: ArrayLayout
    scene: Scene
    seed: int
    temps: np.ndarray = field(default_factory=lambda: np.empty(0))
    first_frame: int = 0
    counts: Counter = field(default_factory=Counter)
    flicker: _noise.FlickerState | None = None
    #: ``demand(product)`` computes (once) and returns a product no stage input declared:
    #: for results needed only on a rare path, like the skimming fallback voltage.
    demand: Callable[[str], Any] | None = None


# ---- static stages ---------------------------------------------------------------------

def _stage_params(ctx: RunContext, _: dict) -> dict:
    b = ctx.cfg["bolometer"]
    f = ctx.cfg["fpa"]
    nominal = {"R_ref": b["R_ref"], "g": b["g"], "C": b["C"]}
    return {"params": draw_pixel_parameters(ctx.layout, nominal, f["tolerance"], ctx.seed,
                                            f["spread"])}


def _defect_spec(cfg: Mapping[str, Any]) -> DefectSpec:
    return DefectSpec.from_dict(cfg["fpa"]["defects"], path="fpa.defects")


def _stage_defects(ctx: RunContext, _: dict) -> dict:
    return {"defects": inject_defects(ctx.layout.active_shape, _defect_spec(ctx.cfg), ctx.seed)}


def focal_length(cfg: Mapping[str, Any], layout: ArrayLayout) -> float:
    """Focal length, m: given, or from the FOV across the active width (eq. 7)."""
    o = cfg["optics"]
    if o["focal_length"] is not None:
        return float(o["focal_length"])
    return focal_length_from_fov(o["fov"], layout.active_cols * cfg["fpa"]["pitch"])


def _stage_cos4(ctx: RunContext, _: dict) -> dict:
    lay = ctx.layout
    return {"cos4": cos4_map(lay.rows, lay.cols, ctx.cfg["fpa"]["pitch"],
                             focal_length(ctx.cfg, lay), lay.optical_centre)}


def _radiance(ctx: RunContext, temps: np.ndarray) -> np.ndarray:
    r = ctx.cfg["radiometry"]
    ctx.counts["radiance_points"] += int(np.size(temps))
    return band_radiance(temps, tuple(r["band"]), rtol=r["rtol"], method=r["method"])


def _stage_env_radiance(ctx: RunContext, _: dict) -> dict:
    env = ctx.cfg["environment"]
    L = _radiance(ctx, np.array([env["T_cam"], env["T_substrate"]]))
    return {"L_env": (float(L[0]), float(L[1]))}


def _stage_coupling(ctx: RunContext, inp: dict) -> dict:
    """Per-pixel optical coupling: Q = k_scene * L_scene + q_env (W).

    The pixel (absorptance eps, sensitive area A) sees, over the projected solid angle
    pi sin^2(theta) cos^4(beta), the scene through the optics (transmission tau), and the
    housing and optics at T_cam over the rest of the hemisphere. With ``net_radiation``
    it also emits at the substrate temperature (linearised emission is part of g), so a
    scene, housing and substrate all at one temperature heat the pixel by exactly 0.
    Blind pixels see only the shield at T_cam.
    """
    cfg, lay = ctx.cfg, ctx.layout
    f, o = cfg["fpa"], cfg["optics"]
    L_cam, L_s = inp["L_env"]
    net = 1.0 if cfg["bolometer"]["net_radiation"] else 0.0
    area = f["pitch"] ** 2 * f["fill_factor"]
    cone = cone_factor(o["cone_method"], f_number=o["f_number"], fov=o["fov"])
    base = f["absorptance"] * area * math.pi
    seen = o["transmission"] * cone * inp["cos4"]
    seen[lay.kind_map() == 2] = 0.0  # blind pixels: no scene
    return {"k_scene": base * seen, "q_env": base * ((1.0 - seen) * L_cam - net * L_s)}


def _stage_v_skim(ctx: RunContext, inp: dict) -> dict:
    """Reference voltage for ``skimming = none`` and the fallback of a failed blind row:
    the configured value, or a nominal blind pixel at the substrate temperature."""
    r, b = ctx.cfg["readout"], ctx.cfg["bolometer"]
    if r["v_skim"] is not None:
        return {"v_skim": float(r["v_skim"])}
    L_cam, L_s = inp["L_env"]
    f = ctx.cfg["fpa"]
    net = 1.0 if b["net_radiation"] else 0.0
    q = f["absorptance"] * f["pitch"] ** 2 * f["fill_factor"] * math.pi * (L_cam - net * L_s)
    v = _solve(ctx, np.full((1, 1, 1), q), {k: np.full((1, 1), b[k]) for k in ("R_ref", "g", "C")})
    return {"v_skim": float(v["v_bolo"][0, 0, 0])}


# ---- per-chunk stages ------------------------------------------------------------------

def _stage_scene(ctx: RunContext, _: dict) -> dict:
    return {"T_scene": scene_temperatures(ctx.scene, ctx.temps, ctx.layout.active_shape)}


def _stage_scene_radiance(ctx: RunContext, inp: dict) -> dict:
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


def _stage_power(ctx: RunContext, inp: dict) -> dict:
    L = inp["L_scene"]
    if L.ndim == 1:
        L = L[:, None, None]
    Q = inp["k_scene"][None] * L + inp["q_env"][None]
    defects: DefectMap = inp["defects"]
    if (defects.resp != 1.0).any():
        Q[(slice(None), *ctx.layout.active_slice)] *= defects.resp
    return {"Q": Q}


def _solve(ctx: RunContext, Q: np.ndarray, params: Mapping[str, np.ndarray]) -> dict:
    b = ctx.cfg["bolometer"]
    B = _kb.activation_temperature(b["tcr"], b["T_ref"])
    shape = Q.shape
    dT = np.empty(shape)
    v = np.empty(shape)
    status = np.empty(shape, np.uint8)
    iters = np.empty(shape, np.int32)
    _kb.solve_frames(np.ascontiguousarray(Q), params["R_ref"], params["g"], params["C"], B,
                     b["T_ref"], ctx.cfg["environment"]["T_substrate"], b["bias_current"],
                     b["t_int"], BOLOMETER_VARIANTS[b["variant"]], b["rtol"], b["max_iter"],
                     b["runaway_temperature"], dT, v, status, iters)
    return {"v_bolo": v, "dT": dT, "status": status, "iters": iters}


def _stage_bolometer(ctx: RunContext, inp: dict) -> dict:
    return _solve(ctx, inp["Q"], inp["params"])


def _make_skim_stage(mode: str) -> Stage:
    fn = _readout.SKIMMING_MODES[mode]
    if mode == "none":
        def run_fixed(ctx: RunContext, inp: dict) -> dict:
            return {"v_ref": fn(inp["v_bolo"], inp["status"], ctx.layout, inp["v_skim"])}

        return Stage("skimming_none", ("v_bolo", "status", "v_skim"), ("v_ref",), True,
                     run_fixed)

    # Row/column skimming needs the nominal reference voltage (a solve) only as the
    # fallback of a row or column whose blind pixels all failed: asked for on demand.
    def run(ctx: RunContext, inp: dict) -> dict:
        assert ctx.demand is not None
        demand = ctx.demand
        return {"v_ref": fn(inp["v_bolo"], inp["status"], ctx.layout,
                            lambda: demand("v_skim"))}

    return Stage(f"skimming_{mode}", ("v_bolo", "status"), ("v_ref",), True, run)


def _stage_integrator(ctx: RunContext, inp: dict) -> dict:
    r = ctx.cfg["readout"]
    act = (slice(None), *ctx.layout.active_slice)
    v = _readout.integrate(inp["v_bolo"][act], inp["v_ref"], r["gain"], r["v_reset"])
    v = apply_voltage_defects(v, inp["defects"], r["v_low"], r["v_high"], r["v_reset"])
    failed = (inp["status"][act] != _kb.STATUS_OK) if np.count_nonzero(inp["status"]) else None
    if failed is not None and failed.any():
        # A runaway or unsolved pixel drives its integrator into the high rail; it is
        # counted in Frames.diagnostics, never passed on as NaN.
        v[failed] = r["v_high"]
    return {"v_int": v}


def _stage_noisy_pixels(ctx: RunContext, inp: dict) -> dict:
    """Extra noise of NOISY defect pixels, V (None without any): fixed per sensor."""
    r = ctx.cfg["readout"]
    sigma = noisy_sigma(inp["defects"], r["v_low"], r["v_high"])
    if sigma is None:
        return {"noisy_sigma": None}
    idx = np.flatnonzero(sigma)
    return {"noisy_sigma": (sigma, idx, sigma.reshape(-1)[idx])}


def _stage_noise(ctx: RunContext, inp: dict) -> dict:
    cfg = ctx.cfg
    n, r, b = cfg["noise"], cfg["readout"], cfg["bolometer"]
    noisy = inp["noisy_sigma"]
    extra = noisy[0] if noisy is not None else None
    if not n["enabled"]:
        if noisy is None:
            return {"v_out": inp["v_int"]}
        ctx.counts["noise_frames"] += inp["v_int"].shape[0]
        return {"v_out": _noise.add_noise_at(inp["v_int"], noisy[1], noisy[2], ctx.seed,
                                             ctx.first_frame)}
    sigma2: np.ndarray | float = n["readout_sigma"] ** 2
    if n["johnson"]:
        act = (slice(None), *ctx.layout.active_slice)
        T = cfg["environment"]["T_substrate"] + inp["dT"][act]
        sj = _noise.johnson_sigma(np.abs(inp["v_bolo"][act]), np.maximum(T, 0.0),
                                  max(b["bias_current"], 1e-30), b["t_int"], r["gain"])
        sigma2 = sigma2 + np.nan_to_num(sj) ** 2
    if extra is not None:
        sigma2 = sigma2 + extra**2
    flicker = n["flicker_sigma"]
    if flicker > 0.0 and ctx.flicker is None:
        ctx.flicker = _noise.FlickerState(ctx.layout.active_shape)
    ctx.counts["noise_frames"] += inp["v_int"].shape[0]
    return {"v_out": _noise.add_noise(inp["v_int"], np.sqrt(sigma2), ctx.seed, ctx.first_frame,
                                      flicker, ctx.flicker)}


def _stage_adc(ctx: RunContext, inp: dict) -> dict:
    r, a = ctx.cfg["readout"], ctx.cfg["adc"]
    return {"codes": _adc.adc_convert(inp["v_out"], a["bits"], a["v_low"], a["v_high"],
                                      a["rounding"], rails=(r["v_low"], r["v_high"]))}


def _noise_configured(cfg: Mapping[str, Any]) -> bool:
    """True if some noise source is non-zero: noise enabled with every sigma 0 (and no
    Johnson noise) adds exactly nothing, so it gets no stage and draws nothing."""
    n = cfg["noise"]
    if n["enabled"] and (n["johnson"] or n["readout_sigma"] > 0 or n["flicker_sigma"] > 0):
        return True
    spec = _defect_spec(cfg)
    kinds = set(spec.cluster_kinds) | {spec.line_kind} if (spec.clusters or spec.rows or spec.cols) else set()
    kinds |= {k for k, rate in spec.rates.items() if rate > 0}
    kinds |= {str(p.get("kind")) for p in spec.listed}
    return DefectKind.NOISY.name.lower() in {str(k).lower() for k in kinds}


def build_stages(cfg: Mapping[str, Any]) -> list[Stage]:
    """The stage graph for one validated configuration."""
    stages = [
        Stage("params", (), ("params",), False, _stage_params),
        Stage("defects", (), ("defects",), False, _stage_defects),
        Stage("cos4", (), ("cos4",), False, _stage_cos4),
        Stage("env_radiance", (), ("L_env",), False, _stage_env_radiance),
        Stage("coupling", ("cos4", "L_env"), ("k_scene", "q_env"), False, _stage_coupling),
        Stage("v_skim", ("L_env",), ("v_skim",), False, _stage_v_skim),
        Stage("scene", (), ("T_scene",), True, _stage_scene),
        Stage("scene_radiance", ("T_scene",), ("L_scene",), True, _stage_scene_radiance),
        Stage("power", ("L_scene", "k_scene", "q_env", "defects"), ("Q",), True, _stage_power),
        Stage("bolometer", ("Q", "params"), ("v_bolo", "dT", "status", "iters"), True,
              _stage_bolometer),
        _make_skim_stage(cfg["readout"]["skimming"]),
        Stage("integrator", ("v_bolo", "v_ref", "defects", "status"), ("v_int",), True,
              _stage_integrator),
    ]
    if _noise_configured(cfg):
        stages.append(Stage("noisy_pixels", ("defects",), ("noisy_sigma",), False,
                            _stage_noisy_pixels))
        stages.append(Stage("noise", ("v_int", "v_bolo", "dT", "noisy_sigma"), ("v_out",), True,
                            _stage_noise))
    else:
        stages.append(Stage("no_noise", ("v_int",), ("v_out",), True,
                            lambda ctx, inp: {"v_out": inp["v_int"]}))
    stages.append(Stage("adc", ("v_out",), ("codes",), True, _stage_adc))
    return stages


def plan(stages: Sequence[Stage], products: Iterable[str],
         have: Iterable[str] = ()) -> list[Stage]:
    """The stages needed for ``products``, each once, in dependency order; products in
    ``have`` are already known and need no stage."""
    producer = {out: s for s in stages for out in s.outputs}
    order: list[Stage] = []
    seen: set[str] = set()
    known = set(have)

    def visit(product: str) -> None:
        if product in known:
            return
        if product not in producer:
            raise ConfigError(f"no stage produces {product!r}")
        stage = producer[product]
        if stage.name in seen:
            return
        for dep in stage.inputs:
            visit(dep)
        seen.add(stage.name)
        order.append(stage)

    for p in products:
        visit(p)
    return order


def run_planned(stages: Sequence[Stage], ctx: RunContext, values: dict[str, Any],
                products: Sequence[str]) -> None:
    """Run the stages that ``products`` need beyond the products already in ``values``,
    counting each in ``ctx.counts``; results are added to ``values``. Stages asking for a
    product on demand get it computed into ``values`` the same way."""
    if ctx.demand is None:
        def demand(product: str) -> Any:
            run_planned(stages, ctx, values, [product])
            return values[product]

        ctx.demand = demand
    for stage in plan(stages, products, values):
        ctx.counts[stage.name] += 1
        values.update(stage.fn(ctx, {k: values[k] for k in stage.inputs}))


@dataclass
class Frames:
    """Result of :func:`simulate`.

    Attributes
    ----------
    codes : ndarray or None
        (N, H, W) raw ADC codes (uint16 up to 16 bits).
    temps : ndarray
        (N,) scene base temperature of every frame, K.
    defect_kind, defect_pattern : ndarray or None
        (H, W) ground truth (model.defects.DefectKind / DefectPattern codes).
    outputs : dict
        Every requested output by name (see :data:`OUTPUTS`).
    diagnostics : dict
        Self-heating, solver failures, clipped codes.
    counts : dict
        Stage executions and radiance evaluations of this run.
    """

    codes: np.ndarray | None
    temps: np.ndarray
    defect_kind: np.ndarray | None
    defect_pattern: np.ndarray | None
    adc_bits: int
    config: dict[str, Any]
    seed: int
    scene: Scene
    outputs: dict[str, Any]
    diagnostics: dict[str, Any]
    counts: dict[str, int]

    def config_json(self) -> str:
        return json.dumps({"config": self.config, "scene": {"kind": self.scene.kind,
                           "params": _jsonable(self.scene.params)}, "seed": self.seed,
                           "config_digest": config_digest(self.config)}, sort_keys=True)


def _jsonable(params: Mapping[str, Any]) -> dict[str, Any]:
    return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in params.items()}


class Pipeline:
    """A configured sensor: per-pixel parameters, defects and optics fixed by (config, seed).

    The scene-independent products are computed on first use and kept, so a sensor that
    produces frames call after call pays for them once. They depend only on the
    configuration and the seed, both fixed for the lifetime of the object.
    """

    def __init__(self, cfg: Mapping[str, Any], seed: int = 0) -> None:
        cfg = checked_config(cfg)
        self.cfg = cfg
        self.seed = check_int("seed", seed, 0, 2**63 - 1)
        f = cfg["fpa"]
        self.layout = ArrayLayout(f["active_rows"], f["active_cols"], tuple(f["boundary"]),
                                  tuple(f["blind"]))
        self.stages = build_stages(cfg)
        self.counts: Counter = Counter()
        self._static: dict[str, Any] = {}

    def run(self, temps: np.ndarray, products: Sequence[str], scene: Scene | None = None,
            progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
        """Compute ``products`` for the frames of ``temps``; per-chunk products stacked."""
        order = plan(self.stages, products)
        chunked = [s for s in order if s.per_chunk]
        ctx = RunContext(self.cfg, self.layout, scene or Scene(), self.seed, counts=self.counts)
        static = [s for s in self.stages if not s.per_chunk]

        def demand(product: str) -> Any:  # a static product needed only on a rare path
            run_planned(static, ctx, self._static, [product])
            return self._static[product]

        ctx.demand = demand
        for stage in order:
            if not stage.per_chunk and not all(o in self._static for o in stage.outputs):
                self.counts[stage.name] += 1
                self._static.update(stage.fn(ctx, {k: self._static[k] for k in stage.inputs}))
        per_chunk: dict[str, list] = {p: [] for p in products}
        n = len(temps)
        step = self.cfg["run"]["chunk_frames"] if chunked else max(n, 1)
        for start in range(0, n, step):
            ctx.temps = temps[start:start + step]
            ctx.first_frame = start
            chunk = dict(self._static)
            for stage in chunked:
                self.counts[stage.name] += 1
                chunk.update(stage.fn(ctx, {k: chunk[k] for k in stage.inputs}))
            for p in products:
                per_chunk[p].append(chunk[p])
            if progress is not None:
                progress(min(start + step, n), n)
        out: dict[str, Any] = {}
        chunk_products = {o for s in chunked for o in s.outputs}
        for p in products:
            if p in chunk_products:
                parts = per_chunk[p]
                out[p] = np.concatenate(parts) if len(parts) > 1 else parts[0]
            else:
                out[p] = self._static[p]
        return out

    def simulate(self, temps: Sequence[float] | np.ndarray, scene: str | Scene = "uniform", *,
                 repeats: int = 1, outputs: Sequence[str] = ("codes",),
                 scene_params: Mapping[str, Any] | None = None,
                 progress: Callable[[int, int], None] | None = None) -> Frames:
        """Frames of this sensor; see :func:`simulate` for the parameters."""
        if isinstance(scene, str):
            scene = Scene(scene, dict(scene_params or {}))
        t = check_temps(temps)
        repeats = check_int("repeats", repeats, 1, 1_000_000)
        t = np.repeat(t, repeats)
        unknown = [o for o in outputs if o not in OUTPUTS]
        if unknown:
            raise ConfigError(f"outputs: unknown name(s) {unknown}; known {sorted(OUTPUTS)}")
        check_simulation_memory(self.cfg, t.size, outputs)
        wanted = [OUTPUTS[o] for o in outputs]
        if "codes" in outputs:
            wanted += ["defects", "status", "dT"]  # ground truth and diagnostics
        before = Counter(self.counts)
        values = self.run(t, list(dict.fromkeys(wanted)), scene, progress)
        defects = values.get("defects")
        return Frames(
            codes=values.get("codes"),
            temps=t,
            defect_kind=defects.kind if defects is not None else None,
            defect_pattern=defects.pattern if defects is not None else None,
            adc_bits=self.cfg["adc"]["bits"],
            config=dict(self.cfg),
            seed=self.seed,
            scene=scene,
            outputs={o: values[OUTPUTS[o]] for o in outputs},
            diagnostics=_diagnostics(self, values) if "status" in values else {},
            counts=dict(self.counts - before),
        )


# ---- argument and size checks at the API boundary ---------------------------------------

def checked_config(cfg: Any) -> dict[str, Any]:
    """``cfg`` validated (a no-op copy for a configuration from ``load_preset``/``load_config``);
    a bare dict, ``None`` or a half-filled mapping is one :class:`ConfigError` naming ``cfg``
    and the field, instead of a ``KeyError`` deep inside a stage."""
    from irnuc.model.config import validate

    if not isinstance(cfg, Mapping):
        raise ConfigError(f"cfg = {cfg!r:.60} is not a sensor configuration; use "
                          "model.load_preset(...) or model.load_config(...)")
    return validate(cfg, source="cfg")


#: Generous bytes per pixel of the full array: kept per run (parameters, defects, optics),
#: per frame of a chunk (the stages' float64 products and temporaries), and per frame of
#: the result for codes (uint16 + status + dT kept for the diagnostics) and for each other
#: per-frame output (float64). Checked against measured peaks (docs/robustness.md).
_BYTES_STATIC, _BYTES_CHUNK, _BYTES_CODES = 200, 160, 11
_PER_FRAME_OUTPUTS = ("voltage", "bolometer_voltage", "power", "scene_radiance", "scene_temperature")


def simulation_bytes(cfg: Mapping[str, Any], n_frames: int, outputs: Sequence[str] = ("codes",)
                     ) -> int:
    """Estimated peak memory of simulating ``n_frames`` frames of ``cfg`` (bytes)."""
    f = cfg["fpa"]
    layout = ArrayLayout.from_dict({k: f[k] for k in ("active_rows", "active_cols", "boundary",
                                                      "blind") if k in f})
    pixels = layout.rows * layout.cols
    chunk = min(int(cfg["run"]["chunk_frames"]), n_frames)
    per_frame = _BYTES_CODES + 8 * sum(o in outputs for o in _PER_FRAME_OUTPUTS)
    # The result is concatenated from its chunks: twice its size at the peak.
    return pixels * (_BYTES_STATIC + _BYTES_CHUNK * chunk + 2 * n_frames * per_frame)


def check_simulation_memory(cfg: Mapping[str, Any], n_frames: int,
                            outputs: Sequence[str] = ("codes",), what: str = "") -> None:
    """:class:`~irnuc.common.memory.ResourceError` before any work when the frames would not fit."""
    from irnuc.common.memory import check_memory

    f = cfg["fpa"]
    check_memory(simulation_bytes(cfg, n_frames, outputs),
                 what or (f"simulate: {n_frames} frame(s) (temps x repeats) of fpa.active_rows x "
                          f"fpa.active_cols = {f['active_rows']} x {f['active_cols']} pixels"),
                 "use fewer or smaller frames")


def simulate(cfg: Mapping[str, Any], temps: Sequence[float] | np.ndarray, scene: str | Scene = "uniform",
             *, seed: int = 0, repeats: int = 1, outputs: Sequence[str] = ("codes",),
             scene_params: Mapping[str, Any] | None = None,
             progress: Callable[[int, int], None] | None = None) -> Frames:
    """Sensor frames for a batch of scene temperatures (a one-shot :class:`Pipeline`).

    Parameters
    ----------
    cfg : dict
        A validated configuration (:func:`model.load_preset` / :func:`model.load_config`).
    temps : sequence of float
        Scene base temperature of each frame, K (> 0).
    scene : str or Scene
        Scene kind (``uniform``, ``gradient``, ``disk``, ``map``) or a :class:`Scene`.
    seed : int
        Seed of every random draw (spread, defects, noise); same config and seed give the
        same bits.
    repeats : int
        Frames per temperature (temperature-major order), e.g. for calibration stacks.
    outputs : sequence of str
        Keys of :data:`OUTPUTS`; only the stages they need run.
    scene_params : dict, optional
        Parameters of the scene kind when ``scene`` is a name.
    progress : callable, optional
        Called as ``progress(done, total)`` after each chunk of frames.
    """
    return Pipeline(cfg, seed).simulate(temps, scene, repeats=repeats, outputs=outputs,
                                        scene_params=scene_params, progress=progress)


def _diagnostics(pipe: Pipeline, values: Mapping[str, Any]) -> dict[str, Any]:
    status = values["status"]
    act = (slice(None), *pipe.layout.active_slice)
    dT = values["dT"][act]
    # Failures are rare: count them only when there are any.
    counts = (np.bincount(status.reshape(-1), minlength=4) if np.count_nonzero(status)
              else np.zeros(4, np.int64))
    if counts[_kb.STATUS_INVALID]:  # those hold 0 K (-T_s), no rise of the pixel's own
        dT = dT[status[act] != _kb.STATUS_INVALID]
    diag: dict[str, Any] = {
        "temperature_rise_K": {"min": float(dT.min()) if dT.size else math.nan,
                               "mean": float(dT.mean()) if dT.size else math.nan,
                               "max": float(dT.max()) if dT.size else math.nan},
        "solver_failures": {"no_convergence": int(counts[_kb.STATUS_NO_CONVERGENCE]),
                            "runaway": int(counts[_kb.STATUS_RUNAWAY]),
                            "invalid": int(counts[_kb.STATUS_INVALID])},
    }
    if "codes" in values:
        top = (1 << pipe.cfg["adc"]["bits"]) - 1
        hist_ends = values["codes"].reshape(-1)
        diag["clipped_low"] = int(np.count_nonzero(hist_ends == 0))
        diag["clipped_high"] = int(np.count_nonzero(hist_ends == top))
    failures = sum(diag["solver_failures"].values())
    if failures:
        warnings.warn(f"{failures} pixel solve(s) failed (thermal runaway or no convergence): "
                      f"{diag['solver_failures']}; those pixels read the high rail",
                      RuntimeWarning, stacklevel=3)
    return diag
