"""``irnuc mutate``: mutation testing of the RTL against the co-simulation suite (standard
library only at import time)."""

from __future__ import annotations

import argparse

from irnuc.cli._args import add_executor, add_out, progress, say


def add_mutate_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--only", action="append", default=[], metavar="ID",
                   help="run only this mutant of the catalogue (repeatable; see --list)")
    p.add_argument("--list", action="store_true", help="list the catalogue and exit")
    p.add_argument("--configs", metavar="LIST",
                   help="run each selected mutant of nuc_dpc_top on every configuration of "
                        "LIST (comma-separated: 'sample', the CI sample of random legal "
                        "configurations, and named configurations, e.g. sample,minimal) "
                        "where its code elaborates differently, one at a time, and print "
                        "the score per configuration (no coverage run)")
    p.add_argument("--auto", type=int, metavar="N",
                   help="mutants nobody chose: N mutations per module drawn by Yosys "
                        "(mutate -list N, --seed), run in the module's top with its suite; "
                        "each survivor decided equivalent or not by a miter (no coverage "
                        "run); see --modules")
    p.add_argument("--seed", type=int, default=1,
                   help="the seed of --auto's draw (default: %(default)s)")
    p.add_argument("--decide", action="append", default=[], metavar="ID",
                   help="decide catalogue mutant ID equivalent or not formally, without a "
                        "simulation: a miter of the original and mutated netlists that "
                        "compares each output stream's payload only while its valid is 1 and "
                        "assumes the top's input contract (legal frame sizes, the AXI4-Stream "
                        "rules on the inputs); proved equivalent, different (with a VCD) or "
                        "undecided within --budget (repeatable; nuc_dpc_top and method_dpc_top)")
    p.add_argument("--budget", type=float, default=1200.0, metavar="SECONDS",
                   help="--decide: wall-time budget per mutant (default: %(default)s)")
    p.add_argument("--frame-max", metavar="WxH",
                   help="--decide on the mutant's configuration with max_width x max_height "
                        "replaced by W x H (a smaller model of the same design; default: the "
                        "configuration's own)")
    p.add_argument("--modules", metavar="LIST",
                   help="--auto: these modules only (comma-separated; default: every module "
                        "of irnuc.verif.automut.TARGETS)")
    p.epilog = ("exit status: 0 when every non-equivalent mutant was killed (--decide: "
                "every mutant proved equivalent), 1 when one survived (--decide: one "
                "different or undecided), 2 for bad input, 3 when a tool failed")
    add_executor(p, "run the mutants", workers=1, cache="a mutant's result")
    p.add_argument("--no-coverage", action="store_true",
                   help="skip the coverage run of the unmutated design (coverage.json)")
    add_out(p, "out/mutate")


