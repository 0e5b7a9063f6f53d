"""Random legal pipeline configurations of an RTL top, and the classes a sample must cover.

A top's legal configuration space is a :class:`ConfigSpace`: the fields it draws with their
legal ranges (from the shared-constants spec, :data:`irnuc.nuc_fixed.rtl_spec.RANGES`), the
modes (the spec's enums), the limits a testbench adds (a coefficient word of at most 64
bits: the golden model packs words in uint64), and the classes of a configuration that a
sample must cover (:meth:`ConfigSpace.classes`). :data:`SPACES` holds one per top; a new top
(an AXI4 wrapper, a method's top) adds its space with :func:`register_space`.

A draw is seeded and stratified: draw ``i`` of a sample takes rounding x overflow mode
``i mod 6``, the order of the fraction widths (offset above, gain above, equal)
``(i // 6) mod 3`` and the shape of the maximum frame (square, wide, tall) ``(i // 2) mod 3``,
so 18 consecutive draws cover every mode x fraction order; every width is drawn from its
legal range with a bias to its ends (``lo``, ``lo + 1``, ``hi - 1``, ``hi``) and the maximum
frame sizes log-uniformly with a bias to 1, 2, 3, 4 and 2^k - 1 (the sizes where the RTL's
frame-size port is all ones). An illegal draw (a sum wider than ``SumBitsMax``, a word
wider than 64 bits) is drawn again.

:data:`BRANCHES` lists every parameter-dependent branch of ``hdl/`` (each generate block
and each parameter ternary) with the condition, in the configuration's terms, under which it
is elaborated; :func:`cover` picks from a seeded pool the fewest configurations that,
together with the named ones, hit every class (:func:`ci_sample`, the sample CI runs).
``tests/test_configspace.py`` checks the generate-block conditions against Verilator's
elaboration of every configuration that runs (``irnuc.cosim.elaborate``).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from irnuc.nuc_fixed import PipelineConfig, load_pipeline, pipeline_names, rtl_spec
from irnuc.nuc_fixed.config import ConfigError

#: Rounding x overflow modes, in the order draws take them.
MODES: tuple[tuple[str, str], ...] = tuple(
    (r, o) for o in rtl_spec.OVERFLOW_MODES for r in rtl_spec.ROUNDING_MODES)
#: Order of the fraction widths: offset fraction bits above, below or equal to the gain's.
FRAC_ORDERS = ("offset_above", "gain_above", "equal")
#: Shape of the maximum frame: MaxWidth = MaxHeight, MaxWidth > MaxHeight, or below.
SHAPES = ("square", "wide", "tall")
#: Widest coefficient word the testbenches pack (``nuc_fixed.pack_words``: uint64).
WORD_BITS_MAX = 64
#: The seed and pool size of the fixed sample CI runs (:func:`ci_sample`).
CI_SEED = 20
CI_POOL = 240
#: Largest maximum frame size the CI sample draws (frames of MaxWidth pixels are
#: simulated); the campaign draws up to :data:`rtl_spec.FRAME_DIM_MAX`.
CI_MAX_DIM = 1024


# ---- the branches of hdl/ ------------------------------------------------------------------

def _f(c: PipelineConfig) -> int:
    return c.frac_bits


def _rnd_bits(c: PipelineConfig) -> int:
    """nuc_core's RndBits: SumBits + 1 - F."""
    return c.sum_bits + 1 - c.frac_bits


def _full_port(n: int) -> bool:
    """The frame-size port of clog2(n + 1) bits is all ones at n (no upper check)."""
    return n == (1 << rtl_spec.clog2(n + 1)) - 1


def _dpc_parts(c: PipelineConfig) -> int:
    return rtl_spec.mul_parts(c.out_bits + 3, rtl_spec.dpc_recip_shift(c.out_bits) + 1)


