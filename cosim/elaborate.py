"""What a configuration elaborates: Verilator's elaborated design, without a build.

``verilator --json-only`` parses and elaborates a top for one set of parameters in a
fraction of a second and writes the elaborated tree (every module specialised for its
parameters, generate blocks resolved). From it:

* :attr:`Elaboration.blocks`: the generate blocks each module elaborates, as nested label
  paths (``gen_wrap/gen_sign_ext``; loop indices dropped), the ground truth for the branch
  conditions of :mod:`irnuc.cosim.configspace`;
* :attr:`Elaboration.digest`: a digest of the tree without source positions and with node
  addresses renumbered in traversal order, so that two designs elaborate to the same
  digest exactly when they elaborate to the same tree. Mutation testing uses it to run a
  mutant only on the configurations where the mutated code elaborates to something else.

:func:`source_blocks` lists every labelled generate block of the source files with its
nesting, so that a block no configuration elaborates is found too.
"""

from __future__ import annotations

import hashlib
import json
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from irnuc.common.process import run_child
from irnuc.cosim.sources import hdl_sources, top_parameters, verilator_g
from irnuc.cosim.verilator import RtlError, verilator_env, verilator_executable
from irnuc.nuc_fixed.config import PipelineConfig

#: Labels of generate blocks (lowRISC style: every generate block is named gen_*).
GEN_PREFIX = "gen_"
_PTR = re.compile(r"^\([A-Z]+\)$")
_INDEX = re.compile(r"\[\d+\]$")


@dataclass(frozen=True)
class Elaboration:
    """One top elaborated for one configuration."""

    top: str
    digest: str
    #: module (its source name) -> generate-block paths elaborated in some instance
    blocks: dict[str, frozenset[str]]
    #: module (its source name) -> digests of its elaborated instances (specialisations)
    modules: dict[str, frozenset[str]]


def elaborate(top: str, cfg: PipelineConfig, hdl_dir: Path | None = None) -> Elaboration:
    """Elaborate ``top`` with the parameters of ``cfg`` (from ``hdl_dir``, a modified copy
    of ``hdl/``, when given). Synthesis view: ``SYNTHESIS`` defined, no assertions."""
    with tempfile.TemporaryDirectory(prefix="irnuc-elab-") as tmp:
        cmd = [str(verilator_executable()), "--json-only", "-Mdir", tmp, "--top-module", top,
               "-DSYNTHESIS", "-Wno-fatal",
               *verilator_g(top_parameters(top, cfg)),
               *[str(p) for p in hdl_sources(top, hdl_dir)]]
        proc = run_child(cmd, env=verilator_env(), capture=True)
        tree = Path(tmp) / f"V{top}.tree.json"
        if proc.returncode != 0 or not tree.is_file():
            tail = "\n".join((proc.stdout or "").splitlines()[-8:])
            raise RtlError(f"Verilator could not elaborate {top} for {cfg.name} (exit "
                           f"{proc.returncode}):\n{tail}")
        data = json.loads(tree.read_text())
    return Elaboration(top, _canonical_digest(data), *_modules(data))


def _canonical(node: object, ids: dict[str, str]) -> object:
    if isinstance(node, dict):
        return {k: _canonical(v, ids) for k, v in node.items() if k not in ("addr", "loc")}
    if isinstance(node, list):
        return [_canonical(v, ids) for v in node]
    if isinstance(node, str) and _PTR.match(node):
        return ids.setdefault(node, f"#{len(ids)}")
    return node


def _number(node: object, ids: dict[str, str]) -> None:
    """Node addresses in traversal order (the renumbering of :func:`_canonical`)."""
    if isinstance(node, dict):
        if isinstance(node.get("addr"), str):
            ids.setdefault(node["addr"], f"#{len(ids)}")
        for v in node.values():
            _number(v, ids)
    elif isinstance(node, list):
        for v in node:
            _number(v, ids)


def _tree_digest(node: object) -> str:
    ids: dict[str, str] = {}
    _number(node, ids)
    text = json.dumps(_canonical(node, ids), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _canonical_digest(data: dict) -> str:
    return _tree_digest(data)


def _modules(data: dict) -> tuple[dict[str, frozenset[str]], dict[str, frozenset[str]]]:
    blocks: dict[str, set[str]] = {}
    specs: dict[str, set[str]] = {}

    def walk(node: object, path: tuple[str, ...], module: str) -> None:
        if isinstance(node, dict):
            if node.get("type") == "GENBLOCK" and isinstance(node.get("name"), str):
                label = _INDEX.sub("", node["name"])
                if label and (not path or path[-1] != label):
                    path = (*path, label)
                    blocks.setdefault(module, set()).add("/".join(path))
            for k, v in node.items():
                if k not in ("addr", "loc"):
                    walk(v, path, module)
        elif isinstance(node, list):
            for v in node:
                walk(v, path, module)

    for mod in data.get("modulesp", []):
        if not isinstance(mod, dict) or mod.get("type") != "MODULE":
            continue
        name = str(mod.get("origName") or mod.get("name"))
        if name.startswith("@"):
            continue
        blocks.setdefault(name, set())
        specs.setdefault(name, set()).add(_tree_digest(mod))
        walk(mod.get("stmtsp", []), (), name)
    return ({m: frozenset(b) for m, b in blocks.items()},
            {m: frozenset(s) for m, s in specs.items()})


# ---- the source side -------------------------------------------------------------------------

_COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_STRING = re.compile(r'"(?:\\.|[^"\\])*"')
_TOKEN = re.compile(r"\b(module|endmodule|begin|end)\b(\s*:\s*([A-Za-z_]\w*))?")


def source_blocks(path: Path) -> dict[str, set[str]]:
    """module -> paths of every labelled generate block (``gen_*``) in one SystemVerilog
    file, nested as written. Every ``begin`` (labelled or not) opens a scope and every
    ``end`` closes one, so blocks inside procedural code nest correctly."""
    text = _STRING.sub('""', _COMMENT.sub(" ", Path(path).read_text()))
    out: dict[str, set[str]] = {}
    module: str | None = None
    stack: list[str | None] = []
    for m in _TOKEN.finditer(text):
        word, label = m.group(1), m.group(3)
        if word == "module":
            name = re.match(r"\s*(?:import\s+[\w:*,\s]+;\s*)?([A-Za-z_]\w*)", text[m.end():])
            module = name.group(1) if name else None
            stack = []
            if module:
                out.setdefault(module, set())
        elif word == "endmodule":
            module, stack = None, []
        elif word == "begin" and module:
            stack.append(label if label and label.startswith(GEN_PREFIX) else None)
            if stack[-1]:
                out[module].add("/".join(s for s in stack if s))
        elif word == "end" and module and stack:
            stack.pop()
    return out


__all__ = ["Elaboration", "elaborate", "source_blocks"]
