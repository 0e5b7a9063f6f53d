"""The robustness cases of ``irnuc noise``."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from robustness.harness import case, command, other_kind, user_folder


def _equal_codes(w: Path, t: Path) -> None:
    # The scene varies, the codes do not (a stuck or saturated sensor).
    np.savez(t / "eq.npz", codes=np.full((8, 4, 5), 1000, np.uint16),
             temps=np.array([300.0] * 4 + [310.0] * 4), adc_bits=np.int64(14))


def _frames_in_out(w: Path, t: Path) -> None:
    (t / "out").mkdir()
    (t / "out" / ".irnuc-output").write_text("irnuc noise\n")
    (t / "out" / "frames.npz").write_bytes((w / "good.npz").read_bytes())


N = command("noise", (("irnuc.model.noise_metrics", "fit_frames"),))
NG = "--frames {w}/good.npz"
case("noise-no-frames", N, "", ("--frames", "required"), "--frames missing")
case("noise-frames-missing", N, "--frames none.npz", ("--frames", "no such file"),
     "frames that do not exist")
case("noise-frames-text", N, "--frames {w}/text.npz", ("--frames", "not an .npz"),
     "a text file as frames")
case("noise-header-size", N, "--frames {w}/header_size.npz",
     ("--frames", "damaged", "declares shape (5, 6, 8)"),
     "a codes header that disagrees with the stored size (read anyway: NETD -115540 mK, exit 0)")
case("noise-codes-equal", N, "--frames eq.npz", ("--frames", "responsivity is 0 codes/K"),
     "codes that do not follow the scene (ZeroDivisionError)", setup=_equal_codes,
     before_work=False)
case("noise-range-text", N, f"{NG} --range x", ("--range", "START:STOP"), "a range that is a word")
case("noise-range-short", N, f"{NG} --range 0:2", ("--range", "at least 3"), "two frames")
case("noise-settle-negative", N, f"{NG} --settle=-1", ("--settle", "0..100000"),
     "a negative settling time")
case("noise-seed-negative", N, f"{NG} --seed=-4", ("--seed -4", "0..2^63-1"), "a negative seed")
case("noise-out-holds-frames", N, "--frames out/frames.npz --out out",
     ("--out", "--frames", "would replace"), "--out holds the frames it reads",
     setup=_frames_in_out)
case("noise-out-user-folder", N, f"{NG} --out out", ("--out", "other content"),
     "--out is a user's folder (never deleted)", setup=user_folder)
case("noise-out-other-command", N, f"{NG} --out out", ("--out", "irnuc frames"),
     "--out holds another command's output", setup=other_kind("frames"))
