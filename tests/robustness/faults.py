"""The fault table: what each ``test_fault_<id>`` of ``test_faults.py`` does."""

from __future__ import annotations

#: Every fault test, named as in the documentation (``test_fault_<id>`` runs it).
FAULTS: dict[str, str] = {
    "kill_calibrate": "SIGKILL of `irnuc calibrate` writing over an earlier result, at a seeded "
                      "random time or once it has written a random number (1-8) of files, "
                      "wherever (6 trials): the folder is the old result or the new one, whole "
                      "(every file checked against both results, the manifest and the summary)",
    "concurrent_calibrate": "two `irnuc calibrate` runs (different frames) on one `--out`, "
                            "started a seeded random time apart (3 trials): each exits 0, or 2 with "
                            "'another irnuc run is writing it'; the folder is one run's result, whole",
    "stale_tmp_removed": "a killed run's temporary folder and a stale lock beside `--out`: the next "
                         "run removes the folder and writes a whole result",
    "children_die_with_parent": "SIGKILL of a process that started a child process group with "
                                "`run_child`, the child having started a grandchild; the child "
                                "either irnuc's own or a foreign tool (a shell, as make, run "
                                "under the reaper): both are gone",
    "single_process_child_dies_with_parent": "SIGKILL of a process that started a tool with "
                                             "`run_child(single_process=True)` (no reaper, the "
                                             "bulk harness): the tool, its direct child, is gone",
}
