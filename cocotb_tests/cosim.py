"""Glue between pytest and the cocotb runs: one simulation per (top, configuration,
testbench module), cached for the session, one pytest test per cocotb test."""

from __future__ import annotations

import functools
import os

from irnuc.nuc_fixed import PipelineConfig, rtl


def waves_requested() -> bool:
    """FST waveforms on request: ``pytest --waves`` or ``IRNUC_WAVES=1``."""
    return os.environ.get("IRNUC_WAVES", "0") not in ("", "0")


def cocotb_test_names(module: str) -> list[str]:
    """Names of the cocotb tests defined in a testbench module (imported, not run)."""
    import importlib

    mod = importlib.import_module(module)
    return [name for name, obj in vars(mod).items()
            if type(obj).__name__ == "TestGenerator" and getattr(obj, "module", None) == module]


@functools.cache
def cosim(top: str, cfg: PipelineConfig, module: str, seed: int = 1
          ) -> dict[str, rtl.CaseResult]:
    """Build (cached) and run every cocotb test of ``module`` on ``top``; parse the XML.

    A failed RTL assertion stops the simulation: the cocotb test running then fails (and
    those after it); its assertion lines from the simulator log are added to the message.
    """
    waves = waves_requested()
    bld = rtl.build(top, cfg, waves=waves)
    tag = f"{cfg.name}-{cfg.digest()[:8]}-{top}-{module.rsplit('.', 1)[-1]}"
    xml = rtl.run(bld, module, env={"IRNUC_SEED": str(seed)}, seed=seed, waves=waves,
                  results_xml=rtl.OUT_DIR / "cocotb_results" / f"{tag}.xml")
    results = rtl.read_results(xml)
    fired = rtl.assertion_failures(xml)
    if fired:
        note = "\nRTL assertions failed (simulation stopped):\n" + "\n".join(fired[:10])
        results = {k: v if v.passed else rtl.CaseResult(v.name, False, v.message + note)
                   for k, v in results.items()}
    return results


def check_case(results: dict[str, rtl.CaseResult], case: str) -> None:
    if case not in results:
        raise AssertionError(f"cocotb test {case!r} did not run; results: {sorted(results)}")
    res = results[case]
    assert res.passed, f"cocotb test {case} failed:\n{res.message}"
