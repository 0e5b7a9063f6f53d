"""Every file a command reads is refused inside its own ``--out``: replacing the output
would delete it (a sequence's table CSV once was read, then deleted with the folder).

Every option of every command whose metavar names a file or folder is a row here (a new
one fails :func:`test_every_file_option_has_a_row`); each is given a file inside ``--out``
(an earlier output of the same command) and must end in one line naming ``--out`` and the
input, exit status 2, the file and the folder as they were, no lock file left. The files
named inside inputs (a sequence's CSV, a manifest's files) are the table cases
``frames-sequence-table-inside-out`` and the reader's own guard (``guard_input``).
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from robustness.harness import run_cli, snapshot

#: (command, option) -> (what to put at out/NAME, the other arguments the command needs).
ROWS: dict[tuple[str, str], tuple[str, list[str]]] = {
    ("frames", "--sensor"): ("s.toml", []),
    ("frames", "--sequence"): ("s.toml", []),
    ("calibrate", "--frames"): ("f.npz", []),
    ("calibrate", "--plan"): ("p.toml", []),
    ("calibrate", "--pipeline"): ("p.toml", ["--frames", "{w}/good.npz"]),
    ("calibrate", "--sensor"): ("s.toml", ["--plan", "{w}/none.toml"]),
    ("calibrate", "--thresholds"): ("t.toml", ["--frames", "{w}/good.npz"]),
    ("correct", "--frames"): ("f.npz", ["--coeffs", "{w}/cal"]),
    ("correct", "--coeffs"): ("cal/", ["--frames", "{w}/good.npz"]),
    ("correct", "--pipeline"): ("p.toml", ["--frames", "{w}/good.npz", "--coeffs", "{w}/cal"]),
    ("sweep", "--sensor"): ("s.toml", []),
    ("sweep", "--pipeline"): ("p.toml", []),
    ("report", "--config"): ("c.toml", []),
    ("report", "--baseline"): ("b.json", ["--config", "small", "--no-cosim"]),
    ("report", "--junit"): ("j.xml", ["--config", "small"]),
    ("synth", "--pipeline"): ("p.toml", []),
    ("regmap", "--pipeline"): ("p.toml", []),
    ("study", "--sensor"): ("s.toml", ["ffc_interval", "--quick"]),
    ("noise", "--frames"): ("f.npz", []),
}


def _file_options() -> set[tuple[str, str]]:
    from irnuc.cli import build_parser

    parser, _ = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    return {(name, a.option_strings[-1]) for name, sp in sub.choices.items()
            for a in sp._actions
            if a.option_strings and a.option_strings[-1] != "--out"
            and re.search(r"FILE|DIR", str(a.metavar or ""))}


def test_every_file_option_has_a_row() -> None:
    assert _file_options() == set(ROWS)


@pytest.mark.parametrize(("command", "option"), sorted(ROWS), ids=lambda v: v)
def test_an_input_inside_out_is_refused(command: str, option: str, world: Path,
                                        tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    name, extra = ROWS[(command, option)]
    out = tmp_path / "out"
    out.mkdir()
    (out / ".irnuc-output").write_text(f"irnuc {command}\n")
    inside = out / name.rstrip("/")
    if name.endswith("/"):
        shutil.copytree(world / "cal", inside)
    elif name.endswith(".npz"):
        shutil.copy(world / "good.npz", inside)
    else:
        inside.write_text("[x]\n")
    before = snapshot(out)
    monkeypatch.chdir(tmp_path)
    argv = [command, *(a.format(w=world) for a in extra), option, str(inside), "--out", str(out)]
    code = run_cli(argv)
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and "Traceback" not in err, err
    assert code == 2, lines[0]
    assert lines[0].startswith(f"irnuc {command}: error: --out {out}: holds "), lines[0]
    assert "would replace" in lines[0] and str(inside) in lines[0], lines[0]
    assert snapshot(out) == before
    assert not (tmp_path / ".out.lock").exists()
