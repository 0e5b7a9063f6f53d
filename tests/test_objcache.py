"""The shared Verilator runtime objects (``irnuc.cosim._objcache``): kept once per key,
copied into the next build newer than its makefile, keyed by what their compilation
depends on and not by the design. (That a seeded build links them instead of compiling
them shows in every co-simulation: their build logs compile no ``verilated*.cpp``.)"""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from irnuc.cosim import _objcache

MK = """# Verilated -*- Makefile -*-
#    make -f {prefix}.mk
default: {top}
VM_PREFIX = {prefix}
VM_MODPREFIX = {prefix}
VM_USER_CFLAGS = \\
  -std=c++20 \\
include {prefix}_classes.mk
{top}: $(VK_USER_OBJS) $(VK_GLOBAL_OBJS) $(VM_PREFIX)__ALL.a
"""
CLASSES = """VM_COVERAGE = {cov}
VM_TRACE = 0
VM_CLASSES_FAST += \\
  Vtop \\
  Vtop___024root__{top} \\

VM_GLOBAL_FAST += \\
  verilated \\
  verilated_vpi \\

VM_GLOBAL_SLOW += \\

"""


def _build(path: Path, top: str, cov: int = 0, objects: bool = True,
           prefix: str = "Vtop") -> Path:
    path.mkdir(parents=True)
    (path / f"{prefix}.mk").write_text(MK.format(top=top, prefix=prefix))
    (path / f"{prefix}_classes.mk").write_text(CLASSES.format(top=top, cov=cov))
    if objects:
        for name in ("verilated", "verilated_vpi", "verilator"):
            (path / f"{name}.o").write_bytes(f"object {name} of {top}".encode())
            (path / f"{name}.d").write_text(f"{name}.o: /x/{name}.cpp\n")
    return path


def test_store_then_seed_and_keys(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    first = _build(tmp_path / "a", "nuc_core")
    assert _objcache._global_objects(first) == ["verilated.o", "verilated_vpi.o"]
    assert _objcache.seed(first) == 0  # nothing cached yet
    assert _objcache.store(first) and not _objcache.store(first)  # once per key
    # Another design, same settings: same key, the runtime objects arrive, stamped after
    # its makefile; the design's own objects (verilator.o) are never copied.
    second = _build(tmp_path / "b", "nuc_dpc_top", objects=False)
    assert _objcache.key(second) == _objcache.key(first)
    time.sleep(0.01)
    assert _objcache.seed(second) == 4
    assert (second / "verilated_vpi.o").read_bytes() == b"object verilated_vpi of nuc_core"
    assert not (second / "verilator.o").exists()
    assert os.stat(second / "verilated.o").st_mtime_ns > os.stat(second / "Vtop.mk").st_mtime_ns
    # Another setting (coverage): another key, nothing to seed.
    cov = _build(tmp_path / "c", "nuc_core", cov=1, objects=False)
    assert _objcache.key(cov) != _objcache.key(first)
    assert _objcache.seed(cov) == 0


def test_the_model_prefix_is_not_in_the_key(tmp_path) -> None:
    """The bulk harness names each model after its top (Vnuc_dpc_top, Vmethod_dpc_top, ...):
    its name in the makefiles (comments, VM_PREFIX, the classes file's include) does not
    split the key, so the bulk builds of every top share one set of runtime objects."""
    a = _build(tmp_path / "a", "bulk", prefix="Vnuc_dpc_top", objects=False)
    b = _build(tmp_path / "b", "bulk", prefix="Vmethod_ffc_top", objects=False)
    c = _build(tmp_path / "c", "bulk", prefix="Vmethod_ffc_top", cov=1, objects=False)
    assert _objcache.key(a) == _objcache.key(b) != _objcache.key(c)


def test_nothing_is_stored_from_an_incomplete_build(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    d = _build(tmp_path / "a", "nuc_core")
    (d / "verilated_vpi.o").unlink()
    assert not _objcache.store(d)
    assert _objcache.seed(_build(tmp_path / "b", "nuc_core", objects=False)) == 0


def test_usage_error() -> None:
    assert _objcache.main(["nope"]) == 2
    with pytest.raises(ValueError):
        _objcache._makefiles(Path("/nonexistent-folder"))


def test_children_ignore_files_in_the_current_folder(tmp_path) -> None:
    """irnuc's Python children run with ``-P``: an ``inspect.py`` in the folder irnuc is
    started from does not replace the standard module (it broke every simulation)."""
    from irnuc.common.process import python_module, run_child

    (tmp_path / "inspect.py").write_text("raise SystemExit('the wrong inspect')\n")
    proc = run_child(python_module("irnuc.cosim._objcache", "nope"), cwd=tmp_path, capture=True)
    assert proc.returncode == 2 and "usage" in proc.stderr, proc.stderr


@pytest.mark.cosim
def test_a_build_compiles_against_the_precompiled_header() -> None:
    """A cocotb build and a bulk build link the precompiled header beside the header they
    -include, and g++ used it for every C++ file (``-Winvalid-pch`` would say otherwise in
    the build log); both builds' models then run (the suite's co-simulations)."""
    from irnuc import cosim
    from irnuc.cosim.bulk import build_bulk
    from irnuc.nuc_fixed import load_pipeline

    cfg = load_pipeline("minimal")
    for bld, log in ((cosim.build("nuc_core", cfg), "build.log"),
                     (build_bulk(cfg), "make.log")):
        gch = bld.build_dir / f"{_objcache.PCH_HEADER}.gch"
        assert (bld.build_dir / _objcache.PCH_HEADER).read_text() == _objcache.PCH_TEXT
        assert gch.is_symlink() and gch.resolve().is_file(), gch
        text = (bld.build_dir / log).read_text()
        assert f"-include {_objcache.PCH_HEADER}" in text
        assert "Winvalid-pch" in text and "not used" not in text, log
