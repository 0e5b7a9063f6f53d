"""Netlists of the RTL and the mutations Yosys draws in them (``mutate`` through pyosys),
as a plain Python API for the automatic mutants of ``irnuc mutate --auto``
(:mod:`irnuc.verif.automut`).

* :func:`draw` lists N mutations of the cells of one source file inside a top, for one
  configuration, with a fixed seed (Yosys ``mutate -list N -seed S``, an even sampling over
  the file's source lines, wires and bits): each a ``mutate -mode ...`` command;
* :func:`write_netlist` writes the top elaborated for a configuration (slang, ``prep``,
  ``SYNTHESIS`` defined: the parameter checks and protocol assertions left out) as one
  flat Verilog module, with or without a mutation, every flop initialised to 0 (as Verilator
  starts them), renamed ``<top>__<tag>``;
* :func:`wrapper` is the top's own header (its parameters and ports) around that netlist,
  so that a copy of ``hdl/`` whose top file holds wrapper and netlist builds and runs with
  the top's testbench as the RTL does (:func:`install`).
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

from irnuc.cosim.sources import tool_parameters
from irnuc.cosim.synth import _run_yosys


def _read(sources: Sequence[Path], top: str, params: Mapping[str, int]) -> list[str]:
    files = " ".join(str(Path(s).resolve()) for s in sources)
    # slang converts no integer to a typed enum parameter (a top's Method): its literal.
    gens = " ".join(f"-G {k}={v}" for k, v in tool_parameters(params, "slang").items())
    return [f"read_slang -D SYNTHESIS --top {top} {gens} {files}", f"prep -top {top}"]


_SRC = re.compile(r"\s+-src\s+\S+")


def draw(sources: Sequence[Path], top: str, params: Mapping[str, int], file: str, n: int,
         seed: int, workdir: Path) -> list[dict[str, str]]:
    """``n`` mutations of the cells of ``top`` that come from ``file`` (a file name of
    ``hdl/``): ``[{"command": "mutate -mode ...", "src": "file:line"}, ...]``, the same for
    the same design, ``n`` and ``seed``."""
    workdir.mkdir(parents=True, exist_ok=True)
    listing = workdir / "mutations.txt"
    sel = f"a:src=*/{file}:*"
    _run_yosys(workdir, "draw", [*_read(sources, top, params),
                                 f"mutate -list {int(n)} -seed {int(seed)} -o {listing} {sel}"])
    out = []
    for line in listing.read_text().splitlines():
        line = line.strip()
        if not line.startswith("mutate "):
            continue
        srcs = re.findall(r"-src\s+(\S+)", line)
        src = next((s for s in srcs if f"/{file}:" in s), srcs[0] if srcs else "")
        src = src.rsplit("/", 1)[-1].split("-", 1)[0]
        out.append({"command": _SRC.sub("", line), "src": src})
    return out


#: Bumped when :func:`write_netlist`'s passes change (the cached netlists' key has it).
NETLIST_VERSION = 2


def write_netlist(sources: Sequence[Path], top: str, params: Mapping[str, int], out: Path,
                  tag: str, mutation: str | None = None) -> Path:
    """The flat netlist of ``top`` (module ``<top>__<tag>``) with ``mutation`` (a
    ``mutate -mode ...`` command of :func:`draw`) applied; returns ``out``."""
    out = Path(out)
    wd = out.parent
    wd.mkdir(parents=True, exist_ok=True)
    passes = [*_read(sources, top, params), "flatten"]
    if mutation:
        passes.append(mutation)
    # bwmuxmap: the register block's masked writes become $bwmux cells, which Verilog
    # cannot name (Verilator refused the netlist of irnuc_axis_top with them).
    passes += ["opt_clean", "bwmuxmap", "setundef -zero -init", f"rename {top} {top}__{tag}",
               f"write_verilog -noattr -norename {out}",
               f"write_json {out.with_suffix('.json')}"]
    _run_yosys(wd, out.stem, passes)
    return out


def ports(netlist: Path) -> list[tuple[str, str, int]]:
    """(name, direction, width) of the netlist module's ports, in order (its JSON)."""
    data = json.loads(Path(netlist).with_suffix(".json").read_text())
    (mod,) = data["modules"].values()
    return [(name, p["direction"], len(p["bits"])) for name, p in mod["ports"].items()]


def header(text: str, top: str) -> str:
    """The header of module ``top`` in an RTL file: from ``module`` to the end of its port
    list (``);`` at the start of a line)."""
    m = re.search(rf"^module\s+{re.escape(top)}\b.*?^\);", text, re.S | re.M)
    if m is None:
        raise ValueError(f"no header of module {top} found")
    return m.group(0)


def wrapper(text: str, top: str, tag: str) -> str:
    """Module ``top`` with the header of the RTL ``text`` around the netlist module
    ``<top>__<tag>`` (ports by name)."""
    return (f"// {top}: its RTL's header around a netlist ({top}__{tag}, written by Yosys; "
            f"irnuc mutate --auto)\n/* verilator lint_off DECLFILENAME */\n"
            f"{header(text, top)}\n  {top}__{tag} u_netlist (.*);\nendmodule\n")


def install(hdl: Path, top: str, netlist: Path, tag: str) -> None:
    """Replace ``hdl/<top>.sv`` of a copy of the RTL by the wrapper and the netlist."""
    f = Path(hdl) / f"{top}.sv"
    f.write_text(wrapper(f.read_text(), top, tag) + "\n" + Path(netlist).read_text())


__all__ = ["NETLIST_VERSION", "draw", "header", "install", "ports", "wrapper", "write_netlist"]
