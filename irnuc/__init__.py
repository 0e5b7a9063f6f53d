"""irnuc: co-simulation and fixed-point exploration of the NUC and defective-pixel
correction hardware of uncooled infrared (microbolometer) cameras.

Subpackages, each importing only the ones listed after it (docs/architecture.md):
``irnuc.cli`` -> ``irnuc.reports`` -> ``irnuc.cocotb_tests`` -> ``irnuc.cosim`` ->
``irnuc.nuc_fixed`` -> ``irnuc.model`` -> ``irnuc.common``.
"""

import os
import sys
from importlib.metadata import PackageNotFoundError, version

from irnuc.common.cache import cache_dir

# numba's compiled-kernel cache goes to the irnuc cache, not beside the sources.
if "NUMBA_CACHE_DIR" not in os.environ:
    try:
        os.environ["NUMBA_CACHE_DIR"] = str(cache_dir("numba"))
    except OSError:
        # An unwritable cache (read-only home, $IRNUC_CACHE_DIR a file) must not stop every
        # command at import: compile into a private temporary folder instead.
        import tempfile

        _tmp = os.path.join(tempfile.gettempdir(), f"irnuc-numba-{os.getuid()}")
        os.makedirs(_tmp, mode=0o700, exist_ok=True)
        if os.stat(_tmp).st_uid != os.getuid():  # someone else's: never load their code
            _tmp = tempfile.mkdtemp(prefix="irnuc-numba-")
        os.environ["NUMBA_CACHE_DIR"] = _tmp
    if "numba" in sys.modules:  # imported before irnuc: its config was already read
        sys.modules["numba"].config.CACHE_DIR = os.environ["NUMBA_CACHE_DIR"]

try:
    __version__ = version("irnuc")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = ["__version__"]
