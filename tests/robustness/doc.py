"""docs/robustness.md, generated from the tables of this package.

Run ``.venv/bin/python tests/robustness/doc.py`` after changing a table; ``test_doc.py``
checks that the file is in step.
"""

from __future__ import annotations

import sys
from pathlib import Path

if __name__ == "__main__":  # run as a script: make the package importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from robustness.api_cases import API_CASES, BYTE_ORDER_CASES
from robustness.faults import FAULTS
from robustness.harness import CLI_CASES, COMMANDS, REPO, Case, load_tables
from robustness.memory import MEASURED
from robustness.outcomes import OUTCOMES

DOC = REPO / "docs" / "robustness.md"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _outcome(c: Case) -> str:
    if c.xfail:
        return f"**xfail**: {c.xfail}"
    return "exit 2, one line" + ("" if c.before_work else " (found in the data, during the work)")


def render_doc() -> str:
    """The text of docs/robustness.md."""
    load_tables()
    xfails = [c for c in CLI_CASES if c.xfail]
    out = [
        "# Robustness: hostile and careless use",
        "",
        "<!-- Generated from tests/robustness/: run `.venv/bin/python "
        "tests/robustness/doc.py` after changing its tables; a test checks this file. -->",
        "",
        "What irnuc promises when it is used wrongly (issues 12, 19 and 42), and the cases "
        "that check it.",
        "",
        "* **A user error is one line and exit status 2**: `irnuc COMMAND: error: ...` naming the",
        "  flag, file or dotted field and what is allowed, with no traceback, found before the",
        "  command's work wherever it can be known before (the tests replace the work by a",
        "  tripwire). Usage errors are one line too. A failing external tool is one line and",
        "  status 3; anything else is a bug and keeps its traceback.",
        "* **Sizes are checked against the memory there is** (`MemAvailable` in /proc/meminfo,",
        "  `irnuc.common.memory`) before frames are simulated or loaded (an `.npz` is judged by",
        "  its headers before its data is read); the message gives the estimate and what is",
        "  available, worker processes counted with their interpreters.",
        "  `IRNUC_NO_MEMORY_CHECK=1` turns the check off (e.g. with swap).",
        "* **Every `--out` is written as a unit**: into a hidden sibling `.NAME.tmp-*`, swapped",
        "  into place when the command succeeds, under the lock `.NAME.lock`, which the command",
        "  takes before its work (a second run on the folder fails at once). Leftovers of killed",
        "  runs are removed by the next run, and the lock file goes with the lock: a refused",
        "  or finished command leaves nothing beside `--out`. irnuc replaces only what it",
        "  wrote: an existing `--out` must be empty or hold the marker `.irnuc-output` of the",
        "  same command; a user's folder, the current folder, a link, or a folder holding one",
        "  of the command's inputs is refused: every file option (a table checks each) and",
        "  every file read while the folder is claimed (a sequence's table CSV, a manifest's",
        "  files, a baseline). Outputs never nest: an `--out` inside another irnuc output",
        "  (which that output's next run would delete) is refused, and so is replacing an",
        "  output that holds another command's output.",
        "* **A write error is one line naming the file**: a full disk, a file-size limit or a",
        "  quota while the atomic writer or an output folder is being filled is `--out FOLDER:",
        "  FILE: cannot be written (REASON)` with the previous output whole; a stdout that",
        "  cannot be written (`| head`, a closed pipe, `> /dev/full`, closed before irnuc",
        "  started: refused before the work unless `-q`) is one line naming stdout, exit",
        "  status 2.",
        "* **Every input is read with a size cap before it is parsed**: configuration, sensor,",
        "  pipeline, threshold and baseline files, manifests and a sequence's table CSVs at",
        "  most 16 MiB (`irnuc.common.io.MAX_TEXT_BYTES`; `/dev/zero` is refused at once),",
        "  every file a manifest names at its size (the images) or at 16 MiB + 512 bytes a",
        "  pixel (the others), `.npz` frames and `.npy` scene maps by their headers against",
        "  the memory there is, and every array of an `.npz` against the size its header",
        "  declares. Deep nesting and integers too long to convert are one line too. A",
        "  number is a number: `true` or `\"30\"` where one is expected is refused.",
        "* **A name never becomes a path**: a configuration's name must be a plain name",
        "  (letters, digits, `_ . -`), checked where it is read and where it names a folder;",
        "  a cached result carries the name it is asked for.",
        "* **Nothing that checks nothing passes**: a report configuration without a phase to",
        "  run (or whose only phase `--no-cosim` skips) is an error; a baseline is validated",
        "  whole and refused when it is of another schema version, tool or configuration (its",
        "  name or hash); a comparison of no metric, or a run measuring nothing that can fail,",
        "  has status `fail` with the reason. Every report configuration field (presets,",
        "  overrides, pipelines, components) is resolved before the first progress line.",
        "* **The calibration is checked whole**: the manifest hashes every file it names",
        "  (`coeffs.npz`, `coeffs.bin`, `coeffs.hex`, `badpix.csv`, the summaries) and all",
        "  its own fields (`manifest_sha256`: the formats, the frame size, the registers, the",
        "  FPA and housing sensors of the calibration); `irnuc correct` checks all of them, the",
        "  hex image against the binary one, the whole configuration (method and stages too)",
        "  against `--pipeline`, and, for the methods that read them, the frames' FPA sensor and",
        "  housing sensor (its node too: tc_housing) against the calibration's. A",
        "  calibration whose points the model, the sensor or the",
        "  pipeline cannot take (temperatures, readings, their range) is refused before the",
        "  simulation, naming the key.",
        "* **The API** (`nuc_core`, `dpc_core`, `nuc_dpc_top`, `pack_words`, `calibrate`,",
        "  `model.simulate`, `model.Pipeline`, `cos4_map`) raises `ValueError` naming the",
        "  argument for a bad shape, dtype, empty or non-finite input, and accepts integer",
        "  arrays of either byte order (converted once, at the boundary).",
        "* **Child processes** (builds, simulations, the bulk harness) run in their own process",
        "  group and die with the irnuc process that started them.",
        "",
        f"## Command line: {len(CLI_CASES)} cases",
        "",
        f"{len(CLI_CASES) - len(xfails)} end with exit status 2 and one line naming the "
        "flag, file or field"
        + (f"; {len(xfails)} are expected failures (`xfail`, strict), listed with their reason"
           if xfails else "") + ". Every case also checks that",
        "nothing was created or replaced at the output name and no temporary folder or lock "
        "file is left.",
        "",
    ]
    for command, cmd in COMMANDS.items():
        title = cmd.title
        cases = [c for c in CLI_CASES if c.command == command]
        out += [f"### {title}: {len(cases)} cases", "",
                "| case | hostile input | arguments | the message names | outcome |",
                "|---|---|---|---|---|"]
        for c in cases:
            args = c.args.replace("{w}/", "").replace("{t}/", "").replace("{w}", "FOLDER")
            args = args.replace("{t}", "FOLDER") or "(none)"
            out.append(f"| `{c.id}` | {_cell(c.what)} | `{_cell(args)}` | "
                       f"{', '.join(f'`{_cell(n)}`' for n in c.names)} | {_outcome(c)} |")
        out.append("")
    out += [f"## API: {len(API_CASES)} bad calls, {len(BYTE_ORDER_CASES)} functions in both byte orders",
            "", "Each bad call raises `ValueError` (one line) naming the argument.", "",
            "| case | bad input | the message names |", "|---|---|---|"]
    for a in API_CASES:
        out.append(f"| `{a.id}` | {_cell(a.what)} | {', '.join(f'`{_cell(n)}`' for n in a.names)} |")
    out += ["", "Given arrays of the other byte order, or strided views, these give the native "
            "result bit for bit: " + ", ".join(f"`{n}`" for n in sorted(BYTE_ORDER_CASES)) + ".",
            "", "## Faults", "", "| test | what happens | outcome |", "|---|---|---|"]
    for name, text in FAULTS.items():
        out.append(f"| `test_fault_{name}` | {_cell(text)} | passes |")
    out += ["", "## Outcomes", "",
            "Hostile inputs whose right outcome is not only an error line before the work: "
            "write and", "stdout errors, runs and comparisons that check nothing, results "
            "that were silently wrong.", "",
            "| test | hostile input | outcome |", "|---|---|---|"]
    for name, (what, result) in OUTCOMES.items():
        out.append(f"| `test_outcome_{name}` | {_cell(what)} | {_cell(result)} |")
    out += ["", "## Memory estimates", "",
            "Checked before the work against `MemAvailable` (80 % of it may be planned). The",
            "estimates are generous: above the peaks measured for these requests (growth of",
            "the resident size above a warm interpreter), as a test checks.", "",
            "| request | measured peak | estimate |", "|---|---|---|"]
    for what, measured, estimate in MEASURED:
        out.append(f"| {what} | {measured:.0f} MiB | {estimate() / 2**20:.0f} MiB |")
    out += ["", "## Expected failures (commands being rewritten)", ""]
    for reason in sorted({c.xfail for c in xfails if c.xfail}):
        ids = [c.id for c in xfails if c.xfail == reason]
        out.append(f"* {reason}: {', '.join(f'`{i}`' for i in ids)}")
    out.append("")
    return "\n".join(out)


def main() -> None:
    DOC.write_text(render_doc())
    print(f"wrote {DOC}")


if __name__ == "__main__":
    main()
