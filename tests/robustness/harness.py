"""The command-line case table's machinery: :class:`Case`, the registries of commands and
cases, the shared case setups, and running one case.

A command's module (``cli_<command>.py``) declares the command once with :func:`command`
and adds its cases with :func:`case`; :func:`load_tables` imports every such module.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import pkgutil
import shlex
import subprocess
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

REPO = Path(__file__).resolve().parents[2]


@dataclass(frozen=True)
class Command:
    """A command of the table: its title in the documentation and the first functions of
    its work ``(module, name)``, replaced by a tripwire so that a case passes only if its
    error is found before the work."""

    name: str
    title: str
    work: tuple[tuple[str, str], ...]


#: Every command with cases, in the order their modules declared them.
COMMANDS: dict[str, Command] = {}


def command(name: str, work: tuple[tuple[str, str], ...], title: str | None = None) -> str:
    """Declare a command of the table (once, in its ``cli_<name>.py``); returns ``name``."""
    if name in COMMANDS:
        raise ValueError(f"command {name!r} is declared twice")
    COMMANDS[name] = Command(name, title or f"irnuc {name}", work)
    return name


@dataclass(frozen=True)
class Case:
    """One hostile command line.

    ``args`` is split like a shell line; ``{w}`` is the shared folder of valid and hostile
    input files (:func:`world`), ``{t}`` the case's own folder (also the current folder).
    ``--out {t}/out`` is added unless the case gives ``--out``. ``names`` must all appear in
    the one-line message. ``setup(w, t)`` prepares the case's own files.
    """

    id: str
    command: str
    args: str
    names: tuple[str, ...]
    what: str
    setup: Callable[[Path, Path], None] | None = None
    xfail: str | None = None
    before_work: bool = True  # False: the problem is only visible in the data being worked on
    check_out: bool = True    # False for --out values that are no path of the case's own




CLI_CASES: list[Case] = []


def case(id: str, command: str, args: str, names: tuple[str, ...] | str, what: str,
         **kw: Any) -> None:
    """Add one case (``command`` declared before with :func:`command`)."""
    if command not in COMMANDS:
        raise ValueError(f"case {id!r}: command {command!r} is not declared")
    CLI_CASES.append(Case(id, command, args, (names,) if isinstance(names, str) else names,
                          what, **kw))


#: The commands of the pipeline, in its order (frames -> ... -> mutate), documented first;
#: any other ``cli_*.py`` module follows in alphabetical order.
PIPELINE_ORDER = ("frames", "calibrate", "correct", "sweep", "report", "precision", "synth",
                  "mutate")


def load_tables() -> list[Case]:
    """Import every ``cli_*.py`` module of this package (each declares its command and adds
    its cases) and return the whole table."""
    found = {m.name.removeprefix("cli_") for m in pkgutil.iter_modules([str(Path(__file__).parent)])
             if m.name.startswith("cli_")}
    for name in [*(n for n in PIPELINE_ORDER if n in found), *sorted(found - set(PIPELINE_ORDER))]:
        importlib.import_module(f"{__package__}.cli_{name}")
    return CLI_CASES


# ---- case setups (files in the case's own folder) --------------------------------------

def write_file(name: str, content: str | bytes) -> Callable[[Path, Path], None]:
    def setup(w: Path, t: Path) -> None:
        p = t / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_bytes(content if isinstance(content, bytes) else content.encode())
    return setup


def user_folder(w: Path, t: Path) -> None:
    (t / "out").mkdir()
    (t / "out" / "thesis.tex").write_text("years of work\n")


def other_kind(kind: str) -> Callable[[Path, Path], None]:
    def setup(w: Path, t: Path) -> None:
        (t / "out").mkdir()
        (t / "out" / ".irnuc-output").write_text(f"irnuc {kind}\n")
        (t / "out" / "result.bin").write_bytes(b"\x00")
    return setup


def link_out(w: Path, t: Path) -> None:
    (t / "elsewhere").mkdir()
    (t / "out").symlink_to(t / "elsewhere")


def out_is_file(w: Path, t: Path) -> None:
    (t / "out").write_text("not a folder\n")


def out_under_file(w: Path, t: Path) -> None:
    (t / "plain").write_text("a file\n")


def ro_parent(w: Path, t: Path) -> None:
    ro = t / "ro"
    ro.mkdir()
    make_read_only(ro)


def make_read_only(path: Path) -> None:
    """A folder nobody may write into: immutable when run as root (root ignores modes)."""
    if os.geteuid() == 0:
        r = subprocess.run(["chattr", "+i", str(path)], capture_output=True)
        if r.returncode != 0:
            pytest.skip("cannot make a read-only folder as root here (no chattr +i)")
    else:
        path.chmod(0o555)


def undo_read_only(path: Path) -> None:
    if os.geteuid() == 0:
        subprocess.run(["chattr", "-i", str(path)], capture_output=True)
    with contextlib.suppress(OSError):
        path.chmod(0o755)


def stale_tmp(w: Path, t: Path) -> None:
    # A killed run's temporary folder beside the output: ignored and removed safely.
    (t / ".out.tmp-killed").mkdir()
    (t / ".out.tmp-killed" / "coeffs.npz").write_bytes(b"half")


# ---- running a case ---------------------------------------------------------------------

class WorkStarted(AssertionError):
    """The command started its work although the error could be known before."""


def tripwire(*_: Any, **__: Any) -> Any:
    raise WorkStarted("the command's work started before the error was reported")


def snapshot(path: Path) -> Any:
    """Everything at ``path`` (kind, bytes, link target), to show it was left alone."""
    if path.is_symlink():
        return ("link", os.readlink(path))
    if not path.exists():
        return None
    if path.is_file():
        return ("file", path.read_bytes())
    return ("folder", {str(p.relative_to(path)): (p.read_bytes() if p.is_file() and not p.is_symlink()
                                                   else "folder" if p.is_dir() else "link")
                       for p in sorted(path.rglob("*"))})


def case_argv(c: Case, w: Path, t: Path) -> list[str]:
    """The command line of a case, with ``--out {t}/out`` added unless it gives one."""
    args = [a.format(w=w, t=t) for a in shlex.split(c.args)]
    if not any(a == "--out" or a.startswith("--out=") for a in args):
        args += ["--out", str(t / "out")]
    return [c.command, *args]


def out_path(argv: list[str], t: Path) -> Path | None:
    """The ``--out`` of a command line (relative to the case folder ``t``), if any."""
    for i, a in enumerate(argv):
        if a == "--out" and i + 1 < len(argv):
            value = argv[i + 1]
        elif a.startswith("--out="):
            value = a[len("--out="):]
        else:
            continue
        return (t / value) if value and not os.path.isabs(value) else Path(value) if value else None
    return None


def run_cli(argv: list[str]) -> int:
    """``irnuc ARGV`` in this process; argparse's exit becomes the status."""
    from irnuc.cli import main

    try:
        return main(argv)
    except SystemExit as exc:  # argparse
        return int(exc.code or 0)