def run_mutate(args: argparse.Namespace) -> int:
    import json

    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.verif import mutate

    if args.list:
        for m in mutate.CATALOGUE:
            say(f"{m.id:28s} {m.file:26s} {m.what}"
                + (" [equivalent]" if m.equivalent else ""), level=0)
        return 0
    if not 0 <= args.workers <= 256:
        raise UserError(f"--workers {args.workers} is outside the allowed range 0..256")
    if args.decide or args.frame_max is not None:
        return _run_decide(args)
    if args.auto is not None or args.modules is not None:
        return _run_auto(args)
    mutants = mutate.catalogue(args.only)  # an unknown id is a one-line error, before work
    if args.configs is not None:
        return _run_per_configuration(args, mutants)
    out = claim_output_folder(args.out, kind="mutate")
    summary = mutate.run_mutants(mutants, workers=args.workers, scheduler=args.scheduler,
                                 use_cache=not args.no_cache, progress=progress("mutate"))
    cov = None
    if not args.no_coverage:
        import tempfile

        from irnuc.verif import SuiteCase, run_suite

        cases = {(m.pipeline().digest(), m.top, m.suite): SuiteCase(m.top, m.pipeline(), m.suite)
                 for m in mutants}
        with tempfile.TemporaryDirectory() as tmp:
            res = run_suite(list(cases.values()), tmp, coverage=True)
        cov = res.coverage
    with output_folder(out, kind="mutate") as tmp:
        write_text_atomic(tmp / "mutate.json", json.dumps(summary, indent=1) + "\n")
        if cov is not None:
            write_text_atomic(tmp / "coverage.json", json.dumps(cov, indent=1) + "\n")
    for r in summary["mutants"]:
        say(f"{r['id']:28s} {r['status']:10s} "
            + (f"by {r['killed_by']}" if r["killed_by"] else (r["equivalent"] or "")[:60]),
            level=2)
    say(f"{summary['killed']} killed, {summary['survived']} survived, "
        f"{summary['equivalent']} equivalent of {summary['total']} mutants "
        f"(score {100 * summary['score']:.1f} % of the non-equivalent ones)"
        + (f"; survivors: {', '.join(summary['survivors'])}" if summary["survivors"] else ""))
    say(f"wrote {out / 'mutate.json'}")
    # A surviving non-equivalent mutant is a bug the suite would miss: fail like a test.
    return 1 if summary["survived"] else 0


def _run_auto(args: argparse.Namespace) -> int:
    """``--auto N``: the automatic mutants; mutate.json holds the summary, with each
    survivor's formal verdict (different, with its trace; undecided)."""
    import json

    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.verif import automut

    if args.auto is None:
        raise UserError("--modules needs --auto N (the mutants per module)")
    if not 1 <= args.auto <= 1000:
        raise UserError(f"--auto {args.auto} is outside the allowed range 1..1000")
    if args.only or args.configs is not None:
        raise UserError("--auto draws its own mutants: it takes neither --only nor --configs")
    if not 0 <= args.seed < 2**31:
        raise UserError(f"--seed {args.seed} is outside the allowed range 0..2147483647")
    tgts = automut.targets(args.modules)
    out = claim_output_folder(args.out, kind="mutate")
    s = automut.run_auto(tgts, args.auto, seed=args.seed, workers=args.workers,
                         scheduler=args.scheduler, use_cache=not args.no_cache,
                         progress=progress("mutate"))
    with output_folder(out, kind="mutate") as tmp:
        write_text_atomic(tmp / "mutate.json", json.dumps(s, indent=1) + "\n")
    for r in s["mutants"]:
        say(f"{r['id']:34s} {r['status']:10s} "
            + (f"by {r['killed_by']}" if r["killed_by"] else (r["equivalent"] or r["message"])[:70]),
            level=2)
    for mod, row in s["per_module"].items():
        score = "-" if row["score"] is None else f"{100 * row['score']:.1f} %"
        say(f"{mod:22s} {row['killed']} killed, {row['survived']} survived, "
            f"{row['equivalent']} proved equivalent: score {score}")
    say(f"{s['killed']} killed, {s['survived']} survived, {s['equivalent']} proved equivalent of "
        f"{s['total']} automatic mutants (score {100 * s['score']:.1f} %)"
        + (f"; survivors: {', '.join(s['survivors'])}" if s["survivors"] else ""))
    say(f"wrote {out / 'mutate.json'}")
    return 1 if s["survived"] else 0


