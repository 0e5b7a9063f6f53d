"""``verilator --lint-only -Wall`` is clean for every RTL module and every configuration."""

from __future__ import annotations

import pytest

from irnuc.cosim import HDL_DIR, MODULE_FILES, SIM_HDL_DIR, lint
from irnuc.nuc_fixed import load_pipeline, methods, pipeline_names

#: Every design module (the building blocks with the sizes they get in nuc_dpc_top, see
#: irnuc.cosim.top_parameters), the simulation-only package probe and batch transactor.
MODULES = ("nuc_core", "dpc_core", "nuc_dpc_top", "dpc_ctrl", "irnuc_spill_register",
           "irnuc_stream_assert", "irnuc_frame_assert", "irnuc_add_tree", "irnuc_mul_parts",
           "irnuc_line_buffer", "irnuc_pkg_probe", "nuc_dpc_batch", "irnuc_dsp_mul",
           "irnuc_round", "irnuc_clip", "dpc_tail")
#: Each method's front (hdl/<MethodSpec.rtl_module>.sv), with the methods it serves
#: (tc_offset's serves tc_housing too, with its Housing flag).
FRONTS = {f: tuple(m.name for m in methods.BASES.values() if m.rtl_module == f)
          for f in dict.fromkeys(m.rtl_module for m in methods.BASES.values())}
#: The modules of the correction methods, linted with every method configuration.
METHOD_MODULES = ("method_dpc_top", "frame_coefficients", "method_core", "pwl_core",
                  "quad_core", "tc_poly", "tc_reading", "table_interp", "interp_weight",
                  *FRONTS)
#: The AXI wrapper of the two-point core and its parts, linted with every two-point
#: configuration (their parameters are widths and the frame limit, not the modes); the
#: protocol checkers take no configuration (once). Its core (AXI_CORE) is linted with every
#: method it wraps, its FFC side (irnuc_axis_ffc) with the ffc stage (STAGE_MODULES).
AXI_MODULES = ("irnuc_axis_top", "irnuc_axil_regs", "irnuc_axis_framer", "irnuc_axis_buffer")
AXI_CHECKERS = ("irnuc_axis_assert", "irnuc_axil_assert", "irnuc_axil_regs_check",
                "irnuc_assert_armed")
AXI_CORE = ("irnuc_axis_core",)
#: The register block generated from the map (no parameter: once), the FuseSoC core's
#: smoke testbench (irnuc_axis_top at its defaults: once) and the FFC request at its
#: defaults (once; inside irnuc_axil_regs with each FFC build's reading width, 0 included).
AXI_ONCE = ("irnuc_axil_regblock", "irnuc_axis_top_tb", "irnuc_ffc_trigger")
#: table_interp's selection in the wrapper, linted with the table_interp configuration.
AXI_TABLE = ("irnuc_axis_table",)
#: The modules of the stages (blind_drift, ffc) and the stages each serves, linted with every
#: configuration of those stages and the mode variants.
STAGE_MODULES = {"method_drift_top": ("blind_drift",), "blind_drift": ("blind_drift",),
                 "drift_sub": ("blind_drift",), "core_sum": ("blind_drift", "ffc"),
                 "core_out": ("blind_drift", "ffc"), "method_ffc_top": ("ffc",),
                 "ffc_ctrl": ("ffc",), "ffc_mean": ("ffc",), "ffc_refresh": ("ffc",),
                 "ffc_sums": ("ffc",), "irnuc_axis_ffc": ("ffc",)}
#: Each method module and the methods it serves (method_dpc_top: every one).
_METHOD_OF = {"pwl_core": ("piecewise",), "quad_core": ("quadratic",),
              "tc_poly": ("tc_offset", "tc_housing"), "tc_reading": ("tc_offset", "tc_housing"),
              "table_interp": ("table_interp",), "interp_weight": ("table_interp",), **FRONTS}


