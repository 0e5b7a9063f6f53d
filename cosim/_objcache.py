"""Verilator's runtime objects and its main header, compiled once and shared by every build.

Every cocotb build compiles the same Verilator runtime (``verilated.cpp``,
``verilated_vpi.cpp``, ``verilated_threads.cpp``, ``verilated_dpi.cpp``, with coverage or
tracing ``verilated_cov.cpp`` and the FST writer): about half of a build's compile time,
although nothing in them depends on the design. After a build, :func:`store` keeps them
in the irnuc cache under a key of everything their compilation depends on (the generated
makefiles' settings, the Verilator and compiler versions); before the next build's
``make``, :func:`seed` copies them into the new build folder, newer than its makefile, so
make links them instead of compiling them again. The design's own objects (the model and
cocotb's ``verilator.cpp``, which includes the model's header) are always compiled.

Every C++ file of a build (the model, cocotb's ``verilator.cpp``, the bulk harness, the
runtime) is compiled with ``-include vl_pch.h`` (:data:`PCH_HEADER`, in ``BUILD_ARGS``), a
header that includes ``verilated.h``: parsing it took about 1.4 s of every file's compile,
two files per build. :func:`seed` writes the header into the build folder and links next
to it a precompiled ``vl_pch.h.gch``, made once per set of compile flags (read from make's
dry run of the build's own rule) in the irnuc cache. g++ uses it only where it matches the
file's flags (and parses the header otherwise): the code compiled is the same either way.

Run by the cocotb runner between Verilator and make (``cosim._cocotb_adapter``):
``python -P <this file> seed|store BUILD_DIR`` (a script: no import of irnuc.cosim).
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from irnuc.common.cache import cache_dir
from irnuc.common.digest import digest


def _makefiles(build_dir: Path) -> tuple[Path, Path]:
    """The build's generated makefile and class list (``<prefix>.mk``,
    ``<prefix>_classes.mk``; the prefix is ``Vtop`` for cocotb's builds)."""
    (classes,) = build_dir.glob("*_classes.mk")
    return classes.with_name(classes.name.removesuffix("_classes.mk") + ".mk"), classes


def _global_objects(build_dir: Path) -> list[str]:
    """The runtime objects the build's makefiles list (``VM_GLOBAL_FAST``/``_SLOW``)."""
    text = _makefiles(build_dir)[1].read_text()
    names: list[str] = []
    for block in re.findall(r"VM_GLOBAL_(?:FAST|SLOW) \+= \\\n((?:  \S+ \\\n)*)", text):
        names += [ln.strip().rstrip("\\").strip() for ln in block.splitlines()]
    return [f"{n}.o" for n in names if n]


def _compiler() -> str:
    cxx = os.environ.get("CXX", "c++")
    try:
        out = subprocess.run([cxx, "--version"], capture_output=True, text=True, check=False)
        return out.stdout.splitlines()[0] if out.stdout else cxx
    except OSError:
        return cxx


def key(build_dir: Path) -> str:
    """What the runtime objects of ``build_dir`` depend on: the makefiles' settings (not
    the design-specific class lists and targets), the Verilator headers' folder and the
    compiler."""
    mk_file, classes_file = _makefiles(build_dir)
    # The model's name (VM_PREFIX: Vtop for cocotb's builds, V<top> for the bulk harness's)
    # appears in its own lines, in comments and in the classes file's include; none of them
    # reaches the runtime objects, so builds of every top share them.
    mk = [ln for ln in mk_file.read_text().splitlines()
          if not re.match(r"(#|include \S+_classes\.mk$|default:|\S+: \$\(VK_USER_OBJS\)"
                          r"|VM_(MOD)?PREFIX)", ln)]
    classes = [ln for ln in classes_file.read_text().splitlines()
               if ln.startswith("VM_") and "+=" not in ln]
    return digest({"mk": mk, "classes": classes, "globals": _global_objects(build_dir),
                   "compiler": _compiler()})


def _store_dir(build_dir: Path) -> Path:
    return cache_dir("sim_build", "_runtime") / key(build_dir)


#: The header every C++ file of a build includes first (``-include``, ``BUILD_ARGS``).
PCH_HEADER = "vl_pch.h"
PCH_TEXT = '#include "verilated.h"\n'


