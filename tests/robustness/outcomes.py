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
    "write_file_too_large": (
        "`irnuc calibrate` over an earlier result with a file-size limit (`ulimit -f`, "
        "SIGXFSZ ignored) below its `coeffs.npz`: `OSError` 27 inside the atomic writer",
        "exit 2, one line naming `--out`, the file and 'File too large'; the earlier result "
        "whole, no temporary folder left (was a traceback)"),
    "write_disk_full": (
        "a full disk (ENOSPC) while the atomic writer writes a file, alone and inside an "
        "output folder",
        "`WriteError` naming the file (or `--out` and the file in it) and 'No space left'; the "
        "previous file or folder whole"),
    "stdout_closed": (
        "`irnuc calibrate ... | true`: stdout is a pipe whose reader has gone",
        "exit 2, one line naming stdout ('the reader closed it'), no second error at exit "
        "(was `BrokenPipeError`)"),
    "stdout_full": (
        "`irnuc calibrate ... > /dev/full`",
        "exit 2, one line naming stdout and 'No space left'; the result in `--out` whole "
        "(was `OSError` 28 at exit)"),
    "frames_some_solves_fail": (
        "`irnuc frames` of a positive-TCR sensor near runaway with a 5 % spread: some pixels run away",
        "exit 0, the frames written, and one warning line counting the failed solves and "
        "their kinds (was a raw two-line RuntimeWarning); every pixel failing is the "
        "command-line case `frames-every-solve-fails`"),
    "stdout_closed_at_start": (
        "`irnuc calibrate ... >&-`: stdout closed before irnuc starts",
        "exit 2, one line naming stdout before the work, nothing written; with `-q` exit 0 "
        "and the result whole (was `AttributeError` in `_flush_stdout` after the work)"),
    "ffc_without_a_good_pixel": (
        "`irnuc correct` of an FFC sequence with a calibration whose every pixel is bad: "
        "the mean frame has no good pixel to take the target from",
        "exit 0; the refresh keeps the previous offsets (`ffc_kept` names it, the offsets "
        "are the ones before), one warning line (the golden model raised and the whole "
        "sequence was refused; the RTL's division would have divided by 2 n = 0)"),
    "report_checks_nothing": (
        "a report whose baseline shares no compared metric with the run (every metric new), "
        "or a run that measured only `info` metrics",
        "status `fail` with the reason ('nothing was checked against it', 'measured nothing "
        "that can pass or fail'), never `pass` (was `compared: 0` and pass)"),
}
