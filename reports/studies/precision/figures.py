"""The work-precision figures: error against run time and against work, per component
(matplotlib Agg, PNG bytes for the report)."""

from __future__ import annotations

import io
from typing import Any

#: Short labels of failure reasons on the figures.
_REASONS = (("budget", "budget"), ("StiffnessError", "stiff"), ("did not converge", "no conv."),
            ("non-finite", "non-finite"))


def failure_label(reason: str | None) -> str:
    for key, label in _REASONS:
        if reason and key in reason:
            return label
    return "failed"


def figure_png(component: dict[str, Any]) -> bytes:
    """One component: error against run time (left) and against work (right), log-log.

    Failed settings are crosses in the method's colour, one row per failing method above
    the data, at the time (work) they took to fail (refusals before any work at the left
    edge), each row labelled with the method and the reasons; the default is a large star;
    the dashed line is 100 times the reference's own error estimate (if within view).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts = component["points"]
    ok = [p for p in pts if p["error"] is not None]
    errs = [max(p["error"], 1e-17) for p in ok] or [1.0]
    top = max(errs) * 20
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 5.2), sharey=True)
    methods = list(dict.fromkeys(p["method"] for p in pts))
    color = {m: f"C{k % 10}" for k, m in enumerate(methods)}
    marker = {m: "osD^v<>ph*"[k % 10] for k, m in enumerate(methods)}
    failing = [m for m in methods if any(p["failed"] for p in pts if p["method"] == m)]
    for ax, key, xlabel in ((axes[0], "time_s", "run time, s (min of runs, 1 thread)"),
                            (axes[1], "work", component.get("work_name", "work"))):
        xs = [p[key] for p in pts if p[key]]
        left = min(xs) / 2 if xs else 1.0
        for m in methods:
            good = [p for p in pts if p["method"] == m and p["error"] is not None and p[key]]
            if good:
                ax.loglog([p[key] for p in good], [max(p["error"], 1e-17) for p in good],
                          marker=marker[m], ms=4, lw=1, color=color[m], label=m)
        for k, m in enumerate(failing):
            bad = [p for p in pts if p["method"] == m and p["failed"]]
            y = top * 4.0**k
            ax.plot([p[key] or left for p in bad], [y] * len(bad), ls="none", marker="X",
                    ms=6, color=color[m])
            reasons = ", ".join(dict.fromkeys(failure_label(p["reason"]) for p in bad))
            ax.text(0.01, y * 1.3, f"{m} failed: {reasons} ({len(bad)})", fontsize=6,
                    color=color[m], transform=ax.get_yaxis_transform())
        d = [p for p in pts if p["default"] and p["error"] is not None and p[key]]
        if d:
            ax.loglog([d[0][key]], [max(d[0]["error"], 1e-17)], marker="*", ms=16,
                      mfc="none", mec="k", mew=1.5, ls="none", label="default")
        ref = 100 * component.get("reference_error", 0.0)
        if ref >= 1e-17:
            ax.axhline(ref, color="grey", ls="--", lw=0.8, label="100 x reference error")
        if failing:
            ax.axhline(top / 2, color="red", lw=0.5, alpha=0.4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("max relative error (above the red line: failed)")
    handles, labels = axes[1].get_legend_handles_labels()
    # Below the axes: inside, it would hide the points near the best errors.
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=7, frameon=False)
    fig.suptitle(component["title"], fontsize=10)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    return buf.getvalue()


def figures(result: dict[str, Any]) -> list[tuple[str, bytes]]:
    """(caption, PNG bytes) per component, for the regression report (matplotlib Agg)."""
    out = []
    for c in result["components"]:
        d = c["default"]
        state = ("failed" if d["failed"] else
                 f"error {d['error']:.2g}, {d['time_s']:.2g} s, {d['work']:.3g} work, "
                 f"{'on' if d['on_pareto_front'] else 'NOT on'} the front")
        caption = (f"{c['title']}: error against run time and against "
                   f"{c.get('work_name', 'work')}; default {d['method']} "
                   f"{d['setting_name']} = {d['setting']:g} ({state}); "
                   f"{len(c['missing'])} failed setting(s) drawn as crosses in their "
                   "method's colour above the curves.")
        out.append((caption, figure_png(c)))
    return out
