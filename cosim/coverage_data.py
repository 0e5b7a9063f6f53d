"""Coverage data as files: merging exported functional-coverage snapshots, their summary
(hit/total and the uncovered bins per coverpoint and configuration), and Verilator's code
coverage (``coverage.dat``) per module.

Split from :mod:`irnuc.cosim.coverage` (the coverage model the testbenches sample), which
re-exports these names; this module needs no pipeline configuration.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

#: Schema version of the exported and merged coverage files.
FORMAT_VERSION = 1


def merge_data(datas: Iterable[Mapping[str, Any]], add_hits: bool = True) -> dict[str, Any]:
    """Merge coverage dicts: per configuration, per coverpoint, hits added per bin (or
    the maximum with ``add_hits=False``, for snapshots of one database)."""
    out: dict[str, Any] = {"version": FORMAT_VERSION, "configurations": {}}
    for data in datas:
        for cname, cdata in data.get("configurations", {}).items():
            dst = out["configurations"].setdefault(
                cname, {"config_digest": cdata.get("config_digest"), "tops": [],
                        "coverpoints": {}})
            dst["tops"] = sorted(set(dst["tops"]) | set(cdata.get("tops", [])))
            for pname, p in cdata.get("coverpoints", {}).items():
                d = dst["coverpoints"].setdefault(
                    pname, {"kind": p.get("kind", "point"), "bins": {}, "removed": {}})
                for b, hits in p.get("bins", {}).items():
                    old = d["bins"].get(b, 0)
                    d["bins"][b] = old + int(hits) if add_hits else max(old, int(hits))
                d["removed"].update(p.get("removed", {}))
    return out


def merge(paths: Iterable[str | Path]) -> dict[str, Any]:
    """Merge exported coverage files (missing files are skipped)."""
    datas = []
    for p in paths:
        p = Path(p)
        if p.is_file():
            datas.append(json.loads(p.read_text()))
    return merge_data(datas)


def summarize(data: Mapping[str, Any]) -> dict[str, Any]:
    """hit/total, percent and uncovered bins per coverpoint, per configuration and over
    everything (a JSON-ready dict)."""
    out: dict[str, Any] = {"configurations": {}}
    all_hit = all_total = 0
    for cname, cdata in sorted(data.get("configurations", {}).items()):
        points = {}
        c_hit = c_total = 0
        uncovered: list[str] = []
        for pname, p in sorted(cdata.get("coverpoints", {}).items()):
            bins = p.get("bins", {})
            hit = sum(1 for v in bins.values() if v > 0)
            miss = [b for b, v in bins.items() if v <= 0]
            points[pname] = {"kind": p.get("kind", "point"), "hit": hit, "total": len(bins),
                             "percent": _pct(hit, len(bins)), "bins": dict(bins),
                             "uncovered": miss, "removed": dict(p.get("removed", {}))}
            c_hit += hit
            c_total += len(bins)
            uncovered += [f"{pname}:{b}" for b in miss]
        out["configurations"][cname] = {"hit": c_hit, "total": c_total,
                                        "percent": _pct(c_hit, c_total),
                                        "tops": cdata.get("tops", []),
                                        "uncovered": uncovered, "coverpoints": points}
        all_hit += c_hit
        all_total += c_total
    out.update(hit=all_hit, total=all_total, percent=_pct(all_hit, all_total))
    return out


def _pct(hit: int, total: int) -> float:
    return round(100.0 * hit / total, 2) if total else 100.0


# ---- code coverage (Verilator coverage.dat) -------------------------------------------------

def read_coverage_dat(path: str | Path) -> dict[tuple[str, ...], int]:
    """Points of a Verilator ``coverage.dat``: (type, module, file, line, column, comment)
    -> count, summed over instances."""
    out: dict[tuple[str, ...], int] = {}
    for line in Path(path).read_text(errors="replace").splitlines():
        if not line.startswith("C '"):
            continue
        body, _, count = line[3:].rpartition("' ")
        fields = {}
        for kv in body.split("\x01"):
            if "\x02" in kv:
                k, v = kv.split("\x02", 1)
                fields[k] = v
        page = fields.get("page", "")
        kind, _, module = page.partition("/")
        key = (kind, module, Path(fields.get("f", "")).name, fields.get("l", ""),
               fields.get("n", ""), fields.get("o", ""))
        out[key] = out.get(key, 0) + int(count or 0)
    return out


def merge_points(points: Iterable[Mapping[tuple[str, ...], int]]) -> dict[tuple[str, ...], int]:
    out: dict[tuple[str, ...], int] = {}
    for p in points:
        for k, v in p.items():
            out[k] = out.get(k, 0) + v
    return out


def code_coverage(points: Mapping[tuple[str, ...], int]) -> dict[str, Any]:
    """Per module: line coverage (Verilator's line and branch points) and toggle coverage,
    hit/total/percent, and the source lines never reached."""
    mods: dict[str, dict[str, Any]] = {}
    for (kind, module, file, line, _col, _comment), count in points.items():
        group = {"v_line": "line", "v_branch": "line", "v_toggle": "toggle"}.get(kind)
        if group is None or not module:
            continue
        m = mods.setdefault(module.split("__")[0],
                            {"line": [0, 0], "toggle": [0, 0], "missed_lines": set()})
        m[group][1] += 1
        if count > 0:
            m[group][0] += 1
        elif group == "line":
            m["missed_lines"].add(f"{file}:{line}")
    return {mod: {"line": {"hit": v["line"][0], "total": v["line"][1],
                           "percent": _pct(*v["line"])},
                  "toggle": {"hit": v["toggle"][0], "total": v["toggle"][1],
                             "percent": _pct(*v["toggle"])},
                  "missed_lines": sorted(v["missed_lines"])}
            for mod, v in sorted(mods.items())}


__all__ = ["FORMAT_VERSION", "code_coverage", "merge", "merge_data", "merge_points",
           "read_coverage_dat", "summarize"]