def _tree_passes(leaves: int) -> bool:
    """Whether an irnuc_add_tree of ``leaves`` leaves has a level with an odd count (a node
    that passes its one input on)."""
    while leaves > 1:
        if leaves % 2:
            return True
        leaves = (leaves + 1) // 2
    return False


@dataclass(frozen=True)
class Branch:
    """One parameter-dependent branch of one module.

    ``block`` is the path of a generate block (``gen_wrap/gen_sign_ext``: nested labels),
    checked against Verilator's elaboration; otherwise ``text`` is a parameter ternary that
    occurs in ``module``'s file, and ``name`` tells which side. ``when`` says, in the
    configuration's terms, whether the branch is elaborated (taken).
    """

    module: str
    name: str
    when: Callable[[PipelineConfig], bool]
    block: str | None = None
    text: str | None = None
    #: Why no configuration of this top elaborates the branch in simulation (None: some
    #: configuration must).
    never: str | None = None

    @property
    def key(self) -> str:
        return f"{self.module}:{self.block or self.name}"


def _gen(module: str, block: str, when: Callable[[PipelineConfig], bool]) -> Branch:
    return Branch(module, block, when, block=block)


def _not_here(module: str, block: str, why: str) -> Branch:
    """A generate block that no configuration of this top elaborates in simulation."""
    return Branch(module, block, lambda c: False, block=block, never=why)


def _mul_pairs(c: PipelineConfig) -> tuple[tuple[int, int], ...]:
    """(ABits, BBits) of nuc_dpc_top's two irnuc_mul_parts instances (x * g, M * R[n])."""
    return ((c.adc_bits, c.gain_bits),
            (c.out_bits + 3, rtl_spec.dpc_recip_shift(c.out_bits) + 1))


def _ternary(module: str, name: str, text: str, when: Callable[[PipelineConfig], bool]
             ) -> Branch:
    return Branch(module, name, when, text=text)


_ALWAYS: Callable[[PipelineConfig], bool] = lambda c: True  # noqa: E731

