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
    os.environ["NUMBA_CACHE_DIR"] = str(cache_dir("numba"))
    if "numba" in sys.modules:  # imported before irnuc: its config was already read
        sys.modules["numba"].config.CACHE_DIR = os.environ["NUMBA_CACHE_DIR"]

try:
    __version__ = version("irnuc")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = ["__version__"]
