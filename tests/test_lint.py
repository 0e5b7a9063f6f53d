"""``verilator --lint-only -Wall`` is clean for every RTL module and every configuration."""

from __future__ import annotations

import pytest

from irnuc.cosim import HDL_DIR, MODULE_FILES, SIM_HDL_DIR, lint
from irnuc.nuc_fixed import load_pipeline, pipeline_names

#: Every design module (the building blocks with the sizes they get in nuc_dpc_top, see
#: irnuc.cosim.top_parameters), the simulation-only package probe and batch transactor.
MODULES = ("nuc_core", "dpc_core", "nuc_dpc_top", "dpc_ctrl", "irnuc_spill_register",
           "irnuc_stream_assert", "irnuc_frame_assert", "irnuc_add_tree", "irnuc_mul_parts",
           "irnuc_line_buffer", "irnuc_pkg_probe", "nuc_dpc_batch")


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
        assert path.stem in MODULES, f"{path.name} is not in the lint list"
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
