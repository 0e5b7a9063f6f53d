"""``irnuc synth --seeds N``: the seed list, the cache keys of a seed sweep (one netlist,
one placement per seed), the best / worst fold and the command line, with the tools stubbed
(no Yosys, no nextpnr: the real flow is ``tests/test_synth.py``'s, marked slow)."""

from __future__ import annotations

import json

import pytest

from irnuc.cli import main
from irnuc.common.errors import ToolError
from irnuc.cosim import synth
from irnuc.nuc_fixed import load_pipeline


def _run(seed: int, fmax: float, **kw) -> dict:
    """A placement as synth_config returns it (the fields best_of_seeds reads)."""
    return {"seed": seed, "fmax_mhz": fmax, "top": "nuc_dpc_top", "xc7": {"lut": 10},
            "ecp5": {"lut4": 12}, "config_digest": "c0", "target_mhz": 150.0,
            "critical_path": [f"path of seed {seed}"], "cached": True, **kw}


def test_seed_list() -> None:
    assert synth.seed_list(4) == [1, 2, 3, 4]
    assert synth.seed_list(1) == [1]
    assert synth.seed_list(3, 7) == [7, 8, 9]
    assert synth.seed_list(2, 2**31 - 2) == [2**31 - 2, 2**31 - 1]
    for bad in (0, -1, synth.MAX_SEEDS + 1, True, 2.0):
        with pytest.raises(ValueError, match="seeds"):
            synth.seed_list(bad)
    with pytest.raises(ValueError, match="first seed"):
        synth.seed_list(2, 2**31 - 1)
    with pytest.raises(ValueError, match="first seed"):
        synth.seed_list(2, -1)


def test_best_of_seeds_keeps_the_best_placement() -> None:
    runs = [_run(1, 148.0), _run(2, 161.5, cached=False), _run(3, 139.25), _run(4, 152.0)]
    r = synth.best_of_seeds(runs)
    sd = r["seeds"]
    # The best placement's own figures, not a mixture.
    assert r["fmax_mhz"] == 161.5 and r["seed"] == 2
    assert r["critical_path"] == ["path of seed 2"]
    assert sd["seeds"] == [1, 2, 3, 4]
    assert sd["fmax_mhz"] == {"1": 148.0, "2": 161.5, "3": 139.25, "4": 152.0}
    assert (sd["best_mhz"], sd["best_seed"], sd["worst_mhz"], sd["worst_seed"]) == (
        161.5, 2, 139.25, 3)
    assert sd["spread_mhz"] == 22.25
    assert sd["median_mhz"] == 150.0  # (148 + 152) / 2
    assert sd["mean_mhz"] == 150.19  # 600.75 / 4, rounded
    assert sd["at_target"] == 2 and sd["runs"] == 4 and sd["target_mhz"] == 150.0
    assert r["cached"] is False  # one placement ran


def test_best_of_seeds_ties_and_refusals() -> None:
    r = synth.best_of_seeds([_run(5, 150.0), _run(3, 150.0), _run(4, 149.9)])
    assert r["seed"] == 3 and r["seeds"]["best_seed"] == 3  # a tie: the lower seed
    assert r["seeds"]["worst_seed"] == 4 and r["seeds"]["at_target"] == 2
    assert r["cached"] is True
    one = synth.best_of_seeds([_run(1, 140.0)])
    assert one["seeds"]["spread_mhz"] == 0.0 and one["seeds"]["best_seed"] == 1
    with pytest.raises(ValueError, match="no placement"):
        synth.best_of_seeds([])
    with pytest.raises(ValueError, match="netlist"):  # another design is not a seed
        synth.best_of_seeds([_run(1, 150.0), _run(2, 151.0, ecp5={"lut4": 13})])
    with pytest.raises(ValueError, match="twice"):
        synth.best_of_seeds([_run(1, 150.0), _run(1, 151.0)])


def test_synth_configs_places_every_seed(monkeypatch) -> None:
    """Per configuration, one netlist job, then one placement per seed; folded per
    configuration in input order."""
    nets, calls = [], []

    def fake_config(cfg, **kw):
        calls.append((cfg.name, kw["seed"], kw.get("netlist_cache")))
        return _run(kw["seed"], 140.0 + 10 * (kw["seed"] % 3) + (cfg.name == "minimal"),
                    config_digest=cfg.digest(), name=cfg.name)

    monkeypatch.setattr(synth, "synth_config", fake_config)
    monkeypatch.setattr(synth, "_netlist_job", lambda d, o: nets.append((d["name"], o)))
    cfgs = [load_pipeline("minimal"), load_pipeline("typical14")]
    out = synth.synth_configs(cfgs, workers=0, seeds=3, seed=4, speed=8)
    assert [n for n, _ in nets] == ["minimal", "typical14"]
    assert all(o["speed"] == 8 and "seed" not in o for _, o in nets)
    assert [c[:2] for c in calls] == [("minimal", 4), ("minimal", 5), ("minimal", 6),
                                      ("typical14", 4), ("typical14", 5), ("typical14", 6)]
    assert [r["name"] for r in out] == ["minimal", "typical14"]
    # seed 4 -> 150 (+1 on minimal), 5 -> 160, 6 -> 140
    assert [(r["seeds"]["best_seed"], r["seeds"]["worst_seed"]) for r in out] == [(5, 6)] * 2
    assert out[0]["fmax_mhz"] == 161.0 and out[1]["seeds"]["worst_mhz"] == 140.0
    # One seed: synth_config's own result, no fold, no netlist job.
    nets.clear()
    one = synth.synth_configs(cfgs[:1], workers=0, seed=9)
    assert "seeds" not in one[0] and one[0]["seed"] == 9 and nets == []
    # Without the cache: the netlist once (uncached), every placement again on it.
    calls.clear()
    synth.synth_configs(cfgs[:1], workers=0, seeds=2, use_cache=False)
    assert nets[0][1]["use_cache"] is False
    assert calls == [("minimal", 1, True), ("minimal", 2, True)]