def _configs() -> list[tuple[str, dict[str, object]]]:
    named = [(n, {}) for n in pipeline_names()]
    # Mode variants: every generate branch (rounding, overflow) is elaborated somewhere.
    variants = [("minimal", {"rounding": r, "overflow": o})
                for r in ("truncate", "half_up", "half_even") for o in ("saturate", "wrap")]
    return named + variants


@pytest.mark.parametrize("module", MODULES)
@pytest.mark.parametrize(("config", "changes"), _configs())
def test_lint_clean(module: str, config: str, changes: dict[str, object]) -> None:
    cfg = load_pipeline(config)
    cfg = cfg.replace(**changes) if changes else cfg
    proc = lint(module, cfg)
    report = proc.stdout + proc.stderr
    assert proc.returncode == 0 and "%Warning" not in report and "%Error" not in report, report


def _method_cases() -> list[tuple[str, str, dict[str, object]]]:
    """(module, configuration, changes): every method module with every configuration of
    its methods, and the mode variants that reach the other generate branches (tc_offset of
    order 1 without tc2/tg2, every rounding and overflow mode)."""
    from irnuc.nuc_fixed import PipelineConfig

    names = [n for n in pipeline_names(method=None) if "+" not in load_pipeline(n).method]
    cases = []
    for module in METHOD_MODULES:
        for n in names:
            cfg = load_pipeline(n)
            if cfg.base_method in _METHOD_OF.get(module, (cfg.base_method,)):
                cases.append((module, n, {}))
    d = load_pipeline("tcgain14").to_dict()
    d["formats"] = {k: v for k, v in d["formats"].items() if k not in ("tc2", "tg2")}
    order1 = PipelineConfig(**{**d, "tc_order": 1, "name": "tcgain14_order1"})
    for module in ("method_dpc_top", "tc_poly", "tc_reading", "method_tc_offset"):
        cases.append((module, order1, {}))  # type: ignore[arg-type]
    # tc_housing of order 1 with tc_gain (u2 not formed: the housing's products alone).
    d = load_pipeline("tchousing14").to_dict()
    d["formats"] = {k: v for k, v in d["formats"].items() if k != "tc2"}
    d["formats"]["tg1"] = load_pipeline("tcgain14").to_dict()["formats"]["tg1"]
    h1 = PipelineConfig(**{**d, "tc_order": 1, "tc_gain": True, "name": "tchousing14_order1"})
    for module in ("method_dpc_top", "tc_poly", "tc_reading", "method_tc_offset"):
        cases.append((module, h1, {}))  # type: ignore[arg-type]
    for module in ("method_dpc_top", "pwl_core", "quad_core"):
        for r in ("truncate", "half_even"):
            cases.append((module, "piecewise14" if module != "quad_core" else "quadratic14",
                          {"rounding": r, "overflow": "wrap"}))
    cases.append(("interp_weight", "table14",
                  {"formats": {"weight": {"rounding": "half_even", "frac_bits": 0}}}))
    return cases


@pytest.mark.parametrize(("module", "config", "changes"), _method_cases())
def test_lint_clean_methods(module: str, config, changes: dict[str, object]) -> None:
    cfg = config if not isinstance(config, str) else load_pipeline(config)
    cfg = cfg.replace(**changes) if changes else cfg
    proc = lint(module, cfg)
    report = proc.stdout + proc.stderr
    assert proc.returncode == 0 and "%Warning" not in report and "%Error" not in report, report


def _axi_method_configs() -> list[str]:
    """The method configurations irnuc_axis_top is built around (every base method without
    a stage, the plain two_point aside) and those it builds a stage top for
    (method_ffc_top, method_drift_top)."""
    from irnuc.cosim.sources import stage_top

    out = []
    for n in pipeline_names(method=None):
        cfg = load_pipeline(n)
        if (not cfg.stages and not cfg.plain) \
                or stage_top(cfg) in ("method_ffc_top", "method_drift_top"):
            out.append(n)
    return out


