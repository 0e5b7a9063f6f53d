"""Every documented command has a test that runs its default path through the command line.

`irnuc mutate` exactly as documented (coverage on, the default) once ran its whole campaign
and then ended in a traceback: the glue after a command's work runs only on the path a test
takes. The table below names, per command, the test that runs it through the command line
on a small configuration, and the flags that would leave its default path (skip a phase
of the command). This module checks that the table covers every command of the parser and
of README's table, and that each named test calls its command without those flags.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from irnuc.cli import build_parser

TESTS = Path(__file__).resolve().parent
REPO = TESTS.parent

#: command -> (test file, the test function or fixture that runs it through the CLI)
DEFAULT_PATH_TESTS: dict[str, tuple[str, str]] = {
    "frames": ("test_cli.py", "test_frames_npz_contents"),
    "noise": ("test_noise_metrics.py", "test_noise_command_prints_and_writes_the_figures"),
    "calibrate": ("test_frame_file.py", "test_calibrate_and_correct_read_model_frames_and_sequences"),
    "correct": ("test_frame_file.py", "test_calibrate_and_correct_read_model_frames_and_sequences"),
    "sweep": ("test_sweep.py", "test_sweep_cli"),
    "report": ("test_report_e2e.py", "tiny_run"),
    "precision": ("test_precision.py", "test_cli_writes_the_report"),
    "synth": ("test_synth.py", "test_irnuc_synth_minimal_and_its_cache"),
    "mutate": ("test_mutate.py", "test_small_campaign_cache_and_cli"),
    "study": ("test_methods_studies.py", "test_study_cli"),
    "regmap": ("test_registers.py", "test_regmap_command_writes_one_build"),
    "formal": ("test_formal.py", "test_quick_campaign"),
    "traffic": ("test_traffic.py", "test_command_line_runs_the_traffic_and_closes_its_bins"),
}

#: study name -> (test file, the test function or fixture that runs ``irnuc study NAME``
#: through the command line): a study whose own glue (a text table, its figure) runs only
#: from there.
STUDY_TESTS: dict[str, tuple[str, str]] = {
    "ffc_interval": ("test_methods_studies.py", "test_study_cli"),
    "housing": ("test_housing_study.py", "housing_run"),
}

#: Flags that skip a phase of a command (its default path runs it).
OFF_PATH = {
    "mutate": ("--no-coverage", "--configs", "--list"),
    "report": ("--no-cosim", "--junit"),
    "sweep": ("--no-figures",),
    "calibrate": ("--plan",),
    "formal": ("--list", "--no-faults"),
    "traffic": ("--no-coverage",),
}


def _commands_in_readme() -> set[str]:
    text = (REPO / "README.md").read_text()
    return set(re.findall(r"^\| `irnuc ([a-z]+)` \|", text, flags=re.MULTILINE))


def _cli_calls(func: ast.AST, command: str) -> list[list[str]]:
    """The string literals of every list in ``func`` that starts a command line of
    ``command`` (``["mutate", ...]`` or ``[str(irnuc), "mutate", ...]``)."""
    calls = []
    for node in ast.walk(func):
        if not isinstance(node, ast.List) or not node.elts:
            continue
        words = [e.value if isinstance(e, ast.Constant) and isinstance(e.value, str) else None
                 for e in node.elts]
        head = words[:2]
        if command in head and (head[0] == command or head[0] is None):
            calls.append([w for w in words if w is not None])
    return calls


def test_every_documented_command_has_a_default_path_test() -> None:
    _, commands = build_parser()
    assert set(commands) == _commands_in_readme(), "README's command table and the parser"
    assert set(DEFAULT_PATH_TESTS) == set(commands)


@pytest.mark.parametrize("command", sorted(DEFAULT_PATH_TESTS))
def test_the_named_test_runs_the_default_path(command: str) -> None:
    file, name = DEFAULT_PATH_TESTS[command]
    tree = ast.parse((TESTS / file).read_text())
    funcs = [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef) and n.name == name]
    assert len(funcs) == 1, f"{file}::{name} not found"
    calls = _cli_calls(funcs[0], command)
    assert calls, f"{file}::{name} does not run `irnuc {command}`"
    off = OFF_PATH.get(command, ())
    assert any(not set(c) & set(off) for c in calls), (
        f"{file}::{name} runs `irnuc {command}` only with {off}: not its default path")


@pytest.mark.parametrize("study", sorted(STUDY_TESTS))
def test_the_named_test_runs_the_study(study: str) -> None:
    from irnuc.cli.study import STUDIES

    assert study in STUDIES
    file, name = STUDY_TESTS[study]
    tree = ast.parse((TESTS / file).read_text())
    funcs = [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef) and n.name == name]
    assert len(funcs) == 1, f"{file}::{name} not found"
    calls = [c for c in _cli_calls(funcs[0], "study") if study in c]
    assert calls, f"{file}::{name} does not run `irnuc study {study}`"


def test_the_check_can_fail() -> None:
    # A command line with a flag off the default path is not counted.
    tree = ast.parse('def f():\n    main(["mutate", "--no-coverage", "--out", "o"])\n')
    calls = _cli_calls(tree, "mutate")
    assert calls == [["mutate", "--no-coverage", "--out", "o"]]
    assert not any(not set(c) & set(OFF_PATH["mutate"]) for c in calls)
