"""``irnuc.cosim`` gives its names on first use (PEP 562): each public name is the object
its submodule defines, and the cocotb child's import does not load the golden model."""

from __future__ import annotations

import subprocess
import sys

from irnuc import cosim
from irnuc.cosim import builds, bulk, scoreboard, sources, verilator


def test_every_public_name_is_its_submodules_object() -> None:
    defined = {n: m for m in (builds, bulk, scoreboard, sources, verilator)
               for n in dir(m) if n in cosim.__all__}
    assert set(defined) == set(cosim.__all__), set(cosim.__all__) - set(defined)
    # The dispatch table of __getattr__ names exactly the public names.
    lazy = cosim._BUILDS | cosim._BULK | cosim._SCOREBOARD | cosim._SOURCES | cosim._VERILATOR
    assert lazy == set(cosim.__all__)
    for name, module in defined.items():
        assert getattr(cosim, name) is getattr(module, name), name


def test_the_cocotb_childs_import_leaves_out_the_golden_model() -> None:
    code = ("import sys, irnuc.cosim._cocotb_adapter; "
            "print(sorted(m for m in sys.modules if m.startswith(('irnuc.nuc_fixed', 'numba'))))")
    out = subprocess.run([sys.executable, "-P", "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]", out
