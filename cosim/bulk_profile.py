"""Where a bulk co-simulation's CPU goes inside the Verilated model, per RTL instance and
module (``benchmarks/bench_bulk_profile.py``).

Verilator flattens the design into a few C++ functions (``nba_sequent``: the flops,
``nba_comb``: the logic after them, ``ico``: the logic from the inputs), so a sampling
profile names no module. Here the instructions of a run are counted per line of the
generated C++ (valgrind's callgrind on a copy of the bulk build compiled with ``-g``:
the same optimised code with line tables), each line is given to the design instance
whose signal it assigns (Verilator names a signal by its hierarchy,
``method_dpc_top__DOT__u_tail__DOT__u_dpc__DOT__cnt_q``), and each instance to its module
(from the function names of a ``--prof-cfuncs`` Verilation, which end in
``__PROF__<module>__l<line>``). What is not the model's is reported beside it: the
harness's own loop, the scheduler (triggers, the eval loops) and Verilator's inlined
helpers (sign extension, signed multiply, popcount), which callgrind puts in their header.
Instructions are not time (a division or a missed branch costs more than an add), but the
count is exact and repeats on a busy machine, where a timer's samples do not.
"""

from __future__ import annotations

import re
import shutil
from collections import Counter
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

#: callgrind_annotate's line of a source line with its instruction count (or ``.``).
_LINE = re.compile(r"\s*([\d,]+|\.)\s(?:\(\s*[\d.]+%\))?\s{0,8}(.*)$")
#: An assignment's left-hand side: ``vlSelfRef.<var>[...] =`` on one line, or the variable
#: alone on its line (Verilator wraps long assignments before the ``=``).
_LHS = re.compile(r"vlSelfRef\.(\w+?)(?:\[[^\]]*\])*\s*=[^=]")
_LHS_ALONE = re.compile(r"^\s*vlSelfRef\.(\w+)(?:\[[^\]]*\])*\s*$")
_SIGNAL = re.compile(r"vlSelfRef\.(\w+)")
_PROF_FN = re.compile(r"^(?:[\w()]+ )*void (\w+__PROF__(\w+?)__l\d+)\([^)]*\)\s*\{(.*?)^\}",
                      re.S | re.M)
#: The scheduler's own variables (triggers, iteration counts, first-iteration flags).
_SCHED = re.compile(r"__V(ico|act|nba|stl|trig)")
SCHEDULER, PORTS, OTHER = "(scheduler)", "(ports)", "(unassigned)"


def instance_of(var: str, top: str) -> str:
    """The design instance (``u_a/u_b``; ``(top)`` for the top's own signals) a generated
    variable belongs to; :data:`SCHEDULER` and :data:`PORTS` for the scheduler's and the
    top's ports. Verilator's shadow copies (``__Vdly__<var>``) count as ``<var>``."""
    m = re.match(r"__Vdly(?:Set|Val|Dim\d+)?__(\w+)", var)
    if m:
        var = m.group(1)
    if var.startswith(f"{top}__DOT__"):
        parts = var.split("__DOT__")[1:-1]
        return "/".join(parts) or "(top)"
    if _SCHED.match(var):
        return SCHEDULER
    if var.startswith("__V"):
        return OTHER
    return PORTS


def annotated_lines(text: str) -> Iterator[tuple[str, int, str]]:
    """``(file, instructions, code)`` of every source line in ``callgrind_annotate
    --auto=yes`` output (call lines, ``=> ...``, carry a callee's inclusive count and are
    left out)."""
    for section in text.split("-- Auto-annotated source: ")[1:]:
        head, _, body = section.partition("\n")
        for line in body.splitlines():
            m = _LINE.match(line)
            if not m:
                continue
            code = m.group(2)
            if code.lstrip().startswith("=>") or "events annotated" in code:
                continue
            n = 0 if m.group(1) == "." else int(m.group(1).replace(",", ""))
            yield head.strip(), n, code


