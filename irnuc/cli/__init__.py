"""The ``irnuc`` command line: the top layer (docs/architecture.md).

Each module in :data:`COMMAND_MODULES` defines ``COMMANDS``, a mapping from a sub-command
name to ``(help, add_arguments, run)``. Those modules import only the standard library at
top level, so ``irnuc --help`` stays fast; the heavy imports happen inside ``run``.

:func:`main` is the boundary between the user and irnuc: a
:class:`~irnuc.common.errors.UserError` (bad flag, value, file or configuration field),
or an operating-system error on a path the user gave, becomes ONE line on stderr and exit
status 2; a failing external tool (:class:`~irnuc.common.errors.ToolError`) one line and
status 3; anything else is a bug and keeps its traceback.
"""

from __future__ import annotations

import argparse
import errno
import importlib
import os
import sys
from collections.abc import Callable, Sequence
from typing import NoReturn

from irnuc.cli._args import add_verbosity, set_verbosity, stdout_error
from irnuc.common.errors import StreamError, ToolError, UserError

COMMAND_MODULES: tuple[str, ...] = (
    "irnuc.cli.frames", "irnuc.cli.calibrate", "irnuc.cli.sweep", "irnuc.cli.report",
    "irnuc.cli.precision", "irnuc.cli.synth", "irnuc.cli.mutate", "irnuc.cli.formal",
    "irnuc.cli.traffic", "irnuc.cli.study", "irnuc.cli.noise", "irnuc.cli.regmap",
)

Command = tuple[str, Callable[[argparse.ArgumentParser], None], Callable[[argparse.Namespace], int]]

def _version() -> str:
    from irnuc import __version__

    return __version__


class OneLineParser(argparse.ArgumentParser):
    """argparse, but a usage error is ONE line (flag, problem, where to look), exit 2,
    like every other user error."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> tuple[argparse.ArgumentParser, dict[str, Command]]:
    parser = OneLineParser(
        prog="irnuc",
        description="Infrared NUC hardware co-simulation and fixed-point exploration toolkit.",
    )
    parser.add_argument("--version", action="version", version=f"irnuc {_version()}")
    add_verbosity(parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    commands: dict[str, Command] = {}
    for module_name in COMMAND_MODULES:
        module = importlib.import_module(module_name)
        for name, command in module.COMMANDS.items():
            help_text, add_arguments, _ = command
            sp = sub.add_parser(name, help=help_text, description=help_text)
            add_verbosity(sp)
            add_arguments(sp)
            sp.set_defaults(_parser=sp)  # so a stray argument is reported by its command
            commands[name] = command
    return parser, commands


def _os_error_line(exc: OSError) -> str | None:
    """One line for an OS error on a user's path; None when it is not about a path."""
    if exc.filename is None:
        return None
    what = {errno.ENOENT: "no such file or folder", errno.EACCES: "permission denied",
            errno.EPERM: "operation not permitted", errno.EISDIR: "is a folder",
            errno.ENOTDIR: "a part of the path is not a folder", errno.ENOSPC: "no space left",
            errno.EFBIG: "file too large (the file-size limit)", errno.EDQUOT: "disk quota exceeded",
            errno.EROFS: "read-only file system", errno.EEXIST: "already exists"}
    return f"{exc.filename}: {what.get(exc.errno, exc.strerror or 'cannot be used')}"


def _one_line(text: object) -> str:
    """A message as one line (a file's own text quoted in it may hold line breaks)."""
    return " ".join(str(text).split())


def _flush_stdout() -> None:
    if sys.stdout is None:  # closed when irnuc started (and then refused unless -q)
        return
    try:
        sys.stdout.flush()
    except OSError as exc:
        raise stdout_error(exc) from None


def _closed_standard_streams() -> list[str]:
    """The standard streams (stdin, stdout, stderr) whose file descriptor is closed, each
    reopened on /dev/null: a file irnuc opens must never become fd 1 or 2, where a child
    process (a compiler, a simulator) would write into it."""
    closed = []
    for fd, name in ((0, "stdin"), (1, "stdout"), (2, "stderr")):
        try:
            os.fstat(fd)
        except OSError:
            null = os.open(os.devnull, os.O_RDWR)
            if null != fd:
                os.dup2(null, fd)
                os.close(null)
            closed.append(name)
    return closed


def _silence_stdout() -> None:
    """Point a broken stdout at /dev/null, so the interpreter's last flush at exit does not
    print a second error."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # a replaced stream (tests): nothing to do
        return
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, fd)
    os.close(null)


def main(argv: Sequence[str] | None = None) -> int:
    closed = _closed_standard_streams()
    parser, commands = build_parser()
    args, extra = parser.parse_known_args(argv)
    sub = args.__dict__.pop("_parser")
    if extra:
        sub.error(f"unrecognized arguments: {' '.join(extra)}")
    set_verbosity(getattr(args, "verbosity", 1))
    _, _, run = commands[args.command]
    prefix = f"irnuc {args.command}: error:"
    if (sys.stdout is None or "stdout" in closed) and getattr(args, "verbosity", 1) >= 1:
        # Like a stdout that cannot be written (a closed pipe, a full disk), but known now:
        # refused before any work.
        print(f"{prefix} stdout: cannot be written (it is closed); give -q to print nothing, "
              "or redirect it to a file", file=sys.stderr)
        return 2
    from irnuc.common.io import release_claims

    try:
        code = int(run(args) or 0)
        _flush_stdout()  # a buffered stdout fails here, not silently at exit
        return code
    except UserError as exc:
        if isinstance(exc, StreamError):
            _silence_stdout()
        print(f"{prefix} {_one_line(exc)}", file=sys.stderr)
        return 2
    except ToolError as exc:
        print(f"{prefix} {_one_line(exc)}", file=sys.stderr)
        return 3
    except OSError as exc:
        line = _os_error_line(exc)
        if line is None:
            raise
        print(f"{prefix} {_one_line(line)}", file=sys.stderr)
        return 2
    except MemoryError:
        print(f"{prefix} out of memory; use a smaller frame, fewer frames or fewer points",
              file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"irnuc {args.command}: interrupted; outputs left as they were", file=sys.stderr)
        return 130
    finally:
        release_claims()  # the --out lock of a command that ended before its output


if __name__ == "__main__":
    sys.exit(main())
