"""The robustness cases of ``irnuc precision``."""

from __future__ import annotations

from robustness.harness import case, command, out_is_file, user_folder

Q = command("precision", (("irnuc.reports.studies.precision", "run_precision"),))
case("precision-unknown-flag", Q, "--fast", ("--fast", "unrecognized"), "an unknown flag")
case("precision-only-no-value", Q, "--only", ("--only", "expected one argument"), "--only without value")
case("precision-extra-argument", Q, "--quick now", ("now", "unrecognized"), "a stray argument")
case("precision-only-unknown", Q, "--quick --only radiancee", ("--only", "band_radiance"),
     "an unknown component")
case("precision-out-file", Q, "--quick --out {t}/out", ("--out",), "--out is a file",
     setup=out_is_file)
case("precision-out-user-folder", Q, "--quick --out {t}/out", ("--out",), "--out is a user's folder",
     setup=user_folder)