def total_instructions(text: str) -> int:
    """The run's instruction count (``PROGRAM TOTALS``)."""
    m = re.search(r"^\s*([\d,]+) \(100\.0%\)\s+PROGRAM TOTALS", text, re.M)
    if not m:
        raise ValueError("no PROGRAM TOTALS line in the callgrind_annotate output")
    return int(m.group(1).replace(",", ""))


def module_map(prof_source: str, top: str) -> dict[str, str]:
    """Instance -> module from a ``--prof-cfuncs`` root source: each function is named
    after the module of its statement; the instances it assigns are of that module."""
    votes: dict[str, Counter] = {}
    for _fn, module, body in _PROF_FN.findall(prof_source):
        for var in _LHS.findall(body) + _LHS_ALONE.findall("\n".join(body.splitlines())):
            votes.setdefault(instance_of(var, top), Counter())[module] += 1
    return {i: c.most_common(1)[0][0] for i, c in votes.items() if not i.startswith("(")}


@dataclass
class ModelProfile:
    """Instructions of one run, by where they were spent."""

    total: int
    cycles: int
    instances: Counter = field(default_factory=Counter)
    modules: Counter = field(default_factory=Counter)
    #: Not the model's lines: the harness, Verilator's inlined helpers, the rest.
    outside: Counter = field(default_factory=Counter)
    #: The costliest generated lines of each module (instructions, code).
    lines: dict[str, list[tuple[int, str]]] = field(default_factory=dict)

    def shares(self, counter: Counter, limit: int | None = None) -> list[dict]:
        """Rows ``{name, percent, per_cycle}``, costliest first."""
        return [{"name": k, "percent": round(100 * v / max(self.total, 1), 2),
                 "per_cycle": round(v / max(self.cycles, 1), 1)}
                for k, v in counter.most_common(limit)]


def attribute(text: str, root_source_name: str, modules: Mapping[str, str], top: str,
              cycles: int, keep_lines: int = 3) -> ModelProfile:
    """Share out the instructions of ``callgrind_annotate --auto=yes`` output ``text``:
    the lines of the generated root source (file name ending ``root_source_name``) by the
    instance whose signal the statement assigns (a statement's continuation lines and the
    condition of an ``if`` go with it), instances by ``modules``; every other file by its
    kind."""
    prof = ModelProfile(total=total_instructions(text), cycles=cycles)
    per_line: dict[str, list[tuple[int, str]]] = {}
    current = OTHER
    last_file = None
    for fname, n, code in annotated_lines(text):
        if fname != last_file:
            current, last_file = OTHER, fname
        if not fname.endswith(root_source_name):
            name = Path(fname).name
            kind = ("harness" if "harness" in fname or name.startswith("stl_")
                    else "Verilator helpers (inlined)" if name == "verilated_funcs.h"
                    else "Verilator runtime" if name.startswith("verilated")
                    else f"other ({name})")
            prof.outside[kind] += n
            continue
        if re.match(r"(?:\w+ )*void \w+\(", code) or re.match(r"\s*\w+\(vlSelf\);", code):
            current = OTHER  # a function's entry and exit, a call: the schedule's overhead
        m = _LHS.search(code) or _LHS_ALONE.match(code)
        if m:
            current = instance_of(m.group(1), top)
        elif code.lstrip().startswith("if ("):
            s = _SIGNAL.search(code)
            if s:
                current = instance_of(s.group(1), top)
        # A closing brace with instructions is a function's return (its epilogue).
        owner = OTHER if code.strip() == "}" else current
        if n:
            prof.instances[owner] += n
            module = owner if owner.startswith("(") else modules.get(owner, owner)
            prof.modules[module] += n
            per_line.setdefault(module, []).append((n, code.strip()))
    prof.lines = {k: sorted(v, reverse=True)[:keep_lines] for k, v in per_line.items()}
    return prof


