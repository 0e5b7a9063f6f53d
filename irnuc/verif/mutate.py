"""Mutation testing of the RTL: does the co-simulation suite notice a wrong design?

A :class:`Mutant` is one small, plausible change to one ``hdl/`` file (a constant off by
one, a dropped term in a condition, swapped neighbours, a handshake or marker change, a
reset value, flush and line-buffer addressing). :func:`run_mutants` applies each to a copy
of ``hdl/``, builds ``nuc_dpc_top`` from it and runs the mutation suite (every cocotb test
of ``cocotb_tests/tb_top.py``, one simulation) on the mutant's configuration:

* **killed**: a test failed (or an RTL assertion fired, or the build or simulation broke);
  the first failing test is the killing test;
* **survived**: every test passed;
* **equivalent**: survived, and the catalogue carries the argument why no test can tell
  the mutant from the design at the ports of ``nuc_dpc_top`` (argued; proved where
  ``irnuc mutate --decide`` decided it by a miter, :mod:`irnuc.verif.miter`, and
  :func:`with_decisions` reads that decision: a mutant found different counts as survived);
* **invalid**: the mutant did not build (a catalogue error, not a kill; not counted).

Results are cached in the irnuc cache by the digest of the RTL sources the mutant's top
elaborates, the mutant and the testbench sources; :func:`current_results` gathers each
catalogue mutant's result on the current sources (the report shows it). Mutants run on
the sweep's executor (worker processes, in-process, or a Dask cluster). Mutation testing
runs testbenches, so it sits above them (the ``irnuc.verif`` layer, which imports the
testbench it runs).
"""

from __future__ import annotations

import ast
import functools
import importlib.util
import json
import shutil
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from irnuc.cocotb_tests import tb_top
from irnuc.common.cache import cache_dir, read_cached_json
from irnuc.common.digest import digest, files_digest
from irnuc.common.errors import ToolError, UserError
from irnuc.common.io import write_text_atomic
from irnuc.cosim.sources import HDL_DIR, SIM_HDL_DIR
from irnuc.verif.catalogue import (
    CATALOGUE,
    PKG_FILE,
    PKG_SUITE,
    PKG_TOP,
    SUITE_MODULE,
    SUITE_TOP,
    Mutant,
    catalogue,
)

#: Wall-time limit of one mutant's simulation (a mutant may hang the stream).
RUN_TIMEOUT = 300.0


def rtl_digest() -> str:
    """Digest of the current RTL sources (every ``hdl/*.sv``)."""
    return files_digest(sorted(HDL_DIR.glob("*.sv")))


#: What runs a suite besides its own imports: the build and run layer and the cocotb
#: child's adapter (a broken build or run is a verdict too).
RUNNER_MODULES = ("irnuc.cosim.builds", "irnuc.cosim._cocotb_adapter")
IRNUC_DIR = Path(__file__).resolve().parents[1]


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


@functools.cache
def _imported_names(path: Path, package: str) -> frozenset[str]:
    """Every module name a file may import when it runs (function-level imports too; the
    bodies of ``if TYPE_CHECKING:`` never run): for ``from X import a``, X and X.a."""
    out: set[str] = set()
    todo: list[ast.stmt] = list(ast.parse(path.read_text()).body)
    while todo:  # statements only: an import is never inside an expression
        node = todo.pop()
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = importlib.util.resolve_name("." * node.level + base, package)
            out.add(base)
            out.update(f"{base}.{a.name}" for a in node.names)
        elif isinstance(node, ast.If) and _is_type_checking(node.test):
            todo.extend(node.orelse)
        else:
            for field in ("body", "orelse", "finalbody", "handlers", "cases"):
                for child in getattr(node, field, ()):
                    todo.extend(child.body if isinstance(child, ast.excepthandler | ast.match_case)
                                else [child])
    return frozenset(out)