@pytest.mark.parametrize(("module", "config"),
                         [(m, c) for m in AXI_MODULES for c in pipeline_names()]
                         + [(m, c) for m in ("irnuc_axis_top", *AXI_CORE)
                            for c in _axi_method_configs()]
                         + [(m, "minimal") for m in AXI_CORE]
                         + [(m, "table14") for m in AXI_TABLE]
                         + [(m, "minimal") for m in (*AXI_CHECKERS, *AXI_ONCE)])
def test_lint_clean_axi(module: str, config: str) -> None:
    proc = lint(module, load_pipeline(config))
    report = proc.stdout + proc.stderr
    assert proc.returncode == 0 and "%Warning" not in report and "%Error" not in report, report


def _stage_cases() -> list[tuple[str, str, dict[str, object]]]:
    """(module, configuration, changes): every stage module with every configuration of
    its stages, and variants reaching the other rounding and overflow branches and the
    ffc pass/hold modes."""
    names = [n for n in pipeline_names(method=None) if load_pipeline(n).stages]
    cases = [(m, n, {}) for m, stages in STAGE_MODULES.items() for n in names
             if set(load_pipeline(n).stages) & set(stages)]
    for m in ("method_drift_top", "blind_drift"):
        cases.append((m, "drift14", {"formats": {"drift": {"rounding": "truncate",
                                                           "overflow": "wrap"}}}))
        cases.append((m, "drift14", {"rounding": "half_even", "overflow": "wrap"}))
    cases.append(("method_ffc_top", "ffc14", {"ffc_output": "pass", "ffc_frames": 1,
                                              "formats": {"ffc": {"rounding": "half_even",
                                                                  "overflow": "wrap"}}}))
    cases.append(("method_ffc_top", "quadffc14", {"ffc_output": "hold", "rounding": "truncate"}))
    cases.append(("irnuc_axis_top", "ffc14", {"ffc_output": "pass", "ffc_frames": 1}))
    cases.append(("irnuc_axis_ffc", "ffc14", {"ffc_output": "pass", "ffc_frames": 1}))
    return cases


@pytest.mark.parametrize(("module", "config", "changes"), _stage_cases())
def test_lint_clean_stages(module: str, config: str, changes: dict[str, object]) -> None:
    cfg = load_pipeline(config)
    cfg = cfg.replace(**changes) if changes else cfg
    proc = lint(module, cfg)
    report = proc.stdout + proc.stderr
    assert proc.returncode == 0 and "%Warning" not in report and "%Error" not in report, report


def test_one_module_per_file() -> None:
    """One module (or the one package) per file, named like the file; every file linted."""
    paths = sorted(HDL_DIR.glob("*.sv")) + sorted(SIM_HDL_DIR.glob("*.sv"))
    for path in paths:
        lines = path.read_text().splitlines()
        units = [ln for ln in lines if ln.startswith(("module ", "package "))]
        assert len(units) == 1, f"{path.name} defines {len(units)} modules or packages"
        assert units[0].split()[1].rstrip("#(;") == path.stem
        if units[0].startswith("package "):
            continue
        linted = (*MODULES, *METHOD_MODULES, *AXI_MODULES, *AXI_CHECKERS, *AXI_CORE,
                  *AXI_TABLE, *AXI_ONCE, *STAGE_MODULES)
        assert path.stem in linted, f"{path.name} is not in the lint list"
        assert path.name in MODULE_FILES[path.stem], f"{path.name} is not in MODULE_FILES"


def test_lint_catches_a_warning(tmp_path) -> None:
    """The lint check can fail: an unused input is reported under -Wall."""
    import subprocess

    from irnuc.cosim.verilator import verilator_env, verilator_executable

    src = tmp_path / "bad.sv"
    src.write_text("module bad (input logic a_i, output logic b_o);\n"
                   "  assign b_o = 1'b0;\nendmodule\n")
    proc = subprocess.run([str(verilator_executable()), "--lint-only", "-Wall", str(src)],
                          capture_output=True, text=True, env=verilator_env(), check=False)
    assert proc.returncode != 0 and "UNUSED" in proc.stdout + proc.stderr
