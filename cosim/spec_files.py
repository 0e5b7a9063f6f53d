"""The files generated from the shared-constants spec (:mod:`irnuc.nuc_fixed.rtl_spec`) and
the method registry (:mod:`irnuc.nuc_fixed.methods.rtl`): the block between the markers of
``hdl/irnuc_pkg.sv``, the whole package probe ``cosim/hdl/irnuc_pkg_probe.sv``, the
generated blocks of the design (``// irnuc-params:``: ``irnuc_method_pkg``'s functions, the
tops' and the method fronts' parameter headers, the forwarded parameter lists,
irnuc_axis_top's frame word), the whole ``hdl/frame_coefficients.sv`` and, in a checkout,
the register map's documentation ``docs/registers.md``
(:func:`irnuc.nuc_fixed.regmap.markdown`).

``python -m irnuc.cosim.spec_files --write`` rewrites them; ``--check`` (the default)
lists the stale ones and exits 1. ``tests/test_rtl_spec.py`` runs the check.
"""

from __future__ import annotations

import sys
from pathlib import Path

from irnuc.common.io import write_text_atomic
from irnuc.cosim.sources import HDL_DIR, SIM_HDL_DIR
from irnuc.nuc_fixed import regmap, rtl_spec
from irnuc.nuc_fixed.methods import rtl as methods_rtl

PACKAGE = HDL_DIR / "irnuc_pkg.sv"
PROBE = SIM_HDL_DIR / "irnuc_pkg_probe.sv"
#: The register map's page (only in a checkout: docs/ is not installed).
REGISTERS_DOC = HDL_DIR.parent / "docs" / "registers.md"


FRAME_COEFFICIENTS = HDL_DIR / "frame_coefficients.sv"


def design_files(hdl_dir: Path = HDL_DIR) -> dict[Path, str]:
    """The generated design files of a copy of ``hdl/`` (``hdl_dir``) and their text: the
    package's block, ``frame_coefficients.sv`` and every file with generated blocks."""
    hdl_dir = Path(hdl_dir)
    pkg, frame = hdl_dir / PACKAGE.name, hdl_dir / FRAME_COEFFICIENTS.name
    out = {pkg: rtl_spec.replace_block(pkg.read_text(), rtl_spec.sv_package_block()),
           frame: methods_rtl.frame_coefficients()}
    for p in sorted(hdl_dir.glob("*.sv")):
        if p == frame:
            continue
        text = p.read_text()
        if any(m in text for m in (methods_rtl.BEGIN, methods_rtl.FORWARD, methods_rtl.FRAME,
                                   methods_rtl.PORTS)):
            out[p] = methods_rtl.fill(text, hdl_dir)
    return out


def expected() -> dict[Path, str]:
    """Each generated file and the text it must have."""
    out = {**design_files(), PROBE: rtl_spec.sv_probe()}
    if REGISTERS_DOC.parent.is_dir():
        out[REGISTERS_DOC] = regmap.markdown()
    return out


def stale() -> list[Path]:
    """The generated files whose text differs from the spec's."""
    return [p for p, text in expected().items() if not p.is_file() or p.read_text() != text]


def write() -> list[Path]:
    """Regenerate the stale files; return them."""
    changed = stale()
    want = expected()
    for p in changed:
        write_text_atomic(p, want[p])
    return changed


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if args not in ([], ["--check"], ["--write"]):
        print("usage: python -m irnuc.cosim.spec_files [--check | --write]", file=sys.stderr)
        return 2
    if args == ["--write"]:
        for p in write():
            print(f"wrote {p}")
        return 0
    old = stale()
    for p in old:
        print(f"{p} is stale: python -m irnuc.cosim.spec_files --write")
    return 1 if old else 0


if __name__ == "__main__":
    sys.exit(main())