#: Every parameter-dependent branch of nuc_dpc_top's modules (docs/verification.md,
#: "Configuration sampling"). Generate blocks (``block``) are checked against Verilator's
#: elaboration; ternaries (``text``) are listed with the text they mirror.
BRANCHES: tuple[Branch, ...] = (
    # ---- nuc_core: rounding (FracBits == 0 or truncate: no increment) --------------------
    _gen("nuc_core", "gen_leaf", _ALWAYS),
    _gen("nuc_core", "gen_inc_none", lambda c: _f(c) == 0 or c.rounding == "truncate"),
    _gen("nuc_core", "gen_inc_none/gen_frac_unused",
         lambda c: _f(c) > 0 and c.rounding == "truncate"),
    _gen("nuc_core", "gen_inc_half_up", lambda c: _f(c) > 0 and c.rounding == "half_up"),
    _gen("nuc_core", "gen_inc_half_up/gen_frac_unused",
         lambda c: _f(c) > 1 and c.rounding == "half_up"),
    _gen("nuc_core", "gen_inc_half_even", lambda c: _f(c) > 0 and c.rounding == "half_even"),
    _gen("nuc_core", "gen_inc_half_even/gen_sticky",
         lambda c: _f(c) > 1 and c.rounding == "half_even"),
    _gen("nuc_core", "gen_inc_half_even/gen_no_sticky",
         lambda c: _f(c) == 1 and c.rounding == "half_even"),
    # ---- nuc_core: overflow ----------------------------------------------------------------
    _gen("nuc_core", "gen_saturate", lambda c: c.overflow == "saturate"),
    _gen("nuc_core", "gen_saturate/gen_hi_check",
         lambda c: c.overflow == "saturate" and _rnd_bits(c) - 1 > c.out_bits),
    _gen("nuc_core", "gen_saturate/gen_no_hi_check",
         lambda c: c.overflow == "saturate" and _rnd_bits(c) - 1 <= c.out_bits),
    _gen("nuc_core", "gen_wrap", lambda c: c.overflow == "wrap"),
    _gen("nuc_core", "gen_wrap/gen_low_bits",
         lambda c: c.overflow == "wrap" and _rnd_bits(c) >= c.out_bits),
    _gen("nuc_core", "gen_wrap/gen_low_bits/gen_hi_unused",
         lambda c: c.overflow == "wrap" and _rnd_bits(c) > c.out_bits),
    _gen("nuc_core", "gen_wrap/gen_sign_ext",
         lambda c: c.overflow == "wrap" and _rnd_bits(c) < c.out_bits),
    # ---- nuc_core: widths ------------------------------------------------------------------
    _ternary("nuc_core", "frac_from_gain",
             "(GainFracBits > OffsetFracBits) ? GainFracBits : OffsetFracBits",
             lambda c: c.gain_frac_bits > c.offset_frac_bits),
    _ternary("nuc_core", "frac_from_offset",
             "(GainFracBits > OffsetFracBits) ? GainFracBits : OffsetFracBits",
             lambda c: c.gain_frac_bits <= c.offset_frac_bits),
    _ternary("nuc_core", "sum_from_product", "((SumBitsA > SumBitsB) ? SumBitsA : SumBitsB)",
             lambda c: c.adc_bits + c.gain_int_bits + _f(c) + 1 > c.offset_int_bits + _f(c)),
    _ternary("nuc_core", "sum_from_offset", "((SumBitsA > SumBitsB) ? SumBitsA : SumBitsB)",
             lambda c: c.adc_bits + c.gain_int_bits + _f(c) + 1 <= c.offset_int_bits + _f(c)),
    # ---- irnuc_mul_parts (nuc x * g, dpc M * R[n]) -------------------------------------------
    _gen("irnuc_mul_parts", "gen_a", _ALWAYS),
    _gen("irnuc_mul_parts", "gen_a/gen_b", _ALWAYS),
    _gen("irnuc_mul_parts", "gen_a/gen_zero", _ALWAYS),
    _gen("irnuc_mul_parts", "gen_a/gen_b/gen_zero", _ALWAYS),
    _not_here("irnuc_mul_parts", "gen_a/gen_sign", "signed operands: the method tops only"),
    _not_here("irnuc_mul_parts", "gen_a/gen_b/gen_sign", "signed operands: the method tops only"),
    _gen("irnuc_mul_parts", "gen_a/gen_b/gen_part_high",
         lambda c: any(a + b < 36 for a, b in _mul_pairs(c))),
    # The last chunk of an operand takes what is left; the others are full chunks (an
    # operand wider than one chunk).
    _ternary("irnuc_mul_parts", "a_last_chunk", "(i == AChunks - 1) ? ABits - ALsb : ChunkBits",
             _ALWAYS),
    _ternary("irnuc_mul_parts", "a_inner_chunk",
             "(i == AChunks - 1) ? ABits - ALsb : ChunkBits",
             lambda c: any(a > rtl_spec.MUL_CHUNK_BITS for a, _ in _mul_pairs(c))),
    _ternary("irnuc_mul_parts", "b_last_chunk", "(j == BChunks - 1) ? BBits - BLsb : ChunkBits",
             _ALWAYS),
    _ternary("irnuc_mul_parts", "b_inner_chunk",
             "(j == BChunks - 1) ? BBits - BLsb : ChunkBits",
             lambda c: any(b > rtl_spec.MUL_CHUNK_BITS for _, b in _mul_pairs(c))),
    # ---- irnuc_add_tree (nuc sum, dpc sum, dpc product) -----------------------------------
    _gen("irnuc_add_tree", "gen_single", lambda c: _dpc_parts(c) == 1),
    _gen("irnuc_add_tree", "gen_tree", _ALWAYS),
    _gen("irnuc_add_tree", "gen_tree/gen_level", _ALWAYS),
    _gen("irnuc_add_tree", "gen_tree/gen_level/gen_from_leaves", _ALWAYS),
    _gen("irnuc_add_tree", "gen_tree/gen_level/gen_from_leaves/gen_leaf", _ALWAYS),
    _gen("irnuc_add_tree", "gen_tree/gen_level/gen_from_level", _ALWAYS),
    _gen("irnuc_add_tree", "gen_tree/gen_level/gen_node", _ALWAYS),
    _gen("irnuc_add_tree", "gen_tree/gen_level/gen_node/gen_add", _ALWAYS),
    # The trees: nuc_core's partial products and offset, dpc_core's 8 neighbours (never a
    # pass) and its product's partial products.
    _gen("irnuc_add_tree", "gen_tree/gen_level/gen_node/gen_pass",
         lambda c: _tree_passes(rtl_spec.mul_parts(c.adc_bits, c.gain_bits) + 1)
         or _tree_passes(_dpc_parts(c))),
    # ---- dpc_core's input register (method_dpc_top feeds it from the NUC core's output
    # register: InReg = 0 there) and the checkers (inside `ifdef IRNUC_ASSERT`: this
    # elaboration is the synthesized design's; nuc_dpc_top's dpc_core has CheckIn = 0) ----
    _gen("dpc_core", "gen_in_reg", _ALWAYS),
    _not_here("dpc_core", "gen_in_direct", "InReg = 0: method_dpc_top only"),
    _not_here("dpc_core", "gen_assert_frame",
              "a checker (IRNUC_ASSERT, simulation only); CheckIn = 0 in nuc_dpc_top"),
    _not_here("irnuc_spill_register", "gen_assert_in",
              "a checker (IRNUC_ASSERT, simulation only): not in the synthesized design"),
    # ---- dpc_ctrl: upper frame-size check unless the port is all ones at the maximum -----
    _gen("dpc_ctrl", "gen_w_full", lambda c: _full_port(c.max_width)),
    _gen("dpc_ctrl", "gen_w_check", lambda c: not _full_port(c.max_width)),
    _gen("dpc_ctrl", "gen_h_full", lambda c: _full_port(c.max_height)),
    _gen("dpc_ctrl", "gen_h_check", lambda c: not _full_port(c.max_height)),
    # ---- line-buffer address width (dpc_core, dpc_ctrl, irnuc_line_buffer) -------------------
    _ternary("dpc_ctrl", "one_column", "(MaxWidth > 1) ? $clog2(MaxWidth) : 1",
             lambda c: c.max_width == 1),
    _ternary("dpc_ctrl", "columns", "(MaxWidth > 1) ? $clog2(MaxWidth) : 1",
             lambda c: c.max_width > 1),
    _ternary("dpc_core", "one_column", "(MaxWidth > 1) ? $clog2(MaxWidth) : 1",
             lambda c: c.max_width == 1),
    _ternary("dpc_core", "columns", "(MaxWidth > 1) ? $clog2(MaxWidth) : 1",
             lambda c: c.max_width > 1),
    _gen("irnuc_line_buffer", "gen_inferred", _ALWAYS),
    _not_here("irnuc_line_buffer", "gen_dp16kd",
              "ECP5 block RAM: only with IRNUC_ECP5 defined (irnuc synth), never simulated"),
    _not_here("irnuc_line_buffer", "gen_dp16kd/gen_tile",
              "ECP5 block RAM: only with IRNUC_ECP5 defined (irnuc synth), never simulated"),
    _ternary("irnuc_line_buffer", "one_word", "(Depth > 1) ? $clog2(Depth) : 1",
             lambda c: c.max_width == 1),
    _ternary("irnuc_line_buffer", "words", "(Depth > 1) ? $clog2(Depth) : 1",
             lambda c: c.max_width > 1),
)


