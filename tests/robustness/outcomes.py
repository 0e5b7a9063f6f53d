"""The outcome table: hostile inputs whose right outcome is not (only) an error line before
the work: write and stdout errors, runs or comparisons that check nothing, results that
were silently wrong. Each ``test_outcome_<id>`` of ``test_outcomes.py`` checks one row."""

from __future__ import annotations

#: id -> (the hostile input, the outcome the test checks)
OUTCOMES: dict[str, tuple[str, str]] = {
    "synth_cache_carries_the_asked_name": (
        "`irnuc synth` of a configuration whose design (sources and parameters) is cached "
        "under another configuration's name",
        "the result and its folder carry the name asked for, written inside `--out` only "
        "(a cached result used to report the name that made it, and write outside `--out`)"),
}