def test_synth_configs_rtl_changed_between_seeds(monkeypatch) -> None:
    """A seed whose netlist differs (hdl/ edited during the run): one line, not a
    traceback."""
    monkeypatch.setattr(synth, "_netlist_job", lambda d, o: None)
    monkeypatch.setattr(synth, "synth_config", lambda cfg, **kw: _run(
        kw["seed"], 150.0, xc7={"lut": 10 + (kw["seed"] > 1)}, config_digest=cfg.digest()))
    with pytest.raises(ToolError, match="RTL changed while the seeds were placed"):
        synth.synth_configs([load_pipeline("minimal")], workers=0, seeds=2)


def _stub_flow(monkeypatch) -> dict:
    """Yosys and nextpnr stubbed: counts of the netlists made (and of which tops), the
    placements (seed, speed grade), each on the cached netlist; Fmax 140 + seed."""
    counts: dict = {"xc7": 0, "ecp5": 0, "pnr": [], "tops": []}

    def xc7(sources, top, params, workdir):
        counts["xc7"] += 1
        counts["tops"].append(top)
        return {**{k: 1 for k in synth.XC7_KEYS}, "cells": {"LUT4": 1}, "seconds": 0.1,
                "log": "x"}

    def ecp5(sources, top, params, workdir):
        counts["ecp5"] += 1
        workdir.mkdir(parents=True, exist_ok=True)
        net = workdir / f"{top}.json"
        net.write_text('{"modules": {}}')
        return net, {**{k: 2 for k in synth.ECP5_KEYS}, "cells": {"LUT4": 2},
                     "seconds": 0.1, "log": "e"}

    def pnr(net, workdir, **kw):
        assert json.loads(open(net).read()) == {"modules": {}}  # the cached netlist
        counts["pnr"].append((kw["seed"], kw["speed"]))
        return {"fmax_mhz": 140.0 + kw["seed"], "utilization": {}, "critical_path": [],
                "timing_weight": 30, "timing_ripup": True, "out_of_context": False,
                "seconds": 0.1}

    monkeypatch.setattr(synth, "synth_xc7", xc7)
    monkeypatch.setattr(synth, "synth_ecp5", ecp5)
    monkeypatch.setattr(synth, "place_route_ecp5", pnr)
    monkeypatch.setattr(synth, "tool_versions", lambda: {"yosys": "stub"})
    return counts


def test_seed_sweep_synthesizes_once_and_places_each_seed(tmp_path, monkeypatch) -> None:
    """The cache: the netlist keyed without the seed (synthesized once for every seed, and
    not again for another speed grade), each placement under its own key with the seed."""
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    counts = _stub_flow(monkeypatch)
    cfg = load_pipeline("minimal")
    r = synth.synth_seeds(cfg, seeds=3, workers=0)
    assert (counts["xc7"], counts["ecp5"]) == (1, 1)
    assert counts["pnr"] == [(1, 6), (2, 6), (3, 6)]
    assert r["fmax_mhz"] == 143.0 and r["seeds"]["worst_mhz"] == 141.0 and not r["cached"]
    assert r["source_digest"] == synth.synth_key(cfg, seed=3)
    again = synth.synth_seeds(cfg, seeds=4, workers=0)  # seeds 1-3 cached, 4 placed
    assert counts["pnr"][3:] == [(4, 6)] and (counts["xc7"], counts["ecp5"]) == (1, 1)
    assert again["seeds"]["best_seed"] == 4 and not again["cached"]
    from irnuc.common import executor

    def no_executor(*a, **kw):
        raise AssertionError("an executor opened for placements that are all cached")

    with monkeypatch.context() as m:  # all cached (a warm report): no worker processes
        m.setattr(executor, "open_executor", no_executor)
        assert synth.synth_seeds(cfg, seeds=4, workers=2)["cached"] is True
        with pytest.raises(AssertionError, match="executor opened"):
            synth.synth_seeds(cfg, seeds=5, workers=2)  # seed 5 is not: it needs one
    synth.synth_config(cfg, seed=1, speed=8)  # another grade: placed, not synthesized
    assert counts["pnr"][-1] == (1, 8) and (counts["xc7"], counts["ecp5"]) == (1, 1)
    synth.synth_config(cfg, seed=1, max_width=48)  # another design: synthesized
    assert (counts["xc7"], counts["ecp5"]) == (2, 2)