def debug_copy(build_dir: Path, dest: Path, makefile: str, make_opt: tuple[str, ...]) -> Path:
    """A copy of a bulk build folder compiled again with line tables (``-g``; gcc emits
    the same code with or without it); returns the copy."""
    from irnuc.common.process import run_child
    from irnuc.cosim.verilator import verilator_env

    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(build_dir, dest)
    for pattern in ("*.o", "*.a", "*.gch", "*.gcda"):
        for f in dest.glob(pattern):
            f.unlink()
    proc = run_child(["make", "-j", "2", "-C", str(dest), "-f", makefile, *make_opt,
                      "USER_CPPFLAGS=-g"], env=verilator_env(), log=dest / "make-g.log")
    if proc.returncode != 0:
        raise RuntimeError(f"make of the -g copy failed; see {dest / 'make-g.log'}")
    return dest


def callgrind_tools() -> tuple[str, str]:
    """valgrind and callgrind_annotate, or a one-line error naming what is missing."""
    vg, ann = shutil.which("valgrind"), shutil.which("callgrind_annotate")
    if not vg or not ann:
        raise FileNotFoundError("the bulk profile needs valgrind (callgrind and "
                                "callgrind_annotate; Debian: apt-get install valgrind)")
    return vg, ann


def annotate(out_file: Path) -> str:
    """``callgrind_annotate --auto=yes`` of a callgrind output, every line."""
    from irnuc.common.process import run_child

    _, ann = callgrind_tools()
    proc = run_child([ann, "--auto=yes", "--threshold=100", "--context=10000000",
                      str(out_file)], capture=True, single_process=True)
    if proc.returncode != 0:
        raise RuntimeError(f"callgrind_annotate {out_file} failed: {proc.stderr.strip()}")
    return proc.stdout


def profile_method(cfg, coeffs, raw, readings=None, *, hdl_dir: Path | None = None,
                   work_dir: Path | None = None) -> tuple[ModelProfile, int]:
    """Profile the bulk harness of ``method_dpc_top`` for ``cfg`` on ``raw`` frames
    corrected with ``coeffs`` (:func:`irnuc.cosim.method_bulk.run_method_bulk`'s
    arguments): the plain build's code (a ``-g`` copy, :func:`debug_copy`) under callgrind,
    its instance -> module map from a ``--prof-cfuncs`` build (cached), the outputs checked
    bit for bit against the golden model. Returns the profile and the mismatches (missing,
    extra and a framing error counted; 0 expected)."""
    from irnuc.common.cache import cache_dir
    from irnuc.cosim.builds import Build
    from irnuc.cosim.bulk import _MAKE_OPT, build_bulk
    from irnuc.cosim.method_bulk import check_method_bulk, run_method_bulk

    vg, _ = callgrind_tools()
    top = "method_dpc_top"
    bld = build_bulk(cfg, top=top, hdl_dir=hdl_dir)
    pbld = build_bulk(cfg, top=top, hdl_dir=hdl_dir, verilator_args=("--prof-cfuncs",))
    root = f"V{top}___024root__0.cpp"
    modules = module_map((pbld.build_dir / root).read_text(), top)
    work = Path(work_dir) if work_dir is not None else cache_dir("bulk_profile", cfg.name)
    gdir = debug_copy(bld.build_dir, work / "build-g", f"V{top}.mk", _MAKE_OPT)
    gbld = Build(top=top, cfg=cfg, build_dir=gdir, parameters=bld.parameters, waves=False)
    out = work / "callgrind.out"
    out.unlink(missing_ok=True)
    res = run_method_bulk(gbld, coeffs, raw, readings, work_dir=work / "run",
                          wrapper=(vg, "--tool=callgrind", "--dump-instr=yes",
                                   f"--callgrind-out-file={out}"))
    chk = check_method_bulk(res, coeffs, raw, readings)
    bad = chk.mismatches + chk.missing + chk.extra + int(res.frame_err)
    return attribute(annotate(out), root, modules, top, res.cycles), bad
