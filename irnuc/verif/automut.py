"""Mutants nobody chose: ``irnuc mutate --auto N`` (docs/mutation.md, "Automatic mutants").

Besides the hand-written catalogue (:mod:`irnuc.verif.catalogue`), Yosys draws N mutations
per module (``mutate -list N -seed S`` through pyosys, :func:`irnuc.cosim.netlist.draw`: an
even sampling over the module's source lines, wires and bits; each inverts a cell's port
bit, ties it to 0 or 1, or XORs it with another bit). Each becomes a
:class:`~irnuc.verif.mutant.Mutant` whose ``yosys`` field is that command, run by the
mutation machinery (:func:`irnuc.verif.mutate.run_mutant`) in the module's top with that
top's testbench: the top's mutated netlist, behind the top's own header, replaces its RTL.
A mutant the suite does not kill is not argued equivalent: a miter of the original and
mutated netlists decides it (:func:`irnuc.cosim.formal.equivalence`: induction, PDR, or a
distinguishing trace). The score is killed / (killed + survived) over the mutants not
proved equivalent, reported beside the catalogue's.

The netlist of the unmutated top must pass the same suite first (:func:`baseline`), or
every mutant would look killed.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from irnuc.cocotb_tests import tb_axis, tb_axis_ffc, tb_axis_table, tb_interp_weight, tb_top
from irnuc.common.cache import cache_dir, read_cached_json
from irnuc.common.digest import digest
from irnuc.common.errors import UserError
from irnuc.common.io import write_text_atomic
from irnuc.verif import mutate
from irnuc.verif.mutant import Mutant

#: The seed of the campaigns (a fixed seed: the same mutants on the same RTL).
SEED = 1
#: The mutants per module of the campaign the report shows (``irnuc mutate --auto 8``).
CAMPAIGN_N = 8


@dataclass(frozen=True)
class Target:
    """A module (``hdl/<module>.sv``) whose mutants run in ``top`` with ``suite`` on
    ``config``."""

    module: str
    top: str
    suite: str
    config: str


#: The modules of the integration layer and the two-point path, each in the top and suite
#: that exercise it (the wrapper's parts through the wrapper).
TARGETS: dict[str, Target] = {t.module: t for t in (
    Target("irnuc_axis_framer", "irnuc_axis_top", tb_axis.__name__, "minimal"),
    Target("irnuc_axis_buffer", "irnuc_axis_top", tb_axis.__name__, "minimal"),
    Target("irnuc_axil_regs", "irnuc_axis_top", tb_axis.__name__, "minimal"),
    # The register file's generated block (peakrdl-regblock, irnuc's CPU interface).
    Target("irnuc_axil_regblock", "irnuc_axis_top", tb_axis.__name__, "minimal"),
    Target("irnuc_axis_top", "irnuc_axis_top", tb_axis.__name__, "minimal"),
    Target("irnuc_axis_ffc", "irnuc_axis_top", tb_axis_ffc.__name__, "ffc14"),
    Target("ffc_ctrl", "irnuc_axis_top", tb_axis_ffc.__name__, "ffc14"),
    Target("irnuc_axis_table", "irnuc_axis_top", tb_axis_table.__name__, "table14"),
    Target("irnuc_spill_register", "nuc_dpc_top", tb_top.__name__, "minimal"),
    Target("nuc_core", "nuc_dpc_top", tb_top.__name__, "minimal"),
    Target("dpc_ctrl", "nuc_dpc_top", tb_top.__name__, "minimal"),
    Target("interp_weight", "interp_weight", tb_interp_weight.__name__, "table14"),
)}


def targets(spec: str | None) -> list[Target]:
    """The targets of ``--modules`` (comma-separated module names; None: all)."""
    if spec is None:
        return list(TARGETS.values())
    from irnuc.common.schema import nearest

    out = []
    for w in (x.strip() for x in spec.split(",")):
        if w not in TARGETS:
            raise UserError(f"--modules {w or repr(spec)}: no such module{nearest(w, list(TARGETS))}"
                            f" (allowed: {', '.join(TARGETS)})")
        out.append(TARGETS[w])
    return out


def _what(command: str, src: str) -> str:
    opts = dict(zip(command.split()[1::2], command.split()[2::2], strict=False))
    mode = {"inv": "inverted", "const0": "tied to 0", "const1": "tied to 1",
            "cnot0": "XOR with bit {ctrl} (0)", "cnot1": "XOR with bit {ctrl} (1)"}
    how = mode.get(opts.get("-mode", ""), opts.get("-mode", "?")).format(
        ctrl=opts.get("-ctrlbit", "?"))
    cell = opts.get("-cell", "?").lstrip("\\")
    sig = opts.get("-wire", cell).lstrip("\\")
    bit = opts.get("-wirebit", opts.get("-portbit", "0"))
    return f"{sig}[{bit}] ({opts.get('-port', '?')} of {cell}) {how} at {src}"


def _draw_cache(target: Target, n: int, seed: int) -> Path:
    key = digest({"rtl": mutate.rtl_digest(), "target": asdict(target), "n": n, "seed": seed})
    return cache_dir("mutate", "auto") / f"draw-{target.module}-{key}.json"


def draw(target: Target, n: int, seed: int = SEED, *, cached_only: bool = False
         ) -> list[Mutant] | None:
    """``n`` automatic mutants of ``target`` (cached per RTL, target, n and seed;
    ``cached_only``: None when that draw is not in the cache)."""
    import shutil
    import tempfile

    from irnuc.cosim import netlist
    from irnuc.cosim.sources import hdl_sources, top_parameters
    from irnuc.nuc_fixed import load_pipeline

    cfg = load_pipeline(target.config)
    cache = _draw_cache(target, n, seed)
    if cache.is_file():
        drawn = json.loads(cache.read_text())
    elif cached_only:
        return None
    else:
        work = Path(tempfile.mkdtemp(prefix="draw.", dir=cache_dir("mutate", "work")))
        try:
            drawn = netlist.draw(hdl_sources(target.top), target.top,
                                 top_parameters(target.top, cfg), f"{target.module}.sv", n,
                                 seed, work)
        finally:
            shutil.rmtree(work, ignore_errors=True)
        write_text_atomic(cache, json.dumps(drawn, indent=1))
    return [Mutant(f"auto_{target.module}_s{seed}_{k}", f"{target.module}.sv", "", "",
                   _what(d["command"], d["src"]), config=target.config, top=target.top,
                   suite=target.suite, yosys=d["command"])
            for k, d in enumerate(drawn)]


def baseline(target: Target, use_cache: bool = True) -> None:
    """The unmutated netlist of the target's top must pass its suite (raises RtlError)."""
    from irnuc.cosim import RtlError

    probe = Mutant(f"auto_baseline_{target.top}_{target.config}", f"{target.top}.sv", "", "",
                   "the unmutated netlist", config=target.config, top=target.top,
                   suite=target.suite, yosys="")
    res = mutate.run_mutant(probe, use_cache=use_cache)
    if res["status"] != "survived":
        raise RtlError(f"the netlist of {target.top} on {target.config} does not pass "
                       f"{target.suite.rsplit('.', 1)[-1]} ({res['status']}: "
                       f"{res['message'][:300]}); automatic mutants cannot be scored there")


