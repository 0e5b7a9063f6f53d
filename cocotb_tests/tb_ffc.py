"""cocotb tests of the stage top ``method_ffc_top`` (one_point / two_point / quadratic / tc_offset +
ffc), run through ``cocotb_tests/test_method_ffc_top.py``.

Chain: a shutter sequence (seeded) -> :func:`irnuc.cosim.stages.ffc_run` (one run of
``nuc_fixed.method_top`` over the sequence: the expected pixels, accumulator words,
refreshed corrections and held frames) -> the drive engine's sources on ``s_pix`` (with
the frame's shutter flag), ``s_coef``, ``s_foff`` (the correction in effect: the host's
memory, written back from ``m_foff``) and ``s_acc`` (the accumulator, written back from
``m_acc``), with pause patterns -> DUT -> sinks with backpressure on ``m_pix``, ``m_acc``
and ``m_foff`` -> one in-order scoreboard per output stream, and the target register
``ffc_target_o`` against the golden targets. Widths are read back from the DUT.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.method_stim import ffc_calibration, ffc_raws, random_reading
from irnuc.cocotb_tests.streams import Sink, Source, StreamBus, reset, run_streams
from irnuc.cosim import coverage
from irnuc.cosim.scoreboard import Scoreboard
from irnuc.cosim.stages import FfcRun, StageScoreboard, ffc_run
from irnuc.cosim.stream import coef_stream_bits, frame_word_bits
from irnuc.nuc_fixed import PipelineConfig
from irnuc.nuc_fixed.method_top import MethodCoefficients
from irnuc.nuc_fixed.widths import ffc_shift


async def _setup(dut, salt: int) -> tb_lib.Env:
    """Clock, reset, the configuration and a seeded rng; the widths of every stream and
    of the target register read back from the DUT against the layouts."""
    env = await tb_lib.setup(dut, salt)
    cfg = env.cfg
    buses = {p: StreamBus.from_prefix(dut, p)
             for p in ("s_pix", "s_coef", "s_foff", "s_acc", "m_acc", "m_foff", "m_pix")}
    mem = cfg.memories
    got = (buses["s_pix"].width("data"), buses["s_pix"].width("frame"),
           buses["s_coef"].width("data"), buses["s_foff"].width("data"),
           buses["s_acc"].width("data"), buses["m_acc"].width("data"),
           buses["m_foff"].width("data"), buses["m_pix"].width("data"),
           len(dut.ffc_target_o))
    want = (cfg.adc_bits, frame_word_bits(cfg), coef_stream_bits(cfg),
            mem["ffc_offset"].word_bits, mem["ffc_acc"].word_bits, mem["ffc_acc"].word_bits,
            mem["ffc_offset"].word_bits, cfg.out_bits, cfg.registers["ffc_target"].width)
    assert got == want, f"widths (pixel, frame word, coefficient word, s_foff, s_acc, " \
                        f"m_acc, m_foff, output, target) {got}; the layouts give {want}"
    return env


def _run_of(cfg: PipelineConfig, golden: PipelineConfig, rng: np.random.Generator,
            shutter: list[int], shape: tuple[int, int], kind: str = "camera") -> FfcRun:
    c = ffc_calibration(cfg, *shape, rng, kind)
    readings = [random_reading(cfg, c, rng) for _ in shutter]
    return ffc_run(c, ffc_raws(cfg, shutter, *shape, rng, kind), [bool(s) for s in shutter],
                   readings=readings, golden=golden)


def _unsigned(a: np.ndarray, bits: int) -> np.ndarray:
    return np.asarray(a, dtype=np.int64) & ((1 << bits) - 1)


def _pattern(p: float | str) -> str:
    """The coverage name of a pause pattern (0: none)."""
    return p if isinstance(p, str) else ("none" if p == 0 else "random")


async def run_sequence(dut, run: FfcRun, golden: PipelineConfig, rng: np.random.Generator,
                       idle: float | str = 0.0, backpressure: float | str = 0.0,
                       flip_mid_frame: bool = False) -> dict[str, Sink]:
    """Reset the DUT (the golden model's run starts from the sequencer's reset state and
    zero corrections), drive the sequence and check every output stream and the target;
    return the sinks. ``flip_mid_frame``: the shutter flag turns over from the middle of
    each frame of two pixels or more (the frame keeps its first pixel's flag). On a pass
    the run's coverage is sampled."""
    await reset(dut, 2)
    pix_bus = StreamBus.from_prefix(dut, "s_pix", extra=("frame_width_i", "frame_height_i"))
    cols: dict[str, list[np.ndarray]] = {k: [] for k in pix_bus.names}
    for fr, sh in zip(run.frames, run.shutter, strict=True):
        h, w = fr.raw.shape
        sof, eol = tb_lib.markers(h, w)
        for k, v in (("data", fr.raw.ravel()), ("sof", sof), ("eol", eol),
                     ("frame", np.full(h * w, fr.drive.frame_word, dtype=object)),
                     ("shutter", _shutter_column(int(sh), h * w, flip_mid_frame)),
                     ("frame_width", np.full(h * w, w)),
                     ("frame_height", np.full(h * w, h))):
            cols[k].append(np.asarray(v, dtype=object))
    cbits = len(dut.s_foff_data_i)
    acc_items = [a.ravel() for a in run.acc_in if a is not None]
    sources = [
        Source(pix_bus, {k: np.concatenate(v) for k, v in cols.items()}, idle, rng),
        Source(StreamBus.from_prefix(dut, "s_coef"),
               {"data": np.concatenate([f.drive.words.ravel() for f in run.frames])}, idle,
               rng),
        Source(StreamBus.from_prefix(dut, "s_foff"),
               {"data": np.concatenate([_unsigned(f.ravel(), cbits) for f in run.foff_in])},
               idle, rng),
        Source(StreamBus.from_prefix(dut, "s_acc"),
               {"data": np.concatenate(acc_items) if acc_items else np.zeros(0, np.int64)},
               idle, rng),
    ]
    shown = [f for f, held in zip(run.frames, run.held, strict=True) if not held]
    acc_want = [a.ravel() for a in run.acc_out if a is not None]
    foff_want = [_unsigned(a.ravel(), cbits) for a in run.foff_out if a is not None]
    sinks = {
        "m_pix": Sink(StreamBus.from_prefix(dut, "m_pix"), backpressure, rng,
                      expect=sum(f.raw.size for f in shown)),
        "m_acc": Sink(StreamBus.from_prefix(dut, "m_acc"), backpressure, rng,
                      expect=sum(a.size for a in acc_want)),
        "m_foff": Sink(StreamBus.from_prefix(dut, "m_foff"), backpressure, rng,
                       expect=sum(a.size for a in foff_want)),
    }
    await run_streams(dut, sources, list(sinks.values()))
    await ClockCycles(dut.clk_i, 4)  # nothing more may come
    for s in sinks.values():
        s.bus.ready.value = 1
    await ClockCycles(dut.clk_i, 40)
    extra = {k: int(s.bus.valid.value) for k, s in sinks.items()}
    sb = StageScoreboard(golden)
    for fr in shown:
        sb.expect_frame(fr)
    tb_lib.assert_passed(tb_lib.score(sb, sinks["m_pix"]))
    for name, want in (("m_acc", acc_want), ("m_foff", foff_want)):
        wsb = Scoreboard(("data",))
        if want:
            wsb.expect(data=np.concatenate(want))
        tb_lib.assert_passed(tb_lib.score(wsb, sinks[name]))
    assert not any(extra.values()), f"outputs after the sequence: {extra}"
    if run.targets and any(f is not None for f in run.foff_out):
        assert int(dut.ffc_target_valid_o.value) == 1, "no target after a mean pass"
        assert int(dut.ffc_target_o.value) == run.targets[-1], \
            f"target {int(dut.ffc_target_o.value)}, the golden model's {run.targets[-1]}"
    if coverage.enabled() and golden == run.frames[0].coeffs.cfg:
        cov = coverage.model("method_ffc_top", golden)
        idle_p, bp_p = _pattern(idle), _pattern(backpressure)
        cov.sample("stream.idle", idle_p)
        cov.sample("stream.backpressure", bp_p)
        cov.sample_run(run, "full_rate" if (idle_p, bp_p) == ("none", "none") else
                       "idle_backpressure" if "none" not in (idle_p, bp_p) else "other")
        if flip_mid_frame and any(f.raw.size > 1 for f in run.frames):
            cov.sample("ffc.shutter_mid_frame", "ignored")
        coverage.export()
    return sinks


def _shutter_column(flag: int, pixels: int, flip: bool) -> np.ndarray:
    col = np.full(pixels, flag)
    if flip and pixels > 1:
        col[pixels // 2:] = 1 - flag
    return col


def _n(cfg: PipelineConfig) -> int:
    return 1 << ffc_shift(cfg)


@cocotb.test()
async def shutter_sequence_full_rate(dut) -> None:
    """Open frames, a shutter run of N frames (accumulated, held or passed), the refresh
    frame, a short run (no refresh), open frames: every stream exact at valid = ready = 1,
    the refreshed corrections used from the refresh frame on."""
    env = await _setup(dut, 0)
    n = _n(env.cfg)
    seq = [0, 0] + [1] * n + [0, 0] + [1] * max(1, n // 2) + [0]
    run = _run_of(env.cfg, env.golden, env.rng, seq, (6, 10))
    assert any(f is not None for f in run.foff_out), "no refresh in the sequence"
    await run_sequence(dut, run, env.golden, env.rng)


@cocotb.test()
async def shutter_sequence_patterns(dut) -> None:
    """The shutter sequence with idle cycles on every input and backpressure on every
    output (a shutter event and the refresh under backpressure), every pattern pair."""
    env = await _setup(dut, 1)
    n = _n(env.cfg)
    for idle, bp in (("random", "random"), ("bursty", "alternate"), ("none", "bursty"),
                     ("alternate", "none")):
        seq = [0] + [1] * n + [0, 1, 0]
        run = _run_of(env.cfg, env.golden, env.rng, seq, (4, 7))
        await run_sequence(dut, run, env.golden, env.rng, idle=idle, backpressure=bp)


@cocotb.test()
async def refresh_edges(dut) -> None:
    """Shutter frames before any open frame (passed even with hold), a refresh frame that
    is itself a shutter frame, two full runs back to back apart by one open frame, and
    1x1 / 1x3 frames far shorter than the pipeline and the target's division."""
    env = await _setup(dut, 2)
    n = _n(env.cfg)
    for shape in ((5, 6), (1, 1), (1, 3)):
        seq = [1] * (n + 2) + [0] + [1] * n + [0, 0]
        run = _run_of(env.cfg, env.golden, env.rng, seq, shape)
        await run_sequence(dut, run, env.golden, env.rng, backpressure="random")


@cocotb.test()
async def shutter_flag_mid_frame(dut) -> None:
    """The shutter flag turning over in the middle of every frame (an FFC requested, or
    the shutter opening, mid-frame): each frame keeps the flag of its first pixel, so the
    run and its refresh start at the next frame."""
    env = await _setup(dut, 5)
    n = _n(env.cfg)
    run = _run_of(env.cfg, env.golden, env.rng, [0] + [1] * n + [0, 0], (4, 6))
    await run_sequence(dut, run, env.golden, env.rng, backpressure="random",
                       flip_mid_frame=True)


@cocotb.test()
async def random_calibrations(dut) -> None:
    """Every coefficient over its whole code range and random shutter images: sums,
    targets and corrections saturate; still exact."""
    env = await _setup(dut, 3)
    n = _n(env.cfg)
    seq = [0] + [1] * n + [0, 0] + [1] * n + [1, 0]
    run = _run_of(env.cfg, env.golden, env.rng, seq, (4, 8), kind="random")
    await run_sequence(dut, run, env.golden, env.rng, idle="random", backpressure="random")


@cocotb.test()
async def no_good_pixel_keeps_corrections(dut) -> None:
    """A calibration whose every pixel is bad: a mean frame without a good pixel gives no
    target (the golden model's None; the RTL's division by 2 n = 0 must not be used), so
    the refresh frame keeps the corrections it reads and writes them back unchanged
    (m_foff), and ffc_kept_o says so; from nonzero corrections, two runs, exact."""
    env = await _setup(dut, 6)
    cfg = env.cfg
    n = _n(cfg)
    c = ffc_calibration(cfg, 3, 5, env.rng, "camera")
    fields = {m: dict(v) for m, v in c.fields.items()}
    fields["coeffs"]["bad"] = np.ones((3, 5), dtype=bool)
    c = MethodCoefficients(cfg, fields, c.registers)
    lo = -(1 << (cfg.format("ffc").bits - 1))
    start = env.rng.integers(lo, -lo, size=(3, 5))
    seq = [0] + [1] * n + [0, 0] + [1] * n + [0]
    readings = [random_reading(cfg, c, env.rng) for _ in seq]
    run = ffc_run(c, ffc_raws(cfg, seq, 3, 5, env.rng, "camera"), [bool(s) for s in seq],
                  readings=readings, golden=env.golden, offset=start)
    assert len(run.kept) == 2 and all(t == 0 for t in run.targets)
    refreshed = [f for f in run.foff_out if f is not None]
    assert refreshed and all(np.array_equal(f, start) for f in refreshed)
    await run_sequence(dut, run, env.golden, env.rng, backpressure="random")
    assert int(dut.ffc_kept_o.value) == 1, "ffc_kept_o low after a mean frame of bad pixels"
    # A good pixel again: a target, and the flag falls with the next division.
    ok = _run_of(cfg, env.golden, env.rng, [0] + [1] * n + [0, 0], (3, 5))
    assert not ok.kept
    await run_sequence(dut, ok, env.golden, env.rng)
    assert int(dut.ffc_kept_o.value) == 0, "ffc_kept_o high after a target was taken"


@cocotb.test()
async def checker_detects_mismatch(dut) -> None:
    """Against the golden model with another rounding of the correction the check must
    fail with mismatching outputs (of m_pix or m_foff), not a timeout."""
    env = await _setup(dut, 4)
    cfg = env.cfg
    other = cfg.replace(formats={"ffc": {"rounding": "truncate"}})
    assert other.format("ffc").rounding != cfg.format("ffc").rounding
    n = _n(cfg)
    run = _run_of(cfg, other, env.rng, [0] + [1] * n + [0, 0], (6, 10))
    try:
        await run_sequence(dut, run, other, env.rng)
    except AssertionError as e:
        assert "mismatching" in str(e) and " 0 mismatching" not in str(e), str(e)
    else:
        raise AssertionError("no mismatch against another rounding of the correction")