def _module_file(name: str) -> Path | None:
    """The source file of module ``irnuc...`` (found on disk: importing it to ask would load
    numba and the model), or None for a name that is not a module."""
    base = IRNUC_DIR.joinpath(*name.split(".")[1:])
    for path in (base / "__init__.py", base.with_suffix(".py")):
        if path.is_file():
            return path
    return None


@functools.cache
def suite_closure(module: str) -> tuple[Path, ...]:
    """The irnuc source files a cocotb suite runs: the suite module, every ``irnuc`` module it
    imports, transitively (parent packages included), and :data:`RUNNER_MODULES`'."""
    seen: dict[str, Path | None] = {}
    todo = [module, *RUNNER_MODULES]
    while todo:
        name = todo.pop()
        if name in seen or not (name == "irnuc" or name.startswith("irnuc.")):
            continue
        path = _module_file(name)
        seen[name] = path
        if path is None:
            continue  # a name imported from a module, not a module
        todo.extend(name.rsplit(".", k)[0] for k in range(1, name.count(".") + 1))
        is_pkg = path.name == "__init__.py"
        todo.extend(_imported_names(path, name if is_pkg else name.rpartition(".")[0]))
    return tuple(sorted({p for p in seen.values() if p is not None}))


def _suite_digest(module: str = SUITE_MODULE) -> str:
    """What a mutant's verdict depends on besides the RTL: the Python its suite runs
    (:func:`suite_closure`: the testbench, its helpers, the golden model and co-simulation
    modules it imports, not the pytest files) and the simulation-only HDL. A change to
    another suite's testbench keeps this suite's cached verdicts."""
    return files_digest([*suite_closure(module), *sorted(SIM_HDL_DIR.glob("*.sv"))])


def top_digest(top: str) -> str:
    """Digest of the RTL sources ``top`` elaborates (a mutant's verdict depends on these
    only: a change elsewhere in hdl/ keeps its cached result)."""
    from irnuc.cosim.sources import hdl_sources

    return files_digest(hdl_sources(top))


def _mutant_key(m: Mutant, suites: dict[str, str] | None = None,
                tops: dict[str, str] | None = None) -> str:
    """The cache key of a mutant's result: the RTL its top elaborates, its suite's sources
    (the package check's too for the package's mutants), the mutant (``suites``, ``tops``:
    digests computed once for many mutants)."""
    d = asdict(m)
    if not d["also"]:
        del d["also"]  # keys of one-site mutants as before the field existed
    if not d["equivalent_when"]:
        del d["equivalent_when"]  # and of mutants equivalent nowhere or everywhere
    if d["yosys"] is None:
        del d["yosys"]  # and of the catalogue's (text) mutants
    if (d["top"], d["suite"]) == (SUITE_TOP, SUITE_MODULE):
        del d["top"], d["suite"]  # and of the mutants of the two-point suite
        if d["file"] == PKG_FILE:
            d["package_check"] = PKG_SUITE  # the verdict includes the package check
    rtl = (tops or {}).get(m.top) or top_digest(m.top)
    suite = (suites or {}).get(m.suite) or _suite_digest(m.suite)
    if "package_check" in d:
        suite = digest([suite, _suite_digest(PKG_SUITE)])
    return digest({"rtl": rtl, "suite": suite, "mutant": d})


@dataclass
class MutantResult:
    id: str
    file: str
    what: str
    config: str
    status: str  # killed, survived, equivalent, invalid
    killed_by: str | None = None
    message: str = ""
    equivalent: str | None = None
    seconds: float = 0.0
    cached: bool = False


def _suite_cases(m: Mutant, cfg) -> list[str] | None:
    """The cocotb tests a mutant runs on ``cfg``: all, but on a configuration that is not
    a named one the tb_top tests that need a sensor-like format are left out
    (``tb_top.RANDOM_CONFIG_SKIP``)."""
    from irnuc.cosim import cocotb_test_names
    from irnuc.nuc_fixed import pipeline_names

    if m.suite != SUITE_MODULE or cfg.name in pipeline_names():
        return None
    return [t for t in cocotb_test_names(tb_top) if t not in tb_top.RANDOM_CONFIG_SKIP]


