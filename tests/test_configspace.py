"""Random legal configurations (``irnuc.cosim.configspace``) and the parameter branches of
``hdl/`` they elaborate (``irnuc.cosim.elaborate``, Verilator's elaborated tree).

The branch conditions of ``configspace.BRANCHES`` are written in the configuration's terms;
Verilator's elaboration of every configuration that runs in CI (the named ones and the CI
sample) is the independent reference for the generate blocks, and the source files list
every generate block there is, so a new one cannot be left out.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from irnuc.cosim import configspace as cs
from irnuc.cosim import coverage, elaborate
from irnuc.cosim.sources import hdl_sources
from irnuc.nuc_fixed import PipelineConfig, rtl_spec
from irnuc.nuc_fixed.config import ConfigError

TOP = "nuc_dpc_top"


def _running() -> list[PipelineConfig]:
    """Every configuration tb_top runs on in CI."""
    return cs.named(TOP) + list(cs.ci_sample(TOP))


@functools.cache
def _elaborated(name: str) -> elaborate.Elaboration:
    cfg = {c.name: c for c in _running()}[name]
    return elaborate.elaborate(TOP, cfg)


def test_draws_are_seeded_legal_and_stratified() -> None:
    sp = cs.space(TOP)
    a = sp.sample(18, seed=5)
    assert [c.to_dict() for c in a] == [c.to_dict() for c in sp.sample(18, seed=5)]
    assert [c.to_dict() for c in a] != [c.to_dict() for c in sp.sample(18, seed=6)]
    for c in a:
        assert sp.legal(c) is None, c
        for name, (lo, hi) in rtl_spec.PIPELINE_RANGES.items():
            assert lo <= getattr(c, name) <= hi, (c.name, name)
        assert c.word_bits <= cs.WORD_BITS_MAX
    # 18 consecutive draws: every rounding x overflow mode x fraction order once.
    got = {((c.rounding, c.overflow), cs.frac_order(c)) for c in a}
    assert got == {(m, o) for m in cs.MODES for o in cs.FRAC_ORDERS}
    # The order of the fraction widths is the one the stratum names (from the fields).
    for c in a:
        gf, of = c.gain_frac_bits, c.offset_frac_bits
        assert cs.frac_order(c) == ("offset_above" if of > gf else "gain_above" if gf > of
                                    else "equal")
    assert {cs.shape(c) for c in a} == set(cs.SHAPES)


def test_legal_rejects_out_of_range_and_wide_words() -> None:
    sp = cs.space(TOP)
    base = sp.sample(1, seed=3)[0]
    # 16.16 gain and 32.0 offset: a 65-bit word (16 + 16 + 32 + 1), a 49-bit sum (legal).
    wide = PipelineConfig(**(base.to_dict() | {
        "adc_bits": 1, "gain_int_bits": 16, "gain_frac_bits": 16, "offset_int_bits": 32,
        "offset_frac_bits": 0}))
    assert wide.word_bits == 65
    assert "64" in (sp.legal(wide) or "")
    assert sp.legal(base.replace(max_width=1)) is None
    narrow = sp.fields | {"max_width": (1, 8)}
    assert "max_width" in (cs.ConfigSpace(TOP, fields=narrow).legal(
        base.replace(max_width=9)) or "")
    with pytest.raises(ConfigError, match="max_dim"):
        sp.sample(1, seed=1, max_dim=0)


def test_ci_sample_covers_every_class_with_the_named_configurations() -> None:
    sp = cs.space(TOP)
    sample = cs.ci_sample(TOP)
    assert 1 <= len(sample) <= 5
    cov = cs.coverage_of(sp, [*cs.named(TOP), *sample])
    for point in cs.CI_POINTS:
        assert cov[point], point
        missing = [b for b, n in cov[point].items() if n == 0]
        assert not missing, f"{point}: no configuration that runs hits {missing}"
    # Configurations the issue names: half_up with wrap, more offset than gain fraction
    # bits, a non-square maximum.
    running = _running()
    assert any(c.rounding == "half_up" and c.overflow == "wrap" for c in running)
    assert any(c.offset_frac_bits > c.gain_frac_bits for c in running)
    assert any(c.max_width != c.max_height for c in running)


def test_cover_is_greedy_and_complete_on_a_toy_pool() -> None:
    sp = cs.space(TOP)
    pool = sp.sample(30, seed=11)
    picked = cs.cover(pool, sp, ("config.modes",))
    modes = {(c.rounding, c.overflow) for c in picked}
    assert modes == {(c.rounding, c.overflow) for c in pool}
    assert len(picked) == len(modes)  # one mode per draw: the fewest is one per mode


def test_source_generate_blocks_are_all_listed() -> None:
    """Every labelled generate block of the top's sources is a listed branch, and every
    listed block exists (the list can neither miss a new block nor keep a stale one)."""
    src: dict[str, set[str]] = {}
    for path in hdl_sources(TOP):
        for module, blocks in elaborate.source_blocks(path).items():
            src.setdefault(module, set()).update(blocks)
    listed = {(b.module, b.block) for b in cs.BRANCHES if b.block}
    in_src = {(m, blk) for m, blocks in src.items() for blk in blocks}
    assert in_src - listed == set(), "generate blocks missing from configspace.BRANCHES"
    assert listed - in_src == set(), "branches listed that the sources do not have"
    files = {p.stem: p.read_text() for p in hdl_sources(TOP)}
    for b in cs.BRANCHES:
        if b.text:
            assert b.text in files[b.module], (b.key, b.text)


def test_source_blocks_nest_as_written(tmp_path) -> None:
    sv = tmp_path / "m.sv"
    sv.write_text("module m #(parameter int P = 1) ();\n"
                  "  if (P > 0) begin : gen_a\n    always_comb begin\n    end\n"
                  "    if (P > 1) begin : gen_b\n    end\n  end else begin : gen_c\n  end\n"
                  "  // begin : gen_comment\nendmodule\n")
    assert elaborate.source_blocks(sv) == {"m": {"gen_a", "gen_a/gen_b", "gen_c"}}


@pytest.mark.cosim
@pytest.mark.parametrize("config", [c.name for c in _running()])
def test_branch_conditions_match_verilator(config: str) -> None:
    """Each generate block's condition says elaborated exactly when Verilator elaborates
    it for this configuration."""
    cfg = {c.name: c for c in _running()}[config]
    e = _elaborated(config)
    wrong = [(b.key, b.when(cfg)) for b in cs.BRANCHES if b.block
             and b.when(cfg) != (b.block in e.blocks.get(b.module, frozenset()))]
    assert not wrong, f"{config}: condition != elaboration for {wrong}"


def test_every_branch_is_elaborated_by_a_configuration_that_runs() -> None:
    running = _running()
    for b in cs.BRANCHES:
        hit = [c.name for c in running if b.when(c)]
        if b.never:
            assert not hit, (b.key, b.never)
        else:
            assert hit, f"{b.key}: no configuration that runs in CI elaborates it"


def test_digest_tells_elaborations_apart() -> None:
    """The canonical digest ignores node addresses and source positions only."""
    a = {"type": "MODULE", "addr": "(B)", "loc": "a,1:1", "name": "m",
         "stmtsp": [{"type": "VAR", "addr": "(C)", "dtypep": "(B)", "name": "x"}]}
    b = {"type": "MODULE", "addr": "(Z)", "loc": "b,9:9", "name": "m",
         "stmtsp": [{"type": "VAR", "addr": "(Y)", "dtypep": "(Z)", "name": "x"}]}
    c = {**b, "stmtsp": [{"type": "VAR", "addr": "(Y)", "dtypep": "(Y)", "name": "x"}]}
    assert elaborate._tree_digest(a) == elaborate._tree_digest(b)
    assert elaborate._tree_digest(a) != elaborate._tree_digest(c)


# ---- the coverage model's bins for the new stimulus ------------------------------------------

def test_dpc_arith_unreachable_by_enumeration() -> None:
    """Reachability of (n, residue, range) from value intervals, against brute force over
    every multiset of n values of a small code range."""
    from itertools import combinations_with_replacement

    out_bits, values = 3, [(0, 1), (6, 7)]
    codes = [v for a, b in values for v in range(a, b + 1)]
    for n in (1, 2, 3):
        seen = {(s % n, coverage.dpc_range(s, n, out_bits))
                for combo in combinations_with_replacement(codes, n) for s in [sum(combo)]}
        for r in range(n):
            for rng in coverage.DPC_RANGES:
                assert coverage.dpc_arith_unreachable(n, r, rng, out_bits, values) == (
                    (r, rng) not in seen), (n, r, rng)


def test_nuc_output_intervals_by_enumeration() -> None:
    """The NUC output intervals of small random configurations contain every output of
    every (x, g, o), enumerated with the golden model."""
    from irnuc.nuc_fixed import nuc_core

    for cfg in cs.space(TOP).sample(12, seed=9, max_dim=8):
        if cfg.adc_bits + cfg.gain_bits + cfg.offset_bits > 18:
            continue
        x, g, o = np.meshgrid(np.arange(1 << cfg.adc_bits), np.arange(1 << cfg.gain_bits),
                              np.arange(-(1 << (cfg.offset_bits - 1)),
                                        1 << (cfg.offset_bits - 1)), indexing="ij")
        y = np.unique(nuc_core(x.ravel(), g.ravel(), o.ravel(), cfg))
        iv = coverage.nuc_output_intervals(cfg)
        inside = np.zeros(y.size, bool)
        for a, b in iv:
            inside |= (y >= a) & (y <= b)
        assert inside.all(), (cfg.name, iv, y[~inside][:5])