# ---- configuration classes -----------------------------------------------------------------

def frac_order(cfg: PipelineConfig) -> str:
    if cfg.offset_frac_bits > cfg.gain_frac_bits:
        return "offset_above"
    return "gain_above" if cfg.gain_frac_bits > cfg.offset_frac_bits else "equal"


def shape(cfg: PipelineConfig) -> str:
    if cfg.max_width == cfg.max_height:
        return "square"
    return "wide" if cfg.max_width > cfg.max_height else "tall"


def _range_class(value: int, lo: int, hi: int) -> str:
    return "min" if value == lo else "max" if value == hi else "inner"


# ---- the space -----------------------------------------------------------------------------

@dataclass(frozen=True)
class ConfigSpace:
    """The legal configurations of one RTL top (see the module's docstring).

    ``base`` names the configuration whose other fields (method, formats) every draw keeps;
    ``fields`` are the drawn integer fields with their legal ranges; ``checks`` are the
    testbench limits beyond :class:`PipelineConfig`'s own validation (each returns a reason
    or None); ``branches`` the parameter branches of the top's modules. ``draw`` makes one
    configuration from an rng and the draw's index (the stratum); the default draws the
    two-point widths, modes and maximum frame sizes.
    """

    top: str
    base: str = "minimal"
    fields: Mapping[str, tuple[int, int]] = field(
        default_factory=lambda: dict(rtl_spec.PIPELINE_RANGES))
    checks: tuple[Callable[[PipelineConfig], str | None], ...] = ()
    branches: tuple[Branch, ...] = BRANCHES
    draw: Callable[[ConfigSpace, np.random.Generator, int, int, str], PipelineConfig] | None = None

    def legal(self, cfg: PipelineConfig) -> str | None:
        """Why ``cfg`` is outside this space (None when it is inside)."""
        for name, (lo, hi) in self.fields.items():
            v = getattr(cfg, name)
            if not lo <= v <= hi:
                return f"{name} = {v} outside {lo}..{hi}"
        for check in self.checks:
            why = check(cfg)
            if why:
                return why
        return None

    def classes(self, cfg: PipelineConfig) -> dict[str, set[str]]:
        """Coverpoint -> the bins ``cfg`` hits: modes, fraction order, shape, every branch
        it elaborates, and min / inner / max of every drawn field."""
        out: dict[str, set[str]] = {
            "config.modes": {f"{cfg.rounding}+{cfg.overflow}"},
            "config.frac_order": {frac_order(cfg)},
            "config.shape": {shape(cfg)},
            "config.branch": {b.key for b in self.branches if b.when(cfg)},
        }
        for name, (lo, hi) in self.fields.items():
            out[f"config.range.{name}"] = {_range_class(getattr(cfg, name), lo, hi)}
        return out

    def class_bins(self) -> dict[str, tuple[str, ...]]:
        """Every bin of :meth:`classes`."""
        out = {"config.modes": tuple(f"{r}+{o}" for r, o in MODES),
               "config.frac_order": FRAC_ORDERS, "config.shape": SHAPES,
               "config.branch": tuple(dict.fromkeys(b.key for b in self.branches
                                                    if b.never is None))}
        for name, (lo, hi) in self.fields.items():
            out[f"config.range.{name}"] = ("min", "inner", "max") if hi > lo + 1 else (
                ("min", "max") if hi > lo else ("min",))
        return out

    def sample(self, n: int, seed: int, *, max_dim: int = CI_MAX_DIM, prefix: str = "rnd",
               start: int = 0) -> list[PipelineConfig]:
        """``n`` legal configurations, named ``<prefix><seed>-<index>``: draws ``start`` ..
        ``start + n - 1`` of the stratified sequence of ``seed``."""
        if not 1 <= max_dim <= rtl_spec.FRAME_DIM_MAX:
            raise ConfigError(f"max_dim = {max_dim} outside 1..{rtl_spec.FRAME_DIM_MAX}")
        out = []
        for i in range(start, start + n):
            rng = np.random.default_rng([seed, i])
            name = f"{prefix}{seed}-{i:03d}"
            for _ in range(1000):
                cfg = (self.draw or _draw_two_point)(self, rng, i, max_dim, name)
                if cfg is not None and self.legal(cfg) is None:
                    out.append(cfg)
                    break
            else:  # pragma: no cover - the space would be (nearly) empty
                raise ConfigError(f"no legal configuration of {self.top} in 1000 draws")
        return out


