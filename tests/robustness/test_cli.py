"""Every command-line case of the ``cli_*.py`` tables: exit 2, one line naming the
input, before the work, the output name untouched."""

from __future__ import annotations

import importlib
from pathlib import Path
from typing import Any

import pytest

from robustness.harness import (
    CLI_CASES,
    COMMANDS,
    Case,
    case_argv,
    load_tables,
    out_path,
    run_cli,
    snapshot,
    tripwire,
    undo_read_only,
)


def _cli_params() -> list[Any]:
    out = []
    for c in load_tables():
        marks = [pytest.mark.xfail(strict=True, reason=c.xfail)] if c.xfail else []
        out.append(pytest.param(c, id=c.id, marks=marks))
    return out


@pytest.mark.parametrize("c", _cli_params())
def test_cli_case(c: Case, world: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                  capsys: pytest.CaptureFixture[str]) -> None:
    t = tmp_path / "case"
    t.mkdir()
    try:
        if c.setup is not None:
            c.setup(world, t)
        argv = case_argv(c, world, t)
        out = out_path(argv, t) if c.check_out else None
        before = snapshot(out) if out is not None else None
        monkeypatch.chdir(t)
        if c.before_work:
            for module, name in COMMANDS[c.command].work:
                monkeypatch.setattr(importlib.import_module(module), name, tripwire, raising=False)
        code = run_cli(argv)
        err = capsys.readouterr().err
        assert "Traceback" not in err
        lines = [line for line in err.splitlines() if line.strip()]
        assert len(lines) == 1, f"expected one line on stderr, got:\n{err}"
        line = lines[0]
        assert line.startswith(f"irnuc {c.command}: error: "), line
        for name in c.names:
            assert name.format(w=world, t=t) in line, f"{name!r} not named in: {line}"
        assert code == 2, line
        if out is not None:
            assert snapshot(out) == before, f"{out} was changed"
            assert not list(out.parent.glob(f".{out.name}.tmp-*")), "temporary folder left"
            assert not (out.parent / f".{out.name}.lock").exists(), "lock file left"
    finally:
        if (t / "ro").exists():
            undo_read_only(t / "ro")


def test_table_is_large_and_unique() -> None:
    ids = [c.id for c in CLI_CASES]
    assert len(ids) == len(set(ids)), "case ids must be unique"
    assert len(CLI_CASES) >= 150
    assert {c.command for c in CLI_CASES} == set(COMMANDS)
