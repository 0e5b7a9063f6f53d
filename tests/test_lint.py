"""``verilator --lint-only -Wall`` is clean for every RTL module and every configuration."""

from __future__ import annotations

import pytest

from irnuc.cosim import HDL_DIR, lint
from irnuc.nuc_fixed import load_pipeline, pipeline_names

MODULES = ("nuc_core", "dpc_core", "nuc_dpc_top")


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
    for path in sorted(HDL_DIR.glob("*.sv")):
        text = path.read_text()
        modules = [ln for ln in text.splitlines() if ln.startswith("module ")]
        assert len(modules) == 1, f"{path.name} defines {len(modules)} modules"
        assert modules[0].split()[1].rstrip("#(") == path.stem


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
