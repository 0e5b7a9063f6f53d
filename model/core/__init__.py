"""numba kernels of the physics model: plain ndarrays and floats, no unit or range checks.

The API modules one level up validate their inputs and call these kernels.
"""
