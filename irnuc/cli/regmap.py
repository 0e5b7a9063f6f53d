"""``irnuc regmap``: the register map of one build, for firmware and vendor tools.

From ``nuc_fixed/registers.rdl`` elaborated with a pipeline configuration's values (every
reset that is a configuration value is that build's): the C header (peakrdl-cheader), the
IP-XACT description (peakrdl-ipxact) and the Markdown page, written into ``--out`` as a
unit (docs/integration.md, "Firmware"). Only the standard library is imported here.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from irnuc.cli._args import add_out, add_pipeline, load_pipeline_arg, say

DEFAULT_OUT = Path("out/regmap")
FILES = ("irnuc_regs.h", "irnuc_regs.xml", "registers.md")


def add_arguments(p: argparse.ArgumentParser) -> None:
    add_pipeline(p, help_extra="; the build whose reset values the files carry")
    add_out(p, str(DEFAULT_OUT))


def run(args: argparse.Namespace) -> int:
    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.cosim import regfiles
    from irnuc.nuc_fixed import regmap

    # --out first: a --pipeline file inside it is refused before it is read
    out = claim_output_folder(args.out, kind="regmap")
    cfg = load_pipeline_arg(args.pipeline)
    root = regmap.elaborate_for(cfg)
    texts = {"irnuc_regs.h": regfiles.c_header(root), "irnuc_regs.xml": regfiles.ipxact(root),
             "registers.md": regmap.markdown(build=cfg)}
    with output_folder(out, kind="regmap") as tmp:
        for name, text in texts.items():
            write_text_atomic(tmp / name, text)
    say(f"pipeline {cfg.name!r}: wrote {', '.join(str(out / n) for n in FILES)}")
    return 0


COMMANDS = {
    "regmap": ("The register map of one build: C header, IP-XACT and Markdown",
               add_arguments, run),
}