def write_pch_header(build_dir: Path) -> None:
    """Put :data:`PCH_HEADER` into ``build_dir`` (every build needs it, precompiled or not)."""
    (Path(build_dir) / PCH_HEADER).write_text(PCH_TEXT)


def _compile_flags(build_dir: Path) -> list[str] | None:
    """The compiler and flags make uses for the build's C++ files: its dry run of the first
    runtime object's rule, less the object, the source, the dependency file and the
    header's own ``-include``. None where make prints no such command."""
    objs = _global_objects(build_dir)
    if not objs:
        return None
    mk_file, _ = _makefiles(build_dir)
    proc = subprocess.run(["make", "-n", "-B", "-f", mk_file.name, objs[0]], cwd=build_dir,
                          capture_output=True, text=True, check=False)
    line = next((ln for ln in proc.stdout.splitlines() if f" -o {objs[0]} " in ln), None)
    if proc.returncode != 0 or line is None:
        return None
    words, out, skip = shlex.split(line), [], 0
    for i, w in enumerate(words):
        if skip:
            skip -= 1
        elif w in ("-c", "-MMD", "-MP"):
            continue
        elif w == "-o" or (w == "-include" and i + 1 < len(words)
                           and words[i + 1] == PCH_HEADER):
            skip = 1
        elif w.endswith(".cpp"):
            continue
        else:
            out.append(w)
    return out


def seed_pch(build_dir: Path) -> bool:
    """Write the header into ``build_dir`` and link its precompiled form beside it, compiled
    into the cache first for a new set of flags. Returns whether the build has it; a
    failure only costs the time it would save."""
    build_dir = Path(build_dir)
    write_pch_header(build_dir)
    flags = _compile_flags(build_dir)
    if not flags:
        return False
    store = cache_dir("sim_build", "_pch", digest({"flags": flags, "compiler": _compiler(),
                                                   "text": PCH_TEXT}))
    gch = store / f"{PCH_HEADER}.gch"
    if not gch.is_file():
        (store / PCH_HEADER).write_text(PCH_TEXT)
        fd, tmp = tempfile.mkstemp(prefix=".gch-", dir=store)
        os.close(fd)
        proc = subprocess.run([*flags, "-x", "c++-header", "-o", tmp, PCH_HEADER], cwd=store,
                              capture_output=True, text=True, check=False)
        if proc.returncode != 0:
            Path(tmp).unlink(missing_ok=True)
            return False
        os.chmod(tmp, 0o644)
        os.replace(tmp, gch)  # whole or not at all, whoever made it first
    link = build_dir / gch.name
    link.unlink(missing_ok=True)
    link.symlink_to(gch)
    return True


def seed(build_dir: Path) -> int:
    """Copy the cached runtime objects (and their dependency files) into ``build_dir``,
    stamped now, and provide the precompiled header (:func:`seed_pch`); return how many
    objects (0 when none are cached yet)."""
    seed_pch(build_dir)
    src = _store_dir(build_dir)
    if not src.is_dir():
        return 0
    n = 0
    for obj in _global_objects(build_dir):
        for name in (obj, obj.removesuffix(".o") + ".d"):
            if (src / name).is_file():
                shutil.copyfile(src / name, build_dir / name)
                os.utime(build_dir / name)  # newer than the makefile generated just before
                n += 1
    return n


def store(build_dir: Path) -> bool:
    """Keep ``build_dir``'s runtime objects for the next builds (once per key; the folder
    is filled aside and renamed into place). Returns whether it stored them."""
    dst = _store_dir(build_dir)
    objs = _global_objects(build_dir)
    if dst.is_dir() or not objs or not all((build_dir / o).is_file() for o in objs):
        return False
    tmp = Path(tempfile.mkdtemp(prefix=".runtime-", dir=dst.parent))
    for obj in objs:
        for name in (obj, obj.removesuffix(".o") + ".d"):
            if (build_dir / name).is_file():
                shutil.copyfile(build_dir / name, tmp / name)
    try:
        tmp.rename(dst)
    except OSError:  # another build stored them first
        shutil.rmtree(tmp, ignore_errors=True)
        return False
    return True


def main(argv: list[str]) -> int:
    if len(argv) != 2 or argv[0] not in ("seed", "store"):
        print("usage: python -P _objcache.py seed|store BUILD_DIR", file=sys.stderr)
        return 2
    build_dir = Path(argv[1])
    if argv[0] == "seed":
        seed(build_dir)
    else:
        store(build_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
