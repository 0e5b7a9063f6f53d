"""The shared-constants spec (``irnuc.nuc_fixed.rtl_spec``): the generated SystemVerilog is
current, the spec's Python functions agree with independent derivations, and every Python
user reads the spec (one error class, no shadowed module). The RTL side is read back by
simulation in ``cocotb_tests/tb_pkg.py``."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from irnuc.cosim import spec_files
from irnuc.nuc_fixed import load_pipeline, pack_words, pipeline_names, rtl_spec


def test_generated_files_are_current() -> None:
    assert spec_files.stale() == [], "python -m irnuc.cosim.spec_files --write"


def test_a_changed_spec_makes_the_files_stale(monkeypatch) -> None:
    """The staleness check can fail: a new constant is missing from both files."""
    extra = rtl_spec.Constant("TestOnlyBits", 3, "a constant added to the spec")
    monkeypatch.setattr(rtl_spec, "CONSTANTS", (*rtl_spec.CONSTANTS, extra))
    assert set(spec_files.stale()) == {spec_files.PACKAGE, spec_files.PROBE}
    assert "localparam int unsigned TestOnlyBits = 3;" in rtl_spec.sv_package_block()
    assert "const_test_only_bits_o" in rtl_spec.sv_probe()
    assert rtl_spec.probe_values()["const_test_only_bits_o"] == 3


def test_every_item_has_a_probe_port() -> None:
    probe = rtl_spec.sv_probe()
    for port in rtl_spec.probe_values():
        assert f" {port}," in probe or f" {port}\n" in probe, port
    pkg = spec_files.PACKAGE.read_text()
    for c in rtl_spec.CONSTANTS:
        assert f"localparam int unsigned {c.name} = {c.value};" in pkg
    for r in rtl_spec.RANGES:  # every range is asserted by a module of the design
        used = [p.name for p in spec_files.PACKAGE.parent.glob("*.sv")
                if p.name != "irnuc_pkg.sv" and f"{r.name}Max" in p.read_text()]
        assert used, f"no module of hdl/ asserts {r.name}Max"


@pytest.mark.parametrize("bits", range(1, 65))
def test_mul_chunks_against_ceil(bits: int) -> None:
    assert rtl_spec.mul_chunks(bits) == math.ceil(bits / 17)
    assert rtl_spec.mul_parts(bits, 40) == math.ceil(bits / 17) * 3


def test_dpc_reciprocal_against_fractions() -> None:
    for b in range(1, 25):
        k = rtl_spec.dpc_recip_shift(b)
        assert k == b + 6
        for n in range(1, 9):
            r = rtl_spec.dpc_recip(b, n)
            assert r == math.ceil(Fraction(2**k, n))
            # exact division of every M < 2^(B+3) (checked at the largest M)
            m = 2 ** (b + 3) - 1
            assert (m * r) >> k == m // n
        assert rtl_spec.dpc_recip(b, 0) == 0


def test_clog2_is_systemverilogs() -> None:
    assert [rtl_spec.clog2(n) for n in (0, 1, 2, 3, 4, 5, 9, 1024, 1025)] == \
        [0, 0, 1, 2, 2, 3, 4, 10, 11]


def test_coefficient_layout_against_pack_words() -> None:
    """The layout the spec gives is where pack_words puts each field (one-hot fields)."""
    for name in pipeline_names():
        cfg = load_pipeline(name)
        lay = rtl_spec.COEF_WORD.layout(GainBits=cfg.gain_bits, OffsetBits=cfg.offset_bits)
        assert cfg.word_fields == lay and cfg.word_bits == sum(w for _, w in lay.values())
        w = pack_words(np.array([1]), np.array([0]), np.array([False]), cfg)
        assert int(w[0]) == 1 << lay["gain"][0]
        w = pack_words(np.array([0]), np.array([1]), np.array([False]), cfg)
        assert int(w[0]) == 1 << lay["offset"][0]
        w = pack_words(np.array([0]), np.array([0]), np.array([True]), cfg)
        assert int(w[0]) == 1 << lay["bad"][0]
    with pytest.raises(TypeError, match="OffsetBits"):
        rtl_spec.COEF_WORD.layout(GainBits=3)


def test_stage_model_of_typical14() -> None:
    """typical14 (A = 14, GW = 16, B = 14): one partial product in nuc_core (two DSP
    registers, one sum stage: clog2(2)), the DPC's mask register, 9 leaves in dpc_core (4
    stages) and 1 x 2 partial products of its divider (two DSP registers, one product
    stage), as docs/rtl.md lists."""
    s = rtl_spec.pipeline_stages("nuc_dpc_top", 14, 16, 14)
    assert s == ["top_input", "nuc_input", "nuc_product_1", "nuc_product_2", "nuc_sum",
                 "nuc_round", "nuc_output", "dpc_input", "dpc_window", "dpc_mask",
                 "dpc_sum_1", "dpc_sum_2", "dpc_sum_3", "dpc_sum_4", "dpc_multiply_1",
                 "dpc_multiply_2", "dpc_product", "dpc_output", "flush"]
    with pytest.raises(ValueError, match="no stage model"):
        rtl_spec.pipeline_stages("other", 14, 16, 14)


def test_python_users_read_the_spec() -> None:
    from irnuc.nuc_fixed import config

    assert config.ROUNDING_MODES is rtl_spec.ROUNDING_MODES
    assert config.OVERFLOW_MODES is rtl_spec.OVERFLOW_MODES
    lo, hi = rtl_spec.PIPELINE_RANGES["max_width"]
    assert (lo, hi) == (1, rtl_spec.FRAME_DIM_MAX)
    with pytest.raises(ValueError, match=f"max_width .*{hi}"):
        load_pipeline("minimal").replace(max_width=hi + 1)


def test_one_config_error_and_model_validate_is_the_module() -> None:
    import importlib

    from irnuc.common.errors import ConfigError
    from irnuc.model import validate as model_validate
    from irnuc.nuc_fixed.config import ConfigError as PipelineConfigError

    assert model_validate.ConfigError is ConfigError is PipelineConfigError
    assert importlib.import_module("irnuc.model.validate") is model_validate
    assert hasattr(model_validate, "check_scalar")