def run_auto(tgts: Sequence[Target], n: int, *, seed: int = SEED, workers: int = 1,
             scheduler: str | None = None, use_cache: bool = True,
             progress: Callable[[int, int], None] | None = None) -> dict:
    """Draw ``n`` mutants per target and run them; the summary (the score over the mutants
    not proved equivalent), cached as the latest automatic campaign of this RTL when every
    target ran (:func:`cached_summary`)."""
    from irnuc.common.executor import open_executor

    mutants = [m for t in tgts for m in draw(t, n, seed) or ()]
    seen = set()
    for t in tgts:
        if (t.top, t.config, t.suite) not in seen:
            seen.add((t.top, t.config, t.suite))
            baseline(t, use_cache)
    results = []
    with open_executor(workers, scheduler) as handle:
        futures = [handle.executor.submit(mutate._job, asdict(m), use_cache) for m in mutants]
        for i, fut in enumerate(futures):
            results.append(fut.result())
            if progress is not None:
                progress(i + 1, len(futures))
    summary = summarize(results)
    summary |= {"n": n, "seed": seed, "modules": [t.module for t in tgts],
                "complete": {t.module for t in tgts} == set(TARGETS)}
    path = cache_dir("mutate") / f"auto-{mutate.rtl_digest()}.json"
    if summary["complete"] or not path.is_file():
        write_text_atomic(path, json.dumps(summary, indent=1))
    return summary


def summarize(results: Sequence[dict]) -> dict:
    """The mutation summary (:func:`irnuc.verif.mutate.summarize`) with the survivors'
    formal verdicts (different: a distinguishing trace; undecided) and per module."""
    s = mutate.summarize(results, total_catalogue=len(results))
    s["decided"] = {r["id"]: r.get("decided", {}).get("verdict") for r in results
                    if r.get("decided")}
    per: dict[str, dict[str, Any]] = {}
    for r in results:
        row = per.setdefault(r["file"].removesuffix(".sv"),
                             {"killed": 0, "survived": 0, "equivalent": 0, "invalid": 0})
        row[r["status"]] += 1
    for row in per.values():
        non_eq = row["killed"] + row["survived"]
        row["score"] = round(row["killed"] / non_eq, 4) if non_eq else None
    s["per_module"] = per
    return s


def cached_summary() -> dict | None:
    """The latest automatic campaign of the current RTL, or None."""
    return read_cached_json(cache_dir("mutate") / f"auto-{mutate.rtl_digest()}.json")


def current_results(n: int = CAMPAIGN_N, seed: int = SEED) -> dict:
    """The automatic campaign (``n`` per module, ``seed``) as the cache holds it for the
    current sources, nothing run or drawn: per module of :data:`TARGETS` whose draw is
    cached, each mutant's result on these sources; ``missing`` the mutants without one,
    ``not_drawn`` the modules never drawn on this RTL (neither counted)."""
    mutants, not_drawn = [], []
    for t in TARGETS.values():
        drawn = draw(t, n, seed, cached_only=True)
        if drawn is None:
            not_drawn.append(t.module)
        else:
            mutants += drawn
    found, missing = mutate.cached_results(mutants)
    s = summarize(found)
    s |= {"n": n, "seed": seed, "modules": sorted({r["file"].removesuffix(".sv")
                                                   for r in found}),
          "missing": missing, "not_drawn": not_drawn,
          "complete": not missing and not not_drawn}
    return s


__all__ = [
    "CAMPAIGN_N",
    "SEED",
    "TARGETS",
    "Target",
    "baseline",
    "cached_summary",
    "current_results",
    "draw",
    "run_auto",
    "summarize",
    "targets",
]
