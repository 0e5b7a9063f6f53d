"""Arguments shared by every sub-command, parsed one way everywhere.

One name per concept (docs/architecture.md, "Command line"):

* ``--sensor``   the physics model: a preset name (``default``, ``paper``) or a sensor TOML;
* ``--pipeline`` the NUC + DPC configuration: a name in ``pipelines.toml`` or a TOML file;
* ``--config``   a run configuration (only ``irnuc report``);
* ``--out``      the folder under which every output of the command goes;
* ``--set KEY=VALUE`` dotted overrides, values parsed as TOML;
* ``-q`` / ``-v`` less or more on the terminal.

Only the standard library is imported here, so ``irnuc --help`` stays fast.
"""

from __future__ import annotations

import argparse
import sys
import tomllib
from typing import Any

from irnuc.common.errors import StreamError, UserError

#: 0 quiet (errors only), 1 normal, 2 verbose; set by ``-q`` / ``-v``.
_VERBOSITY = [1]


def set_verbosity(level: int) -> None:
    _VERBOSITY[0] = level


def verbosity() -> int:
    return _VERBOSITY[0]


def say(message: str, level: int = 1) -> None:
    """Print a line on stdout when the verbosity is at least ``level``; a stdout that
    cannot be written (closed pipe, full disk) is a :class:`StreamError`."""
    if _VERBOSITY[0] >= level:
        try:
            print(message, flush=True)
        except OSError as exc:
            raise stdout_error(exc) from None


def stdout_error(exc: OSError) -> StreamError:
    """The one-line error of a stdout that cannot be written."""
    why = ("the reader closed it" if isinstance(exc, BrokenPipeError)
           else exc.strerror or str(exc))
    return StreamError(f"stdout: cannot be written ({why}); the command stopped, and every "
                       "--out is whole (replaced only as a unit)")


def progress(label: str):
    """A progress callback ``(done, total)`` on stderr, or None when quiet."""
    if _VERBOSITY[0] < 1:
        return None
    from irnuc.common.progress import ProgressBar

    return ProgressBar(label)


def add_verbosity(p: argparse.ArgumentParser) -> None:
    g = p.add_mutually_exclusive_group()
    g.add_argument("-q", "--quiet", action="store_const", const=0, dest="verbosity",
                   default=argparse.SUPPRESS, help="print only errors")
    g.add_argument("-v", "--verbose", action="store_const", const=2, dest="verbosity",
                   default=argparse.SUPPRESS, help="print more detail")


def add_out(p: argparse.ArgumentParser, default: str) -> None:
    p.add_argument("--out", default=default, metavar="DIR",
                   help="folder for every output of this command; replaced as a whole "
                        "when the command succeeds (default: %(default)s)")


def add_executor(p: argparse.ArgumentParser, what: str, workers: int = 2,
                 workers_help: str = "worker processes; 0 = in-process",
                 cache: str | None = None) -> None:
    """``--workers``, ``--scheduler`` (the sweep executor: processes or a Dask cluster) and,
    when ``cache`` says what is cached, ``--no-cache``."""
    p.add_argument("--workers", type=int, default=workers,
                   help=f"{workers_help} (default: %(default)s)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help=f"{what} on a Dask distributed cluster (needs dask[distributed])")
    if cache is not None:
        p.add_argument("--no-cache", action="store_true",
                       help=f"run again even if the cache holds {cache}")


def add_pipeline(p: argparse.ArgumentParser, default: str | None = "typical14",
                 help_extra: str = "") -> None:
    p.add_argument("--pipeline", default=default, required=default is None,
                   metavar="NAME|FILE.toml",
                   help="NUC + DPC configuration: a name in nuc_fixed/pipelines.toml or a "
                        f"pipeline TOML file (FILE.toml or FILE.toml:NAME){help_extra}"
                        + (" (default: %(default)s)" if default else ""))


def add_sensor(p: argparse.ArgumentParser, default: str = "default") -> None:
    p.add_argument("--sensor", default=default, metavar="PRESET|FILE.toml",
                   help="sensor model: a preset (default, paper) or a sensor TOML file "
                        "(default: %(default)s)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a sensor field, e.g. --set fpa.active_rows=120 (repeatable)")


def parse_assignments(items: list[str] | None, flag: str) -> dict[str, Any]:
    """``["a.b=1", "c=[1, 2]"]`` -> ``{"a.b": 1, "c": [1, 2]}`` (values parsed as TOML;
    a bare word is a string)."""
    out: dict[str, Any] = {}
    for item in items or []:
        key, sep, text = item.partition("=")
        key = key.strip()
        if not sep or not key or not text.strip():
            raise UserError(f"{flag} {item!r} must look like KEY=VALUE")
        try:
            out[key] = tomllib.loads(f"v = {text}")["v"]
        except tomllib.TOMLDecodeError:
            out[key] = text.strip()
    return out


def parse_floats(text: str, flag: str, unit: str = "") -> list[float]:
    """A comma-separated list of finite numbers."""
    import math

    try:
        vals = [float(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise UserError(f"{flag} {text!r} must be a comma-separated list of numbers"
                        + (f" ({unit})" if unit else "")) from None
    if not vals:
        raise UserError(f"{flag} {text!r} holds no number")
    bad = [v for v in vals if not math.isfinite(v)]
    if bad:
        raise UserError(f"{flag} {text!r}: {bad[0]} is not a finite number")
    return vals


def flagged(flag: str, value: str, exc: Exception) -> UserError:
    """``exc`` as a one-line :class:`UserError` that starts with the flag and its value
    (an error of the output folder, which names ``--out`` itself, unchanged)."""
    from irnuc.common.io import OutputError

    if isinstance(exc, OutputError):
        return exc
    msg = str(exc)
    if msg.startswith(flag):
        return UserError(msg)
    if msg.startswith(f"{value}:") or msg.startswith(f"{value} "):
        return UserError(f"{flag} {msg}")
    return UserError(f"{flag} {value}: {msg}")


def load_pipeline_arg(value: str, flag: str = "--pipeline"):
    """The pipeline configuration a ``--pipeline`` value names (name or TOML file)."""
    from irnuc.nuc_fixed.config import load_pipeline

    try:
        return load_pipeline(value)
    except UserError as exc:
        raise flagged(flag, value, exc) from None


def load_sensor_arg(value: str, overrides: dict[str, Any], flag: str = "--sensor"):
    """The validated sensor configuration a ``--sensor`` value names, with overrides."""
    from irnuc import model

    if value.endswith(".toml") or "/" in value:
        try:
            return model.load_config(value, overrides)
        except UserError as exc:
            raise flagged(flag, value, exc) from None
    if value not in model.preset_names():
        raise UserError(f"{flag} {value!r} is neither a preset ({', '.join(model.preset_names())}) "
                        "nor a .toml file")
    return model.load_preset(value, overrides)


def stderr(message: str) -> None:
    print(message, file=sys.stderr, flush=True)
