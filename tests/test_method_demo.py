"""Issue 38's proof that a method is a thing: ``offset_only`` (tests/demo_method), a registry
module and an RTL front, registered at run time, is a method of every layer without a change
to a production file: the configuration and its checks, the golden model (against the
two-point top at unity gain, an independent path), the generated SystemVerilog (the files a
real addition regenerates are exactly docs/architecture.md's list) and, in the bulk harness,
``method_dpc_top`` built with its front, bit for bit."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from irnuc.common.errors import ConfigError, UserError
from irnuc.cosim import spec_files
from irnuc.cosim.sources import HDL_DIR, top_parameters
from irnuc.nuc_fixed import PipelineConfig, load_pipeline, methods, nuc_dpc_top, pack_words, rtl_spec
from irnuc.nuc_fixed.method_top import MethodCoefficients, method_top
from irnuc.nuc_fixed.methods import rtl as methods_rtl
from tests.demo_method import offset_only


@pytest.fixture(scope="module")
def demo():
    methods.register_method(offset_only.METHOD)
    try:
        yield offset_only.METHOD
    finally:
        methods.unregister_method(offset_only.METHOD.name)


def _cfg(**changes: object) -> PipelineConfig:
    d = load_pipeline("typical14").to_dict()
    return PipelineConfig(**{**d, "name": "offset14", "method": "offset_only",
                             "max_width": 64, "max_height": 64, **changes})


def _coeffs(cfg: PipelineConfig, shape: tuple[int, int], rng: np.random.Generator
            ) -> MethodCoefficients:
    half = 1 << (cfg.offset_bits - 1)
    return MethodCoefficients(cfg, {"coeffs": {
        "offset": rng.integers(-half, half, size=shape), "bad": rng.random(shape) < 0.1}})


def test_the_method_is_known_to_the_configuration(demo) -> None:
    cfg = _cfg()
    assert cfg.base is demo and not cfg.stages and not cfg.plain
    assert rtl_spec.METHOD.codes["offset_only"] == len(methods.BASES) - 1
    mem = cfg.memories["coeffs"]
    assert [(f.name, f.lsb, f.width) for f in mem.fields] == [("offset", 0, 16), ("bad", 16, 1)]
    assert cfg.registers == {} and methods.needs(cfg) == ()
    # Its checks and the composition rules apply.
    with pytest.raises(ConfigError, match="cannot hold the unity gain"):
        _cfg(gain_int_bits=0, gain_frac_bits=16)
    with pytest.raises(ConfigError, match="blind_drift composes only with"):
        methods.parse_method("offset_only+blind_drift")
    ffc = load_pipeline("ffc14").to_dict()
    cfg_ffc = PipelineConfig(**{**ffc, "name": "offsetffc", "method": "offset_only+ffc"})
    with pytest.raises(UserError, match="not in RTL yet"):  # the golden model has it only
        top_parameters("method_ffc_top", cfg_ffc)


def test_the_golden_model_is_the_two_point_top_at_unity_gain(demo) -> None:
    cfg = _cfg()
    rng = np.random.default_rng(38)
    c = _coeffs(cfg, (7, 9), rng)
    raw = rng.integers(0, 1 << cfg.adc_bits, size=(3, 7, 9))
    got = method_top(raw, c).y
    f = c.fields["coeffs"]
    plain = load_pipeline("typical14").replace(max_width=64, max_height=64)
    words = pack_words(np.full((7, 9), 1 << cfg.gain_frac_bits), f["offset"], f["bad"], plain)
    assert np.array_equal(got, nuc_dpc_top(raw, words, plain))


def _design(tmp_path: Path) -> tuple[Path, dict[Path, str]]:
    """A copy of hdl/ with the method's front and every generated file rewritten."""
    hdl = tmp_path / "hdl"
    shutil.copytree(HDL_DIR, hdl, ignore=shutil.ignore_patterns("__pycache__", "*.py"))
    shutil.copy(offset_only.FRONT, hdl / offset_only.FRONT.name)
    design = spec_files.design_files(hdl)
    for p, text in design.items():
        p.write_text(text)
    return hdl, design


def test_the_generated_files_are_the_walkthrough_list(demo, tmp_path) -> None:
    """What `spec_files --write` changes for a new method without new parameters: the
    package (method_e, its word), irnuc_method_pkg's functions, frame_coefficients and the
    package probe, and the new front's own header (docs/architecture.md, "Add a method")."""
    hdl, design = _design(tmp_path)
    changed = {p.name for p, text in design.items()
               if not (HDL_DIR / p.name).is_file() or (HDL_DIR / p.name).read_text() != text}
    assert changed == {"irnuc_pkg.sv", "irnuc_method_pkg.sv", "frame_coefficients.sv",
                       "method_offset_only.sv"}
    assert rtl_spec.sv_probe() != spec_files.PROBE.read_text()
    pkg = (hdl / "irnuc_pkg.sv").read_text()
    code = len(methods.BASES) - 1
    assert f"MethodOffsetOnly = 3'd{code}" in pkg and "coef_offset_only_bits" in pkg
    mpkg = (hdl / "irnuc_method_pkg.sv").read_text()
    # The new method is each function's last case (the default), table_interp now named.
    assert "MethodTableInterp:" in mpkg and "return coef_offset_only_bits(offset_bits);" in mpkg
    frame = (hdl / "frame_coefficients.sv").read_text()
    assert "method_offset_only #(" in frame and "gen_offset_only" in frame
    assert methods_rtl.parameters_of("method_offset_only")[:4] == [
        "GainIntBits", "GainFracBits", "OffsetIntBits", "OffsetFracBits"]


@pytest.mark.slow
@pytest.mark.cosim
def test_method_dpc_top_corrects_it_bit_for_bit(demo, tmp_path) -> None:
    """method_dpc_top of the copy with the new front, in the bulk harness: every pixel of
    frames of random codes and offsets against the golden model."""
    from irnuc.cosim.bulk import build_bulk
    from irnuc.cosim.method_bulk import check_method_bulk, run_method_bulk

    hdl, _ = _design(tmp_path)
    cfg = _cfg()
    rng = np.random.default_rng(7)
    c = _coeffs(cfg, (6, 10), rng)
    raw = rng.integers(0, 1 << cfg.adc_bits, size=(4, 6, 10))
    bld = build_bulk(cfg, top="method_dpc_top", hdl_dir=hdl)
    res = run_method_bulk(bld, c, raw, stall_percent=20, seed=3)
    chk = check_method_bulk(res, c, raw)
    assert chk.compared == raw.size and chk.mismatches == 0 and not chk.missing, chk.lines
