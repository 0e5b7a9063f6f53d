"""The SystemVerilog RTL of the irnuc pipeline (``*.sv``, one module per file).

A Python package only so that the sources install with irnuc and are found with
``importlib.resources.files("irnuc.hdl")``; see docs/rtl.md.
"""