def _biased(rng: np.random.Generator, lo: int, hi: int) -> int:
    """An integer of lo..hi, one time in three one of its ends (lo, lo + 1, hi - 1, hi)."""
    if hi <= lo:
        return lo
    if rng.random() < 1 / 3:
        return int(rng.choice(sorted({lo, min(lo + 1, hi), max(hi - 1, lo), hi})))
    return int(rng.integers(lo, hi + 1))


def _dim(rng: np.random.Generator, cap: int) -> int:
    """A maximum frame size of 1..cap: one time in three 1, 2, 3, 4 or 2^k - 1, else
    log-uniform."""
    if rng.random() < 1 / 3:
        special = [v for v in (1, 2, 3, 4, *((1 << k) - 1 for k in range(3, 17))) if v <= cap]
        return int(rng.choice(special))
    return max(1, min(cap, round(math.exp(rng.uniform(0.0, math.log(cap + 1))))))


def _fracs(rng: np.random.Generator, order: str, lo_g: int, hi_g: int, lo_o: int, hi_o: int
           ) -> tuple[int, int]:
    """(gain_frac_bits, offset_frac_bits) in the given order, small values favoured (F of
    0, 1 and 2 decide the rounding branches)."""
    def small(lo: int, hi: int) -> int:
        return int(rng.integers(lo, min(hi, lo + 2) + 1)) if rng.random() < 0.4 else \
            _biased(rng, lo, hi)
    if order == "equal":
        v = small(max(lo_g, lo_o), min(hi_g, hi_o))
        return v, v
    if order == "offset_above":
        g = small(lo_g, min(hi_g, hi_o - 1))
        return g, _biased(rng, max(lo_o, g + 1), hi_o) if rng.random() < 0.5 else \
            int(rng.integers(max(lo_o, g + 1), min(hi_o, g + 3) + 1))
    o = small(lo_o, min(hi_o, hi_g - 1))
    return (_biased(rng, max(lo_g, o + 1), hi_g) if rng.random() < 0.5 else
            int(rng.integers(max(lo_g, o + 1), min(hi_g, o + 3) + 1))), o


