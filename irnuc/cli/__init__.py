"""The ``irnuc`` command line: one entry point, sub-commands contributed by the packages.

Each module listed in :data:`COMMAND_MODULES` defines ``COMMANDS``, a mapping from a
sub-command name to ``(help, add_arguments, run)``. Those modules import only the
standard library at top level, so ``irnuc --help`` stays fast; the heavy imports (numba,
scipy, matplotlib) happen inside ``run``.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Callable, Sequence

COMMAND_MODULES: tuple[str, ...] = ("irnuc.cli.frames", "irnuc.cli.calibrate",
                                      "irnuc.cli.commands", "irnuc.cli.precision")

Command = tuple[str, Callable[[argparse.ArgumentParser], None], Callable[[argparse.Namespace], int]]


class UsageError(Exception):
    """A user error found before any work: printed as one line, exit status 2."""


def build_parser() -> tuple[argparse.ArgumentParser, dict[str, Command]]:
    parser = argparse.ArgumentParser(
        prog="irnuc",
        description="Infrared NUC hardware co-simulation and fixed-point exploration toolkit.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    commands: dict[str, Command] = {}
    for module_name in COMMAND_MODULES:
        module = importlib.import_module(module_name)
        for name, command in module.COMMANDS.items():
            help_text, add_arguments, _ = command
            add_arguments(sub.add_parser(name, help=help_text, description=help_text))
            commands[name] = command
    return parser, commands


def main(argv: Sequence[str] | None = None) -> int:
    parser, commands = build_parser()
    args = parser.parse_args(argv)
    _, _, run = commands[args.command]
    try:
        return int(run(args) or 0)
    except (UsageError, ValueError, FileNotFoundError) as exc:
        # Configuration and input errors are reported as one clear line, not a traceback.
        print(f"irnuc {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
