"""irnuc: co-simulation and fixed-point exploration of the NUC and defective-pixel
correction hardware of uncooled infrared (microbolometer) cameras.

Subpackages, each importing only the ones listed after it (docs/architecture.md):
``irnuc.cli`` -> ``irnuc.reports`` -> ``irnuc.cocotb_tests`` -> ``irnuc.cosim`` ->
``irnuc.nuc_fixed`` -> ``irnuc.model`` -> ``irnuc.common``.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("irnuc")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = ["__version__"]