def _draw_two_point(space: ConfigSpace, rng: np.random.Generator, i: int, max_dim: int,
                    name: str) -> PipelineConfig | None:
    r = space.fields
    rounding, overflow = MODES[i % len(MODES)]
    order = FRAC_ORDERS[(i // len(MODES)) % len(FRAC_ORDERS)]
    shp = SHAPES[(i // 2) % len(SHAPES)]
    gf, of = _fracs(rng, order, *r["gain_frac_bits"], *r["offset_frac_bits"])
    cap = min(max_dim, r["max_width"][1], r["max_height"][1])
    w, h = _dim(rng, cap), _dim(rng, cap)
    if shp == "square":
        h = w
    elif w == h:
        return None
    elif (shp == "wide") != (w > h):
        w, h = h, w
    base = load_pipeline(space.base).to_dict()
    fields = {
        "adc_bits": _biased(rng, *r["adc_bits"]),
        "gain_int_bits": _biased(rng, *r["gain_int_bits"]),
        "gain_frac_bits": gf, "offset_frac_bits": of,
        "offset_int_bits": _biased(rng, *r["offset_int_bits"]),
        "out_bits": _biased(rng, *r["out_bits"]),
        "rounding": rounding, "overflow": overflow, "max_width": w, "max_height": h,
    }
    try:
        return PipelineConfig(**{**base, **fields, "name": name,
                                 "description": f"random legal configuration of {space.top}"})
    except ConfigError:
        return None


def _word_fits(cfg: PipelineConfig) -> str | None:
    if cfg.word_bits > WORD_BITS_MAX:
        return f"a {cfg.word_bits}-bit coefficient word (the testbenches pack at most 64)"
    return None


#: One space per top. A new top registers its own (:func:`register_space`).
SPACES: dict[str, ConfigSpace] = {"nuc_dpc_top": ConfigSpace("nuc_dpc_top",
                                                             checks=(_word_fits,))}


def register_space(space: ConfigSpace) -> None:
    """Add (or replace) the configuration space of ``space.top``."""
    SPACES[space.top] = space


def space(top: str) -> ConfigSpace:
    if top not in SPACES:
        raise ConfigError(f"no configuration space for {top!r}; known: {', '.join(SPACES)}")
    return SPACES[top]


# ---- samples -------------------------------------------------------------------------------

def coverage_of(sp: ConfigSpace, configs: Iterable[PipelineConfig]) -> dict[str, dict[str, int]]:
    """Coverpoint -> bin -> number of the configurations that hit it (every bin listed)."""
    out = {p: dict.fromkeys(bins, 0) for p, bins in sp.class_bins().items()}
    for cfg in configs:
        for point, hit in sp.classes(cfg).items():
            for b in hit:
                out[point][b] = out[point].get(b, 0) + 1
    return out


def cover(pool: Sequence[PipelineConfig], sp: ConfigSpace, points: Sequence[str],
          given: Iterable[PipelineConfig] = ()) -> list[PipelineConfig]:
    """The fewest configurations of ``pool`` (greedy, first in pool order on ties) that
    with ``given`` hit every bin of the coverpoints ``points`` that the pool can hit."""
    def hits(cfg: PipelineConfig) -> set[tuple[str, str]]:
        return {(p, b) for p, bins in sp.classes(cfg).items() if p in points for b in bins}

    done: set[tuple[str, str]] = set().union(*(hits(c) for c in given)) if given else set()
    reachable = set().union(*(hits(c) for c in pool)) - done
    picked: list[PipelineConfig] = []
    cand = [(c, hits(c)) for c in pool]
    while reachable:
        best, gain = max(((c, h & reachable) for c, h in cand), key=lambda t: len(t[1]))
        if not gain:
            break
        picked.append(best)
        reachable -= gain
    return picked


#: Coverpoints the CI sample covers (with the named configurations): every mode, fraction
#: order, shape and branch. The campaign sample also covers the ends of every width.
CI_POINTS = ("config.modes", "config.frac_order", "config.shape", "config.branch")


def named(top: str = "nuc_dpc_top") -> list[PipelineConfig]:
    """The named configurations of the top (``pipelines.toml``) inside its space."""
    sp = space(top)
    return [c for c in map(load_pipeline, pipeline_names()) if sp.legal(c) is None]


@functools.cache
def ci_sample(top: str = "nuc_dpc_top") -> tuple[PipelineConfig, ...]:
    """The fixed random sample CI runs through the top's testbench: from a pool of
    :data:`CI_POOL` draws of seed :data:`CI_SEED`, the fewest that with the named
    configurations cover every mode, fraction order, shape and branch."""
    sp = space(top)
    pool = sp.sample(CI_POOL, CI_SEED, max_dim=CI_MAX_DIM, prefix="ci")
    return tuple(cover(pool, sp, CI_POINTS, given=named(top)))


def campaign_sample(n: int = 36, seed: int = 1, top: str = "nuc_dpc_top",
                    max_dim: int = 4096) -> list[PipelineConfig]:
    """The first ``n`` draws of ``seed`` (the slow campaign: every mode x fraction order in
    18 draws, the ends of every width, maximum frames up to ``max_dim``)."""
    return space(top).sample(n, seed, max_dim=max_dim, prefix="rnd")


__all__ = ["BRANCHES", "CI_POINTS", "FRAC_ORDERS", "MODES", "SHAPES", "Branch", "ConfigSpace",
           "campaign_sample", "ci_sample", "cover", "coverage_of", "frac_order", "named",
           "register_space", "shape", "space"]