def run_mutant(m: Mutant, *, use_cache: bool = True, timeout: float = RUN_TIMEOUT,
               cfg=None) -> dict:
    """Apply, build and run one mutant; a JSON-ready :class:`MutantResult` (cached).
    ``cfg``: run on this configuration instead of the mutant's own."""
    from irnuc import cosim
    from irnuc.cosim.coverage import config_label

    key = _mutant_key(m) if cfg is None else digest({"mutant": _mutant_key(m),
                                                     "config": cfg.to_dict()})
    cache = cache_dir("mutate", "mutants") / f"{m.id}-{key}.json"
    if use_cache and cache.is_file():
        out = json.loads(cache.read_text())
        out["cached"] = True
        return out
    cfg = cfg if cfg is not None else m.pipeline()
    t0 = time.perf_counter()
    work = Path(tempfile.mkdtemp(prefix=f"{m.id}.", dir=cache_dir("mutate", "work")))
    bld = None
    try:
        hdl = work / "hdl"
        shutil.copytree(HDL_DIR, hdl, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
        killed_by, message, invalid = None, "", False
        try:
            if m.yosys is not None:  # an automatic mutant: the top's mutated netlist
                _install_netlist(m, cfg, hdl, work)
            else:
                f = hdl / m.file
                f.write_text(m.apply(f.read_text()))
            bld = cosim.build(m.top, cfg, hdl_dir=hdl)
        except (cosim.RtlError, ToolError) as exc:  # ToolError: a netlist Yosys refused
            invalid, message = True, str(exc)[:600]
            _remove_failed_builds(hdl)
        if bld is not None:
            xml = work / "results.xml"
            try:
                res = cosim.read_results(cosim.run(bld, m.suite, results_xml=xml,
                                                   testcase=_suite_cases(m, cfg),
                                                   timeout=timeout))
                fired = cosim.assertion_failures(xml)
                failed = [r for r in res.values() if not r.passed]
                if failed:
                    killed_by = failed[0].name
                    message = (fired[0] if fired else failed[0].message)[:600]
                elif m.file == PKG_FILE and m.suite == SUITE_MODULE:
                    killed_by, message = _package_check(m, cfg, hdl, work, timeout)
            except cosim.SimulationTimeout as exc:
                killed_by, message = "timeout", str(exc)[:600]
            except cosim.RtlError as exc:
                killed_by, message = "simulation", str(exc)[:600]
        why = m.equivalence(cfg)
        status = ("invalid" if invalid else "killed" if killed_by else
                  "equivalent" if why else "survived")
        decided = None
        if status == "survived" and m.yosys:
            # A survivor of the automatic mutants: equivalent or not, decided by a miter.
            decided = _decide(m, cfg, work)
            if decided["verdict"] == "equivalent":
                status, why = "equivalent", f"proved ({decided['engine']}): {decided['message']}"
            else:
                message = f"{decided['verdict']} ({decided['engine']}): {decided['message']}"
        out = asdict(MutantResult(id=m.id, file=m.file, what=m.what, config=config_label(cfg),
                                  status=status, killed_by=killed_by, message=message,
                                  equivalent=why,
                                  seconds=round(time.perf_counter() - t0, 2)))
        if decided is not None:
            out["decided"] = decided
    finally:
        shutil.rmtree(work, ignore_errors=True)
        if bld is not None:
            shutil.rmtree(bld.build_dir, ignore_errors=True)
    write_text_atomic(cache, json.dumps(out, indent=1))
    return out


def _netlists(m: Mutant, cfg, work: Path) -> tuple[Path, Path, list]:
    """The original (``<top>__gold``, cached per RTL and configuration) and mutated
    (``<top>__mut``) netlists of an automatic mutant, and the top's ports."""
    from irnuc.cosim import netlist
    from irnuc.cosim.sources import hdl_sources, top_parameters

    srcs = hdl_sources(m.top)
    params = top_parameters(m.top, cfg)
    gold_dir = cache_dir("mutate", "netlists") / digest({"rtl": rtl_digest(), "top": m.top,
                                                        "params": params,
                                                        "passes": netlist.NETLIST_VERSION})
    gold = gold_dir / "gold.v"
    if not gold.is_file():
        tmp = Path(tempfile.mkdtemp(prefix="gold.", dir=cache_dir("mutate", "work")))
        netlist.write_netlist(srcs, m.top, params, tmp / "gold.v", "gold")
        gold_dir.mkdir(parents=True, exist_ok=True)
        for name in ("gold.json", "gold.v"):  # gold.v last: it marks the pair complete
            write_text_atomic(gold_dir / name, (tmp / name).read_text())
        shutil.rmtree(tmp, ignore_errors=True)
    mut = work / "netlist" / "mut.v"
    if not mut.is_file():
        netlist.write_netlist(srcs, m.top, params, mut, "mut", mutation=m.yosys or None)
    return gold, mut, netlist.ports(gold)


def _install_netlist(m: Mutant, cfg, hdl: Path, work: Path) -> None:
    from irnuc.cosim import netlist

    _, mut, _ = _netlists(m, cfg, work)
    netlist.install(hdl, m.top, mut, "mut")


def _decide(m: Mutant, cfg, work: Path) -> dict:
    """Whether a surviving automatic mutant is equivalent to the design (a miter of the
    two netlists: irnuc.cosim.formal.equivalence); its trace kept in the cache."""
    from irnuc.cosim import formal

    gold, mut, ports = _netlists(m, cfg, work)
    res = formal.equivalence(gold, mut, m.top, ports, work / "equiv")
    if res.get("vcd") and Path(res["vcd"]).is_file():
        dest = cache_dir("mutate", "traces") / f"{m.id}-{_mutant_key(m)[:16]}.vcd"
        shutil.copyfile(res["vcd"], dest)
        res["vcd"] = str(dest)
    return res


def _package_check(m: Mutant, cfg, hdl: Path, work: Path, timeout: float
                   ) -> tuple[str | None, str]:
    """The package check (``tb_pkg``) on the mutated package: (killing test, message) or
    (None, "") when it passes."""
    from irnuc import cosim

    bld = cosim.build(PKG_TOP, cfg, hdl_dir=hdl)
    try:
        xml = work / "pkg.xml"
        res = cosim.read_results(cosim.run(bld, PKG_SUITE, results_xml=xml, timeout=timeout))
        failed = [r for r in res.values() if not r.passed]
        if failed:
            return f"tb_pkg.{failed[0].name}", failed[0].message[:600]
        return None, ""
    finally:
        shutil.rmtree(bld.build_dir, ignore_errors=True)


def baseline_check(mutants: Sequence[Mutant], use_cache: bool = True) -> None:
    """The design itself must pass the mutation suite on every configuration the mutants
    use (else every mutant would look killed); raises :class:`RtlError` otherwise. A pass
    is cached, keyed like a mutant's verdict (the RTL, the suite, the configuration)."""
    from irnuc import cosim

    seen: set[tuple[str, str, str]] = set()
    for m in mutants:
        cfg = m.pipeline()
        if (cfg.digest(), m.top, m.suite) in seen:
            continue
        seen.add((cfg.digest(), m.top, m.suite))
        key = digest({"rtl": rtl_digest(), "suite": _suite_digest(m.suite), "config": cfg.digest(),
                      "top": m.top, "module": m.suite})
        passed = cache_dir("mutate", "baseline") / f"{cfg.name}-{key}.passed"
        if use_cache and passed.is_file():
            continue
        bld = cosim.build(m.top, cfg)
        xml = (cache_dir("mutate", "baseline")
               / f"{cfg.name}-{cfg.digest()[:8]}-{m.suite.rsplit('.', 1)[-1]}.xml")
        res = cosim.read_results(cosim.run(bld, m.suite, results_xml=xml,
                                           timeout=RUN_TIMEOUT))
        bad = [r.name for r in res.values() if not r.passed]
        if bad or not res:
            raise cosim.RtlError(f"the unmutated design fails the mutation suite on "
                                 f"{cfg.name} ({', '.join(bad) or 'no result'}); see {xml}")
        write_text_atomic(passed, json.dumps(sorted(res)) + "\n")


def _remove_failed_builds(hdl: Path) -> None:
    """Remove the build folders of a mutant copy that did not build (no stamp file)."""
    from irnuc.cosim.builds import sim_build_dir

    for spec in sim_build_dir().glob("*/irnuc_build_spec.json"):
        try:
            if str(hdl) in spec.read_text():
                shutil.rmtree(spec.parent, ignore_errors=True)
        except OSError:
            continue


def _job(m: dict, use_cache: bool) -> dict:
    return run_mutant(Mutant(**{**m, "changes": _tuples(m["changes"]),
                                "also": tuple(tuple(c) for c in m["also"]),
                                "equivalent_when": tuple(tuple(c) for c in
                                                         m["equivalent_when"])}),
                      use_cache=use_cache)


def _tuples(v: Any) -> Any:
    """Lists (of a round trip through asdict / JSON) back to the nested tuples of
    ``changes``."""
    return tuple(_tuples(x) for x in v) if isinstance(v, list | tuple) else v


def summarize(results: Sequence[dict], total_catalogue: int | None = None) -> dict:
    """killed / survived / equivalent counts, score and the per-mutant table."""
    killed = [r for r in results if r["status"] == "killed"]
    survived = [r for r in results if r["status"] == "survived"]
    equivalent = [r for r in results if r["status"] == "equivalent"]
    invalid = [r for r in results if r["status"] == "invalid"]
    non_eq = len(killed) + len(survived)
    return {
        "rtl_digest": rtl_digest(), "total": len(results),
        "catalogue_size": total_catalogue if total_catalogue is not None else len(CATALOGUE),
        "killed": len(killed), "survived": len(survived), "equivalent": len(equivalent),
        "invalid": [r["id"] for r in invalid],
        "score": round(len(killed) / non_eq, 4) if non_eq else 1.0,
        "survivors": [r["id"] for r in survived],
        "equivalents": {r["id"]: r["equivalent"] for r in equivalent},
        "killing_tests": {r["id"]: r["killed_by"] for r in killed},
        "mutants": list(results),
    }


def run_mutants(mutants: Sequence[Mutant] | None = None, *, workers: int = 1,
                scheduler: str | None = None, use_cache: bool = True,
                progress: Callable[[int, int], None] | None = None) -> dict:
    """Run mutants (default: the whole catalogue) on the sweep's executor; the summary.

    The summary is also cached as the latest campaign of the current RTL sources
    (:func:`cached_summary`) when the whole catalogue ran.
    """
    from irnuc.common.executor import open_executor

    mutants = list(CATALOGUE if mutants is None else mutants)
    results = []
    with open_executor(workers, scheduler) as handle:  # a bad --scheduler fails first
        baseline_check(mutants, use_cache)
        futures = [handle.executor.submit(_job, asdict(m), use_cache) for m in mutants]
        for i, fut in enumerate(futures):
            results.append(fut.result())
            if progress is not None:
                progress(i + 1, len(futures))
    summary = summarize(with_decisions(results))
    summary["complete"] = {m.id for m in mutants} == {m.id for m in CATALOGUE}
    path = cache_dir("mutate") / f"summary-{rtl_digest()}.json"
    if summary["complete"] or not path.is_file():
        write_text_atomic(path, json.dumps(summary, indent=1))
    return summary


def cached_summary() -> dict | None:
    """The latest mutation campaign for the current RTL sources (killed, survived,
    equivalent with reasons, total, score, killing test per mutant), or None."""
    return read_cached_json(cache_dir("mutate") / f"summary-{rtl_digest()}.json")


def cached_results(mutants: Sequence[Mutant]) -> tuple[list[dict], list[str]]:
    """The cached result of each mutant on the current RTL and suite sources, nothing
    run: (the results found, the ids without one)."""
    suites = {s: _suite_digest(s) for s in {m.suite for m in mutants}}
    tops = {top: top_digest(top) for top in {m.top for m in mutants}}
    found, missing = [], []
    for m in mutants:
        res = read_cached_json(cache_dir("mutate", "mutants")
                               / f"{m.id}-{_mutant_key(m, suites, tops)}.json")
        if isinstance(res, dict):
            found.append(res)
        else:
            missing.append(m.id)
    return found, missing


def with_decisions(results: Sequence[dict]) -> list[dict]:
    """The results with each catalogue equivalent's formal decision where the cache holds
    one (``irnuc mutate --decide``, :mod:`irnuc.verif.miter`): proved equivalent (the
    reason says so, the argument after it), different on legal inputs (the mutant counts
    as survived: its argument is wrong), undecided or never decided (the reason starts
    "argued"). Nothing is run."""
    from irnuc.verif import miter

    by_id = {m.id: m for m in CATALOGUE}
    out = []
    for r in results:
        m = by_id.get(r["id"])
        if r["status"] != "equivalent" or m is None or m.yosys is not None:
            out.append(r)
            continue
        dec = miter.cached(m) if m.top in miter.FRAME_TOPS else None
        r = dict(r)
        if dec is not None:
            r["decided"] = dec
        if dec is not None and dec.get("verdict") == "equivalent":
            r["equivalent"] = f"{miter.label(dec)}; argument: {r['equivalent']}"
        elif dec is not None and dec.get("verdict") == "different":
            r["status"], r["message"] = "survived", miter.label(dec)
        else:
            r["equivalent"] = f"argued: {r['equivalent']}" + (
                f" ({miter.label(dec)})" if dec is not None else "")
        out.append(r)
    return out


def current_results() -> dict:
    """The catalogue's campaign as the cache holds it for the current sources: every
    mutant's result on exactly these sources (however many ``irnuc mutate --only`` runs
    produced them), ``missing`` the ones without (never counted), ``complete`` when none
    is; the counts and score of :func:`summarize` over the ones found."""
    found, missing = cached_results(CATALOGUE)
    summary = summarize(with_decisions(found))
    summary |= {"missing": missing, "complete": not missing}
    return summary


# ---- several configurations ---------------------------------------------------------------

def elaborates_differently(m: Mutant, cfg, hdl_root: Path | None = None) -> bool:
    """Whether the mutant's RTL elaborates (Verilator, ``irnuc.cosim.elaborate``) to
    another design than the unmutated RTL on ``cfg``: where it does not, no test on that
    configuration can tell them apart. A mutant that does not elaborate differs."""
    from irnuc.cosim import elaborate
    from irnuc.cosim.verilator import RtlError

    base = _base_elaboration(m.top, cfg.digest(), cfg)
    with tempfile.TemporaryDirectory(prefix=f"{m.id}.elab.", dir=hdl_root) as tmp:
        hdl = Path(tmp) / "hdl"
        shutil.copytree(HDL_DIR, hdl, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
        f = hdl / m.file
        f.write_text(m.apply(f.read_text()))
        try:
            return elaborate.elaborate(m.top, cfg, hdl).digest != base
        except RtlError:
            return True


_BASE: dict[tuple[str, str], str] = {}


def _base_elaboration(top: str, key: str, cfg) -> str:
    from irnuc.cosim import elaborate

    if (top, key) not in _BASE:
        _BASE[(top, key)] = elaborate.elaborate(top, cfg).digest
    return _BASE[(top, key)]


#: The ``--configs`` word for the CI sample of random legal configurations.
SAMPLE = "sample"


def configurations(spec: str) -> list:
    """The configurations of ``irnuc mutate --configs``: a comma-separated list of named
    two-point pipelines (``pipelines.toml``) and ``sample`` (``configspace.ci_sample()``,
    the fixed random sample CI runs), in the order given. A one-line error (UserError)
    for an empty list, an unknown name or a name given twice."""
    from irnuc.common.schema import nearest
    from irnuc.cosim import configspace

    names = {c.name: c for c in configspace.named(SUITE_TOP)}
    words = [w.strip() for w in spec.split(",")]
    if not spec.strip() or "" in words:
        raise UserError(f"--configs {spec!r}: an empty name; give a comma-separated list of "
                        f"{SAMPLE!r} and named configurations ({', '.join(names)})")
    out = []
    for w in words:
        if words.count(w) > 1:
            raise UserError(f"--configs {w}: given more than once")
        if w == SAMPLE:
            out += configspace.ci_sample(SUITE_TOP)
        elif w in names:
            out.append(names[w])
        else:
            raise UserError(f"--configs {w}: no such configuration"
                            f"{nearest(w, [SAMPLE, *names])} (allowed: {SAMPLE!r} and "
                            f"{', '.join(names)})")
    seen = [c.name for c in out]
    twice = sorted({n for n in seen if seen.count(n) > 1})
    if twice:
        raise UserError(f"--configs: configuration {twice[0]} given twice (it is in the "
                        f"sample and named)")
    return out


def run_per_configuration(mutants: Sequence[Mutant], configs: Sequence, *,
                          use_cache: bool = True,
                          progress: Callable[[str, str, str], None] | None = None) -> dict:
    """Each two-point mutant (``nuc_dpc_top``) on every configuration of ``configs`` where
    its code elaborates differently; the score per configuration and per mutant.

    Returns ``{"configurations": {name: {killed, survived, equivalent, same, score}},
    "mutants": {id: {name: status}}, "overall": {...}}``: status ``same`` where the
    mutant elaborates to the unmutated design (not run); a mutant is killed overall when
    some configuration kills it."""
    from irnuc import cosim

    per_cfg: dict[str, dict[str, Any]] = {}
    per_mut: dict[str, dict[str, str]] = {}
    for cfg in configs:
        bld = cosim.build(SUITE_TOP, cfg)  # the design must pass first (else every mutant dies)
        xml = cache_dir("mutate", "baseline") / f"{cfg.name}-{cfg.digest()[:8]}-percfg.xml"
        probe = Mutant("baseline", "", "", "", "")
        res = cosim.read_results(cosim.run(bld, SUITE_MODULE, results_xml=xml,
                                           testcase=_suite_cases(probe, cfg),
                                           timeout=RUN_TIMEOUT))
        bad = [r.name for r in res.values() if not r.passed]
        if bad or not res:
            raise cosim.RtlError(f"the unmutated design fails tb_top on {cfg.name}: "
                                 f"{', '.join(bad) or 'no result'}; see {xml}")
        row = {"killed": 0, "survived": 0, "equivalent": 0, "same": 0, "invalid": 0}
        for m in mutants:
            if m.top != SUITE_TOP:
                continue
            if not elaborates_differently(m, cfg):
                status = "same"
            else:
                status = run_mutant(m, use_cache=use_cache, cfg=cfg)["status"]
            row[status] += 1
            per_mut.setdefault(m.id, {})[cfg.name] = status
            if progress is not None:
                progress(cfg.name, m.id, status)
        non_eq = row["killed"] + row["survived"]
        row["score"] = round(row["killed"] / non_eq, 4) if non_eq else None
        per_cfg[cfg.name] = row
    killed = [i for i, v in per_mut.items() if "killed" in v.values()]
    survived = [i for i, v in per_mut.items() if i not in killed and "survived" in v.values()]
    return {"configurations": per_cfg, "mutants": per_mut,
            "overall": {"killed": len(killed), "survived": len(survived),
                        "survivors": survived,
                        "score": round(len(killed) / (len(killed) + len(survived)), 4)
                        if killed or survived else None}}


__all__ = [
    "CATALOGUE",
    "SAMPLE",
    "Mutant",
    "cached_results",
    "cached_summary",
    "catalogue",
    "configurations",
    "current_results",
    "elaborates_differently",
    "rtl_digest",
    "run_mutant",
    "run_mutants",
    "run_per_configuration",
    "summarize",
    "top_digest",
    "with_decisions",
]
