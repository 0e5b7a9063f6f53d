"""The robustness cases of ``irnuc mutate``."""

from __future__ import annotations

from robustness.harness import case, command, out_is_file, user_folder

M = command("mutate", (("irnuc.verif.mutate", "baseline_check"), ("irnuc.verif.mutate", "run_mutant"),
                      ("irnuc.verif.mutate", "run_per_configuration")))
case("mutate-only-unknown", M, "--only spill_ready_halfrate",
     ("--only", "did you mean 'spill_ready_half_rate'"), "a misspelt mutant id")
case("mutate-only-twice", M, "--only dpc_no_rounding --only dpc_no_rounding",
     ("--only", "more than once"), "one mutant twice")
case("mutate-workers-negative", M, "--workers -1", ("--workers", "0..256"),
     "a negative worker count")
case("mutate-workers-text", M, "--workers many", ("--workers", "invalid int"),
     "a worker count that is a word")
case("mutate-scheduler-malformed", M, "--scheduler tcp://nohost", ("--scheduler", "tcp://HOST:PORT"),
     "a scheduler address without a port")
case("mutate-out-file", M, "--out {t}/out", ("--out",), "--out is a file", setup=out_is_file)
case("mutate-out-user-folder", M, "--out {t}/out", ("--out",),
     "--out is a user's folder (never deleted)", setup=user_folder)
case("mutate-configs-unknown", M, "--configs sample,minimall",
     ("--configs minimall", "did you mean 'minimal'"), "a misspelt configuration name")
case("mutate-configs-twice", M, "--configs minimal,minimal", ("--configs", "more than once"),
     "one configuration twice")
case("mutate-configs-empty", M, "--configs sample,", ("--configs", "empty name"),
     "an empty name in the configuration list")
case("mutate-configs-other-top", M, "--only mul_a_top_unsigned --configs minimal",
     ("--configs", "nuc_dpc_top"), "per configuration, only mutants of another top")