def _run_decide(args: argparse.Namespace) -> int:
    """``--decide ID``: each mutant decided by the contract miter (irnuc.verif.miter);
    mutate.json holds the decisions, the counterexamples' VCDs are copied beside it."""
    import json
    import shutil
    from pathlib import Path

    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.verif import miter

    if not args.decide:
        raise UserError("--frame-max needs --decide ID")
    if args.auto is not None or args.modules is not None or args.only or args.configs:
        raise UserError("--decide runs no simulation: it takes none of --auto, --modules, "
                        "--only, --configs")
    if not 10.0 <= args.budget <= 86400.0:
        raise UserError(f"--budget {args.budget:g} is outside the allowed range 10..86400 s")
    if len(set(args.decide)) < len(args.decide):
        raise UserError("--decide: a mutant given twice")
    frame_max = None
    if args.frame_max is not None:
        import re

        from irnuc.nuc_fixed.rtl_spec import FRAME_DIM_MAX

        fm = re.fullmatch(r"(\d+)x(\d+)", args.frame_max.strip())
        if not fm or not all(1 <= int(v) <= FRAME_DIM_MAX for v in fm.groups()):
            raise UserError(f"--frame-max {args.frame_max}: expected WxH with W, H in "
                            f"1..{FRAME_DIM_MAX} (e.g. 8x8)")
        frame_max = (int(fm.group(1)), int(fm.group(2)))
    mutants = [miter.mutant(i) for i in args.decide]  # a bad id: one line, before work
    out = claim_output_folder(args.out, kind="mutate")
    decided = {}
    for m in mutants:
        decided[m.id] = miter.decide_mutant(m, budget=args.budget, frame_max=frame_max,
                                            use_cache=not args.no_cache)
        say(f"{m.id:28s} {miter.label(decided[m.id])}")
    with output_folder(out, kind="mutate") as tmp:
        for mid, r in decided.items():
            if r.get("vcd") and Path(r["vcd"]).is_file():
                shutil.copyfile(r["vcd"], tmp / f"{mid}.vcd")
                r = r | {"vcd": str(out / f"{mid}.vcd"), "cached_vcd": r["vcd"]}
                decided[mid] = r
        write_text_atomic(tmp / "mutate.json", json.dumps({"decided": decided}, indent=1)
                          + "\n")
    say(f"wrote {out / 'mutate.json'}")
    return 0 if all(r["verdict"] == "equivalent" for r in decided.values()) else 1


def _run_per_configuration(args: argparse.Namespace, mutants: list) -> int:
    """``--configs``: each two-point mutant on each configuration; mutate.json holds the
    score per configuration and the status of every mutant on every configuration."""
    import json

    from irnuc.common.errors import UserError
    from irnuc.common.io import claim_output_folder, output_folder, write_text_atomic
    from irnuc.verif import mutate

    configs = mutate.configurations(args.configs)
    two_point = [m for m in mutants if m.top == mutate.SUITE_TOP]
    if not two_point:
        raise UserError("--configs: none of the selected mutants runs in nuc_dpc_top (the "
                        "per-configuration run takes the mutants of the two-point suite)")
    out = claim_output_folder(args.out, kind="mutate")

    def show(cfg: str, mid: str, status: str) -> None:
        say(f"{cfg:12s} {mid:28s} {status}", level=2)

    res = mutate.run_per_configuration(two_point, configs, use_cache=not args.no_cache,
                                       progress=show)
    with output_folder(out, kind="mutate") as tmp:
        write_text_atomic(tmp / "mutate.json", json.dumps(res, indent=1) + "\n")
    for name, row in res["configurations"].items():
        score = "-" if row["score"] is None else f"{100 * row['score']:.1f} %"
        say(f"{name:12s} {row['killed']} killed, {row['survived']} survived, "
            f"{row['equivalent']} equivalent, {row['same']} same (not run): score {score}")
    ov = res["overall"]
    say(f"overall: {ov['killed']} killed on some configuration, {ov['survived']} survived"
        + (f" ({', '.join(ov['survivors'])})" if ov["survivors"] else "")
        + (f"; {len(mutants) - len(two_point)} mutants of other tops left out"
           if len(two_point) < len(mutants) else ""))
    say(f"wrote {out / 'mutate.json'}")
    return 1 if ov["survived"] else 0


COMMANDS = {
    "mutate": ("Mutation testing of the RTL: apply each mutant of the catalogue to a copy "
               "of hdl/, build it and run the co-simulation suite; killed / survived / "
               "equivalent, cached by source digest", add_mutate_arguments, run_mutate),
}