@pytest.mark.parametrize(("args", "words"), [
    (["--seeds", "0"], ("--seeds 0", "1..64")),
    (["--seeds", "65"], ("--seeds 65", "1..64")),
    (["--seeds", "many"], ("--seeds", "invalid int")),
    (["--seed", str(2**31 - 1), "--seeds", "2"], ("--seed", "--seeds 2", "2^31-1")),
])
def test_seeds_flag_errors(args, words, tmp_path, monkeypatch, capsys) -> None:
    """Bad --seeds: one line naming the flag, before any synthesis."""
    monkeypatch.setattr(synth, "synth_configs", lambda *a, **k: pytest.fail("synthesized"))
    try:
        code = main(["synth", "--pipeline", "minimal", *args, "--out", str(tmp_path / "o")])
    except SystemExit as exc:  # argparse's own errors
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and all(w in err for w in words), err
    assert "Traceback" not in err


def test_irnuc_synth_seeds_writes_the_fold(tmp_path, monkeypatch, capsys) -> None:
    """`irnuc synth --seeds 3 --seed 2`: seeds 2-4 asked for, in parallel on --workers;
    synth.json is the best placement with its seeds; the line says best, worst, spread."""
    asked = {}

    def fake(cfgs, **kw):
        asked.update(kw)
        cfg = cfgs[0]
        xc7 = {"lut": 343, "ff": 546, "dsp": 2, "bram18": 0, "bram36": 0, "lutram": 5}
        ecp5 = {"lut4": 445, "ff": 659, "mult18": 2, "dp16kd": 0}
        runs = [_run(s, f, config={"name": cfg.name, "max_width": 64, "max_height": 64},
                     xc7=xc7, ecp5=ecp5,
                     speed=6, cached=False, config_digest=cfg.digest())
                for s, f in ((2, 151.2), (3, 144.8), (4, 158.0))]
        return [synth.best_of_seeds(runs)]

    monkeypatch.setattr(synth, "synth_configs", fake)
    out = tmp_path / "o"
    assert main(["synth", "--pipeline", "minimal", "--seeds", "3", "--seed", "2",
                 "--out", str(out)]) == 0
    assert asked["seeds"] == 3 and asked["seed"] == 2 and asked["workers"] == 2
    r = json.loads((out / "synth.json").read_text())
    assert r["fmax_mhz"] == 158.0 and r["seed"] == 4 and r["seeds"]["worst_seed"] == 3
    line = capsys.readouterr().out
    assert ("Fmax best 158.0 MHz (seed 4), worst 144.8 (seed 3), spread 13.2, 2 of 3 at "
            "150 MHz over seeds 2-4") in line


def test_report_text_of_a_seed_sweep() -> None:
    """The report's Fmax text: nothing for one placement; the best of N, the worst and, in
    detail, every seed's figure for a sweep."""
    from irnuc.reports.report.render import seeds_text

    assert seeds_text({"fmax_mhz": 150.0}) == ""
    sweep = synth.best_of_seeds([_run(1, 148.04), _run(2, 161.5), _run(3, 139.25)])
    assert seeds_text(sweep) == (" (best of 3 placer seeds, seed 2; worst 139.2 MHz, 1 of 3 "
                                 "at the target)")
    assert seeds_text(sweep, True).endswith("; seed 1: 148.0, seed 2: 161.5, seed 3: 139.2)")


def test_prepare_netlists_makes_the_missing_ones_then_placements_reuse_them(
        tmp_path, monkeypatch) -> None:
    """Two designs (the wrapper and the bare core of one configuration): their netlists made
    first (in-process here), then nothing more to make; a seed sweep of either places on
    that netlist without synthesizing again; one design alone is left to its placements."""
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path / "cache"))
    counts = _stub_flow(monkeypatch)
    cfg = load_pipeline("tcgain14")
    designs = [(cfg, "irnuc_axis_top"), (cfg, synth.default_top(cfg))]
    assert synth.prepare_netlists(designs, workers=0) == 2
    assert sorted(counts["tops"]) == sorted(t for _, t in designs) and counts["ecp5"] == 2
    assert synth.prepare_netlists(designs, workers=0) == 0
    synth.synth_seeds(cfg, top="irnuc_axis_top", seeds=2, workers=0)
    assert counts["xc7"] == 2 and len(counts["pnr"]) == 2  # placed on the prepared netlist
    assert synth.prepare_netlists([(load_pipeline("typical14"), None)], workers=0) == 0
    assert counts["xc7"] == 2
